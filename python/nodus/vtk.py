"""Reading nodus's VTK files (DIR/vtk/step_NNNNNN.vtp, contact_NNNNNN.vtp) into numpy arrays, without VTK.

    from nodus.vtk import read_vtp
    picture = read_vtp("out/vtk/step_000010.vtp")
    picture.points                  # (points, 3) [mm]: the node centres first, then the tube rings
    picture.point_data["g1"]        # (points, 3)
    picture.cell_data               # {} for the beams; kind, zone, normal_force, ... for contact files
    picture.time                    # load time [s], or None

Both encodings of output.vtk_format are read: binary (zlib-compressed appended arrays, header_type UInt64, as
VTK's own writer makes them) and ascii. Units and the meaning of each array: docs/output.md.
"""

import struct
import xml.etree.ElementTree as ET
import zlib
from dataclasses import dataclass, field

import numpy as np

_TYPES = {"Float64": "<f8", "Float32": "<f4", "Int64": "<i8", "Int32": "<i4", "UInt64": "<u8", "UInt8": "u1"}


@dataclass
class Picture:
    """The arrays of one VTK PolyData file."""

    points: np.ndarray
    point_data: dict = field(default_factory=dict)
    cell_data: dict = field(default_factory=dict)
    lines: dict = field(default_factory=dict)  # {"connectivity": ..., "offsets": ...}; empty without lines
    polys: dict = field(default_factory=dict)
    time: float = None


def _appended_values(appended, offset, dtype):
    """The values of the compressed appended array at `offset`: UInt64 header [blocks, block size, last block
    size or 0, compressed sizes], then the zlib-compressed blocks."""
    blocks, block_size, last_size = struct.unpack_from("<3Q", appended, offset)
    sizes = struct.unpack_from(f"<{blocks}Q", appended, offset + 24)
    at = offset + 24 + 8 * blocks
    chunks = []
    for b, size in enumerate(sizes):
        chunk = zlib.decompress(appended[at:at + size])
        expected = last_size if b == blocks - 1 and last_size else block_size
        if len(chunk) != expected:
            raise ValueError(f"appended block {b} holds {len(chunk)} bytes, its header says {expected}")
        chunks.append(chunk)
        at += size
    return np.frombuffer(b"".join(chunks), dtype=dtype)


def read_vtp(path):
    """The Picture of VTK PolyData file `path` (binary or ascii). Raises ValueError on a file it cannot read."""
    with open(path, "rb") as f:
        raw = f.read()
    appended = b""
    start = raw.find(b'<AppendedData encoding="raw">')
    if start >= 0:
        underscore = raw.index(b"_", start)
        end = raw.rindex(b"</AppendedData>")
        appended = raw[underscore + 1:end]
        raw = raw[:start] + raw[end + len(b"</AppendedData>"):]
    root = ET.fromstring(raw)
    if root.get("type") != "PolyData":
        raise ValueError(f"{path}: expected a VTK PolyData file, got type {root.get('type')}")
    if appended and (root.get("header_type") != "UInt64" or root.get("compressor") != "vtkZLibDataCompressor"):
        raise ValueError(f"{path}: expected header_type UInt64 and compressor vtkZLibDataCompressor")

    def values(array):
        dtype = _TYPES[array.get("type")]
        if array.get("format") == "appended":
            data = _appended_values(appended, int(array.get("offset")), dtype)
        else:
            data = np.array((array.text or "").split(), dtype=dtype)
        components = int(array.get("NumberOfComponents", "1"))
        return data.reshape(-1, components) if components > 1 else data

    def arrays(element):
        return {} if element is None else {a.get("Name"): values(a) for a in element.iter("DataArray")}

    poly = root.find("PolyData")
    piece = poly.find("Piece")
    time = None
    field_data = poly.find("FieldData")
    if field_data is not None:
        for a in field_data.iter("DataArray"):
            if a.get("Name") == "TimeValue":
                time = float(values(a)[0])
    points = arrays(piece.find("Points")).get("Points", np.zeros((0, 3)))
    return Picture(points=np.asarray(points).reshape(-1, 3), point_data=arrays(piece.find("PointData")),
                   cell_data=arrays(piece.find("CellData")), lines=arrays(piece.find("Lines")),
                   polys=arrays(piece.find("Polys")), time=time)
