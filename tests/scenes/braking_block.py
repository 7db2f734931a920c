#!/usr/bin/python3
"""The ctest `braking_block`: a block braking under the slip-rate law stops
where the closed form says, at backward Euler's first order in k.

    braking_block.py --program build/dynamic-contact --work-dir DIR
                     [--source-dir REPO]

prm/braking_block.prm (2D) and prm/braking_block_3d.prm (3D, sliding
obliquely) run with k = 8e-6, 4e-6 and 2e-6 s. A rigid block of height H
pressed by P on the foundation, with mu(v) = (a - b) exp(-alpha v) + b,
obeys dv/dt = -P mu(v)/(rho H); it stops at

    T_stop = rho H/(P alpha b) ln(((a - b) + b exp(alpha v0))/a)

after the distance D = rho H/P * integral_0^v0 v/mu(v) dv. From each run:

- the stopping time: where the velocity of the centre of mass, v0 plus the
  sum of k inertia_force/M over the steps (time_series.csv; the discrete
  momentum balance), first reaches zero (linear in the step's time);
- the distance: the mean displacement of the contact nodes from the first
  contact CSV to the last (the block rests on them after the stop).

Checks: every run completes with 0 cut-backs; at k = 2e-6 s the distance
and the time within 0.5 % of the closed form; the distance converges at
first order (the ratio of successive differences between 1.6 and 2.5); its
Richardson limit within 0.2 % of the closed form (what is left of the
body's elasticity); in 3D the block keeps its direction (0.6, 0, 0.8) to
1e-4. Prints the table and one line per check; exit code 1 if one failed.
"""

import glob
import math
import os

from script_checks import (check, finish, program_arguments, read_csv,
                           run_scene)

# The scenes' data (the closed form's).
RHO, H, P = 1000., 0.2, 1e6
A, B, ALPHA, V0 = 1., 0.5, 0.5, 4.
STEPS = [8e-6, 4e-6, 2e-6]
SCENES = {2: ("prm/braking_block.prm", (1., 0.)),
          3: ("prm/braking_block_3d.prm", (0.6, 0.8))}


def mu(v):
    return (A - B) * math.exp(-ALPHA * v) + B


def closed_form():
    """T_stop and D of the rigid block (D by Simpson's rule, 2e4 panels)."""
    scale = RHO * H / P
    t_stop = scale / (ALPHA * B) * math.log(((A - B) + B *
                                             math.exp(ALPHA * V0)) / A)
    n = 20000
    h = V0 / n
    f = [i * h / mu(i * h) for i in range(n + 1)]
    simpson = h / 3 * (f[0] + f[-1] + 4 * sum(f[1:-1:2]) +
                       2 * sum(f[2:-1:2]))
    return t_stop, scale * simpson


def stopping_time(rows, mass, direction, dim):
    """Where the centre of mass's speed along the sliding direction first
    reaches zero."""
    v = V0
    components = ["inertia_force_x", "inertia_force_z"] if dim == 3 else \
                 ["inertia_force_x"]
    for row in rows[1:]:
        k, t = float(row["time_step"]), float(row["time"])
        force = sum(d * float(row[c]) for d, c in zip(direction, components))
        v_new = v + k * force / mass
        if v_new <= 0:
            return t - k + k * v / (v - v_new)
        v = v_new
    return float("nan")


def distance(out, direction, dim):
    files = sorted(glob.glob(os.path.join(out, "contact_*.csv")))
    first, last = read_csv(files[0]), read_csv(files[-1])
    columns = ["u_x", "u_z"] if dim == 3 else ["u_x"]
    moved = [sum(float(b[c]) - float(a[c]) for a, b in zip(first, last)) /
             len(first) for c in columns]
    along = sum(d * m for d, m in zip(direction, moved))
    across = (moved[1] * direction[0] - moved[0] * direction[1]
              if dim == 3 else 0.)
    return along, across


def main():
    args = program_arguments(__doc__).parse_args()
    os.makedirs(args.work_dir, exist_ok=True)
    t_exact, d_exact = closed_form()
    print("closed form: T_stop = %.6e s, D = %.6e m" % (t_exact, d_exact))
    for dim, (scene, direction) in SCENES.items():
        area = 1. if dim == 2 else 1. * 1.   # the footprint (2D: per m)
        mass = RHO * H * area
        distances = []
        print("%dD  k          T_stop        error     D             error"
              % dim)
        for k in STEPS:
            out = os.path.join(args.work_dir, "%dd-%g" % (dim, k))
            completed = run_scene(args.program,
                                  os.path.join(args.source_dir, scene), out,
                                  ["Time/Time step=%g" % k])
            rows = read_csv(os.path.join(out, "time_series.csv")) \
                if completed else []
            cutbacks = sum(int(r["cutbacks"]) for r in rows)
            check(completed and cutbacks == 0,
                  "%dD, k = %g: completed with 0 cut-backs" % (dim, k))
            if not rows:
                continue
            t_stop = stopping_time(rows, mass, direction, dim)
            d, across = distance(out, direction, dim)
            distances.append(d)
            print("    %-9g  %.6e  %+.3f %%  %.6e  %+.3f %%"
                  % (k, t_stop, 100 * (t_stop / t_exact - 1), d,
                     100 * (d / d_exact - 1)))
            if dim == 3:
                check(abs(across) <= 1e-4 * d,
                      "3D, k = %g: the block keeps its direction (sideways "
                      "%.1e of the distance)" % (k, abs(across) / d))
            if k == STEPS[-1]:
                check(abs(t_stop / t_exact - 1) <= 5e-3,
                      "%dD, k = 2e-6 s: stopping time within 0.5 %% of the "
                      "closed form (%+.3f %%)"
                      % (dim, 100 * (t_stop / t_exact - 1)))
                check(abs(d / d_exact - 1) <= 5e-3,
                      "%dD, k = 2e-6 s: stopping distance within 0.5 %% of "
                      "the closed form (%+.3f %%)"
                      % (dim, 100 * (d / d_exact - 1)))
        if len(distances) == 3:
            ratio = (distances[1] - distances[0]) / \
                (distances[2] - distances[1])
            limit = distances[2] + (distances[2] - distances[1])
            check(1.6 <= ratio <= 2.5,
                  "%dD: the distance converges at first order in k (ratio "
                  "of successive differences %.2f)" % (dim, ratio))
            check(abs(limit / d_exact - 1) <= 2e-3,
                  "%dD: its Richardson limit within 0.2 %% of the closed "
                  "form (%+.3f %%)" % (dim, 100 * (limit / d_exact - 1)))
    finish("braking_block")


if __name__ == "__main__":
    main()
