#!/usr/bin/python3
"""The ctest `python_readers`: the readers of python/dynamic_contact take
the output files in the format of this version and in the changed one
(a leading '#' comment line or none, a contact CSV with or without a
leading `time` column, columns in another order), and read every column
by its name.

    python_readers.py --work-dir DIR

Writes small files by hand into DIR (no run of the program) and prints one
line per check; exit code 1 if one fails.
"""

import argparse
import os

from dynamic_contact import (Run, is_completed, read_contact, read_prm,
                             read_run_status, read_table, read_time_series,
                             test_overrides)
from dynamic_contact.plotting import pick_steps

from script_checks import check, finish, write


def contact_text(with_comment, with_time, time):
    rows = [(1.0, 0.0, 3.0, "slip"), (0.0, 0.0, 2.0, "stick"),
            (0.5, 0.0, 5.0, "free")]
    header = ["x", "y", "normal_pressure", "mu", "state"]
    if with_time:
        header = ["time"] + header
    lines = []
    if with_comment:
        lines.append("# contact boundary Gamma_3, step 7")
    lines.append(",".join(header))
    for x, y, p, state in rows:
        values = [repr(x), repr(y), repr(p), "0.5", state]
        if with_time:
            values = [repr(time)] + values
        lines.append(",".join(values))
    return "\n".join(lines) + "\n"


def check_error(read, path, what, words=(), naming="",
                error_type=ValueError):
    """read(path) raises @p error_type, its message holding every one of
    @p words: one line, "<what><naming>" (just <what> if nothing is
    raised)."""
    try:
        read(path)
        check(False, what)
    except error_type as error:
        check(all(w in str(error) for w in words), what + naming)


def check_run_format(work_dir, with_comment, with_time):
    """A run directory written by hand in one of the formats, read by
    Run: the contact columns, the time series, run_status."""
    name = "%s, %s" % ("'#' line" if with_comment else "no '#' line",
                       "time column" if with_time else "no time")
    directory = os.path.join(
        work_dir, "run_%d%d" % (with_comment, with_time))
    os.makedirs(directory, exist_ok=True)
    write(os.path.join(directory, "time_series.csv"),
          ("# time series\n" if with_comment else "") +
          "step,normal_force,time\n0,0,0\n7,2.5,0.35\n")
    write(os.path.join(directory, "contact_00007.csv"),
          contact_text(with_comment, with_time, 0.35))
    write(os.path.join(directory, "run_status"), "completed\n")
    run = Run(directory)
    c = run.contact(7)
    check(c["x"].tolist() == [0.0, 0.5, 1.0] and
          c["normal_pressure"].tolist() == [2.0, 5.0, 3.0] and
          c["state"].tolist() == ["stick", "free", "slip"],
          "%s: contact columns by name, rows sorted by x" % name)
    check(("time" in c) == with_time and c.is_numeric("mu") and
          not c.is_numeric("state"),
          "%s: the time column only if written; state as text"
          % name)
    check(run.time_of(7) == 0.35 and
          run.time_series["normal_force"].tolist() == [0.0, 2.5],
          "%s: time series by name; the time of step 7" % name)
    check(run.completed and run.contact_steps == [7],
          "%s: run_status and the contact steps" % name)


def check_contact_only(work_dir):
    """Without time_series.csv the time comes from the contact file."""
    directory = os.path.join(work_dir, "contact_only")
    os.makedirs(directory, exist_ok=True)
    write(os.path.join(directory, "contact_00003.csv"),
          contact_text(False, True, 0.125))
    write(os.path.join(directory, "contact_surface_00003.pvtu"), "")
    run = Run(directory)
    check(run.time_of(3) == 0.125 and run.contact_steps == [3] and
          sorted(run.surface_paths) == [3],
          "without time_series.csv: the time from the contact file; "
          "contact_surface_* is not a contact CSV")
    check(run.status is None and not run.completed and
          read_run_status(work_dir) is None,
          "no run_status: status None, not completed")
    check(is_completed("completed with warnings: 2 steps kept") and
          not is_completed("failed: NaN") and not is_completed("running"),
          "which run_status lines are complete")


def check_table_errors(work_dir):
    """Errors name the file."""
    bad = os.path.join(work_dir, "bad.csv")
    write(bad, "a,b\n1,2\n3\n")
    check_error(read_table, bad, "a short line is an error",
                ("bad.csv", "line 3"), " naming the file and the line")
    partial = os.path.join(work_dir, "partial.csv")
    write(partial, "step,time\n0,0\n1,0.5\n2,1.")
    check(read_table(partial)["time"].tolist() == [0.0, 0.5],
          "a last row without its line end (being written) is left out")
    empty = os.path.join(work_dir, "empty.csv")
    write(empty, "# only a comment\n")
    check_error(read_time_series, empty,
                "a file without a header is an error", ("empty.csv",),
                " naming the file")
    header_only = os.path.join(work_dir, "header_only.csv")
    write(header_only, "x,y,normal_pressure\n")
    c = read_contact(header_only)
    check(len(c) == 0 and c.columns == ["x", "y", "normal_pressure"],
          "a header without rows: empty columns")
    check_error(Run, os.path.join(work_dir, "missing"),
                "a missing directory is an error",
                error_type=FileNotFoundError)


def check_parameter_files(work_dir):
    """read_prm and test_overrides on a parameter file written by hand."""
    prm = os.path.join(work_dir, "scene.prm")
    write(prm, "# test-overrides: Geometry/Repetitions=4, 2 | Time/End time=1\n"
          "# test-overrides: Output/Output every=3\n"
          "set Dimension = 2  # a comment\n"
          "subsection Geometry\n  set Repetitions = 32, \\\n    8\n"
          "  subsection Inner\n    set A = x # b\n  end\nend\n")
    entries = read_prm(prm)
    check(entries == {"Dimension": "2", "Geometry/Repetitions": "32, 8",
                      "Geometry/Inner/A": "x"},
          "read_prm: sections, comments, continued lines")
    check(test_overrides(prm) == ["Geometry/Repetitions=4, 2",
                                  "Time/End time=1", "Output/Output every=3"],
          "test_overrides: every '# test-overrides:' line, split at '|'")
    write(prm, "subsection Geometry\n  set A = 1\n")
    check_error(read_prm, prm, "an unclosed subsection is an error",
                ("scene.prm", "Geometry"), " naming the file")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    parser.add_argument("--work-dir", required=True)
    args = parser.parse_args()
    os.makedirs(args.work_dir, exist_ok=True)

    for with_comment in (False, True):
        for with_time in (False, True):
            check_run_format(args.work_dir, with_comment, with_time)
    check_contact_only(args.work_dir)
    check_table_errors(args.work_dir)
    check_parameter_files(args.work_dir)
    check(pick_steps([0, 1, 2, 3], 8) == [1, 2, 3] and
          pick_steps([0], 8) == [0] and
          pick_steps(list(range(0, 101)), 5) == [1, 26, 51, 75, 100],
          "the profile steps: step 0 left out, evenly spread, the last")
    finish("python_readers")


if __name__ == "__main__":
    main()
