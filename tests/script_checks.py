"""What the Python test scripts of tests/ share: a check that prints one
line and remembers a failure, a small file writer, the last line with the
exit code (1 if a check failed), the arguments of a script that runs
the program, one run of a scene and a CSV reader. The scripts import it from their own folder (Python puts a
script's folder first on its path)."""

import argparse
import csv
import os
import shlex
import subprocess
import sys

failures = []


def check(condition, text):
    print("%s: %s" % ("ok" if condition else "FAILED", text), flush=True)
    if not condition:
        failures.append(text)


def write(path, text):
    with open(path, "w") as f:
        f.write(text)


def finish(name):
    print("%s: %s" % (name, "every check passed" if not failures else
                      "%d checks failed" % len(failures)))
    sys.exit(1 if failures else 0)


def program_arguments(doc):
    """A parser with --program, --work-dir and --source-dir (the folder
    above tests/ by default), described by the second line of @p doc."""
    here = os.path.dirname(os.path.realpath(__file__))
    parser = argparse.ArgumentParser(description=doc.split("\n")[1])
    parser.add_argument("--program", required=True)
    parser.add_argument("--work-dir", required=True)
    parser.add_argument("--source-dir", default=os.path.dirname(here))
    return parser


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def run_scene(program, scene, out, overrides=(), processes=1,
              mpiexec="mpiexec"):
    """Run @p program on @p scene into the directory @p out (no timings,
    no progress lines, one thread) with the entries @p overrides
    ("Section/Name=value"), on @p processes MPI processes (started by
    @p mpiexec) if more than one; whether it exited 0 with run_status
    'completed' (if not, the end of its output goes to stderr)."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")
    command = shlex.split(mpiexec) + ["-np", str(processes)] \
        if processes > 1 else []
    command += [program, "--set", "Output/Directory=" + out,
                "--set", "Output/Print timings=false",
                "--set", "Output/Progress every=0"]
    for o in overrides:
        command += ["--set", o]
    result = subprocess.run(command + [scene], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            universal_newlines=True)
    status = ""
    if os.path.exists(os.path.join(out, "run_status")):
        with open(os.path.join(out, "run_status")) as f:
            status = f.read().strip()
    if result.returncode != 0 or status != "completed":
        sys.stderr.write(result.stdout[-3000:])
    return result.returncode == 0 and status == "completed"
