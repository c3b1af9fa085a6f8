"""glTF 2.0: a writer of ``.gltf`` (JSON beside a ``.bin`` buffer) and ``.glb``.

Each object is one node with one mesh of one triangle primitive: the drawn
faces (not holes, three corners or more) as fans from their head corners, a
vertex per face corner (so a face's normal and colour stay its own), with
``POSITION``, ``NORMAL`` (the face's normal by default, the vertex's area-weighted
normal with ``smooth=True``), optional ``COLOR_0`` (the face's colour) and
``uint32`` indices. The buffers are written with whole-array numpy steps: a
1,000,000-quad mesh is about 120 MB of buffer.
"""

from __future__ import annotations

import json
import os
import struct
from collections.abc import Iterator

import numpy as np

from ._float32 import check_float32_range
from ._scene_out import Objects, Part, drawn_faces, parts
from .atomic import write_atomically
from .source import companion_path

_FLOAT, _UBYTE, _UINT = 5126, 5121, 5125  # glTF componentType codes
_ARRAY_BUFFER, _ELEMENT_ARRAY_BUFFER = 34962, 34963
_TRIANGLES = 4


def write_gltf(objects: Objects, path: str | os.PathLike[str], *, smooth: bool = False,
               face_colors: object = None) -> None:
    """Write objects as glTF 2.0, atomically: ``.glb`` (one binary file) or
    ``.gltf`` (JSON naming a ``<stem>.bin`` beside it, written first).

    Args:
        objects: a mesh, or ``(name, mesh)`` pairs (one node each).
        path: the target; its extension picks the form.
        smooth: averaged vertex normals instead of each face's own.
        face_colors: see :func:`._scene_out.parts` (written as ``COLOR_0``).

    Raises:
        InvalidArgumentError: no object, or colours of the wrong shape or range.
        GeometryError: a coordinate beyond float32's range (about 3.4e38), which
            glTF cannot hold; nothing is written.
        OSError: a file cannot be written; existing files are left intact.
    """
    name = os.fspath(path)
    if name.lower().endswith(".glb"):
        write_glb(objects, name, smooth=smooth, face_colors=face_colors)
        return
    buffer = companion_path(name, ".bin")
    document, chunks = gltf_document(objects, smooth=smooth, face_colors=face_colors,
                                     uri=os.path.basename(buffer))
    write_atomically(buffer, chunks)
    write_atomically(name, json.dumps(document, indent=1).encode())


def write_glb(objects: Objects, path: str | os.PathLike[str], *, smooth: bool = False,
              face_colors: object = None) -> None:
    """:func:`write_gltf` as ``.glb`` whatever ``path``'s extension (a temporary
    name, say)."""
    write_atomically(os.fspath(path), glb_pieces(objects, smooth=smooth,
                                                 face_colors=face_colors))


def glb_bytes(objects: Objects, *, smooth: bool = False, face_colors: object = None) -> bytes:
    """The ``.glb`` of ``objects`` (see :func:`write_gltf`)."""
    return b"".join(glb_pieces(objects, smooth=smooth, face_colors=face_colors))


