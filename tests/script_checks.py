"""What the Python test scripts of tests/ share: a check that prints one
line and remembers a failure, a small file writer, the last line with the
exit code (1 if a check failed), and the arguments of a script that runs
the program. The scripts import it from their own folder (Python puts a
script's folder first on its path)."""

import argparse
import os
import sys

failures = []


def check(condition, text):
    print("%s: %s" % ("ok" if condition else "FAILED", text), flush=True)
    if not condition:
        failures.append(text)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def finish(name):
    print("%s: %s" % (name, "every check passed" if not failures else
                      "%d checks failed" % len(failures)))
    sys.exit(1 if failures else 0)


def program_arguments(doc):
    """A parser with --program, --work-dir and --source-dir (the folder
    above tests/ by default), described by the second line of @p doc."""
    here = os.path.dirname(os.path.realpath(__file__))
    parser = argparse.ArgumentParser(description=doc.split("\n")[1])
    parser.add_argument("--program", required=True)
    parser.add_argument("--work-dir", required=True)
    parser.add_argument("--source-dir", default=os.path.dirname(here))
    return parser
