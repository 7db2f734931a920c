"""The table of scripts/convert-units: the unit systems, the physical
dimension of every entry of a parameter file (TABLE; --print-table lists
it), the program's defaults of the numbers of a dimension (DEFAULTS), and
the entries of the old layout (MOVED) and removed ones (REMOVED).

A new parameter of the program gets its line here, with its dimension
(and its default where it is a number of a dimension): the test
tests/scenes/convert_units.py compares the table with doc/parameters.md
and the defaults with the program's. Standard library only.
"""

from fractions import Fraction

# ----------------------------------------------------------- unit systems
INCH = Fraction("0.0254")            # m, exact
LBF = Fraction("4.4482216152605")    # N, exact

# (length, mass, time) in SI units, and a description.
SYSTEMS = {
    "SI": ((Fraction(1), Fraction(1), Fraction(1)),
           "length m, mass kg, time s; force N, stress Pa"),
    "mm-t-s": ((Fraction(1, 1000), Fraction(1000), Fraction(1)),
               "length mm, mass t, time s; force N, stress MPa"),
    "in-lbf-s": ((INCH, LBF / INCH, Fraction(1)),
                 "length in, mass lbf s^2/in, time s; force lbf, stress "
                 "psi"),
}


def unit(system, dimension):
    """The unit of @p dimension (L, M, T exponents) of @p system, in SI."""
    base = SYSTEMS[system][0]
    u = Fraction(1)
    for b, e in zip(base, dimension):
        u *= b ** e
    return u


# ------------------------------------------------------ dimension table
LENGTH = (1, 0, 0)
TIME = (0, 0, 1)
VELOCITY = (1, 0, -1)
DENSITY = (-3, 1, 0)
STRESS = (-1, 1, -2)            # Pa
STRESS_PER_LENGTH = (-2, 1, -2)  # Pa/m = N/m^3
VISCOSITY = (-1, 1, -1)         # Pa s
DAMPING = (-2, 1, -1)           # Pa s/m
SLOWNESS = (-1, 0, 1)           # s/m

UNIT_NAMES = {
    LENGTH: "m", TIME: "s", VELOCITY: "m/s", DENSITY: "kg/m^3",
    STRESS: "Pa", STRESS_PER_LENGTH: "Pa/m = N/m^3", VISCOSITY: "Pa s",
    DAMPING: "Pa s/m", SLOWNESS: "s/m",
}

# Kinds of entries.
NAME = "not a quantity"        # names, booleans, ids, counts, files, GB
RATIO = "dimensionless"
NUMBER = "number"              # a number of a dimension
LIST = "list"                  # a list of numbers of one dimension
FUNCTION = "function"          # Function expression of f(x, t)
FUNCTION_PART = "function part"  # Function constants, Variable names
FRICTION = "friction"          # Friction/Expression/Function expression
FRICTION_PART = "friction part"
MESH = "mesh file"

# The functions of space and time: subsection -> dimension of the value.
FUNCTIONS = {
    "Body force": STRESS_PER_LENGTH,                    # N/m^3
    "Boundary conditions/Traction function": STRESS,
    "Boundary conditions/Contact source": STRESS,
    "Initial conditions/Displacement": LENGTH,
    "Initial conditions/Velocity": VELOCITY,
    "Exact solution/Displacement": LENGTH,
    "Exact solution/Velocity": VELOCITY,
    "Foundation/Initial gap": LENGTH,
}


def _add(t, kind, dimension, *paths):
    for p in paths:
        t[p] = (kind, dimension)


def _table_functions_and_boundary(t):
    _add(t, NAME, None, "Dimension")
    for f, dimension in FUNCTIONS.items():
        _add(t, FUNCTION, dimension, f + "/Function expression")
        _add(t, FUNCTION_PART, dimension, f + "/Function constants",
             f + "/Variable names")
    bc = "Boundary conditions/"
    _add(t, NAME, None, *(bc + n for n in
                         ("Clamped", "Contact", "Free", "Roller", "Traction")))
    _add(t, RATIO, None, bc + "Load quadrature tolerance")
    _add(t, NAME, None, "Checkpoint/Every", "Checkpoint/Keep",
         "Finite element/Polynomial degree")


