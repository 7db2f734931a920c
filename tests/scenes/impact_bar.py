#!/usr/bin/python3
"""The ctest `impact_bar`: a bar dropped onto the foundation against the 1D
wave solution of an impact on a spring-dashpot wall, at backward Euler's
first order in k.

    impact_bar.py --program build/dynamic-contact --work-dir DIR
                  [--source-dir REPO]

prm/impact_bar.prm (2D, a column with rollers on its sides) and
prm/impact_bar_3d.prm (3D, rollers on four sides), each with the
foundation's damping d_nu = 5e5 Pa s/m (the files) and d_nu = 0, run with
backward Euler at k = 2e-5, 1e-5 and 5e-6 s (Q2, 32 cells along the bar).
The closed form (tests/closed_form.py, doc/theory.md section 10.1):
Z ds/dt + c_nu s_+ + d_nu (ds/dt)_+ = R(t) at the bar's end, R = Z V until
the reflection from the free top returns at T2 = 2L/c, d'Alembert's waves
after. From each run:

- s_n, the penetration of the end (contact CSV of every step), against
  s(t_n): the largest error over t_n < T2 (where s is the exponential
  Z V/c_nu (1 - exp(-t c_nu/(Z + d_nu)))), relative to Z V/c_nu;
- the contact duration T_c: where s_n falls through 0 (linear in the step);
- the peak force per unit area: the largest normal_force/area of a step;
- the rebound velocity v_r of the centre of mass at the end time, -V plus
  the sum of k inertia_force_y/M (the discrete momentum balance).

Checks: every run completes with 0 cut-backs; the 3D runs give the 2D
numbers to 1e-9 (the problem is 1D in both); at k = 5e-6 s the errors of
T_c within 0.5 %, of v_r within 2 % of V, of the peak force within 2 %;
T_c and v_r converge at first order (ratio of successive differences 1.6
to 2.5) and their Richardson limits lie within 0.05 % of T_c and 0.1 % of
V; the errors of s(t < T2) and of the peak force fall by a factor 1.25 or
more at each halving of k (they converge more slowly than first order:
the force has a kink at T2, and with damping a jump at 0 and T2, which
backward Euler smooths over a width that shrinks like the square root of
k). Prints the table and one line per check;
exit code 1 if one failed.
"""

import glob
import math
import os

from closed_form import ImpactBar, crossing
from script_checks import (check, finish, program_arguments, read_csv,
                           run_scene)

RHO, EP, LENGTH, V, C_NU = 1000., 1e9, 1., 1., 2.5e9
WIDTH = 0.1
END = 3e-3
STEPS = [2e-5, 1e-5, 5e-6]
DAMPINGS = [5e5, 0.]
SCENES = {2: "prm/impact_bar.prm", 3: "prm/impact_bar_3d.prm"}


def measure(out, dim, exact):
    """(window error of s, T_c, peak force, v_r) of a run."""
    rows = read_csv(os.path.join(out, "time_series.csv"))
    area = WIDTH if dim == 2 else WIDTH * WIDTH
    mass = RHO * LENGTH * area
    times = [float(r["time"]) for r in rows]
    force = [float(r["normal_force"]) / area for r in rows]
    v = -V
    for r in rows[1:]:
        v += float(r["time_step"]) * float(r["inertia_force_y"]) / mass
    s = [0.]
    for path in sorted(glob.glob(os.path.join(out, "contact_*.csv")))[1:]:
        nodes = read_csv(path)
        s.append(sum(float(n["u_nu"]) for n in nodes) / len(nodes))
    window = max(abs(a - exact.penetration(t)) for a, t in zip(s, times)
                 if t < exact.t2) / (exact.z * V / C_NU)
    cutbacks = sum(int(r["cutbacks"]) for r in rows)
    return window, crossing(times, s), max(force), v, times[-1], cutbacks


def order_checks(name, values, reference, scale, limit_tolerance, what):
    """First order of three values at k, k/2, k/4 and their Richardson
    limit."""
    ratio = (values[1] - values[0]) / (values[2] - values[1])
    limit = 2 * values[2] - values[1]
    check(1.6 <= ratio <= 2.5,
          "%s: %s converges at first order in k (ratio of successive "
          "differences %.2f)" % (name, what, ratio))
    check(abs(limit - reference) <= limit_tolerance * scale,
          "%s: the Richardson limit of %s within %g %% of the closed form "
          "(%+.4f %%)" % (name, what, 100 * limit_tolerance,
                         100 * (limit - reference) / scale))


