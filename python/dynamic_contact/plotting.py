"""Standard plots of any run (2D or 3D, any geometry, serial or parallel,
with or without friction): what `scripts/plot-run OUTDIR` draws.

    from dynamic_contact.plotting import plot_run
    written = plot_run("output-pressed-block", "output-pressed-block/plots")

Files (PNG), each drawn from what the run wrote (doc/output.md):

    forces.png          contact forces (normal_force, tangential_force) and
                        the applied load (applied_force_*) against time
    energies.png        the energies, the cumulated balance (E_n - E_0
                        against the sum of W_n - D_n) and the energy balance
                        defect (absolute and relative, logarithmic)
    iterations.png      per step: Newton iterations and convexification
                        passes, Krylov iterations, the time step (with the
                        cut-backs)
    gamma3_profiles.png normal pressure, friction traction, tangential
                        velocity (slip rate) and friction coefficient mu on
                        Gamma_3 against the position, one curve per contact
                        CSV time (at most max_profiles of them, evenly
                        spread, always the last)

A quantity the run does not have (no friction, a direct solver, a column of
another version) leaves its panel with a note saying so; a file whose data
is missing altogether (no time_series.csv, no contact CSV) is not written,
and the note says why. Nothing is written anywhere but in out_dir.
"""

import argparse
import os
import sys

import numpy as np

from .output import Run, is_completed

FIGURE_NAMES = ("forces.png", "energies.png", "iterations.png",
                "gamma3_profiles.png")


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


class _Notes:
    def __init__(self, log):
        self.log = log
        self.items = []

    def __call__(self, text):
        self.items.append(text)
        if self.log:
            self.log("plot-run: note: " + text)


def _note_panel(ax, text):
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center",
            va="center", fontsize=9, color="0.35", wrap=True)
    ax.set_yticks([])  # (the x axis may be shared with other panels)


def _title(run):
    name = os.path.basename(os.path.normpath(os.path.abspath(run.directory)))
    status = run.status if run.status is not None else "no run_status"
    if is_completed(run.status):
        return name
    return "%s (run_status: %s: results incomplete)" % (name, status)


def _steps_after_zero(ts):
    """Rows of the steps (row 0, the initial state, left out)."""
    if "step" in ts:
        return ts["step"] > 0
    return np.arange(len(ts)) > 0


def _plot_columns(ax, ts, names, notes, panel, labels=None, scale=1.0,
                  style="-"):
    """Plot the columns that exist against time; a note for the others.
    Returns the names drawn."""
    drawn = []
    for name in names:
        if ts.is_numeric(name):
            ax.plot(ts["time"], ts[name] * scale, style,
                    label=(labels or {}).get(name, name))
            drawn.append(name)
    if not drawn:
        notes("%s: no column %s in time_series.csv, panel left empty"
              % (panel, " or ".join(names)))
        _note_panel(ax, "%s: not in time_series.csv\n(%s)"
                    % (panel, ", ".join(names)))
    return drawn


def _no_offset(ax):
    """Tick labels as values (no '+1e7' offset above the axis)."""
    if ax.get_yscale() == "linear":
        ax.ticklabel_format(axis="y", useOffset=False)


def _finish(ax, drawn, ylabel):
    if drawn:
        _no_offset(ax)
        ax.set_ylabel(ylabel)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)


def _figure(rows, height):
    """A column of `rows` panels, 8 inches wide, sharing the x axis."""
    return _pyplot().subplots(rows, 1, figsize=(8, height), sharex=True,
                              constrained_layout=True)


def _save(fig, axes, xlabel, heading, run, out_dir, name, dpi):
    """The x label below the last panel, the heading with the run's title
    above them; the figure written to out_dir/name and closed."""
    axes[-1].set_xlabel(xlabel)
    fig.suptitle(heading + _title(run), fontsize=11)
    path = os.path.join(out_dir, name)
    fig.savefig(path, dpi=dpi)
    _pyplot().close(fig)
    return path


# --------------------------------------------------------------------------
# Time series
# --------------------------------------------------------------------------

