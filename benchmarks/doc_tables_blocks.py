"""The blocks of benchmarks/doc-tables: each function takes the results
directory (doc_tables_common.Results) and returns the lines of one
generated block of a page (doc-tables' BLOCKS names them). Python 3
standard library only.
"""
import re

from doc_tables_common import (BE, QUANTITIES_2D, QUANTITIES_3D,
                               REFERENCE_NAMES, SCENE_FILES, SCHEME_NAMES,
                               THRESHOLDS, Failure, best, cells, cheapest,
                               cheapest_table, cost_2d, cost_3d, describe_2d,
                               describe_3d, family_order, number, order, para,
                               pct, reference_estimates, scheme_order, sci,
                               secs, sources, table)


def reference_block(csv_name, txt_name):
    """The extrapolated reference of a 2D scene (benchmarks/reference): its
    estimated error per quantity, the differences between the runs of each
    sequence, and the runs."""
    def block(results):
        rows = results.rows(csv_name)
        line = results.machine_line(csv_name)
        seq = re.search(r"in space \(([^)]*)\) and time \((\S+) at k=([^)]*)\)", line)
        if not seq:
            raise Failure("benchmarks/results/%s: its header does not name the space and "
                          "time sequences ('in space (...) and time (... at k=...)')" % csv_name)
        meshes = [cells(m.strip()) for m in seq.group(1).split(",")]
        ks = [k.strip() for k in seq.group(3).split(",")]
        out = sources(results, [csv_name, txt_name])
        l1 = (" but the friction force (L1 in time), whose error is the mean of its "
              "difference over time relative to the mean of the force"
              if any(r["quantity"] == "friction_l1" for r in rows) else "")
        out += para("Estimated error of the reference per quantity (relative, max norms%s; "
                    "\"none\": the observed order is below 1/2, no correction is made, the "
                    "observed order in brackets):" % l1)
        body = []
        for r in rows:
            def observed(key, used):
                if r[used] == "none":
                    return "none (%s)" % order(number(r, key))
                return order(number(r, key))
            body.append([REFERENCE_NAMES.get(r["quantity"], r["quantity"]),
                         observed("p_space", "p_used"), observed("q_time", "q_used"),
                         sci(number(r, "correction_space")), sci(number(r, "correction_time")),
                         sci(number(r, "e_space")), sci(number(r, "e_time")),
                         sci(number(r, "e_thickness")),
                         "**%s**" % sci(number(r, "estimate"))])
        out += table(["quantity", "p (space)", "q (time)", "C_space", "C_time", "e_space",
                      "e_time", "e_y", "**estimated error of the reference**"], body)
        out += [""] + para(
            "The differences between successive runs of each sequence (norms relative "
            "to the quantity's; space at k = %s, time on %s), e_interp (the error "
            "of interpolating a history linearly between the steps of k = %s, measured on "
            "k = %s) and the bound (the error of the finest run itself):"
            % (ks[0], cells(seq.group(2)), ks[0], ks[1]))
        body = [[REFERENCE_NAMES.get(r["quantity"], r["quantity"]),
                 sci(number(r, "diff_space_coarse")), sci(number(r, "diff_space_fine")),
                 sci(number(r, "diff_time_coarse")), sci(number(r, "diff_time_fine")),
                 sci(number(r, "e_interpolation")), sci(number(r, "bound"))] for r in rows]
        out += table(["quantity", "%s → %s" % (meshes[0], meshes[1]),
                      "%s → %s" % (meshes[1], meshes[2]),
                      "k = %s → %s" % (ks[0], ks[1]), "k = %s → %s" % (ks[1], ks[2]),
                      "e_interp", "bound"], body)
        runs = []
        for text in results.lines(txt_name):
            m = re.match(r"^\s+h(\d+x\d+)-k(\d+)\s+(\d+) DoFs\s+wall\s+([\d.]+) s"
                         r"\s+CPU\s+([\d.]+) s", text)
            if m:
                runs.append([cells(m.group(1)) + ", k = 1/" + m.group(2), m.group(3),
                             m.group(5), m.group(4)])
        if not runs:
            raise Failure("benchmarks/results/%s: no run lines ('  hNXxNY-kM  N DoFs  wall "
                          "W s  CPU C s')" % txt_name)
        out += [""] + para("The runs (one process each):")
        out += table(["run (Q1)", "DoFs", "CPU (s)", "wall (s)"], runs)
        return out
    return block


