#!/usr/bin/env python3
"""Figures 2 and 3 of Barboteu & Danan (2016) from the program's output.

    plot_figures.py OUTPUT_ROOT FIGURE_DIR [--prm-dir DIR]

OUTPUT_ROOT holds one output directory per scene, named after the scene's
parameter file (what scripts/make-figures writes):

    barboteu_danan_2016/   Figure 2 (slip-weakening friction, psi = 50)
    figure3_psi5/          Figure 3, frictionless, psi = 5
    figure3_psi20/         Figure 3, frictionless, psi = 20

Each holds time_series.csv, contact_NNNNN.csv and solution_NNNNN.pvtu (see
README.md). Writes into FIGURE_DIR:

    figure2.png           deformed mesh and contact forces on Gamma_3 at
                          t = 0.2, 0.4, 0.6, 0.8 s
    figure2_pressure.png  normal pressure, friction traction and vertical
                          displacement of Gamma_3 against x at those times
    figure3.png           deformed mesh and contact pressure, psi = 5 and 20
    figure3_pressure.png  pressure profiles of psi = 5 and 20 (and psi = 50)

The applied load g(x, t) = F exp(-psi (x - c t)^2) is drawn from the
constants in the scene's parameter file (PRM_DIR/<scene>.prm, default: the
repository's prm/). Geometry is drawn at true scale (displacement factor 1).
"""

import argparse
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.patches import Polygon  # noqa: E402

# The package python/dynamic_contact (scripts/dynamic_contact links to it).
from dynamic_contact import Run as OutputRun  # noqa: E402

FIG2_SCENE = "barboteu_danan_2016"
FIG3_SCENES = [("figure3_psi5", 5.0), ("figure3_psi20", 20.0)]
FIG2_TIMES = [0.2, 0.4, 0.6, 0.8]
FIG3_TIMES = [0.4]            # the mesh figure
FIG3_PROFILE_TIMES = [0.4, 0.6]
DPI = 120

# Mesh lines drawn: about MESH_LINES_X vertical and MESH_LINES_Y horizontal
# grid lines (128 x 128 cells: every 8th vertical and every 32nd horizontal
# line), plus the outline.
MESH_LINES_X = 16
MESH_LINES_Y = 4

COLOR_PRESSURE = "tab:red"
COLOR_FRICTION = "tab:blue"
COLOR_LOAD = "tab:green"
TIME_COLORS = ["tab:blue", "tab:orange", "tab:green", "tab:red"]


# --------------------------------------------------------------------------
# Reading the output
# --------------------------------------------------------------------------

class Run:
    """One output directory (dynamic_contact.Run): step times, VTU steps,
    contact files."""

    def __init__(self, directory, prm_file=None):
        self.directory = directory
        self.name = os.path.basename(os.path.normpath(directory))
        self.output = OutputRun(directory)
        self.status = self.output.status or "no run_status"
        if not self.output.completed:
            print("plot_figures: warning: %s: run_status is '%s'; plotting "
                  "what is there" % (directory, self.status), file=sys.stderr)
        ts = self.output.time_series
        self.step_time = {int(s): float(t)
                          for s, t in zip(ts["step"], ts["time"])}
        self.vtu_steps = sorted(self.output.solution_paths)
        if not self.vtu_steps:
            raise SystemExit("plot_figures: no solution_*.pvtu in %s"
                             % directory)
        self.load = read_load(prm_file) if prm_file else None
        self._meshes = {}

    def step_near(self, t):
        """The VTU step whose time is closest to t, and that time."""
        steps = [s for s in self.vtu_steps if s in self.step_time]
        step = min(steps, key=lambda s: abs(self.step_time[s] - t))
        return step, self.step_time[step]

    def mesh(self, step):
        if step not in self._meshes:
            self._meshes[step] = self.output.solution(step)
        return self._meshes[step]

    def contact_length(self, step):
        """Length of Gamma_3 in contact (u_nu > 0), from the node spacing."""
        c = self.contact(step)
        dx = np.gradient(c["x"]) if c["x"].size > 1 else np.ones(1)
        return float(np.sum(dx[c["u_nu"] > 0]))

    def contact(self, step):
        """contact_NNNNN.csv as a dynamic_contact.Table (columns by name,
        rows sorted by x), read once per step."""
        return self.output.contact(step)


