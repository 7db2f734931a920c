#!/usr/bin/env python3
"""Read the ParaView output of a dynamic-contact run with meshio (a reader
that is not the project's) and print deterministic facts about it, for the
test paraview_output:

    python3 tests/read_output.py OUTPUT_DIRECTORY

For solution.pvd and contact_surface.pvd: the (time, file) entries, the
same times in both. For every VTU step: the pieces named by each .pvtu
record, read one by one with meshio.read (deal.II's zlib-compressed binary
VTU); the time (and step) each piece carries; the stress as a symmetric
tensor (9 components in the file, as VTK stores tensors) constant on each
cell, von Mises from it equal to the von_mises_stress field; the surface
of Gamma_3 with its fields, a point at every node of Gamma_3 (the rows of
the contact CSV), its values equal to the contact CSV of the same step
node by node (normal_pressure, u_nu, the displacement, mu, the tangential
friction traction, the state as its code), zero at its other points (the
clamped ends, which are no contact nodes).

Prints "FAILED: ..." lines and exits 1 if anything does not hold; exits 0
otherwise. Needs numpy and meshio (Debian: python3-numpy, python3-meshio).
"""
import csv
import glob
import os
import re
import sys
import xml.etree.ElementTree as ET

import meshio
import numpy as np

# float32 in the files: values agree with the CSV (11 digits) to this.
FLOAT32 = 1e-6
STATE_CODES = {"free": 0, "contact": 1, "stick": 2, "slip": 3}

failures = []


def check(condition, what):
    if not condition:
        failures.append(what)
        print("FAILED: " + what)


def read_pvd(path):
    root = ET.parse(path).getroot()
    return [(float(d.get("timestep")), d.get("file")) for d in root.iter("DataSet")]


def pieces_of(directory, pvtu):
    """The piece files a .pvtu record names, and the compressor of its
    pieces."""
    root = ET.parse(os.path.join(directory, pvtu)).getroot()
    check(root.get("type") == "PUnstructuredGrid", pvtu + ": a PUnstructuredGrid record")
    return [p.get("Source") for p in root.iter("Piece")]


def read_piece(path, time, step, facts):
    """A piece with meshio, after checking its time and step; None for an
    empty piece (a process without cells or faces of Gamma_3), which
    meshio cannot read (it wants cells): its time, step and field names are
    checked in the XML instead."""
    name = os.path.basename(path)
    root = ET.parse(path).getroot()
    piece = root.find("UnstructuredGrid/Piece")
    if int(piece.get("NumberOfPoints")) > 0:
        facts.setdefault("compressor", set()).add(root.get("compressor", "none"))
        mesh = meshio.read(path)
        field_data = {k: np.ravel(v)[0] for k, v in mesh.field_data.items()}
        fields = set(mesh.point_data)
    else:
        mesh = None
        field_data = {a.get("Name"): float(a.text)
                      for a in root.iter("DataArray") if a.get("Name") in ("TIME", "CYCLE")}
        fields = {a.get("Name") for a in piece.find("PointData")}
        facts["empty pieces"] = facts.get("empty pieces", 0) + 1
    t, cycle = field_data.get("TIME"), field_data.get("CYCLE")
    check(t is not None and np.float32(t) == np.float32(time),
          "%s: TIME %s is the time %r of the .pvd" % (name, t, time))
    check((cycle is None and step == 0) or (cycle is not None and int(cycle) == step),
          "%s: CYCLE %s is the step %d" % (name, cycle, step))
    return mesh, fields


def field(mesh, name):
    """The field of a piece as a (points, components) float64 array."""
    data = np.asarray(mesh.point_data[name], dtype=np.float64)
    return data.reshape(data.shape[0], -1)


def cell_point_indices(mesh):
    return [np.asarray(block.data) for block in mesh.cells]


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def von_mises(s, szz):
    """From the 3x3 tensor rows (n, 9); in 2D s_zz of the file is 0 and the
    out-of-plane stress szz is given."""
    xx, yy, zz = s[:, 0], s[:, 4], s[:, 8] + szz
    xy, xz, yz = s[:, 1], s[:, 2], s[:, 5]
    return np.sqrt(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                   + 3 * (xy ** 2 + xz ** 2 + yz ** 2))


def nonempty_pieces(directory, pvtu, time, step, facts, kind):
    """(name, mesh) of each piece of a .pvtu record that has points, read
    one after the other (read_piece); the number of pieces and the field
    names of every piece go into facts as '<kind> pieces' and '<kind>
    fields'."""
    names = pieces_of(directory, pvtu)
    facts.setdefault(kind + " pieces", set()).add(len(names))
    for name in names:
        mesh, fields = read_piece(os.path.join(directory, name), time, step,
                                  facts)
        facts.setdefault(kind + " fields", set()).update(fields)
        if mesh is not None:
            yield name, mesh


