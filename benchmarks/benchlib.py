"""Shared pieces of the benchmark scripts (benchmarks/figure4,
benchmarks/work-precision and others): the Python with numpy/matplotlib,
the executable, one timed run of a scene, the cached 128 x 128 reference
run of the paper's scene, the machine line, and reading a results file's
header back (benchmarks/performance-page, benchmarks/doc-tables).

Not a command; imported by the scripts (and usable on its own). Its
imports are of the standard library only: numpy and matplotlib are
imported by the scripts that need them, after ensure_python().
"""
import csv
import json
import os
import platform
import re
import resource
import shutil
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BENCH = os.path.join(ROOT, "benchmarks")
RESULTS = os.path.join(BENCH, "results")
FIGURES = os.path.join(ROOT, "doc", "figures")
SCRATCH = os.path.join(ROOT, "build", "benchmarks")

PAPER_PRM = os.path.join(ROOT, "prm", "barboteu_danan_2016.prm")
ADAPTIVE_PRM = os.path.join(ROOT, "prm", "barboteu_danan_2016_adaptive.prm")

# The comparison times: multiples of 1/8 s lie on the time grid of every run
# with k = 1/n, n a multiple of 8 (and k = 1/(2n)).
COMMON_TIMES = [i / 8 for i in range(1, 9)]

# The reference: the paper's resolution, uniform Q1, h = k = 1/128.
REFERENCE_N = 128
REFERENCE_DIR = os.path.join(SCRATCH, "reference-%d" % REFERENCE_N)

# 'Output/Output times': the program writes at the first step with
# t >= t_out (to a round-off allowance). Asking for t - 1e-7 (well below any
# step, well above the allowance) makes the step at t the one that writes,
# however the step times round.
OUTPUT_TIME_SHIFT = 1e-7


# A Python that may have numpy and matplotlib when the one running does not
# (e.g. a pyenv or virtualenv python3 first on the PATH): Debian's.
SYSTEM_PYTHON = "/usr/bin/python3"


def ensure_python():
    """Make sure numpy and matplotlib can be imported: with this Python, or
    by re-executing the calling script with /usr/bin/python3 if that one
    has them; else stop with what to install. (No virtual environment is
    created.)"""
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
        return
    except ImportError:
        pass
    check = [SYSTEM_PYTHON, "-c", "import matplotlib, numpy"]
    if (not os.environ.get("BENCHLIB_REEXECUTED") and os.path.exists(SYSTEM_PYTHON)
            and os.path.realpath(SYSTEM_PYTHON) != os.path.realpath(sys.executable)
            and subprocess.run(check, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL).returncode == 0):
        os.environ["BENCHLIB_REEXECUTED"] = "1"
        os.execv(SYSTEM_PYTHON, [SYSTEM_PYTHON] + sys.argv)
    sys.exit("%s needs numpy and matplotlib (%s lacks them): apt-get install python3-numpy "
             "python3-matplotlib, or pip install -r requirements.txt"
             % (os.path.basename(sys.argv[0]), sys.executable))


def executable():
    """$DYNAMIC_CONTACT, else build/dynamic-contact (built with scripts/build
    if missing)."""
    exe = os.environ.get("DYNAMIC_CONTACT")
    if exe:
        if not os.path.exists(exe):
            sys.exit("no executable %s ($DYNAMIC_CONTACT)" % exe)
        return os.path.abspath(exe)
    exe = os.path.join(ROOT, "build", "dynamic-contact")
    if not os.path.exists(exe):
        print("== building %s (scripts/build)" % exe, flush=True)
        subprocess.run([os.path.join(ROOT, "scripts", "build")], check=True)
    return exe


# A run that is measured, not watched: no progress lines, no timings.
QUIET = ["Output/Progress every=0", "Output/Print timings=false"]
# No VTU and no contact CSV files: time_series.csv only.
NO_OUTPUT_FILES = ["Output/Write VTU=false", "Output/Output every=0", "Output/Output times="]


def output_times_entry(times):
    return ", ".join("%.10g" % (t - OUTPUT_TIME_SHIFT) for t in times)


