"""Readers for the files a run writes into its Output/Directory
(doc/output.md): time_series.csv, contact_NNNNN.csv, run_status, and the
VTU records (through dynamic_contact.vtu).

Columns are always read by their header name, never by position, and
tolerate the format as it changes:

- leading lines that start with '#' (a comment line before the header, as
  some versions write) are skipped;
- the contact CSV may or may not have a leading `time` column (without it,
  the time of the file is the time of its step in time_series.csv);
- a column that is not numeric (the contact CSV's `state`) is kept as an
  array of strings;
- a last line without its line end (the row a running program is
  appending to time_series.csv) is left out.

Only numpy and the standard library.

    from dynamic_contact import Run
    run = Run("output-barboteu-danan-2016")
    run.status                       # 'completed', 'running', 'failed: ...'
    ts = run.time_series             # Table: ts["time"], ts["normal_force"]
    for step in run.contact_steps:   # the steps with a contact_NNNNN.csv
        c = run.contact(step)        # Table: c["x"], c["normal_pressure"]
        print(step, run.time_of(step), c.columns)
"""

import csv
import os
import re

import numpy as np

CONTACT_PATTERN = re.compile(r"^contact_(\d{5,})\.csv$")
SOLUTION_PATTERN = re.compile(r"^solution_(\d{5,})\.pvtu$")
SURFACE_PATTERN = re.compile(r"^contact_surface_(\d{5,})\.pvtu$")


class Table:
    """Columns of a CSV file by header name: numpy float arrays, or arrays
    of strings for columns that are not numbers.

    t["time"] is the column; "time" in t tells whether it exists;
    t.get(name) gives None for a missing one; t.columns lists the names in
    the file's order; len(t) is the number of rows."""

    def __init__(self, columns, path=None):
        self._columns = dict(columns)
        self.path = path

    @property
    def columns(self):
        return list(self._columns)

    def __contains__(self, name):
        return name in self._columns

    def __getitem__(self, name):
        try:
            return self._columns[name]
        except KeyError:
            raise KeyError("%s: no column %r (columns: %s)"
                           % (self.path or "table", name,
                              ", ".join(self._columns))) from None

    def get(self, name, default=None):
        return self._columns.get(name, default)

    def __len__(self):
        for values in self._columns.values():
            return len(values)
        return 0

    def select(self, mask_or_order):
        """A new Table with the rows picked by a boolean mask or an index
        array."""
        return Table({k: v[mask_or_order] for k, v in self._columns.items()},
                     self.path)

    def is_numeric(self, name):
        return name in self._columns and \
            self._columns[name].dtype.kind in "fiu"


def _data_lines(path):
    """The lines of a CSV file without the leading '#' comment lines and
    blank lines, and without a last line that has no line end yet (a row
    that a running program is writing)."""
    with open(path, newline="") as f:
        text = f.read()
    lines = text.splitlines()
    if lines and not text.endswith("\n"):
        lines.pop()
    start = 0
    while start < len(lines) and (not lines[start].strip() or
                                  lines[start].lstrip().startswith("#")):
        start += 1
    return lines[start:]


def read_table(path):
    """A comma-separated file with a header line (after any leading '#'
    lines) as a Table. Numeric columns become float arrays; a column with
    any entry that is not a number stays an array of strings. A header
    without rows gives empty float columns."""
    lines = _data_lines(path)
    if not lines:
        raise ValueError("%s: no header line" % path)
    rows = list(csv.reader(lines))
    header = [name.strip() for name in rows[0]]
    if len(set(header)) != len(header):
        raise ValueError("%s: repeated column names in the header" % path)
    body = [r for r in rows[1:] if r]
    for i, r in enumerate(body):
        if len(r) != len(header):
            raise ValueError("%s: line %d has %d fields, the header %d"
                             % (path, i + 2, len(r), len(header)))
    columns = {}
    for j, name in enumerate(header):
        values = [r[j].strip() for r in body]
        try:
            columns[name] = np.array([float(v) for v in values],
                                     dtype=np.float64)
        except ValueError:
            columns[name] = np.array(values, dtype=str)
    return Table(columns, path)