def glb_pieces(objects: Objects, *, smooth: bool = False, face_colors: object = None,
               ) -> Iterator[bytes | memoryview]:
    """The ``.glb`` in pieces: header, JSON chunk, then the buffer's arrays."""
    document, chunks = gltf_document(objects, smooth=smooth, face_colors=face_colors)
    text = json.dumps(document, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    size = document["buffers"][0]["byteLength"]
    yield struct.pack("<4sII", b"glTF", 2, 12 + 8 + len(text) + 8 + size)
    yield struct.pack("<I4s", len(text), b"JSON") + text
    yield struct.pack("<I4s", size, b"BIN\0")
    yield from chunks


def gltf_document(objects: Objects, *, smooth: bool = False, face_colors: object = None,
                  uri: str | None = None) -> tuple[dict, list[memoryview]]:
    """The glTF JSON document and the buffer's pieces (each a multiple of 4 bytes).

    Args:
        uri: the buffer's file (``.gltf``); None for the GLB's own chunk.
    """
    doc: dict = {"asset": {"version": "2.0", "generator": "livemod"}, "scene": 0,
                 "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "accessors": [],
                 "bufferViews": []}
    chunks: list[memoryview] = []
    offset = 0
    for part in parts(objects, face_colors):
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]))
        node: dict = {"name": part.name}
        doc["nodes"].append(node)
        if len(part.triangles) == 0:  # glTF has no empty accessor: a node alone
            continue
        node["mesh"] = len(doc["meshes"])
        attributes: dict[str, int] = {}
        for key, array, bounds in _vertex_arrays(part, smooth):
            attributes[key] = _add_view(doc, chunks, array, offset, _ARRAY_BUFFER, bounds)
            offset += array.nbytes
        indices = part.triangles.astype("<u4").ravel()
        index = _add_view(doc, chunks, indices, offset, _ELEMENT_ARRAY_BUFFER)
        offset += indices.nbytes
        doc["meshes"].append({"name": part.name, "primitives": [
            {"attributes": attributes, "indices": index, "mode": _TRIANGLES}]})
    doc["buffers"] = [{"byteLength": offset} | ({"uri": uri} if uri else {})]
    return doc, chunks


_Bounds = tuple[np.ndarray, np.ndarray] | None  # an accessor's (min, max), where it has them


def _vertex_arrays(part: Part, smooth: bool) -> Iterator[tuple[str, np.ndarray, _Bounds]]:
    """``(attribute, (K, n) array, its (min, max) or None)`` of every vertex
    attribute of ``part``: a vertex per written corner."""
    a = part.arrays
    vertex_of = a.corner_vertex[part.corners]
    # float32 first: a gather of 12-byte rows, and min/max of the vertices used
    # (each once) equal to those of the written rows, as glTF asks
    check_float32_range(a.positions, "glTF")
    positions = a.positions.astype("<f4")
    used = np.zeros(len(positions), dtype=bool)
    used[vertex_of] = True
    written = positions if used.all() else positions[used]
    yield "POSITION", positions[vertex_of], (written.min(axis=0), written.max(axis=0))
    yield "NORMAL", _normals(part, vertex_of, smooth), None
    if part.rgba is not None:
        yield "COLOR_0", part.rgba[a.corner_face[part.corners]], None


def _normals(part: Part, vertex_of: np.ndarray, smooth: bool) -> np.ndarray:
    """``(K, 3)`` float32 unit normal of each written vertex: its face's vector area
    made unit, or with ``smooth`` the sum of the vector areas of the faces round
    its vertex. A zero sum (no area) gets +z: glTF asks for unit normals."""
    sizes = part.arrays.face_sizes[drawn_faces(part.arrays)]
    faces = _face_areas(part.arrays.positions, vertex_of, sizes)
    if smooth:
        around = _sum_rows(vertex_of, np.repeat(faces, sizes, axis=0), len(part.arrays.positions))
        return _unit(around)[vertex_of]
    return np.repeat(_unit(faces), sizes, axis=0)


