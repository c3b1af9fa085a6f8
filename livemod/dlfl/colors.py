"""Face colours: set many at once, select faces by colour.

A mesh keeps one colour per face (:meth:`Mesh.face_color`, :meth:`Mesh.face_colors`):
three float32 numbers ``(r, g, b)`` in ``[0, 1]``, or none, which viewers and
writers show as the default modelling colour. Faces an operation makes from a
face take its colour: a split's new face, subdivision's children (every scheme),
an extrusion's sides and end. A face merged into another keeps the surviving
face's colour, or the other's when the surviving face has none. Faces made
around an old vertex or edge (the vertex and edge faces of Doo-Sabin, a dual's
faces, a handle's tube) have no single source face and get no colour.

TopMod's counterpart of :func:`faces_by_color` is ``selectFacesByColor``.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import numpy as np

from ._checks import finite_number, id_list, is_id, rgb
from .errors import InvalidArgumentError
from .mesh import Mesh

__all__ = ["MODELLING_COLOR", "SAME_IN_8_BITS", "colored_like", "faces_by_color",
           "filled_colors", "rgba_bytes", "set_face_colors"]

# TopMod's render colour (255, 151, 92): what a face without colour is drawn in, and
# written as by the formats that give every face a colour
MODELLING_COLOR = (1.0, 151 / 255, 92 / 255)

# half a step of an 8-bit channel: colours an 8-bit file (PLY, 3MF) writes alike
SAME_IN_8_BITS = 0.5 / 255


def set_face_colors(mesh: Mesh, faces: int | Iterable[int], color: Any) -> list[int]:
    """Give every face of ``faces`` the colour ``color``, or take their colour away
    with None.

    Args:
        faces: one face id or several.
        color: ``(r, g, b)``, three numbers in ``[0, 1]``; or None.

    Returns:
        The face ids, in the order given.

    Raises:
        InvalidArgumentError: ``faces`` is not an id or a list of ids, or ``color``
            is neither None nor three numbers in ``[0, 1]``.
        DLFLError: a face id is not live (nothing is changed then).
    """
    ids = [int(faces)] if is_id(faces) else id_list(faces, "faces")
    value = None if color is None else rgb(color)
    for face in ids:
        mesh.face_size(face)  # every id checked before any face changes
    for face in ids:
        mesh.set_face_color(face, value)
    return ids


def filled_colors(colors: np.ndarray) -> np.ndarray:
    """``(F, 3)`` float32 ``colors`` (NaN rows: no colour, see
    :meth:`Mesh.face_colors`) with :data:`MODELLING_COLOR` in the NaN rows."""
    missing = np.isnan(colors[:, 0])
    if not missing.any():
        return colors
    filled = np.array(colors, dtype=np.float32)
    filled[missing] = MODELLING_COLOR
    return filled


def rgba_bytes(colors: np.ndarray | None) -> np.ndarray | None:
    """``(F, 4)`` uint8 RGBA of ``(F, 3)`` float ``colors`` in ``[0, 1]`` (NaN rows:
    no colour, see :meth:`Mesh.face_colors`): each channel rounded to 8 bits, alpha
    255 for a face with a colour and all zero for one without; None for None (no
    face has a colour). How viewers hand face colours to the GPU."""
    if colors is None:
        return None
    rgba = np.zeros((len(colors), 4), np.uint8)
    has = ~np.isnan(colors[:, 0])
    rgba[has, :3] = np.rint(colors[has] * 255)
    rgba[has, 3] = 255
    return rgba


def faces_by_color(mesh: Mesh, color: Any, tolerance: float = SAME_IN_8_BITS) -> list[int]:
    """TopMod's ``selectFacesByColor``: the faces whose colour is within
    ``tolerance`` of ``color`` in each channel, in increasing id order.

    Args:
        color: ``(r, g, b)`` in ``[0, 1]``, a face id (the colour of that face; a
            face without colour selects the faces without one), or None (the
            faces without colour). Holes are never selected.
        tolerance: the largest difference per channel; the default takes the
            colours an 8-bit file writes alike as equal.

    Raises:
        InvalidArgumentError: a bad ``color`` or ``tolerance`` (negative, not finite).
        DLFLError: ``color`` is the id of no live face.
    """
    limit = finite_number(tolerance, "tolerance")
    if limit < 0:
        raise InvalidArgumentError(f"tolerance must be >= 0, got {tolerance!r}")
    target = mesh.face_color(int(color)) if is_id(color) else (
        None if color is None else rgb(color))
    ids = mesh.face_ids()
    chosen = colored_like(mesh.face_colors(), len(ids), target, limit)
    return ids[chosen & ~mesh.hole_mask()].tolist()


def colored_like(colors: np.ndarray | None, count: int, target: tuple[float, float, float] | None,
                 limit: float) -> np.ndarray:
    """``(count,)`` bool: the faces whose ``(count, 3)`` ``colors`` (NaN rows, or None
    for all: no colour) are within ``limit`` of ``target`` in each channel, or,
    for a None ``target``, have no colour."""
    if colors is None:
        return np.full(count, target is None)
    if target is None:
        return np.isnan(colors[:, 0])
    # NaN rows (no colour) compare False: never selected
    return (np.abs(colors - np.asarray(target, np.float32)) <= np.float32(limit)).all(axis=1)