def plot_forces(run, out_dir, notes, dpi):
    ts = run.time_series
    fig, axes = _figure(2, 7)
    drawn = _plot_columns(axes[0], ts, ["normal_force", "tangential_force"],
                          notes, "contact forces",
                          {"normal_force": "normal force (sum of m_i (p+q))",
                           "tangential_force":
                           "friction force (sum of |lambda_i|)"})
    if drawn == ["normal_force"]:
        notes("forces: no tangential_force column (a run without "
              "friction): friction force not drawn")
    _finish(axes[0], drawn, "force (N, 2D: N/m)")
    axes[0].set_title("contact forces on Gamma_3", fontsize=10)
    load = ["applied_force_%s" % c for c in "xyz"]
    drawn = _plot_columns(axes[1], ts, load, notes, "applied load")
    if drawn and all(np.all(ts[n] == 0) for n in drawn):
        notes("forces: the applied load is zero at every step")
    _finish(axes[1], drawn, "force (N, 2D: N/m)")
    axes[1].set_title("applied load (body force + traction on Gamma_2)",
                      fontsize=10)
    return _save(fig, axes, "time (s)", "forces: ", run, out_dir,
                 "forces.png", dpi)


def plot_energies(run, out_dir, notes, dpi):
    ts = run.time_series
    fig, axes = _figure(4, 12)
    drawn = _plot_columns(axes[0], ts, ["kinetic_energy", "elastic_energy",
                                        "foundation_energy", "total_energy"],
                          notes, "energies")
    _finish(axes[0], drawn, "energy (J, 2D: J/m)")
    axes[0].set_title("energies E_n", fontsize=10)

    ax = axes[1]
    if all(ts.is_numeric(n) for n in ("total_energy", "load_work",
                                      "dissipation")):
        t = ts["time"]
        after = _steps_after_zero(ts)
        work = np.cumsum(np.where(after, ts["load_work"], 0.0))
        dissipation = np.cumsum(np.where(after, ts["dissipation"], 0.0))
        ax.plot(t, ts["total_energy"] - ts["total_energy"][0],
                label="E_n - E_0")
        ax.plot(t, work - dissipation, "--",
                label="sum of W_k - D_k (load work - dissipation)")
        ax.plot(t, work, ":", label="sum of W_k")
        ax.plot(t, dissipation, ":", label="sum of D_k")
        _finish(ax, True, "energy (J, 2D: J/m)")
        ax.set_title("energy balance, cumulated: E_n - E_0 = sum (W - D) "
                     "up to the defect", fontsize=10)
    else:
        notes("energies: total_energy, load_work or dissipation missing: "
              "no cumulated balance")
        _note_panel(ax, "cumulated balance: total_energy, load_work or "
                    "dissipation not in time_series.csv")

    after = _steps_after_zero(ts)
    for ax, name, ylabel, title in (
            (axes[2], "relative_energy_defect", "relative defect",
             "relative energy balance defect |E_n - E_n-1 + D_n - W_n| / "
             "scale per step"),
            (axes[3], "energy_balance_defect", "|defect| (J, 2D: J/m)",
             "energy balance defect |E_n - E_n-1 + D_n - W_n| per step")):
        values = np.abs(ts[name][after]) if ts.is_numeric(name) else None
        positive = values > 0 if values is not None else None
        if values is None or not np.any(positive):
            why = ("not in time_series.csv" if values is None else
                   "no step after the initial state" if not values.size
                   else "0 at every step")
            notes("energies: %s: %s, panel left empty" % (name, why))
            _note_panel(ax, "%s: %s" % (name, why))
            continue
        ax.semilogy(ts["time"][after][positive], values[positive], ".-",
                    markersize=3, label=name + " (zeros left out)")
        if name == "relative_energy_defect":
            ax.axhline(1e-8, color="tab:red", linewidth=0.8, linestyle="--",
                       label="1e-8 (the bound the run checks)")
        _finish(ax, True, ylabel)
        ax.set_title(title + " (logarithmic)", fontsize=10)
    return _save(fig, axes, "time (s)", "energies: ", run, out_dir,
                 "energies.png", dpi)