def check_solution(directory, pvtu, time, step, facts):
    for name, mesh in nonempty_pieces(directory, pvtu, time, step, facts,
                                      "solution"):
        stress = field(mesh, "stress")
        facts.setdefault("stress components", set()).add(stress.shape[1])
        check(stress.shape[1] == 9, "%s: the stress has 9 components" % name)
        scale = max(np.abs(stress).max(), 1e-300)
        asym = max(np.abs(stress[:, 1] - stress[:, 3]).max(),
                   np.abs(stress[:, 2] - stress[:, 6]).max(),
                   np.abs(stress[:, 5] - stress[:, 7]).max())
        check(asym == 0, "%s: the stress tensor is symmetric (%g)" % (name, asym / scale))
        dim = 3 if "stress_zz" not in mesh.point_data else 2
        if dim == 2:
            check(np.abs(stress[:, [2, 5, 6, 7, 8]]).max() == 0,
                  "%s: in 2D the z row and column of the tensor are 0" % name)
        # Per cell (deal.II writes per-cell values as point data, constant
        # on the cell's patch): the stress is constant over its points (a
        # cell average), and von Mises of it is von_mises_stress.
        cells = np.concatenate(cell_point_indices(mesh))
        first = stress[cells[:, 0]]
        constant = max(np.abs(stress[cells[:, j]] - first).max()
                       for j in range(cells.shape[1]))
        check(constant == 0, "%s: the stress is constant on each cell" % name)
        szz = field(mesh, "stress_zz")[:, 0] if dim == 2 else 0
        vm = field(mesh, "von_mises_stress")[:, 0]
        deviation = np.abs(von_mises(stress, szz) - vm).max() / max(vm.max(), 1e-300)
        check(deviation < 10 * FLOAT32,
              "%s: von Mises of the stress tensor is von_mises_stress (%g)" % (name, deviation))
        facts["von Mises checked"] = facts.get("von Mises checked", 0) + 1


def node_of(row):
    """The position of a contact CSV row as a key of the surface points."""
    return tuple(np.round([float(row["x"]), float(row["y"]),
                           float(row["z"]) if "z" in row else 0.0], 6))


def read_surface(directory, pvtu, time, step, facts):
    """The points of the surface pieces of @p pvtu and their fields: the
    points, the values by field, the first index of each distinct point
    (faces are patches of their own: shared nodes repeat)."""
    points, values = [], {}
    for _, mesh in nonempty_pieces(directory, pvtu, time, step, facts,
                                   "surface"):
        points.append(np.asarray(mesh.points, dtype=np.float64))
        for key in mesh.point_data:
            values.setdefault(key, []).append(field(mesh, key))
    points = np.concatenate(points)
    values = {k: np.concatenate(v) for k, v in values.items()}
    # Distinct points: faces are patches of their own (shared nodes repeat).
    keys = [tuple(np.round(p, 6)) for p in points]
    distinct = {}
    for i, k in enumerate(keys):
        distinct.setdefault(k, i)
    facts.setdefault("surface points (distinct)", set()).add(len(distinct))
    # Repeated points carry the same values (a continuous field).
    for key, v in values.items():
        for i, k in enumerate(keys):
            if not np.array_equal(v[i], v[distinct[k]]):
                check(False, "%s: %s differs between the copies of a node" % (pvtu, key))
                break
    return values, distinct


def node_pairs(r, i, values, dim, friction):
    """The (field, value in the file, value in the CSV) of the surface
    point @p i and the CSV row @p r of its node, and the state the CSV
    says."""
    pairs = [("normal_pressure", values["normal_pressure"][i, 0], float(r["normal_pressure"])),
             ("penetration", values["penetration"][i, 0], float(r["u_nu"]))]
    for d, axis in enumerate("xyz"[:dim]):
        pairs.append(("displacement", values["displacement"][i, d], float(r["u_" + axis])))
    if friction:
        pairs.append(("friction_coefficient", values["friction_coefficient"][i, 0],
                      float(r["mu"])))
        if dim == 2:
            # The tangent t = (1, 0) on a bottom face, the scene's Gamma_3.
            pairs.append(("friction_traction", values["friction_traction"][i, 0],
                          float(r["tangential_traction"])))
        state = r["state"]
    else:
        state = "contact" if float(r["normal_pressure"]) > 0 else "free"
    return pairs, state


