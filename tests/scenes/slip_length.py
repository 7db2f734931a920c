#!/usr/bin/python3
"""The ctest `slip_length`: the friction coefficient as a state that follows
the slip-rate law over a slip length (Friction/Slip length, doc/theory.md
section 1.6), checked against an ODE solution and node by node.

    slip_length.py --program build/dynamic-contact --work-dir DIR
                   [--source-dir REPO] [--mpiexec "mpiexec"]

1. The braking block (prm/braking_block.prm) with L = 1 mm: the rigid block
   of height H pressed by P obeys

       dv/dt = -P mu~/(rho H),   dmu~/dt = -((v + v*)/L) (mu~ - mu(v)),

   from v = v0 and mu~ = mu(v0) (steady sliding), integrated here by RK4
   with a step 100 times smaller than the program's smallest; it stops
   about 10 % later than with the law itself (L = 0). The program runs
   k = 8e-6, 4e-6 and 2e-6 s; checks: 0 cut-backs, the stopping time and
   distance within 0.5 % of the ODE's at 2e-6 s, first order in k (ratio
   of successive differences of the distance between 1.6 and 2.5), the
   Richardson limit within 0.2 % (what the body's elasticity leaves), and
   the run's distance at least 10 times closer to the ODE's than to the
   ODE's of L = 0, the law itself (the state acts). At k = 4e-6 s the
   coupled linearization (Friction/Linearization = coupled, the state's
   derivative inside Newton's method) gives the frozen run's answers to
   1e-6 of each column's peak, without a fallback, in fewer Newton
   iterations.
2. The adaptive small paper scene (prm/barboteu_danan_2016_adaptive_small.prm,
   remeshing every 8 steps) with L = 1 cm and v* = 1e-3 m/s, 32 steps on 1
   and on 2 processes: at every node of Gamma_3 in contact at two
   successive steps, at the same place (also across a change of the
   mesh), the coefficient the step used obeys the discrete law of
   backward Euler,

       mu_n = mu(s_n) + (mu_{n-1} - mu(s_n)) exp(-k (s_n + v*)/L),

   to 3e-6 (twice Friction/Coefficient tolerance and round-off: mu_{n-1}
   is the step's frozen coefficient, the state itself within the
   tolerance of it); and the 2-process run's time_series.csv equals the
   1-process run's to 1e-8 of each column's peak.
3. The same node by node on the small 3D rail (prm/rail_3d_small.prm, the
   paper's law, 16 steps, slip rate |w_tau| of both tangential
   components) on 1 and 2 processes.

Prints one line per check; exit code 1 if one failed.
"""

import glob
import math
import os

from script_checks import (check, finish, program_arguments, read_csv,
                           run_scene)

# The braking block's data (prm/braking_block.prm).
RHO, H, P = 1000., 0.2, 1e6
A, B, ALPHA, V0 = 1., 0.5, 0.5, 4.
BLOCK_L = 1e-3
STEPS = [8e-6, 4e-6, 2e-6]

# The paper's law (the adaptive small scene).
PAPER = (1., 0.5, 2000.)
SCENE_L, SCENE_VSTAR = 1e-2, 1e-3

PHYSICAL = ["normal_force", "tangential_force", "total_energy",
            "kinetic_energy", "friction_dissipation", "load_work"]


def law(a, b, alpha):
    return lambda v: (a - b) * math.exp(-alpha * v) + b


def ode_stop(L, mu, dt):
    """Stopping time and distance of the rigid block with the state law
    (RK4 in t; linear at the stop)."""
    def f(v, m):
        if L == 0:  # the law itself
            return (-P * mu(v) / (RHO * H), 0., v)
        return (-P * m / (RHO * H), -(v / L) * (m - mu(v)), v)
    v, m, t, x = V0, mu(V0), 0., 0.
    while True:
        k1 = f(v, m)
        k2 = f(v + dt / 2 * k1[0], m + dt / 2 * k1[1])
        k3 = f(v + dt / 2 * k2[0], m + dt / 2 * k2[1])
        k4 = f(v + dt * k3[0], m + dt * k3[1])
        step = [dt / 6 * (a + 2 * b + 2 * c + d)
                for a, b, c, d in zip(k1, k2, k3, k4)]
        if v + step[0] <= 0:
            frac = v / -step[0]
            return t + frac * dt, x + frac * step[2]
        v, m, x, t = v + step[0], m + step[1], x + step[2], t + dt


def run(args, processes, scene, out, overrides):
    return run_scene(args.program, os.path.join(args.source_dir, scene), out,
                     overrides, processes, args.mpiexec)


