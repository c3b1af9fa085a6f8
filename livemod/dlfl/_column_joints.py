"""The joint at a vertex of :func:`livemod.dlfl.wireframe.columns`, as TopMod builds it.

TopMod's ``createWireframeWithSegments`` takes the convex hull of the rings of
``s`` points around a vertex's edges, runs ``edgeCleanup`` on it (merging hull
triangles whose normals agree) and then deletes hull edges by a parity rule:
number each ring's points ``0 .. s-1`` round the ring; the shortest hull edge
that is not a ring side joins points ``i`` and ``j``; every other such edge
whose ``i - j`` has the other parity goes. On its rings (turned by
``2 * 3.15 / s`` instead of ``2 pi / s``, placed 1e-4 apart) no two hull
triangles are coplanar, so the parity rule meets a triangulated hull.

livemod's rings are exact, so faces of the hull are truly coplanar. The rule
here is TopMod's on a triangulated hull: the hull of the rings cut into
triangles (:func:`.hull.hull_triangles`), the parity rule for an even ``s``,
then every two faces that lie in one plane (every point within
:data:`FLAT` times the joint's extent of it) merged. On the platonic solids,
the cube, a 4 x 4 torus and the soccer ball this gives TopMod's counts
exactly (docs/topmod.md). For an odd ``s`` the parity of ``i - j`` does not
go round a ring (points ``s - 1`` and ``0`` are neighbours of one parity),
and TopMod's rule there merged whole bands into 9- to 15-gons: livemod keeps
the merged hull (triangles and planar polygons).
"""

from __future__ import annotations

import numpy as np

from ._vectors import shifted_in_range, unit
from .hull import hull_triangles
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
    triangles = hull_triangles(points)
    edges = _Edges(np.array(triangles), segments)
    faces = _Faces(triangles)
    # the caps first, as TopMod's edgeCleanup merged them before its parity rule
    for u, v in edges.pairs(edges.chord):
        faces.merge_across(u, v)
    across = ~edges.same_ring
    if segments % 2 == 0:
        for u, v in edges.pairs(across & edges.other_parity(points)):
            faces.merge_across(u, v)
    tol = FLAT * float(np.ptp(points, axis=0).max())
    faces.merge_flat(points, edges.pairs(across & edges.flat(points, tol)), tol)
    return faces.polygons()


class _Edges:
    """The edges of a triangulated joint hull ``tri`` (``(T, 3)`` point indices),
    each once as ``(u, v)`` with ``u < v``, in order of ``(u, v)``."""

    def __init__(self, tri: np.ndarray, segments: int) -> None:
        head, tail = tri.ravel(), tri[:, [1, 2, 0]].ravel()
        size = int(tri.max()) + 1
        key = head * size + tail
        order = np.argsort(key)
        mate = order[np.searchsorted(key[order], tail * size + head)]
        lower = np.flatnonzero(head < tail)
        lower = lower[np.argsort(key[lower])]
        self.tri = tri
        self.u, self.v = head[lower], tail[lower]
        # the two triangles beside each edge, and the point of each off the edge
        third = tri[:, [2, 0, 1]].ravel()
        self.sides = (lower // 3, mate[lower] // 3)
        self.thirds = (third[lower], third[mate[lower]])
        self.same_ring = self.u // segments == self.v // segments
        step = (self.v - self.u) % segments
        self.chord = self.same_ring & (step != 1) & (step != segments - 1)
        self.segments = segments

    def pairs(self, mask: np.ndarray) -> list[tuple[int, int]]:
        """The edges of ``mask`` (``(E,)`` bool) as ``(u, v)`` pairs."""
        return list(zip(self.u[mask].tolist(), self.v[mask].tolist(), strict=True))

    def other_parity(self, points: np.ndarray) -> np.ndarray:
        """``(E,)`` bool: the edges TopMod's parity rule deletes. Of the edges
        between two rings, those whose ends' places in their rings differ in
        parity from those of the shortest such edge (the first in order of their
        ends among equal shortest)."""
        across = np.flatnonzero(~self.same_ring)
        length = np.linalg.norm(points[self.u[across]] - points[self.v[across]], axis=1)
        first = across[np.flatnonzero(length <= length.min() * (1.0 + _TIE))[0]]
        parity = (self.u % self.segments - self.v % self.segments) % 2
        return ~self.same_ring & (parity != parity[first])

    def flat(self, points: np.ndarray, tol: float) -> np.ndarray:
        """``(E,)`` bool: the edges whose two triangles each have the other's
        third point within ``tol`` of their plane."""
        a, b, c = (points[self.tri[:, k]] for k in range(3))
        normal = unit(np.cross(b - a, c - a))
        near, far = self.sides
        near_third, far_third = self.thirds

        def off(tri: np.ndarray, point: np.ndarray) -> np.ndarray:
            return np.abs(np.einsum("ij,ij->i", points[point] - a[tri], normal[tri]))

        return (off(near, far_third) <= tol) & (off(far, near_third) <= tol)


class _Faces:
    """Polygons of a closed surface, merged as the edges between them go."""

    def __init__(self, polygons: list[list[int]]) -> None:
        self.rings = dict(enumerate(polygons))
        self.side: dict[tuple[int, int], int] = {}
        for i, p in self.rings.items():
            self.side.update(zip(zip(p, p[1:] + p[:1], strict=True), (i,) * len(p), strict=True))

    def merge_across(self, u: int, v: int) -> bool:
        """Delete edge ``u v``, merging its two faces; False (nothing done) when
        it is gone or both its sides are one face."""
        a, b = self.side.get((u, v)), self.side.get((v, u))
        if a is None or b is None or a == b:
            return False
        merged = _opened(self.rings[a], u, v) + _opened(self.rings[b], v, u)[1:-1]
        del self.side[(u, v)], self.side[(v, u)], self.rings[b]
        self.rings[a] = merged
        for j, w in enumerate(merged):
            if (w, merged[(j + 1) % len(merged)]) in self.side:
                self.side[(w, merged[(j + 1) % len(merged)])] = a
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
