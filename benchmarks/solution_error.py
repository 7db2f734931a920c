#!/usr/bin/env python3
"""The error of a run against a reference run of the same 2D rectangular
scene, at the times both runs wrote VTU for (doc/theory.md section 7).

    solution_error.py RUN_DIR REFERENCE_DIR [--times 0.125,0.25,...]
                      [--young 1e11] [--poisson 0.3] [--density 1000]
                      [--csv per_time.csv]

Everything is evaluated on the reference's structured grid:
- the reference must be a uniform Q1 mesh of nx x ny equal rectangles (e.g.
  the paper's 128 x 128); its fields are its vertex values;
- the run (uniform or adaptive, Q1, or Q2 written with 'Output/VTU
  subdivisions') is evaluated at the reference's vertices by bilinear
  interpolation within the run's VTU cell that contains each vertex (VTU
  cells are axis-aligned rectangles). Where several cells contain a vertex
  (on cell edges) their values are averaged; the largest difference between
  them is reported (it is round-off for continuous fields). For nested Q1
  meshes this is exact; for Q2 (or any run written with subdivisions) the
  field between the VTU points is approximated bilinearly, so the error is
  that of the run's Q1 interpolant on its VTU points - an approximation,
  said so in the output (exact at the reference's vertices when the
  subdivided cells are the reference's cells, e.g. Q2 on n x n with
  128/n subdivisions);
- e_u, e_w (displacement and velocity differences) are Q1 fields on the
  reference grid, integrated with 2x2 Gauss points per cell (exact for
  bilinear fields):
    ||eps(e_u)||_L2, ||e_w||_L2,
    energy norm (rho ||e_w||^2 + a_E(e_u, e_u))^(1/2),
  a_E with the plane-strain Lame constants lambda = E nu/((1+nu)(1-2nu)),
  mu = E/(2(1+nu)) (eq. (87) as written, doc/theory.md section 8), per
  unit depth.

Summary (maximum over the compared times):
  error_theorem6 = max_t (||eps(e_u)|| + ||e_w||)
  error_energy   = max_t energy norm of (e_u, e_w)
  relative_error_energy   = error_energy / max_t ||(u_ref, w_ref)||_E
  relative_error_theorem6 = error_theorem6 / max_t (||eps(u_ref)|| + ||w_ref||)
(each relative to the reference's own norm of the same kind: the Theorem-6
norm adds a strain and a velocity and has other units than the energy norm.)

Times: by default every time > 0 both solution.pvd files list (matched to
within 1e-6 s, the precision of the .pvd), or the given --times.
Needs numpy; reads the VTU files with dynamic_contact.vtu (python/).
"""
import argparse
import csv
import math
import os
import sys

import numpy as np

# The package python/dynamic_contact (benchmarks/dynamic_contact links to it).
from dynamic_contact.vtu import read_pvd, read_vtu

TIME_TOLERANCE = 1e-6
VTK_QUAD = 9
GAUSS = (0.5 - 0.5 / math.sqrt(3.0), 0.5 + 0.5 / math.sqrt(3.0))


class Grid:
    """The reference's structured grid: x_i = x0 + i hx (i = 0..nx),
    y_j = y0 + j hy (j = 0..ny); fields are arrays (ny+1, nx+1, 2)."""

    def __init__(self, x0, y0, hx, hy, nx, ny):
        self.x0, self.y0, self.hx, self.hy, self.nx, self.ny = x0, y0, hx, hy, nx, ny

    @property
    def x(self):
        return self.x0 + self.hx * np.arange(self.nx + 1)

    @property
    def y(self):
        return self.y0 + self.hy * np.arange(self.ny + 1)

    def __repr__(self):
        return "%d x %d grid on (%g, %g) x (%g, %g)" % (
            self.nx, self.ny, self.x0, self.x0 + self.nx * self.hx, self.y0, self.y0 + self.ny * self.hy)


