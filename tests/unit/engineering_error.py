#!/usr/bin/python3
"""The ctest `engineering_error`: the error measures and the Richardson
extrapolation of benchmarks/engineering_error.py (used by
benchmarks/reference and benchmarks/work-precision, doc/accuracy.md), on
data made by hand whose answers are known:

- Richardson in space (order 2) and in time (order 1) on nested samples
  recovers the limit exactly and the observed order to round-off;
- a profile at a time between two output steps is the linear interpolation
  in time, read from contact CSVs;
- the Output times a run needs hit or bracket t = 0.2, ..., 0.8;
- the history and profile errors are the relative maxima they are defined
  to be, the friction force's L1 measure (friction_l1) the relative mean:
  a dip one step wide weighs k in it, and a reference without its column
  leaves it out;
- the same for the 3D rail's measures (benchmarks/rail_error.py, used by
  benchmarks/work-precision-3d): the observed order with unequal
  refinement ratios, the centre-line pressure and the largest deflection
  read from 3D contact CSVs, the errors.

    engineering_error.py --source-dir REPO --work-dir DIR

Prints one line per check; exit code 1 if one fails.
"""

import argparse
import os
import sys

import numpy as np

from script_checks import check, failures, write


def space_level(n, h):
    """Q_h(x) = sin(x) + 0.3 h^2 cos(3x) + 2 on n + 1 nodes of [0, 2]."""
    x = np.linspace(0.0, 2.0, n + 1)
    return [(x, np.sin(x) + 0.3 * h ** 2 * np.cos(3 * x) + 2.0)]


def time_level(m):
    """exp(-t) + 0.05 k t^2 at the m steps of k = 1/m."""
    t = np.arange(1, m + 1) / m
    return [(t, np.exp(-t) + 0.05 * (1.0 / m) * t ** 2)]


def check_space_richardson(ee):
    """Richardson in space on nested grids: order 2."""
    levels = [space_level(16, 1 / 16), space_level(32, 1 / 32),
              space_level(64, 1 / 64)]
    scales = ee.scale(levels[2])
    p, d01, d12 = ee.order(levels, scales)
    check(abs(p - 2.0) < 1e-6, "observed order in space %.8f (2 expected)" % p)
    x, c = ee.correction(levels[1][0], levels[2][0], p)
    fine_x, fine_y = levels[2][0]
    extrapolated = fine_y + np.interp(fine_x, x, c)
    exact = np.sin(fine_x) + 2.0
    # exact on the nodes of the middle level; between them the correction
    # is interpolated linearly (an O(h^2) part of an O(h^2) correction)
    on_mid = np.abs(fine_x * 16 - np.round(fine_x * 16)) < 1e-9  # x = 2 j / 32
    check(np.max(np.abs(extrapolated - exact)[on_mid]) < 1e-12,
          "space extrapolation exact on the middle level's nodes (%.1e)"
          % np.max(np.abs(extrapolated - exact)[on_mid]))
    check(np.max(np.abs(extrapolated - exact)) < 0.1 * np.max(np.abs(fine_y - exact)),
          "space extrapolation at least 10 times better than the finest level everywhere")


def check_time_richardson(ee):
    """Richardson in time, order 1, correction of the middle level
    (k = 1/320); the orders used."""
    tl = [time_level(160), time_level(320), time_level(640)]
    q, _, _ = ee.order(tl, ee.scale(tl[1]))
    check(abs(q - 1.0) < 1e-6, "observed order in time %.8f (1 expected)" % q)
    t, ct = ee.correction(tl[1][0], tl[2][0], q, factor_fine=True)
    check(np.max(np.abs(tl[1][0][1] + ct - np.exp(-t))) < 1e-12,
          "time correction of k = 1/320 gives the limit")
    q1, _, _ = ee.order(tl, ee.scale(tl[1], "friction_l1"), "friction_l1")
    check(abs(q1 - 1.0) < 1e-6, "observed order in time in the L1 norm %.8f (1 expected)" % q1)
    check(ee.used(0.7) == 1.0 and ee.used(5.0) == 3.0 and ee.used(1.7) == 1.7,
          "orders used for the corrections are clipped to [1, 3]")
    check(ee.used(float("nan")) is None and ee.used(0.3) is None and ee.used(-1.0) is None,
          "no correction for a sequence that does not converge (order < 1/2)")


