"""The quantities an engineer reads from a run of the paper's scene, and
their errors against the extrapolated reference of benchmarks/reference
(doc/accuracy.md defines every one of them).

Not a command; imported by benchmarks/reference and benchmarks/work-precision.

Quantities (keys of QUANTITIES):
  normal_force     N(t), time_series.csv `normal_force`
  friction_force   the friction-force history, time_series.csv
                   `tangential_force` (sum over Gamma_3 of |lambda_i|)
  friction_l1      the same history measured by its mean error over time
                   (the L1 norm below), with its own reference: where a
                   node's slip reverses, the node sticks for less than a
                   step, and F(t) has dips one step wide that a given step
                   catches or misses; they keep its max-norm error from
                   falling with k, while their weight in the mean is of
                   the order of k
  deflection       the largest deflection over Gamma_3,
                   delta(t) = max_x (-u_y(x, t)), from the contact CSVs
  pressure         the Gamma_3 pressure profiles p(x, t), contact CSV
                   `normal_pressure`, at t = 0.2, 0.4, 0.6, 0.8
  traction         the Gamma_3 friction-traction profiles, contact CSV
                   `tangential_traction`, at the same times
  energy           the energy history E(t), time_series.csv `total_energy`
  theorem6         max_t (||eps(e_u)|| + ||e_w||) on the VTU fields at
                   t = 1/8, ..., 1 (benchmarks/solution_error.py), against the
                   finest reference run (not extrapolated)

Errors (relative; maxima but for friction_l1):
  history q(t):  max over the run's samples t_i in [1/16, 1] of
                 |q(t_i) - q_ref(t_i)| / max_t |q_ref(t)|, over the samples
                 that are steps of the reference (k = 1/320) if there are 4
                 or more, else q_ref interpolated linearly (the first 1/16 s, the transient of the load
                 switched on at t = 0 next to the clamped end, is left out:
                 there the first steps' values depend on k at the per-cent
                 level and do not converge at the rate of the rest);
  L1 history:    int |q - q_ref| dt / int |q_ref| dt over the same samples
                 and interval (trapezoidal rule), for friction_l1;
  profile at T:  max over the run's Gamma_3 nodes x_j of
                 |p(x_j, T) - p_ref(x_j, T)| / max_x |p_ref(x, T)|,
                 p_ref interpolated linearly in x; the error of the quantity
                 is the largest over T = 0.2, 0.4, 0.6, 0.8. A run whose
                 time grid misses T gives the linear interpolation in time
                 between its steps just before and just after T.
"""
import math
import os

import numpy as np

import benchlib
from dynamic_contact.output import Run

PROFILE_TIMES = [0.2, 0.4, 0.6, 0.8]
HISTORY_START = 1.0 / 16  # histories are compared on [HISTORY_START, 1]
VTU_TIMES = [i / 8 for i in range(1, 9)]
HISTORIES = ["normal_force", "friction_force", "friction_l1", "deflection", "energy"]
# The histories measured in the L1 norm in time (size()), each a column of
# time_series.csv.
L1_HISTORIES = {"friction_l1": "tangential_force"}
PROFILES = ["pressure", "traction"]
QUANTITIES = {  # key: (title, short label)
    "normal_force": ("contact-force history N(t)", "N(t)"),
    "friction_force": ("friction-force history", "friction force(t)"),
    "friction_l1": ("friction-force history, mean error over time (L1)",
                    "friction force (L1)"),
    "deflection": ("largest deflection max_x(-u_y) over time", "deflection(t)"),
    "pressure": ("Gamma3 pressure profiles, t = 0.2, 0.4, 0.6, 0.8", "pressure profiles"),
    "traction": ("Gamma3 friction-traction profiles, t = 0.2, ..., 0.8", "traction profiles"),
    "energy": ("energy history E(t)", "energy E(t)"),
    "theorem6": ("Theorem-6 norm max_t(||eps(e_u)|| + ||e_w||)", "Theorem-6 norm"),
}
COLUMN = {"normal_force": "normal_force", "friction_force": "tangential_force",
          "energy": "total_energy"}
PROFILE_COLUMN = {"pressure": "normal_pressure", "traction": "tangential_traction"}

# The runs of benchmarks/reference: cells nx x ny, k = 1/m; the finest one's
# VTU fields are the reference of the Theorem-6 error.
REFERENCE_RUNS = os.path.join(benchlib.SCRATCH, "reference-wp")
FINEST = (512, 64, 320)


def run_name(nx, ny, m):
    return "h%dx%d-k%d" % (nx, ny, m)


def finest_directory():
    return os.path.join(REFERENCE_RUNS, run_name(*FINEST))


def field_times(directory):
    """The VTU_TIMES the run in `directory` wrote VTU at (a cut-back shifts
    a run's later steps off 'VTU every')."""
    from dynamic_contact.vtu import read_pvd
    written = [t for t, _ in read_pvd(os.path.join(directory, "solution.pvd"))]
    return [t for t in VTU_TIMES if any(abs(t - w) < 1e-6 for w in written)]


# 'Output/Output times' writes at the first step with t >= t_out (to a
# round-off allowance); asking for t - 1e-7 makes the step at t the one.
SHIFT = 1e-7


