"""The quantities of the 3D rail's first 0.25 s (prm/rail_3d.prm) and their
errors against the extrapolated reference of benchmarks/work-precision-3d
(doc/accuracy.md section 4), and the observed order of a sequence of
three levels with any refinement ratios.

Not a command; imported by benchmarks/work-precision-3d and checked by the
ctest `engineering_error`.
"""
import numpy as np

from dynamic_contact.output import Run

T_END, T_START = 0.25, 1.0 / 16
GRID = [j / 128 for j in range(8, 33)]  # the reference's samples of histories
PROFILE_TIMES = [0.125, 0.25]
CENTRE_Z = 0.05
HISTORIES = ["normal_force", "friction_force", "deflection", "energy"]
PROFILES = ["pressure"]
KEYS = HISTORIES + PROFILES
COLUMN = {"normal_force": "normal_force", "friction_force": "tangential_force",
          "energy": "total_energy"}
LABEL = {"normal_force": "N(t)", "friction_force": "friction force(t)",
         "deflection": "deflection(t)", "pressure": "pressure profiles",
         "energy": "energy E(t)"}


def extract(directory):
    """{key: (t, q)} for the histories (deflection over the steps with a
    contact CSV), {T: (x, p)} for the pressure on the centre line."""
    run = Run(directory)
    ts = run.time_series
    q = {}
    t = np.asarray(ts["time"], dtype=float)
    for key, column in COLUMN.items():
        q[key] = (t, np.asarray(ts[column], dtype=float))
    steps = [(s, run.time_of(s)) for s in run.contact_steps if s > 0]
    td = np.array([tt for _, tt in steps])
    d = np.array([float(np.max(-np.asarray(run.contact(s)["u_y"], dtype=float)))
                  for s, _ in steps])
    q["deflection"] = (td, d)
    profiles = {}
    for T in PROFILE_TIMES:
        at = [s for s, tt in steps if abs(tt - T) < 1e-9]
        if not at:
            raise ValueError("%s: no contact CSV at t = %g" % (directory, T))
        c = run.contact(at[0])
        z = np.asarray(c["z"], dtype=float)
        keep = np.abs(z - CENTRE_Z) < 1e-9
        x = np.asarray(c["x"], dtype=float)[keep]
        p = np.asarray(c["normal_pressure"], dtype=float)[keep]
        order = np.argsort(x)
        profiles[T] = (x[order], p[order])
    q["pressure"] = profiles
    return q


def points(q, key):
    """The sample points of a run's quantity: its times (histories) or its
    (T, x) nodes (profiles)."""
    if key in HISTORIES:
        t = q[key][0]
        return [tt for tt in t if tt >= T_START - 1e-9]
    return [(T, x) for T in PROFILE_TIMES for x in q[key][T][0]]


def sample(q, key, at):
    """The run's quantity at the points `at` (linear interpolation)."""
    if key in HISTORIES:
        t, v = q[key]
        return np.interp(np.asarray(at, dtype=float), t, v)
    out = []
    for T, x in at:
        xs, p = q[key][T]
        out.append(np.interp(x, xs, p))
    return np.asarray(out)


def interpolate(at_from, values, at_to, key):
    """Values given at the points at_from, at the points at_to (linear)."""
    if key in HISTORIES:
        return np.interp(np.asarray(at_to, dtype=float), np.asarray(at_from, dtype=float),
                         values)
    out = np.zeros(len(at_to))
    for T in PROFILE_TIMES:
        xf = np.array([x for (TT, x) in at_from if TT == T])
        vf = np.array([v for (TT, _), v in zip(at_from, values) if TT == T])
        for i, (TT, x) in enumerate(at_to):
            if TT == T:
                out[i] = np.interp(x, xf, vf)
    return out


def history_error(q, key, ref_t, ref_v):
    t, v = q[key]
    keep = t >= T_START - 1e-9
    t, v = t[keep], v[keep]
    on_grid = np.array([np.min(np.abs(ref_t - tt)) < 1e-9 for tt in t])
    if on_grid.sum() >= 4:
        t, v = t[on_grid], v[on_grid]
    return float(np.max(np.abs(v - np.interp(t, ref_t, ref_v))) / np.max(np.abs(ref_v)))


def errors(q, ref):
    e = {}
    for key in HISTORIES:
        e[key] = history_error(q, key, *ref[key])
    scale = max(np.max(np.abs(p)) for _, p in ref["pressure"].values())
    e["pressure"] = max(float(np.max(np.abs(q["pressure"][T][1] -
                                            np.interp(q["pressure"][T][0], *ref["pressure"][T]))))
                        for T in PROFILE_TIMES) / scale
    return e


def observed_order(coarse, middle, fine, ratio_cm=2.0, ratio_mf=2.0):
    """The order p with (h_c^p - h_m^p) / (h_m^p - h_f^p) equal to the
    ratio of the max norms of the differences (h_c / h_m = ratio_cm,
    h_m / h_f = ratio_mf), by bisection on [0.05, 8]; nan if the
    differences do not shrink."""
    a = np.max(np.abs(coarse - middle))
    b = np.max(np.abs(middle - fine))
    if b == 0 or a <= b:
        return float("nan")
    r = a / b

    def f(p):
        hm = 1.0
        hc = ratio_cm ** p
        hf = ratio_mf ** -p
        return (hc - hm) / (hm - hf) - r

    lo, hi = 0.05, 8.0
    if f(lo) > 0 or f(hi) < 0:
        return float("nan")
    for _ in range(100):
        mid = (lo + hi) / 2
        lo, hi = (mid, hi) if f(mid) < 0 else (lo, mid)
    return (lo + hi) / 2


def used(p):
    return 2.0 if p != p else min(4.0, max(1.0, p))