def check_surface_against_csv(pvtu, csv_path, time, values, distinct, facts):
    """Node by node against the contact CSV @p csv_path of the same step."""
    codes = values["contact_state"][:, 0]
    rows = read_csv(csv_path)
    check(all(float(r["time"]) == time for r in rows),
          "%s: the time column is %r" % (os.path.basename(csv_path), time))
    dim = 3 if "z" in rows[0] else 2
    friction = "mu" in rows[0]
    # The points that are not nodes of the contact laws (the clamped ends
    # of Gamma_3): no contact quantity.
    nodes = {node_of(r) for r in rows}
    others = [i for k, i in distinct.items() if k not in nodes]
    facts.setdefault("surface points that are not contact nodes", set()).add(len(others))
    for key in ("normal_pressure", "penetration", "friction_traction", "slip_velocity",
                "friction_coefficient", "contact_state"):
        check(all(np.all(values[key][i] == 0) for i in others),
              "%s: %s is 0 at the points that are not nodes" % (pvtu, key))
    worst = {}
    for r in rows:
        x = node_of(r)
        i = distinct.get(x)
        if i is None:
            check(False, "%s: no surface point at the node %s" % (pvtu, x))
            continue
        pairs, state = node_pairs(r, i, values, dim, friction)
        check(int(codes[i]) == STATE_CODES[state],
              "%s: state code %d at %s, the CSV says %s" % (pvtu, codes[i], x, state))
        for key, a, b in pairs:
            worst.setdefault(key, [0.0, 0.0])
            worst[key][0] = max(worst[key][0], abs(a - b))
            worst[key][1] = max(worst[key][1], abs(b))
    for key, (dev, scale) in worst.items():
        check(dev <= FLOAT32 * max(scale, 1e-30),
              "%s: %s equals the contact CSV (%g of %g)" % (pvtu, key, dev, scale))
    facts["surface steps checked against the CSV"] = \
        facts.get("surface steps checked against the CSV", 0) + 1


def check_surface(directory, pvtu, time, step, facts):
    values, distinct = read_surface(directory, pvtu, time, step, facts)
    codes = values["contact_state"][:, 0]
    check(np.all(codes == np.round(codes)) and np.all(np.isin(codes, [0, 1, 2, 3])),
          "%s: the states are the codes 0, 1, 2, 3" % pvtu)
    facts.setdefault("state codes", set()).update(int(c) for c in codes)

    # Node by node against the contact CSV of the same step.
    csv_path = os.path.join(directory, "contact_%05d.csv" % step)
    if not os.path.exists(csv_path):
        # A step without a contact CSV: the nodes of the initial mesh, if
        # the mesh does not change (time_series.csv: the same cells).
        series = read_csv(os.path.join(directory, "time_series.csv"))
        if len({r["cells"] for r in series}) == 1:
            rows = read_csv(os.path.join(directory, "contact_00000.csv"))
            check({node_of(r) for r in rows} <= set(distinct),
                  "%s: a point at every node of Gamma_3" % pvtu)
        return
    check_surface_against_csv(pvtu, csv_path, time, values, distinct, facts)


def main():
    directory = sys.argv[1]
    print("%s:" % os.path.basename(os.path.normpath(directory)))
    solution = read_pvd(os.path.join(directory, "solution.pvd"))
    surface = read_pvd(os.path.join(directory, "contact_surface.pvd"))
    check([t for t, _ in solution] == [t for t, _ in surface],
          "contact_surface.pvd has the times of solution.pvd")
    n_nodes = len(read_csv(os.path.join(directory, "contact_00000.csv")))
    facts = {}
    steps = []
    for (time, pvtu), (time_s, surface_pvtu) in zip(solution, surface):
        step = int(re.search(r"_(\d+)\.pvtu$", pvtu).group(1))
        check(surface_pvtu == "contact_surface_%05d.pvtu" % step,
              "%s beside %s" % (surface_pvtu, pvtu))
        steps.append("%d (t = %.10g)" % (step, time))
        check_solution(directory, pvtu, time, step, facts)
        check_surface(directory, surface_pvtu, time, step, facts)
    # Nothing written that the indexes do not list.
    listed = {f for _, f in solution} | {f for _, f in surface}
    on_disk = {os.path.basename(p) for p in glob.glob(os.path.join(directory, "*.pvtu"))}
    check(on_disk == listed, "every .pvtu is in its .pvd")

    print("  VTU steps: " + ", ".join(steps))
    print("  contact_surface.pvd: the same times")
    for key in sorted(facts):
        value = facts[key]
        if isinstance(value, set):
            value = ", ".join(str(v) for v in sorted(value))
        print("  %s: %s" % (key, value))
    print("  Gamma_3 nodes (contact_00000.csv rows): %d" % n_nodes)
    print("  %s" % ("all checks passed" if not failures else "%d checks FAILED" % len(failures)))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