def check_output_times(ee):
    """Output times: on the grid, or bracketing."""
    check(ee.output_times(1.0 / 80)[:3] == [0.125, 0.2, 0.25],
          "k = 1/80: the profile times are steps (%s)" % ee.output_times(1.0 / 80)[:3])
    check([0.1875, 0.203125] == [t for t in ee.output_times(1.0 / 64) if 0.15 < t < 0.21],
          "k = 1/64: the steps around t = 0.2 (0.1875, 0.203125)")
    o = ee.output_overrides(1.0 / 64, write_vtu=False)
    check("Output/Write VTU=false" in o and any(s.startswith("Output/Output times=0.1249999")
                                                for s in o),
          "output overrides: no VTU, Output times shifted below the steps")


def empty_directory(path):
    """@p path, made if missing, without the files a previous run left."""
    os.makedirs(path, exist_ok=True)
    for name in os.listdir(path):
        os.remove(os.path.join(path, name))


def write_time_series(run, times, number):
    """time_series.csv of a run written by hand: N(t) = 1 + t, T(t) = 2 t,
    E(t) = 3 - t at @p times, written with the format @p number."""
    lines = ["step,time,normal_force,tangential_force,total_energy"]
    for s, t in enumerate(times):
        lines.append(("%d," + ",".join([number] * 4)) % (s, t, 1 + t, 2 * t, 3 - t))
    write(os.path.join(run, "time_series.csv"), "\n".join(lines) + "\n")


def write_run(run, times, xs):
    """A run written by hand: steps at @p times with profiles linear in t;
    N(t) = 1 + t."""
    empty_directory(run)
    write_time_series(run, times, "%g")
    for s, t in enumerate(times):
        rows = ["time,x,y,normal_pressure,tangential_traction,u_y"]
        for x in xs:
            rows.append("%g,%g,0,%g,%g,%g" % (t, x, 10 * t + x, -t * x, -(t + x)))
        write(os.path.join(run, "contact_%05d.csv" % s), "\n".join(rows) + "\n")
    write(os.path.join(run, "run_status"), "completed\n")


def check_extract(ee, work_dir):
    """The run of write_run() at t = 0.1, 0.3, 0.5, 0.7, 0.9 read back;
    returns what ee.extract() read."""
    run = os.path.join(work_dir, "run")
    times = [0.0, 0.1, 0.3, 0.5, 0.7, 0.9]
    xs = [0.0, 0.5, 1.0]
    write_run(run, times, xs)
    q = ee.extract(run)
    x, p = q["pressure"][0.4]
    check(np.allclose(p, 4.0 + np.array(xs)), "pressure profile at t = 0.4 interpolated in time "
          "between t = 0.3 and 0.5 (%s)" % p)
    x, tr = q["traction"][0.8]
    check(np.allclose(tr, -0.8 * np.array(xs)), "traction profile at t = 0.8 (%s)" % tr)
    td, d = q["deflection"]
    check(np.allclose(td, times[1:]) and np.allclose(d, np.array(times[1:]) + 1.0),
          "largest deflection max_x(-u_y) at every contact CSV (%s)" % d)
    check(np.allclose(q["normal_force"][1], 1 + np.array(times[1:])),
          "N(t) read, row 0 left out")
    ee.HISTORY_START = 0.2
    late = ee.extract(run)
    check(np.allclose(late["normal_force"][0], times[2:]) and np.allclose(late["deflection"][0],
                                                                          times[2:]),
          "histories start at HISTORY_START")
    ee.HISTORY_START = 0.0
    return q