def main():
    args = program_arguments(__doc__).parse_args()
    os.makedirs(args.work_dir, exist_ok=True)
    results = {}
    for d_nu in DAMPINGS:
        exact = ImpactBar(RHO, EP, LENGTH, V, C_NU, d_nu, END + 1e-4, 20000)
        t_c, f_max = exact.contact_end(), exact.peak_force()
        print("d_nu = %g Pa s/m: closed form T_c = %.6e s, peak force "
              "%.6e Pa, v_r = %.6f m/s (T2 = %g s)"
              % (d_nu, t_c, f_max, exact.centre_velocity(END), exact.t2))
        for dim, scene in SCENES.items():
            name = "%dD, d_nu = %g" % (dim, d_nu)
            print("%-16s k        s error (t<T2)  T_c error   peak force "
                  "error  v_r error (of V)" % name)
            tcs, vrs, windows, peaks = [], [], [], []
            for k in STEPS:
                out = os.path.join(args.work_dir, "%dd-%g-%g" % (dim, d_nu, k))
                ok = run_scene(args.program,
                               os.path.join(args.source_dir, scene), out,
                               ["Time/Time step=%g" % k,
                                "Time/End time=%g" % END,
                                "Foundation/Normal damping/Capped ramp/"
                                "Coefficient=%g" % d_nu])
                m = measure(out, dim, exact) if ok else None
                check(ok and m[5] == 0, "%s, k = %g: completed with 0 "
                      "cut-backs" % (name, k))
                if not m:
                    continue
                window, tc, fm, vr, t_end, _ = m
                vr_exact = exact.centre_velocity(t_end)
                results[(dim, d_nu, k)] = (window, tc, fm, vr)
                tcs.append(tc)
                vrs.append(vr)
                windows.append(window)
                peaks.append(abs(fm / f_max - 1))
                print("%-16s %-8g %+.3e      %+.3f %%   %+.3f %%        "
                      "%+.3f %%" % ("", k, window, 100 * (tc / t_c - 1),
                                    100 * (fm / f_max - 1),
                                    100 * (vr - vr_exact) / V))
                if dim == 3 and (2, d_nu, k) in results:
                    two = results[(2, d_nu, k)]
                    spread = max(abs(a - b) / abs(b) for a, b in
                                 zip(two[1:], (tc, fm, vr)))
                    check(spread <= 1e-9, "%s, k = %g: the 3D run gives the "
                          "2D numbers (largest relative difference %.1e)"
                          % (name, k, spread))
                if k == STEPS[-1]:
                    check(abs(fm / f_max - 1) <= 0.02,
                          "%s, k = %g: peak force within 2 %% (%+.3f %%)"
                          % (name, k, 100 * (fm / f_max - 1)))
                    check(abs(tc / t_c - 1) <= 5e-3,
                          "%s, k = %g: contact duration within 0.5 %% "
                          "(%+.3f %%)" % (name, k, 100 * (tc / t_c - 1)))
                    check(abs(vr - vr_exact) <= 0.02 * V,
                          "%s, k = %g: rebound velocity within 2 %% of V "
                          "(%+.3f %%)" % (name, k,
                                          100 * (vr - vr_exact) / V))
            if len(tcs) == 3:
                for what, e in (("s(t) for t < T2", windows),
                                ("the peak force", peaks)):
                    ratios = [e[i] / e[i + 1] for i in range(2)]
                    check(min(ratios) >= 1.25,
                          "%s: the error of %s falls with k (ratios %.2f, "
                          "%.2f; order %.2f at the finest)"
                          % (name, what, ratios[0], ratios[1],
                             math.log(ratios[1], 2)))
                order_checks(name, tcs, t_c, t_c, 5e-4, "T_c")
                order_checks(name, vrs, exact.centre_velocity(END), V, 1e-3,
                             "v_r")
    finish("impact_bar")


if __name__ == "__main__":
    main()
