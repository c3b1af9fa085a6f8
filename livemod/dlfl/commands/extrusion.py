"""Thesis commands of the extrusion and connection family: extrude, connect*, addHandle.

Thin wrappers over :mod:`livemod.dlfl.extrusion` and :mod:`livemod.dlfl.connect`
acting on the current object. Options follow the thesis appendix (Tett 2007),
positionally in its order per extrusion type, or by keyword.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

from .. import connect as _connect
from .. import extrusion as _extrusion
from .._checks import finite_number, flag, id_list, is_id, whole_count
from ..errors import InvalidArgumentError, unknown_name
from ..mesh import Mesh
from ._base import mesh, modeling_command, resolve_corner, scene

__all__ = ["extrude", "connectEdges", "connectCorners", "connectFaces", "addHandle"]

# the keywords of TopMod's GUI shape (dodeca and icosa): fields of extrusion.Shape
SHAPE_KEYWORDS = ("angle", "l1", "l2", "l3")
# the options a shape replaces (the rings are placed by its angle and lengths)
SHAPE_REPLACES = ("distance", "rotation", "twist", "scale")


def _kind(name: Any) -> str:
    """Exact names and aliases first, then TopMod's first prefix match, in the
    registry's order (TopMod's seven types first, as its module matched them)."""
    if isinstance(name, str):
        key = name.strip().lower().replace("_", "-")
        if key in _extrusion.KINDS or key in _extrusion.ALIASES:
            return _extrusion.resolve_kind(key)
        for kind in _extrusion.KINDS:
            if key and kind.startswith(key):
                return kind
    raise InvalidArgumentError(unknown_name("unknown extrusion type", name, _extrusion.KINDS,
                                            "valid types"))


def kind_keywords(kind: str) -> tuple[str, ...]:
    """Every option of ``kind`` a script can set: its positional options in the
    thesis's order, then those only a keyword sets (and its GUI shape's)."""
    spec = _extrusion.KINDS[kind]
    shape = SHAPE_KEYWORDS if spec.shape is not None else ()
    return (*spec.options, *spec.keyword_options, *shape)


def _options(kind: str, options: tuple[Any, ...], keywords: dict[str, Any]) -> dict[str, Any]:
    """The options of an ``extrude(kind, faceid, *options, **keywords)`` call by name.

    Raises:
        InvalidArgumentError: more positional options than ``kind`` takes, a
            keyword that is none of its options (nor TopMod's name for one), or
            an option given twice.
    """
    order = _extrusion.KINDS[kind].options
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
        InvalidArgumentError: ``kind`` has no such option.
    """
    spec = _extrusion.KINDS[kind]
    option = spec.topmod_names.get(name) or _extrusion.TOPMOD_KEYWORDS.get(name, name)
    accepted = kind_keywords(kind)
    if option not in accepted:
        raise InvalidArgumentError(f"extrude('{kind}') has no option {name!r}; options: "
                                   f"{', '.join(accepted)}")
    return option


def _library_arguments(kind: str, given: dict[str, Any]) -> dict[str, Any]:
    """Map the script's option names to :func:`livemod.dlfl.extrusion.extrude`'s;
    the GUI shape keywords become one ``shape``.

    Raises:
        InvalidArgumentError: a shape keyword together with an option the shape
            replaces.
    """
    spec = _extrusion.KINDS[kind]
    shape = ({name: given.pop(name) for name in SHAPE_KEYWORDS if name in given}
             if spec.shape is not None else None)
    renamed = spec.library_names
    out = {renamed.get(name, name): value for name, value in given.items()} if renamed else given
    if shape:
        clash = [name for name in SHAPE_REPLACES if name in given]
        if clash:
            raise InvalidArgumentError(
                f"extrude('{kind}'): the GUI shape ({', '.join(shape)}) places the rings "
                f"itself; it takes no {', '.join(clash)}")
        assert spec.shape is not None
        out["shape"] = replace(spec.shape, **shape)
    return out


@modeling_command
def extrude(type: str, faceid: Any, *options: Any, fan: bool = False,  # noqa: A002
            **keywords: Any) -> Any:
    """``extrude(type, faceid[, ...])``: extrude a face; return the new end face id.

    Types and their options, positional in the thesis appendix's order or by
    keyword (keyword-only options after the semicolon):

    * doo-sabin [distance, segments, rotation, scale] (rotation is TopMod's
      twist fraction)
    * dodeca [distance, segments, twist, scale, hexagonalize; angle, l1, l2, l3]
    * icosa [distance, segments, rotation, scale; angle, l1, l2, l3]
    * octa [distance, rotation, scale; segments, mesh]
    * stellate and double-stellate [distance]
    * cubical, cuboctahedral and hex-tile [distance, segments, rotation, scale]
    * dome [distance, rotation, scale]
    * planar-offset [distance, rotation, thickness, fractional]

    Defaults: distance 2, segments 1, rotation 0, scale 1. ``angle``, ``l1``,
    ``l2``, ``l3`` are the shape options of TopMod's GUI (dodeca 40, .5, 1, 1;
    icosa 50, .5, .7, .8, the ones not given): they place the rings instead of
    distance, rotation and scale. A type may be abbreviated (the first match in
    TopMod's order doo-sabin, dodeca, icosa, octa, stellate, double-stellate,
    cubical, then livemod's kinds); TopMod's argument names ``dist``, ``num``,
    ``rot`` (dodeca: twist), ``sf`` and ``flag`` (octa: mesh, dodeca:
    hexagonalize) work as keywords, so TopMod's ``extrude("octa", f, d, num,
    rot, sf, flag)`` is written with ``num=``, ``rot=``, ``sf=``, ``flag=``.

    ``faceid`` may be a list of faces: each is extruded in turn, as TopMod
    extrudes a selection (see :func:`livemod.dlfl.extrusion.extrude_faces`), and
    the list of end faces comes back.

    Returns:
        The end face id. Stellate, double-stellate and dome end in a fan of
        triangles: they return the triangle over the first side of the face
        (from its head corner), and with ``fan=True`` the list of all the
        fan's triangles, that one first (TopMod returned -1).

    Raises:
        DLFLError: unknown type (lists the valid ones), unknown option, too many
            options, ``fan`` for a type without a fan, or see
            :func:`livemod.dlfl.extrusion.extrude`; the mesh is unchanged.
    """
    kind = _kind(type)
    arguments = _library_arguments(kind, _options(kind, options, keywords))
    whole_fan = fan is not False and flag(fan, "fan")  # (the chained path: no call)
    if whole_fan and _extrusion.KINDS[kind].fan is None:
        raise InvalidArgumentError(f"extrude('{kind}') ends in a face, not a fan of triangles: "
                                   "fan=True is for stellate, double-stellate and dome")
    m, budget = mesh(), scene().face_budget
    if not is_id(faceid):
        return _extrude_list(m, faceid, kind, whole_fan, arguments, budget)
    if whole_fan:
        return _extrusion.extrude_fan(m, int(faceid), kind, **arguments, max_faces=budget)
    return _extrusion.extrude(m, int(faceid), kind, **arguments, max_faces=budget)


def _extrude_list(m: Mesh, faceids: Any, kind: str, fan: bool, arguments: dict[str, Any],
                  budget: int | None) -> list[Any]:
    """``extrude`` of a list of faces: their end faces (with ``fan``, their fans).

    Raises:
        InvalidArgumentError: ``faceids`` is neither a face id nor a list of them.
    """
    if isinstance(faceids, str | bytes) or not hasattr(faceids, "__iter__"):
        raise InvalidArgumentError(f"faceid must be a face id or a list of face ids, "
                                   f"got {faceids!r}")
    return _extrusion.extrude_faces(m, faceids, kind, **arguments, fans=fan, max_faces=budget)


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
                   dual: Any = False, *, pinch: float = 1.0, pinchCenter: float = 0.5,
                   bubble: float = 1.0) -> None:
    """``connectCorners(c1, c2[, numsegs, maxconn, 'dual'])``: join the faces of two
    corners with ``numsegs`` segments (at most ``maxconn`` joins, -1 for all);
    ``'dual'`` makes bands of triangles instead of quads. ``pinch``,
    ``pinchCenter`` and ``bubble`` shape the quad tube as for :func:`connectFaces`."""
    m = mesh()
    a, b = _two_faces_corners(m, c1, c2, "connectCorners")
    segments, limit = _segments(numsegs, maxconn)
    profile = _pinch_profile(pinch, pinchCenter, bubble)
    if _is_dual(dual):
        if profile != NO_PINCH:
            raise InvalidArgumentError("a 'dual' (triangle) band takes no pinch, pinchCenter "
                                       "or bubble (TopMod's dualConnectFaces has none)")
        _connect.connect_corners(m, a, b, segments, max_connections=limit, dual=True,
                                 max_faces=scene().face_budget)
        return
    _connect.connect_corners(m, a, b, segments, max_connections=limit, pinch=profile[0],
                             pinch_center=profile[1], bubble=profile[2],
                             max_faces=scene().face_budget)


