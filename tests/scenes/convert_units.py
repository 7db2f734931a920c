#!/usr/bin/python3
"""The test `convert_units`: scripts/convert-units converts scenes between
the unit systems SI, mm-t-s and in-lbf-s exactly.

    convert_units.py --work-dir DIR [--source-dir REPO] [--program EXE]

1. Every prm/*.prm and prm/stress/*.prm (and the rail on its MSH 2.2
   mesh, and the scene of 2.) goes SI -> mm-t-s -> in-lbf-s -> SI and
   comes back to itself in the values a run uses (the program's defaults
   filled in where a file leaves an entry out, since the conversion
   writes them out): numbers to 1e-12 (relative), the functions
   evaluated at a few points to 1e-12 and textually the same (the unit
   constants taken out again; components that are numbers to 1e-12), the
   mesh file's node coordinates to 1e-12. On the way, the mm-t-s scene
   states exactly the defaults of a dimension that the scene leaves out
   and that are not 0 (nor converted with a factor of 1), converted
   exactly; its functions at the points scaled to mm equal the SI ones
   times their factor (1e-12), and its mesh nodes are 1000 times the SI
   ones (correctly rounded). With --program, every converted scene passes
   `dynamic-contact --validate`.
2. Known values, computed here from the definitions (inch = 0.0254 m, lbf =
   4.4482216152605 N) in exact arithmetic: E = 2.1e11 Pa is 2.1e5 MPa and
   30457924.92... psi, the density 7850 kg/m^3 is 7.85e-9 t/mm^3, and one
   entry of every other dimension; the friction law mu(s) of the slip rate.
   'auto' stays in Friction/Maximum slip rate and the Windows of Mesh
   refinement (also in a test-overrides line), 0 (automatic) stays 0 in
   Time/Minimum and Maximum time step and Friction/Complementarity
   constant (with --program: the scenes pass --validate).
3. Errors: an unknown entry or subsection, a number that does not parse
   ('auto' in another entry too), an include line, an old-layout entry, an
   unclosed subsection, Variable names that do not fit the dimension are
   refused with exit code 1 and one message naming the file, the line and
   the entry, and nothing is written; so are an unknown unit system and
   -o IN.prm.
4. The converter's table (--print-table) has exactly the entries of
   doc/parameters.md, and where the documentation gives a unit in an
   entry's text, the table's dimension is that unit (but for the known
   disagreement below); a number of a dimension has its unit in the text.
5. The defaults a scene leaves out: a minimal 2D scene (an exponential
   friction law, an initial velocity) in mm-t-s gets, each with the
   comment '# default of the program (SI), converted', Density 1e-9,
   Young modulus 1e5, Stiffness 5 N/mm^3, the caps, the damping, Decay
   rate 2 s/mm and Upper right 2000, 100 (not the times: factor 1; not
   Lower left: 0), as the exact text expected, in new blocks at the end;
   a 3D scene that has some of the subsections gets them there, before
   their 'end', at their indentation; back to SI they are the defaults
   again; a scene in mm-t-s converted to SI states the defaults as it ran
   them (Density 1000 t/mm^3 = 1e15 kg/m^3), and no corners for a gmsh
   mesh. With --program: these scenes pass --validate, and the minimal
   scene runs three steps identically in SI and in mm-t-s (iterations,
   contact states, mu; displacements times 1000).
6. With --program: the converter's table of defaults (DEFAULTS) has every
   number and list of a dimension of its table, and is what
   `dynamic-contact --print-parameters=json` prints in 2D and in 3D; the
   functions of a dimension are 0 by default.

Standard library only. Prints one line per check; exit code 1 if one fails.
"""

import math
import os
import re
import subprocess
from fractions import Fraction

from convert_units_common import (FUNCTIONS, INCH, LBF, Converter,
                                  Expression, close, constants_of,
                                  differences, evaluate, exact, factor,
                                  load_prm_reader, mesh_nodes, number_list,
                                  points, unstated_defaults, variables_of,
                                  with_defaults)
