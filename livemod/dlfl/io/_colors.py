"""Per-face colours as the writers take them and the readers give them."""

from __future__ import annotations

import numpy as np

from ..arrays import MeshArrays
from ..colors import filled_colors
from ..errors import InvalidArgumentError


def face_rgba(colors: object, num_faces: int) -> np.ndarray | None:
    """Per-face colours as ``(F, 4)`` uint8 RGBA, or None for no colours.

    Args:
        colors: None, or an ``(F, 3)`` RGB or ``(F, 4)`` RGBA array, one row per
            face of ``mesh_arrays(mesh)`` (face id order, holes included): floats
            in ``[0, 1]``, or integers in ``[0, 255]``. Alpha defaults to opaque.
        num_faces: ``F``.

    Raises:
        InvalidArgumentError: another shape, or values outside the range.
    """
    if colors is None:
        return None
    array = np.asarray(colors)
    if array.ndim != 2 or array.shape[0] != num_faces or array.shape[1] not in (3, 4):
        raise InvalidArgumentError(f"face colours must be an ({num_faces}, 3) or ({num_faces}, 4) "
                                   f"array, one row per face; got shape {array.shape}")
    if array.dtype.kind == "f":
        if not (np.isfinite(array).all() and (array >= 0).all() and (array <= 1).all()):
            raise InvalidArgumentError("float face colours must lie in [0, 1]")
        array = np.rint(array * 255)
    elif array.dtype.kind in "iu":
        if len(array) and (array.min() < 0 or array.max() > 255):
            raise InvalidArgumentError("integer face colours must lie in [0, 255]")
    else:
        raise InvalidArgumentError(f"face colours must be numbers, got {array.dtype}")
    rgba = np.full((num_faces, 4), 255, dtype=np.uint8)
    rgba[:, : array.shape[1]] = array
    return rgba


def face_rgb8(arrays: MeshArrays) -> np.ndarray | None:
    """``(F, 3)`` uint8 colours of the faces of ``arrays`` (faces without one in the
    modelling colour), or None when no face has one."""
    if arrays.face_colors is None:
        return None
    return np.rint(filled_colors(arrays.face_colors) * 255).astype(np.uint8)


def rgb_from_channels(channels: list[np.ndarray], types: list[str]) -> np.ndarray:
    """``(F, 3)`` float32 colours in ``[0, 1]`` from the ``(F,)`` channels red, green,
    blue as a file declares them (numpy type codes, ``"u1"`` for PLY's ``uchar``):
    integers scaled from their type's range (``uchar``: 0-255), floats clipped
    to ``[0, 1]``."""
    out = np.empty((len(channels[0]), 3), dtype=np.float32)
    for k, (channel, code) in enumerate(zip(channels, types, strict=True)):
        kind = np.dtype(code)
        if kind.kind in "iu":
            top = float(np.iinfo(kind).max)
            out[:, k] = np.clip(channel, 0, top) / top
        else:
            out[:, k] = np.clip(channel, 0.0, 1.0)
    return out
