"""PLY: a reader for ASCII and binary files, a binary little-endian writer.

Reading keeps the ``x``, ``y``, ``z`` properties of element ``vertex``, the
``vertex_indices`` list (or ``vertex_index``, else the first list) of element
``face`` and its ``red``, ``green``, ``blue`` (face colours: integers scaled from
their type's range, floats taken in ``[0, 1]``); every other element and
property is skipped. Binary elements whose
rows all have one layout are read with whole-array numpy steps, others row by
row (:mod:`._ply_binary`). ASCII elements laid out one row per line, as exporters
write them, are parsed in blocks of lines by the OBJ reader's vectorized parsers
(see :mod:`._lines`); any other layout, and every error, goes token by token
(:mod:`._ply_ascii`). :mod:`._ply_layout` parses the header.

Writing gives polygons as they are, holes left out, with ``uchar`` face colours
when the mesh has any (a face without one gets the modelling colour).
"""

from __future__ import annotations

import os
from dataclasses import dataclass

import numpy as np

from ..arrays import mesh_arrays
from ..build import from_polygons, point_cloud
from ..mesh import Mesh
from ..soup import offsets_of
from ._colors import face_rgb8, rgb_from_channels
from ._ply_ascii import _AsciiBody
from ._ply_binary import _BinaryBody
from ._ply_layout import _Header, _parse_header, _Table
from .atomic import write_atomically
from .source import file_error, read_source, show_path


def write_ply(mesh: Mesh, path: str | os.PathLike[str]) -> None:
    """Write ``mesh`` as binary little-endian PLY, atomically.

    Vertices as ``double x, y, z`` in id order (point-spheres included, so ids
    map to PLY indices); one polygon per face that is not a hole and not a
    point-sphere, from its head corner, as ``list uchar int`` (``list uint
    int`` when a face has more than 255 corners), followed by ``uchar red,
    green, blue`` when the mesh has face colours.

    Raises:
        OSError: the file cannot be written; an existing file is left intact.
    """
    data = ply_bytes(mesh)
    write_atomically(path, data)


def ply_bytes(mesh: Mesh) -> bytes:
    """The binary PLY of ``mesh`` (see :func:`write_ply`)."""
    a = mesh_arrays(mesh)
    sizes, indices = a.surface_polygons()
    rgb = face_rgb8(a)
    if rgb is not None:
        rgb = rgb[a.face_is_surface]
    count_type = "uchar" if len(sizes) == 0 or sizes.max() <= 255 else "uint"
    header = "\n".join([
        "ply", "format binary_little_endian 1.0", "comment written by livemod",
        f"element vertex {len(a.positions)}",
        "property double x", "property double y", "property double z",
        f"element face {len(sizes)}",
        f"property list {count_type} int vertex_indices",
        *([] if rgb is None else [f"property uchar {c}" for c in ("red", "green", "blue")]),
        "end_header", "",
    ]).encode()
    vertices = np.ascontiguousarray(a.positions, dtype="<f8").tobytes()
    return header + vertices + _face_records(sizes, indices, count_type, rgb)


def _face_records(sizes: np.ndarray, indices: np.ndarray, count_type: str,
                  rgb: np.ndarray | None = None) -> bytes:
    """Each face as its corner count followed by its ``int32`` vertex indices and,
    given ``(F, 3)`` uint8 ``rgb``, its colour."""
    count_bytes = 1 if count_type == "uchar" else 4
    tail = 0 if rgb is None else 3
    record_sizes = count_bytes + 4 * sizes + tail
    starts = np.cumsum(record_sizes) - record_sizes
    out = np.empty(int(record_sizes.sum()), dtype=np.uint8)
    is_count = np.zeros(len(out), dtype=bool)
    count_pos = starts[:, None] + np.arange(count_bytes)
    is_count[count_pos] = True
    counts = sizes.astype("<u1" if count_bytes == 1 else "<u4")
    out[count_pos.ravel()] = counts.view(np.uint8)
    if rgb is not None:
        color_pos = (starts + record_sizes - tail)[:, None] + np.arange(tail)
        is_count[color_pos] = True
        out[color_pos.ravel()] = rgb.ravel()
    out[~is_count] = indices.astype("<i4").view(np.uint8)
    return out.tobytes()


