"""The helpers of the test convert_units (tests/scenes/convert_units.py):
the unit systems from their definitions (independent of
scripts/convert-units), a muparser expression evaluated in Python (the
functions of space and time compared at points), and the utilities of the
round trips: the converter run and loaded as a module, the prm reader,
the nodes of a mesh file, the entries compared. Standard library only.
"""

import importlib.machinery
import importlib.util
import math
import os
import re
import subprocess
import sys
from fractions import Fraction

INCH = Fraction("0.0254")
LBF = Fraction("4.4482216152605")
# (length, mass, time) of each system in SI units.
SYSTEMS = {"SI": (Fraction(1), Fraction(1), Fraction(1)),
           "mm-t-s": (Fraction(1, 1000), Fraction(1000), Fraction(1)),
           "in-lbf-s": (INCH, LBF / INCH, Fraction(1))}

# The dimension (L, M, T) of the value of each function of space and time.
FUNCTIONS = {
    "Body force": (-2, 1, -2),
    "Boundary conditions/Traction function": (-1, 1, -2),
    "Boundary conditions/Contact source": (-1, 1, -2),
    "Initial conditions/Displacement": (1, 0, 0),
    "Initial conditions/Velocity": (1, 0, -1),
    "Exact solution/Displacement": (1, 0, 0),
    "Exact solution/Velocity": (1, 0, -1),
    "Foundation/Initial gap": (1, 0, 0),
}


def unit(system, dimension):
    u = Fraction(1)
    for b, e in zip(SYSTEMS[system], dimension):
        u *= b ** e
    return u


def factor(source, target, dimension):
    """A value of @p dimension in @p source times this is in @p target."""
    return unit(source, dimension) / unit(target, dimension)


def exact(x, f):
    return float(Fraction(x) * f)


def close(a, b, tolerance=1e-12, scale=0.0):
    return abs(a - b) <= tolerance * max(abs(a), abs(b), scale)


# ------------------------------------------------- muparser expressions
class Expression:
    """A muparser expression (deal.II's FunctionParser syntax) evaluated
    in Python: numbers, names, + - * / ^, comparisons, && ||, a ? b : c,
    and the usual functions."""

    FUNCTIONS = {
        "sin": math.sin, "cos": math.cos, "tan": math.tan,
        "asin": math.asin, "acos": math.acos, "atan": math.atan,
        "sinh": math.sinh, "cosh": math.cosh, "tanh": math.tanh,
        "exp": math.exp, "log": math.log, "ln": math.log,
        "log10": math.log10, "sqrt": math.sqrt, "abs": abs,
        "floor": math.floor, "ceil": math.ceil, "pow": math.pow,
        "atan2": math.atan2, "min": min, "max": max,
        "sign": lambda x: (x > 0) - (x < 0),
        "if": lambda c, a, b: a if c else b,
    }
    TOKEN = re.compile(r"\s*(?:(\d+\.?\d*(?:[eE][+-]?\d+)?|\.\d+(?:[eE][+-]?"
                       r"\d+)?)|([A-Za-z_][A-Za-z0-9_]*)|(&&|\|\||<=|>=|==|"
                       r"!=|[-+*/^(),?:<>!]))")

    def __init__(self, text):
        self.tokens = []
        position = 0
        text = text.rstrip()
        while position < len(text):
            m = self.TOKEN.match(text, position)
            if not m:
                raise ValueError("cannot read '%s' at %d" % (text, position))
            self.tokens.append(m.group(1) and ("num", float(m.group(1))) or
                               m.group(2) and ("id", m.group(2)) or
                               ("op", m.group(3)))
            position = m.end()

    def __call__(self, names):
        self.names = names
        self.k = 0
        value = self.ternary()
        if self.k != len(self.tokens):
            raise ValueError("unexpected %r" % (self.tokens[self.k],))
        return value

    def peek(self):
        return self.tokens[self.k][1] if self.k < len(self.tokens) else None

    def take(self, op=None):
        token = self.tokens[self.k]
        if op is not None and token[1] != op:
            raise ValueError("expected %s, got %r" % (op, token))
        self.k += 1
        return token

    def ternary(self):
        c = self.binary(0)
        if self.peek() == "?":
            self.take()
            a = self.ternary()
            self.take(":")
            b = self.ternary()
            return a if c else b
        return c

    LEVELS = [("||",), ("&&",), ("==", "!=", "<", ">", "<=", ">="),
              ("+", "-"), ("*", "/")]

    def binary(self, level):
        if level == len(self.LEVELS):
            return self.unary()
        value = self.binary(level + 1)
        while self.peek() in self.LEVELS[level] and \
                self.tokens[self.k][0] == "op":
            op = self.take()[1]
            right = self.binary(level + 1)
            value = {"||": lambda a, b: float(bool(a) or bool(b)),
                     "&&": lambda a, b: float(bool(a) and bool(b)),
                     "==": lambda a, b: float(a == b),
                     "!=": lambda a, b: float(a != b),
                     "<": lambda a, b: float(a < b),
                     ">": lambda a, b: float(a > b),
                     "<=": lambda a, b: float(a <= b),
                     ">=": lambda a, b: float(a >= b),
                     "+": lambda a, b: a + b, "-": lambda a, b: a - b,
                     "*": lambda a, b: a * b,
                     "/": lambda a, b: a / b}[op](value, right)
        return value

    def unary(self):
        if self.peek() in ("-", "+", "!") and self.tokens[self.k][0] == "op":
            op = self.take()[1]
            value = self.unary()
            return -value if op == "-" else (
                value if op == "+" else float(not value))
        return self.power()

    def power(self):
        base = self.primary()
        if self.peek() == "^":
            self.take()
            return math.pow(base, self.unary())
        return base

    def primary(self):
        kind, value = self.take()
        if kind == "num":
            return value
        if kind == "id":
            if self.peek() == "(":
                self.take()
                arguments = [self.ternary()]
                while self.peek() == ",":
                    self.take()
                    arguments.append(self.ternary())
                self.take(")")
                return float(self.FUNCTIONS[value](*arguments))
            return self.names[value]
        if value == "(":
            inner = self.ternary()
            self.take(")")
            return inner
        raise ValueError("unexpected %r" % value)


