"""The files of scripts/convert-units: a parameter file read into its
statements as deal.II's ParameterHandler reads it (with the lines each
one takes, so that the converter rewrites only the values), and a Gmsh
mesh file (MSH 2 or 4, ASCII) with its node coordinates rescaled.
Standard library only.
"""

import re

from convert_units_table import SUBSECTIONS
from convert_units_values import fail, scale_number_text


# ----------------------------------------------------------- prm reading
class Statement:
    """One logical line of a prm file: physical lines first..last."""

    def __init__(self, kind, first, last, sections, name=None, value=None,
                 comment=None):
        self.kind = kind          # set, subsection, end, blank
        self.first = first
        self.last = last
        self.sections = list(sections)
        self.name = name
        self.value = value
        self.comment = comment

    @property
    def path(self):
        return "/".join(self.sections + [self.name])


def split_lines(text):
    """[(line, end of line)] of @p text."""
    out = []
    for piece in re.split(r"(?<=\n)", text):
        if not piece:
            continue
        if piece.endswith("\r\n"):
            out.append((piece[:-2], "\r\n"))
        elif piece.endswith("\n"):
            out.append((piece[:-1], "\n"))
        else:
            out.append((piece, ""))
    return out


def keyword(line, word):
    return line.startswith(word + " ") or line.startswith(word.upper() + " ")


def read_statements(lines, file):
    """The statements of a prm file, as deal.II's ParameterHandler reads
    them (a trailing backslash joins the next line; '#' starts a
    comment)."""
    statements = []
    sections = []
    opened = []
    joined, first = "", None
    for number, (line, _) in enumerate(lines):
        trimmed = line.strip()
        if first is None:
            first = number
        if trimmed.endswith("\\"):
            joined += trimmed[:-1]
            if number + 1 < len(lines):
                continue
        else:
            joined += trimmed
        code, hash_, comment = joined.partition("#")
        code = code.replace("\t", " ").strip()
        where = "'%s', line %d: " % (file, first + 1)
        if not code:
            statements.append(Statement("blank", first, number, sections))
        elif keyword(code, "subsection"):
            name = code[len("subsection") + 1:].strip()
            sections.append(name)
            opened.append(first)
            if "/".join(sections) not in SUBSECTIONS:
                fail(where + "there is no subsection '%s' (unknown to the "
                     "converter's table: --print-table lists them)"
                     % "/".join(sections))
            statements.append(Statement("subsection", first, number,
                                        sections[:-1], name))
        elif code[:3] in ("end", "END"):
            if code[3:].strip():
                fail(where + "'%s': nothing may follow 'end'" % code)
            if not sections:
                fail(where + "'end' without a subsection to leave")
            sections.pop()
            opened.pop()
            statements.append(Statement("end", first, number, sections))
        elif keyword(code, "set"):
            rest = code[4:]
            if "=" not in rest:
                fail(where + "'%s': a 'set' line needs '='" % code)
            name, _, value = rest.partition("=")
            statements.append(Statement(
                "set", first, number, sections, name.strip(), value.strip(),
                comment if hash_ else None))
        elif keyword(code, "include"):
            fail(where + "'%s': include lines are not converted; convert "
                 "the included file on its own and set its entries here"
                 % code)
        else:
            fail(where + "'%s' is none of 'subsection NAME', 'set NAME = "
                 "VALUE', 'end' or a comment" % code)
        joined, first = "", None
    if sections:
        fail("'%s', line %d: subsection '%s' is not closed (no 'end')"
             % (file, opened[-1] + 1, "/".join(sections)))
    return statements


def value_span(line):
    """(start, end) of the value in the physical line 'set NAME = VALUE #'"""
    code = line.split("#", 1)[0]
    start = code.index("=") + 1
    end = len(code.rstrip())
    while start < end and code[start] in " \t":
        start += 1
    return start, max(start, end)


# ------------------------------------------------------------ mesh files
class MeshLines:
    """The lines of a Gmsh file being converted (@p out: as they become),
    read field by field with errors that name the file and the line."""

    def __init__(self, text, factor, file):
        self.lines = split_lines(text)
        self.out = [list(l) for l in self.lines]
        self.factor = factor
        self.file = file

    def where(self, k):
        return "mesh file '%s', line %d: " % (self.file, k + 1)

    def numbers(self, k, count, section):
        if k >= len(self.lines):
            fail("mesh file '%s' ends inside its $%s section"
                 % (self.file, section))
        fields = self.lines[k][0].split()
        if len(fields) < count:
            fail(self.where(k) + "cannot read this line of the $%s section"
                 % section)
        return fields

    def integer(self, text, k, section):
        try:
            return int(text)
        except ValueError:
            fail(self.where(k) + "'%s' is not an integer ($%s section)"
                 % (text, section))

    def scale_fields(self, k, positions, section):
        fields = self.lines[k][0].split()
        for p in positions:
            if p >= len(fields):
                fail(self.where(k) + "cannot read this line of the $%s "
                     "section" % section)
            fields[p] = scale_number_text(fields[p], self.factor,
                                          self.where(k) + "coordinate ")
        self.out[k][0] = " ".join(fields)


