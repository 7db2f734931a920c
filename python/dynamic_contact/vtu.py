"""Minimal reader for the VTK XML unstructured-grid files deal.II writes.

Handles exactly what DataOut::write_vtu / write_pvtu_record produce:

- .vtu files (VTKFile type="UnstructuredGrid") with DataArrays in format
  "binary" (base64), optionally compressed with vtkZLibDataCompressor, or
  in format "ascii";
- the header of a binary DataArray in UInt32 (the default) or UInt64
  (attribute header_type of VTKFile);
- .pvtu records (type="PUnstructuredGrid"): the pieces are read and
  concatenated (point and cell indices of later pieces are shifted);
- the FieldData TIME and CYCLE (the time and the step the program writes
  into every piece).

Only numpy, zlib, base64 and xml.etree: no dependency on VTK or meshio.
"Appended" data (format="appended") is not supported (deal.II does not
write it) and raises an error. The same reader reads the surface output of
Gamma_3 (contact_surface_NNNNN.pvtu, if the program writes it).

    from dynamic_contact.vtu import read_vtu, read_pvd
    mesh = read_vtu("solution_00026.pvtu")
    mesh.points            # (n_points, 3) float array
    mesh.point_data["displacement"]   # (n_points, 3)
    mesh.point_data["stress"]         # (n_points, 9): the 3x3 tensor, row by row
    mesh.time, mesh.step              # TIME and CYCLE (None if absent)
    mesh.connectivity, mesh.offsets, mesh.types
    mesh.cells()           # list of point-index arrays, one per cell
"""

import base64
import os
import xml.etree.ElementTree as ET
import zlib

import numpy as np

_DTYPES = {
    "Int8": "i1", "UInt8": "u1",
    "Int16": "i2", "UInt16": "u2",
    "Int32": "i4", "UInt32": "u4",
    "Int64": "i8", "UInt64": "u8",
    "Float32": "f4", "Float64": "f8",
}


class UnstructuredGrid:
    """Points, cells (VTK connectivity/offsets/types) and point/cell data."""

    def __init__(self, points, connectivity, offsets, types,
                 point_data, cell_data, field_data=None):
        self.points = points
        self.connectivity = connectivity
        self.offsets = offsets
        self.types = types
        self.point_data = point_data
        self.cell_data = cell_data
        self.field_data = field_data or {}

    @property
    def time(self):
        """The time the file carries (FieldData TIME), or None."""
        t = self.field_data.get("TIME")
        return None if t is None else float(np.ravel(t)[0])

    @property
    def step(self):
        """The step the file carries (FieldData CYCLE), or None."""
        c = self.field_data.get("CYCLE")
        return None if c is None else int(np.ravel(c)[0])

    @property
    def n_points(self):
        return self.points.shape[0]

    @property
    def n_cells(self):
        return self.offsets.shape[0]

    def cells(self):
        starts = np.concatenate(([0], self.offsets[:-1]))
        return [self.connectivity[s:e] for s, e in zip(starts, self.offsets)]

    def cell_array(self):
        """(n_cells, n_vertices) array if all cells have the same size."""
        sizes = np.diff(np.concatenate(([0], self.offsets)))
        if sizes.size == 0:
            return np.zeros((0, 0), dtype=np.int64)
        if not np.all(sizes == sizes[0]):
            raise ValueError("cells of different sizes")
        return self.connectivity.reshape(-1, int(sizes[0]))