def read_load(prm_file):
    """(F, psi, c) of the traction g = F exp(-psi (x - c t)^2), or None."""
    if not os.path.exists(prm_file):
        print("plot_figures: warning: %s not found, the load is not drawn"
              % prm_file, file=sys.stderr)
        return None
    stack, constants, expression = [], None, None
    for line in open(prm_file):
        line = line.split("#", 1)[0].strip()
        m = re.match(r"subsection\s+(.*)$", line)
        if m:
            stack.append(m.group(1).strip())
            continue
        if line == "end":
            stack.pop()
            continue
        if stack and stack[-1] == "Traction function":
            m = re.match(r"set\s+Function constants\s*=\s*(.*)$", line)
            if m:
                constants = m.group(1)
            m = re.match(r"set\s+Function expression\s*=\s*(.*)$", line)
            if m:
                expression = m.group(1)
    if constants is None or expression is None:
        return None
    if "exp(-psi*(x-c*t)^2)" not in expression.replace(" ", ""):
        print("plot_figures: warning: %s: traction is not the Gaussian "
              "load, not drawn" % prm_file, file=sys.stderr)
        return None
    values = dict((k.strip(), float(v)) for k, v in
                  (item.split("=") for item in constants.split(",")))
    return values["F"], values["psi"], values["c"]


def load_profile(load, x, t):
    F, psi, c = load
    return F * np.exp(-psi * (x - c * t) ** 2)


# --------------------------------------------------------------------------
# Deformed mesh
# --------------------------------------------------------------------------

def structured_grid(mesh):
    """Nodal displacement on the tensor-product grid of a rectangle mesh.

    Returns (xs, ys, U) with U[j, i] = (u_x, u_y) at (xs[i], ys[j]), or None
    if the mesh is not a full tensor-product grid. deal.II writes every cell
    with its own copy of its vertices; copies are merged here (averaged).
    """
    p = mesh.points[:, :2]
    u = mesh.point_data["displacement"][:, :2].astype(np.float64)
    scale = max(np.ptp(p[:, 0]), np.ptp(p[:, 1]), 1e-300)
    key = np.round(p / scale * 1e6).astype(np.int64)
    kx, ix = np.unique(key[:, 0], return_inverse=True)
    ky, iy = np.unique(key[:, 1], return_inverse=True)
    nx, ny = kx.size, ky.size
    total = np.zeros((ny, nx, 2))
    count = np.zeros((ny, nx))
    np.add.at(total, (iy, ix), u)
    np.add.at(count, (iy, ix), 1.0)
    if np.any(count == 0):
        return None
    xs = np.zeros(nx)
    ys = np.zeros(ny)
    xs[ix] = p[:, 0]
    ys[iy] = p[:, 1]
    return xs, ys, total / count[..., None]