def _face_areas(positions: np.ndarray, vertex_of: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """``(D, 3)`` float64 vector area (doubled) of each written face: its
    corners are ``vertex_of`` ``(K,)``, ``sizes`` ``(D,)`` a face, in order.

    Triangles and quads take one cross product (:func:`_small_areas`), larger
    faces sum their fan's triangles. Non-finite results (coordinates near the
    float maximum) are zero."""
    with np.errstate(invalid="ignore", over="ignore"):
        if len(sizes) and sizes[0] in (3, 4) and sizes.min() == sizes.max():
            # one size throughout (a quad or triangle mesh): its rows as they lie
            areas = _small_areas(positions, vertex_of.reshape(len(sizes), int(sizes[0])))
        else:
            areas = np.empty((len(sizes), 3))
            starts = np.cumsum(sizes) - sizes
            for size in (3, 4):
                faces = np.flatnonzero(sizes == size)
                ring = vertex_of[starts[faces][:, None] + np.arange(size)]
                areas[faces] = _small_areas(positions, ring)
            larger = np.flatnonzero(sizes > 4)
            areas[larger] = _fan_areas(positions, vertex_of, starts[larger], sizes[larger])
    areas[~np.isfinite(areas).all(axis=1)] = 0.0
    return areas


def _small_areas(positions: np.ndarray, rings: np.ndarray) -> np.ndarray:
    """``(n, 3)`` vector areas (doubled) of triangles or quads whose vertices are
    the rows of ``rings`` ``(n, 3)`` or ``(n, 4)``: a triangle's is the cross
    product of two sides, a quad's that of its diagonals (each equals the Newell
    sum and the sum of its fan's triangles)."""
    p = [np.take(positions, rings[:, k], axis=0) for k in range(rings.shape[1])]
    if rings.shape[1] == 3:
        return _cross(p[1] - p[0], p[2] - p[0])
    return _cross(p[2] - p[0], p[3] - p[1])


def _fan_areas(positions: np.ndarray, vertex_of: np.ndarray, starts: np.ndarray,
               sizes: np.ndarray) -> np.ndarray:
    """``(n, 3)`` sums of the fan triangles' area vectors (doubled) of the faces
    whose corners are ``vertex_of[starts[i] : starts[i] + sizes[i]]``."""
    count = sizes - 2
    face = np.repeat(np.arange(len(sizes)), count)
    step = np.arange(len(face)) - np.repeat(np.cumsum(count) - count, count)
    head = positions[vertex_of[starts[face]]]
    second = vertex_of[starts[face] + step + 1]
    u, v = positions[second] - head, positions[vertex_of[starts[face] + step + 2]] - head
    return _sum_rows(face, _cross(u, v), len(sizes))


def _cross(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Row-wise ``u x v`` of ``(N, 3)`` arrays (np.cross's temporaries cost more)."""
    out = np.empty_like(u)
    out[:, 0] = u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1]
    out[:, 1] = u[:, 2] * v[:, 0] - u[:, 0] * v[:, 2]
    out[:, 2] = u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]
    return out


def _sum_rows(owner: np.ndarray, rows: np.ndarray, count: int) -> np.ndarray:
    """``(count, 3)`` sums of the ``(N, 3)`` rows by their ``(N,)`` owner."""
    return np.stack([np.bincount(owner, rows[:, k], minlength=count) for k in range(3)], axis=1)


def _unit(vectors: np.ndarray) -> np.ndarray:
    """``vectors`` made unit as float32; +z where one is zero."""
    length = np.sqrt(np.einsum("ij,ij->i", vectors, vectors))[:, None]
    unit = np.divide(vectors, length, out=np.zeros_like(vectors), where=length > 0)
    unit[length[:, 0] == 0] = (0.0, 0.0, 1.0)
    return unit.astype("<f4")


_TYPES = {1: "SCALAR", 3: "VEC3", 4: "VEC4"}
_COMPONENTS = {np.dtype("<f4"): _FLOAT, np.dtype("u1"): _UBYTE, np.dtype("<u4"): _UINT}


def _add_view(doc: dict, chunks: list[memoryview], array: np.ndarray, offset: int,
              target: int, bounds: _Bounds = None) -> int:
    """Append ``array`` to the buffer as a view and an accessor (with ``bounds`` as
    its min and max); the accessor's index."""
    # every array a multiple of 4 bytes; its memory itself, not a copy
    chunks.append(np.ascontiguousarray(array).data.cast("B"))
    doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": array.nbytes,
                               "target": target})
    width = 1 if array.ndim == 1 else array.shape[1]
    accessor: dict = {"bufferView": len(doc["bufferViews"]) - 1, "count": len(array),
                      "componentType": _COMPONENTS[array.dtype], "type": _TYPES[width]}
    if array.dtype == np.uint8:
        accessor["normalized"] = True
    if bounds is not None:
        accessor["min"], accessor["max"] = bounds[0].tolist(), bounds[1].tolist()
    doc["accessors"].append(accessor)
    return len(doc["accessors"]) - 1