def mesh_version(mesh, i, section):
    """The version of the $MeshFormat section at the line @p i (ASCII,
    MSH 2 or 4)."""
    fields = mesh.numbers(i + 1, 2, section)
    version = fields[0]
    if fields[1] != "0":
        fail(mesh.where(i + 1) + "a binary mesh file (MSH %s) is not "
             "converted; save it as ASCII" % version)
    if version.split(".")[0] not in ("2", "4"):
        fail(mesh.where(i + 1) + "MSH %s: only the formats 2 and 4 "
             "(ASCII) are converted" % version)
    return version


def scale_nodes(mesh, i, version, section):
    """The $Nodes section at the line @p i scaled; returns the line after
    its $EndNodes."""
    k = i + 1
    if version.split(".")[0] == "2":
        n = mesh.integer(mesh.numbers(k, 1, section)[0], k, section)
        for j in range(n):
            mesh.numbers(k + 1 + j, 4, section)
            mesh.scale_fields(k + 1 + j, (1, 2, 3), section)
        k += 1 + n
    else:
        header = mesh.numbers(k, 2, section)
        blocks = mesh.integer(header[0], k, section)
        k += 1
        for _ in range(blocks):
            block = mesh.numbers(k, 4, section)
            n = mesh.integer(block[3], k, section)
            k += 1
            if version == "4.0":
                for j in range(n):
                    mesh.numbers(k + j, 4, section)
                    mesh.scale_fields(k + j, (1, 2, 3), section)
                k += n
            else:
                k += n      # the node tags
                for j in range(n):
                    mesh.numbers(k + j, 3, section)
                    mesh.scale_fields(k + j, (0, 1, 2), section)
                k += n
    if k >= len(mesh.lines) or mesh.lines[k][0].strip() != "$EndNodes":
        fail(mesh.where(min(k, len(mesh.lines) - 1)) + "expected $EndNodes "
             "after the nodes the $Nodes header announces")
    return k + 1


def scale_entities(mesh, i, version, section):
    """The bounding boxes of the $Entities section (MSH 4) at the line
    @p i scaled; returns the line after its $EndEntities."""
    k = i + 1
    counts = [mesh.integer(c, k, section)
              for c in mesh.numbers(k, 4, section)[:4]]
    k += 1
    for d, n in enumerate(counts):
        positions = ((1, 2, 3) if d == 0 and version != "4.0"
                     else (1, 2, 3, 4, 5, 6))
        for j in range(n):
            mesh.numbers(k + j, len(positions) + 1, section)
            mesh.scale_fields(k + j, positions, section)
        k += n
    if k >= len(mesh.lines) or mesh.lines[k][0].strip() != "$EndEntities":
        fail(mesh.where(min(k, len(mesh.lines) - 1)) +
             "expected $EndEntities")
    return k + 1


def convert_mesh(text, factor, file):
    """The Gmsh file @p text (ASCII, MSH 2 or 4) with its node coordinates
    (and the bounding boxes of $Entities) times @p factor."""
    mesh = MeshLines(text, factor, file)
    lines = mesh.lines
    version = None
    i = 0
    found_nodes = False
    while i < len(lines):
        line = lines[i][0].strip()
        if not line.startswith("$") or line.startswith("$End"):
            i += 1
            continue
        section = line[1:]
        if i == 0 or version is None:
            if section != "MeshFormat":
                fail(mesh.where(i) + "the file is not a Gmsh mesh file in "
                     "the MSH 2 or 4 ASCII format (it does not begin with "
                     "$MeshFormat)")
        if section == "MeshFormat":
            version = mesh_version(mesh, i, section)
            i += 2
        elif section == "Nodes":
            found_nodes = True
            i = scale_nodes(mesh, i, version, section)
        elif section == "Entities" and version.split(".")[0] == "4":
            i = scale_entities(mesh, i, version, section)
        elif section in ("Periodic", "Parametrizations",
                         "PartitionedEntities", "GhostElements"):
            fail(mesh.where(i) + "the $%s section is not converted (it "
                 "holds lengths or partitions); save the mesh without it"
                 % section)
        else:
            i += 1
    if version is None:
        fail("mesh file '%s' has no $MeshFormat section" % file)
    if not found_nodes:
        fail("mesh file '%s' has no $Nodes section" % file)
    return "".join(l + e for l, e in mesh.out)