@modeling_command
def connectFaces(f1: int, f2: int, numsegs: int = 1, maxconn: int = -1, *,
                 pinch: float = 1.0, pinchCenter: float = 0.5, bubble: float = 1.0) -> None:
    """``connectFaces(faceid, faceid[, numsegs, maxconn])``: join two faces at their
    closest corners; intermediate rings by linear interpolation. ``maxconn`` is
    honoured (TopMod ignored it).

    TopMod's pinch profile (its GUI's spin boxes, never passed on): each
    intermediate ring is scaled about its centroid, 1 at both ends and
    ``pinch`` at ``pinchCenter`` (0 to 1 along the tube), the curve sharpened
    by ``bubble`` (a quadratic Bezier (1, pinch, pinch) in
    ``(t / pinchCenter) ^ (1 / bubble)``, mirrored past the centre). They need
    ``numsegs`` > 1 to show.
    """
    _face_id(f1, "f1")
    _face_id(f2, "f2")
    if f1 == f2:
        raise InvalidArgumentError(
            f"connectFaces needs two different faces, f1 and f2 are both face {f1}")
    segments, limit = _segments(numsegs, maxconn)
    profile = _pinch_profile(pinch, pinchCenter, bubble)
    _connect.connect_faces_closest(mesh(), f1, f2, segments, max_connections=limit,
                                   pinch=profile[0], pinch_center=profile[1],
                                   bubble=profile[2], max_faces=scene().face_budget)


