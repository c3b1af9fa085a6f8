"""Thesis commands of the extrusion and connection family: extrude, connect*, addHandle.

Thin wrappers over :mod:`livemod.dlfl.extrusion` and :mod:`livemod.dlfl.connect`
acting on the current object. Options follow the thesis appendix (Tett 2007),
positionally in its order per extrusion type, or by keyword.
"""

from __future__ import annotations

from typing import Any

from .. import connect as _connect
from .. import extrusion as _extrusion
from .._checks import finite_number, flag, id_list, is_id, whole_count
from ..errors import InvalidArgumentError
from ..mesh import Mesh
from ._base import mesh, modeling_command, resolve_corner, scene

__all__ = ["extrude", "connectEdges", "connectCorners", "connectFaces", "addHandle"]

# positional options after the face id, per kind. TopMod's binding read every one of
# its seven types as (dist, num, rot, sf, flag), ignoring what a type does not use; the
# thesis lists each type's options in that order (for octa it leaves out segments,
# which the binding passed second). The kinds TopMod's binding lacks follow its C++
# parameter order.
OPTION_ORDER: dict[str, tuple[str, ...]] = {
    "doo-sabin": ("distance", "segments", "rotation", "scale"),
    "dodeca": ("distance", "segments", "twist", "scale", "hexagonalize"),
    "icosa": ("distance", "segments", "rotation", "scale"),
    "octa": ("distance", "segments", "rotation", "scale", "mesh"),
    "stellate": ("distance",),
    "double-stellate": ("distance",),
    "cubical": ("distance", "segments", "rotation", "scale"),
    "dome": ("distance", "rotation", "scale"),
    "cuboctahedral": ("distance", "segments", "rotation", "scale"),
    "hex-tile": ("distance", "segments", "rotation", "scale"),
    "planar-offset": ("distance", "rotation", "thickness", "fractional"),
}
# TopMod's prefix order for its seven Python types, then livemod's additions
PREFIX_ORDER = ("doo-sabin", "dodeca", "icosa", "octa", "stellate", "double-stellate",
                "cubical", "dome", "cuboctahedral", "hex-tile", "planar-offset")


def _kind(name: Any) -> str:
    """Exact names and aliases first, then TopMod's first prefix match in its order."""
    if isinstance(name, str):
        key = name.strip().lower().replace("_", "-")
        if key in OPTION_ORDER or key in _extrusion.ALIASES:
            return _extrusion.resolve_kind(key)
        for kind in PREFIX_ORDER:
            if key and kind.startswith(key):
                return kind
    raise InvalidArgumentError(
        f"unknown extrusion type {name!r}; valid types: {', '.join(PREFIX_ORDER)}")


# TopMod's own argument names (TOPMOD.md §8) accepted as keywords too; ``rot`` is
# TopMod's rotTwist, dodeca's twist; ``flag`` is octa's mesh and dodeca's hexagonalize
KEYWORD_ALIASES = {"dist": "distance", "num": "segments", "numsegs": "segments",
                   "rot": "rotation", "sf": "scale"}
KIND_KEYWORD_ALIASES = {"dodeca": {"rot": "twist", "flag": "hexagonalize"},
                        "octa": {"flag": "mesh"}}


def _options(kind: str, options: tuple[Any, ...], keywords: dict[str, Any]) -> dict[str, Any]:
    """The options of an ``extrude(kind, faceid, *options, **keywords)`` call by name.

    Raises:
        DLFLError: more positional options than ``kind`` takes, a keyword that is
            none of its options (nor TopMod's name for one), or an option given twice.
    """
    order = OPTION_ORDER[kind]
    if len(options) > len(order):
        raise InvalidArgumentError(
            f"extrude('{kind}', faceid, ...) takes at most {len(order)} options "
            f"({', '.join(order)}), got {len(options)}")
    given = dict(zip(order, options, strict=False))
    for name, value in keywords.items():
        option = _keyword(kind, name)
        if option in given:
            said = repr(option) if option == name else f"{name!r} (= {option!r})"
            raise InvalidArgumentError(f"extrude('{kind}'): option {said} given twice")
        given[option] = value
    return given