from convert_units_defaults import check_defaults, check_defaults_written
from script_checks import check, finish, write

# The units of doc/parameters.md's texts: (L, M, T) of each symbol.
SYMBOLS = {"m": (1, 0, 0), "kg": (0, 1, 0), "s": (0, 0, 1),
           "N": (1, 1, -2), "Pa": (-1, 1, -2)}
UNIT_RE = re.compile(r"(?:Pa|N|kg|m|s)(?:\^-?\d+)?"
                     r"(?:(?: |/)(?:Pa|N|kg|m|s)(?:\^-?\d+)?)*")


def doc_unit(text):
    """The dimension of the first unit in parentheses in an entry's text
    of doc/parameters.md ("(Pa)", "(kg/m^3)", "(Pa s/m), >= 0", "(Pa s/m^2
    ... scaled like E/h)"; not the argument of "mu(s)"), None if none."""
    for group in re.findall(r"(?<![A-Za-z0-9_])\(([^()]*)\)", text):
        m = UNIT_RE.match(group)
        if not m or not re.match(r"\s*($|,|;|\.\.\.)", group[m.end():]):
            continue
        dimension = [0, 0, 0]
        sign = 1
        for separator, symbol, power in re.findall(
                r"(^|[ /])(Pa|N|kg|m|s)(?:\^(-?\d+))?", m.group()):
            if separator == "/":
                sign = -1
            for i in range(3):
                dimension[i] += sign * int(power or 1) * SYMBOLS[symbol][i]
        return tuple(dimension)
    return None


# Where the documentation's text and the converter may disagree on
# purpose (none), and entries whose texts give no unit (none).
DOC_DISAGREEMENTS = set()
DOC_WITHOUT_UNIT = set()

# ----------------------------------------------------------------- 1.
def convert_chain(converter, directory, name, relative, original):
    """@p original converted SI -> mm-t-s -> in-lbf-s -> SI into
    @p directory: the (system, path) of each, the original first; None
    if a conversion failed."""
    chain = [("SI", original)]
    try:
        for system, tag in (("mm-t-s", "mm"), ("in-lbf-s", "in"),
                            ("SI", "si")):
            out = os.path.join(directory, "%s_%s.prm" % (name, tag))
            converter.convert(chain[-1][0], system, chain[-1][1], out)
            chain.append((system, out))
    except RuntimeError as e:
        check(False, "%s: converts SI -> mm-t-s -> in-lbf-s -> SI (%s)"
              % (relative, e))
        return None
    check(True, "%s: converts SI -> mm-t-s -> in-lbf-s -> SI" % relative)
    return chain


def check_stated_defaults(module, relative, a, mm):
    """The defaults the scene leaves out: stated in mm-t-s, converted."""
    expected = {}
    for key, text in unstated_defaults(module, a).items():
        f = factor("SI", "mm-t-s", module.TABLE[key][1])
        if f != 1:
            expected[key] = [exact(v, f) for v in number_list(text)]
    stated = {key: number_list(mm[key]) for key in mm
              if key not in a and key in module.DEFAULTS}
    check(stated == expected, "%s: the mm-t-s scene states the defaults "
          "the scene leaves out (not 0, a factor other than 1), converted "
          "exactly: %s" % (relative, ", ".join(
              "%s = %s" % (key.split("/", 1)[-1], mm.get(key))
              for key in sorted(set(stated) | set(expected))) or "none"))