def _rectangles(mesh):
    """Per VTU cell: x0, x1, y0, y1 and the corner flags (cx, cy) in {0, 1} of
    its 4 points; checks that every cell is a non-degenerate axis-aligned
    rectangle."""
    if mesh.n_cells == 0:
        raise ValueError("VTU without cells")
    if not np.all(mesh.types == VTK_QUAD):
        raise ValueError("VTU cells of types %s: only VTK_QUAD (9) is supported (2D, no "
                         "higher-order cells)" % sorted(set(mesh.types.tolist())))
    cells = mesh.cell_array()
    p = mesh.points[cells][:, :, :2]
    x0, x1 = p[:, :, 0].min(axis=1), p[:, :, 0].max(axis=1)
    y0, y1 = p[:, :, 1].min(axis=1), p[:, :, 1].max(axis=1)
    dx, dy = x1 - x0, y1 - y0
    if np.any(dx <= 0) or np.any(dy <= 0):
        raise ValueError("degenerate VTU cell")
    cx = (p[:, :, 0] - x0[:, None]) > 0.5 * dx[:, None]
    cy = (p[:, :, 1] - y0[:, None]) > 0.5 * dy[:, None]
    # Every corner exactly at a rectangle corner (single precision points).
    ex = np.abs(p[:, :, 0] - np.where(cx, x1[:, None], x0[:, None])) / dx[:, None]
    ey = np.abs(p[:, :, 1] - np.where(cy, y1[:, None], y0[:, None])) / dy[:, None]
    if max(ex.max(), ey.max()) > 1e-4:
        raise ValueError("VTU cells are not axis-aligned rectangles")
    code = cx.astype(int) + 2 * cy.astype(int)
    if not np.all(np.sort(code, axis=1) == np.arange(4)):
        raise ValueError("VTU cells are not axis-aligned rectangles (corners)")
    return cells, x0, x1, y0, y1, cx, cy


def reference_grid(mesh):
    """The structured grid of a uniform reference VTU (nx x ny equal cells,
    one VTU cell per grid cell)."""
    _, x0, x1, y0, y1, _, _ = _rectangles(mesh)
    hx, hy = float(np.median(x1 - x0)), float(np.median(y1 - y0))
    X0, Y0 = float(x0.min()), float(y0.min())
    nx = int(round((float(x1.max()) - X0) / hx))
    ny = int(round((float(y1.max()) - Y0) / hy))
    hx, hy = (float(x1.max()) - X0) / nx, (float(y1.max()) - Y0) / ny
    if (mesh.n_cells != nx * ny or np.abs(x1 - x0 - hx).max() > 1e-4 * hx
            or np.abs(y1 - y0 - hy).max() > 1e-4 * hy):
        raise ValueError("the reference is not a uniform mesh of equal rectangles written "
                         "without subdivisions (%d VTU cells, %d x %d grid)" % (mesh.n_cells, nx, ny))
    return Grid(X0, Y0, hx, hy, nx, ny)


