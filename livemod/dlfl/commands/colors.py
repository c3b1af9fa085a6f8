"""Face colour commands: setFaceColor and selectFacesByColor.

livemod additions in the style of the thesis (TopMod set colours in its GUI and
selected by them with ``selectFacesByColor``); ``faceInfo(f)["color"]`` reports
a face's colour. Wrappers over :mod:`livemod.dlfl.colors`, acting on the
current object.
"""

from __future__ import annotations

from typing import Any

from .. import colors as _colors
from ._base import id_arguments, mesh, modeling_command

__all__ = ["setFaceColor", "selectFacesByColor"]


@modeling_command
def setFaceColor(faceids: Any, color: Any) -> list[int]:
    """Colour faces: ``setFaceColor(f, (1, 0.5, 0))`` or ``setFaceColor([f, g], c)``;
    None as ``faceids`` colours the selected faces, None as ``color`` takes the
    colour away (the face shows the modelling colour again).

    ``color`` is three numbers in ``[0, 1]`` (divide 0-255 values by 255). Faces
    made later from a coloured face take its colour.

    Returns:
        The face ids coloured.

    Raises:
        DLFLError: an id that is not a live face, or a bad colour; the mesh is
            unchanged.
    """
    return _colors.set_face_colors(mesh(), id_arguments(faceids, "faceids", "faces"), color)


def selectFacesByColor(color: Any, tolerance: float = _colors.SAME_IN_8_BITS) -> list[int]:
    """TopMod's ``selectFacesByColor``: ids of the faces coloured ``color`` (an
    ``(r, g, b)`` in ``[0, 1]``, or a face id meaning that face's colour, or None
    for the faces without colour), each channel within ``tolerance``; holes left
    out.

    Raises:
        DLFLError: a bad colour or tolerance, or a face id that is not live.
    """
    return _colors.faces_by_color(mesh(), color, tolerance)