def _decode_binary(text, dtype, header_dtype, compressed):
    """Decode the text of a DataArray with format="binary"."""
    text = "".join(text.split())
    hsize = np.dtype(header_dtype).itemsize
    if not compressed:
        # One base64 stream: [byte count][raw data].
        raw = base64.b64decode(text)
        nbytes = int(np.frombuffer(raw[:hsize], dtype=header_dtype)[0])
        data = raw[hsize:hsize + nbytes]
        if len(data) != nbytes:
            raise ValueError("binary DataArray shorter than its header says")
        return np.frombuffer(data, dtype=dtype)

    # vtkZLibDataCompressor: header [n_blocks, block_size, last_block_size,
    # compressed_size_1 .. compressed_size_n] base64-encoded on its own,
    # followed by the base64 encoding of the concatenated zlib blocks.
    first = base64.b64decode(text[:4 * ((hsize + 2) // 3)])
    n_blocks = int(np.frombuffer(first[:hsize], dtype=header_dtype)[0])
    header_bytes = (3 + n_blocks) * hsize
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = np.frombuffer(base64.b64decode(text[:header_chars])[:header_bytes],
                           dtype=header_dtype).astype(np.int64)
    block_size, last_size = int(header[1]), int(header[2])
    comp_sizes = header[3:]
    payload = base64.b64decode(text[header_chars:])
    if len(payload) < int(comp_sizes.sum()):
        # Some writers encode header and data as one base64 stream.
        whole = base64.b64decode(text)
        payload = whole[header_bytes:]
    if len(payload) < int(comp_sizes.sum()):
        raise ValueError("compressed DataArray shorter than its header says")
    chunks = []
    pos = 0
    for i, size in enumerate(comp_sizes):
        size = int(size)
        block = zlib.decompress(payload[pos:pos + size])
        pos += size
        expected = last_size if (i == n_blocks - 1 and last_size) else block_size
        if len(block) != expected:
            raise ValueError("zlib block %d: %d bytes, expected %d"
                             % (i, len(block), expected))
        chunks.append(block)
    return np.frombuffer(b"".join(chunks), dtype=dtype)


def _read_data_array(elem, header_dtype, compressed):
    vtype = elem.get("type")
    if vtype not in _DTYPES:
        raise ValueError("unsupported DataArray type %r" % vtype)
    dtype = np.dtype(_DTYPES[vtype]).newbyteorder("<")
    fmt = elem.get("format", "ascii")
    text = elem.text or ""
    if fmt == "ascii":
        values = np.array(text.split(), dtype=np.float64).astype(dtype)
    elif fmt == "binary":
        values = _decode_binary(text, dtype, header_dtype, compressed)
    else:
        raise ValueError("DataArray format %r not supported" % fmt)
    ncomp = int(elem.get("NumberOfComponents", "1"))
    if ncomp > 1:
        values = values.reshape(-1, ncomp)
    return values.astype(values.dtype.newbyteorder("="))


def _read_piece_file(path):
    root = ET.parse(path).getroot()
    if root.get("type") != "UnstructuredGrid":
        raise ValueError("%s: not a VTK UnstructuredGrid file" % path)
    if root.get("byte_order", "LittleEndian") != "LittleEndian":
        raise ValueError("%s: only little-endian files are supported" % path)
    compressor = root.get("compressor", "")
    if compressor not in ("", "vtkZLibDataCompressor"):
        raise ValueError("%s: unsupported compressor %r" % (path, compressor))
    compressed = compressor == "vtkZLibDataCompressor"
    header_dtype = np.dtype(_DTYPES[root.get("header_type", "UInt32")]
                            ).newbyteorder("<")

    def arrays(element):
        """The DataArrays under `element` (which may be None), by name."""
        if element is None:
            return {}
        return {da.get("Name"): _read_data_array(da, header_dtype, compressed)
                for da in element.findall("DataArray")}

    grid = root.find("UnstructuredGrid")
    field_data = arrays(grid.find("FieldData"))
    pieces = []
    for piece in grid.findall("Piece"):
        n_points = int(piece.get("NumberOfPoints"))
        n_cells = int(piece.get("NumberOfCells"))
        points = _read_data_array(piece.find("Points/DataArray"),
                                  header_dtype, compressed)
        points = points.reshape(n_points, -1 if n_points else 3).astype(np.float64)
        cells = arrays(piece.find("Cells"))
        point_data = arrays(piece.find("PointData"))
        cell_data = arrays(piece.find("CellData"))
        offsets = cells["offsets"].astype(np.int64)
        if offsets.shape[0] != n_cells:
            raise ValueError("%s: %d offsets for %d cells"
                             % (path, offsets.shape[0], n_cells))
        pieces.append(UnstructuredGrid(
            points, cells["connectivity"].astype(np.int64), offsets,
            cells["types"].astype(np.int64), point_data, cell_data,
            field_data))
    return pieces


def _merge(pieces):
    if len(pieces) == 1:
        return pieces[0]
    points, conn, offs, types = [], [], [], []
    pshift, cshift = 0, 0
    names_p = set(pieces[0].point_data)
    names_c = set(pieces[0].cell_data)
    for p in pieces:
        points.append(p.points)
        conn.append(p.connectivity + pshift)
        offs.append(p.offsets + cshift)
        types.append(p.types)
        pshift += p.n_points
        cshift += p.connectivity.shape[0]
        names_p &= set(p.point_data)
        names_c &= set(p.cell_data)
    point_data = {n: np.concatenate([p.point_data[n] for p in pieces])
                  for n in names_p}
    cell_data = {n: np.concatenate([p.cell_data[n] for p in pieces])
                 for n in names_c}
    return UnstructuredGrid(np.concatenate(points), np.concatenate(conn),
                            np.concatenate(offs), np.concatenate(types),
                            point_data, cell_data, pieces[0].field_data)


def read_vtu(path):
    """Read a .vtu file or a .pvtu record (all its pieces) into one grid."""
    root = ET.parse(path).getroot()
    kind = root.get("type")
    if kind == "UnstructuredGrid":
        return _merge(_read_piece_file(path))
    if kind == "PUnstructuredGrid":
        base = os.path.dirname(path)
        pieces = []
        for piece in root.find("PUnstructuredGrid").findall("Piece"):
            pieces.extend(_read_piece_file(os.path.join(base,
                                                        piece.get("Source"))))
        if not pieces:
            raise ValueError("%s: no pieces" % path)
        return _merge(pieces)
    raise ValueError("%s: VTKFile type %r is not supported" % (path, kind))


def read_pvd(path):
    """The (time, file) pairs of a .pvd collection, sorted by time."""
    root = ET.parse(path).getroot()
    base = os.path.dirname(path)
    out = [(float(ds.get("timestep")), os.path.join(base, ds.get("file")))
           for ds in root.iter("DataSet")]
    return sorted(out)
