#!/usr/bin/python3
"""The ctest `unit_invariance`: the same scene in SI, mm-tonne-s and inch-lbf-s
takes the same solver path and gives the same answers.

    unit_invariance.py --program build/dynamic-contact --work-dir DIR
                       [--source-dir REPO] [--mpiexec "mpiexec"]
                       [--scenes paper,rail,...]

Each scene of SCENES is converted from SI by scripts/convert-units into
mm-t-s and in-lbf-s and run in all three on one process and on two (every
process taking part). Against the SI run on as many processes:

1. every run completes, with the same cut-backs, Newton iterations and
   convexification passes in every step (`time_series.csv`);
2. every column of `time_series.csv` and of the contact CSVs, converted
   back to SI by its unit, equals the SI run's to 1e-8 of the largest
   magnitude of that column (the nodes' states exactly); the round-off
   diagnostics (the energy balance's defect, the friction law's residual)
   are compared with their own tolerances instead;
3. the well-posedness report of `log.txt` (doc/theory.md section 1.5, its
   ratios dimensionless) is the SI run's, line for line.

Prints one line per check and exits with 1 if any failed.
"""

import glob
import os
import subprocess
import sys
from fractions import Fraction

from script_checks import (check, finish, program_arguments, read_csv,
                           run_scene)

# The scenes (unit-free overrides only: seconds are the time unit of all
# three systems, counts and switches have no unit).
SCENES = {
    "paper": ("prm/barboteu_danan_2016_small.prm", []),
    "rail": ("prm/rail_3d_small.prm", []),
    "braking_block": ("prm/braking_block.prm", []),
    "slip_length": ("prm/barboteu_danan_2016_slip_length.prm",
                    ["Time/End time=0.5"]),
    "braking_block_3d": ("prm/braking_block_3d.prm", ["Time/Time step=4e-6"]),
    "tiny_time_step": ("prm/stress/tiny_time_step.prm",
                       ["Geometry/Repetitions=32, 8"]),
    "nearly_incompressible_q1": ("prm/stress/nearly_incompressible_q1.prm",
                                 ["Geometry/Repetitions=32, 8",
                                  "Time/End time=0.5"]),
}
# The overrides of every run (besides no timings and no progress lines,
# which script_checks.run_scene sets).
COMMON = ["Output/Write VTU=false", "Output/Output every=8",
          "Solver/Minimum DoFs per process=0"]
SYSTEMS = ["SI", "mm-t-s", "in-lbf-s"]

# Units of the systems in SI: length, mass, time (scripts/convert-units).
INCH = Fraction("0.0254")
LBF = Fraction("4.4482216152605")
UNITS = {"SI": (Fraction(1), Fraction(1)),
         "mm-t-s": (Fraction(1, 1000), Fraction(1000)),
         "in-lbf-s": (INCH, LBF / INCH)}

# Columns by their dimension (L, M, T) in 3D; in 2D forces and energies
# are per unit length (one L less). 'count': compared exactly.
FORCE, ENERGY = (1, 1, -2), (2, 1, -2)
TIME_SERIES = {
    "time": (0, 0, 1), "time_step": (0, 0, 1),
    "normal_force": FORCE, "tangential_force": FORCE,
    "kinetic_energy": ENERGY, "elastic_energy": ENERGY,
    "foundation_energy": ENERGY, "total_energy": ENERGY,
    "load_work": ENERGY, "dissipation": ENERGY,
    "remesh_energy_change": ENERGY,
    "uniqueness_bound": (0, 0, 0), "uniqueness_certificate": (0, 0, 0),
    "contraction_factor": (0, 0, 0),
}
for prefix in ("applied_force", "reaction_force", "inertia_force"):
    for c in "xyz":
        TIME_SERIES[prefix + "_" + c] = FORCE
for term in ("inertia", "elastic", "viscous", "compliance", "damping"):
    TIME_SERIES["dissipation_" + term] = ENERGY
TIME_SERIES["friction_dissipation"] = ENERGY
COUNTS = {"step", "cutbacks", "newton_iterations",
          "convexification_iterations", "convexification_converged",
          "coupled_fallbacks", "factorizations", "n_contact", "n_stick",
          "n_slip", "dofs", "cells"}