def _table_foundation_and_friction(t):
    fo = "Foundation/"
    _add(t, NAME, None, fo + "Normal compliance/Law",
         fo + "Normal damping/Law", fo + "Normal damping/Only in contact")
    _add(t, NUMBER, STRESS_PER_LENGTH,
         fo + "Normal compliance/Capped ramp/Stiffness")
    _add(t, NUMBER, STRESS, fo + "Normal compliance/Capped ramp/Cap",
         fo + "Normal damping/Capped ramp/Cap")
    _add(t, NUMBER, DAMPING, fo + "Normal damping/Capped ramp/Coefficient")
    fr = "Friction/"
    _add(t, RATIO, None, fr + "Coefficient tolerance",
         fr + "Convexification tolerance", fr + "Relaxation",
         fr + "Constant/Coefficient", fr + "Exponential/Static coefficient",
         fr + "Exponential/Dynamic coefficient")
    # c_t: c = c_t k and c m_i w_tau is a nodal force (m_i an area), so
    # c_t is a force per volume, like its default E/h.
    _add(t, NUMBER, STRESS_PER_LENGTH, fr + "Complementarity constant")
    _add(t, NAME, None, fr + "Law", fr + "Linearization",
         fr + "Maximum convexification iterations", fr + "Uniqueness monitor",
         fr + "Count solutions", fr + "Velocity strengthening")
    _add(t, NUMBER, VELOCITY, fr + "Maximum slip rate",
         fr + "Reference slip rate")
    _add(t, NUMBER, LENGTH, fr + "Slip length")
    _add(t, NUMBER, SLOWNESS, fr + "Exponential/Decay rate")
    _add(t, FRICTION, None, fr + "Expression/Function expression")
    _add(t, FRICTION_PART, None, fr + "Expression/Function constants")


def _table_geometry_material_refinement(t):
    g = "Geometry/"
    _add(t, NAME, None, g + "Global refinements", g + "Repetitions",
         g + "Type")
    _add(t, LIST, LENGTH, g + "Lower left", g + "Upper right")
    _add(t, MESH, LENGTH, g + "Mesh file")
    ma = "Material/"
    _add(t, NUMBER, DENSITY, ma + "Density")
    _add(t, NUMBER, STRESS, ma + "Young modulus")
    _add(t, NUMBER, VISCOSITY, ma + "Viscosity lambda", ma + "Viscosity mu")
    _add(t, RATIO, None, ma + "Poisson ratio")
    _add(t, NAME, None, ma + "Plane model")
    mr = "Mesh refinement/"
    _add(t, NAME, None, mr + "Cell budget", mr + "Maximum level",
         mr + "Minimum level", mr + "Refine every", mr + "Strategy")
    _add(t, NUMBER, LENGTH, mr + "Contact following/Window",
         mr + "Load following/Window")
    _add(t, RATIO, None, mr + "Error indicator/Coarsen fraction",
         mr + "Error indicator/Refine fraction",
         mr + "Load following/Threshold")


def _table_output_solver_time(t):
    o = "Output/"
    _add(t, NAME, None, o + "Directory", o + "Output every",
         o + "Print iteration counts", o + "Print timings",
         o + "Progress every", o + "Solver details", o + "VTU every",
         o + "VTU subdivisions", o + "Write VTU")
    _add(t, LIST, TIME, o + "Output times")
    s = "Solver/"
    _add(t, NAME, None, *(s + n for n in (
         "AMG/Aggregation", "Assembled/Provisional passes", "Condensed/Limit",
         "Condensed/Limit on several processes", "Condensed/Provisional passes",
         "Contact solver", "Direct solver package", "Line search",
         "Linear solver", "Maximum Newton iterations", "Maximum linear iterations",
         "Memory per process", "Minimum DoFs per process", "Preconditioner")))
    _add(t, RATIO, None, s + "Linear tolerance", s + "Newton tolerance")
    ti = "Time/"
    _add(t, NAME, None, ti + "Adaptive", ti + "Cut back where not unique",
         ti + "Scheme")
    _add(t, RATIO, None, ti + "Adaptive tolerance",
         ti + "Bathe/Spectral radius at infinity",
         ti + "Sdirk/Spectral radius at infinity")
    _add(t, NUMBER, TIME, ti + "End time", ti + "Time step",
         ti + "Minimum time step", ti + "Maximum time step")


def _table():
    """Every entry of the program's parameters: (kind, dimension)."""
    t = {}
    _table_functions_and_boundary(t)
    _table_foundation_and_friction(t)
    _table_geometry_material_refinement(t)
    _table_output_solver_time(t)
    return t


TABLE = _table()
SUBSECTIONS = {"/".join(p.split("/")[:i])
               for p in TABLE for i in range(1, p.count("/") + 1)}

# Entries that also take the word 'auto': the program derives the value
# from the scene itself (in the scene's units), so 'auto' stays as it is.
AUTO = {"Friction/Maximum slip rate",
        "Mesh refinement/Contact following/Window",
        "Mesh refinement/Load following/Window"}