def check_functions(relative, a, mm, back, dimension):
    """The functions: evaluated, round trip and mm-t-s."""
    problems = []
    for subsection, dimension_of_value in FUNCTIONS.items():
        key = subsection + "/Function expression"
        if not a.get(key, "").strip():
            continue
        constants_key = subsection + "/Function constants"
        variables = variables_of(a, subsection, dimension)
        f = float(factor("SI", "mm-t-s", dimension_of_value))
        for p, q in zip(points(dimension), points(dimension, "mm-t-s")):
            reference = evaluate(a[key], a.get(constants_key, ""), variables,
                                 p)
            scale = max(abs(r) for r in reference)
            again = evaluate(back[key], back.get(constants_key, ""),
                             variables_of(back, subsection, dimension), p)
            in_mm = evaluate(mm[key], mm.get(constants_key, ""),
                             variables_of(mm, subsection, dimension), q)
            if not all(close(r, s, scale=scale)
                       for r, s in zip(reference, again)):
                problems.append("%s round trip at %s" % (subsection, p))
            if not all(close(r * f, s, scale=scale * f)
                       for r, s in zip(reference, in_mm)):
                problems.append("%s in mm-t-s at %s" % (subsection, q))
    check(not problems, "%s: the functions evaluated: the same after the "
          "round trip, and in mm-t-s at the points in mm the SI values "
          "times their factor (1e-12)%s"
          % (relative, "" if not problems else ": " + "; ".join(problems)))


def mesh_of(prm_path, entries):
    """The nodes of the Gmsh mesh the scene @p prm_path names."""
    return mesh_nodes(os.path.join(os.path.dirname(prm_path),
                                   entries["Geometry/Mesh file"]))


def check_mesh_copies(relative, directory, name, chain, entries):
    """A Gmsh scene: the mm-t-s mesh copy beside its scene, its nodes
    scaled, the round trip's nodes back. @p entries: the scenes of
    @p chain read (SI, mm-t-s, back to SI)."""
    a, mm, back = entries
    nodes = mesh_of(chain[0][1], a)
    nodes_mm = mesh_of(chain[1][1], mm)
    nodes_back = mesh_of(chain[3][1], back)
    check(os.path.dirname(os.path.join(
        directory, mm["Geometry/Mesh file"])) == directory and
        mm["Geometry/Mesh file"] == name + "_mm.msh",
        "%s: the mm-t-s scene names its mesh copy next to it" % relative)
    check(nodes_mm == [exact(x, 1000) for x in nodes],
          "%s: the mm-t-s mesh's nodes are 1000 times the SI ones "
          "(correctly rounded)" % relative)
    check(len(nodes_back) == len(nodes) and
          all(close(x, y, scale=1e-3) for x, y in zip(nodes, nodes_back)),
          "%s: the mesh's nodes come back to 1e-12" % relative)


def check_validate(program, relative, directory, chain):
    """The converted scenes of @p chain pass dynamic-contact --validate."""
    failed = []
    for system, path in chain[1:]:
        r = subprocess.run([program, "--validate", path],
                           capture_output=True, text=True,
                           cwd=directory)
        if r.returncode != 0:
            failed.append("%s: %s" % (system, (r.stdout + r.stderr)
                                      .strip().splitlines()[-1:]))
    check(not failed, "%s: the converted scenes pass dynamic-contact "
          "--validate%s" % (relative, "" if not failed else
                            ": " + "; ".join(failed)))


def check_scene(converter, read_prm, work, relative, original, program):
    """The round trip of the scene @p original (named @p relative)."""
    name = re.sub(r"[^A-Za-z0-9_.-]+", "_",
                  os.path.splitext(relative)[0]).strip("_")
    directory = os.path.join(work, "round_trip", name)
    os.makedirs(directory, exist_ok=True)
    chain = convert_chain(converter, directory, name, relative, original)
    if chain is None:
        return
    a = read_prm(original)
    mm = read_prm(chain[1][1])
    back = read_prm(chain[3][1])
    dimension = int(a.get("Dimension", "2"))
    module = converter.module

    check_stated_defaults(module, relative, a, mm)

    # Back to itself: the values a run uses (the defaults filled in).
    problems = differences(with_defaults(module, a),
                           with_defaults(module, back))
    check(not problems, "%s: the round trip gives every value a run uses "
          "back (numbers to 1e-12, expressions and constants as they "
          "were, but for components that are numbers)%s"
          % (relative, "" if not problems else ": " + "; ".join(problems)))

    check_functions(relative, a, mm, back, dimension)
    if a.get("Geometry/Type") == "gmsh":
        check_mesh_copies(relative, directory, name, chain, (a, mm, back))
    if program:
        check_validate(program, relative, directory, chain)


