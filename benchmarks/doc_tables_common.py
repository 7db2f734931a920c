"""The parts of benchmarks/doc-tables that its blocks share: the
quantities of the studies, the results files read once (Results) and the
error (Failure) a block raises where one lacks what it needs, the
formatting of numbers, prose and tables in the pages' style, and the
configurations of the work-precision studies (in words, the cheapest one
per accuracy, the order of the tables). Python 3 standard library only.
"""
import csv
import os
import re
import textwrap

import benchlib
from benchlib import read_lines, results_header

MINUS = "\u2212"
BE = "backward Euler"

# The quantities of the work-precision studies, in the order of the tables.
QUANTITIES_2D = [("normal_force", "N(t)"), ("friction_force", "friction force"),
                 ("deflection", "largest deflection"), ("pressure", "pressure profiles"),
                 ("traction", "traction profiles"), ("energy", "energy"),
                 ("theorem6", "Theorem-6 norm")]
QUANTITIES_3D = [("normal_force", "N(t)"), ("deflection", "deflection"),
                 ("energy", "energy"), ("pressure", "pressure"),
                 ("friction_force", "friction force")]
# The rows of the references (reference_*_error.csv).
REFERENCE_NAMES = {"normal_force": "N(t)", "friction_force": "friction force",
                   "friction_l1": "friction force (L1 in time)",
                   "deflection": "largest deflection", "energy": "energy",
                   "pressure": "pressure profiles",
                   "traction": "friction-traction profiles"}
THRESHOLDS = [(0.1, "10 %"), (0.01, "1 %"), (0.001, "0.1 %")]
SCHEME_NAMES = {"bathe": "Bathe"}
# Configurations that are a ready scene file of prm/.
SCENE_FILES = {"q2-be-56x3-k56": "prm/barboteu_danan_2016_fast.prm",
               "q2-bathe-h24-k32": "prm/rail_3d_fast.prm"}


class Failure(Exception):
    """A results file lacks what a block needs, or a page's markers are
    wrong: the message says which."""


# ---------------------------------------------------------------------------
# Reading the results files


class Results:
    """The results directory: files read once, each with the line of its
    header that records its date and machine."""

    def __init__(self, directory):
        self.directory = directory
        self.cache = {}

    def path(self, name):
        return os.path.join(self.directory, name)

    def exists(self, name):
        return os.path.isfile(self.path(name))

    def lines(self, name):
        if name not in self.cache:
            try:
                self.cache[name] = read_lines(self.path(name))
            except OSError as e:
                raise Failure("benchmarks/results/%s cannot be read (%s)" % (name, e.strerror))
        return self.cache[name]

    def machine_line(self, name):
        """The first header line with a date (the machine line of
        benchlib.machine_line() and what follows it on that line); the first
        header line if none has a date."""
        header = results_header(name, self.lines(name))
        for line in header:
            if benchlib.DATE.search(line):
                return line
        return header[0] if header else "(the file has no header line)"

    def rows(self, name):
        """The rows of a CSV file (after its comment lines), as dicts."""
        body = [line for line in self.lines(name) if not line.startswith("#")]
        return list(csv.DictReader(body))

    def row(self, names, key, value):
        """The first row whose `key` is `value`, from the first file of
        `names` (those that exist) that has one: (file, row)."""
        for name in names:
            if self.exists(name):
                for r in self.rows(name):
                    if r.get(key) == value:
                        return name, r
        raise Failure("no row with %s = %s in benchmarks/results/%s"
                      % (key, value, " or ".join(names)))


def number(row, key):
    """A float of the row, None where the column is missing or empty."""
    value = row.get(key)
    if value in (None, ""):
        return None
    try:
        return float(value)
    except ValueError:
        return None


# ---------------------------------------------------------------------------
# Formatting


def minus(text):
    return text.replace("-", MINUS)


def sci(x, digits=2):
    """7.3e−2 (the pages' style); a plain mantissa for exponent 0."""
    if x is None:
        return "–"
    if x == 0:
        return "0"
    mantissa, exponent = ("%.*e" % (digits - 1, x)).split("e")
    exponent = int(exponent)
    if exponent == 0:
        return minus(mantissa)
    return minus("%se%d" % (mantissa, exponent))


def pct(x):
    """A relative error in per cent, two significant digits (0.46 %, 15 %)."""
    if x is None:
        return "–"
    v = 100 * x
    text = "%.0f" % v if v >= 9.95 else ("%#.2g" % v).rstrip(".")
    return text + " %"


def secs(x):
    if x is None:
        return "–"
    return "%.2f" % x if x < 10 else "%.1f" % x


def order(x):
    return "–" if x is None or x != x else minus("%.2f" % x)


def cells(text):
    """'128x16' -> '128 × 16'."""
    return text.replace("x", " × ")


def steps_of(k):
    return int(round(1 / k))


def para(text):
    """A paragraph of prose in lines of at most 78 columns (long words kept
    whole, no break inside '10 %', '128 × 16', 'k = 1/16', '0.84 s'), and
    the blank line after it."""
    keep = re.sub(r"(?<=\d) (?=[%×]|s\b)|(?<=[×=]) (?=\d)|(?<= [k=]) (?=[=\d])", "\0", text)
    lines = textwrap.wrap(keep, 78, break_long_words=False, break_on_hyphens=False)
    return [line.replace("\0", " ") for line in lines] + [""]


def table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(row) + " |" for row in rows]
    return out