def bracket_times(T, k):
    """The step times of a fixed step k just before and just after T (one
    time if T is a step time)."""
    m = T / k
    if abs(m - round(m)) < 1e-6:
        return [round(m) * k]
    return [math.floor(m) * k, math.ceil(m) * k]


def output_times(k):
    """The Output times a run with step k needs: the VTU times 1/8, ..., 1
    and the steps at or around each profile time."""
    times = set(round(t, 12) for t in VTU_TIMES)
    for T in PROFILE_TIMES:
        times.update(round(t, 12) for t in bracket_times(T, k))
    return sorted(t for t in times if t > 0)


def output_overrides(k, write_vtu=True):
    """The output of a measured run: contact CSV (and VTU) at output_times(k)
    only, no progress lines, no timings."""
    entry = ", ".join("%.10g" % (t - SHIFT) for t in output_times(k))
    return ["Output/Output every=0", "Output/VTU every=0",
            "Output/Write VTU=%s" % ("true" if write_vtu else "false"),
            "Output/Output times=" + entry,
            "Output/Progress every=0", "Output/Print timings=false"]


def _profile_at(run, steps_times, T, column):
    """(x, values) of a contact CSV column at time T: the file at T, or the
    linear interpolation in time between the files just before and after."""
    before = [(t, s) for s, t in steps_times if t <= T + 1e-9]
    after = [(t, s) for s, t in steps_times if t >= T - 1e-9]
    if not before or not after:
        raise ValueError("%s: no contact CSV at or around t = %g" % (run.directory, T))
    t0, s0 = max(before)
    t1, s1 = min(after)
    c0 = run.contact(s0)
    x = np.asarray(c0["x"], dtype=float)
    v0 = np.asarray(c0[column], dtype=float)
    if s1 == s0 or t1 - t0 < 1e-12:
        return x, v0
    c1 = run.contact(s1)
    v1 = np.interp(x, np.asarray(c1["x"], dtype=float), np.asarray(c1[column], dtype=float))
    a = (T - t0) / (t1 - t0)
    return x, (1 - a) * v0 + a * v1


def extract(directory):
    """The quantities of one run: histories as (t, q) arrays over its steps
    (deflection: over the steps with a contact CSV), profiles as
    {T: (x, p)}."""
    run = Run(directory)
    ts = run.time_series
    t = np.asarray(ts["time"], dtype=float)
    keep = t >= HISTORY_START - 1e-9
    q = {}
    for key, column in list(COLUMN.items()) + list(L1_HISTORIES.items()):
        q[key] = (t[keep], np.asarray(ts[column], dtype=float)[keep])
    steps_times = [(s, run.time_of(s)) for s in run.contact_steps if s > 0]
    kept = [(s, tt) for s, tt in steps_times if tt >= HISTORY_START - 1e-9]
    td = np.array([tt for _, tt in kept])
    d = np.array([float(np.max(-np.asarray(run.contact(s)["u_y"], dtype=float)))
                  for s, _ in kept])
    q["deflection"] = (td, d)
    for key, column in PROFILE_COLUMN.items():
        q[key] = {T: _profile_at(run, steps_times, T, column) for T in PROFILE_TIMES}
    return q


def size(key, x, y):
    """The norm of quantity `key` of the values y at the samples x: the
    mean of |y| over [x_0, x_end] (trapezoidal rule) for an L1 history,
    else max |y|."""
    y = np.abs(np.asarray(y, dtype=float))
    if key in L1_HISTORIES and len(x) > 1:
        return float(np.trapz(y, x) / (x[-1] - x[0]))
    return float(np.max(y))


def history_error(run_t, run_q, ref_t, ref_q, key=None):
    """max_i |q(t_i) - q_ref(t_i)| / max |q_ref| over the run's samples
    (extract() has left out those before HISTORY_START); for an L1 history
    the mean of |q - q_ref| over them relative to the mean of |q_ref| over
    the same samples (size())."""
    keep = (run_t >= ref_t[0] - 1e-9) & (run_t <= ref_t[-1] + 1e-9)
    j = np.clip(np.searchsorted(ref_t, run_t), 1, len(ref_t) - 1)
    nearest = np.minimum(np.abs(ref_t[j] - run_t), np.abs(ref_t[j - 1] - run_t))
    on_grid = keep & (nearest < 1e-9)
    if on_grid.sum() >= 4:  # compare where the reference has a step: no interpolation
        keep = on_grid
    t = run_t[keep]
    ref_on = np.interp(t, ref_t, ref_q)
    if key in L1_HISTORIES:
        return size(key, t, run_q[keep] - ref_on) / size(key, t, ref_on)
    return size(key, t, run_q[keep] - ref_on) / float(np.max(np.abs(ref_q)))


def profile_error(run_profiles, ref_profiles):
    """max over T of max_j |p(x_j) - p_ref(x_j)| / max |p_ref| at T."""
    worst = 0.0
    for T in PROFILE_TIMES:
        x, p = run_profiles[T]
        xr, pr = ref_profiles[T]
        worst = max(worst, float(np.max(np.abs(p - np.interp(x, xr, pr))) / np.max(np.abs(pr))))
    return worst