# The solver's path, compared step by step.
PATH = ["cutbacks", "newton_iterations", "convexification_iterations"]
# Round-off and solver diagnostics: the energy balance's defect (relative
# to the energy: round-off), the friction law's residual (below
# Friction/Coefficient tolerance), the line search's and cycles' counts.
DIAGNOSTICS = {"energy_balance_defect", "relative_energy_defect",
               "relative_min_dissipation", "coefficient_residual",
               "active_set_cycles", "line_search_steps",
               "linear_iterations"}

VELOCITY, STRESS = (1, 0, -1), (-1, 1, -2)
CONTACT = {"time": (0, 0, 1), "x": (1, 0, 0), "y": (1, 0, 0),
           "z": (1, 0, 0), "u_nu": (1, 0, 0), "w_nu": VELOCITY,
           "normal_pressure": STRESS, "w_tau": VELOCITY,
           "w_tau_1": VELOCITY, "w_tau_2": VELOCITY,
           "tangential_traction": STRESS, "tangential_traction_1": STRESS,
           "tangential_traction_2": STRESS, "mu": (0, 0, 0),
           "u_x": (1, 0, 0), "u_y": (1, 0, 0), "u_z": (1, 0, 0)}


def to_si(system, dimension, dim, per_length=False):
    """The factor from a value in @p system to SI."""
    length, mass = UNITS[system]
    l, m, t = dimension
    if per_length and dim == 2:
        l -= 1
    return float(length ** l * mass ** m)


def dimension_of(prm):
    with open(prm) as f:
        for line in f:
            words = line.split("#")[0].split()
            if words[:3] == ["set", "Dimension", "="]:
                return int(words[3])
    return 2


def peaks(tables, table):
    """The scale of each column of @p table over @p tables (lists of
    rows): the largest magnitude of the columns of its unit (a force
    column against every force column: the reaction in a direction
    nothing pushes is round-off of the forces, not a quantity of its
    own)."""
    largest = {}
    for rows in tables:
        for column in table:
            if rows and column in rows[0]:
                unit = table[column]
                largest[unit] = max([largest.get(unit, 0.)] +
                                    [abs(float(r[column])) for r in rows])
    return {column: largest.get(table[column], 0.) for column in table}


def compare_columns(label, si_rows, rows, system, dim, table, per_length,
                    peak_of, tolerance=1e-8):
    """Columns of @p rows (in @p system) against @p si_rows, each relative
    to its peak over the SI run (@p peak_of); returns the largest relative
    deviation."""
    worst, where, unequal = 0., "", []
    for column in si_rows[0]:
        if column in COUNTS or column == "state":
            if any(a[column] != b[column] for a, b in zip(si_rows, rows)):
                unequal.append(column)
            continue
        if column not in table:
            continue
        factor = to_si(system, table[column], dim,
                       per_length and table[column] in (FORCE, ENERGY))
        a = [float(r[column]) for r in si_rows]
        b = [float(r[column]) * factor for r in rows]
        peak = peak_of[column]
        if peak == 0:
            deviation = max(abs(x) for x in b)
        else:
            deviation = max(abs(x - y) for x, y in zip(a, b)) / peak
        if deviation > worst:
            worst, where = deviation, column
    check(worst <= tolerance and not unequal,
          "%s: every column equal to %g of its peak (largest %.1e, %s)%s"
          % (label, tolerance, worst, where or "-",
             "; counts or states differ: " + ", ".join(unequal)
             if unequal else ""))
    return worst


def well_posedness(out):
    """The lines of the well-posedness report in out/log.txt ([]: none)."""
    with open(os.path.join(out, "log.txt")) as f:
        lines = f.read().splitlines()
    report = []
    for line in lines:
        if line.startswith("  well-posedness"):
            report.append(line)
        elif report and line.startswith("    "):
            report.append(line)
        elif report:
            break
    return report


def convert_scene(args, name, source):
    """@p source converted from SI into every system of SYSTEMS by
    scripts/convert-units; returns the files by system."""
    converter = os.path.join(args.source_dir, "scripts", "convert-units")
    files = {}
    for system in SYSTEMS:
        files[system] = os.path.join(args.work_dir,
                                     "%s-%s.prm" % (name, system))
        command = [sys.executable, converter, "--from", "SI", "--to",
                   system, source, "-o", files[system]]
        subprocess.run(command, check=True)
    return files