def comparison_overrides(times):
    """Every output off except the VTU (and, unavoidably, the contact CSV) at
    the comparison times (and at the initial and the last step)."""
    return ["Output/Output every=0",
            "Output/Write VTU=true",
            "Output/VTU every=0",
            "Output/Output times=" + output_times_entry(times)] + QUIET


def program_command(exe, prm, overrides, ranks=1, extra=(), mpirun=None):
    """The command line of one run: `exe prm --set o ...` (under mpirun with
    `ranks` > 1 processes, or with any number if `mpirun` is True)."""
    command = [exe, prm] + list(extra)
    for o in overrides:
        command += ["--set", o]
    if ranks > 1 if mpirun is None else mpirun:
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + command
    return command


def print_parameters(exe, prm, overrides):
    """Runs `exe prm --print-parameters` with `overrides`: (the completed
    process, with its output as text; what it prints as a dict
    'Section/Name' -> value, None if it failed)."""
    result = subprocess.run(program_command(exe, prm, overrides, extra=["--print-parameters"]),
                            env=_program_environment(), stdout=subprocess.PIPE,
                            stderr=subprocess.STDOUT, text=True)
    if result.returncode != 0:
        return result, None
    values, sections = {}, []
    for line in result.stdout.splitlines():
        line = line.split("#", 1)[0].strip()
        if line.startswith("subsection "):
            sections.append(line[len("subsection "):].strip())
        elif line == "end":
            sections.pop()
        elif line.startswith("set ") and "=" in line:
            name, value = line[4:].split("=", 1)
            values["/".join(sections + [name.strip()])] = value.strip()
    return result, values


def effective_parameters(exe, prm, overrides):
    """The parameters a run of `prm` with `overrides` uses, as the program
    prints them (--print-parameters): a dict 'Section/Name' -> value."""
    result, values = print_parameters(exe, prm, overrides)
    if values is None:
        sys.exit("%s --print-parameters failed:\n%s" % (prm, result.stdout[-2000:]))
    return values


def _program_environment():
    return dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                OMP_NUM_THREADS="1")


def run_scene(exe, prm, overrides, directory, log=None, ranks=1, mpirun=None):
    """One run of the program (on `ranks` MPI processes, the whole command
    timed) into `directory` (emptied first). Returns (wall time in s, return
    code, tail of the output, command); the CPU time (user + system) of the
    processes is in run_scene.last_cpu_time."""
    if os.path.exists(directory):
        shutil.rmtree(directory)
    command = program_command(exe, prm, ["Output/Directory=" + directory] + list(overrides),
                              ranks, mpirun=mpirun)
    env = _program_environment()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    result = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    run_scene.last_cpu_time = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if log:
        with open(log, "w") as f:
            f.write("$ " + " ".join("'%s'" % c if " " in c else c for c in command) + "\n")
            f.write(result.stdout)
            f.write("\n[exit code %d, wall time %.3f s]\n" % (result.returncode, wall))
    return wall, result.returncode, result.stdout[-3000:], command


run_scene.last_cpu_time = None


def run_measured(exe, prm, overrides, directory, ranks=1, who="benchmark", mpirun=None):
    """One quiet run of `prm` (a path) without output files but
    time_series.csv; exits naming `who` if it fails. Returns (wall time in
    s, the rows of time_series.csv after the initial state)."""
    wall, code, tail, command = run_scene(exe, prm, NO_OUTPUT_FILES + QUIET + list(overrides),
                                          directory, ranks=ranks, mpirun=mpirun)
    if code != 0:
        sys.exit("%s: run failed:\n  %s\n%s" % (who, " ".join(command), tail))
    return wall, read_time_series(directory)[1:]


# Columns whose agreement says two runs gave the same answers.
ANSWER_COLUMNS = ["normal_force", "tangential_force", "total_energy", "dissipation",
                  "friction_dissipation"]


def answer_difference(rows, reference):
    """Largest difference over ANSWER_COLUMNS and steps, relative to the
    column's largest value in `reference`; None if the steps differ."""
    if len(rows) != len(reference):
        return None
    worst = 0.0
    for column in ANSWER_COLUMNS:
        if column not in rows[0] or column not in reference[0]:
            continue
        a = [float(r[column]) for r in rows]
        b = [float(r[column]) for r in reference]
        scale = max(abs(x) for x in b) or 1.0
        worst = max(worst, max(abs(x - y) for x, y in zip(a, b)) / scale)
    return worst


