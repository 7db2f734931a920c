#!/usr/bin/env python3
"""Compare two runs of a 2D scene on Gamma_3: pressure profiles and
displacements at given times, and the DoFs and wall time of each.

    compare_runs.py REFERENCE_DIR RUN_DIR [--times 0.2,0.4,0.6,0.8]

Both directories hold time_series.csv and contact_NNNNN.csv files (written
at the steps that reach the times, e.g. with Output/Output times). Nodes are
matched by position (the nodes of a coarser mesh are nodes of the finer
one); differences are relative to the reference's maximum:
  pressure: max_i |p_i - p_ref,i| / max |p_ref|
  displacement: max_i |u_i - u_ref,i| / max |u_ref|   (u = (u_x, u_y))
"""
import argparse
import csv
import glob
import os


def read_series(directory):
    with open(os.path.join(directory, "time_series.csv")) as f:
        return list(csv.DictReader(f))


def contact_at(directory, series, t):
    # The first step that reaches t.
    for row in series[1:]:
        time, k = float(row["time"]), float(row["time_step"])
        if time >= t * (1 - 1e-12) and time - k < t:
            step = int(row["step"])
            name = os.path.join(directory, "contact_%05d.csv" % step)
            with open(name) as f:
                rows = list(csv.DictReader(f))
            return time, {(round(float(r["x"]), 9), round(float(r["y"]), 9)): r
                          for r in rows}
    raise SystemExit("no step reaches t = %g in %s" % (t, directory))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("reference")
    parser.add_argument("run")
    parser.add_argument("--times", default="0.2,0.4,0.6,0.8")
    args = parser.parse_args()
    ref_series, run_series = read_series(args.reference), read_series(args.run)
    for name, series in (("reference", ref_series), ("run", run_series)):
        dofs = [int(r["dofs"]) for r in series[1:]]
        print("%-9s DoFs mean %.0f max %d" % (name, sum(dofs) / len(dofs), max(dofs)))
    print("time      pressure_diff  displacement_diff  common_nodes")
    for t in map(float, args.times.split(",")):
        time, ref = contact_at(args.reference, ref_series, t)
        _, run = contact_at(args.run, run_series, t)
        common = [key for key in run if key in ref]
        p_max = max(float(r["normal_pressure"]) for r in ref.values())
        u_max = max((float(r["u_x"]) ** 2 + float(r["u_y"]) ** 2) ** 0.5
                    for r in ref.values())
        dp = max(abs(float(run[k]["normal_pressure"]) -
                     float(ref[k]["normal_pressure"])) for k in common) / p_max
        du = max(((float(run[k]["u_x"]) - float(ref[k]["u_x"])) ** 2 +
                  (float(run[k]["u_y"]) - float(ref[k]["u_y"])) ** 2) ** 0.5
                 for k in common) / u_max
        print("%.4f    %.3e      %.3e          %d" % (time, dp, du, len(common)))


if __name__ == "__main__":
    main()
