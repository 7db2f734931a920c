#!/usr/bin/python3
"""The ctest `well_posedness_scenes`: the well-posedness report on every scene.

    well_posedness_scenes.py --program build/dynamic-contact --work-dir DIR
                             [--source-dir REPO] [--jobs 2]

Runs `dynamic-contact --validate` on every *.prm of prm/ and prm/stress/
(found at run time, so that a new scene is covered at once) and reads the
well-posedness report it prints after the verdict (doc/theory.md section
1.5): the radiation-damping line (L S/(rho c_s) < 1) and the line of the
viscosity against the weakening (the paper's Remark 8). Checks:

1. every scene validates, and prints either no report (no slip-rate
   dependent friction) or both lines, each of which says "holds" or
   "fails" (or, for the second, "no viscosity");
2. the paper's scenes (those with its slip-weakening law on its rail,
   PAPER below) are flagged: radiation damping fails, no viscosity;
3. the scenes built to be covered (COVERED below,
   prm/barboteu_danan_2016_well_posed.prm) hold on both lines;
4. the scenes with a slip length (SLIP_LENGTH below) are flagged as the
   paper's, their radiation line says it concerns the steady-sliding law,
   and they alone print the report's slip-length line.

Prints one line per scene (its two verdicts), then the checks. Takes a few
seconds (each --validate builds the mesh, and stops).
"""

import concurrent.futures
import glob
import os
import re
import subprocess

from script_checks import check, finish, program_arguments

# The paper's scenes (Barboteu & Danan 2016: its slip-weakening law, its
# rail and foundation, no viscosity), in 2D and 3D, with their variants.
PAPER = ["prm/barboteu_danan_2016.prm", "prm/barboteu_danan_2016_small.prm",
         "prm/barboteu_danan_2016_fast.prm", "prm/barboteu_danan_2016_adaptive.prm",
         "prm/barboteu_danan_2016_adaptive_small.prm", "prm/gmsh_rail.prm",
         "prm/rail_3d.prm", "prm/rail_3d_small.prm", "prm/rail_3d_fast.prm"]
# Scenes whose data were chosen so that both conditions hold.
COVERED = ["prm/barboteu_danan_2016_well_posed.prm"]
# Scenes with a slip length (Friction/Slip length > 0): the paper's data,
# flagged like the paper's scenes, and the report's slip-length line,
# which no other scene prints.
SLIP_LENGTH = ["prm/barboteu_danan_2016_slip_length.prm"]


def report(program, source, prm):
    """(exit code, the radiation line, the viscosity line, output)."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")
    r = subprocess.run([program, "--validate", prm], cwd=source, env=env,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                       universal_newlines=True, timeout=120)
    radiation = [x.strip() for x in r.stdout.splitlines()
                 if x.strip().startswith("radiation damping")]
    viscosity = [x.strip() for x in r.stdout.splitlines()
                 if x.strip().startswith("viscosity against the weakening")]
    return (r.returncode, radiation[0] if radiation else None,
            viscosity[0] if viscosity else None, r.stdout)


def verdict(line):
    """'holds', 'fails', 'no viscosity', 'none' (no line) or '?'."""
    if line is None:
        return "none"
    if "no viscosity" in line:
        return "no viscosity"
    m = re.search(r": (holds|fails) by a factor", line)
    if m:
        return m.group(1)
    if "holds at any normal stress" in line:
        return "holds"
    return "?"


def main():
    parser = program_arguments(__doc__)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args()
    source = os.path.abspath(args.source_dir)
    os.makedirs(args.work_dir, exist_ok=True)
    scenes = sorted(os.path.relpath(p, source) for p in
                    glob.glob(os.path.join(source, "prm", "*.prm"))
                    + glob.glob(os.path.join(source, "prm", "stress", "*.prm")))
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        results = dict(zip(scenes, pool.map(
            lambda s: report(args.program, source, s), scenes)))
    with open(os.path.join(args.work_dir, "reports.txt"), "w") as f:
        for s in scenes:
            f.write("== %s\n%s\n" % (s, results[s][3]))
    for s in scenes:
        code, rad, vis, _ = results[s]
        print("%-50s radiation: %-6s viscosity: %s"
              % (s, verdict(rad), verdict(vis)))
    for s in scenes:
        code, rad, vis, out = results[s]
        check(code == 0 and "is valid" in out, "%s validates" % s)
        check((rad is None) == (vis is None)
              and verdict(rad) in ("none", "holds", "fails")
              and verdict(vis) in ("none", "holds", "fails", "no viscosity"),
              "%s: no report, or both lines with their verdicts" % s)
    for s in PAPER:
        code, rad, vis, _ = results.get(s, (1, None, None, ""))
        check(verdict(rad) == "fails" and verdict(vis) == "no viscosity",
              "%s (the paper's scene) is flagged: radiation damping fails, "
              "no viscosity" % s)
    for s in SLIP_LENGTH:
        code, rad, vis, out = results.get(s, (1, None, None, ""))
        check(verdict(rad) == "fails" and verdict(vis) == "no viscosity"
              and "the steady-sliding law outruns" in (rad or ""),
              "%s (the paper's data with a slip length) is flagged for its "
              "steady-sliding law" % s)
    printed = sorted(s for s in scenes if "    slip length (" in results[s][3])
    check(printed == SLIP_LENGTH,
          "the slip-length line only where a scene sets a slip length (%s)"
          % (", ".join(printed) or "none"))
    for s in COVERED:
        code, rad, vis, _ = results.get(s, (1, None, None, ""))
        check(verdict(rad) == "holds" and verdict(vis) == "holds",
              "%s is covered: both conditions hold" % s)
    finish("well_posedness_scenes")


if __name__ == "__main__":
    main()
