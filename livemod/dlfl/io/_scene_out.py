"""What the triangle formats (glTF, 3MF) write of each object: the drawn faces as
triangles, and the objects of a scene with their names and colours."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..arrays import MeshArrays, mesh_arrays
from ..colors import filled_colors
from ..errors import InvalidArgumentError
from ..mesh import Mesh
from ._colors import face_rgba

# what a writer of several objects takes: one mesh, or (name, mesh) pairs
Objects = Mesh | Sequence[tuple[str, Mesh]]


@dataclass(frozen=True)
class Part:
    """One object to write.

    Attributes:
        name: its name (a node's or an object's).
        arrays: its mesh's arrays.
        rgba: ``(F, 4)`` uint8 face colours, or None.
        corners: ``(K,)`` int64 dense corners of the drawn faces (not holes,
            three corners or more), in face order.
        triangles: ``(T, 3)`` int64 indices into ``corners``: each drawn face a
            fan from its head corner (:meth:`MeshArrays.fan_triangles`).
        faces: ``(T,)`` int64 dense face of each triangle.
    """

    name: str
    arrays: MeshArrays
    rgba: np.ndarray | None
    corners: np.ndarray
    triangles: np.ndarray
    faces: np.ndarray


def parts(objects: Objects, face_colors: object = None) -> list[Part]:
    """The objects to write, each triangulated.

    Args:
        objects: a mesh (one object named ``mesh``), or ``(name, mesh)`` pairs.
        face_colors: for one mesh, None or its ``(F, 3)``/``(F, 4)`` colours;
            for pairs, None or a sequence of those, one per object. None (for
            an object) writes the mesh's own face colours, if it has any, faces
            without one in the modelling colour.

    Raises:
        InvalidArgumentError: no object, or colours of the wrong shape or range.
    """
    pairs = [("mesh", objects)] if isinstance(objects, Mesh) else list(objects)
    if not pairs:
        raise InvalidArgumentError("nothing to write: no object")
    colors: Sequence[object]
    if face_colors is None:
        colors = [None] * len(pairs)
    elif isinstance(objects, Mesh):
        colors = [face_colors]
    else:
        colors = list(face_colors)  # type: ignore[call-overload]
        if len(colors) != len(pairs):
            raise InvalidArgumentError(f"{len(colors)} colour arrays for {len(pairs)} objects")
    return [_part(name, mesh, rgba) for (name, mesh), rgba in zip(pairs, colors, strict=True)]


def drawn_faces(arrays: MeshArrays) -> np.ndarray:
    """``(F,)`` bool: the faces written, those with fan triangles (not holes,
    three corners or more)."""
    return ~arrays.face_hole & (arrays.face_sizes >= 3)


def _part(name: str, mesh: Mesh, colors: object) -> Part:
    a = mesh_arrays(mesh)
    if colors is None and a.face_colors is not None:
        colors = filled_colors(a.face_colors)
    corners, faces = a.fan_triangles()
    rgba = face_rgba(colors, len(a.face_ids))
    drawn = drawn_faces(a)
    if drawn.all():  # (most meshes) every corner written, numbered as it is
        return Part(name, a, rgba, np.arange(len(a.corner_vertex)), corners, faces)
    used = np.repeat(drawn, a.face_sizes)
    renumber = np.cumsum(used) - 1
    return Part(name, a, rgba, np.flatnonzero(used), renumber[corners], faces)