def constants_of(text):
    # pi as scenes write it, and muparser's own constants (deal.II's
    # FunctionParser): _pi, _e.
    names = {"pi": math.pi, "Pi": math.pi, "_pi": math.pi, "_e": math.e}
    for item in text.split(","):
        if item.strip():
            name, value = item.split("=")
            names[name.strip()] = float(value)
    return names


def evaluate(expression, constants, variables, point):
    """The components of @p expression at @p point (values of the
    @p variables)."""
    names = constants_of(constants)
    names.update(zip(variables, point))
    return [Expression(c)(names) for c in expression.split(";")]


# ------------------------------------------------------------ utilities
def load_prm_reader(source_dir):
    """read_prm of python/dynamic_contact/prm.py (without the package,
    which needs numpy)."""
    path = os.path.join(source_dir, "python", "dynamic_contact", "prm.py")
    spec = importlib.util.spec_from_file_location("dc_prm", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.read_prm


def mesh_nodes(path):
    """The node coordinates [x, y, z, ...] of a MSH 2 or 4.1 ASCII file."""
    with open(path) as f:
        lines = [l.strip() for l in f]
    version = lines[lines.index("$MeshFormat") + 1].split()[0]
    k = lines.index("$Nodes") + 1
    coordinates = []
    if version.startswith("2"):
        n = int(lines[k])
        for line in lines[k + 1:k + 1 + n]:
            coordinates.extend(float(v) for v in line.split()[1:4])
        return coordinates
    blocks = int(lines[k].split()[0])
    k += 1
    for _ in range(blocks):
        n = int(lines[k].split()[3])
        k += 1 + n
        for line in lines[k:k + n]:
            coordinates.extend(float(v) for v in line.split()[:3])
        k += n
    return coordinates


def load_script(path):
    """The script @p path (no .py) as a module: its tables. Its directory
    is first on Python's path while it loads, as when it runs, for the
    modules next to it that it imports (scripts/convert_units_*.py)."""
    loader = importlib.machinery.SourceFileLoader("convert_units_script",
                                                  path)
    spec = importlib.util.spec_from_loader(loader.name, loader)
    module = importlib.util.module_from_spec(spec)
    directory = os.path.dirname(os.path.realpath(path))
    sys.path.insert(0, directory)
    try:
        loader.exec_module(module)
    finally:
        sys.path.remove(directory)
    return module


class Converter:
    def __init__(self, source_dir):
        self.script = os.path.join(source_dir, "scripts", "convert-units")
        self.module = load_script(self.script)

    def run(self, *arguments):
        return subprocess.run([sys.executable, self.script] + list(arguments),
                              capture_output=True, text=True)

    def convert(self, source, target, path, output):
        r = self.run("--from", source, "--to", target, path, "-o", output)
        if r.returncode != 0:
            raise RuntimeError(r.stderr.strip())


def points(dimension, system="SI"):
    """Points (x, y, [z,] t) in the units of @p system."""
    si = [(0.375, 0.0625, 0.03125, 0.3125), (1.25, 0.046875, 0.0859375, 0.625),
          (0.8125, 0.015625, 0.0703125, 0.9375)]
    f = float(factor("SI", system, (1, 0, 0)))
    return [tuple(c * f for c in p[:dimension]) + (p[3],) for p in si]


def variables_of(entries, subsection, dimension):
    names = entries.get(subsection + "/Variable names",
                        "x,y,t" if dimension == 2 else "x,y,z,t")
    return [v.strip() for v in names.split(",")]


def number_list(text):
    try:
        return [float(v) for v in text.split(",")]
    except ValueError:
        return None


def nonzero_numbers(text):
    """True if @p text is a number or list of numbers not all 0."""
    numbers = number_list(text) if text.strip() else None
    return bool(numbers) and any(numbers)


def unstated_defaults(module, entries):
    """{entry: the program's default} of the numbers of a dimension that
    @p entries (a scene) leave out and whose default is not 0 (the corners
    of the rectangle: only for Type = rectangle), by the converter's table
    of defaults (which check_defaults() compares with the program)."""
    dimension = int(entries.get("Dimension", "2"))
    rectangle = entries.get("Geometry/Type", "rectangle") == "rectangle"
    out = {}
    for key in module.DEFAULTS:
        text = module.default_of(key, dimension)
        if key not in entries and nonzero_numbers(text) and \
                (rectangle or key not in module.RECTANGLE_ONLY):
            out[key] = text
    return out


def with_defaults(module, entries):
    """@p entries with the defaults they leave out: the values a run
    uses."""
    out = dict(entries)
    dimension = int(entries.get("Dimension", "2"))
    for key in module.DEFAULTS:
        out.setdefault(key, module.default_of(key, dimension))
    return out


def differences(a, back):
    """What differs between the entries @p a and @p back: numbers to
    1e-12, expressions and constants as they were (but for components
    that are numbers), the mesh file's name not at all."""
    problems = []
    for key in sorted(set(a) | set(back)):
        if key not in a:
            if not (key.endswith("/Function constants") and not back[key]):
                problems.append("%s added" % key)
            continue
        if key not in back:
            problems.append("%s lost" % key)
            continue
        x, y = a[key], back[key]
        if key == "Geometry/Mesh file" or x == y:
            continue
        if key.endswith("/Function constants"):
            if constants_of(x) != constants_of(y):
                problems.append(key)
            continue
        if key.endswith("/Function expression"):
            # The same text, but for components that are numbers.
            u, v = x.split(";"), y.split(";")
            if len(u) != len(v) or not all(
                    p.strip() == q.strip() or (
                        number_list(p) and number_list(q) and
                        close(number_list(p)[0], number_list(q)[0]))
                    for p, q in zip(u, v)):
                problems.append("%s: '%s' -> '%s'" % (key, x, y))
            continue
        u, v = number_list(x), number_list(y)
        if u is None or v is None or len(u) != len(v) or \
                not all(close(p, q) for p, q in zip(u, v)):
            problems.append("%s: '%s' -> '%s'" % (key, x, y))
    return problems