# ----------------------------------------------------------------- 2.
KNOWN = """# test-overrides: Geometry/Upper right=4, 0.2 | Time/End time=0.1
set Dimension = 2
subsection Geometry
  set Lower left  = 0, -0.25
  set Upper right = 2, 0.1   # the rail
end
subsection Material
  set Density          = 7850
  set Young modulus    = 2.1e11
  set Viscosity mu     = 1e3
end
subsection Foundation
  subsection Normal compliance
    subsection Capped ramp
      set Stiffness = 5e9
      set Cap = 1e17
    end
  end
  subsection Normal damping
    subsection Capped ramp
      set Coefficient = 1e8
    end
  end
end
subsection Friction
  set Law = expression
  set Maximum slip rate = 100
  set Complementarity constant = 1e12
  subsection Exponential
    set Decay rate = 2000
  end
  subsection Expression
    set Function expression = 0.5 + 0.5*exp(-alpha*s)
    set Function constants = alpha=2000
  end
end
subsection Mesh refinement
  subsection Load following
    set Window = 0.2
    set Threshold = 0.05
  end
end
subsection Body force
  set Function expression = 0; -9810
end
subsection Time
  set End time = 0.8
  set Time step = 0.0078125
end
subsection Output
  set Output times = 0.2, 0.4
end
"""

# entry: (SI value, dimension)
KNOWN_VALUES = {
    "Material/Young modulus": (2.1e11, (-1, 1, -2)),
    "Material/Density": (7850, (-3, 1, 0)),
    "Material/Viscosity mu": (1e3, (-1, 1, -1)),
    "Foundation/Normal compliance/Capped ramp/Stiffness": (5e9, (-2, 1, -2)),
    "Foundation/Normal compliance/Capped ramp/Cap": (1e17, (-1, 1, -2)),
    "Foundation/Normal damping/Capped ramp/Coefficient": (1e8, (-2, 1, -1)),
    "Friction/Maximum slip rate": (100, (1, 0, -1)),
    "Friction/Complementarity constant": (1e12, (-2, 1, -2)),
    "Friction/Exponential/Decay rate": (2000, (-1, 0, 1)),
    "Mesh refinement/Load following/Window": (0.2, (1, 0, 0)),
    "Mesh refinement/Load following/Threshold": (0.05, (0, 0, 0)),
    "Time/End time": (0.8, (0, 0, 1)),
    "Time/Time step": (0.0078125, (0, 0, 1)),
}