def plot_iterations(run, out_dir, notes, dpi):
    ts = run.time_series
    after = _steps_after_zero(ts)
    steps = ts["step"][after] if "step" in ts else np.nonzero(after)[0]
    fig, axes = _figure(3, 8.5)

    def draw(ax, names, labels, title, ylabel, skip_zero=False):
        drawn = []
        for name in names:
            if not ts.is_numeric(name):
                continue
            values = ts[name][after]
            if skip_zero and values.size and np.all(values == 0):
                notes("iterations: %s is 0 at every step (%s), not drawn"
                      % (name, "a direct linear solver"
                         if name == "linear_iterations" else "none"))
                continue
            ax.step(steps, values, where="mid", label=labels[name])
            drawn.append(name)
        if drawn:
            _finish(ax, drawn, ylabel)
            ax.set_title(title, fontsize=10)
        else:
            notes("iterations: %s: no data (%s), panel left empty"
                  % (title, ", ".join(names)))
            _note_panel(ax, "%s: no data\n(%s missing or 0 everywhere)"
                        % (title, ", ".join(names)))
        return drawn

    draw(axes[0], ["newton_iterations", "convexification_iterations"],
         {"newton_iterations": "Newton iterations (all passes)",
          "convexification_iterations": "convexification passes"},
         "nonlinear iterations per step", "count")
    draw(axes[1], ["linear_iterations"],
         {"linear_iterations": "Krylov iterations"},
         "Krylov iterations per step", "count", skip_zero=True)
    ax = axes[2]
    if ts.is_numeric("time_step"):
        k = ts["time_step"][after]
        ax.step(steps, k, where="mid", label="time step k")
        if ts.is_numeric("cutbacks"):
            cut = ts["cutbacks"][after] > 0
            if np.any(cut):
                ax.plot(steps[cut], k[cut], "v", color="tab:red",
                        label="step with cut-backs")
        if np.all(k > 0):
            ax.set_yscale("log")
        _finish(ax, True, "k (s)")
        ax.set_title("time step (cut back on a step that fails)",
                     fontsize=10)
    else:
        notes("iterations: no time_step column, panel left empty")
        _note_panel(ax, "time step: not in time_series.csv")
    return _save(fig, axes, "step", "iterations: ", run, out_dir,
                 "iterations.png", dpi)


# --------------------------------------------------------------------------
# Gamma_3 profiles
# --------------------------------------------------------------------------

def pick_steps(steps, most):
    """At most `most` of the steps, evenly spread, the last always among
    them; step 0 (the initial state, whose contact fields are 0) only if
    it is the only one."""
    later = [s for s in steps if s > 0]
    steps = later or list(steps)
    if len(steps) <= most:
        return list(steps)
    picks = np.linspace(0, len(steps) - 1, most).round().astype(int)
    return [steps[i] for i in sorted(set(picks.tolist()))]


def _position(tables):
    """The coordinate along which Gamma_3 extends most (its name and the
    arrays of each table)."""
    best, extent = None, -1.0
    for name in ("x", "y", "z"):
        if all(t.is_numeric(name) for t in tables):
            values = np.concatenate([t[name] for t in tables])
            spread = float(np.ptp(values)) if values.size else 0.0
            if spread > extent:
                best, extent = name, spread
    return best


def _component_or_magnitude(table, base):
    """2D: the column `base`; 3D: the magnitude of base_1, base_2. Returns
    (values, label suffix) or (None, None)."""
    if table.is_numeric(base):
        return table[base], ""
    first, second = base + "_1", base + "_2"
    if table.is_numeric(first) and table.is_numeric(second):
        return np.hypot(table[first], table[second]), " (magnitude)"
    return None, None


def plot_profiles(run, out_dir, notes, dpi, max_profiles=8):
    plt = _pyplot()
    steps = pick_steps(run.contact_steps, max_profiles)
    tables = [run.contact(s) for s in steps]
    later = [s for s in run.contact_steps if s > 0]
    if len(later) > len(steps):
        notes("gamma3_profiles: %d of the %d contact CSV files after step 0 "
              "drawn (steps %s)" % (len(steps), len(later),
                                    ", ".join(str(s) for s in steps)))
    coord = _position(tables)
    three_d = all(t.is_numeric("z") for t in tables)
    fig, axes = _figure(4, 11)
    colors = plt.get_cmap("viridis")(np.linspace(0, 0.9, len(steps)))
    panels = [
        ("normal_pressure", "normal pressure p+q (Pa)",
         "normal pressure on Gamma_3"),
        ("tangential_traction", "friction traction (Pa)",
         "friction traction of the foundation on the body"),
        ("w_tau", "tangential velocity (m/s)",
         "tangential velocity w_tau (slip rate where the node slips)"),
        ("mu", "mu", "friction coefficient mu"),
    ]
    for ax, (base, ylabel, title) in zip(axes, panels):
        drawn = False
        suffix = ""
        for color, step, table in zip(colors, steps, tables):
            values, suffix_here = _component_or_magnitude(table, base)
            if values is None or coord is None:
                continue
            suffix = suffix_here
            time = run.time_of(step)
            label = "step %d" % step if time is None else \
                "t = %.6g s (step %d)" % (time, step)
            order = np.argsort(table[coord], kind="stable")
            position, values = table[coord][order], values[order]
            if three_d or np.any(np.diff(position) <= 0):
                # A surface, or a curve with several nodes at one position:
                # the nodes only.
                ax.plot(position, values, ".", markersize=2.5, color=color,
                        label=label)
            else:
                ax.plot(position, values, ".-", markersize=3, linewidth=1,
                        color=color, label=label)
            drawn = True
        if drawn:
            ax.set_title(title + suffix, fontsize=10)
            ax.set_ylabel(ylabel)
            ax.grid(True, alpha=0.3)
            _no_offset(ax)
            if base == "normal_pressure":
                ax.set_ylim(bottom=min(0.0, ax.get_ylim()[0]))
        else:
            why = ("no friction columns (a run without friction)"
                   if base != "normal_pressure" else "no column")
            notes("gamma3_profiles: %s: %s, panel left empty" % (base, why))
            _note_panel(ax, "%s: %s" % (title, why))
    if any(ax.get_legend_handles_labels()[0] for ax in axes):
        for ax in axes:
            if ax.get_legend_handles_labels()[0]:
                ax.legend(fontsize=7, ncol=2)
                break
    return _save(fig, axes, "%s (m)%s" % (coord or "position",
                                          ", every node of the surface"
                                          if three_d else ""),
                 "Gamma_3 at the contact CSV times: ", run, out_dir,
                 "gamma3_profiles.png", dpi)