def sample(mesh, grid, names=("displacement", "velocity")):
    """The fields `names` (first two components) of the VTU `mesh` at the
    vertices of `grid`, by bilinear interpolation in the VTU cell that holds
    each vertex. Returns (fields {name: (ny+1, nx+1, 2)}, info) with info:
    nested (every VTU point is a grid vertex), vtu_cells, min/max_cell_size
    (width, height) of the VTU cells, and per field the largest disagreement
    between cells sharing a vertex, relative to the field's maximum."""
    cells, x0, x1, y0, y1, cx, cy = _rectangles(mesh)
    tol = 1e-4
    # Grid vertices in each cell (closed rectangle).
    i_lo = np.ceil((x0 - grid.x0) / grid.hx - tol).astype(np.int64)
    i_hi = np.floor((x1 - grid.x0) / grid.hx + tol).astype(np.int64)
    j_lo = np.ceil((y0 - grid.y0) / grid.hy - tol).astype(np.int64)
    j_hi = np.floor((y1 - grid.y0) / grid.hy + tol).astype(np.int64)
    i_lo, j_lo = np.maximum(i_lo, 0), np.maximum(j_lo, 0)
    i_hi, j_hi = np.minimum(i_hi, grid.nx), np.minimum(j_hi, grid.ny)
    ni, nj = np.maximum(i_hi - i_lo + 1, 0), np.maximum(j_hi - j_lo + 1, 0)
    counts = ni * nj
    c = np.repeat(np.arange(cells.shape[0]), counts)
    local = np.arange(c.size) - np.repeat(np.cumsum(counts) - counts, counts)
    ii = i_lo[c] + local % ni[c]
    jj = j_lo[c] + local // ni[c]
    s = np.clip((grid.x0 + ii * grid.hx - x0[c]) / (x1[c] - x0[c]), 0.0, 1.0)
    t = np.clip((grid.y0 + jj * grid.hy - y0[c]) / (y1[c] - y0[c]), 0.0, 1.0)
    weights = (np.where(cx[c], s[:, None], 1 - s[:, None])
               * np.where(cy[c], t[:, None], 1 - t[:, None]))          # (m, 4)
    flat = jj * (grid.nx + 1) + ii
    n_vertices = (grid.nx + 1) * (grid.ny + 1)
    hits = np.bincount(flat, minlength=n_vertices)
    if np.any(hits == 0):
        raise ValueError("%d of the reference grid's vertices lie in no VTU cell of the run "
                         "(not the same domain?)" % int(np.sum(hits == 0)))
    fields, disagreement = {}, {}
    for name in names:
        if name not in mesh.point_data:
            raise ValueError("the VTU has no point field %r" % name)
        values = mesh.point_data[name].astype(np.float64)[:, :2]
        at = np.einsum("mk,mkd->md", weights, values[cells[c]])           # (m, 2)
        mean = np.stack([np.bincount(flat, weights=at[:, d], minlength=n_vertices)
                         for d in range(2)], axis=1) / hits[:, None]
        scale = max(np.abs(values).max(), 1e-300)
        disagreement[name] = float(np.abs(at - mean[flat]).max() / scale)
        fields[name] = mean.reshape(grid.ny + 1, grid.nx + 1, 2)
    # Nested: every VTU point lies on a grid vertex (then Q1 interpolation of
    # a Q1 run is exact).
    px = (mesh.points[:, 0] - grid.x0) / grid.hx
    py = (mesh.points[:, 1] - grid.y0) / grid.hy
    nested = bool(np.abs(px - np.round(px)).max() < tol and np.abs(py - np.round(py)).max() < tol)
    info = {"nested": nested, "disagreement": disagreement,
            "vtu_cells": int(cells.shape[0]),
            "min_cell_size": (float((x1 - x0).min()), float((y1 - y0).min())),
            "max_cell_size": (float((x1 - x0).max()), float((y1 - y0).max()))}
    return fields, info


def lame(young, poisson):
    lam = young * poisson / ((1 + poisson) * (1 - 2 * poisson))
    mu = young / (2 * (1 + poisson))
    return lam, mu


