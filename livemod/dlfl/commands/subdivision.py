"""Thesis commands of the remeshing family: subdivide, subdivideFace(s), dual.

Thin wrappers over :mod:`livemod.dlfl.subdivision` acting on the current object.
Differences from TopMod's Python module (TOPMOD.md section 8): every option is
honoured (TopMod ignored most of them), and ``subdivideFaces`` with one face
honours ``usequads``.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from .. import subdivision as _subdivision
from .._checks import flag, is_id
from ..errors import InvalidArgumentError
from ._base import id_arguments, mesh, modeling_command, scene

__all__ = ["subdivide", "subdivideFace", "subdivideFaces", "dual"]

# the thesis appendix's option names where livemod's differ, accepted as keywords
THESIS_KEYWORDS = {"root4": {"a": "weight"}}


@modeling_command
def subdivide(scheme: str, *options: Any, **keywords: Any) -> None:
    """Remesh the current object with ``scheme`` (TOPMOD.md section 3 names).

    Options may be positional, in TopMod's argument order
    (``subdivide("checker", 0.25)``, ``subdivide("double-stellate", 0.1, 0.2)``),
    or by keyword; ``max_faces=`` overrides the face budget (default: the
    scene's, see :mod:`livemod.dlfl.budget`).

    Raises:
        DLFLError: an unknown scheme (listing the valid names), too many options,
            an unknown option, a bad value or the face budget; the mesh is unchanged.
    """
    order = _subdivision.scheme_options(scheme)
    if len(options) > len(order):
        names = ", ".join(order) or "none"
        raise InvalidArgumentError(f"subdivide({scheme!r}, ...) takes at most {len(order)} options "
                                   f"({names}), got {len(options)}")
    given = dict(zip(order, options, strict=False))
    aliases = THESIS_KEYWORDS.get(scheme, {}) if isinstance(scheme, str) else {}
    for name, value in keywords.items():
        option = aliases.get(name, name)
        if option in given:
            said = repr(option) if option == name else f"{name!r} (= {option!r})"
            raise InvalidArgumentError(f"subdivide({scheme!r}): option {said} given twice")
        given[option] = value
    given.setdefault("max_faces", scene().face_budget)
    _subdivision.subdivide(mesh(), scheme, **given)


@modeling_command
def subdivideFace(faceid: int, usequads: bool = True) -> None:
    """Split one face about its centroid: quads (edges split) or a triangle fan.

    Raises:
        DLFLError: ``faceid`` is not a face.
    """
    if not is_id(faceid):
        raise InvalidArgumentError(f"faceid must be a face id, got {faceid!r}")
    _subdivision.subdivide_faces(mesh(), [int(faceid)], usequads=flag(usequads, "usequads"),
                                 max_faces=scene().face_budget)


@modeling_command
def subdivideFaces(faceids: Iterable[int] | None = None, usequads: bool = True) -> None:
    """Split several faces (default: the selected ones) about their centroids.

    Edges shared by two of the faces are split once. With no faces (an empty
    list, or nothing selected) the object is left as it is, ids included.

    Raises:
        DLFLError: an id that is not a face.
    """
    ids = id_arguments(faceids, "faceids", "faces")
    quads = flag(usequads, "usequads")
    if not ids:  # nothing to split: keep every id (a rebuild would renumber them all)
        return
    _subdivision.subdivide_faces(mesh(), ids, usequads=quads, max_faces=scene().face_budget)


@modeling_command
def dual(accurate: bool = False) -> None:
    """Replace the current object by its dual (vertices at the face centroids)."""
    _subdivision.dual(mesh(), accurate=flag(accurate, "accurate"),
                      max_faces=scene().face_budget)