def stress_quick_overrides():
    """prm/stress/quick.txt: scene -> list of overrides (the quick mode of
    the stress suite: smaller meshes, the same physics)."""
    result = {}
    with open(os.path.join(ROOT, "prm", "stress", "quick.txt")) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line:
                fields = [x.strip() for x in line.split("|")]
                result[fields[0]] = [x for x in fields[1:] if x]
    return result


def run_status(directory):
    try:
        with open(os.path.join(directory, "run_status")) as f:
            return f.read().strip()
    except OSError:
        return None


def read_time_series(directory):
    with open(os.path.join(directory, "time_series.csv")) as f:
        return list(csv.DictReader(f))


def mean_dofs(steps):
    """Mean of the dofs column over the rows of the steps (time_series.csv
    without row 0, the initial state), and their number."""
    return statistics.mean(int(r["dofs"]) for r in steps), len(steps)


def rail_mesh(n):
    """Geometry entries of the rail on 10n x n x n cells, made as large
    deal.II meshes are: the coarsest box that refines globally to it. Every
    process of a distributed mesh holds the whole coarse mesh; 320 x 32 x
    32 coarse cells cost each of 16 processes 250 MB (doc/running.md,
    "Large runs")."""
    refinements = 0
    while n % 2 == 0:
        n //= 2
        refinements += 1
    return ["Geometry/Repetitions=%d, %d, %d" % (10 * n, n, n),
            "Geometry/Global refinements=%d" % refinements]


def uniform_overrides(n, k, degree=1, scheme="backward Euler"):
    """The paper's scene on a uniform n x n mesh with time step k: how every
    run compared with the reference (and the reference itself) is set up."""
    return ["Geometry/Repetitions=%d, %d" % (n, n),
            "Time/Time step=%.17g" % k,
            "Finite element/Polynomial degree=%d" % degree,
            "Time/Scheme=" + scheme]


def reference_overrides(times=COMMON_TIMES):
    n = REFERENCE_N
    return uniform_overrides(n, 1.0 / n) + comparison_overrides(times)


def ensure_reference(exe, directory=REFERENCE_DIR, times=COMMON_TIMES):
    """The reference run (uniform Q1 128 x 128, k = 1/128, backward Euler,
    VTU at the comparison times), made once and kept in `directory`: it is
    run again only if its run_status is not 'completed'. Returns a dict with
    its wall time (of the run that made it) and its directory."""
    info_path = os.path.join(directory, "benchmark_reference.json")
    if run_status(directory) == "completed":
        info = {}
        if os.path.exists(info_path):
            with open(info_path) as f:
                info = json.load(f)
        info["reused"] = True
        info["directory"] = directory
        stamp = _executable_stamp(exe)
        if info.get("executable_stamp") not in (None, stamp):
            print("   warning: the reference was made by another executable (%s, %s), not by %s "
                  "(%s); delete %s to redo it" % (info.get("executable"), info.get("executable_stamp"),
                                                  exe, stamp, directory), flush=True)
        print("== reference %s: run_status 'completed', reused (wall time of the run: %s s)"
              % (os.path.relpath(directory, ROOT), info.get("wall_time", "unknown")), flush=True)
        return info
    print("== reference: uniform Q1 %d x %d, k = 1/%d, into %s"
          % (REFERENCE_N, REFERENCE_N, REFERENCE_N, os.path.relpath(directory, ROOT)), flush=True)
    log = directory + ".log"
    os.makedirs(os.path.dirname(directory), exist_ok=True)
    wall, code, tail, command = run_scene(exe, PAPER_PRM, reference_overrides(times), directory, log)
    if code != 0 or run_status(directory) != "completed":
        sys.exit("reference run failed (exit code %d, log %s):\n%s" % (code, log, tail))
    dofs, steps = mean_dofs(read_time_series(directory)[1:])
    info = {"wall_time": round(wall, 3), "cpu_time": round(run_scene.last_cpu_time, 3),
            "load_1min_after": round(os.getloadavg()[0], 2), "date": time.strftime("%Y-%m-%d %H:%M:%S"),
            "machine": machine_line(), "executable": exe,
            "executable_stamp": _executable_stamp(exe), "command": command,
            "dofs": dofs, "steps": steps}
    with open(info_path, "w") as f:
        json.dump(info, f, indent=1)
    print("   done in %.1f s" % wall, flush=True)
    info["reused"] = False
    info["directory"] = directory
    return info


