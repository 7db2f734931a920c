#!/usr/bin/python3
"""The ctest `shear_wave`: a plane shear wave reaching the frictional base
against the closed form of the base's slip rate, at backward Euler's first
order in k, in the regime with one root and in that with several.

    shear_wave.py --program build/dynamic-contact --work-dir DIR
                  [--source-dir REPO] [--steps K1,K2,...] [--dims 2]
                  [--scheme NAME]

prm/shear_wave.prm (2D, a layer with free sides) and
prm/shear_wave_3d.prm (3D, the pulse polarized along z), each with the
decay rate alpha = 8 s/m of the files (several roots: (a - b) alpha P > Z)
and alpha = 1 s/m (one root), run with k = 1e-5, 5e-6 and 2.5e-6 s (the
ctest: 2D only; the 3D runs take minutes each, benchmarks/closed-form). The
closed form (tests/closed_form.py, doc/theory.md section 10.2): the base
sticks while 2 tau_inc <= mu(0) P and slips otherwise at the v > 0 with
2 tau_inc - Z v = mu(v) P; where that has several roots, the program's
convexification loop, started from the last step's velocity, stays on the
branch it is on: the base sticks until 2 tau_inc exceeds mu(0) P, then
slips on the upper root, which it keeps after 2 tau_inc has fallen below
mu(0) P again, until that root disappears at the fold tau_fold. From the
node of the base at the centre of the layer (contact CSV of every step):

- D, the slip distance (its u_x, in 3D u_z, from the first CSV to the
  last) against the integral of v;
- the L1 error of the slip rate, sum_n k |w_n - v(t_n)| / D;
- with several roots, t_off: the time of the last step that slips,
  against the fold's time and the time at which 2 tau_inc falls to
  mu(0) P (where a rule "stick wherever sticking is a solution" would stop).

Checks: every run completes (cut-backs are counted, not refused: at the
jumps between the branches the semismooth Newton iteration needs some);
the error of D falls at each halving of k; with one root, D converges at
first order (ratio of successive differences 1.6 to 2.5; its Richardson
limit within 2 % of the closed form: what is left is the mesh's error,
-1.0 % on this mesh) and so does the L1 error (ratio 1.5 to 2.5); with
several roots, the base stops within 2 k of the fold's time at every k
and, at the finest k (where the two times lie 3.2 steps apart), at least
2 k after the time at which 2 tau_inc falls to mu(0) P, which tells the
upper root from the rule "stick wherever sticking is a solution"; in 3D (--dims 3) the pulse keeps its
polarization (the slip across it below 1e-3 of D).
Prints the table and one line per check;
exit code 1 if one failed.
"""

import glob
import math
import os

from closed_form import ShearBase
from script_checks import (check, finish, program_arguments, read_csv,
                           run_scene)

Z, P, A, TP = 1e6, 1e6, 1., 2.5e-4
MU_A, MU_B = 1., 0.5
CENTRE = 1.
STEPS = [1e-5, 5e-6, 2.5e-6]
ALPHAS = [8., 1.]
SCENES = {2: "prm/shear_wave.prm", 3: "prm/shear_wave_3d.prm"}


def tau_inc(t):
    return Z * A * math.sin(math.pi * t / TP) ** 2 if 0 <= t <= TP else 0.


def centre_history(out, dim):
    """(times, slip rate, slip along, slip across) of the centre node."""
    times, rates, u = [], [], []
    for path in sorted(glob.glob(os.path.join(out, "contact_*.csv"))):
        for n in read_csv(path):
            # 3D: the slab is thin in x, the pulse runs along z: the first
            # node at z = 1 (the nodes across the thickness move alike).
            if abs(float(n["z" if dim == 3 else "x"]) - CENTRE) > 1e-9:
                continue
            times.append(float(n["time"]))
            if dim == 2:
                rates.append(float(n["w_tau"]))
                u.append((float(n["u_x"]), 0.))
            else:
                # t_2 = t_1 x nu = x x (-y) = -z.
                rates.append(-float(n["w_tau_2"]))
                u.append((float(n["u_z"]), float(n["u_x"])))
            break
    return times, rates, u[-1][0] - u[0][0], u[-1][1] - u[0][1]


_DISTANCES = {}


def exact_distance(base, t_end, n=200000):
    """The integral of the closed form's v over [0, t_end] (trapezoidal
    rule, n intervals); computed once per base and t_end (the runs of one
    alpha end at the same time)."""
    key = (base.z, base.p, base.a, base.b, base.alpha, t_end, n)
    if key not in _DISTANCES:
        dt = t_end / n
        v = base.history([tau_inc(i * dt) for i in range(n + 1)])
        _DISTANCES[key] = dt * (sum(v) - (v[0] + v[-1]) / 2)
    return _DISTANCES[key]


def falling_time(level):
    """The time after the pulse's peak at which tau_inc falls to level:
    sin^2(pi t/Tp) = L, t = Tp - Tp/(2 pi) acos(1 - 2 L)."""
    ratio = min(level / (Z * A), 1.)
    return TP - TP / (2 * math.pi) * math.acos(1 - 2 * ratio)


