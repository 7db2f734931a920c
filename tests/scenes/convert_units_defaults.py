"""Checks 5 and 6 of the test convert_units (tests/scenes/convert_units.py):
the defaults a scene leaves out, which scripts/convert-units writes
converted (the expected texts of a minimal and a partial scene, which run
alike in SI and mm-t-s), and the converter's table of defaults against
what the program prints (--print-parameters=json). Standard library only.
"""

import csv
import json
import os
import subprocess

from convert_units_common import (FUNCTIONS, close, number_list,
                                  unstated_defaults)
from script_checks import check, write


# ----------------------------------------------------------------- 5.
# A scene that sets next to nothing: it runs with the program's defaults,
# numbers of SI, which the mm-t-s scene must state converted.
MINIMAL = """set Dimension = 2
subsection Friction
  set Law = exponential
end
subsection Initial conditions
  subsection Velocity
    set Function expression = 1; -0.1
  end
end
"""

COMMENT = "  # default of the program (SI), converted"


def reindented(text, unit):
    """@p text, indented by two spaces a level, with @p unit a level."""
    lines = []
    for line in text.splitlines(True):
        body = line.lstrip(" ")
        lines.append(unit * ((len(line) - len(body)) // 2) + body)
    return "".join(lines)


def mm_scene(template, stiffness, unit):
    """The mm-t-s scene @p template (two spaces a level) with the converted
    defaults that both scenes below gain (%(material)s, %(exponential)s,
    %(foundation)s, the latter with the compliance's @p stiffness), each
    with COMMENT; indented with @p unit a level."""
    defaults = """  set Density = 1e-09%(c)s
  set Young modulus = 100000%(c)s""" % {"c": COMMENT}
    exponential = """  subsection Exponential
    set Decay rate = 2%(c)s
  end""" % {"c": COMMENT}
    foundation = """subsection Foundation
  subsection Normal compliance
    subsection Capped ramp
      set Stiffness = %(stiffness)s
      set Cap = 100000000000%(c)s
    end
  end
  subsection Normal damping
    subsection Capped ramp
      set Coefficient = 0.1%(c)s
      set Cap = 100000000000%(c)s
    end
  end
end""" % {"c": COMMENT, "stiffness": stiffness}
    return reindented(template % {"c": COMMENT, "material": defaults,
                                  "exponential": exponential,
                                  "foundation": foundation}, unit)


MINIMAL_MM = mm_scene("""set Dimension = 2
subsection Friction
  set Law = exponential
%(exponential)s
end
subsection Initial conditions
  subsection Velocity
    set Function expression = 1000; -100
  end
end

%(foundation)s
subsection Geometry
  set Upper right = 2000, 100%(c)s
end
subsection Material
%(material)s
end
""", "5" + COMMENT, "  ")

# Entries into the subsections the file has (before their 'end'), at
# their depth; in 3D.
PARTIAL = """set Dimension = 3
subsection Boundary conditions
    set Roller = 4, 5
end
subsection Material
    set Poisson ratio = 0.25
end
subsection Foundation
    subsection Normal compliance
        subsection Capped ramp
            set Stiffness = 1e10
        end
    end
end
subsection Time
    set End time = 0.5
end
"""

# The converted scene keeps PARTIAL's four spaces a level.
PARTIAL_MM = mm_scene("""set Dimension = 3
subsection Boundary conditions
  set Roller = 4, 5
end
subsection Material
  set Poisson ratio = 0.25
%(material)s
end
%(foundation)s
subsection Time
  set End time = 0.5
end

subsection Friction
%(exponential)s
end
subsection Geometry
  set Upper right = 2000, 100, 100%(c)s
end
""", "10", "    ")


def run_steps(program, path, output, steps=3):
    """Runs the scene @p path for @p steps steps of its Time step (the
    default) into @p output; the run's time series and contact files."""
    r = subprocess.run([program, "--set", "Time/End time=%r" %
                        (steps * 0.0078125), "--set", "Output/Directory=" +
                        output, "--set", "Output/Write VTU=false", path],
                       capture_output=True, text=True,
                       cwd=os.path.dirname(path))
    if r.returncode != 0:
        return None
    with open(os.path.join(output, "time_series.csv")) as f:
        series = list(csv.DictReader(f))
    contact = []
    for n in range(steps + 1):
        with open(os.path.join(output, "contact_%05d.csv" % n)) as f:
            contact.append(list(csv.DictReader(f)))
    return series, contact


def convert_written(converter, directory):
    """The minimal and the partial scene converted into mm-t-s, each
    against the exact text expected; returns (path, converted path,
    converted text) by name for those converted."""
    header = "# Units: mm-t-s (length mm, mass t, time s; force N, stress " \
        "MPa); converted from SI by scripts/convert-units (from %s).\n"
    results = {}
    for name, text, expected in (("minimal", MINIMAL, MINIMAL_MM),
                                 ("partial", PARTIAL, PARTIAL_MM)):
        path = os.path.join(directory, name + ".prm")
        out = os.path.join(directory, name + "_mm.prm")
        write(path, text)
        try:
            converter.convert("SI", "mm-t-s", path, out)
        except RuntimeError as e:
            check(False, "%s scene: converted (%s)" % (name, e))
            continue
        with open(out) as f:
            results[name] = (path, out, f.read())
        got = results[name][2]
        want = header % (name + ".prm") + expected
        check(got == want, "%s scene: the defaults it leaves out are "
              "written in mm-t-s, each with the comment '%s': into the "
              "subsection the file has, before its 'end' (at its "
              "indentation), else in a new block at the end%s"
              % (name, COMMENT.strip(), "" if got == want else
                 "; got:\n" + got))
    return results


def check_minimal_mm(converter, read_prm, directory, minimal):
    """The minimal scene in mm-t-s (@p minimal: its paths) read back, and
    back to SI the numbers of the program's defaults again."""
    mm = read_prm(minimal[1])
    check(mm.get("Material/Density") == "1e-09" and
          mm.get("Material/Young modulus") == "100000" and
          mm.get("Foundation/Normal compliance/Capped ramp/Stiffness")
          == "5" and
          mm.get("Friction/Exponential/Decay rate") == "2" and
          mm.get("Geometry/Upper right") == "2000, 100" and
          "Time/Time step" not in mm and "Time/End time" not in mm and
          "Geometry/Lower left" not in mm,
          "the minimal scene in mm-t-s: Density 1e-9 t/mm^3, Young "
          "modulus 1e5 MPa, Stiffness 5e9 Pa/m = 5 N/mm^3, Decay rate "
          "2 s/mm, Upper right 2000, 100 mm; the times (factor 1) and "
          "the lower left corner (0) are not written")
    # Back to SI: the numbers of the program's defaults again.
    back = os.path.join(directory, "minimal_si.prm")
    try:
        converter.convert("mm-t-s", "SI", minimal[1], back)
        entries = read_prm(back)
        module = converter.module
        wrong = [key for key, text in unstated_defaults(
                     module, read_prm(minimal[0])).items()
                 if key in mm and not all(close(p, q) for p, q in zip(
                     number_list(entries[key]), number_list(text)))]
        check(not wrong, "the minimal scene back in SI states the "
              "program's defaults (to 1e-12)%s"
              % ("" if not wrong else ": " + ", ".join(wrong)))
    except RuntimeError as e:
        check(False, "the minimal scene back to SI (%s)" % e)


def check_mm_scene_to_si(converter, read_prm, directory):
    """A scene in mm-t-s without a density ran with 1000 t/mm^3."""
    path = os.path.join(directory, "mm_scene.prm")
    write(path, "subsection Geometry\n  set Type = gmsh\n  set Mesh file = "
          + os.path.join(os.path.dirname(converter.script), "..", "prm",
                         "gmsh_rail.msh") + "\nend\n")
    r = converter.run("--from", "mm-t-s", "--to", "SI", path, "-o",
                      os.path.join(directory, "mm_scene_si.prm"))
    entries = read_prm(os.path.join(directory, "mm_scene_si.prm")) \
        if r.returncode == 0 else {}
    check(entries.get("Material/Density") == "1000000000000000" and
          entries.get("Material/Young modulus") == "1e+17" and
          "Geometry/Upper right" not in entries,
          "a scene in mm-t-s without Density ran with 1000 t/mm^3: in SI "
          "1e15 kg/m^3, E 1e11 MPa = 1e17 Pa; no corners for Type = gmsh")


def check_written_validate(program, directory, results):
    """The scenes and their conversions pass dynamic-contact --validate."""
    failed = []
    for name, (path, out, _) in sorted(results.items()):
        for scene in (path, out):
            r = subprocess.run([program, "--validate", scene],
                               capture_output=True, text=True,
                               cwd=directory)
            if r.returncode != 0:
                failed.append("%s: %s" % (os.path.basename(scene),
                                          (r.stdout + r.stderr).strip()
                                          .splitlines()[-1:]))
    check(not failed, "the scenes with their defaults written pass "
          "dynamic-contact --validate%s"
          % ("" if not failed else ": " + "; ".join(failed)))


def check_runs_alike(program, directory, minimal):
    """The minimal scene runs three steps identically in SI and in
    mm-t-s (@p minimal: its paths)."""
    path, out, _ = minimal
    si = run_steps(program, path, os.path.join(directory, "run_si"))
    mm = run_steps(program, out, os.path.join(directory, "run_mm"))
    if si is None or mm is None:
        check(False, "the minimal scene runs three steps in SI and in "
              "mm-t-s")
        return
    counts = ("time", "cutbacks", "newton_iterations",
              "convexification_iterations", "n_contact", "n_stick", "n_slip",
              "dofs", "cells")
    same = len(si[0]) == len(mm[0]) and all(
        p[k] == q[k] for p, q in zip(si[0], mm[0]) for k in counts)
    scale = max(abs(float(p[k])) for step in si[1] for p in step
                for k in ("u_x", "u_y")) or 1.0
    for s_step, m_step in zip(si[1], mm[1]):
        same = same and len(s_step) == len(m_step) and all(
            p["state"] == q["state"] and
            close(float(p["mu"]), float(q["mu"]), 1e-9, 1.0) and
            all(close(1000 * float(p[k]), float(q[k]), 1e-9, 1000 * scale)
                for k in ("x", "u_x", "u_y"))
            for p, q in zip(s_step, m_step))
    check(same, "the minimal scene runs identically in SI and in mm-t-s "
          "(three steps: the same iterations, contact states and mu, the "
          "displacements 1000 times in mm, to 1e-9)")


def check_defaults_written(converter, read_prm, work, program):
    """The defaults a scene leaves out are written, converted, into the
    mm-t-s scene, where a reader finds them; the scene runs as before."""
    directory = os.path.join(work, "defaults")
    os.makedirs(directory, exist_ok=True)
    results = convert_written(converter, directory)
    if "minimal" in results:
        check_minimal_mm(converter, read_prm, directory, results["minimal"])
    check_mm_scene_to_si(converter, read_prm, directory)
    if not program or "minimal" not in results:
        return
    check_written_validate(program, directory, results)
    check_runs_alike(program, directory, results["minimal"])


def program_entries(program, dimension, directory):
    """{entry: (value, default)} that the program prints for a scene of
    @p dimension that sets nothing else."""
    path = os.path.join(directory, "dimension_%d.prm" % dimension)
    write(path, "set Dimension = %d\n" % dimension)
    r = subprocess.run([program, "--print-parameters=json", path],
                       capture_output=True, text=True, cwd=directory)
    if r.returncode != 0:
        return None
    out = {}

    def walk(node, prefix):
        for name, value in node.items():
            if isinstance(value, dict) and "default_value" in value:
                out[prefix + name] = value["default_value"]
            elif isinstance(value, dict):
                walk(value, prefix + name + "/")
    walk(json.loads(r.stdout), "")
    return out


def same_value(a, b):
    if a is None or b is None:
        return a is b
    if a.strip() == b.strip():
        return True
    u, v = number_list(a), number_list(b)
    return u is not None and u == v


def check_defaults(converter, program, work):
    """The converter's table of defaults (what it writes where a scene
    leaves an entry out) is what the program prints, in 2D and 3D."""
    module = converter.module
    directory = os.path.join(work, "program_defaults")
    os.makedirs(directory, exist_ok=True)
    numbers = {key for key, (kind, _) in module.TABLE.items()
               if kind in (module.NUMBER, module.LIST)}
    check(set(module.DEFAULTS) == numbers, "the converter's table of "
          "defaults has every number and list of a dimension%s"
          % "".join("; %s %s" % (what, ", ".join(sorted(keys)))
                    for what, keys in (
                        ("missing:", numbers - set(module.DEFAULTS)),
                        ("not a number of a dimension:",
                         set(module.DEFAULTS) - numbers)) if keys))
    for dimension in (2, 3):
        printed = program_entries(program, dimension, directory)
        if printed is None:
            check(False, "%dD: dynamic-contact --print-parameters=json"
                  % dimension)
            continue
        wrong = []
        for key in sorted(module.DEFAULTS):
            ours = module.default_of(key, dimension)
            if not same_value(ours, printed.get(key)):
                wrong.append("%s: the program's %r, the table's %r"
                             % (key, printed.get(key), ours))
        # The functions of a dimension: 0 by default (nothing to write).
        for subsection in FUNCTIONS:
            text = printed.get(subsection + "/Function expression")
            if text is None or any(
                    c.strip() and number_list(c) != [0.0]
                    for c in text.split(";")):
                wrong.append("%s/Function expression: the program's %r, "
                             "not 0" % (subsection, text))
        check(not wrong, "%dD: the converter's table of defaults is what "
              "dynamic-contact --print-parameters prints (and the "
              "functions of a dimension are 0 by default)%s"
              % (dimension, "" if not wrong else ": " + "; ".join(wrong)))