def _keyword(kind: str, name: str) -> str:
    """The option of ``kind`` that keyword ``name`` sets (TopMod's names mapped).

    Raises:
        DLFLError: ``kind`` has no such option.
    """
    option = KIND_KEYWORD_ALIASES.get(kind, {}).get(name) or KEYWORD_ALIASES.get(name, name)
    if option not in OPTION_ORDER[kind]:
        raise InvalidArgumentError(f"extrude('{kind}') has no option {name!r}; options: "
                                   f"{', '.join(OPTION_ORDER[kind])}")
    return option


def _library_arguments(kind: str, given: dict[str, Any]) -> dict[str, Any]:
    """Map the thesis's option names to :func:`livemod.dlfl.extrusion.extrude`'s."""
    out = dict(given)
    if kind == "doo-sabin" and "rotation" in out:
        out["twist"] = out.pop("rotation")  # TopMod passes rot as the Doo-Sabin twist
    if kind == "dodeca" and "twist" in out:
        out["rotation"] = out.pop("twist")  # the dual step's rotation angle
    if "mesh" in out:
        out["dual_mesh"] = flag(out.pop("mesh"), "mesh")
    if "hexagonalize" in out:
        out["hexagonalize"] = flag(out["hexagonalize"], "hexagonalize")
    return out


@modeling_command
def extrude(type: str, faceid: int, *options: Any, **keywords: Any) -> int | list[int]:  # noqa: A002
    """``extrude(type, faceid[, ...])``: extrude a face; return the new end face id.

    Types and their options (positional in this order, or by keyword):
    doo-sabin [distance, segments, rotation, scale] (rotation is TopMod's twist
    fraction), dodeca [distance, segments, twist, scale, hexagonalize], icosa,
    cubical, cuboctahedral and hex-tile [distance, segments, rotation, scale],
    octa [distance, segments, rotation, scale, mesh], stellate and
    double-stellate [distance], dome [distance, rotation, scale], planar-offset
    [distance, rotation, thickness, fractional]. Defaults: distance 2, segments
    1, rotation 0, scale 1. These are the positions of TopMod's binding, which
    read every type as (dist, num, rot, sf, flag); the thesis's list for octa
    leaves out segments, which livemod takes second as TopMod did. A type may be
    abbreviated (TopMod's prefix order); TopMod's names ``dist``, ``num``,
    ``rot`` (dodeca: twist) and ``sf`` work as keywords, and ``flag`` for octa's
    mesh and dodeca's hexagonalize.

    Returns:
        The end face id; for stellate, double-stellate and dome, which end in a
        fan of triangles, the list of those triangles' ids (TopMod returned -1).

    Raises:
        DLFLError: unknown type (lists the valid ones), unknown option, too many
            options, or see :func:`livemod.dlfl.extrusion.extrude`.
    """
    kind = _kind(type)
    arguments = _library_arguments(kind, _options(kind, options, keywords))
    _face_id(faceid, "faceid")
    m = mesh()
    budget = scene().face_budget
    if _extrusion.KINDS[kind].fan is not None:
        return _extrusion.extrude_fan(m, faceid, kind, **arguments, max_faces=budget)
    return _extrusion.extrude(m, faceid, kind, **arguments, max_faces=budget)


def _half_edge(value: Any, what: str) -> tuple[int, int]:
    """``value`` as an ``(edgeid, faceid)`` pair of ints.

    Raises:
        DLFLError: not a pair, or an entry that is not an integer id.
    """
    if not (isinstance(value, tuple | list) and len(value) == 2):
        raise InvalidArgumentError(f"{what} must be an (edgeid, faceid) pair, got {value!r}")
    edge, face = id_list(value, what)
    return edge, face


@modeling_command
def connectEdges(e1: Any, e2: Any, loopCheck: bool = False) -> None:
    """``connectEdges((edgeid, faceid), (edgeid, faceid)[, loopCheck])``: join two
    half-edges with a face; with ``loopCheck`` corners already adjacent get no edge."""
    edge1, face1 = _half_edge(e1, "e1")
    edge2, face2 = _half_edge(e2, "e2")
    if edge1 == edge2:
        raise InvalidArgumentError(
            f"connectEdges needs two different edges, e1 and e2 are both on edge {edge1}")
    _connect.connect_edges(mesh(), edge1, face1, edge2, face2, check=flag(loopCheck, "loopCheck"))