def norms(grid, u, w, young=1e11, poisson=0.3, density=1000.0):
    """||eps(u)||_L2, ||w||_L2 and (rho ||w||^2 + a_E(u, u))^(1/2) of the Q1
    fields u, w (arrays (ny+1, nx+1, 2)) on `grid`, 2x2 Gauss per cell."""
    lam, mu = lame(young, poisson)
    hx, hy = grid.hx, grid.hy
    weight = 0.25 * hx * hy
    eps2 = w2 = a = 0.0
    u00, u10, u01, u11 = u[:-1, :-1], u[:-1, 1:], u[1:, :-1], u[1:, 1:]
    w00, w10, w01, w11 = w[:-1, :-1], w[:-1, 1:], w[1:, :-1], w[1:, 1:]
    for s in GAUSS:
        for t in GAUSS:
            dx = ((1 - t) * (u10 - u00) + t * (u11 - u01)) / hx
            dy = ((1 - s) * (u01 - u00) + s * (u11 - u10)) / hy
            exx, eyy = dx[..., 0], dy[..., 1]
            exy = 0.5 * (dx[..., 1] + dy[..., 0])
            ee = exx * exx + eyy * eyy + 2 * exy * exy
            eps2 += weight * ee.sum()
            a += weight * (lam * (exx + eyy) ** 2 + 2 * mu * ee).sum()
            wv = (1 - s) * (1 - t) * w00 + s * (1 - t) * w10 + (1 - s) * t * w01 + s * t * w11
            w2 += weight * (wv * wv).sum()
    return {"eps": math.sqrt(eps2), "w": math.sqrt(w2),
            "energy": math.sqrt(density * w2 + a)}


def _pick(pvd, t, what):
    best = min(pvd, key=lambda e: abs(e[0] - t))
    if abs(best[0] - t) > TIME_TOLERANCE:
        raise ValueError("%s has no VTU at t = %g (solution.pvd)" % (what, t))
    return best


def _time_series(run_dir):
    """The rows of the run's time_series.csv (None if it cannot be read)."""
    try:
        with open(os.path.join(run_dir, "time_series.csv")) as f:
            return list(csv.DictReader(f))
    except OSError:
        return None


def _subdivisions(rows, vtu_time, vtu_cells):
    """The VTU subdivisions of the run at that time: sqrt(VTU cells / mesh
    cells), from the rows of time_series.csv (None if unknown)."""
    try:
        row = min(rows, key=lambda r: abs(float(r["time"]) - vtu_time))
        return int(round(math.sqrt(vtu_cells / float(row["cells"]))))
    except (TypeError, KeyError, ValueError, ZeroDivisionError):
        return None