def block_stop(out):
    """Stopping time (momentum balance of time_series.csv) and distance
    (mean displacement of the contact nodes) of a run."""
    rows = read_csv(os.path.join(out, "time_series.csv"))
    mass, v, t_stop = RHO * H, V0, float("nan")
    for row in rows[1:]:
        k, t = float(row["time_step"]), float(row["time"])
        v_new = v + k * float(row["inertia_force_x"]) / mass
        if v_new <= 0:
            t_stop = t - k + k * v / (v - v_new)
            break
        v = v_new
    files = sorted(glob.glob(os.path.join(out, "contact_*.csv")))
    first, last = read_csv(files[0]), read_csv(files[-1])
    d = sum(float(b["u_x"]) - float(a["u_x"])
            for a, b in zip(first, last)) / len(first)
    return t_stop, d, sum(int(r["cutbacks"]) for r in rows)


def braking_block(args):
    mu = law(A, B, ALPHA)
    t_ode, d_ode = ode_stop(BLOCK_L, mu, STEPS[-1] / 100)
    t_law, d_law = ode_stop(0., mu, STEPS[-1] / 100)
    print("ODE, L = %g m: T_stop = %.6e s, D = %.6e m (L = 0: %.6e s, "
          "%.6e m)" % (BLOCK_L, t_ode, d_ode, t_law, d_law))
    distances = []
    for k in STEPS:
        out = os.path.join(args.work_dir, "block-%g" % k)
        ok = run(args, 1, "prm/braking_block.prm", out,
                 ["Time/Time step=%g" % k, "Friction/Slip length=%g" % BLOCK_L])
        if not ok:
            check(False, "braking block, k = %g: completed" % k)
            continue
        t_stop, d, cutbacks = block_stop(out)
        distances.append(d)
        print("  k = %-7g T_stop %.6e (%+.3f %%)  D %.6e (%+.3f %%)"
              % (k, t_stop, 100 * (t_stop / t_ode - 1), d,
                 100 * (d / d_ode - 1)))
        check(cutbacks == 0, "braking block, k = %g: 0 cut-backs" % k)
        if k == STEPS[-1]:
            check(abs(t_stop / t_ode - 1) <= 5e-3 and
                  abs(d / d_ode - 1) <= 5e-3,
                  "braking block, k = 2e-6 s: stopping time and distance "
                  "within 0.5 %% of the ODE (%+.3f %%, %+.3f %%)"
                  % (100 * (t_stop / t_ode - 1), 100 * (d / d_ode - 1)))
            check(abs(d - d_law) >= 10 * abs(d - d_ode),
                  "braking block: the run is %.0f times closer to the ODE "
                  "with the slip length than to the law without it"
                  % (abs(d - d_law) / max(abs(d - d_ode), 1e-300)))
    coupled_linearization(args)
    if len(distances) == 3:
        ratio = (distances[1] - distances[0]) / (distances[2] - distances[1])
        limit = 2 * distances[2] - distances[1]
        check(1.6 <= ratio <= 2.5,
              "braking block: the distance converges at first order in k "
              "(ratio of successive differences %.2f)" % ratio)
        check(abs(limit / d_ode - 1) <= 2e-3,
              "braking block: its Richardson limit within 0.2 %% of the ODE "
              "(%+.3f %%)" % (100 * (limit / d_ode - 1)))


def coupled_linearization(args):
    """The braking block at k = 4e-6 s with Friction/Linearization =
    coupled (the state's derivative d mu_e/ds inside Newton's method)
    against the run of braking_block() (the default, frozen)."""
    frozen = os.path.join(args.work_dir, "block-4e-06")
    out = os.path.join(args.work_dir, "block-4e-06-coupled")
    ok = run(args, 1, "prm/braking_block.prm", out,
             ["Time/Time step=4e-06", "Friction/Slip length=%g" % BLOCK_L,
              "Friction/Linearization=coupled"])
    if not ok or not os.path.exists(os.path.join(frozen, "time_series.csv")):
        check(False, "braking block, coupled linearization: completed")
        return
    a = read_csv(os.path.join(frozen, "time_series.csv"))
    b = read_csv(os.path.join(out, "time_series.csv"))
    worst = 0.
    for column in PHYSICAL:
        x = [float(r[column]) for r in a]
        y = [float(r[column]) for r in b]
        peak = max(abs(v) for v in x) or 1.
        worst = max(worst, max(abs(p - q) for p, q in zip(x, y)) / peak)
    newton = [sum(int(r["newton_iterations"]) for r in t[1:]) for t in (a, b)]
    fallbacks = sum(int(r["coupled_fallbacks"]) for r in b[1:])
    check(len(a) == len(b) and worst <= 1e-6 and fallbacks == 0 and
          newton[1] < newton[0],
          "braking block, coupled linearization: the frozen run's answers to "
          "1e-6 of each column's peak (largest %.1e), 0 fallbacks (%d), fewer "
          "Newton iterations (%d against %d)"
          % (worst, fallbacks, newton[1], newton[0]))