# --------------------------------------------------------------------------

def plot_run(directory, out_dir, max_profiles=8, dpi=100, log=print):
    """Draw the plots of the run in `directory` into `out_dir` (created if
    missing). Returns (paths written, notes)."""
    run = Run(directory)
    notes = _Notes(log)
    if os.path.realpath(out_dir) == os.path.realpath(directory):
        raise ValueError("the plots must not go into the output directory "
                         "itself (%s): it belongs to the program" % out_dir)
    if not run.has_time_series() and not run.contact_steps:
        raise ValueError("%s: neither time_series.csv nor contact_*.csv: "
                         "not an output directory of dynamic-contact, or "
                         "a run that did not start" % directory)
    if not is_completed(run.status):
        notes("run_status is '%s': plotting what is there"
              % (run.status if run.status is not None else "missing"))
    os.makedirs(out_dir, exist_ok=True)
    written = []
    if run.has_time_series():
        ts = run.time_series
        if "time" not in ts or not ts.is_numeric("time"):
            notes("time_series.csv has no numeric time column: forces.png, "
                  "energies.png and iterations.png not written")
        else:
            written.append(plot_forces(run, out_dir, notes, dpi))
            written.append(plot_energies(run, out_dir, notes, dpi))
            written.append(plot_iterations(run, out_dir, notes, dpi))
    else:
        notes("no time_series.csv: forces.png, energies.png and "
              "iterations.png not written")
    if run.contact_steps:
        written.append(plot_profiles(run, out_dir, notes, dpi, max_profiles))
    else:
        notes("no contact_NNNNN.csv: gamma3_profiles.png not written")
    return written, notes.items


def main(argv=None, doc=None):
    """The command line of scripts/plot-run (and of
    `python3 -m dynamic_contact.plotting`)."""
    doc = doc or __doc__
    parser = argparse.ArgumentParser(
        prog="plot-run", description=doc.strip().split("\n")[0],
        formatter_class=argparse.RawDescriptionHelpFormatter,
        epilog=doc.strip().split("\n", 1)[1] if "\n" in doc.strip() else None)
    parser.add_argument("outdir", help="the run's Output/Directory")
    parser.add_argument("--out", help="where the PNG files go "
                        "(default: OUTDIR/plots)")
    parser.add_argument("--profiles", type=int, default=8,
                        help="most contact CSV times in the profiles "
                        "(default 8)")
    parser.add_argument("--dpi", type=int, default=100)
    args = parser.parse_args(argv)
    if args.profiles < 1:
        parser.error("--profiles must be at least 1")
    out = args.out or os.path.join(args.outdir, "plots")
    try:
        written, _ = plot_run(args.outdir, out, max_profiles=args.profiles,
                              dpi=args.dpi,
                              log=lambda text: print(text, file=sys.stderr))
    except (OSError, ValueError) as error:
        sys.exit("plot-run: %s" % error)
    for path in written:
        print("wrote", path)


if __name__ == "__main__":
    main()