# ---------------------------------------------------------------------- reader


@dataclass
class PlySoup:
    """What a PLY file holds.

    Attributes:
        positions: ``(V, 3)`` float64, one row per ``vertex`` row.
        indices: ``(C,)`` int64 0-based vertex index of every face corner.
        offsets: ``(F + 1,)`` int64 face start offsets into ``indices`` (``[0]``
            when the file has no ``face`` element or no face rows).
        face_colors: ``(F, 3)`` float32 in ``[0, 1]`` from the faces' ``red``,
            ``green``, ``blue``, or None when they have none.
    """

    positions: np.ndarray
    indices: np.ndarray
    offsets: np.ndarray
    face_colors: np.ndarray | None = None


@dataclass(frozen=True)
class _Roles:
    """Which element and properties the mesh comes from (indices into the header)."""

    vertex: int
    xyz: tuple[int, int, int]
    face: int | None
    corners: int | None  # the face element's list of vertex indices
    rgb: tuple[int, int, int] | None = None  # the face element's red, green, blue


def read_ply(source: str | os.PathLike[str] | bytes, *, name: str | None = None) -> Mesh:
    """Load an ASCII or binary (either byte order) PLY file into a mesh.

    Args:
        source: a path, or the file contents as bytes.
        name: the file name to use in messages (default: the path, or ``<ply>``).

    Returns:
        The mesh; face ``i`` is the ``i``-th ``face`` row, vertex ``j`` the
        ``j``-th ``vertex`` row. Open boundaries get hole faces, unused vertices
        become point-spheres (all of them when there are no faces).

    Raises:
        DLFLError: ``file: ...`` for a malformed header, a file that ends inside
            an element, a bad number or list count, a coordinate that is not
            finite, a vertex index out of range, or a mesh that is not an
            orientable 2-manifold (from :func:`livemod.dlfl.from_polygons`).
        OSError: the file cannot be read.
    """
    data, label = read_source(source, name, "<ply>")
    soup = parse_ply(data, label)
    if len(soup.offsets) == 1:
        return point_cloud(soup.positions)
    return from_polygons(soup.positions, soup.indices, soup.offsets, source=show_path(label),
                         face_colors=soup.face_colors)


def parse_ply(data: bytes, label: str = "<ply>") -> PlySoup:
    """Parse PLY bytes into a polygon soup (see :class:`PlySoup`).

    Raises:
        DLFLError: ``label: ...`` for anything malformed (see :func:`read_ply`).
    """
    header = _parse_header(data, label)
    roles = _roles(header, label)
    wanted = {roles.vertex: set(roles.xyz)}
    if roles.face is not None and roles.corners is not None:
        wanted[roles.face] = {roles.corners, *(roles.rgb or ())}
    body: _BinaryBody | _AsciiBody
    if header.encoding == "ascii":
        body = _AsciiBody(data[header.body_start :], label, header.body_line)
    else:
        body = _BinaryBody(data, header.body_start, header.encoding, label)
    tables = [body.element(e, wanted.get(i, set())) for i, e in enumerate(header.elements)]
    try:
        positions = _positions(tables[roles.vertex], roles.xyz, roles.vertex)
        if roles.face is None or roles.corners is None:
            return PlySoup(positions, np.zeros(0, dtype=np.int64), np.zeros(1, dtype=np.int64))
        counts, items = tables[roles.face].lists[roles.corners]
        offsets = offsets_of(counts)
        indices = _vertex_indices(items, offsets, len(positions), roles.face)
    except _RowProblem as problem:
        line = body.line_of_row(problem.element, problem.row)
        raise file_error(label, line, str(problem)) from None
    colors = None
    if roles.rgb is not None:
        properties = header.elements[roles.face].properties
        colors = rgb_from_channels([tables[roles.face].scalars[i] for i in roles.rgb],
                                   [properties[i].code for i in roles.rgb])
    return PlySoup(positions, indices, offsets, colors)