def check_errors(ee, q):
    """Errors against a reference: N_ref = 1 + t on a fine grid, the
    friction force off by 0.02, the traction by 10 %; returns the
    reference and the errors."""
    tr_ = np.linspace(0, 1, 1001)
    ref = {"normal_force": (tr_, 1 + tr_), "friction_force": (tr_, 2 * tr_ + 0.02),
           "friction_l1": (tr_, 2 * tr_ + 0.02), "energy": (tr_, 3 - tr_),
           "deflection": (tr_, tr_ + 1.0)}
    for key in ("pressure", "traction"):
        ref[key] = {T: (np.array([0.0, 1.0]),
                        (10 * T + np.array([0.0, 1.0])) if key == "pressure"
                        else -T * np.array([0.0, 1.0]) * 1.1)
                    for T in ee.PROFILE_TIMES}
    e = ee.errors(q, ref)
    check(e["normal_force"] < 1e-12 and e["energy"] < 1e-12 and e["deflection"] < 1e-12,
          "exact histories have no error")
    check(abs(e["friction_force"] - 0.02 / 2.02) < 1e-12,
          "friction-force error 0.02 / max|ref| (%.6g)" % e["friction_force"])
    # L1 over the run's samples t = 0.1 ... 0.9: int 0.02 / int (2 t + 0.02)
    check(abs(e["friction_l1"] - 0.016 / 0.816) < 1e-12,
          "friction-force L1 error int|F - F_ref| / int|F_ref| (%.6g)" % e["friction_l1"])
    check(e["pressure"] < 1e-12, "exact pressure profiles have no error")
    # traction: run -T x, reference -1.1 T x: max |0.1 T x| / (1.1 T) = 0.1/1.1
    check(abs(e["traction"] - 0.1 / 1.1) < 1e-12,
          "traction error max_x |p - p_ref| / max|p_ref| (%.6g)" % e["traction"])
    return ref, e


def check_reference_files(ee, work_dir, ref):
    """The reference files round-trip."""
    hist = {k: ref[k] for k in ee.HISTORIES}
    ee.write_reference(work_dir, hist, {"pressure": ref["pressure"],
                                        "traction": ref["traction"]}, "# test\n")
    back = ee.read_reference(work_dir)
    check(all(np.allclose(back[k][1], ref[k][1]) for k in ee.HISTORIES)
          and np.allclose(back["pressure"][0.6][1], ref["pressure"][0.6][1]),
          "reference_histories.csv and reference_profiles.csv read back")


def check_old_reference(ee, work_dir, q, e):
    """A reference made before friction_l1 existed (the files of
    check_reference_files() without that column): that error is left
    out."""
    path = os.path.join(work_dir, "old_histories.csv")
    with open(os.path.join(work_dir, "reference_histories.csv")) as f:
        write(path, "".join(line if line.startswith("#") else
                            line.rsplit(",", 1)[0] + "\n" for line in f))
    os.replace(path, os.path.join(work_dir, "old_reference_histories.csv"))
    os.replace(os.path.join(work_dir, "reference_profiles.csv"),
               os.path.join(work_dir, "old_reference_profiles.csv"))
    old = ee.read_reference(work_dir, "old_reference")
    check("friction_l1" not in old and "friction_l1" not in ee.errors(q, old)
          and abs(ee.errors(q, old)["friction_force"] - e["friction_force"]) < 1e-12,
          "a reference without the friction_l1 column: that error left out, the rest as before")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--source-dir", required=True)
    parser.add_argument("--work-dir", required=True)
    args = parser.parse_args()
    sys.path.insert(0, os.path.join(args.source_dir, "benchmarks"))
    import engineering_error as ee

    check_space_richardson(ee)
    check_time_richardson(ee)
    check_output_times(ee)
    q = check_extract(ee, args.work_dir)
    ref, e = check_errors(ee, q)
    check_reference_files(ee, args.work_dir, ref)
    check_dips(ee)
    check_old_reference(ee, args.work_dir, q, e)
    rail(args.work_dir)
    if failures:
        print("%d check(s) failed" % len(failures))
        sys.exit(1)
    print("all checks passed")


