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

from ._scene_out import Objects, Part, parts
from .atomic import write_atomically

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
        OSError: a file cannot be written; existing files are left intact.
    """
    name = os.fspath(path)
    if name.lower().endswith(".glb"):
        write_glb(objects, name, smooth=smooth, face_colors=face_colors)
        return
    stem = os.path.splitext(os.path.basename(name))[0] or "mesh"
    document, chunks = gltf_document(objects, smooth=smooth, face_colors=face_colors,
                                     uri=f"{stem}.bin")
    write_atomically(os.path.join(os.path.dirname(name), f"{stem}.bin"), chunks)
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
               ) -> Iterator[bytes]:
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
                  uri: str | None = None) -> tuple[dict, list[bytes]]:
    """The glTF JSON document and the buffer's pieces (each a multiple of 4 bytes).

    Args:
        uri: the buffer's file (``.gltf``); None for the GLB's own chunk.
    """
    doc: dict = {"asset": {"version": "2.0", "generator": "livemod"}, "scene": 0,
                 "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "accessors": [],
                 "bufferViews": []}
    chunks: list[bytes] = []
    offset = 0
    for part in parts(objects, face_colors):
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]))
        node: dict = {"name": part.name}
        doc["nodes"].append(node)
        if len(part.triangles) == 0:  # glTF has no empty accessor: a node alone
            continue
        node["mesh"] = len(doc["meshes"])
        attributes: dict[str, int] = {}
        for key, array in _vertex_arrays(part, smooth):
            attributes[key] = _add_view(doc, chunks, array, offset, _ARRAY_BUFFER)
            offset += array.nbytes
        indices = part.triangles.astype("<u4").ravel()
        index = _add_view(doc, chunks, indices, offset, _ELEMENT_ARRAY_BUFFER)
        offset += indices.nbytes
        doc["meshes"].append({"name": part.name, "primitives": [
            {"attributes": attributes, "indices": index, "mode": _TRIANGLES}]})
    doc["buffers"] = [{"byteLength": offset} | ({"uri": uri} if uri else {})]
    return doc, chunks


def _vertex_arrays(part: Part, smooth: bool) -> Iterator[tuple[str, np.ndarray]]:
    """``(attribute, (K, n) array)`` of every vertex attribute of ``part``."""
    a = part.arrays
    vertex_of = a.corner_vertex[part.corners]
    yield "POSITION", a.positions[vertex_of].astype("<f4")
    yield "NORMAL", _normals(part, vertex_of, smooth)
    if part.rgba is not None:
        yield "COLOR_0", part.rgba[a.corner_face[part.corners]]


def _normals(part: Part, vertex_of: np.ndarray, smooth: bool) -> np.ndarray:
    """``(K, 3)`` float32 unit normal of each written vertex: its face's vector area
    (the sum of the face's fan triangles' area vectors) made unit, or with
    ``smooth`` the sum of the vector areas of the faces round its vertex. A zero
    sum (no area) gets +z: glTF asks for unit normals."""
    p = part.arrays.positions
    tri = vertex_of[part.triangles]
    u, v = p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]]
    with np.errstate(invalid="ignore", over="ignore"):
        area = np.stack([u[:, 1] * v[:, 2] - u[:, 2] * v[:, 1],
                         u[:, 2] * v[:, 0] - u[:, 0] * v[:, 2],
                         u[:, 0] * v[:, 1] - u[:, 1] * v[:, 0]], axis=1)
    area[~np.isfinite(area).all(axis=1)] = 0.0
    # the written faces in order: each triangle's, and each written vertex's (corner's)
    face_of_triangle = _runs(part.faces)
    face_of_corner = _runs(part.arrays.corner_face[part.corners])
    faces = _sum_rows(face_of_triangle, area, int(face_of_corner[-1]) + 1 if len(tri) else 0)
    if smooth:
        return _unit(_sum_rows(vertex_of, faces[face_of_corner], len(p)))[vertex_of]
    return _unit(faces)[face_of_corner]


def _runs(keys: np.ndarray) -> np.ndarray:
    """``(N,)`` int64: the number of the run of equal ``keys`` each belongs to."""
    return np.cumsum(np.r_[True, keys[1:] != keys[:-1]]) - 1


def _sum_rows(owner: np.ndarray, rows: np.ndarray, count: int) -> np.ndarray:
    """``(count, 3)`` sums of the ``(N, 3)`` rows by their ``(N,)`` owner."""
    return np.stack([np.bincount(owner, rows[:, k], minlength=count) for k in range(3)], axis=1)


def _unit(vectors: np.ndarray) -> np.ndarray:
    """``vectors`` made unit as float32; +z where one is zero."""
    length = np.linalg.norm(vectors, axis=1, keepdims=True)
    unit = np.divide(vectors, length, out=np.zeros_like(vectors), where=length > 0)
    unit[(length == 0).ravel()] = (0.0, 0.0, 1.0)
    return unit.astype("<f4")


_TYPES = {1: "SCALAR", 3: "VEC3", 4: "VEC4"}
_COMPONENTS = {np.dtype("<f4"): _FLOAT, np.dtype("u1"): _UBYTE, np.dtype("<u4"): _UINT}


def _add_view(doc: dict, chunks: list[bytes], array: np.ndarray, offset: int, target: int) -> int:
    """Append ``array`` to the buffer as a view and an accessor; the accessor's index."""
    chunks.append(np.ascontiguousarray(array).tobytes())  # every array: a multiple of 4 bytes
    doc["bufferViews"].append({"buffer": 0, "byteOffset": offset, "byteLength": array.nbytes,
                               "target": target})
    width = 1 if array.ndim == 1 else array.shape[1]
    accessor: dict = {"bufferView": len(doc["bufferViews"]) - 1, "count": len(array),
                      "componentType": _COMPONENTS[array.dtype], "type": _TYPES[width]}
    if array.dtype == np.uint8:
        accessor["normalized"] = True
    if target == _ARRAY_BUFFER and array.dtype.kind == "f":
        accessor["min"] = array.min(axis=0).tolist()
        accessor["max"] = array.max(axis=0).tolist()
    doc["accessors"].append(accessor)
    return len(doc["accessors"]) - 1
