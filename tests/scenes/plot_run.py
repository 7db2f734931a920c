#!/usr/bin/python3
"""The ctest `plot_run`: scripts/plot-run draws its PNG files for runs of
every kind, and touches nothing of the run but its plots/ directory.

    plot_run.py --program build/dynamic-contact --work-dir DIR
                [--mpiexec "mpiexec --allow-run-as-root --oversubscribe"]

Three small runs (a few steps each) into DIR:
  friction_2d    prm/barboteu_danan_2016_small.prm: 2D, the exponential
                 friction law (convexification passes), serial, contact
                 CSV every 2 steps
  friction_3d    prm/sliding_block_3d.prm: 3D, constant friction, on 2 MPI
                 processes (serially if --mpiexec is not given)
  frictionless   prm/pressed_block.prm: 2D without friction
For each, plot-run OUTDIR must exit with 0 and write exactly forces.png,
energies.png, iterations.png and gamma3_profiles.png (PNG files, not empty)
into OUTDIR/plots/, and leave every other file of OUTDIR as it was. The
frictionless run must get a note for its friction panels. Then:
  - a new run of the program into friction_2d/ (with its plots/) completes
    and leaves plots/ alone;
  - plot-run --out OUTDIR (the output directory itself) is refused and
    writes nothing.
Prints the file names and the verdicts (no numbers, no paths); exit code 1
if a check fails.
"""

import os
import shlex
import subprocess
import sys

EXPECTED = ["energies.png", "forces.png", "gamma3_profiles.png",
            "iterations.png"]
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"

CASES = [
    ("friction_2d", "prm/barboteu_danan_2016_small.prm", 1,
     ["Time/End time=0.0625", "Output/Output every=2"]),
    ("friction_3d", "prm/sliding_block_3d.prm", 2,
     ["Time/End time=0.03", "Output/Output every=1"]),
    ("frictionless", "prm/pressed_block.prm", 1,
     ["Time/End time=3", "Output/Output every=1"]),
]
QUIET = ["Output/Write VTU=false", "Output/Progress every=0",
         "Output/Print timings=false",
         "Output/Print iteration counts=false"]

from script_checks import check, finish, program_arguments


def environment():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")


def snapshot(directory, skip="plots"):
    """Every file below directory but skip/: {relative path: (size,
    modification time)}."""
    found = {}
    for base, dirs, files in os.walk(directory):
        if base == directory and skip in dirs:
            dirs.remove(skip)
        for name in files + dirs:
            path = os.path.join(base, name)
            st = os.lstat(path)
            found[os.path.relpath(path, directory)] = \
                (st.st_size if name in files else 0, st.st_mtime_ns)
    return found


def run_program(args, root, prm, ranks, overrides, directory):
    command = [args.program, os.path.join(root, prm)]
    for o in QUIET + overrides + ["Output/Directory=" + directory]:
        command += ["--set", o]
    if ranks > 1 and args.mpiexec:
        command = shlex.split(args.mpiexec) + ["-np", str(ranks)] + command
    result = subprocess.run(command, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True,
                            env=environment())
    status = None
    if os.path.exists(os.path.join(directory, "run_status")):
        with open(os.path.join(directory, "run_status")) as f:
            status = f.read().strip()
    if result.returncode != 0 or status != "completed":
        print(result.stdout[-3000:], file=sys.stderr)
    return result.returncode == 0 and status == "completed"


def plot_run(root, arguments):
    return subprocess.run([sys.executable,
                           os.path.join(root, "scripts", "plot-run")]
                          + arguments, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True)


def main():
    parser = program_arguments(__doc__)
    parser.add_argument("--mpiexec", default="")
    args = parser.parse_args()
    root = os.path.realpath(args.source_dir)
    os.makedirs(args.work_dir, exist_ok=True)
    work = os.path.realpath(args.work_dir)

    for name, prm, ranks, overrides in CASES:
        directory = os.path.join(work, name)
        if not run_program(args, root, prm, ranks, overrides, directory):
            check(False, "%s: the run of %s completed" % (name, prm))
            continue
        before = snapshot(directory)
        result = plot_run(root, [directory])
        if result.returncode != 0:
            print(result.stdout + result.stderr, file=sys.stderr)
        check(result.returncode == 0, "%s: plot-run exit code 0" % name)
        plots = os.path.join(directory, "plots")
        names = sorted(os.listdir(plots)) if os.path.isdir(plots) else []
        print("%s: plots/ holds %s" % (name, " ".join(names) or "nothing"))
        check(names == EXPECTED, "%s: the four PNG files" % name)
        good = True
        for png in names:
            with open(os.path.join(plots, png), "rb") as f:
                good &= f.read(8) == PNG_SIGNATURE
        check(good and bool(names), "%s: they are PNG files" % name)
        check(snapshot(directory) == before,
              "%s: nothing else in the output directory changed" % name)
        if name == "frictionless":
            check("tangential_traction" in result.stderr and
                  "without friction" in result.stderr,
                  "%s: a note for the friction panels" % name)

    # The program runs again in a directory with plots/ and leaves it.
    directory = os.path.join(work, "friction_2d")
    _, prm, ranks, overrides = CASES[0]
    if os.path.isdir(os.path.join(directory, "plots")):
        check(run_program(args, root, prm, ranks, overrides, directory),
              "friction_2d: a new run into the directory with plots/ "
              "completes")
        names = sorted(os.listdir(os.path.join(directory, "plots")))
        check(names == EXPECTED, "friction_2d: plots/ is still there")

        # The output directory itself is refused as --out.
        before = snapshot(directory, skip="")
        result = plot_run(root, [directory, "--out", directory])
        check(result.returncode != 0 and
              "must not go into the output directory" in result.stderr,
              "plot-run --out OUTDIR is refused")
        check(snapshot(directory, skip="") == before,
              "plot-run --out OUTDIR wrote nothing")

    finish("plot_run")


if __name__ == "__main__":
    main()
