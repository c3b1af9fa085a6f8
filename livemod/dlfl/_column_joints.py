"""The joint at a vertex of :func:`.wireframe.columns`, as TopMod builds it.

TopMod's ``createWireframeWithSegments`` takes the convex hull of the rings of
``s`` points around a vertex's edges, runs ``edgeCleanup`` on it (merging hull
triangles whose normals agree) and then deletes hull edges by a parity rule:
number each ring's points ``0 .. s-1`` round the ring; the shortest hull edge
that is not a ring side joins points ``i`` and ``j``; every other such edge
whose ``i - j`` has the other parity goes. On its rings (turned by
``2 * 3.15 / s`` instead of ``2 pi / s``, placed 1e-4 apart) no two hull
triangles are coplanar, so the parity rule meets a triangulated hull.

livemod's rings are exact, so faces of the hull are truly coplanar. The rule
here is TopMod's on a triangulated hull: the hull of the rings with every
face but the ring caps cut into a fan of triangles (or, where a point lies on a
hull edge, cut ear by ear, :func:`.hull.hull_triangles`), the parity rule for
an even ``s``,
then every two faces that lie in one plane (every point within
:data:`FLAT` times the joint's extent of it) merged. On the platonic solids,
the cube, a 4 x 4 torus and the soccer ball this gives TopMod's counts
exactly (docs/topmod.md). For an odd ``s`` the parity of ``i - j`` does not
go round a ring (points ``s - 1`` and ``0`` are neighbours of one parity),
and TopMod's rule there merged whole bands into 9- to 15-gons: livemod keeps
the merged hull (triangles and planar polygons).
"""

from __future__ import annotations

import math

import numpy as np

from ._vectors import shifted_in_range
from .hull import hull_polygons, hull_triangles
from .normals import small_polygon_normal

FLAT = 1e-5
"""Two joint faces are merged when all their points lie within this many times
the joint's largest extent (along an axis) of one plane."""

# shortest edges within this relative length of each other are a tie
_TIE = 1e-9


def joint_polygons(points: np.ndarray, rings: int, segments: int) -> list[list[int]]:
    """The faces of the joint of ``rings`` rings of ``segments`` points.

    Args:
        points: ``(rings * segments, 3)`` the ring points, ring after ring, each
            ring in order round its edge.
        rings: at least 2.
        segments: points per ring.

    Returns:
        Point indices per face, counter-clockwise seen from outside, ring caps
        included (each cap is exactly the points of one ring).

    Raises:
        DLFLError: as :func:`.hull.hull_triangles` (the rings lie in one plane).
    """
    points = shifted_in_range(points)  # the same faces at any scale and offset
    # a joint has a few dozen points: plain floats beat numpy's per-call cost
    pts = points.tolist()
    extent = max(max(axis) - min(axis) for axis in zip(*pts, strict=True))
    triangles = _fans(hull_polygons(points), segments)
    edges = _Edges(pts, triangles, segments)
    if not all(a > 1e-9 * extent * extent for a in edges.area):  # a point on a hull edge
        triangles = hull_triangles(points)  # cut by ears: no flat triangle
        edges = _Edges(pts, triangles, segments)
    faces = _Faces(triangles)
    # the caps first, as TopMod's edgeCleanup merged them before its parity rule
    for u, v in edges.chords():
        faces.merge_across(u, v)
    if segments % 2 == 0:
        for u, v in edges.other_parity():
            faces.merge_across(u, v)
    tol = FLAT * extent
    faces.merge_flat(points, edges.flat(tol), tol)
    return faces.polygons()