def draw_deformed_mesh(ax, mesh, factor=1.0):
    """A subset of the grid lines and the outline, deformed.

    Returns (xs, ys, X, Y, (stride_x, stride_y)) for a tensor-product grid,
    None otherwise (then every cell edge is drawn).
    """
    grid = structured_grid(mesh)
    if grid is None:
        # Not a tensor-product grid: draw every cell edge.
        cells = mesh.cell_array()
        xy = mesh.points[:, :2] + factor * \
            mesh.point_data["displacement"][:, :2]
        # deal.II writes quads in VTK order 0-1-3-2 of its own numbering,
        # i.e. counter-clockwise: consecutive vertices share an edge.
        segs = [xy[[c[k], c[(k + 1) % len(c)]]] for c in cells
                for k in range(len(c))]
        ax.add_collection(LineCollection(segs, colors="0.25", linewidths=0.3))
        return None
    xs, ys, U = grid
    X = xs[None, :] + factor * U[..., 0]
    Y = ys[:, None] + factor * U[..., 1]
    ny, nx = X.shape
    stride_x = max(1, (nx - 1) // MESH_LINES_X)
    stride_y = max(1, (ny - 1) // MESH_LINES_Y)
    rows = sorted(set(range(0, ny, stride_y)) | {ny - 1})
    cols = sorted(set(range(0, nx, stride_x)) | {nx - 1})
    outline = np.concatenate([
        np.column_stack([X[0, :], Y[0, :]]),
        np.column_stack([X[:, -1], Y[:, -1]]),
        np.column_stack([X[-1, ::-1], Y[-1, ::-1]]),
        np.column_stack([X[::-1, 0], Y[::-1, 0]])])
    ax.add_patch(Polygon(outline, closed=True, facecolor="#dbe6f1",
                         edgecolor="none", zorder=1))
    segs = [np.column_stack([X[j, :], Y[j, :]]) for j in rows if 0 < j < ny - 1]
    segs += [np.column_stack([X[:, i], Y[:, i]]) for i in cols
             if 0 < i < nx - 1]
    ax.add_collection(LineCollection(segs, colors="0.35", linewidths=0.45,
                                     zorder=2))
    ax.add_patch(Polygon(outline, closed=True, facecolor="none",
                         edgecolor="black", linewidth=0.9, zorder=3))
    return xs, ys, X, Y, (stride_x, stride_y)


def nice_value(v):
    """A round number (1, 2 or 5 times a power of ten) near v."""
    e = np.floor(np.log10(v))
    m = v / 10 ** e
    m = 1 if m < 1.5 else 2 if m < 3.5 else 5 if m < 7.5 else 10
    return m * 10 ** e


def every_other(n, stride):
    return np.arange(0, n, stride)


def draw_panel(ax, run, step, time, arrow_scale, load_scale, title,
               friction=True, arrow_stride=2, friction_stride=3,
               load_stride=3):
    """Deformed mesh, contact forces (head at the node) and load arrows.

    arrow_scale and load_scale: metres of arrow per pascal.
    """
    mesh = run.mesh(step)
    grid = draw_deformed_mesh(ax, mesh)
    c = run.contact(step)
    bx = c["x"] + c["u_x"]
    by = c["y"] + c["u_y"]
    p = c["normal_pressure"]
    sel = every_other(p.size, arrow_stride)
    sel = sel[np.abs(p[sel]) > 1e-3 * max(np.abs(p).max(), 1e-300)]
    # The foundation pushes the body along -nu = +y (linearised kinematics:
    # the reference normal); arrows end at the deformed node.
    ax.quiver(bx[sel], by[sel], np.zeros(sel.size), p[sel] * arrow_scale,
              angles="xy", scale_units="xy", scale=1, pivot="tip",
              color=COLOR_PRESSURE, width=0.0022, headwidth=3.5,
              headlength=4, headaxislength=3.5, zorder=5)
    if friction and "tangential_traction" in c:
        t = c["tangential_traction"]
        selt = every_other(t.size, friction_stride) + 1
        selt = selt[selt < t.size]
        selt = selt[np.abs(t[selt]) > 1e-3 * max(np.abs(t).max(), 1e-300)]
        ax.quiver(bx[selt], by[selt], t[selt] * arrow_scale,
                  np.zeros(selt.size), angles="xy", scale_units="xy",
                  scale=1, pivot="tip", color=COLOR_FRICTION, width=0.0022,
                  headwidth=3.5, headlength=4, headaxislength=3.5, zorder=6)
    # Applied load on the top face, head at the deformed top surface.
    if run.load is not None and grid is not None:
        xs, ys, X, Y, _ = grid
        g = load_profile(run.load, xs, time)
        sel = every_other(xs.size, load_stride)
        sel = sel[g[sel] > 0.02 * run.load[0]]
        ax.quiver(X[-1, sel], Y[-1, sel], np.zeros(sel.size),
                  -g[sel] * load_scale, angles="xy", scale_units="xy",
                  scale=1, pivot="tip", color=COLOR_LOAD, width=0.0018,
                  headwidth=3.5, headlength=4, headaxislength=3.5, zorder=4)
        x0 = run.load[2] * time
        y0 = np.interp(x0, X[-1, :], Y[-1, :]) + load_scale * run.load[0]
        ax.plot([x0], [y0 + 0.03], marker="v", color=COLOR_LOAD,
                markersize=7, zorder=7, clip_on=False)
    # The foundation surface at rest and the clamped ends.
    ax.axhline(0.0, color="0.55", linewidth=0.7, linestyle="--", zorder=0)
    ax.set_title(title, fontsize=10)
    ax.set_aspect("equal")
    ax.set_xlim(-0.05, 2.05)
    ax.set_ylabel("y (m)")
    ax.grid(False)
    return grid[4] if grid is not None else None


def lowest_point(run, step, arrow_scale):
    """Lowest y reached by the body or the tail of a contact arrow."""
    c = run.contact(step)
    return float(np.min(c["y"] + c["u_y"]
                        - np.maximum(c["normal_pressure"], 0) * arrow_scale))


def max_displacement(run, step):
    d = run.mesh(step).point_data["displacement"]
    return float(np.abs(d[:, :2]).max())


def thickness(run, step):
    return float(np.ptp(run.mesh(step).points[:, 1]))


def ordinal(n):
    suffix = "th" if 10 <= n % 100 <= 20 else \
        {1: "st", 2: "nd", 3: "rd"}.get(n % 10, "th")
    return "%d%s" % (n, suffix)


def grid_line_text(strides):
    if strides is None:
        return "all cell edges"
    return "every %s line in x, every %s in y" % (
        ordinal(strides[0]), ordinal(strides[1]))


def scale_text(arrow_value, arrow_len, load_value, load_len):
    return ("arrows (head at the node they act on): %.3g m of arrow = "
            "%.3g GPa for the contact tractions, %.3g m = %.3g GPa for the "
            "applied load" % (arrow_len, arrow_value / 1e9, load_len,
                              load_value / 1e9))


def legend_handles(friction):
    """The legend of the mesh panels: the arrows (the friction traction's
    only if @p friction) and the foundation surface at rest."""
    arrows = [(COLOR_PRESSURE, r"$\uparrow$",
               "normal pressure p+q of the foundation")]
    if friction:
        arrows.append((COLOR_FRICTION, r"$\rightarrow$",
                       "friction traction (along x)"))
    arrows.append((COLOR_LOAD, r"$\downarrow$",
                   "applied load g(x,t); $\\blacktriangledown$ x = c t"))
    handles = [plt.Line2D([], [], color=color, marker=marker,
                          linestyle="none", markersize=10, label=label)
               for color, marker, label in arrows]
    handles.append(plt.Line2D([], [], color="0.55", linestyle="--",
                              label="foundation surface at rest (y = 0)"))
    return handles


# --------------------------------------------------------------------------
# Figure 2
# --------------------------------------------------------------------------

def figure2_mesh(run, picks, contacts, figdir):
    """figure2.png: the deformed mesh and the contact forces at the steps
    @p picks ((requested time, step, time)); returns the line on the
    run's status for the titles ("" if completed)."""
    fmax = max(max(np.abs(c["normal_pressure"]).max(),
                   np.abs(c.get("tangential_traction", np.zeros(1))).max())
               for c in contacts)
    arrow_len = 0.3                           # m for the largest force
    arrow_scale = arrow_len / fmax            # m per Pa
    load_len = 0.25
    load_scale = load_len / run.load[0] if run.load else 0.0
    ymin = min(lowest_point(run, s, arrow_scale) for _, s, _ in picks) - 0.04
    ymax = 0.22
    dmax = max(max_displacement(run, s) for _, s, _ in picks)

    height = (ymax - ymin) / 2.1 * 8.6
    fig, axes = plt.subplots(len(picks), 1, figsize=(9.5, len(picks) *
                                                     (height + 0.55) + 1.4),
                             sharex=True, constrained_layout=True)
    for ax, (target, step, time) in zip(axes, picks):
        title = "t = %.4f s (step %d)" % (time, step)
        if abs(time - target) > 0.02:
            title += " -- requested t = %.1f s not in the output" % target
        if run.load:
            title += ",  load centre c t = %.2f m" % (run.load[2] * time)
        title += ",  in contact ($u_\\nu$ > 0) over %.2f m of $\\Gamma_3$" \
            % run.contact_length(step)
        strides = draw_panel(ax, run, step, time, arrow_scale, load_scale,
                             title)
        ax.set_ylim(ymin, ymax)
    axes[-1].set_xlabel("x (m)")
    # A legend with the arrow scale, in the first panel.
    ref = nice_value(fmax / 2)
    axes[0].legend(handles=legend_handles(friction=True), loc="lower left",
                   fontsize=7.5, ncol=2, framealpha=0.9)
    status = "" if run.status == "completed" else \
        "\n(run not completed: %s)" % run.status
    fig.suptitle(
        "Figure 2: rail (2 m x 0.1 m, clamped ends) on a deformable "
        "foundation under a load moving left to right\n(c = %g m/s, "
        "psi = %g m$^{-2}$, slip-weakening friction)\n"
        "deformed mesh at TRUE SCALE (displacement factor 1; max |u| = "
        "%.2f m = %.1f thicknesses), %s\n%s%s"
        % (run.load[2] if run.load else float("nan"),
           run.load[1] if run.load else float("nan"), dmax,
           dmax / thickness(run, picks[0][1]), grid_line_text(strides),
           scale_text(ref, ref * arrow_scale, run.load[0] if run.load else 0,
                      load_len), status), fontsize=9.5)
    out = os.path.join(figdir, "figure2.png")
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    print("wrote", out, "at steps", [s for _, s, _ in picks])
    return status


def figure2_profiles(run, picks, contacts, status, figdir):
    """figure2_pressure.png: the profiles against x at the steps
    @p picks."""
    fig, axes = plt.subplots(3, 1, figsize=(9, 10.5), sharex=True,
                             constrained_layout=True,
                             gridspec_kw={"height_ratios": [1.3, 1, 1]})
    xx = np.linspace(0, 2, 401)
    for color, (target, step, time), c in zip(TIME_COLORS, picks, contacts):
        label = "t = %.4f s" % time
        axes[0].plot(c["x"], c["normal_pressure"] / 1e9, color=color,
                     label=label)
        if run.load:
            axes[0].plot(xx, load_profile(run.load, xx, time) / 1e9,
                         color=color, linestyle=":", linewidth=1)
        if "tangential_traction" in c:
            axes[1].plot(c["x"], c["tangential_traction"] / 1e9, color=color,
                         label=label)
        axes[2].plot(c["x"], c["u_y"], color=color, label=label)
        lifted = c["u_nu"] < 0
        axes[2].plot(c["x"][lifted], c["u_y"][lifted], linestyle="none",
                     marker="o", markersize=2.5, color=color)
    axes[0].set_ylabel("pressure (GPa)")
    axes[0].set_title("normal pressure p+q of the foundation on $\\Gamma_3$ "
                      "(solid) and applied load g(x,t) on the top face "
                      "(dotted)", fontsize=10)
    axes[1].set_ylabel("friction traction (GPa)")
    axes[1].set_title("friction traction on $\\Gamma_3$ exerted by the "
                      "foundation (> 0: along +x)", fontsize=10)
    axes[1].axhline(0, color="0.6", linewidth=0.6)
    axes[2].set_ylabel("$u_y$ on $\\Gamma_3$ (m)")
    axes[2].set_title("vertical displacement of $\\Gamma_3$ (< 0: into the "
                      "foundation; dots: nodes out of contact, lifted off)",
                      fontsize=10)
    axes[2].axhline(0, color="0.6", linewidth=0.6)
    axes[2].set_xlabel("x (m)")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.set_xlim(0, 2)
    axes[0].legend(fontsize=8, loc="upper right")
    axes[0].set_ylim(bottom=-0.1)
    fig.suptitle("Figure 2 scene (psi = %g m$^{-2}$, slip-weakening "
                 "friction): contact boundary $\\Gamma_3$ against x%s"
                 % (run.load[1] if run.load else float("nan"),
                    status.replace("\n", " ")), fontsize=11)
    out = os.path.join(figdir, "figure2_pressure.png")
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    print("wrote", out)


def figure2(run, figdir):
    picks = [(target,) + run.step_near(target) for target in FIG2_TIMES]
    contacts = [run.contact(step) for _, step, _ in picks]
    status = figure2_mesh(run, picks, contacts, figdir)
    figure2_profiles(run, picks, contacts, status, figdir)


# --------------------------------------------------------------------------
# Figure 3
# --------------------------------------------------------------------------

def figure3_profile_row(ax, curves, target, normalized):
    """One panel of figure3_pressure.png: the pressure of each of
    @p curves ((run, psi or None for the Figure 2 scene, colour)) at the
    step nearest @p target, in GPa or divided by the total load."""
    xx = np.linspace(0, 2, 401)
    for run, psi, color in curves:
        step, time = run.step_near(target)
        c = run.contact(step)
        if psi is None:
            label = "psi = %g, with friction (Figure 2 scene)" \
                % run.load[1]
            width, style = 1.0, "--"
        else:
            label = "psi = %g, frictionless" % psi
            width, style = 1.8, "-"
        label += ", t = %.4f s" % time
        total = np.sqrt(np.pi / run.load[1]) * run.load[0] \
            if run.load else 1.0
        scale = 1.0 / total if normalized else 1e-9
        ax.plot(c["x"], c["normal_pressure"] * scale, color=color,
                linewidth=width, linestyle=style, label=label)
        if run.load:
            ax.plot(xx, load_profile(run.load, xx, time) * scale,
                    color=color, linestyle=":", linewidth=1)
    ax.axvline(2.0 * target, color="0.7", linewidth=0.6)
    ax.grid(True, alpha=0.3)
    ax.set_xlim(0, 2)
    ax.set_ylim(bottom=0)
    if normalized:
        ax.set_ylabel("pressure / total load (m$^{-1}$)")
        ax.set_title("the same at t $\\approx$ %.1f s, divided by the "
                     "total applied load F$\\sqrt{\\pi/\\psi}$ "
                     "(N/m): how the load is spread" % target,
                     fontsize=10)
    else:
        ax.set_ylabel("pressure (GPa)")
        ax.set_title("normal pressure p+q on $\\Gamma_3$ (solid) and "
                     "applied load g on the top face (dotted), "
                     "t $\\approx$ %.1f s" % target, fontsize=10)
    ax.legend(fontsize=7.5, loc="upper right" if target < 0.5
              else "upper left")


def figure3_mesh(runs, figdir):
    """figure3.png: the deformed mesh and the contact pressure of each
    run of @p runs ((run, psi)) at FIG3_TIMES."""
    panels = []
    for run, psi in runs:
        for target in FIG3_TIMES:
            step, time = run.step_near(target)
            panels.append((run, psi, target, step, time))
    fmax = max(run.contact(step)["normal_pressure"].max()
               for run, _, _, step, _ in panels)
    arrow_len = 0.3
    arrow_scale = arrow_len / fmax
    load_len = 0.25
    F = max([run.load[0] for run, _ in runs if run.load] or [0.0])
    load_scale = load_len / F if F > 0 else 0.0
    ymin = min(lowest_point(run, step, arrow_scale)
               for run, _, _, step, _ in panels) - 0.04
    ymax = 0.22
    dmax = max(max_displacement(run, step) for run, _, _, step, _ in panels)
    height = (ymax - ymin) / 2.1 * 8.6
    fig, axes = plt.subplots(len(panels), 1,
                             figsize=(9.5, len(panels) * (height + 0.55) + 1.2),
                             sharex=True, constrained_layout=True)
    axes = np.atleast_1d(axes)
    for ax, (run, psi, target, step, time) in zip(axes, panels):
        c = run.contact(step)
        title = ("psi = %g m$^{-2}$ (load width $1/\\sqrt{\\psi}$ = %.2f m, "
                 "total load %.1f GN/m), frictionless, t = %.4f s (step %d)"
                 "\nmax pressure %.2f GPa, in contact over %.2f m, "
                 "max |u| = %.2f m"
                 % (psi, 1 / np.sqrt(psi),
                    (run.load[0] * np.sqrt(np.pi / run.load[1]) / 1e9)
                    if run.load else float("nan"), time, step,
                    c["normal_pressure"].max() / 1e9,
                    run.contact_length(step), max_displacement(run, step)))
        if run.status != "completed":
            title += " (run not completed: %s)" % run.status
        strides = draw_panel(ax, run, step, time, arrow_scale, load_scale,
                             title, friction=False)
        ax.set_ylim(ymin, ymax)
    axes[-1].set_xlabel("x (m)")
    axes[0].legend(handles=legend_handles(friction=False), loc="lower left",
                   fontsize=7.5, framealpha=0.9)
    ref = nice_value(fmax / 2)
    fig.suptitle(
        "Figure 3: influence of the length of the mass, g = F exp(-psi "
        "(x - c t)$^2$), without friction\ndeformed mesh at TRUE SCALE "
        "(displacement factor 1, max |u| = %.2f m), %s\n%s"
        % (dmax, grid_line_text(strides),
           scale_text(ref, ref * arrow_scale, F, load_len)), fontsize=9.5)
    out = os.path.join(figdir, "figure3.png")
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    print("wrote", out, "at steps", [p[3] for p in panels])


def figure3_profiles(runs, figdir, fig2_run):
    """figure3_pressure.png: the pressure profiles of @p runs (and of
    @p fig2_run, dashed) at FIG3_PROFILE_TIMES, the first again divided
    by the total load."""
    fig, axes = plt.subplots(3, 1, figsize=(9, 10.5), sharex=True,
                             constrained_layout=True)
    colors = ["tab:blue", "tab:orange"]
    curves = [(run, psi, color) for (run, psi), color in zip(runs, colors)]
    if fig2_run is not None:
        curves.append((fig2_run, None, "0.45"))
    rows = [(t, False) for t in FIG3_PROFILE_TIMES] + \
        [(FIG3_PROFILE_TIMES[0], True)]
    for ax, (target, normalized) in zip(axes, rows):
        figure3_profile_row(ax, curves, target, normalized)
    axes[-1].set_xlabel("x (m)")
    fig.suptitle("Figure 3: contact pressure for a long (psi = 5) and a "
                 "shorter (psi = 20) mass, frictionless; thin grey line: x = "
                 "c t", fontsize=11)
    out = os.path.join(figdir, "figure3_pressure.png")
    fig.savefig(out, dpi=DPI)
    plt.close(fig)
    print("wrote", out)


def figure3(runs, figdir, fig2_run=None):
    figure3_mesh(runs, figdir)
    figure3_profiles(runs, figdir, fig2_run)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("output_root")
    parser.add_argument("figure_dir")
    parser.add_argument("--prm-dir", default=os.path.join(here, "..", "prm"))
    args = parser.parse_args()
    os.makedirs(args.figure_dir, exist_ok=True)

    def run_of(name):
        return Run(os.path.join(args.output_root, name),
                   os.path.join(args.prm_dir, name + ".prm"))

    fig2_run = run_of(FIG2_SCENE)
    figure2(fig2_run, args.figure_dir)
    figure3([(run_of(name), psi) for name, psi in FIG3_SCENES],
            args.figure_dir, fig2_run)


if __name__ == "__main__":
    main()