def check_known_values(converter, read_prm, work):
    directory = os.path.join(work, "known")
    os.makedirs(directory, exist_ok=True)
    path = os.path.join(directory, "known.prm")
    write(path, KNOWN)
    converted = {}
    for system in ("mm-t-s", "in-lbf-s"):
        out = os.path.join(directory, "known_%s.prm" % system)
        converter.convert("SI", system, path, out)
        converted[system] = read_prm(out)
    mm, psi = converted["mm-t-s"], converted["in-lbf-s"]

    check(mm["Material/Young modulus"] == "210000",
          "E = 2.1e11 Pa is 210000 MPa")
    e_psi = Fraction(2.1e11) * INCH ** 2 / LBF
    check(float(psi["Material/Young modulus"]) == float(e_psi) and
          psi["Material/Young modulus"].startswith("30457924.92"),
          "E = 2.1e11 Pa is 30457924.92... psi (2.1e11 in^2/lbf, "
          "correctly rounded)")
    check(mm["Material/Density"] == "7.85e-09",
          "the density 7850 kg/m^3 is 7.85e-9 t/mm^3")
    rho_psi = Fraction(7850) * INCH ** 3 / (LBF / INCH)
    check(float(psi["Material/Density"]) == float(rho_psi),
          "the density in lbf s^2/in^4")
    wrong = []
    for system, entries in converted.items():
        for key, (value, dimension) in KNOWN_VALUES.items():
            expected = exact(value, factor("SI", system, dimension))
            if float(entries[key]) != expected:
                wrong.append("%s %s: %s, not %r"
                             % (system, key, entries[key], expected))
        for key in ("Geometry/Lower left", "Geometry/Upper right"):
            expected = [exact(float(v), factor("SI", system, (1, 0, 0)))
                        for v in read_prm(path)[key].split(",")]
            if number_list(entries[key]) != expected:
                wrong.append("%s %s" % (system, key))
    check(not wrong, "every dimension: the stiffness, caps, damping, "
          "viscosity, slip rate, c_t, decay rate, windows, lists of lengths "
          "converted exactly, the threshold and the times unchanged%s"
          % ("" if not wrong else ": " + "; ".join(wrong)))
    check(mm["Time/End time"] == "0.8" and
          mm["Output/Output times"] == "0.2, 0.4" and
          mm["Geometry/Lower left"] == "0, -250",
          "times keep their text (factor 1), 0 stays 0")
    check(mm["Body force/Function expression"] == "0; -9.81e-06",
          "a body force component that is a number: 9810 N/m^3 is "
          "9.81e-6 N/mm^3; 0 stays 0")
    with open(os.path.join(directory, "known_mm-t-s.prm")) as f:
        text = f.read()
    check(text.startswith("# Units: mm-t-s") and "  set Upper right = 2000,"
          " 100   # the rail\n" in text,
          "a first comment line names the units; comments and indentation "
          "stay")
    check("# test-overrides: Geometry/Upper right=4000, 200 | Time/End "
          "time=0.1\n" in text,
          "the values of a '# test-overrides:' line are converted")

    # mu(s): the slip rate in mm/s and in in/s.
    for system, entries in converted.items():
        v = float(factor("SI", system, (1, 0, -1)))
        mu = Expression(entries["Friction/Expression/Function expression"])
        names = constants_of(entries["Friction/Expression/Function constants"])
        ok = True
        for s in (0.0, 1e-4, 5e-4, 0.01):
            names["s"] = s * v
            ok = ok and close(mu(names), 0.5 + 0.5 * math.exp(-2000 * s))
        check(ok and "unit_velocity" in names,
              "friction law 'expression' in %s: mu(s * %.6g) is mu(s) of "
              "the SI scene" % (system, v))


# ------------------------------------------------------- 2. 'auto', 0
AUTO_SCENE = """# test-overrides: Friction/Maximum slip rate=auto
subsection Friction
  set Law = constant
  set Maximum slip rate = auto
  set Complementarity constant = 0
end
subsection Mesh refinement
  subsection Contact following
    set Window = auto
  end
  subsection Load following
    set Window = auto
  end
end
subsection Time
  set Minimum time step = 0
  set Maximum time step = 0
end
"""


def check_auto(converter, read_prm, work, program):
    """'auto' stays 'auto' where the program takes it; 0 (automatic)
    stays 0."""
    directory = os.path.join(work, "auto")
    os.makedirs(directory, exist_ok=True)
    path = os.path.join(directory, "auto.prm")
    write(path, AUTO_SCENE)
    original = read_prm(path)
    for system in ("mm-t-s", "in-lbf-s"):
        out = os.path.join(directory, "auto_%s.prm" % system)
        try:
            converter.convert("SI", system, path, out)
        except RuntimeError as e:
            check(False, "'auto' and 0 in %s: converted (%s)" % (system, e))
            continue
        entries = read_prm(out)
        with open(out) as f:
            text = f.read()
        check(all(entries[key] == original[key] for key in original) and
              "# test-overrides: Friction/Maximum slip rate=auto\n" in text,
              "%s: 'auto' stays in Friction/Maximum slip rate and the "
              "Windows of Contact and Load following (also in a "
              "test-overrides line), 0 in Time/Minimum and Maximum time "
              "step and Friction/Complementarity constant stays 0" % system)
        if program:
            r = subprocess.run([program, "--validate", out],
                               capture_output=True, text=True,
                               cwd=directory)
            last = (r.stdout + r.stderr).strip().splitlines()[-1:]
            check(r.returncode == 0, "%s: the scene with 'auto' passes "
                  "dynamic-contact --validate%s"
                  % (system, "" if r.returncode == 0 else ": %s" % last))