def _fans(polygons: list[list[int]], segments: int) -> list[list[int]]:
    """Each polygon but a ring cap cut into a fan of triangles from its last
    corner, in the order and turn :func:`.hull.hull_triangles` gives a polygon
    none of whose corners lies in line with its neighbours. A cap stays whole:
    its triangles would only be merged again, as TopMod's edgeCleanup merged
    them."""
    out: list[list[int]] = []
    for p in polygons:
        k = len(p)
        if k == segments and p[0] // segments == p[1] // segments == p[2] // segments \
                and len({i // segments for i in p}) == 1:
            out.append(p)
            continue
        out.extend([p[-1], p[i], p[i + 1]] for i in range(k - 3))
        out.append(p[-3:] if k > 3 else list(p))
    return out


class _Edges:
    """The edges of the triangles of a joint hull (``triangles``: point indices
    into ``pts``, a list of ``[x, y, z]``; longer polygons, the ring caps, are
    left out), each once as ``(u, v)`` with ``u < v``, in order of ``(u, v)``.
    The ring of point ``i`` is ``i // segments``."""

    def __init__(self, pts: list[list[float]], triangles: list[list[int]],
                 segments: int) -> None:
        self.pts, self.segments = pts, segments
        # per side u -> v: its triangle and that triangle's point off the side
        self.third: dict[tuple[int, int], tuple[int, int]] = {}
        self.corner: list[list[float]] = []
        self.normal: list[tuple[float, float, float]] = []
        self.area: list[float] = []  # twice each triangle's area
        third = self.third
        for t, (a, b, c) in enumerate(p for p in triangles if len(p) == 3):
            third[(a, b)], third[(b, c)], third[(c, a)] = (t, c), (t, a), (t, b)
            normal, area = _unit_cross(pts[a], pts[b], pts[c])
            self.corner.append(pts[a])
            self.normal.append(normal)
            self.area.append(area)
        self.edges = sorted(e for e in self.third if e[0] < e[1])

    def chords(self) -> list[tuple[int, int]]:
        """The edges joining two points of one ring that are not neighbours in it."""
        s = self.segments
        return [(u, v) for u, v in self.edges
                if u // s == v // s and (v - u) % s not in (1, s - 1)]

    def other_parity(self) -> list[tuple[int, int]]:
        """The edges TopMod's parity rule deletes. Of the edges between two rings,
        those whose ends' places in their rings differ in parity from those of the
        shortest such edge (the first in order of their ends among equal
        shortest)."""
        s = self.segments
        across = [(u, v) for u, v in self.edges if u // s != v // s]
        length = [math.dist(self.pts[u], self.pts[v]) for u, v in across]
        least = min(length) * (1.0 + _TIE)
        u0, v0 = next(e for e, d in zip(across, length, strict=True) if d <= least)
        parity = (u0 % s - v0 % s) % 2
        return [(u, v) for u, v in across if (u % s - v % s) % 2 != parity]

    def flat(self, tol: float) -> list[tuple[int, int]]:
        """The edges between two rings whose two triangles each have the other's
        third point within ``tol`` of their plane."""
        s = self.segments
        return [(u, v) for u, v in self.edges
                if u // s != v // s and self._off(u, v) <= tol and self._off(v, u) <= tol]

    def _off(self, u: int, v: int) -> float:
        """How far the point of the triangle beyond side ``u -> v`` off that side
        lies from the plane of the triangle of ``u -> v``."""
        t, _ = self.third[(u, v)]
        _, far = self.third[(v, u)]
        p, q, n = self.pts[far], self.corner[t], self.normal[t]
        return abs((p[0] - q[0]) * n[0] + (p[1] - q[1]) * n[1] + (p[2] - q[2]) * n[2])


def _unit_cross(a: list[float], b: list[float], c: list[float]
                ) -> tuple[tuple[float, float, float], float]:
    """The unit normal of triangle ``a b c`` (zero when it has no area) and the
    length of ``(b - a) x (c - a)``."""
    ux, uy, uz = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    vx, vy, vz = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    area = math.sqrt(nx * nx + ny * ny + nz * nz)
    scale = 1.0 / max(area, 1e-300)
    return (nx * scale, ny * scale, nz * scale), area


class _Faces:
    """Polygons of a closed surface, merged as the edges between them go."""

    def __init__(self, polygons: list[list[int]]) -> None:
        self.rings = dict(enumerate(polygons))
        self.side: dict[tuple[int, int], int] = {}
        side = self.side
        for i, p in enumerate(polygons):
            u = p[-1]
            for v in p:
                side[(u, v)] = i
                u = v

    def merge_across(self, u: int, v: int) -> bool:
        """Delete edge ``u v``, merging its two faces; False (nothing done) when
        it is gone or both its sides are one face."""
        a, b = self.side.get((u, v)), self.side.get((v, u))
        if a is None or b is None or a == b:
            return False
        ring = self.rings.pop(b)
        self.rings[a] = _opened(self.rings[a], u, v) + _opened(ring, v, u)[1:-1]
        del self.side[(u, v)], self.side[(v, u)]
        w = ring[-1]
        for x in ring:  # b's other sides now bound a
            if (w, x) in self.side:
                self.side[(w, x)] = a
            w = x
        return True

    def merge_flat(self, points: np.ndarray, hinges: list[tuple[int, int]], tol: float) -> None:
        """Merge every two faces beside an edge of ``hinges`` whose points all lie
        within ``tol`` of one plane, until none are left."""
        merged = True
        while merged:
            merged = False
            for u, v in hinges:
                if (u, v) not in self.side:
                    continue
                a, b = self.side[(u, v)], self.side[(v, u)]
                if a != b and _flat(points, self.rings[a], self.rings[b], tol):
                    merged |= self.merge_across(u, v)

    def polygons(self) -> list[list[int]]:
        """The faces, in order of the first triangle each grew from."""
        return [self.rings[i] for i in sorted(self.rings)]


def _opened(ring: list[int], u: int, v: int) -> list[int]:
    """``ring`` turned to run from ``v`` round to ``u``, where it has the side ``u -> v``."""
    k = len(ring)
    j = ring.index(u)
    while ring[(j + 1) % k] != v:  # a ring can pass u twice
        j = ring.index(u, j + 1)
    return ring[j + 1:] + ring[:j + 1]


def _flat(points: np.ndarray, first: list[int], second: list[int], tol: float) -> bool:
    """True when every point of both faces lies within ``tol`` of the plane through
    their centroid square to ``first``'s normal."""
    normal = np.array(small_polygon_normal(points[first].tolist()))
    both = points[first + second]
    return bool(np.abs((both - both.mean(axis=0)) @ normal).max() <= tol)
