"""The entries of a deal.II parameter file (the program's scene.prm) as
written in the file: {"Section/Subsection/Name": "value"}.

Only what the file says: entries it does not set have their defaults in
the program (`dynamic-contact --print-parameters scene.prm` prints them
all). Comments ('#' to the end of the line) and blank lines are skipped,
lines ending in a backslash continue on the next line.

Besides, test_overrides() gives the `--set` overrides a parameter file asks
for in the test that runs every prm file (tests/scenes/run_all_prm.py), from its
comment lines

    # test-overrides: Geometry/Repetitions=8, 2 | Time/Time step=0.05
"""

import re

_SUBSECTION = re.compile(r"^subsection\s+(.+?)\s*$")
_SET = re.compile(r"^set\s+(.+?)\s*=\s*(.*?)\s*$")
_TEST_OVERRIDES = re.compile(r"^\s*#\s*test-overrides\s*:(.*)$")


def _logical_lines(path):
    with open(path) as f:
        pending = ""
        for line in f:
            line = line.rstrip("\n")
            if pending:
                line = line.lstrip()
            if line.rstrip().endswith("\\"):
                pending += line.rstrip()[:-1].rstrip() + " "
                continue
            yield pending + line
            pending = ""
        if pending:
            yield pending


def read_prm(path):
    """The entries the file sets, by "Section/Name" (sections joined with
    '/', as --set takes them)."""
    entries = {}
    sections = []
    for number, line in enumerate(_logical_lines(path), start=1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        m = _SUBSECTION.match(line)
        if m:
            sections.append(m.group(1))
            continue
        if line == "end":
            if not sections:
                raise ValueError("%s:%d: 'end' without a subsection"
                                 % (path, number))
            sections.pop()
            continue
        m = _SET.match(line)
        if m:
            entries["/".join(sections + [m.group(1)])] = m.group(2)
            continue
        if line.startswith("include "):
            continue
        raise ValueError("%s:%d: not a parameter line: %s"
                         % (path, number, line))
    if sections:
        raise ValueError("%s: subsection %s is not closed"
                         % (path, sections[-1]))
    return entries


def test_overrides(path):
    """The overrides of the file's '# test-overrides:' lines, in order
    ("Section/Name=value" strings; several lines add up, items separated by
    '|')."""
    overrides = []
    with open(path) as f:
        for line in f:
            m = _TEST_OVERRIDES.match(line)
            if m:
                overrides += [item.strip() for item in m.group(1).split("|")
                              if item.strip()]
    return overrides