# ----------------------------------------------------------------- 3.
def check_errors(converter, work):
    directory = os.path.join(work, "errors")
    os.makedirs(directory, exist_ok=True)
    cases = [
        ("unknown_entry",
         "subsection Material\n  set Density = 1000\n"
         "  set Youngs modulus = 1e11\nend\n",
         ["line 3", "Material/Youngs modulus", "unknown entry"]),
        ("not_a_number",
         "subsection Material\n  set Young modulus = 1e11x\nend\n",
         ["line 2", "Material/Young modulus", "1e11x", "not a number"]),
        ("include",
         "include other.prm\n", ["line 1", "include"]),
        ("old_layout",
         "subsection Friction\n  set Decay rate = 2000\nend\n",
         ["line 2", "Friction/Decay rate", "update-prm"]),
        ("unclosed",
         "subsection Material\n  set Density = 1000\n",
         ["line 1", "Material", "not closed"]),
        ("unknown_subsection",
         "subsection Materials\n  set Density = 1000\nend\n",
         ["line 1", "Materials"]),
        ("auto_elsewhere",
         "subsection Material\n  set Density = auto\nend\n",
         ["line 2", "Material/Density", "'auto'", "not a number"]),
        ("bad_function",
         "subsection Body force\n  set Variable names = x\n"
         "  set Function expression = x; x\nend\n",
         ["line 2", "Body force/Variable names"]),
    ]
    for name, text, words in cases:
        path = os.path.join(directory, name + ".prm")
        out = os.path.join(directory, name + "_out.prm")
        write(path, text)
        if os.path.exists(out):
            os.remove(out)
        r = converter.run("--from", "SI", "--to", "mm-t-s", path, "-o", out)
        message = r.stderr.strip()
        check(r.returncode == 1 and len(message.splitlines()) == 1 and
              name + ".prm" in message and
              all(w in message for w in words) and not os.path.exists(out),
              "%s: refused with exit code 1 and one message naming the "
              "file, the line and the entry; nothing written" % name)
    path = os.path.join(directory, "unknown_entry.prm")
    r = converter.run("--from", "cgs", "--to", "SI", path)
    check(r.returncode == 1 and "cgs" in r.stderr,
          "an unknown unit system is refused with exit code 1")
    write(os.path.join(directory, "good.prm"),
          "subsection Material\n  set Density = 1000\nend\n")
    good = os.path.join(directory, "good.prm")
    r = converter.run("--from", "SI", "--to", "mm-t-s", good, "-o", good)
    with open(good) as f:
        unchanged = f.read() == \
            "subsection Material\n  set Density = 1000\nend\n"
    check(r.returncode == 1 and "overwrite" in r.stderr and unchanged,
          "-o IN.prm is refused (the input stays)")
    r = converter.run("--from", "SI", "--to", "mm-t-s", good)
    check(r.returncode == 0 and "set Density = 1e-09" in r.stdout,
          "without -o the scene goes to standard output")
    r = converter.run("--help")
    check(r.returncode == 0 and "in-lbf-s" in r.stdout, "--help")


# ----------------------------------------------------------------- 4.
def doc_entries(path):
    """{Section/Entry: text} of doc/parameters.md."""
    entries = {}
    section = ""
    current = None
    with open(path) as f:
        for line in f:
            m = re.match(r"^(#{2,4}) (.*)$", line)
            if m:
                title = m.group(2).strip()
                section = "" if title == "Top level" else title + "/"
                current = None
                continue
            m = re.match(r"^- \*\*(.+?)\*\* =", line)
            if m:
                current = section + m.group(1)
                entries[current] = ""
                continue
            if current is not None and line.startswith("  "):
                entries[current] += line.strip() + " "
    return entries


