"""Binary STL export: triangle fans of the drawn faces."""

from __future__ import annotations

import os

import numpy as np

from ..analysis import face_normals
from ..arrays import MeshArrays, mesh_arrays
from ..mesh import Mesh
from .atomic import write_atomically

_TRIANGLE = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])


def write_stl(mesh: Mesh, path: str | os.PathLike[str]) -> None:
    """Write ``mesh`` as binary STL, atomically.

    Every face that is not a hole and has at least 3 corners becomes a fan of
    triangles from its head corner, each carrying the face's unit normal.
    2-gons and point-spheres have no area and are left out.

    Raises:
        OSError: the file cannot be written; an existing file is left intact.
    """
    data = stl_bytes(mesh)
    write_atomically(path, data)


def stl_bytes(mesh: Mesh) -> bytes:
    """The binary STL of ``mesh`` (see :func:`write_stl`)."""
    a = mesh_arrays(mesh)
    tri_corners, tri_face = triangle_fans(a)
    records = np.zeros(len(tri_face), dtype=_TRIANGLE)
    records["normal"] = face_normals(a)[tri_face]
    records["corners"] = a.positions[a.corner_vertex[tri_corners]]
    header = b"livemod binary STL".ljust(80, b" ")
    return header + np.uint32(len(records)).tobytes() + records.tobytes()


def triangle_fans(a: MeshArrays) -> tuple[np.ndarray, np.ndarray]:
    """Fan triangulation of the non-hole faces with 3 or more corners.

    Returns:
        ``(corners, faces)``: ``(T, 3)`` int64 dense corner indices (head,
        k, k + 1) and ``(T,)`` int64 dense face index of each triangle.
    """
    sizes = a.face_sizes
    count = np.where(a.face_hole | (sizes < 3), 0, sizes - 2)
    faces = np.repeat(np.arange(len(sizes), dtype=np.int64), count)
    k = np.arange(len(faces)) - np.repeat(np.cumsum(count) - count, count) + 1
    head = a.face_offsets[faces]
    return np.stack([head, head + k, head + k + 1], axis=1), faces
