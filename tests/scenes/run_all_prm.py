#!/usr/bin/python3
"""The ctest `run_all_prm`: every parameter file of prm/ and prm/stress/
runs to the end at a small size, so that none of them rots.

    run_all_prm.py --program build/dynamic-contact --work-dir DIR
                   [--source-dir REPO] [--jobs 2] [--steps 3]

Every *.prm under prm/ and prm/stress/ (found at run time: a new file is
tested as soon as it is there) runs once, serially, in DIR/<name>/, with
`--set` overrides that make it small:

1. for every file: no VTU, no progress lines, no timings, and
   Time/End time = STEPS time steps (or the file's own end time if that is
   shorter);
2. prm/stress/*.prm: the overrides of prm/stress/quick.txt (the sizes of
   `benchmarks/stress --quick`);
3. the table below (the repository's large scenes, on smaller meshes);
4. the file's own comment lines `# test-overrides: Section/Name=value | ...`
   (for a new file that is too large as it stands).

Later overrides win. A file passes if the program exits with 0 and its
run_status says 'completed'. Prints one line per file, in the order of the
file names ("prm/NAME.prm: completed" or "... FAILED: reason"; the end of
the failed run's screen output goes to stderr), then a summary; exit code 1
if any file failed.
"""

import concurrent.futures
import os
import subprocess
import sys

from dynamic_contact import read_prm, read_run_status, test_overrides
from dynamic_contact.output import is_completed

from script_checks import program_arguments

# benchmarks/benchlib.py: the program's command line, --print-parameters.
sys.path.insert(0, os.path.join(os.path.dirname(os.path.realpath(__file__)),
                                "..", "..", "benchmarks"))
import benchlib  # noqa: E402

# Files of prm/ that are too large to run as they are: smaller meshes, the
# same physics. (A new file can say this itself: '# test-overrides:'.)
TABLE = {
    "prm/barboteu_danan_2016.prm": ["Geometry/Repetitions=32, 8"],
    "prm/figure3_psi5.prm": ["Geometry/Repetitions=32, 8"],
    "prm/figure3_psi20.prm": ["Geometry/Repetitions=32, 8"],
    "prm/barboteu_danan_2016_adaptive.prm": [
        "Geometry/Repetitions=8, 8", "Mesh refinement/Maximum level=1"],
    "prm/rail_3d.prm": ["Geometry/Repetitions=20, 2, 2"],
}



def quick_table(path):
    """prm/stress/quick.txt: {scene: [overrides]}."""
    table = {}
    if not os.path.exists(path):
        return table
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if not line:
                continue
            fields = [x.strip() for x in line.split("|")]
            table[fields[0]] = [x for x in fields[1:] if x]
    return table


def as_dict(overrides):
    return dict(o.split("=", 1) for o in overrides if "=" in o)


def environment():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
                OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")


def printed_parameter(program, prm, overrides, entry):
    """The value of one entry as `--print-parameters` gives it."""
    result, values = benchlib.print_parameters(program, prm, overrides)
    if values is None:
        raise RuntimeError("--print-parameters failed: "
                           + result.stdout.strip()[-500:])
    if entry not in values:
        raise RuntimeError("--print-parameters does not print " + entry)
    return values[entry]


def overrides_of(program, root, relative, quick, steps):
    path = os.path.join(root, relative)
    own = []
    if relative.startswith("prm/stress/"):
        scene = os.path.splitext(os.path.basename(relative))[0]
        own += quick.get(scene, [])
    own += TABLE.get(relative, [])
    own += test_overrides(path)
    given = dict(read_prm(path))
    given.update(as_dict(own))
    if "Time/Time step" in given:
        k = float(given["Time/Time step"])
    else:
        k = float(printed_parameter(program, path, own, "Time/Time step"))
    end = steps * k
    if "Time/End time" in given:
        end = min(end, float(given["Time/End time"]))
    generic = ["Output/Write VTU=false", "Output/Progress every=0",
               "Output/Print timings=false", "Output/Print iteration counts=false",
               "Time/End time=%.17g" % end]
    return generic + own


def run_one(program, root, relative, work_dir, quick, steps):
    """(relative, verdict line, screen output if it failed)."""
    name = os.path.splitext(relative)[0].replace("/", "_")
    directory = os.path.join(work_dir, name)
    try:
        overrides = overrides_of(program, root, relative, quick, steps)
    except (OSError, ValueError, RuntimeError) as error:
        return relative, "FAILED: %s" % error, ""
    command = benchlib.program_command(
        program, os.path.join(root, relative),
        overrides + ["Output/Directory=" + directory])
    result = subprocess.run(command, stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True,
                            env=environment(), cwd=work_dir)
    status = read_run_status(directory)
    if result.returncode == 0 and is_completed(status):
        return relative, "completed", ""
    return relative, ("FAILED: exit code %d, run_status '%s'"
                      % (result.returncode, status)), \
        "$ %s\n%s" % (" ".join(command), result.stdout[-3000:])


def main():
    parser = program_arguments(__doc__)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--steps", type=int, default=3)
    args = parser.parse_args()

    root = os.path.realpath(args.source_dir)
    files = []
    for sub in ("prm", os.path.join("prm", "stress")):
        directory = os.path.join(root, sub)
        files += sorted(os.path.join(sub, f) for f in os.listdir(directory)
                        if f.endswith(".prm"))
    if not files:
        sys.exit("run_all_prm: no *.prm under %s/prm" % root)
    quick = quick_table(os.path.join(root, "prm", "stress", "quick.txt"))
    os.makedirs(args.work_dir, exist_ok=True)
    work_dir = os.path.realpath(args.work_dir)
    program = os.path.realpath(args.program)

    with concurrent.futures.ThreadPoolExecutor(max(1, args.jobs)) as pool:
        results = list(pool.map(
            lambda f: run_one(program, root, f, work_dir, quick, args.steps),
            files))
    failed = 0
    for relative, verdict, log in results:
        print("%s: %s" % (relative, verdict), flush=True)
        if log:
            failed += 1
            print(log, file=sys.stderr, flush=True)
        elif verdict != "completed":
            failed += 1
    print("run_all_prm: %d of %d parameter files completed"
          % (len(files) - failed, len(files)))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