def check_table(converter, source_dir):
    r = converter.run("--print-table")
    table = {}   # path: (dimension or None, description)
    for line in r.stdout.splitlines():
        m = re.match(r"^(.*?)\s{2,}(\([-0-9, ]*\)|-)\s{2,}(.*)$", line)
        if m:
            table[m.group(1)] = (None if m.group(2) == "-" else tuple(
                int(e) for e in m.group(2)[1:-1].split(",")), m.group(3))
    doc = doc_entries(os.path.join(source_dir, "doc", "parameters.md"))
    missing = sorted(set(doc) - set(table))
    extra = sorted(set(table) - set(doc))
    check(r.returncode == 0 and not missing and not extra,
          "the converter's table has exactly the entries of "
          "doc/parameters.md%s%s"
          % ("; not in the table: " + ", ".join(missing) if missing else "",
             "; not in the doc: " + ", ".join(extra) if extra else ""))
    wrong = []
    for path, text in doc.items():
        if path not in table or path in DOC_DISAGREEMENTS or \
                path.startswith("Friction/Expression/"):
            continue
        documented = doc_unit(text)
        dimension, kind = table[path]
        if documented is not None and documented != dimension:
            wrong.append("%s: the doc's unit %s, the table's %s"
                         % (path, documented, kind))
        if documented is None and path not in DOC_WITHOUT_UNIT and \
                dimension is not None and "function" not in kind and \
                "Gmsh" not in kind:
            wrong.append("%s: the doc gives no unit, the table %s"
                         % (path, kind))
    check(not wrong, "the units in the text of doc/parameters.md are the "
          "table's dimensions%s" % ("" if not wrong else ": " +
                                    "; ".join(wrong)))


def main():
    import argparse
    here = os.path.dirname(os.path.realpath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    parser.add_argument("--work-dir", required=True)
    parser.add_argument("--source-dir", default=os.path.dirname(os.path.dirname(here)))
    parser.add_argument("--program", default=None,
                        help="dynamic-contact: validate the converted "
                        "scenes, run one, compare the converter's defaults "
                        "with the program's")
    args = parser.parse_args()
    source_dir = os.path.abspath(args.source_dir)
    work = os.path.abspath(args.work_dir)
    os.makedirs(work, exist_ok=True)
    converter = Converter(source_dir)
    read_prm = load_prm_reader(source_dir)

    scenes = []
    for folder in ("prm", os.path.join("prm", "stress")):
        for name in sorted(os.listdir(os.path.join(source_dir, folder))):
            if name.endswith(".prm"):
                scenes.append(os.path.join(folder, name))
    # The MSH 2.2 copy of the rail's mesh, through a scene that names it.
    msh22 = os.path.join(work, "gmsh_rail_msh22.prm")
    with open(os.path.join(source_dir, "prm", "gmsh_rail.prm")) as f:
        write(msh22, f.read().replace(
            "set Mesh file = gmsh_rail.msh",
            "set Mesh file = " + os.path.join(source_dir, "prm",
                                              "gmsh_rail_msh22.msh")))
    program = args.program and os.path.abspath(args.program)
    for relative in scenes:
        check_scene(converter, read_prm, work, relative,
                    os.path.join(source_dir, relative), program)
    check_scene(converter, read_prm, work,
                "prm/gmsh_rail.prm on prm/gmsh_rail_msh22.msh", msh22, program)
    check_known_values(converter, read_prm, work)
    check_scene(converter, read_prm, work, "the scene of known values",
                os.path.join(work, "known", "known.prm"), program)
    check_auto(converter, read_prm, work, program)
    check_defaults_written(converter, read_prm, work, program)
    check_errors(converter, work)
    check_table(converter, source_dir)
    if program:
        check_defaults(converter, program, work)
    finish("convert_units")


if __name__ == "__main__":
    main()
