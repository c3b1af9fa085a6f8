"""Connecting faces, edges and corners: the operations that add handles and tubes.

TopMod's ``DLFLConnect.cc`` family (TOPMOD.md §5), built on :meth:`Mesh.insert_edge`
and :meth:`Mesh.create_face` only:

* :func:`connect_faces`: a ring of quads between two faces, optionally through
  ``segments - 1`` intermediate rings (linear interpolation, pinch and bubble);
* :func:`connect_faces_closest`: the same from two face ids, matching their
  closest corners;
* :func:`dual_connect_faces` / :func:`connect_corners` with ``dual=True``: a
  zig-zag band of triangles;
* :func:`connect_edges`: join two half-edges with a quad;
* :func:`hermite_handle` and :func:`bezier_handle`: curved handles;
* :func:`connect_edge_sides`: the same with the half-edges given as corners;
* :func:`multi_face_handle`, :func:`multi_face_handle_fitted` and
  :func:`multi_face_handle_closest_edges`: several faces at once, through a
  convex-hull hub or by quads between their closest edges (from
  :mod:`livemod.dlfl.multihandle`, re-exported here).

Every function checks all of its input, and the face budget
(:mod:`livemod.dlfl.budget`, ``max_faces=``), before touching the mesh, so a
:class:`DLFLError` leaves the mesh unchanged. Each returns the ids of the edges
it created, in creation order.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Callable

import numpy as np

from ._checks import MAX_ELEMENTS, finite_number, first_not_finite, is_id, shown, whole_count
from ._vectors import centroid, lengths, together_in_range, unit
from .analysis import face_points, polygon_normal
from .bands import edges_since, quad_band, triangle_band
from .budget import check_growth
from .errors import GeometryError, InvalidArgumentError, UnknownIdError
from .mesh import Mesh

__all__ = [
    "connect_faces", "connect_faces_closest", "closest_corners", "connect_corners",
    "dual_connect_faces", "connect_edges", "hermite_handle", "hermite_rings",
    "hermite_point", "bezier_handle", "bezier_rings", "resolve_polygon",
    "rotation_between", "connect_edge_sides",
]

# ``connector(mesh, corner1, corner2)`` joins the faces of two corners
Connector = Callable[[Mesh, int, int], object]
_Four = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]


# -- checks ----------------------------------------------------------------------

def _face_ids(face1: object, face2: object) -> None:
    """Refuse face ids that are not ints (a float or bool would pass ``has_face``'s
    hash lookup, or compare equal to a different kind of id)."""
    for what, face in (("face1", face1), ("face2", face2)):
        if not is_id(face):
            raise InvalidArgumentError(f"{what} must be a face id (int), got {face!r}")


def _live_corner(mesh: Mesh, corner: int, what: str) -> int:
    if not is_id(corner):
        raise InvalidArgumentError(f"{what} must be a corner id (int), got {corner!r}")
    if not mesh.has_corner(int(corner)):
        raise UnknownIdError(f"{what}: corner {corner} does not exist (deleted or never made)")
    return int(corner)


def _two_faces(mesh: Mesh, corner1: int, corner2: int, op: str) -> tuple[int, int]:
    """The faces of two live corners, which must differ."""
    c1 = _live_corner(mesh, corner1, "corner1")
    c2 = _live_corner(mesh, corner2, "corner2")
    face1, face2 = mesh.corner_face(c1), mesh.corner_face(c2)
    if face1 == face2:
        raise InvalidArgumentError(
            f"{op} needs corners of two different faces, both are in face {face1}")
    return face1, face2


def _check_segments(segments: int, max_connections: int = -1) -> None:
    """Raises DLFLError unless ``segments`` is a count >= 1 and ``max_connections``
    an integer (:func:`_check_budget` checks that its corners fit)."""
    whole_count(segments, "segments", each=0)
    if isinstance(max_connections, bool) or not isinstance(max_connections, int | np.integer):
        raise InvalidArgumentError(f"max_connections must be an integer, got {max_connections!r}")


def _check_budget(mesh: Mesh, corner1: int, corner2: int, segments: int, op: str,
                  max_faces: object) -> None:
    """Refuse a tube of ``segments`` between the faces of two live corners whose
    result would pass the face budget, before any ring is computed.

    Each of the ``segments - 1`` rings is a two-sided polygon and each of the
    ``segments`` joins cuts two faces into at most ``n1 + n2`` quads or
    triangles, so the tube adds at most ``segments (n1 + n2)`` faces and four
    times that many corners.

    Raises:
        BudgetExceededError: the result would pass the budget.
        DLFLError: a budget raised so far that the corners would not fit in a
            mesh (each segment makes at least two).
    """
    sides = sum(mesh.face_size(mesh.corner_face(c)) for c in (corner1, corner2))
    check_growth(mesh, op, faces=segments * sides, corners=4 * segments * sides,
                 max_faces=max_faces)
    whole_count(segments, "segments", each=2)


def _check_twists(twists: object) -> int:
    """``twists`` as an int: a whole number (``2.0`` too), not a bool or string.

    Raises:
        DLFLError: anything else; ``int()`` would truncate 1.5 to 1 unseen and
            fail on NaN or infinity with a message that names no argument.
    """
    whole = isinstance(twists, numbers.Integral) or (
        isinstance(twists, float | np.floating) and math.isfinite(twists)
        and float(twists).is_integer())
    if isinstance(twists, bool | np.bool_) or not whole:
        raise InvalidArgumentError(f"twists must be a whole number of turns, got {twists!r}")
    turns = int(twists)  # type: ignore[call-overload]
    if abs(turns) > MAX_ELEMENTS:  # 2 pi turns must be a float (10**400 is not)
        raise InvalidArgumentError(
            f"twists must be at most {MAX_ELEMENTS:,} turns either way, got {turns}")
    return turns


def _check_weights(weight1: float, weight2: float) -> None:
    """Raises DLFLError unless both tangent weights are finite numbers."""
    finite_number(weight1, "weight1")
    finite_number(weight2, "weight2")


def _same_size(mesh: Mesh, face1: int, face2: int, op: str) -> None:
    n1, n2 = mesh.face_size(face1), mesh.face_size(face2)
    if n1 != n2:
        raise InvalidArgumentError(
            f"{op} with segments needs faces of equal size; face {face1} has {n1} "
            f"corners and face {face2} has {n2} (connect them with segments=1, "
            "which ends in a triangle or larger polygon)"
        )


# -- single connections ------------------------------------------------------------

def dual_connect_faces(mesh: Mesh, corner1: int, corner2: int) -> list[int]:
    """Join two faces with a zig-zag band of triangles (TopMod's ``dualConnectFaces``).

    Every vertex of one face is joined to two adjacent vertices of the other;
    faces of sizes ``n`` and ``m`` give ``n + m`` triangles (cube top to bottom:
    8/20/12, genus 1).

    Returns:
        The ids of the new edges, the first one joining the two corners.

    Raises:
        DLFLError: a corner is not live, or both corners are in the same face.
    """
    _two_faces(mesh, corner1, corner2, "dual_connect_faces")
    first = mesh.next_ids()[1]
    triangle_band(mesh, corner1, corner2)
    return edges_since(mesh, first)


# -- multi-segment connections -------------------------------------------------------

def _pinch_scale(t: float, pinch: float, center: float, bubble: float) -> float:
    """TopMod's pinch profile: a quadratic Bezier (1, pinch, pinch) in ``t2``, mirrored
    at ``center``, with ``t2 = (t / center) ** (1 / bubble)`` (1 at both ends)."""
    t2 = t / center if t <= center else 1.0 - (t - center) / (1.0 - center)
    t2 = t2 ** (1.0 / bubble)
    return (1 - t2) ** 2 + 2 * (1 - t2) * t2 * pinch + t2 * t2 * pinch


def _check_pinch(pinch: float, center: float, bubble: float) -> None:
    """Raises DLFLError unless the pinch profile's three numbers are usable."""
    pinch = finite_number(pinch, "pinch")
    center = finite_number(center, "pinch_center")
    bubble = finite_number(bubble, "bubble")
    if not 0.0 < center < 1.0:
        raise InvalidArgumentError(
            f"pinch_center must lie strictly between 0 and 1, got {center!r}")
    if not bubble > 0.0:
        raise InvalidArgumentError(f"bubble must be > 0, got {bubble!r}")


def _end_rings(mesh: Mesh, corner1: int, corner2: int) -> tuple[np.ndarray, np.ndarray]:
    """``(n, 3)`` points of face 1 from ``corner1`` forwards and of face 2 from
    ``corner2`` backwards (face 2 reversed, so vertex ``i`` faces vertex ``i``)."""
    ring1 = [mesh.corner_vertex(c) for c in _ring_from(mesh, corner1, mesh.corner_next)]
    ring2 = [mesh.corner_vertex(c) for c in _ring_from(mesh, corner2, mesh.corner_prev)]
    return mesh.positions(ring1), mesh.positions(ring2)


def _ring_from(mesh: Mesh, corner: int, step: Callable[[int], int]) -> list[int]:
    out, c = [corner], step(corner)
    while c != corner:
        out.append(c)
        c = step(c)
    return out


def _scale_about_centroid(points: np.ndarray, factor: float) -> np.ndarray:
    """``(n, 3)`` ``points`` scaled by ``factor`` about their centroid; a point
    beyond the float range comes out inf or NaN, for the caller to refuse."""
    centre = centroid(points)
    with np.errstate(over="ignore", invalid="ignore"):  # refused by the caller
        return centre + (points - centre) * factor


def _check_finite_rings(rings: list[np.ndarray]) -> None:
    """Refuse ``(n, 3)`` rings with a point beyond the float range, before any
    of them reaches the mesh (whose own complaint would not say why).

    Raises:
        DLFLError: a coordinate is inf or NaN.
    """
    for ring in rings:
        bad = first_not_finite(ring)
        if bad is not None:
            raise GeometryError(f"the handle would put a point at {ring[bad].tolist()}: its "
                                "numbers overflow; use a smaller pinch, bubble or weight")


def _chain_rings(
    mesh: Mesh, corner1: int, corner2: int, rings: list[np.ndarray],
    connector: Connector, max_connections: int,
) -> None:
    """Make each ring a two-sided polygon and join face 1, the rings and face 2 in turn.

    At most ``max_connections`` joins are made (-1: all), as TopMod does, so a
    limited chain leaves loose two-sided rings.
    """
    _check_finite_rings(rings)
    limit = len(rings) + 1 if max_connections < 0 else max_connections
    made, current = 0, corner1
    # the rings take face 1's colour (face 2's when it has none): the whole tube is one
    color = mesh.face_color(mesh.corner_face(corner1)) or mesh.face_color(
        mesh.corner_face(corner2))
    for points in rings:
        front, back = mesh.create_face(points.tolist())
        mesh.set_face_color(front, color)
        mesh.set_face_color(back, color)
        if made < limit:
            connector(mesh, current, mesh.face_corner(back))
            made += 1
        current = mesh.face_corner(front)
    if made < limit:
        connector(mesh, current, corner2)


def connect_faces(
    mesh: Mesh, corner1: int, corner2: int, segments: int = 1, *,
    max_connections: int = -1, pinch: float = 1.0, pinch_center: float = 0.5,
    bubble: float = 1.0, max_faces: object = None,
) -> list[int]:
    """Join two faces with a tube, matching ``corner1``'s vertex to ``corner2``'s.

    TopMod's ``connectFaces``. With one segment: one edge merges the faces, then
    quads are cut off the merged face while it has more than four sides; faces
    of equal size ``n`` give ``n`` quads (genus +1 within one component, or two
    components joined), a quad to a pentagon gives 4 quads and a triangle.
    With ``segments`` > 1 the faces must have equal size: ring ``i`` is the
    linear interpolation at ``t = i / segments`` between face 1 (from
    ``corner1``) and face 2 reversed (from ``corner2``), scaled about its
    centroid by the pinch profile (1 at both ends, ``pinch`` at
    ``pinch_center``, sharpened by ``bubble``); consecutive rings are joined.
    Cube top to bottom: 8/16/8 genus 1; 3 segments 16/32/16.

    Args:
        max_connections: at most this many joins (-1, the default: all).
        max_faces: the face budget (None: the session's, see
            :mod:`livemod.dlfl.budget`).

    Returns:
        The ids of the new edges, in creation order (the first joins the corners
        when ``segments`` is 1).

    Raises:
        DLFLError: a corner is not live, both are in one face, ``segments`` not
            an integer >= 1 or more than a mesh can hold, faces of different
            sizes with ``segments`` > 1 (TopMod silently did nothing), or a bad
            pinch value.
        BudgetExceededError: the tube would pass the face budget.
    """
    face1, face2 = _two_faces(mesh, corner1, corner2, "connect_faces")
    _check_segments(segments, max_connections)
    _check_budget(mesh, corner1, corner2, segments, "connect_faces", max_faces)
    _check_pinch(pinch, pinch_center, bubble)
    first = mesh.next_ids()[1]
    if segments == 1:
        if max_connections != 0:
            quad_band(mesh, corner1, corner2)
        return edges_since(mesh, first)
    _same_size(mesh, face1, face2, "connect_faces")
    start, end = _end_rings(mesh, corner1, corner2)
    rings = []
    for i in range(1, segments):
        t = i / segments
        with np.errstate(over="ignore", invalid="ignore"):  # refused by _chain_rings
            ring = start + (end - start) * t
        rings.append(_scale_about_centroid(ring, _pinch_scale(t, pinch, pinch_center, bubble)))
    _chain_rings(mesh, corner1, corner2, rings, quad_band, max_connections)
    return edges_since(mesh, first)


def closest_corners(mesh: Mesh, face1: int, face2: int) -> tuple[int, int]:
    """The corners of two faces whose vertices are closest (TopMod's ``findClosestCorners``).

    Ties go to the first pair in ring order from the heads.

    Raises:
        DLFLError: a face id that is not an int, or not live.
    """
    _face_ids(face1, face2)
    for face in (face1, face2):
        if not mesh.has_face(face):
            raise UnknownIdError(f"face {shown(face)} does not exist (deleted or never made)")
    p1, p2 = face_points(mesh, face1), face_points(mesh, face2)
    # quarters cannot overflow in a difference, and one common power of two
    # keeps the squares in range without changing which pair is closest
    diff = together_in_range(p1[:, None, :] * 0.25 - p2[None, :, :] * 0.25)
    dist = np.linalg.norm(diff, axis=2)
    i, j = np.unravel_index(int(np.argmin(dist)), dist.shape)
    return mesh.face_corners(face1)[int(i)], mesh.face_corners(face2)[int(j)]


def connect_faces_closest(
    mesh: Mesh, face1: int, face2: int, segments: int = 1, *, max_connections: int = -1,
    pinch: float = 1.0, pinch_center: float = 0.5, bubble: float = 1.0,
    max_faces: object = None,
) -> list[int]:
    """:func:`connect_faces` from two face ids, joining their closest corners.

    TopMod's ``connectFaces(f1, f2, numsegs)`` ("Add Hole/Handle CV"); livemod
    also honours ``max_connections``, which TopMod's Python binding ignored, and
    the pinch profile (``pinch``, ``pinch_center``, ``bubble``), which its GUI
    never passed.

    Raises:
        DLFLError: as :func:`connect_faces`, or a face id that is not an int,
            or not live.
    """
    _face_ids(face1, face2)  # before the equality test: 0 == 0.0
    if face1 == face2:
        raise InvalidArgumentError(f"connect_faces_closest needs two different faces, got face "
                                   f"{shown(face1)} twice")
    c1, c2 = closest_corners(mesh, face1, face2)
    return connect_faces(mesh, c1, c2, segments, max_connections=max_connections, pinch=pinch,
                         pinch_center=pinch_center, bubble=bubble, max_faces=max_faces)


def connect_corners(
    mesh: Mesh, corner1: int, corner2: int, segments: int = 1, *,
    max_connections: int = -1, dual: bool = False, pinch: float = 1.0,
    pinch_center: float = 0.5, bubble: float = 1.0, max_faces: object = None,
) -> list[int]:
    """Join the faces of two corners: :func:`connect_faces`, or with ``dual`` a band of
    triangles (:func:`dual_connect_faces`) between every pair of consecutive rings.

    TopMod's ``connectCorners(c1, c2, numsegs, maxconn, 'dual')``. The pinch
    profile (``pinch``, ``pinch_center``, ``bubble``) shapes the quad tube; a
    dual band takes none (TopMod's has none).

    Raises:
        DLFLError: as :func:`connect_faces`; a pinch profile with ``dual``.
    """
    _check_pinch(pinch, pinch_center, bubble)
    if not dual:
        return connect_faces(mesh, corner1, corner2, segments, max_connections=max_connections,
                             pinch=pinch, pinch_center=pinch_center, bubble=bubble,
                             max_faces=max_faces)
    if (float(pinch), float(pinch_center), float(bubble)) != (1.0, 0.5, 1.0):
        raise InvalidArgumentError("a dual (triangle) band takes no pinch, pinch_center or "
                                   "bubble (TopMod's dualConnectFaces has none)")
    face1, face2 = _two_faces(mesh, corner1, corner2, "connect_corners")
    _check_segments(segments, max_connections)
    _check_budget(mesh, corner1, corner2, segments, "connect_corners", max_faces)
    first = mesh.next_ids()[1]
    if segments > 1:
        _same_size(mesh, face1, face2, "connect_corners")
    start, end = _end_rings(mesh, corner1, corner2)
    with np.errstate(over="ignore", invalid="ignore"):  # refused by _chain_rings
        rings = [start + (end - start) * (i / segments) for i in range(1, segments)]
    _chain_rings(mesh, corner1, corner2, rings, triangle_band, max_connections)
    return edges_since(mesh, first)


def connect_edges(
    mesh: Mesh, edge1: int, face1: int, edge2: int, face2: int, check: bool = True,
) -> list[int]:
    """Join two half-edges with a quad (TopMod's ``connectEdges``).

    With ``c1`` the side of ``edge1`` in ``face1`` and ``c2`` that of ``edge2`` in
    ``face2``, inserts the edges ``(c1, next(c2))`` and ``(next(c1), c2)``. With
    ``check`` a pair of corners that are already adjacent gets no edge.

    Returns:
        The ids of the (zero to two) new edges.

    Raises:
        DLFLError: an edge or face is not live, an edge is not on its face, or
            both half-edges are the same.
    """
    c1 = _side_in_face(mesh, edge1, face1, "edge1")
    c2 = _side_in_face(mesh, edge2, face2, "edge2")
    if c1 == c2:
        raise InvalidArgumentError(
            f"connect_edges needs two different half-edges, got edge {edge1} twice")
    return connect_edge_sides(mesh, c1, c2, check)


def connect_edge_sides(mesh: Mesh, side1: int, side2: int, check: bool = True) -> list[int]:
    """:func:`connect_edges` with the half-edges given as corners (a corner's edge
    runs from its vertex to the next corner's): unambiguous where an edge has both
    sides in one face.

    Returns:
        The ids of the (zero to two) new edges.

    Raises:
        DLFLError: a corner is not live, or both are the same.
    """
    c1 = _live_corner(mesh, side1, "side1")
    c2 = _live_corner(mesh, side2, "side2")
    if c1 == c2:
        raise InvalidArgumentError(
            f"connect_edge_sides needs two different corners, got corner {c1} twice")
    c1n, c2n = mesh.corner_next(c1), mesh.corner_next(c2)
    made = []
    for a, b in ((c1, c2n), (c1n, c2)):
        adjacent = mesh.corner_next(a) == b or mesh.corner_prev(a) == b
        if not (check and adjacent) and a != b:
            made.append(mesh.insert_edge(a, b))
    return made


def _side_in_face(mesh: Mesh, edge: int, face: int, what: str) -> int:
    if not mesh.has_edge(edge):
        raise UnknownIdError(f"{what}: edge {edge} does not exist (deleted or never made)")
    if not mesh.has_face(face):
        raise UnknownIdError(f"{what}: face {face} does not exist (deleted or never made)")
    for side in mesh.edge_corners(edge):
        if mesh.corner_face(side) == face:
            return side
    raise InvalidArgumentError(
        f"{what}: edge {edge} is not on face {face} (its faces: {mesh.edge_faces(edge)})")


# -- curved handles --------------------------------------------------------------------

def hermite_point(p1: np.ndarray, m1: np.ndarray, p2: np.ndarray, m2: np.ndarray,
                  t: float) -> tuple[np.ndarray, np.ndarray]:
    """Cubic Hermite curve from ``p1`` (tangent ``m1``) to ``p2`` (tangent ``m2``).

    Returns:
        ``(point, tangent)`` at ``t``, each ``(..., 3)`` like the inputs.
    """
    t2, t3 = t * t, t * t * t
    point = ((2 * t3 - 3 * t2 + 1) * p1 + (t3 - 2 * t2 + t) * m1
             + (-2 * t3 + 3 * t2) * p2 + (t3 - t2) * m2)
    tangent = ((6 * t2 - 6 * t) * p1 + (3 * t2 - 4 * t + 1) * m1
               + (-6 * t2 + 6 * t) * p2 + (3 * t2 - 2 * t) * m2)
    return point, tangent


def rotation_between(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``(3, 3)`` the smallest rotation taking unit vector ``a`` to unit vector ``b``.

    Parallel or opposite vectors give the identity, as TopMod's ``rotate``
    (an axis cannot be chosen for them).
    """
    v = np.cross(a, b)
    c = float(np.dot(a, b))
    if float(v @ v) < 1e-18:
        return np.eye(3)
    k = np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])
    return np.eye(3) + k + k @ k / (1.0 + c)


def _handle_ends(mesh: Mesh, corner1: int, corner2: int, segments: int, op: str,
                 max_faces: object) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Checks shared by the handles (the face budget too); returns the end rings
    and their normals (the second face's normal reversed, as it is seen from the
    first)."""
    face1, face2 = _two_faces(mesh, corner1, corner2, op)
    _check_segments(segments)
    _same_size(mesh, face1, face2, op)
    _check_budget(mesh, corner1, corner2, segments, op, max_faces)
    start, end = _end_rings(mesh, corner1, corner2)
    n1, n2 = polygon_normal(start), polygon_normal(end)
    if not (np.any(n1) and np.any(n2)):
        raise GeometryError(f"{op} needs faces with a normal (not 2-gons or degenerate faces)")
    return start, end, n1, n2


def hermite_rings(
    start: np.ndarray, end: np.ndarray, n1: np.ndarray, n2: np.ndarray, segments: int,
    weight1: float, weight2: float, twists: int = 0,
    pinch: tuple[float, float, float] = (1.0, 0.5, 1.0),
) -> list[np.ndarray]:
    """The intermediate rings of a Hermite handle (TopMod's ``hermiteConnectFaces``).

    Each end polygon, centred at the origin, is turned (smallest rotation) from
    its normal to ``axis = normalize(c2 - c1)`` and resolved into (angle,
    distance) pairs about its centroid against ``x = normalize(q_0 + q_{n-1})``
    (q: ring 1 turned) and ``y = axis x x`` (:func:`resolve_polygon`). Face 2's
    angles lose 2π when they start more than π past face 1's, then gain
    ``2π twists``. Ring ``i`` at ``t = i / segments`` interpolates angles and
    distances linearly, is scaled about its centroid by the pinch profile
    ``(pinch, center, bubble)``, turned from ``axis`` to the Hermite tangent,
    and its centroid put on the Hermite curve from ``c1`` (tangent
    ``weight1 n1``) to ``c2`` (tangent ``weight2 n2``).

    Args:
        start, end: ``(n, 3)`` end polygons, vertex ``i`` facing vertex ``i``.
        n1, n2: ``(3,)`` unit normals of the end polygons, both along the handle.

    Returns:
        ``segments - 1`` arrays of shape ``(n, 3)``.

    Raises:
        DLFLError: the centroids coincide, or a normal points exactly against the
            centroid-to-centroid axis (TopMod refused these too).
    """
    c1, c2 = centroid(start), centroid(end)
    size = float(max(lengths(start - c1).max(), lengths(end - c2).max()))
    axis = _handle_axis(c1, c2, n1, n2, size)
    q1 = (start - c1) @ rotation_between(n1, axis).T
    q2 = (end - c2) @ rotation_between(n2, axis).T
    x = unit((q1[0] + q1[-1])[None])[0]  # unit(): its norm squares huge rings
    y = np.cross(axis, x)
    a1, d1 = resolve_polygon(q1, x, y)
    a2, d2 = resolve_polygon(q2, x, y)
    if a2[0] - a1[0] > np.pi:
        a2 = a2 - 2 * np.pi
    a2 = a2 + 2 * np.pi * twists
    return [_hermite_ring(i / segments, (a1, d1, a2, d2), (x, y, axis),
                          (c1, weight1 * n1, c2, weight2 * n2), pinch)
            for i in range(1, segments)]


def _hermite_ring(t: float, polar: _Four, frame: tuple[np.ndarray, np.ndarray, np.ndarray],
                  curve: _Four, pinch: tuple[float, float, float]) -> np.ndarray:
    """``(n, 3)`` the ring of :func:`hermite_rings` at ``t``. ``polar``: the ``(n,)``
    angles and distances of both ends; ``frame``: ``(3,)`` x, y and axis;
    ``curve``: ``(3,)`` the Hermite ends and tangents. Points beyond the float
    range come out inf or NaN, which :func:`_chain_rings` refuses."""
    a1, d1, a2, d2 = polar
    x, y, axis = frame
    with np.errstate(over="ignore", invalid="ignore"):  # refused by _chain_rings
        angle, dist = a1 + (a2 - a1) * t, d1 + (d2 - d1) * t
        flat = dist[:, None] * (np.cos(angle)[:, None] * x + np.sin(angle)[:, None] * y)
        flat = (flat - flat.mean(axis=0)) * _pinch_scale(t, *pinch)
        p1, m1, p2, m2 = curve
        point, tangent = hermite_point(p1, m1, p2, m2, t)
        turn = rotation_between(axis, unit(tangent[None])[0])
        return point + flat @ turn.T


def _handle_axis(c1: np.ndarray, c2: np.ndarray, n1: np.ndarray, n2: np.ndarray,
                 size: float) -> np.ndarray:
    """``(3,)`` unit vector from centroid ``c1`` to ``c2``, checked against the
    ``(3,)`` unit normals (see :func:`hermite_rings` for what is refused).
    ``size``: the end rings' largest centroid distance, so that "the centroids
    coincide" means the same at every scale (an absolute 1e-12 refused every
    handle on a mesh 1e-13 across)."""
    # quarters: the difference of two huge centroids cannot overflow
    axis = c2 * 0.25 - c1 * 0.25
    if float(lengths(axis[None])[0]) < 0.25e-12 * size:
        raise GeometryError("a Hermite handle needs faces with different centroids")
    axis = unit(axis[None])[0]
    if min(float(n1 @ axis), float(n2 @ axis)) < -1.0 + 1e-9:
        raise GeometryError("a face normal points exactly against the handle's axis; "
                            "TopMod cannot build this handle either (use a bezier handle)")
    return axis


def resolve_polygon(points: np.ndarray, x: np.ndarray, y: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """``(n,)`` angles and ``(n,)`` distances of ``(n, 3)`` points about their centroid,
    against the axes ``x`` and ``y`` (TopMod's ``resolvePolygon``): the first angle
    in ``[0, 2π)``, each next one the first value at or above the previous one."""
    rel = points - centroid(points)
    raw = np.arctan2(rel @ y, rel @ x)
    steps = np.mod(np.diff(raw), 2 * np.pi)
    angles = np.mod(raw[0], 2 * np.pi) + np.concatenate([[0.0], np.cumsum(steps)])
    return angles, lengths(rel)  # lengths(): a norm would square huge distances


def hermite_handle(
    mesh: Mesh, corner1: int, corner2: int, segments: int = 10, weight1: float = 25.0,
    weight2: float = 25.0, *, max_connections: int = -1, twists: int = 0,
    pinch: float = 1.0, pinch_center: float = 0.5, bubble: float = 1.0,
    max_faces: object = None,
) -> list[int]:
    """A handle whose centroid path is a Hermite curve (TopMod's ``hermiteConnectFaces``).

    Rings as in :func:`hermite_rings`, joined in turn with quads like
    :func:`connect_faces` (at most ``max_connections`` joins, -1 for all). Defaults
    are TopMod's GUI ("Add Handle SI": 10 segments, weights 25 and 25). Cube
    faces 0 and 1 with 10 segments: 44/88/44. One segment is :func:`connect_faces`.
    Negative ``twists`` turn the other way (TopMod ignored them).

    Returns:
        The ids of the new edges.

    Raises:
        DLFLError: a corner is not live, both are in one face, faces of different
            sizes with ``segments`` > 1 (TopMod silently did nothing),
            ``segments`` not an integer >= 1 or more than a mesh can hold, a
            weight that is not a finite number, or see
            :func:`hermite_rings`.
    """
    _check_segments(segments, max_connections)
    _check_weights(weight1, weight2)
    # checked even for one segment, which reads neither: a typo must not pass
    turns = _check_twists(twists)
    _check_pinch(pinch, pinch_center, bubble)
    if segments == 1:  # TopMod: a plain connectFaces, whatever the sizes and normals
        return connect_faces(mesh, corner1, corner2, max_connections=max_connections,
                             max_faces=max_faces)
    start, end, n1, n2 = _handle_ends(mesh, corner1, corner2, segments, "hermite_handle",
                                      max_faces)
    rings = hermite_rings(start, end, n1, n2, segments, weight1, weight2, turns,
                          (pinch, pinch_center, bubble))
    first = mesh.next_ids()[1]
    _chain_rings(mesh, corner1, corner2, rings, quad_band, max_connections)
    return edges_since(mesh, first)


def bezier_rings(start: np.ndarray, end: np.ndarray, n1: np.ndarray, n2: np.ndarray,
                 segments: int, weight1: float, weight2: float) -> list[np.ndarray]:
    """Rings of a Bezier handle: vertex ``j`` of ring ``i`` is the Hermite curve from
    ``start[j]`` (tangent ``weight1 * n1``) to ``end[j]`` (``weight2 * n2``) at ``i / segments``.

    Returns:
        ``segments - 1`` arrays of shape ``(n, 3)``.
    """
    with np.errstate(over="ignore", invalid="ignore"):  # refused by _chain_rings
        return [hermite_point(start, weight1 * n1, end, weight2 * n2, i / segments)[0]
                for i in range(1, segments)]


def bezier_handle(
    mesh: Mesh, corner1: int, corner2: int, segments: int = 10,
    weight1: float = 25.0, weight2: float = 25.0, *, max_faces: object = None,
) -> list[int]:
    """A handle whose every vertex follows its own Hermite curve (TopMod's
    ``bezierConnectFaces``); see :func:`bezier_rings`. Rings are joined with quads.

    Returns:
        The ids of the new edges.

    Raises:
        DLFLError: as :func:`hermite_handle` (faces of different sizes included).
    """
    _check_weights(weight1, weight2)
    start, end, n1, n2 = _handle_ends(mesh, corner1, corner2, segments, "bezier_handle",
                                      max_faces)
    rings = bezier_rings(start, end, n1, n2, segments, weight1, weight2)
    first = mesh.next_ids()[1]
    _chain_rings(mesh, corner1, corner2, rings, quad_band, -1)
    return edges_since(mesh, first)


# the multi-face family (multihandle.py) builds on the connections above; these
# names stay reachable here, where users of the connect family looked for them,
# loaded on first use so that neither module imports the other at import time
_MULTIHANDLE_NAMES = frozenset({
    "add_polyhedron", "face_max_offsets", "fitted_factor", "multi_face_handle",
    "multi_face_handle_closest_edges", "multi_face_handle_fitted"})


def __getattr__(name: str) -> object:
    """``connect.multi_face_handle`` and the rest of :mod:`.multihandle` (PEP 562)."""
    if name in _MULTIHANDLE_NAMES:
        from . import multihandle

        return getattr(multihandle, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