def read_time_series(path):
    """time_series.csv (the file, or the output directory that holds it)."""
    if os.path.isdir(path):
        path = os.path.join(path, "time_series.csv")
    return read_table(path)


def read_contact(path):
    """One contact_NNNNN.csv, rows sorted by their position (x, then y,
    then z, as the program writes them; sorted again here so that files of
    other versions read the same)."""
    table = read_table(path)
    keys = [table[k] for k in ("z", "y", "x") if table.is_numeric(k)]
    if keys and len(table):
        table = table.select(np.lexsort(keys))
    return table


def read_run_status(directory):
    """The line in run_status ('running', 'completed', 'completed with
    warnings: ...', 'stopped: ...', 'failed: ...'), or None if the file
    does not exist."""
    path = os.path.join(directory, "run_status")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return f.read().strip()


def is_completed(status):
    """Whether a run_status line says the results are complete."""
    return status is not None and (status == "completed" or
                                   status.startswith("completed with"))


def numbered_files(directory, pattern):
    """(number, path) of the files in directory whose name matches pattern
    (a regex with the number as group 1), sorted by number."""
    found = []
    for name in os.listdir(directory) if os.path.isdir(directory) else []:
        m = pattern.match(name)
        if m:
            found.append((int(m.group(1)), os.path.join(directory, name)))
    return sorted(found)


def contact_files(directory):
    """(step, path) of every contact_NNNNN.csv in directory, by step."""
    return numbered_files(directory, CONTACT_PATTERN)


class Run:
    """One output directory, read lazily: run_status, time_series.csv, the
    contact CSV files, the VTU records (solution_*.pvtu, solution.pvd) and
    the surface records of Gamma_3 (contact_surface_*.pvtu,
    contact_surface.pvd) if there are any."""

    def __init__(self, directory):
        if not os.path.isdir(directory):
            raise FileNotFoundError("%s: not a directory" % directory)
        self.directory = directory
        self.status = read_run_status(directory)
        self._time_series = None
        self._contacts = {}
        self.contact_paths = dict(contact_files(directory))
        self.solution_paths = dict(numbered_files(directory,
                                                  SOLUTION_PATTERN))
        self.surface_paths = dict(numbered_files(directory, SURFACE_PATTERN))

    @property
    def completed(self):
        return is_completed(self.status)

    def has_time_series(self):
        return os.path.exists(os.path.join(self.directory,
                                           "time_series.csv"))

    @property
    def time_series(self):
        if self._time_series is None:
            self._time_series = read_time_series(self.directory)
        return self._time_series

    @property
    def contact_steps(self):
        return sorted(self.contact_paths)

    def contact(self, step):
        """The Table of contact_NNNNN.csv of this step (read once)."""
        if step not in self._contacts:
            if step not in self.contact_paths:
                raise KeyError("%s: no contact file of step %d"
                               % (self.directory, step))
            self._contacts[step] = read_contact(self.contact_paths[step])
        return self._contacts[step]

    def time_of(self, step):
        """The time of a step: from time_series.csv, else from the `time`
        column of its contact file; None if neither has it."""
        if self.has_time_series():
            ts = self.time_series
            if "step" in ts and "time" in ts:
                rows = np.nonzero(ts["step"] == step)[0]
                if rows.size:
                    return float(ts["time"][rows[-1]])
        if step in self.contact_paths:
            c = self.contact(step)
            if c.is_numeric("time") and len(c):
                return float(c["time"][0])
        return None

    def pvd(self, name="solution.pvd"):
        """The (time, path) entries of a .pvd file of the run ([] if
        missing): solution.pvd, or contact_surface.pvd."""
        from .vtu import read_pvd
        path = os.path.join(self.directory, name)
        return read_pvd(path) if os.path.exists(path) else []

    def solution(self, step):
        """The VTU record of a step (all pieces) as one grid."""
        from .vtu import read_vtu
        return read_vtu(self.solution_paths[step])

    def surface(self, step):
        """The surface record of Gamma_3 of a step as one grid."""
        from .vtu import read_vtu
        return read_vtu(self.surface_paths[step])