def _executable_stamp(exe):
    """Size and modification time of the executable: tells a rebuilt one."""
    st = os.stat(exe)
    return "%d bytes, modified %s" % (st.st_size, time.strftime("%Y-%m-%d %H:%M:%S",
                                                                time.localtime(st.st_mtime)))


def cpu_model():
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.lower().startswith("model name"):
                    return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine()


def machine_line():
    return "%s, %s, %d cores, %s" % (time.strftime("%Y-%m-%d"), cpu_model(), os.cpu_count(),
                                     " ".join(platform.uname()[0:3]))


# A row of the program's memory table (the end of log.txt, and of the screen
# with Output/Print timings): "    NAME  MB_ALL  MB_LARGEST  BYTES_PER_DOF".
_MEMORY_ROW = re.compile(r"^    (.+?)\s+([0-9.]+)\s+([0-9.]+)\s+([0-9]+)(  \(measured\))?$")


def memory_table(text):
    """The last memory table in a run's output or log.txt: (DoFs, rows),
    each row (name, MB in all, MB on the largest process, bytes per DoF,
    measured); (None, []) if there is none."""
    start = text.rfind("  memory (")
    if start < 0:
        return None, []
    lines = text[start:].splitlines()
    dofs = int(re.search(r"\((\d+) DoFs", lines[0]).group(1))
    rows = []
    for line in lines[1:]:
        m = _MEMORY_ROW.match(line)
        if not m:
            break
        rows.append((m.group(1).strip(), float(m.group(2)), float(m.group(3)),
                     int(m.group(4)), bool(m.group(5))))
    return dofs, rows


# Reading the header of a results file (benchmarks/performance-page,
# benchmarks/doc-tables): when and where it was measured.

DATE = re.compile(r"\b(\d{4}-\d{2}-\d{2})\b")
# machine_line(): "DATE, CPU, N cores, SYSTEM"
# (SYSTEM: platform.uname()'s system, node and release).
MACHINE_LINE = re.compile(r"\d{4}-\d{2}-\d{2}, ([^,;()]+?), (\d+) cores"
                          r"(?:, ([A-Za-z]+ [^\s,;()]+ [^\s,;()]+))?")
MACHINE_BEFORE_DATE = re.compile(r"\bon ([A-Z][^,;]+), \d{4}-\d{2}-\d{2}")


def read_lines(path):
    with open(path, encoding="utf-8") as f:
        return f.read().splitlines()


def results_header(name, lines):
    """The lines of a results file that say when and where it was measured:
    the leading comment lines (without '# '), else the first paragraph of a
    report (up to 4 lines)."""
    comments = []
    for line in lines:
        if not line.startswith("#"):
            break
        comments.append(line.lstrip("#").strip())
    if comments:
        return comments
    if name.endswith(".txt"):
        paragraph = []
        for line in lines:
            if not line.strip():
                if paragraph:
                    break
                continue
            paragraph.append(line.strip())
            if len(paragraph) == 4:
                break
        return paragraph
    return []


def date_and_machine(header):
    """(date, machine) from the header lines; None where it says none."""
    text = " ".join(header)
    date = DATE.search(text)
    # One line first (a system name must not run into the next line), then
    # the lines together (a date at the end of one, the machine on the next).
    machine = None
    for line in header + [text]:
        machine = MACHINE_LINE.search(line)
        if machine:
            break
    if machine:
        machine = ", ".join(part.strip() for part in
                            (machine.group(1), machine.group(2) + " cores",
                             machine.group(3)) if part and part.strip())
    else:
        before = MACHINE_BEFORE_DATE.search(text)
        machine = before.group(1).strip() if before else None
    return (date.group(1) if date else None), machine