# The program's default of every number and list of a dimension, as
# `dynamic-contact --print-parameters` prints it (a dict by Dimension
# where it depends on it): numbers of the paper's scene, in SI. A scene
# that leaves one out runs with this number in its own units, so a
# converted scene states the ones that are not 0 (nor empty, nor 'auto'),
# converted (add_defaults()). tests/scenes/convert_units.py --program compares
# this table with the program's.
DEFAULTS = {
    "Foundation/Normal compliance/Capped ramp/Stiffness": "5e9",
    "Foundation/Normal compliance/Capped ramp/Cap": "1e17",
    "Foundation/Normal damping/Capped ramp/Coefficient": "1e8",
    "Foundation/Normal damping/Capped ramp/Cap": "1e17",
    "Friction/Complementarity constant": "0",
    "Friction/Maximum slip rate": "auto",
    "Friction/Reference slip rate": "0",
    "Friction/Slip length": "0",
    "Friction/Exponential/Decay rate": "2000",
    "Geometry/Lower left": {2: "0, 0", 3: "0, 0, 0"},
    "Geometry/Upper right": {2: "2, 0.1", 3: "2, 0.1, 0.1"},
    "Material/Density": "1000",
    "Material/Young modulus": "1e11",
    "Material/Viscosity lambda": "0",
    "Material/Viscosity mu": "0",
    "Mesh refinement/Contact following/Window": "auto",
    "Mesh refinement/Load following/Window": "auto",
    "Output/Output times": "",
    "Time/End time": "1",
    "Time/Time step": "0.0078125",
    "Time/Minimum time step": "0",
    "Time/Maximum time step": "0",
}
# The corners of the rectangle: only for Geometry/Type = rectangle.
RECTANGLE_ONLY = {"Geometry/Lower left", "Geometry/Upper right"}


def default_of(path, dimension):
    """The program's default text of @p path in @p dimension."""
    value = DEFAULTS[path]
    return value[dimension] if isinstance(value, dict) else value


# Entries of the old flat layout (the program's moved_entries(), whose
# error message points to scripts/update-prm) and removed entries.
MOVED = {
    "Foundation/Normal compliance stiffness":
        "Foundation/Normal compliance/Capped ramp/Stiffness",
    "Foundation/Compliance cap":
        "Foundation/Normal compliance/Capped ramp/Cap",
    "Foundation/Normal damping":
        "Foundation/Normal damping/Capped ramp/Coefficient",
    "Foundation/Damping cap": "Foundation/Normal damping/Capped ramp/Cap",
    "Foundation/Damping only in contact":
        "Foundation/Normal damping/Only in contact",
    "Friction/Coefficient": "Friction/Constant/Coefficient",
    "Friction/Static coefficient": "Friction/Exponential/Static coefficient",
    "Friction/Dynamic coefficient": "Friction/Exponential/Dynamic coefficient",
    "Friction/Decay rate": "Friction/Exponential/Decay rate",
    "Friction/Expression": "Friction/Expression/Function expression",
    "Friction/Expression constants": "Friction/Expression/Function constants",
    "Mesh refinement/Load window": "Mesh refinement/Load following/Window",
    "Mesh refinement/Load threshold":
        "Mesh refinement/Load following/Threshold",
    "Mesh refinement/Contact window":
        "Mesh refinement/Contact following/Window",
    "Mesh refinement/Refine fraction":
        "Mesh refinement/Error indicator/Refine fraction",
    "Mesh refinement/Coarsen fraction":
        "Mesh refinement/Error indicator/Coarsen fraction",
}
REMOVED = {"Friction/Acceleration depth",
           "Mesh refinement/Load following/Look-ahead steps",
           "Mesh refinement/Look-ahead steps"}


def unit_name(dimension):
    if dimension in UNIT_NAMES:
        return UNIT_NAMES[dimension]
    parts = ["%s^%d" % (b, e) for b, e in zip(("m", "kg", "s"), dimension)
             if e]
    return " ".join(parts) or "1"


def describe(path):
    kind, dimension = TABLE[path]
    if kind in (NAME, RATIO):
        return kind
    if kind in (NUMBER, LIST):
        text = unit_name(dimension)
        if kind == LIST:
            text = "list of " + text
        if path in AUTO:
            text += ", or auto"
        value = DEFAULTS.get(path)
        if isinstance(value, dict):
            text += "; default %s" % ", ".join(
                "'%s' (%dD)" % (value[d], d) for d in sorted(value))
        elif value is not None:
            text += "; default '%s'" % value
        return text
    if kind == FUNCTION:
        return "function of (x, t), value in %s" % unit_name(dimension)
    if kind == FUNCTION_PART:
        return "part of the function (converted with its expression)"
    if kind == FRICTION:
        return "mu(s) of the slip rate s in m/s, dimensionless"
    if kind == FRICTION_PART:
        return "part of mu(s) (converted with its expression)"
    if kind == MESH:
        return "Gmsh file: node coordinates in m (copied, rescaled)"
    return kind