def cheapest_block(results, rows, name, reference, text, quantities, describe, error, cost):
    """A block of the cheapest configuration per accuracy: the sources (the
    study's results file @p name and the reference's @p reference), the
    prose @p text (with the number of configurations for its %d) and the
    table of cheapest_table()."""
    estimates = reference_estimates(results, reference)
    out = sources(results, [name, reference])
    out += para(text % len(rows))
    return out + table(["quantity", "ref. error"] + [t for _, t in THRESHOLDS],
                       cheapest_table(rows, quantities, estimates, describe, error, cost))


def block_paper_cheapest(results):
    rows = [r for r in results.rows("work_precision.csv") if r.get("status") == "completed"]
    return cheapest_block(
        results, rows, "work_precision.csv", "reference_error.csv",
        "The cheapest configuration (by CPU time) whose error is at most 10 %%, 1 %%, "
        "0.1 %%, with its error and cost (CPU s, wall s); backward Euler unless a scheme "
        "is named; * marks a target below the reference's estimated error, where a "
        "configuration agrees with the reference to that level but the accuracy is not "
        "certified; \"none\": no configuration of the %d reaches it (the best one in "
        "brackets).", QUANTITIES_2D, describe_2d, sci, cost_2d)


def block_paper_per_method(results):
    """The cheapest configuration per method at 0.1 % in N(t), and the
    paper's resolution (initial_layer.txt, paper_scene.csv)."""
    rows = [r for r in results.rows("work_precision.csv") if r.get("status") == "completed"]
    key, threshold = "normal_force", 0.001
    groups = [("Q2, backward Euler",
               lambda r: r["degree"] == "2" and r["scheme"] == BE and r["strategy"] == "uniform"),
              ("Q1, backward Euler",
               lambda r: r["degree"] == "1" and r["scheme"] == BE and r["strategy"] == "uniform"),
              ("Q1/Q2, trapezoidal", lambda r: r["scheme"] == "trapezoidal"),
              ("Q1/Q2, Bathe", lambda r: r["scheme"] == "bathe"),
              ("load-following adaptive Q1", lambda r: r["strategy"] == "adaptive")]
    body = []
    for label, member in groups:
        group = [r for r in rows if member(r)]
        if not group:
            continue
        r = cheapest(group, key, threshold)
        if r is not None:
            name = describe_2d(r)
            if r["name"] in SCENE_FILES:
                name += " (`%s`)" % SCENE_FILES[r["name"]]
            body.append([label, name, sci(number(r, key)), secs(number(r, "cpu_time"))])
        else:
            b = best(group, key)
            body.append([label, "not reached (best: %s)" % describe_2d(b),
                         sci(number(b, key)), secs(number(b, "cpu_time"))])
    paper = None
    for text in results.lines("initial_layer.txt"):
        m = re.match(r"^\s*prm/barboteu_danan_2016\.prm \(([^)]*)\)\s+N\(t\) ([0-9.e+-]+)", text)
        if m:
            paper = (m.group(1), float(m.group(2)))
    if paper is None:
        raise Failure("benchmarks/results/initial_layer.txt: no line 'prm/barboteu_danan_2016.prm "
                      "(...) N(t) ERROR' (its part 2)")
    _, scene = results.row(["paper_scene.csv"], "config", "friction")
    reached = "reached" if paper[1] <= threshold else "not reached"
    body.append(["the paper's resolution, %s (`prm/barboteu_danan_2016.prm`)"
                 % paper[0].replace(" x ", " × "),
                 "%s (`initial_layer.txt`, part 2; not a configuration of the study)" % reached,
                 sci(paper[1]),
                 "not timed by the study (`paper_scene.csv`: %s s of wall time, median, "
                 "without output files)" % secs(number(scene, "wall_time_median"))])
    out = sources(results, ["work_precision.csv", "initial_layer.txt", "paper_scene.csv"])
    out += para("The cheapest configuration of each method whose error in N(t) is at most "
                "0.1 %, or the best one where none is (CPU time, one core):")
    out += table(["method", "cheapest configuration at ≤ 0.1 % in N(t)", "error in N(t)",
                  "CPU (s)"], body)
    return out