def compare(run_dir, ref_dir, times=None, young=1e11, poisson=0.3, density=1000.0,
            reference_cache=None):
    """Errors of the run in `run_dir` against the reference in `ref_dir`.
    `reference_cache`: a dict reused between calls (the reference's grid
    fields and norms per time). Returns a dict: per-time rows, the summary
    values (see the module's docstring) and notes."""
    run_pvd = read_pvd(os.path.join(run_dir, "solution.pvd"))
    ref_pvd = read_pvd(os.path.join(ref_dir, "solution.pvd"))
    if times is None:
        times = [t for t, _ in ref_pvd if t > TIME_TOLERANCE
                 and any(abs(t - s) <= TIME_TOLERANCE for s, _ in run_pvd)]
        if not times:
            raise ValueError("no common VTU time > 0 in %s and %s" % (run_dir, ref_dir))
    cache = reference_cache if reference_cache is not None else {}
    rows, notes = [], set()
    run_series = _time_series(run_dir)
    nested_all, max_disagreement = True, 0.0
    for t in times:
        ref_time, ref_file = _pick(ref_pvd, t, ref_dir)
        key = (os.path.abspath(ref_file), young, poisson, density)
        if key not in cache:
            ref_mesh = read_vtu(ref_file)
            grid = reference_grid(ref_mesh)
            fields, _ = sample(ref_mesh, grid)
            cache[key] = (grid, fields, norms(grid, fields["displacement"], fields["velocity"],
                                              young, poisson, density))
        grid, ref_fields, ref_norms = cache[key]
        run_time, run_file = _pick(run_pvd, t, run_dir)
        run_mesh = read_vtu(run_file)
        fields, info = sample(run_mesh, grid)
        eu = fields["displacement"] - ref_fields["displacement"]
        ew = fields["velocity"] - ref_fields["velocity"]
        e = norms(grid, eu, ew, young, poisson, density)
        sub = _subdivisions(run_series, run_time, info["vtu_cells"])
        nested_all = nested_all and info["nested"] and sub == 1
        max_disagreement = max([max_disagreement] + list(info["disagreement"].values()))
        if sub is None or sub > 1:
            notes.add("the run's VTU has %s subdivisions per cell: between its VTU points the "
                      "run's fields (Q2: not bilinear) are approximated by bilinear "
                      "interpolation - an approximation of the run's own field"
                      % (sub if sub else "unknown"))
        elif not info["nested"]:
            notes.add("the run's VTU points are not all reference grid vertices (not nested): "
                      "bilinear interpolation in the run's cells")
        rows.append({"time": ref_time, "run_time": run_time,
                     "eps_error": e["eps"], "w_error": e["w"],
                     "theorem6_error": e["eps"] + e["w"], "energy_error": e["energy"],
                     "ref_eps": ref_norms["eps"], "ref_w": ref_norms["w"],
                     "ref_theorem6": ref_norms["eps"] + ref_norms["w"],
                     "ref_energy": ref_norms["energy"],
                     "vtu_cells": info["vtu_cells"], "subdivisions": sub})
    error_theorem6 = max(r["theorem6_error"] for r in rows)
    error_energy = max(r["energy_error"] for r in rows)
    ref_energy = max(r["ref_energy"] for r in rows)
    ref_theorem6 = max(r["ref_theorem6"] for r in rows)
    if nested_all:
        notes.add("nested Q1 meshes: the run's fields on the reference grid are exact")
    return {"rows": rows, "grid": grid,
            "error_theorem6": error_theorem6, "error_energy": error_energy,
            "reference_energy": ref_energy, "reference_theorem6": ref_theorem6,
            "relative_error_energy": error_energy / ref_energy,
            "relative_error_theorem6": error_theorem6 / ref_theorem6,
            "exact": nested_all, "max_disagreement": max_disagreement,
            "notes": sorted(notes)}


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run")
    parser.add_argument("reference")
    parser.add_argument("--times", help="comma-separated times (default: every common VTU time > 0)")
    parser.add_argument("--young", type=float, default=1e11)
    parser.add_argument("--poisson", type=float, default=0.3)
    parser.add_argument("--density", type=float, default=1000.0)
    parser.add_argument("--csv", help="write the per-time table to this CSV file")
    args = parser.parse_args()
    times = [float(t) for t in args.times.split(",")] if args.times else None
    try:
        r = compare(args.run, args.reference, times, args.young, args.poisson, args.density)
    except (OSError, ValueError) as e:
        sys.exit("solution_error: %s" % e)
    print("run %s against reference %s (%r)" % (args.run, args.reference, r["grid"]))
    print("%-8s %-12s %-12s %-12s %-12s %-12s %-10s" % ("time", "eps(e_u)", "e_w", "theorem6",
                                                        "energy", "ref energy", "rel energy"))
    for row in r["rows"]:
        print("%-8.5g %-12.4e %-12.4e %-12.4e %-12.4e %-12.4e %-10.4e"
              % (row["time"], row["eps_error"], row["w_error"], row["theorem6_error"],
                 row["energy_error"], row["ref_energy"], row["energy_error"] / r["reference_energy"]))
    print("error_theorem6 %.6e (relative %.6e, to max_t ||eps(u_ref)|| + ||w_ref|| = %.6e)"
          % (r["error_theorem6"], r["relative_error_theorem6"], r["reference_theorem6"]))
    print("error_energy   %.6e (relative %.6e, to max_t ||(u_ref, w_ref)||_E = %.6e)"
          % (r["error_energy"], r["relative_error_energy"], r["reference_energy"]))
    print("largest disagreement between VTU cells sharing a vertex: %.2e of the field's maximum"
          % r["max_disagreement"])
    for note in r["notes"]:
        print("note:", note)
    if args.csv:
        with open(args.csv, "w", newline="") as f:
            writer = csv.DictWriter(f, fieldnames=list(r["rows"][0].keys()))
            writer.writeheader()
            writer.writerows(r["rows"])


if __name__ == "__main__":
    main()