def check_run(args, base, fold, dim, k, steps):
    """The run of @p dim with the step k: completed, its line of the
    table, its polarization (3D) and with several roots where it stops
    slipping. Returns (end time, D, L1 error), None if the run failed."""
    scene = os.path.join(args.source_dir, SCENES[dim])
    name = "%dD, alpha = %g" % (dim, base.alpha)
    out = os.path.join(args.work_dir, "%dd-%g-%g" % (dim, base.alpha, k))
    ok = run_scene(args.program, scene, out,
                   ["Time/Time step=%g" % k,
                    "Time/Scheme=" + args.scheme,
                    "Friction/Exponential/Decay rate=%g" % base.alpha])
    check(ok, "%s, k = %g: completed" % (name, k))
    if not ok:
        return None
    rows = read_csv(os.path.join(out, "time_series.csv"))
    cutbacks = sum(int(r["cutbacks"]) for r in rows)
    times, rates, d, across = centre_history(out, dim)
    end = times[-1]
    d_exact = exact_distance(base, end)
    exact = base.history([tau_inc(t) for t in times])
    l1 = sum((times[i] - times[i - 1]) * abs(rates[i] - exact[i])
             for i in range(1, len(times))) / d_exact
    slipping = [t for t, w in zip(times, rates) if w > 1e-3 * A]
    t_off = slipping[-1] if slipping else float("nan")
    print("    %-8g  %.6e  %+.3f %%  %.3e  %.4e  %d"
          % (k, d, 100 * (d / d_exact - 1), l1, t_off, cutbacks))
    if dim == 3:
        check(abs(across) <= 1e-3 * abs(d),
              "%s, k = %g: the slip keeps the pulse's polarization"
              " (across it %.1e of D)" % (name, k,
                                          abs(across / d)))
    if fold:
        t_fold = falling_time(fold[1])
        t_other = falling_time(MU_A * P / 2)
        check(abs(t_off - t_fold) <= 2 * k,
              "%s, k = %g: the base slips on the upper root until "
              "its fold: it stops at %.4e s, %.1f steps from the "
              "fold %.4e s (where 2 tau_inc falls to mu(0) P: "
              "%.4e s)" % (name, k, t_off, (t_off - t_fold) / k,
                           t_fold, t_other))
        if k == steps[-1]:
            check(t_off - t_other >= 2 * k,
                  "%s, k = %g: ... and not where sticking becomes "
                  "a solution again (%.1f steps after it)"
                  % (name, k, (t_off - t_other) / k))
    return end, d, l1


def check_convergence(name, base, fold, distances, l1s, end):
    """The error of D falls with k; with one root, D and the L1 error
    converge at first order."""
    d_exact = exact_distance(base, end)
    errors = [abs(x / d_exact - 1) for x in distances]
    check(errors[0] > errors[1] > errors[2],
          "%s: the error of D falls with k (%s)" % (
              name, ", ".join("%.2f %%" % (100 * e)
                              for e in errors)))
    if fold:
        return
    ratio = (distances[-2] - distances[-3]) / \
        (distances[-1] - distances[-2])
    limit = 2 * distances[-1] - distances[-2]
    check(1.6 <= ratio <= 2.5,
          "%s: D converges at first order in k (ratio of "
          "successive differences %.2f)" % (name, ratio))
    check(abs(limit / d_exact - 1) <= 0.02,
          "%s: the Richardson limit of D within 2 %% of the "
          "closed form %.6e m (%+.3f %%; what is left is "
          "the mesh's error)"
          % (name, d_exact, 100 * (limit / d_exact - 1)))
    r1 = l1s[-2] / l1s[-1]
    check(1.5 <= r1 <= 2.5,
          "%s: the L1 error of the slip rate falls at first "
          "order (ratio %.2f, order %.2f)"
          % (name, r1, math.log(r1, 2)))


def main():
    parser = program_arguments(__doc__)
    parser.add_argument("--steps", default=",".join("%g" % k for k in STEPS))
    parser.add_argument("--dims", default="2")
    parser.add_argument("--scheme", default="backward Euler")
    args = parser.parse_args()
    steps = [float(k) for k in args.steps.split(",")]
    os.makedirs(args.work_dir, exist_ok=True)
    for alpha in ALPHAS:
        base = ShearBase(Z, P, MU_A, MU_B, alpha)
        fold = base.fold()
        for dim in [int(d) for d in args.dims.split(",")]:
            name = "%dD, alpha = %g" % (dim, alpha)
            end = None
            print("%s (%s): k, D, D error, L1 error, t_off, cut-backs"
                  % (name, "several roots" if fold else "one root"))
            distances, l1s = [], []
            for k in steps:
                result = check_run(args, base, fold, dim, k, steps)
                if result is None:
                    continue
                end, d, l1 = result
                distances.append(d)
                l1s.append(l1)
            if len(distances) >= 3 and end:
                check_convergence(name, base, fold, distances, l1s, end)
    finish("shear_wave")


if __name__ == "__main__":
    main()