def _is_dual(value: Any) -> bool:
    if isinstance(value, str):
        if value.lower() != "dual":
            raise InvalidArgumentError(f"connectCorners' last option must be 'dual', got {value!r}")
        return True
    return flag(value, "dual")


@modeling_command
def connectCorners(c1: Any, c2: Any, numsegs: int = 1, maxconn: int = -1,
                   dual: Any = False) -> None:
    """``connectCorners(c1, c2[, numsegs, maxconn, 'dual'])``: join the faces of two
    corners with ``numsegs`` segments (at most ``maxconn`` joins, -1 for all);
    ``'dual'`` makes bands of triangles instead of quads."""
    m = mesh()
    a, b = _two_faces_corners(m, c1, c2, "connectCorners")
    segments, limit = _segments(numsegs, maxconn)
    _connect.connect_corners(m, a, b, segments, max_connections=limit, dual=_is_dual(dual),
                             max_faces=scene().face_budget)


@modeling_command
def connectFaces(f1: int, f2: int, numsegs: int = 1, maxconn: int = -1) -> None:
    """``connectFaces(faceid, faceid[, numsegs, maxconn])``: join two faces at their
    closest corners; intermediate rings by linear interpolation. ``maxconn`` is
    honoured (TopMod ignored it)."""
    _face_id(f1, "f1")
    _face_id(f2, "f2")
    if f1 == f2:
        raise InvalidArgumentError(
            f"connectFaces needs two different faces, f1 and f2 are both face {f1}")
    segments, limit = _segments(numsegs, maxconn)
    _connect.connect_faces_closest(mesh(), f1, f2, segments, max_connections=limit,
                                   max_faces=scene().face_budget)


@modeling_command
def addHandle(interp: str, c1: Any, c2: Any, numsegs: int, w1: float = 25.0,
              w2: float = 25.0, maxconn: int = -1, twists: int = 0) -> None:
    """``addHandle(interp, c1, c2, numsegs[, w1, w2, maxconn, twists])``: a curved
    handle, ``interp`` ``"hermite"`` (centroid on a Hermite curve, rings twisted
    ``twists`` extra turns) or ``"bezier"`` (every vertex on its own curve; takes
    no ``maxconn`` or ``twists``). Weights default to TopMod's GUI values (25)."""
    m = mesh()
    a, b = _two_faces_corners(m, c1, c2, "addHandle")
    segments, limit = _segments(numsegs, maxconn)
    w1, w2 = finite_number(w1, "w1"), finite_number(w2, "w2")
    kind = interp.lower() if isinstance(interp, str) else interp
    if kind == "hermite":
        _connect.hermite_handle(m, a, b, segments, w1, w2, max_connections=limit,
                                twists=twists, max_faces=scene().face_budget)
    elif kind == "bezier":
        if maxconn != -1 or twists != 0:
            raise InvalidArgumentError(
                "a bezier handle takes no maxconn or twists (TopMod's has none); "
                "use 'hermite'")
        _connect.bezier_handle(m, a, b, segments, w1, w2, max_faces=scene().face_budget)
    else:
        raise InvalidArgumentError(
            f"addHandle interp must be 'hermite' or 'bezier', got {interp!r}")


def _face_id(value: Any, name: str) -> None:
    """Raises DLFLError naming ``name`` unless ``value`` is an integer id (not a bool)."""
    if not is_id(value):
        raise InvalidArgumentError(f"{name} must be a face id (an integer), got {value!r}")


def _segments(numsegs: Any, maxconn: Any) -> tuple[int, int]:
    """``numsegs`` and ``maxconn`` checked under the thesis's names (the library's
    own messages call them segments and max_connections)."""
    segments = whole_count(numsegs, "numsegs", each=2)
    if not is_id(maxconn):
        raise InvalidArgumentError(f"maxconn must be an integer (-1 for all), got {maxconn!r}")
    return segments, int(maxconn)


def _two_faces_corners(m: Mesh, c1: Any, c2: Any, command: str) -> tuple[int, int]:
    """The corner ids of ``c1`` and ``c2``, which must lie in two different faces."""
    a, b = resolve_corner(m, c1, "c1"), resolve_corner(m, c2, "c2")
    if m.corner_face(a) == m.corner_face(b):
        raise InvalidArgumentError(f"{command} needs c1 and c2 in two different faces, both are in "
                                   f"face {m.corner_face(a)}")
    return a, b