def _roles(header: _Header, label: str) -> _Roles:
    """Find ``vertex`` with its x, y, z and ``face`` with its index list.

    Raises:
        FileFormatError: no ``vertex`` element (naming the ``end_header``
            line), a missing coordinate, or a ``face`` element without a list
            property (naming the element's line).
    """
    names = [e.name for e in header.elements]
    if "vertex" not in names:
        raise file_error(label, header.body_line - 1, "no 'vertex' element before end_header")
    vertex = names.index("vertex")
    element = header.elements[vertex]
    scalars = [p.name if p.count_code is None else None for p in element.properties]
    for axis in "xyz":
        if axis not in scalars:
            raise file_error(label, element.line, f"element 'vertex' has no property '{axis}'")
    xyz = (scalars.index("x"), scalars.index("y"), scalars.index("z"))
    if "face" not in names:
        return _Roles(vertex, xyz, None, None)
    face = names.index("face")
    lists = [p.name if p.count_code else None for p in header.elements[face].properties]
    named = [n for n in ("vertex_indices", "vertex_index") if n in lists]
    if not named and not any(lists):
        raise file_error(label, header.elements[face].line,
                         "element 'face' has no list property (vertex_indices)")
    corners = lists.index(named[0]) if named else next(i for i, n in enumerate(lists) if n)
    face_scalars = [p.name if p.count_code is None else None
                    for p in header.elements[face].properties]
    rgb = None
    if all(c in face_scalars for c in ("red", "green", "blue")):
        rgb = (face_scalars.index("red"), face_scalars.index("green"), face_scalars.index("blue"))
    return _Roles(vertex, xyz, face, corners, rgb)


class _RowProblem(Exception):
    """What is wrong with row ``row`` of element ``element`` (an index into the
    header's elements); :func:`parse_ply` adds the file and the line."""

    def __init__(self, element: int, row: int, what: str) -> None:
        super().__init__(what)
        self.element, self.row = element, row


# ---------------------------------------------------------------------- mesh data


def _positions(table: _Table, xyz: tuple[int, int, int], element: int) -> np.ndarray:
    """``(V, 3)`` float64 from the x, y, z columns of ``element`` (its index).

    Raises:
        _RowProblem: a NaN or infinite coordinate.
    """
    positions = np.stack([table.scalars[i] for i in xyz], axis=1).astype(np.float64)
    finite = np.isfinite(positions)
    if not finite.all():
        v, axis = (int(k) for k in np.argwhere(~finite)[0])
        value = float(positions[v, axis])
        raise _RowProblem(element, v, f"vertex {v}: coordinate {value} is not finite")
    return positions


def _vertex_indices(items: np.ndarray, offsets: np.ndarray, num_vertices: int,
                    element: int) -> np.ndarray:
    """``(C,)`` int64 corner vertex indices from the face lists' ``(C,)`` items.

    Raises:
        _RowProblem: ``face f: ...`` for an index that is not a whole number
            (ASCII or float items) or not in ``[0, num_vertices)``.
    """
    whole = np.ones(len(items), dtype=bool)
    if items.dtype.kind == "f":
        whole = np.isfinite(items) & (items == np.floor(items))
    bad = ~whole | (items < 0) | (items >= num_vertices)
    if not bad.any():
        return items.astype(np.int64)
    c = int(np.flatnonzero(bad)[0])
    face = int(np.searchsorted(offsets, c, side="right")) - 1
    if not whole[c]:
        raise _RowProblem(element, face, f"face {face}: vertex index {items[c]} is not a "
                          "whole number")
    raise _RowProblem(element, face, f"face {face}: vertex index {int(items[c])} is out of "
                      f"range ({num_vertices} vertices)")