def block_paper_configurations(results):
    rows = [r for r in results.rows("work_precision.csv") if r.get("status") == "completed"]
    rows.sort(key=family_order)
    body = []
    for r in rows:
        body.append([describe_2d(r, scheme=False),
                     SCHEME_NAMES.get(r["scheme"], r["scheme"]) +
                     (", ρ∞ = " + re.search(r"rho_inf=([0-9.]+)", r["label"]).group(1)
                      if "rho_inf" in r["label"] else ""),
                     r["dofs"], r["steps"], secs(number(r, "cpu_time")),
                     secs(number(r, "wall_time")), r.get("load_1min_before") or "–"] +
                    [sci(number(r, key)) for key, _ in QUANTITIES_2D])
    out = sources(results, ["work_precision.csv"])
    out += para("Every configuration of the study (%d), grouped by scheme and mesh family: its "
                "DoFs, steps (more than 1/k where a step was cut back), CPU and wall time "
                "(median of the runs), the machine's 1-minute load before it, and its relative "
                "errors (\"–\": not measured)." % len(rows))
    out += table(["configuration", "scheme", "DoFs", "steps", "CPU (s)", "wall (s)", "load"] +
                 [label for _, label in QUANTITIES_2D], body)
    return out


def rows_block(names, columns, what, error=sci):
    """Named rows of the 2D study (work_precision.csv first, then
    work_precision_sdirk.csv) with the given error columns."""
    def block(results):
        files, body = [], []
        for name in names:
            f, r = results.row(["work_precision.csv", "work_precision_sdirk.csv"], "name", name)
            if f not in files:
                files.append(f)
            rho = re.search(r"rho_inf=([0-9.]+)", r.get("label", ""))
            line = [describe_2d(r, scheme=False), SCHEME_NAMES.get(r["scheme"], r["scheme"])]
            if "rho" in columns:
                line.append(rho.group(1) if rho else "0" if r["scheme"] == "bathe" else "–")
            line += [error(number(r, key)) for key, _ in QUANTITIES_2D if key in columns]
            if "cpu" in columns:
                line += [secs(number(r, "cpu_time")) if number(r, "cpu_time") is not None
                         else "not kept", r.get("load_1min_before") or "–"]
            body.append(line)
        out = sources(results, files, what)
        header = ["configuration", "scheme"] + (["ρ∞"] if "rho" in columns else [])
        header += [label for key, label in QUANTITIES_2D if key in columns]
        header += ["CPU (s)", "load"] if "cpu" in columns else []
        return out + table(header, body)
    return block


def block_rail_reference(results):
    rows = results.rows("reference_3d_error.csv")
    body = [[r["quantity"].replace("_", " ").replace("normal force", "N(t)"),
             "%s, %s" % (order(number(r, "p_space")), order(number(r, "p_space_2"))),
             "%s, %s" % (order(number(r, "q_time")), order(number(r, "q_time_2"))),
             pct(number(r, "correction_space")), pct(number(r, "correction_time")),
             pct(number(r, "e_space")), pct(number(r, "e_time")), pct(number(r, "e_mix")),
             "**%s**" % pct(number(r, "estimate"))] for r in rows]
    out = sources(results, ["reference_3d_error.csv"])
    out += para("Observed orders and corrections of the 3D reference and its estimated error "
                "per quantity (relative to the quantity's maximum; \"–\": undefined, the "
                "differences did not shrink):")
    return out + table(["quantity", "p, p₂ (space)", "q, q₂ (time)", "C_space", "C_time",
                        "e_space", "e_time", "e_mix", "**estimated error**"], body)


def block_rail_cheapest(results):
    rows = results.rows("work_precision_3d.csv")
    return cheapest_block(
        results, rows, "work_precision_3d.csv", "reference_3d_error.csv",
        "The cheapest configuration (by CPU time, one process) whose error is at most "
        "10 %%, 1 %%, 0.1 %%, with its error and CPU time; backward Euler unless a scheme "
        "is named; where the cheapest is an adaptive mesh, the cheapest uniform one "
        "follows; * marks a target below the reference's estimated error; \"none\": "
        "no configuration of the %d reaches it (the best one in brackets).",
        QUANTITIES_3D, describe_3d, pct, cost_3d)


def block_rail_configurations(results):
    rows = results.rows("work_precision_3d.csv")
    rows.sort(key=lambda r: (scheme_order(r), r["strategy"] != "uniform", r["degree"],
                             int(r["mesh"].split("x")[0]), r["mesh"], -float(r["k"])))
    body = [[describe_3d(r, scheme=False), SCHEME_NAMES.get(r["scheme"], r["scheme"]),
             r["dofs"], r["steps"], r["newton_per_step"], secs(number(r, "cpu_time")),
             secs(number(r, "wall_time"))] +
            [pct(number(r, key)) for key, _ in QUANTITIES_3D] for r in rows]
    out = sources(results, ["work_precision_3d.csv"])
    out += para("Every configuration of the 3D study (%d): DoFs (the mean over the steps on "
                "an adaptive mesh), steps, Newton iterations per step, CPU and wall time of "
                "one process, and the relative errors over t ∈ [1/16, 0.25]." % len(rows))
    return out + table(["configuration", "scheme", "DoFs", "steps", "Newton/step",
                        "CPU (s)", "wall (s)"] + [label for _, label in QUANTITIES_3D], body)