def sources(results, names, what=None):
    """The block's first line: where its numbers come from."""
    groups = []  # files with the same header line (a report and its CSV) share it
    for n in names:
        line = results.machine_line(n).rstrip(".")
        for group in groups:
            if group[1] == line:
                group[0].append(n)
                break
        else:
            groups.append(([n], line))
    parts = [" and ".join("`benchmarks/results/%s`" % n for n in files) + " (%s)" % line
             for files, line in groups]
    text = "Generated by `benchmarks/doc-tables` from " + "; ".join(parts) + "."
    if what:
        text += " " + what
    return para("*" + text.replace("*", "\\*") + "*")


# ---------------------------------------------------------------------------
# The configurations of the work-precision studies


def describe_2d(r, scheme=True):
    """A configuration of work_precision*.csv in words: 'Q2 56 × 3, k =
    1/56', 'adaptive, 16 × 2 coarse, level 4, k = 1/256' (the scheme added
    where it is not backward Euler, and scheme=True)."""
    m = steps_of(float(r["k"]))
    if r.get("strategy") == "adaptive":
        coarse = r["family"].split()[2] if len(r["family"].split()) > 2 else "?"
        text = "adaptive, %s coarse, level %s, k = 1/%d" % (cells(coarse), r["max_level"], m)
    else:
        text = "Q%s %s × %s, k = 1/%d" % (r["degree"], r["nx"], r["ny"], m)
    if scheme and r["scheme"] != BE:
        text += ", " + SCHEME_NAMES.get(r["scheme"], r["scheme"])
    rho = re.search(r"rho_inf=([0-9.]+)", r.get("label", ""))
    if scheme and rho:
        text += ", ρ∞ = " + rho.group(1)
    return text


def describe_3d(r, scheme=True):
    """A configuration of work_precision_3d.csv: 'Q2 20 × 2 × 2, k = 1/64',
    'Q2 adaptive, 10 × 1 × 1 coarse, level 1, k = 1/128'."""
    m = steps_of(float(r["k"]))
    mesh = r["mesh"].split()
    if r["strategy"].startswith("adaptive"):
        text = "Q%s adaptive, %s coarse, level %s, k = 1/%d" % (
            r["degree"], cells(mesh[0]), mesh[1].lstrip("L"), m)
    else:
        text = "Q%s %s, k = 1/%d" % (r["degree"], cells(mesh[0]), m)
    if scheme and r["scheme"] != BE:
        text += ", " + SCHEME_NAMES.get(r["scheme"], r["scheme"])
    return text


def cheapest(rows, key, threshold):
    """As benchmarks/work-precision: the row of least CPU time whose error
    is at most `threshold` (the first in the file's order on a tie)."""
    ok = [r for r in rows if number(r, key) is not None and number(r, key) <= threshold]
    return min(ok, key=lambda r: number(r, "cpu_time")) if ok else None


def best(rows, key):
    ok = [r for r in rows if number(r, key) is not None]
    return min(ok, key=lambda r: (number(r, key), number(r, "cpu_time"))) if ok else None


def reference_estimates(results, name):
    return {r["quantity"]: float(r["estimate"]) for r in results.rows(name)}


def cheapest_table(rows, quantities, estimates, describe, error, cost):
    """Rows of the 'cheapest configuration per accuracy' table: per
    quantity the reference's estimated error, then per target the
    cheapest configuration (and, where that is an adaptive one, the
    cheapest uniform one), or the best one where none reaches it."""
    out = []
    for key, label in quantities:
        estimate = estimates.get(key)
        line = [label, sci(estimate) if estimate is not None else "–"]
        said_best = False  # the best one is named once per quantity
        for threshold, _ in THRESHOLDS:
            star = "*" if estimate is not None and threshold < estimate else ""
            r = cheapest(rows, key, threshold)
            if r is None:
                b = best(rows, key)
                line.append("none%s (best %s: %s, %s)" % (
                    star, error(number(b, key)), describe(b), cost(b, short=True))
                    if b and not said_best else "none" + star)
                said_best = True
                continue
            text = "%s%s: %s (%s)" % (describe(r), star, error(number(r, key)), cost(r))
            if r.get("strategy", "").startswith("adaptive"):
                u = cheapest([x for x in rows if x.get("strategy") == "uniform"], key, threshold)
                if u is not None:
                    text += "; uniform: %s: %s (%s)" % (describe(u), error(number(u, key)),
                                                       cost(u))
            line.append(text)
        out.append(line)
    return out


def cost_2d(r, short=False):
    if short:
        return "%s s" % secs(number(r, "cpu_time"))
    return "%s s, %s s" % (secs(number(r, "cpu_time")), secs(number(r, "wall_time")))


def cost_3d(r, short=False):
    return "%s s" % secs(number(r, "cpu_time"))


def scheme_order(r):
    return {BE: 0, "trapezoidal": 1, "bathe": 2}.get(r["scheme"], 3)


def family_order(r):
    """A 2D configuration's place in the tables: by scheme, uniform before
    adaptive, degree, cells from the thickest to the thinnest (n x n, n x
    n/8, n x n/16), cells along the rail, k from the longest; the label
    last (rho_inf)."""
    return (scheme_order(r), r["strategy"] != "uniform", r["degree"],
            -round(float(r["ny"]) / float(r["nx"]), 3), int(r["nx"]), -float(r["k"]),
            r["label"])
