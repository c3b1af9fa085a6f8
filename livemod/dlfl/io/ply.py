"""Binary little-endian PLY export: polygons as they are, holes left out."""

from __future__ import annotations

import os

import numpy as np

from ..arrays import mesh_arrays
from ..mesh import Mesh
from .atomic import write_atomically


def write_ply(mesh: Mesh, path: str | os.PathLike[str]) -> None:
    """Write ``mesh`` as binary little-endian PLY, atomically.

    Vertices as ``double x, y, z`` in id order (point-spheres included, so ids
    map to PLY indices); one polygon per face that is not a hole and not a
    point-sphere, from its head corner, as ``list uchar int`` (``list uint
    int`` when a face has more than 255 corners).

    Raises:
        OSError: the file cannot be written; an existing file is left intact.
    """
    data = ply_bytes(mesh)
    write_atomically(path, data)


def ply_bytes(mesh: Mesh) -> bytes:
    """The binary PLY of ``mesh`` (see :func:`write_ply`)."""
    a = mesh_arrays(mesh)
    sizes, indices = a.surface_polygons()
    count_type = "uchar" if len(sizes) == 0 or sizes.max() <= 255 else "uint"
    header = "\n".join([
        "ply", "format binary_little_endian 1.0", "comment written by livemod",
        f"element vertex {len(a.positions)}",
        "property double x", "property double y", "property double z",
        f"element face {len(sizes)}",
        f"property list {count_type} int vertex_indices", "end_header", "",
    ]).encode()
    vertices = np.ascontiguousarray(a.positions, dtype="<f8").tobytes()
    return header + vertices + _face_records(sizes, indices, count_type)


def _face_records(sizes: np.ndarray, indices: np.ndarray, count_type: str) -> bytes:
    """Each face as its corner count followed by its ``int32`` vertex indices."""
    count_bytes = 1 if count_type == "uchar" else 4
    record_sizes = count_bytes + 4 * sizes
    starts = np.cumsum(record_sizes) - record_sizes
    out = np.empty(int(record_sizes.sum()), dtype=np.uint8)
    is_count = np.zeros(len(out), dtype=bool)
    count_pos = starts[:, None] + np.arange(count_bytes)
    is_count[count_pos] = True
    counts = sizes.astype("<u1" if count_bytes == 1 else "<u4")
    out[count_pos.ravel()] = counts.view(np.uint8)
    out[~is_count] = indices.astype("<i4").view(np.uint8)
    return out.tobytes()