def block_rail_fast_scene(results):
    name = "q2-bathe-h24-k32"
    _, r = results.row(["work_precision_3d.csv"], "name", name)
    estimates = reference_estimates(results, "reference_3d_error.csv")
    body = []
    for key, label in QUANTITIES_3D:
        e, ref = number(r, key), estimates.get(key)
        body.append([label, pct(e), pct(ref), pct(e + ref) if None not in (e, ref) else "–"])
    out = sources(results, ["work_precision_3d.csv", "reference_3d_error.csv"])
    out += para("`%s` (%s; the configuration `%s`): its errors over t ∈ [1/16, 0.25], "
                "the reference's own estimated error, and their sum, the most the scene "
                "can be off; %s s of CPU without output files."
                % (SCENE_FILES[name], describe_3d(r), name, secs(number(r, "cpu_time"))))
    return out + table(["quantity", "error", "reference's estimated error", "sum"], body)


def block_well_posed_configurations(results):
    rows = [r for r in results.rows("work_precision_well_posed.csv")
            if r.get("status") == "completed"]
    rows.sort(key=family_order)
    keys = [q for q in QUANTITIES_2D if q[0] != "theorem6"]
    keys.insert(2, ("friction_l1", "friction force (L1)"))
    body = [[describe_2d(r, scheme=False), SCHEME_NAMES.get(r["scheme"], r["scheme"]),
             r["dofs"], secs(number(r, "cpu_time")), secs(number(r, "wall_time"))] +
            [pct(number(r, key)) for key, _ in keys] for r in rows]
    out = sources(results, ["work_precision_well_posed.csv"])
    out += para("Every configuration (%d): DoFs, CPU and wall time of one process (one run "
                "each), and the relative errors against the reference made with the Bathe "
                "scheme over t ∈ [1/16, 1] (the friction force (L1): the mean of its error "
                "over time relative to its mean)." % len(rows))
    return out + table(["configuration", "scheme", "DoFs", "CPU (s)", "wall (s)"] +
                       [label for _, label in keys], body)


def block_memory_mesh(results):
    rows = results.rows("memory.csv")
    items = ["mesh (with p4est)", "DoF handlers and index sets"]
    body, seen = [], set()
    for r in rows:
        if r["item"] in items and (r["ranks"], r["item"]) not in seen:
            # The first preconditioner's row: the mesh does not depend on it.
            first = next(x for x in rows if x["ranks"] == r["ranks"])["preconditioner"]
            if r["preconditioner"] != first:
                continue
            seen.add((r["ranks"], r["item"]))
            body.append([r["ranks"], r["item"], r["mb_largest"], r["mb_all"],
                         r["bytes_per_dof"]])
    if not body:
        raise Failure("benchmarks/results/memory.csv: no rows of the items %s" % items)
    out = sources(results, ["memory.csv"])
    out += para("The mesh and the DoF handlers of the rail on 320 × 32 × 32 cells made as "
                "`Repetitions = 10, 1, 1` with `Global refinements = 5`, on 1 and 16 processes "
                "(the other parts: [performance.md](performance.md), `memory.csv`):")
    return out + table(["processes", "part", "MB on the largest process", "MB in all",
                        "bytes per DoF"], body)


def block_processes_every_process(results):
    name = "processes_16cores_every_process.csv"
    rows = [r for r in results.rows(name) if r["scene"] == "paper"]
    if not rows:
        raise Failure("benchmarks/results/%s: no rows of the scene 'paper'" % name)
    body = [[r["ranks"], r["wall_time_median"], r["ratio_to_fewest"]] for r in rows]
    out = sources(results, [name])
    out += para("The paper's scene (%s DoFs, %s steps) on the 16-core machine with every "
                "process taking part (before `Solver/Minimum DoFs per process`), one run "
                "each:" % (rows[0]["dofs"], rows[0]["steps"]))
    return out + table(["processes", "wall time (s)", "ratio to one process"], body)


def block_slip_length(results):
    name = "slip_length.txt"
    body = [line for line in results.lines(name) if not line.startswith("#")]
    while body and not body[0].strip():
        body.pop(0)
    while body and not body[-1].strip():
        body.pop()
    if not body:
        raise Failure("benchmarks/results/%s: no report below its header" % name)
    out = sources(results, [name], "The report as `benchmarks/slip-length` writes it.")
    if out[-1].strip():
        out.append("")
    return out + ["```"] + body + ["```"]