def node_law_defect(out):
    """The largest defect of the discrete state law over the nodes in
    contact at two successive steps (matched by position), and how many
    pairs were checked, of which across a change of the mesh (2D or 3D:
    the contact CSV's columns tell)."""
    mu = law(*PAPER)
    rows = {int(r["step"]): r
            for r in read_csv(os.path.join(out, "time_series.csv"))}
    files = sorted(glob.glob(os.path.join(out, "contact_*.csv")))
    worst, pairs, remeshed, previous = 0., 0, 0, None
    for path in files:
        step = int(os.path.basename(path)[8:13])
        nodes = {}
        for r in read_csv(path):
            if float(r["normal_pressure"]) > 0:
                nodes[tuple(round(float(r[c]), 9) for c in "xyz" if c in r)] = r
        if previous is not None and previous[0] == step - 1:
            k = float(rows[step]["time_step"])
            changed = rows[step]["cells"] != rows[step - 1]["cells"]
            for key, r in nodes.items():
                if key not in previous[1]:
                    continue
                m = float(previous[1][key]["mu"])
                s = math.hypot(*[float(r[c]) for c in
                                 ("w_tau", "w_tau_1", "w_tau_2") if c in r])
                expected = mu(s) + (m - mu(s)) * math.exp(
                    -k * (s + SCENE_VSTAR) / SCENE_L)
                worst = max(worst, abs(float(r["mu"]) - expected))
                pairs += 1
                remeshed += changed
        previous = (step, nodes)
    return worst, pairs, remeshed


def node_by_node(args, name, scene, overrides, remeshing):
    """Runs `scene` with the slip length on 1 and 2 processes: the discrete
    state law at every node pair (across a change of the mesh too where
    `remeshing`), and 2 processes equal to 1."""
    overrides = overrides + ["Output/Output every=1", "Output/Output times=",
                             "Friction/Slip length=%g" % SCENE_L,
                             "Friction/Reference slip rate=%g" % SCENE_VSTAR,
                             "Solver/Minimum DoFs per process=0"]
    tables = {}
    for processes in (1, 2):
        out = os.path.join(args.work_dir, "%s-np%d" % (name.split()[0],
                                                       processes))
        ok = run(args, processes, scene, out, overrides)
        check(ok, "%s on %d process(es): completed" % (name, processes))
        if not ok:
            continue
        worst, pairs, remeshed = node_law_defect(out)
        check(worst <= 3e-6 and pairs > 0 and (remeshed > 0 or not remeshing),
              "%s on %d process(es): the discrete state law at %d node pairs "
              "(%d across a change of the mesh), largest defect %.1e <= 3e-6"
              % (name, processes, pairs, remeshed, worst))
        tables[processes] = read_csv(os.path.join(out, "time_series.csv"))
    if len(tables) == 2:
        one, two = tables[1], tables[2]
        worst, where = 0., "-"
        for column in PHYSICAL:
            a = [float(r[column]) for r in one]
            b = [float(r[column]) for r in two]
            peak = max(abs(x) for x in a) or 1.
            d = max(abs(x - y) for x, y in zip(a, b)) / peak
            if d > worst:
                worst, where = d, column
        check(len(one) == len(two) and worst <= 1e-8,
              "%s: 2 processes equal 1 to 1e-8 of each column's peak "
              "(largest %.1e, %s)" % (name, worst, where))


def main():
    parser = program_arguments(__doc__)
    parser.add_argument("--mpiexec", default="mpiexec")
    args = parser.parse_args()
    os.makedirs(args.work_dir, exist_ok=True)
    braking_block(args)
    node_by_node(args, "adaptive small scene",
                 "prm/barboteu_danan_2016_adaptive_small.prm",
                 ["Time/End time=0.25"], remeshing=True)
    node_by_node(args, "3D rail", "prm/rail_3d_small.prm", [],
                 remeshing=False)
    finish("slip_length")


if __name__ == "__main__":
    main()
