"""Convex hulls of point sets, and TopMod's convex-hull sculpting operations.

:func:`hull_polygons` is livemod's one convex-hull routine: the joints of
:func:`.wireframe.columns`, the hub of :func:`.connect.multi_face_handle` and
:func:`convex_hull` / :func:`dual_convex_hull` all use it. It wraps the hull
face by face (gift wrapping: each new face is found by turning the plane of a
known face about one of its sides, one pass over the points per hull edge), so
it takes O(points x edges) time, and coplanar facets come out merged as one
convex polygon.

For up to ``_SMALL`` points (a column joint, a hub), once turning has found one
triangle, the hull's triangles are looked up instead (:mod:`._hull_table`): the
planes through every three points are tried in one array pass, and a plane with
every point on one side and only its three on it is the triangle turning would
reach across each of its sides. Only the other faces are turned to, so the
result is the same, polygon for polygon, in the same order, with the same
normals bit for bit (a looked-up triangle's is computed as turning computes it,
when needed).

For more than ``_LARGE`` points (a mesh's vertices: turning took 38 s for
24,600 of them), a batched quickhull (:mod:`._quickhull`, numpy rounds) builds
a triangulated hull first and checks each of its triangles the way the lookup
checks triples, against the points near it. The triangles that pass are faces
as they are; only the faces across the sides of the others (faces with points
near their plane or on their edges) are turned to. The faces are turning's,
polygon for polygon (their normals to the tolerance), but they come **sorted**
instead of in wrapping order: each from its least point index, ordered by that
index, then by the next (walking them in turning's order was a Python loop over
every face; nothing relies on the order of a large hull). Where turning cannot
close up (points too nearly on one plane for the tolerance: four nearly on one
circle, which grows likely with thousands of points), the quickhull's triangles
are the result instead of a refusal.

**Face order**: up to ``_LARGE`` (1,000) points, the order gift wrapping finds
the faces in (:func:`_wrapped`: the first face, then depth first across each
side), each face from the corner turning reached it by; above, sorted as above.
Both are deterministic: the same points give the same faces in the same order.

**Coplanar rule** (the same for every caller):

* a point on the hull's surface is a polygon vertex when it is a corner of a
  face *or lies on a hull edge*; a point on an edge is then a vertex of both
  faces beside that edge, so the faces still pair side for side and every
  point on the hull's edges is used;
* a point inside a face (off its boundary), a point inside the hull, and a
  repeat of a point that comes earlier in the input are vertices of no polygon.

"On" means within ``tolerance`` times the points' largest extent (along an
axis), so the faces do not depend on the scale of the points. Every other
threshold here scales with them too (a multiple of that distance or of its
product with a length, or a test on unit vectors), and points outside the
float band are moved and scaled by a power of two first: a set scaled by
1e-150 or 1e+150 gives the same polygons.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import NamedTuple, TypeAlias

import numpy as np

from ._hull_faces import check_closed, flat_faces, not_closed, vertex_face_rings
from ._hull_table import triangle_table as _triangle_table
from ._quickhull import convex, quickhull, verified_triangles
from ._vectors import range_exponent, shifted_in_range
from .budget import check_size
from .build import from_polygons
from .errors import DLFLError, GeometryError, InvalidArgumentError
from .mesh import Mesh
from .soup import offsets_of

__all__ = ["hull_polygons", "hull_triangles", "convex_hull", "dual_convex_hull"]


# an outward unit normal, either ``(3,)`` or, for a triangle face found across
# side ``u -> v`` with third corner ``c``, ``(u, v, c)`` until it is needed
_Normal: TypeAlias = np.ndarray | tuple[int, int, int]

# ``across(u, v, normal)``: the face across side ``u -> v`` of the face with that
# normal, as ``(polygon, its normal)``
_Across: TypeAlias = Callable[[int, int, _Normal], tuple[list[int], _Normal]]

_AXES = np.eye(3)
_AXES.flags.writeable = False
_X, _Y, _Z = _AXES

# up to this many points, the hull's triangles are looked up (_triangle_table)
_SMALL = 32
# above this many, the faces are walked over a batched quickhull (_quickhull): below
# it, turning is as fast (a cloud's few hull faces, a lattice's squares)
_LARGE = 1000

class _Hull(NamedTuple):
    """A wrapped hull. ``points`` are the input moved and scaled by a power of two
    when it leaves the float band: the input is ``origin + points * 2**exponent``."""

    points: np.ndarray  # (n, 3) float
    origin: np.ndarray  # (3,) float
    exponent: int
    eps: float  # the absolute tolerance in ``points``' units
    # the polygons, or for a large hull as (corners, offsets): see flat_faces
    faces: list[list[int]] | tuple[np.ndarray, np.ndarray]
    # outward unit normal of each polygon: see _resolved, or (F, 3) for a large hull
    normals: list[_Normal] | np.ndarray

    @property
    def polygons(self) -> list[list[int]]:
        """One list of point indices per face."""
        if isinstance(self.faces, list):
            return self.faces
        corners, offsets = self.faces
        flat, bounds = corners.tolist(), offsets.tolist()
        return [flat[a:b] for a, b in zip(bounds[:-1], bounds[1:], strict=True)]

    def flat(self) -> tuple[np.ndarray, np.ndarray]:
        """``(corners, offsets)`` of the faces (:func:`._hull_faces.flat_faces`)."""
        return self.faces if isinstance(self.faces, tuple) else flat_faces(self.faces)


def hull_polygons(points: np.ndarray, tolerance: float = 1e-9) -> list[list[int]]:
    """Faces of the convex hull of ``(n, 3)`` points, coplanar facets merged.

    Which points are polygon vertices follows the module's coplanar rule: the
    corners and the points on hull edges are, points inside a face or inside
    the hull and repeated points are not.

    Args:
        points: ``(n, 3)`` float positions, at least 4 and not all in one plane.
        tolerance: how far (times the points' largest extent) a point may be from
            a plane, line or point and still count as on it.

    Returns:
        One list of point indices per face, counter-clockwise seen from outside;
        together a closed genus-0 surface. In wrapping order for up to 1,000
        points; above, each face from its least index, the faces sorted by that
        index and the next (see the module's face order).

    Raises:
        DLFLError: fewer than 4 points, a point or a difference of two that is
            not finite, all points in one plane, or faces that do not close up
            (points too nearly coplanar for the tolerance).
    """
    return _wrap_hull(points, tolerance).polygons


def hull_triangles(points: np.ndarray, tolerance: float = 1e-9) -> list[list[int]]:
    """:func:`hull_polygons` cut into triangles, none of them flat.

    A face without points on its edges becomes a fan from its last corner. A
    face with points on its edges is cut ear by ear instead: each time at the
    first corner that juts out (is not in line with its two neighbours) next to
    one that does not, which never leaves a flat triangle.

    Returns:
        ``[i, j, k]`` point indices per triangle, counter-clockwise seen from
        outside, face by face in :func:`hull_polygons` order.

    Raises:
        DLFLError: as :func:`hull_polygons`.
    """
    hull = _wrap_hull(points, tolerance)
    return [t for poly in hull.polygons for t in _ears(hull.points, poly, hull.eps)]


def convex_hull(mesh: Mesh, *, max_faces: object = None) -> None:
    """TopMod's ``createConvexHull()``: replace ``mesh`` by the convex hull of its
    vertices, in triangles (:func:`hull_triangles`; coplanar facets are merged
    first, then each face is cut into a fan from its last corner). Cube:
    8/18/12, 12 triangles, as TopMod.

    Vertices that are hull corners or lie on hull edges are kept at their
    positions (in id order); the others are dropped. The mesh is rebuilt (fresh
    ids), its faces in :func:`hull_polygons` order (above 1,000 vertices: sorted
    by their least vertex, each polygon's triangles in turn). TopMod built the
    hull incrementally, so which coplanar points it kept, and how it split
    coplanar faces, depended on the vertex order.

    Raises:
        DLFLError: fewer than 4 vertices, a position difference beyond the float
            range, or all vertices in one plane; the mesh is unchanged.
        BudgetExceededError: the hull could pass the face budget: at most
            ``2V - 4`` triangles (``max_faces``; None: the session's, see
            :mod:`livemod.dlfl.budget`).
    """
    most = max(2 * mesh.num_vertices - 4, 0)
    check_size("convex hull", most, 3 * most, max_faces=max_faces)
    triangles = _triangle_array(_wrap_hull(mesh.positions_view()))
    _rebuild(mesh, mesh.positions_view(), triangles.ravel(),
             np.arange(0, triangles.size + 1, 3))


def dual_convex_hull(mesh: Mesh, *, max_faces: object = None) -> None:
    """Replace ``mesh`` by the polar dual of the convex hull of its vertices.

    The hull's coplanar facets are merged first (:func:`hull_polygons`), so the
    dual has one vertex per hull face and one face per hull vertex (corners and
    points on edges): a cube gives an octahedron, 6/12/8. Hull face ``f`` with
    outward unit normal ``n`` at distance ``d`` from ``c``, the centroid of the
    hull's vertices, becomes the vertex ``c + r**2 n / d``, ``r`` the root mean
    square distance of the hull's vertices from ``c``; a hull vertex at distance
    ``r`` lies on its dual face. The faces are planar and the result is convex.
    The mesh is rebuilt (fresh ids): vertex ``i`` for hull face ``i`` in
    :func:`hull_polygons` order, one face per hull vertex in id order, each
    starting at the first hull face around that vertex.

    livemod differs here (TopMod's ``createDualConvexHull()``): TopMod cut the
    bounding box by the plane through each hull vertex along its vertex normal,
    which for a cube cuts nothing and gives back the box (8/12/6).

    Raises:
        DLFLError: as :func:`convex_hull`, or a dual vertex beyond the float
            range (a very flat hull); the mesh is unchanged.
        BudgetExceededError: the dual could pass the face budget: a face per
            vertex, at most ``6V - 12`` corners.
    """
    vertices = mesh.num_vertices
    check_size("dual convex hull", vertices, max(6 * vertices - 12, 0), max_faces=max_faces)
    hull = _wrap_hull(mesh.positions_view())
    corners, offsets = hull.flat()
    _rebuild(mesh, _polar_points(hull, corners, offsets), *vertex_face_rings(corners, offsets))


# -- the wrapping ------------------------------------------------------------------


def _wrap_hull(points: np.ndarray, tolerance: float = 1e-9) -> _Hull:
    """The hull of ``(n, 3)`` ``points``; see :func:`hull_polygons`."""
    pts, origin, exponent = _frame(points)
    extent = float(np.ptp(pts, axis=0).max())
    eps = tolerance * extent
    _check_not_flat(pts, eps)
    if len(pts) > _LARGE:
        return _Hull(pts, origin, exponent, eps, *_large_hull(pts, eps, extent))
    polygons, normals = _wrapped(pts, eps, _across(pts, eps, extent))
    _check_closed(polygons)
    return _Hull(pts, origin, exponent, eps, polygons, normals)


def _large_hull(pts: np.ndarray, eps: float, extent: float
                ) -> tuple[tuple[np.ndarray, np.ndarray], np.ndarray]:
    """``((corners, offsets), (F, 3) outward unit normals)`` of the hull of more
    than ``_LARGE`` points, in :func:`_in_order`: the batched quickhull's
    verified triangles as they are and the faces across the others' sides
    turned to (:func:`_walked`). Where those do not close up (points too nearly
    on one plane for the tolerance: four nearly on one circle), the quickhull's
    triangles are the hull, once every edge is checked convex; where the
    quickhull gave up (rounding broke a round), every face is turned to.

    Raises:
        DLFLError: the faces do not close up.
    """
    quick = _quick(pts, eps, extent)
    if quick is None:
        polygons, normals = _wrapped(pts, eps, _across(pts, eps, extent))
        check_closed(*flat_faces(polygons))
        corners, offsets, outward = _in_order(pts, np.zeros((0, 3), np.int64), polygons, normals)
        return (corners, offsets), outward
    try:
        triangles, polygons, normals = _walked(pts, eps, quick)
    except DLFLError:
        if not convex(pts, quick.tri, 4.0 * eps, extent):
            raise
        triangles, polygons, normals = quick.tri, [], []
    corners, offsets, outward = _in_order(pts, triangles, polygons, normals)
    if polygons:  # a turned face may not fit the triangles around it
        check_closed(corners, offsets)
    return (corners, offsets), outward


def _in_order(pts: np.ndarray, triangles: np.ndarray, polygons: list[list[int]],
              normals: list[_Normal]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(corners, offsets, (F, 3) outward unit normals)`` of the ``(k, 3)``
    ``triangles`` (each from its least index) and the other ``polygons`` (with
    their ``normals``), in the order of a large hull: each face from its least
    point index, sorted by that index, then by the next."""
    rotated = [poly[i:] + poly[:i] for poly in polygons for i in [poly.index(min(poly))]]
    others, other_offsets = flat_faces(rotated)
    flat = np.concatenate([triangles.ravel(), others])
    starts = np.concatenate([np.arange(0, triangles.size, 3), triangles.size + other_offsets[:-1]])
    sizes = np.concatenate([np.full(len(triangles), 3), np.diff(other_offsets)])
    order = np.argsort(flat[starts] * (int(flat.max(initial=0)) + 1) + flat[starts + 1])
    offsets = offsets_of(sizes[order])
    moved = np.repeat(starts[order] - offsets[:-1], sizes[order]) + np.arange(len(flat))
    outward = np.concatenate([_triangle_normals(pts, triangles),
                              _resolved_all(pts, normals).reshape(-1, 3)])
    return flat[moved], offsets, outward[order]


class _Quick(NamedTuple):
    """The batched quickhull's triangles (:func:`._quickhull.quickhull`), each
    from its least index, with the triangle across each side (side ``j`` from
    corner ``j`` to ``j + 1``), and which of them are hull faces as they are
    (:func:`._quickhull.verified_triangles`)."""

    tri: np.ndarray  # (F, 3) int
    nbr: np.ndarray  # (F, 3) int
    verified: np.ndarray  # (F,) bool


def _quick(pts: np.ndarray, eps: float, extent: float) -> _Quick | None:
    """The :class:`_Quick` hull of ``(n, 3)`` ``pts``, or None when it gave up."""
    found = quickhull(pts, eps)
    if found is None:
        return None
    tri, nbr = found
    turn = (np.argmin(tri, axis=1)[:, None] + np.arange(3)) % 3
    tri, nbr = np.take_along_axis(tri, turn, axis=1), np.take_along_axis(nbr, turn, axis=1)
    return _Quick(tri, nbr, verified_triangles(pts, tri, eps, extent))


def _walked(pts: np.ndarray, eps: float, quick: _Quick
            ) -> tuple[np.ndarray, list[list[int]], list[_Normal]]:
    """``(triangles, polygons, normals)``: the ``(k, 3)`` verified triangles of
    ``quick`` as they are, and the other faces with their normals, turned to
    (:func:`_face_beyond`: faces with points near their plane or on their
    edges) across the sides of the faces found, depth first from the verified
    triangles beside the others (from :func:`_first_face` when none is
    verified); their sides are claimed by name.

    Raises:
        DLFLError: a turned face does not share the side it was found across,
            or there are more faces than a hull of these points can have.
    """
    verified = quick.verified
    if verified.all():
        return quick.tri, [], []
    turned = _across(pts, eps, 0.0)  # more than _SMALL points: no lookup
    walk = _Walk(quick, len(pts))
    seeds = np.flatnonzero(verified & ~np.take(verified, quick.nbr).all(axis=1))
    for g, (a, b, c) in zip(seeds.tolist(), quick.tri[seeds].tolist(), strict=True):
        walk.todo.append(([a, b, c], (b, a, c), g))
    if not walk.todo:
        walk.add(*_first_face(pts, eps, turned))
    nbr, taken, named = quick.nbr, walk.taken, walk.named
    while walk.todo:
        poly, normal, f = walk.todo.pop()
        for j, u in enumerate(poly):
            v = poly[(j + 1) % len(poly)]
            g = int(nbr[f, j]) if f >= 0 else walk.triangle(v, u)
            if (named and (v, u) in named) or (g >= 0 and taken[g]):
                continue
            found, plane = turned(u, v, normal)
            if (v, u) not in _sides(found) or len(walk.polygons) > 2 * len(pts):
                raise not_closed()
            walk.add(found, plane)
    return quick.tri[verified], walk.polygons, walk.normals


class _Walk:
    """The faces :func:`_walked` has turned to, and which sides the faces found
    claim: a triangle of the quickhull by its index (every verified one is
    claimed from the start), any other face by its sides."""

    def __init__(self, quick: _Quick, n: int) -> None:
        self.tri, self.n = quick.tri, n
        self.taken = quick.verified.copy()
        self.named: set[tuple[int, int]] = set()  # sides of faces that are no triangle of it
        self.polygons: list[list[int]] = []
        self.normals: list[_Normal] = []
        # faces whose sides are still to cross: (polygon, normal, quickhull index or -1)
        self.todo: list[tuple[list[int], _Normal, int]] = []
        self._sides: tuple[np.ndarray, np.ndarray] | None = None

    def triangle(self, u: int, v: int) -> int:
        """The quickhull triangle with side ``u -> v``, -1 for none (a turned face
        can have a side the quickhull's triangles do not)."""
        if self._sides is None:  # sorted side keys, and where each is
            keys = (self.tri * self.n + np.roll(self.tri, -1, axis=1)).ravel()
            order = np.argsort(keys)
            self._sides = keys[order], order
        keys, order = self._sides
        key = u * self.n + v
        at = int(np.searchsorted(keys, key))
        if at == len(keys) or keys[at] != key:
            return -1
        return int(order[at]) // 3

    def add(self, poly: list[int], normal: _Normal) -> None:
        """Record turned face ``poly`` (it may be a triangle of the quickhull)."""
        index = -1
        if len(poly) == 3:
            g = self.triangle(poly[0], poly[1])
            index = g if g >= 0 and self.tri[g].tolist() == poly else -1
        if index >= 0:
            self.taken[index] = True
        else:
            self.named.update(_sides(poly))
        self.polygons.append(poly)
        self.normals.append(normal)
        self.todo.append((poly, normal, index))


def _across(pts: np.ndarray, eps: float, extent: float) -> _Across:
    """The face across a side, turned to (:func:`_face_beyond`) or, for up to
    ``_SMALL`` points once turning has found a triangle (a hull of squares would
    not repay the table), looked up (:func:`_triangle_table`)."""
    table: dict[tuple[int, int], tuple[list[int], int]] | None = None

    def across(u: int, v: int, normal: _Normal) -> tuple[list[int], _Normal]:
        nonlocal table
        found = table.get((v, u)) if table is not None else None
        if found is not None:
            return found[0], (u, v, found[1])
        poly, plane = _face_beyond(pts, u, v, _resolved(pts, normal), eps)
        if table is None and len(poly) == 3 and len(pts) <= _SMALL:
            table = _triangle_table(pts, eps, extent)
        return poly, plane

    return across


def _wrapped(pts: np.ndarray, eps: float, across: _Across
             ) -> tuple[list[list[int]], list[_Normal]]:
    """``(polygons, normals)`` of the hull in wrapping order: :func:`_first_face`,
    then depth first the face ``across`` each side that no face found so far shares.

    Raises:
        DLFLError: a face that does not share the side it was found across, or
            more faces than a hull of these points can have.
    """
    first, normal = _first_face(pts, eps, across)
    polygons, normals, sides_of = [first], [normal], [_sides(first)]
    claimed = set(sides_of[0])
    todo = [0]
    while todo:
        f = todo.pop()
        for u, v in sides_of[f]:
            if (v, u) in claimed:
                continue
            poly, normal = across(u, v, normals[f])
            sides = _sides(poly)
            if (v, u) not in sides or len(polygons) > 2 * len(pts):
                raise not_closed()
            polygons.append(poly)
            normals.append(normal)
            sides_of.append(sides)
            claimed.update(sides)
            todo.append(len(polygons) - 1)
    return polygons, normals


def _frame(points: np.ndarray) -> tuple[np.ndarray, np.ndarray, int]:
    """``(framed, origin, exponent)``: ``(n, 3)`` ``points`` as the hull works on
    them (:func:`.shifted_in_range`), with ``points = origin + framed * 2**exponent``.

    Raises:
        DLFLError: not ``(n, 3)``, fewer than 4 points, or a point or a difference
            of two that is not finite.
    """
    pts = np.asarray(points, dtype=np.float64)
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise InvalidArgumentError(f"a convex hull needs (n, 3) points, got shape {pts.shape}")
    if len(pts) < 4:
        raise InvalidArgumentError(f"a convex hull needs at least 4 points, got {len(pts)}")
    framed = shifted_in_range(pts)
    # before LAPACK: it prints its own complaint about NaN to stderr
    if not (np.isfinite(pts).all() and np.isfinite(framed).all()):
        raise GeometryError("a convex hull needs finite points whose differences are finite; "
                            "these overflow")
    if framed is pts:
        return pts, np.zeros(3), 0
    return framed, pts[0], range_exponent(pts - pts[0])


def _check_not_flat(pts: np.ndarray, eps: float) -> None:
    """Refuse ``(n, 3)`` points that all lie within ``eps`` of their least-squares
    plane (normal to the smallest singular vector of the centred points).

    The singular value decomposition is skipped when the points are plainly
    spread out: the sum of their squared distances from that plane is the
    smallest eigenvalue of their scatter matrix ``S``, at least
    ``4 det(S) / trace(S)**2``, so the farthest lies beyond ``eps`` when that
    bound exceeds ``n eps**2`` (asked here by a factor of a million, and of
    ``det(S)`` far above its own rounding).
    """
    centred = pts - pts.mean(axis=0)
    (a, b, c), (_, d, e), (_, _, f) = (centred.T @ centred).tolist()
    det, trace = a * (d * f - e * e) - b * (b * f - c * e) + c * (b * e - c * d), a + d + f
    bound = max(1e6 * len(pts) * eps * eps, 1e-10 * trace) * trace * trace
    if math.isfinite(det) and 4.0 * det > bound:
        return
    normal = np.linalg.svd(centred, full_matrices=False)[2][-1]
    if not np.abs(centred @ normal).max() > eps:
        raise GeometryError("a convex hull needs at least 4 points not all in one plane; "
                            f"these {len(pts)} points are coplanar")


def _sides(poly: list[int]) -> list[tuple[int, int]]:
    """The directed sides ``(a, b)`` of a polygon, in order."""
    return list(zip(poly, poly[1:] + poly[:1], strict=True))


def _first_face(pts: np.ndarray, eps: float, across: _Across) -> tuple[list[int], _Normal]:
    """``(polygon, outward unit normal)`` of one hull face: the plane ``x = min``
    turned about a line through the lowest point ``a`` until it rests on the
    hull, then, if it touches only along a line ``a -> b``, the face ``across`` it."""
    a = int(np.lexsort(pts.T[::-1])[0])  # lowest x, then y, then z
    normal = _turned_plane(pts, a, _Z, -_X, eps)
    poly = _face_polygon(pts, a, normal, eps)
    found: _Normal = normal
    if len(poly) < 3:
        b = poly[-1] if poly[-1] != a else poly[0]
        poly, found = across(a, b, normal)
    if len(poly) < 3:
        raise not_closed()
    return poly, found


def _face_beyond(pts: np.ndarray, u: int, v: int, normal: np.ndarray, eps: float
                 ) -> tuple[list[int], np.ndarray]:
    """``(polygon, outward unit normal)`` of the hull face across side ``u -> v``
    of the face with outward unit ``normal``."""
    axis = _unit3(pts[v] - pts[u])
    beyond = _turned_plane(pts, u, axis, normal, eps)
    return _face_polygon(pts, u, beyond, eps), beyond


def _turned_plane(pts: np.ndarray, a: int, axis: np.ndarray, normal: np.ndarray,
                  eps: float) -> np.ndarray:
    """``(3,)`` outward unit normal of the supporting plane reached by turning the
    supporting plane with ``normal`` about the line through point ``a`` along the
    unit ``axis`` (the plane's inner side ahead, ``normal x axis``, turning down).

    The point seen at the widest angle gives the plane; while some point lies
    above it (the angle of a point near the line is inexact), the plane is
    turned on to the highest one.
    """
    w = pts - pts[a]
    x, y = w @ _cross3(normal, axis), w @ normal
    off_line = np.hypot(x, y) > eps
    angle = np.where(off_line, np.arctan2(np.maximum(-y, 0.0), x), -1.0)
    best = w[int(angle.argmax())]
    for _ in range(len(pts)):
        plane = _unit3(_cross3(best, axis))
        height = w @ plane
        top = int(height.argmax())
        if height[top] <= eps:
            return plane
        best = w[top]
    raise not_closed()


def _unit3(v: np.ndarray) -> np.ndarray:
    """``(3,)`` ``v`` scaled to length 1.

    Raises:
        DLFLError: ``v`` is zero (or not finite): the points are too degenerate
            to turn a plane about (two that coincide, a line through them).
    """
    length = math.sqrt(v @ v)
    if not 0.0 < length < math.inf:
        raise not_closed()
    return v / length


def _cross3(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a x b`` of two ``(3,)`` vectors, without :func:`numpy.cross`'s overhead
    (in Python floats: the same roundings as numpy's, one operation at a time)."""
    (a0, a1, a2), (b0, b1, b2) = a.tolist(), b.tolist()
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def _resolved(pts: np.ndarray, normal: _Normal) -> np.ndarray:
    """``(3,)`` outward unit normal ``normal`` (see ``_Normal``): for a triangle
    found across ``u -> v`` with third corner ``c``, the plane :func:`_turned_plane`
    turns to about that side, computed as it does, bit for bit."""
    if not isinstance(normal, tuple):
        return normal
    u, v, c = normal
    return _unit3(_cross3(pts[c] - pts[u], _unit3(pts[v] - pts[u])))


def _resolved_all(pts: np.ndarray, normals: list[_Normal]) -> np.ndarray:
    """``(F, 3)``: :func:`_resolved` of every normal, the triangles' at once (to
    the last bit or so: numpy's dot of three may round once differently)."""
    out = np.empty((len(normals), 3))
    lazy = [i for i, n in enumerate(normals) if isinstance(n, tuple)]
    for i, n in enumerate(normals):
        if not isinstance(n, tuple):
            out[i] = n
    if lazy:
        u, v, c = np.array([normals[i] for i in lazy]).T
        out[lazy] = _turned_normals(pts, u, v, c)
    return out


def _triangle_normals(pts: np.ndarray, tri: np.ndarray) -> np.ndarray:
    """``(F, 3)`` outward unit normals of the ``(F, 3)`` triangles ``tri``, as
    turning finds each across its first side (:func:`_resolved`)."""
    return _turned_normals(pts, tri[:, 1], tri[:, 0], tri[:, 2])


def _turned_normals(pts: np.ndarray, u: np.ndarray, v: np.ndarray, c: np.ndarray
                    ) -> np.ndarray:
    """``(k, 3)``: :func:`_resolved` of the normals ``(u[i], v[i], c[i])``."""
    x, y, z = pts.T  # by coordinate: gathers from columns are faster than of rows
    ux, uy, uz = x[u], y[u], z[u]
    sx, sy, sz = x[v] - ux, y[v] - uy, z[v] - uz
    length = np.sqrt(sx * sx + sy * sy + sz * sz)
    sx, sy, sz = sx / length, sy / length, sz / length
    wx, wy, wz = x[c] - ux, y[c] - uy, z[c] - uz
    turned = np.stack([wy * sz - wz * sy, wz * sx - wx * sz, wx * sy - wy * sx], axis=1)
    return turned / np.sqrt(np.einsum("ij,ij->i", turned, turned))[:, None]


# -- one face's polygon ----------------------------------------------------------------


def _face_polygon(pts: np.ndarray, a: int, normal: np.ndarray, eps: float) -> list[int]:
    """The point indices of the hull face in the plane through point ``a`` with
    ``normal``, counter-clockwise about it, by the coplanar rule: its strict
    corners and the points on its sides, repeats and inner points left out."""
    members = np.flatnonzero(np.abs((pts - pts[a]) @ normal) <= eps)
    if len(members) == 3:  # most faces: a triangle, unless its points are in line
        p, q, r = members.tolist()
        if _juts(pts, p, q, r, eps):
            turn = _cross3(pts[q] - pts[p], pts[r] - pts[p]) @ normal
            return [p, q, r] if turn > 0 else [p, r, q]
    u = _cross3(normal, _X)
    if u @ u < 0.25:
        u = _cross3(normal, _Y)
    u = _unit3(u)
    # the (3, 2) matrix with columns u and normal x u
    frame = np.array(list(zip(u.tolist(), _cross3(normal, u).tolist(), strict=True)))
    xy = (pts[members] @ frame).tolist()
    order = _first_copies(xy, sorted(range(len(xy)), key=lambda i: (*xy[i], i)), eps)
    corners = _strict_corners(xy, order, eps)
    if len(corners) < 3 or len(corners) == len(order):  # no point left for the sides
        return members[corners].tolist()
    return members[_with_side_points(np.array(xy), np.array(order), corners, eps)].tolist()


def _first_copies(xy: list[list[float]], order: list[int], eps: float) -> list[int]:
    """``order`` (sorted by position) with each cluster of points within ``eps`` of
    each other kept once, as its lowest index (of ascending point indices)."""
    kept: list[int] = []
    for i in order:
        # the kept points within eps along x are the last few
        j = len(kept) - 1
        while j >= 0 and xy[kept[j]][0] >= xy[i][0] - eps and math.dist(xy[i], xy[kept[j]]) > eps:
            j -= 1
        if j >= 0 and xy[kept[j]][0] >= xy[i][0] - eps:
            kept[j] = min(kept[j], i)
        else:
            kept.append(i)
    return kept


def _strict_corners(xy: list[list[float]], order: list[int], eps: float) -> list[int]:
    """Indices (into the ``k`` points ``xy``, taken in the sorted ``order``) of the
    corners of their convex polygon, counter-clockwise (Andrew's monotone chain;
    a point within ``eps`` of the line through its neighbours is no corner)."""
    def chain(seq: list[int]) -> list[int]:
        out: list[int] = []
        for q in seq:
            while len(out) >= 2 and not _juts2(xy[out[-2]], xy[out[-1]], xy[q], eps):
                out.pop()
            out.append(q)
        return out[:-1]

    ring = chain(order) + chain(order[::-1])
    # the sort's ties can leave a corner in line with its neighbours: drop it
    k = 0
    while len(ring) > 3 and k < len(ring):
        if _juts2(xy[ring[k - 1]], xy[ring[k]], xy[ring[(k + 1) % len(ring)]], eps):
            k += 1
        else:
            del ring[k]
            k = 0
    return ring


def _juts2(a: list[float], b: list[float], c: list[float], eps: float) -> bool:
    """Whether 2D point ``b`` lies more than ``eps`` to the right of the line
    ``a -> c`` (a left turn ``a, b, c`` that is no straight line)."""
    abx, aby, acx, acy = b[0] - a[0], b[1] - a[1], c[0] - a[0], c[1] - a[1]
    return abx * acy - aby * acx > eps * math.hypot(acx, acy)


def _juts(pts: np.ndarray, a: int, b: int, c: int, eps: float) -> bool:
    """Whether 3D point ``b`` lies more than ``eps`` off the line through ``a, c``."""
    ab, ac = pts[b] - pts[a], pts[c] - pts[a]
    twice_area = _cross3(ab, ac)
    return float(np.sqrt(twice_area @ twice_area)) > eps * float(np.sqrt(ac @ ac))


def _with_side_points(xy: np.ndarray, candidates: np.ndarray, corners: list[int],
                      eps: float) -> list[int]:
    """``corners`` with, after each, the ``candidates`` lying on its side to the
    next corner (within ``eps``), in order along the side."""
    start, end = xy[corners], xy[np.roll(corners, -1)]
    side = end - start  # (S, 2), then (S, K) for every side and candidate below
    length = np.hypot(side[:, 0], side[:, 1])[:, None]
    rel = xy[candidates][None, :, :] - start[:, None, :]
    along = (rel[..., 0] * side[:, :1] + rel[..., 1] * side[:, 1:]) / length
    off = np.abs(rel[..., 0] * side[:, 1:] - rel[..., 1] * side[:, :1]) / length
    on = (off <= eps) & (along > eps) & (along < length - eps)
    ring: list[int] = []
    for i, a in enumerate(corners):
        ring.append(a)
        if on[i].any():
            ring.extend(candidates[on[i]][np.argsort(along[i, on[i]])].tolist())
    return ring


# -- checks ------------------------------------------------------------------------


def _check_closed(polygons: list[list[int]]) -> None:
    """Refuse polygons that are not a closed genus-0 surface with one fan per vertex.

    The check of :func:`._hull_faces.check_closed`, in Python: for the few faces
    of a small hull (a column joint's two dozen) its numpy passes cost more than this
    loop (+5 % on ``columns``); a large hull's arrays go there.

    Raises:
        DLFLError: a repeated side, a side without its reverse, a vertex with two
            fans, or an Euler characteristic other than 2.
    """
    heads: list[int] = []
    tails: list[int] = []
    befores: list[int] = []
    for poly in polygons:
        heads += poly
        tails += poly[1:]
        tails.append(poly[0])
        befores.append(poly[-1])
        befores += poly[:-1]
    n = max(heads) + 1
    sides = [p * n + q for p, q in zip(heads, tails, strict=True)]  # side (p, q) as p n + q
    unseen = set(sides)
    if len(unseen) != len(sides) or unseen != {q * n + p for p, q in zip(heads, tails, strict=True)}:
        raise not_closed()
    # around vertex p, side (p, q) is followed by (p, r), (r, p) the side before it
    before = dict(zip(sides, befores, strict=True))
    fans = 0
    while unseen:
        start = side = unseen.pop()
        fans += 1
        base = side - side % n
        while (side := base + before[side]) != start:
            unseen.remove(side)
    vertices = len(set(heads))
    if fans != vertices or vertices - len(sides) // 2 + len(polygons) != 2:
        raise not_closed()


# -- triangles, duals and rebuilding -------------------------------------------------------


def _triangle_array(hull: _Hull) -> np.ndarray:
    """``(T, 3)``: the faces of ``hull`` cut into triangles (:func:`hull_triangles`)."""
    corners, offsets = hull.flat()
    if (np.diff(offsets) == 3).all():
        return corners.reshape(-1, 3)
    triangles = [t for poly in hull.polygons for t in _ears(hull.points, poly, hull.eps)]
    return np.array(triangles, np.int64)


def _ears(pts: np.ndarray, poly: list[int], eps: float) -> list[list[int]]:
    """Triangles of the convex polygon ``poly`` of ``(n, 3)`` ``pts``; see
    :func:`hull_triangles` for the rule."""
    if len(poly) == 3:  # a hull face is never flat: a triangle stays as it is
        return [list(poly)]
    ring = list(poly)
    juts = [_juts(pts, ring[i - 1], ring[i], ring[(i + 1) % len(ring)], eps)
            for i in range(len(ring))]
    triangles = []
    while len(ring) > 3:
        k = len(ring)
        i = next((i for i in range(k) if juts[i] and not (juts[i - 1] and juts[(i + 1) % k])), 0)
        triangles.append([ring[i - 1], ring[i], ring[(i + 1) % k]])
        del ring[i], juts[i]
        for j in (i - 1, i % len(ring)):  # the two new neighbours of the cut
            juts[j] = _juts(pts, ring[j - 1], ring[j], ring[(j + 1) % len(ring)], eps)
    return [*triangles, ring]


def _polar_points(hull: _Hull, corners: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """``(F, 3)`` the polar dual vertex of each hull polygon (``corners`` and
    ``offsets`` as :func:`._hull_faces.flat_faces`), in input coordinates; see
    :func:`dual_convex_hull`.

    Raises:
        DLFLError: a dual vertex beyond the float range.
    """
    used = hull.points[np.flatnonzero(np.bincount(corners))]
    centre = used.mean(axis=0)
    radius2 = float(np.mean(np.sum((used - centre) ** 2, axis=1)))
    normals = hull.normals
    if not isinstance(normals, np.ndarray):
        normals = _resolved_all(hull.points, normals)
    distance = np.einsum("fk,fk->f", normals, hull.points[corners[offsets[:-1]]] - centre)
    with np.errstate(over="ignore", invalid="ignore"):  # refused just below
        dual = np.ldexp(centre + normals * (radius2 / distance)[:, None], hull.exponent)
        dual = hull.origin + dual
    if not np.isfinite(dual).all():
        raise GeometryError("the dual convex hull would put a vertex beyond the float range "
                            "(the hull is too flat)")
    return dual


def _rebuild(mesh: Mesh, points: np.ndarray, corners: np.ndarray, offsets: np.ndarray
             ) -> None:
    """Replace ``mesh`` by the polygons (``corners`` and ``offsets`` as
    :func:`._hull_faces.flat_faces`) over the ``(n, 3)`` ``points`` they use (in
    index order), with fresh ids."""
    used = np.flatnonzero(np.bincount(corners, minlength=len(points)))
    index = np.full(len(points), -1, dtype=np.int64)
    index[used] = np.arange(len(used))
    mesh.replace_with(from_polygons(points[used], index[corners], offsets,
                                    first_ids=mesh.next_ids()))