def errors(run_q, ref):
    """The relative error of every quantity but theorem6 (see the module's
    docstring) of the quantities `run_q` (extract()) against `ref`
    (read_reference()); a history the reference lacks (one made before
    friction_l1 existed) is left out."""
    out = {}
    for key in HISTORIES:
        if key in ref:
            out[key] = history_error(*run_q[key], *ref[key], key=key)
    for key in PROFILES:
        out[key] = profile_error(run_q[key], ref[key])
    return out


# --- Richardson on sampled quantities ------------------------------------------

def samples(q, key):
    """A quantity as a list of (x, y) arrays: one for a history, one per
    profile time for a profile."""
    if key in PROFILES:
        return [q[key][T] for T in PROFILE_TIMES]
    return [q[key]]


def scale(ref_parts, key=None):
    return [size(key, x, y) for x, y in ref_parts]


def rel_max(parts, scales, key=None):
    """max over the parts (x, y) of size(y) / scale of that part."""
    return max(size(key, x, y) / s for (x, y), s in zip(parts, scales))


def diff_on(coarse, fine):
    """fine - coarse on the coarse samples (fine interpolated linearly:
    exact on nested samples)."""
    x, y = coarse
    return x, np.interp(x, fine[0], fine[1]) - y


def order(levels, scales, key=None):
    """Observed order from three levels, coarse to fine, each a list of
    parts: log2(|d01| / |d12|), differences on the coarsest samples."""
    d01 = [diff_on(a, b) for a, b in zip(levels[0], levels[1])]
    d12 = [(x, np.interp(x, *c2) - np.interp(x, *c1))
           for (x, _), c1, c2 in zip(levels[0], levels[1], levels[2])]
    a, b = rel_max(d01, scales, key), rel_max(d12, scales, key)
    if b <= 0 or a <= 0:
        return float("nan"), a, b
    return float(np.log2(a / b)), a, b


def correction(coarse, fine, p, factor_fine=False):
    """(fine - coarse)/(2^p - 1) (times 2^p with factor_fine) on the coarse
    samples."""
    x, d = diff_on(coarse, fine)
    f = 2.0 ** p / (2.0 ** p - 1) if factor_fine else 1.0 / (2.0 ** p - 1)
    return x, f * d


def used(p):
    """The order a correction uses: the observed one clipped to [1, 3]; None
    if the sequence does not converge (observed order below 1/2 or
    undefined): then no correction is made."""
    if not p == p or p < 0.5:
        return None
    return float(min(max(p, 1.0), 3.0))


# --- the reference files in benchmarks/results -------------------------------

def write_reference(results_dir, histories, profiles, header, prefix="reference"):
    """PREFIX_histories.csv (time, normal_force, friction_force, energy,
    deflection interpolated onto the same times, the L1 histories) and PREFIX_profiles.csv (time, x,
    pressure, traction); PREFIX is 'reference' for the paper's scene."""
    t = histories["normal_force"][0]
    path = os.path.join(results_dir, prefix + "_histories.csv")
    with open(path, "w") as f:
        f.write(header)
        f.write("time,normal_force,friction_force,energy,deflection,"
                + ",".join(L1_HISTORIES) + "\n")
        td, d = histories["deflection"]
        dd = np.interp(t, td, d)
        for i in range(len(t)):
            f.write("%.10g,%.10e,%.10e,%.10e,%.10e" % (
                t[i], histories["normal_force"][1][i], histories["friction_force"][1][i],
                histories["energy"][1][i], dd[i]))
            f.write("".join(",%.10e" % histories[key][1][i] for key in L1_HISTORIES) + "\n")
    path2 = os.path.join(results_dir, prefix + "_profiles.csv")
    with open(path2, "w") as f:
        f.write(header)
        f.write("time,x,pressure,traction\n")
        for T in PROFILE_TIMES:
            x, p = profiles["pressure"][T]
            x2, tr = profiles["traction"][T]
            tr = np.interp(x, x2, tr)
            for j in range(len(x)):
                f.write("%.10g,%.10g,%.10e,%.10e\n" % (T, x[j], p[j], tr[j]))
    return path, path2


def _read_csv(path):
    with open(path) as f:
        lines = [line for line in f if not line.startswith("#")]
    names = lines[0].strip().split(",")
    data = np.array([[float(v) for v in line.split(",")] for line in lines[1:] if line.strip()])
    return {n: data[:, i] for i, n in enumerate(names)}


def read_reference(results_dir, prefix="reference"):
    """The reference quantities in the layout of extract() (PREFIX as for
    write_reference)."""
    h = _read_csv(os.path.join(results_dir, prefix + "_histories.csv"))
    ref = {key: (h["time"], h[key]) for key in HISTORIES if key in h}
    p = _read_csv(os.path.join(results_dir, prefix + "_profiles.csv"))
    for key in PROFILES:
        ref[key] = {}
        for T in PROFILE_TIMES:
            rows = np.abs(p["time"] - T) < 1e-9
            ref[key][T] = (p["x"][rows], p[key][rows])
    return ref