def run_systems(args, name, files, overrides, processes):
    """The scene in every system on @p processes; returns the output
    directories by system (None where the run failed)."""
    outputs = {}
    for system in SYSTEMS:
        out = os.path.join(args.work_dir, "%s-%s-np%d"
                           % (name, system, processes))
        ok = run_scene(args.program, files[system], out,
                       COMMON + overrides, processes, args.mpiexec)
        check(ok, "%s in %s on %d process(es): completed"
              % (name, system, processes))
        outputs[system] = out if ok else None
    return outputs


def compare_time_series(label, si_series, series, system, dim):
    """time_series.csv of a run in @p system against the SI run's: the
    steps, the solver's path, the columns, the diagnostics."""
    check(len(series) == len(si_series),
          "%s: as many steps (%d, SI %d)"
          % (label, len(series) - 1, len(si_series) - 1))
    differing = [int(a["step"]) for a, b in
                 zip(si_series, series)
                 if any(a[c] != b[c] for c in PATH)]
    check(not differing,
          "%s: the same cut-backs, Newton iterations and "
          "passes in every step (%d steps differ%s)"
          % (label, len(differing),
             (": " + ", ".join(map(str, differing[:8])))
             if differing else ""))
    compare_columns(label + ", time_series.csv", si_series,
                    series, system, dim, TIME_SERIES, True,
                    peaks([si_series], TIME_SERIES))
    # The diagnostics with their own tolerances.
    energy = max(abs(float(r["total_energy"]))
                 for r in si_series) or 1.
    factor = to_si(system, ENERGY, dim, True)
    defect = max(abs(float(r["energy_balance_defect"])) * factor
                 for r in series)
    check(defect <= 1e-8 * energy,
          "%s: energy balance defect below 1e-8 of the energy "
          "(%.1e)" % (label, defect / energy))
    residual = max(float(r["coefficient_residual"])
                   for r in series)
    check(residual <= 1e-6,
          "%s: friction-law residual below the Coefficient "
          "tolerance (%.1e)" % (label, residual))


def compare_system(label, si, out, system, dim):
    """The run in @p out (in @p system) against the SI run in @p si: its
    time series, the contact CSVs, the well-posedness report."""
    si_series = read_csv(os.path.join(si, "time_series.csv"))
    si_contact = sorted(glob.glob(os.path.join(si, "contact_*.csv")))
    series = read_csv(os.path.join(out, "time_series.csv"))
    compare_time_series(label, si_series, series, system, dim)
    contact = sorted(glob.glob(os.path.join(out,
                                            "contact_*.csv")))
    check([os.path.basename(f) for f in contact] ==
          [os.path.basename(f) for f in si_contact],
          "%s: the same contact CSVs" % label)
    si_report = well_posedness(si)
    check(si_report and well_posedness(out) == si_report,
          "%s: the same well-posedness report (%d lines)"
          % (label, len(si_report)))
    si_tables = [read_csv(f) for f in si_contact]
    peak_of = peaks(si_tables, CONTACT)
    for a, b in zip(si_tables, contact):
        compare_columns("%s, %s" % (label, os.path.basename(b)),
                        a, read_csv(b), system, dim, CONTACT,
                        False, peak_of)


def main():
    parser = program_arguments(__doc__)
    parser.add_argument("--mpiexec", default="mpiexec")
    parser.add_argument("--scenes", default=",".join(SCENES))
    args = parser.parse_args()
    os.makedirs(args.work_dir, exist_ok=True)

    for name in args.scenes.split(","):
        source, overrides = SCENES[name]
        source = os.path.join(args.source_dir, source)
        dim = dimension_of(source)
        files = convert_scene(args, name, source)
        for processes in (1, 2):
            outputs = run_systems(args, name, files, overrides, processes)
            si = outputs["SI"]
            if si is None:
                continue
            for system in SYSTEMS[1:]:
                out = outputs[system]
                if out is None:
                    continue
                label = "%s, %s vs SI, %d process(es)" % (name, system,
                                                          processes)
                compare_system(label, si, out, system, dim)
    finish("unit_invariance")


if __name__ == "__main__":
    main()
