"""Rigid and affine transforms of a mesh's vertices, vectorized (topology untouched).

TopMod kept an object transform (position, scale, quaternion) that reached the
vertices only through ``freezeTransformations``; livemod moves the vertices at
once. Every function acts on all vertices, or on the ``vertices`` listed.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from ._checks import finite_number, finite_vector, first_not_finite, flag, id_list
from .errors import GeometryError, InvalidArgumentError
from .mesh import Mesh

__all__ = ["move_vertices", "rotate", "rotation_matrix", "scale", "transform", "translate"]


def _vector(value: Any, name: str) -> np.ndarray:
    """``(3,)`` float64 from three numbers, or one number repeated."""
    return finite_vector(value, name, repeat_scalar=True)


def _selected(mesh: Mesh, vertices: Iterable[int] | None) -> tuple[np.ndarray, np.ndarray]:
    """``(ids (k,), positions (k, 3))`` of the chosen vertices (all by default).

    Raises:
        DLFLError: an entry that is not an integer, or an id that is not a vertex
            of the mesh.
    """
    if vertices is None:
        return mesh.vertex_ids(), mesh.positions_view()
    ids = np.asarray(id_list(vertices, "vertices"), dtype=np.int64).reshape(-1)
    return ids, mesh.positions(ids)


def transform(
    mesh: Mesh, matrix: Any, *, center: Any = (0.0, 0.0, 0.0),
    vertices: Iterable[int] | None = None,
) -> None:
    """Apply the ``(3, 3)`` linear map ``matrix`` about ``center``: ``p' = M (p - c) + c``.

    Raises:
        DLFLError: ``matrix`` is not a finite 3x3 array, ``center`` not a finite
            point, a vertex id is not live, or a vertex would move to a
            non-finite position. The mesh is unchanged.
    """
    try:
        m = np.asarray(matrix, dtype=np.float64)
    except (TypeError, ValueError):  # strings, ragged rows
        raise InvalidArgumentError(f"matrix must be a finite 3x3 array, got {matrix!r}") from None
    if m.shape != (3, 3) or not np.isfinite(m).all():
        raise InvalidArgumentError(f"matrix must be a finite 3x3 array, got shape {m.shape}")
    c = _vector(center, "center")
    ids, p = _selected(mesh, vertices)
    with np.errstate(over="ignore", invalid="ignore"):  # refused by _finite_moved
        moved = (p - c) @ m.T + c
    mesh.set_positions(ids, _finite_moved(ids, moved))


def _finite_moved(ids: np.ndarray, moved: np.ndarray) -> np.ndarray:
    """``moved`` (``(k, 3)``, the new positions of vertices ``ids``), checked.

    Raises:
        DLFLError: a coordinate overflowed; names the first such vertex.
    """
    k = first_not_finite(moved)
    if k is None:
        return moved
    raise GeometryError(f"the transform would move vertex {int(ids[k])} to {moved[k].tolist()}: "
                        "its numbers overflow; use smaller factors or offsets (nothing is moved)")


def translate(mesh: Mesh, offset: Any, *, vertices: Iterable[int] | None = None) -> None:
    """Move vertices by ``offset`` ``(x, y, z)``."""
    d = _vector(offset, "offset")
    ids, p = _selected(mesh, vertices)
    with np.errstate(over="ignore"):  # refused by _finite_moved
        moved = p + d
    mesh.set_positions(ids, _finite_moved(ids, moved))


def scale(
    mesh: Mesh, factors: Any, *, center: Any = (0.0, 0.0, 0.0),
    vertices: Iterable[int] | None = None,
) -> None:
    """Scale about ``center`` by ``factors``: one number, or one per axis."""
    transform(mesh, np.diag(_vector(factors, "factors")), center=center, vertices=vertices)


def rotation_matrix(axis: Any, degrees: float) -> np.ndarray:
    """``(3, 3)`` rotation by ``degrees`` about ``axis`` (right-handed, Rodrigues).

    Raises:
        DLFLError: a zero or non-finite axis, or ``degrees`` not a finite number.
    """
    theta = np.radians(finite_number(degrees, "degrees"))
    k = _vector(axis, "axis")
    largest = float(np.abs(k).max())
    if largest == 0.0:
        raise InvalidArgumentError("rotation axis must not be zero")
    # to at most 1 first: the squares in the norm of (1e308, 1e308, 0) overflow,
    # and those of (1e-200, 1e-200, 0) vanish
    k = k / largest
    k = k / np.linalg.norm(k)
    cross = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(theta) * cross + (1 - np.cos(theta)) * cross @ cross


def rotate(
    mesh: Mesh, axis: Any, degrees: float, *, center: Any = (0.0, 0.0, 0.0),
    vertices: Iterable[int] | None = None,
) -> None:
    """Rotate by ``degrees`` about the line through ``center`` along ``axis``."""
    transform(mesh, rotation_matrix(axis, degrees), center=center, vertices=vertices)


def move_vertices(
    mesh: Mesh, vertices: Iterable[int], offset: Any, *, relative: bool = True
) -> None:
    """Move the listed vertices by ``offset`` or, with ``relative=False``, to it
    (the thesis's ``move(vertexids, (x, y, z)[, relative])``)."""
    d = _vector(offset, "offset")
    relative = flag(relative, "relative")  # a string such as "False" would mean True
    ids, p = _selected(mesh, vertices)
    if not relative:
        mesh.set_positions(ids, np.broadcast_to(d, p.shape))
        return
    with np.errstate(over="ignore"):  # refused by _finite_moved
        moved = p + d
    mesh.set_positions(ids, _finite_moved(ids, moved))