def check_dips(ee):
    """A history with a dip one step wide (a node that sticks for a step
    where its slip reverses): its max norm stays at the dip's depth as k
    falls, its L1 norm falls like k."""
    for n in (64, 128, 256):
        x = np.linspace(0.0, 1.0, n + 1)
        dip = np.zeros_like(x)
        dip[n // 2] = -0.5
        check(abs(ee.size("friction_force", x, dip) - 0.5) < 1e-15
              and abs(ee.size("friction_l1", x, dip) - 0.5 / n) < 1e-15,
              "a dip one step wide at k = 1/%d: max norm 0.5, L1 norm 0.5 k" % n)


def rail(work_dir):
    """benchmarks/rail_error.py (the 3D rail's measures, work-precision-3d)."""
    import rail_error as re3

    # Observed order with the ratios of the space sequence 80, 120, 160.
    def q(n):
        return np.array([1.0, 2.0]) + 0.7 * (1.0 / n) ** 2
    p = re3.observed_order(q(80), q(120), q(160), 1.5, 4.0 / 3)
    check(abs(p - 2.0) < 1e-6, "rail: observed order with ratios 3/2, 4/3: %.8f (2)" % p)
    p = re3.observed_order(q(40), q(80), q(160))
    check(abs(p - 2.0) < 1e-6, "rail: observed order with ratio 2: %.8f (2)" % p)
    check(re3.observed_order(q(160), q(80), q(40)) != re3.observed_order(q(160), q(80), q(40)),
          "rail: no order for a sequence that diverges")
    check(re3.used(float("nan")) == 2.0 and re3.used(0.4) == 1.0 and re3.used(5) == 4.0,
          "rail: orders used clipped to [1, 4], 2 where none was observed")

    # A 3D run written by hand: Gamma_3 nodes at z = 0, 0.05, 0.1; steps at
    # t = j/32; the pressure on the centre line z = 0.05 is 10 t + x, and
    # -u_y = t + x + z (largest at x = 2, z = 0.1).
    run = os.path.join(work_dir, "rail")
    empty_directory(run)
    times = [j / 32 for j in range(0, 9)]
    write_time_series(run, times, "%.17g")
    for s, t in enumerate(times):
        rows = ["time,x,y,z,normal_pressure,u_y"]
        for x in (1.0, 0.0, 2.0):  # not sorted: extract() sorts by x
            for z in (0.0, 0.05, 0.1):
                pressure = 10 * t + x if z == 0.05 else -1.0
                rows.append("%.17g,%g,0,%g,%.17g,%.17g" % (t, x, z, pressure, -(t + x + z)))
        write(os.path.join(run, "contact_%05d.csv" % s), "\n".join(rows) + "\n")
    write(os.path.join(run, "run_status"), "completed\n")
    data = re3.extract(run)
    x, pressure = data["pressure"][0.125]
    check(np.allclose(x, [0, 1, 2]) and np.allclose(pressure, 1.25 + x),
          "rail: centre-line pressure at t = 0.125, sorted by x (%s)" % pressure)
    td, d = data["deflection"]
    check(np.allclose(td, times[1:]) and np.allclose(d, np.array(times[1:]) + 2.1),
          "rail: largest deflection max(-u_y) at every contact CSV")
    ref = {"normal_force": (np.array(re3.GRID), 1 + np.array(re3.GRID) * 1.01),
           "friction_force": (np.array(re3.GRID), 2 * np.array(re3.GRID)),
           "energy": (np.array(re3.GRID), 3 - np.array(re3.GRID)),
           "deflection": (np.array(re3.GRID), np.array(re3.GRID) + 2.1),
           "pressure": {T: (np.array([0.0, 2.0]), 10 * T + np.array([0.0, 2.0]) + 0.1)
                        for T in re3.PROFILE_TIMES}}
    e = re3.errors(data, ref)
    # N: run 1 + t, reference 1 + 1.01 t: largest 0.01 t / max(1 + 1.01 t) at
    # t = 0.25 (the samples from t = 1/16 on).
    check(abs(e["normal_force"] - 0.0025 / 1.2525) < 1e-12 and e["energy"] < 1e-12
          and e["deflection"] < 1e-12 and e["friction_force"] < 1e-12,
          "rail: history errors (N %.6g)" % e["normal_force"])
    check(abs(e["pressure"] - 0.1 / 4.6) < 1e-12,
          "rail: pressure error 0.1 / max|p_ref| (%.6g)" % e["pressure"])


if __name__ == "__main__":
    main()