@modeling_command
def addHandle(interp: str, c1: Any, c2: Any, numsegs: int, w1: float = 25.0,
              w2: float = 25.0, maxconn: int = -1, twists: int = 0, *, pinch: float = 1.0,
              pinchCenter: float = 0.5, bubble: float = 1.0) -> None:
    """``addHandle(interp, c1, c2, numsegs[, w1, w2, maxconn, twists])``: a curved
    handle, ``interp`` ``"hermite"`` (centroid on a Hermite curve, rings twisted
    ``twists`` extra turns) or ``"bezier"`` (every vertex on its own curve; takes
    no ``maxconn``, ``twists`` or pinch). Weights default to TopMod's GUI values
    (25). ``pinch``, ``pinchCenter`` and ``bubble`` shape a Hermite handle's
    rings as :func:`connectFaces` shapes a tube's (TopMod's "Add Handle SI" spin
    boxes of those names, which it never passed on).

    Raises:
        DLFLError: an unknown ``interp``, a bad number or corner, an option the
            bezier handle has not, or see
            :func:`livemod.dlfl.connect.hermite_handle`; the mesh is unchanged.
    """
    m = mesh()
    a, b = _two_faces_corners(m, c1, c2, "addHandle")
    segments, limit = _segments(numsegs, maxconn)
    w1, w2 = finite_number(w1, "w1"), finite_number(w2, "w2")
    profile = _pinch_profile(pinch, pinchCenter, bubble)
    kind = interp.lower() if isinstance(interp, str) else interp
    if kind == "hermite":
        _connect.hermite_handle(m, a, b, segments, w1, w2, max_connections=limit,
                                twists=twists, pinch=profile[0], pinch_center=profile[1],
                                bubble=profile[2], max_faces=scene().face_budget)
    elif kind == "bezier":
        if limit != -1 or not (is_id(twists) and twists == 0) or profile != NO_PINCH:
            raise InvalidArgumentError("a bezier handle takes no maxconn, twists, pinch, "
                                       "pinchCenter or bubble (TopMod's has none); use "
                                       "'hermite'")
        _connect.bezier_handle(m, a, b, segments, w1, w2, max_faces=scene().face_budget)
    else:
        raise InvalidArgumentError(unknown_name("addHandle interp must be 'hermite' or "
                                                "'bezier', got", interp, ("hermite", "bezier"),
                                                None))


# the pinch profile that leaves a tube's rings as they are: TopMod's GUI defaults
NO_PINCH = (1.0, 0.5, 1.0)


def _pinch_profile(pinch: Any, center: Any, bubble: Any) -> tuple[float, float, float]:
    """``(pinch, pinchCenter, bubble)`` as floats, checked under the commands' names
    (the library checks their ranges).

    Raises:
        InvalidArgumentError: one is not a finite number.
    """
    return (finite_number(pinch, "pinch"), finite_number(center, "pinchCenter"),
            finite_number(bubble, "bubble"))


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
