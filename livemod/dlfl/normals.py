"""TopMod's normals: livemod's one definition of corner and face normals.

Every operation that moves along a face or corner normal reads it here (the
extrusions, the remeshing schemes that lift points off their faces, the
checkerboard's and the inset's concave corners, the crust, the cutting planes)
and so does every measurement of :mod:`.analysis`. The rule is TopMod's
(``DLFLFaceVertex::updateNormal``, ``DLFLFace::computeNormal``):

* a corner at ``p``, with ``prev`` and ``next`` its neighbours in its face, has
  the normal ``normalize((next - p) x (prev - p))``, flipped at a concave corner;
* a *winged* corner (a straight one: the unit directions to its two neighbours
  sum to less than :data:`WINGED`) of a face of more than 3 corners copies the
  normal of the nearest corner of its face that is not winged, the previous one
  on a tie (zero when every corner is winged);
* a face's normal is the normalised sum of its corners' normals.

A corner is *concave* when its face has more than 3 corners, its angle is not
within :data:`WINGED` of 0 or 180 degrees (sine at least 1e-5), and its cross
product points against the face's Newell vector ``sum (p_i - o) x (p_{i+1} - o)``.
On a planar face this is TopMod's test; TopMod instead stepped 0.01 (an absolute
length) from the corner along its bisector and asked whether that point lay in
the face projected onto the coordinate plane most nearly square to the corner's
own cross product, which on a non-planar face depends on how the mesh is
turned and, on a face under about 0.02 across, calls every corner concave
(docs/topmod.md). Normals have no length to lose: the results are the same for
any scale and offset of the points (coordinates are brought into range by
powers of two first, see :mod:`._vectors`).

Two forms: :func:`ring_normals` for many faces at once (numpy) and
:func:`small_polygon_normal` for the handful of points of one face (plain
floats, several times faster there: a chain of extrusions computes one per step).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np

from ._vectors import cross_rows, face_ring_vectors, group_sum, unit
from ._vectors import newell as newell_sums

__all__ = ["WINGED", "RingNormals", "RingLayout", "ring_layout", "ring_normals", "ring_neighbours", "reversed_rings",
           "nearest_unwinged", "polygon_normal", "small_polygon_normal", "inset_offsets"]

WINGED = 1e-5
"""A corner is straight (winged) when its two unit edge directions sum to less
than this, and its angle counts as 0 or 180 degrees (never concave) when the
sine of its angle is below it: TopMod's thresholds."""

# corners whose sine is below twice WINGED are looked at closely (with unit
# edge vectors): the cheap test on raw vectors only has to let them all through
_NEAR = (2.0 * WINGED) ** 2


@dataclass(frozen=True)
class RingNormals:
    """The normals of ``R`` rings (faces) of ``C`` corners in all.

    Attributes:
        corner: ``(C, 3)`` unit corner normals (zero where a corner has none).
        face: ``(R, 3)`` unit face normals (zero for point-spheres, 2-gons and
            faces whose corners have no normals).
        concave: ``(C,)`` bool, the concave corners (their normals are flipped).
        winged: ``(C,)`` bool, the straight corners (their normals are copied).
        source: ``(C,)`` int64, the corner each corner's normal comes from:
            itself, or for a winged corner the nearest corner that is not
            winged (-1 when there is none).
    """

    corner: np.ndarray
    face: np.ndarray
    concave: np.ndarray
    winged: np.ndarray
    source: np.ndarray


def ring_neighbours(offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(next, prev)``, each ``(C,)``: the neighbours of every corner in its ring,
    for rings laid out one after another (ring ``r`` owns corners
    ``offsets[r]:offsets[r + 1]``, in ring order; no ring is empty)."""
    count = int(offsets[-1])
    nxt = np.arange(1, count + 1, dtype=np.int64)
    prv = np.arange(-1, count - 1, dtype=np.int64)
    if count:
        nxt[offsets[1:] - 1] = offsets[:-1]
        prv[offsets[:-1]] = offsets[1:] - 1
    return nxt, prv


def reversed_rings(offsets: np.ndarray) -> np.ndarray:
    """``(C,)`` for every corner the corner at its place in its ring reversed
    (``offsets`` as :func:`ring_neighbours`): ``corners[reversed_rings(offsets)]``
    lists every ring backwards from its last corner. Its own inverse."""
    sizes = np.diff(offsets)
    ring_start = np.repeat(offsets[:-1], sizes)
    return (2 * ring_start + np.repeat(sizes, sizes) - 1
            - np.arange(int(offsets[-1]), dtype=np.int64))


class RingLayout(NamedTuple):
    """Where every corner of rings laid out one after another sits: ``ring``,
    ``next`` and ``prev``, each ``(C,)`` int64 (:func:`ring_layout`)."""

    ring: np.ndarray
    next: np.ndarray
    prev: np.ndarray


def ring_layout(offsets: np.ndarray) -> RingLayout:
    """The :class:`RingLayout` of the rings of ``offsets`` (``(R + 1,)``, as
    :func:`ring_neighbours`): for a caller that asks for the normals of rings of
    one layout several times."""
    ring = np.repeat(np.arange(len(offsets) - 1, dtype=np.int64), np.diff(offsets))
    return RingLayout(ring, *ring_neighbours(offsets))


def ring_normals(positions: np.ndarray, corner_vertex: np.ndarray, offsets: np.ndarray,
                 layout: RingLayout | None = None) -> RingNormals:
    """TopMod's normals of every ring (see the module's rule).

    Args:
        positions: ``(V, 3)`` float points.
        corner_vertex: ``(C,)`` int index into ``positions`` of each corner.
        offsets: ``(R + 1,)`` int, ring ``r`` owns corners
            ``offsets[r]:offsets[r + 1]`` in ring order (none empty).
        layout: :func:`ring_layout` of ``offsets``, when the caller has it.

    Returns:
        The :class:`RingNormals` of the rings.
    """
    positions = np.asarray(positions, dtype=np.float64)
    sizes = np.diff(offsets)
    count = len(sizes)
    ring, nxt, prv = ring_layout(offsets) if layout is None else layout
    r = face_ring_vectors(positions, corner_vertex, offsets, ring)
    ahead = r.along(nxt)
    behind = -np.take(ahead, prv, axis=0)  # prev - p, exactly
    cross = cross_rows(ahead, behind)
    newell = newell_sums(r, ahead, ring, count)
    # triangles are never concave nor winged (no mask at all on a mesh without them)
    big = np.repeat(sizes > 3, sizes) if count and sizes.min() <= 3 else True
    square = np.einsum("ij,ij->i", cross, cross)
    dot = np.einsum("ij,ij->i", ahead, behind)
    # sin^2 = |a x b|^2 / (|a x b|^2 + (a . b)^2): only near-straight corners pass
    with np.errstate(over="ignore", invalid="ignore"):
        near = np.flatnonzero(square < _NEAR * (square + dot * dot))
    winged, flat = _straight(ahead[near], behind[near])
    winged_mask = np.zeros(len(ring), dtype=bool)
    winged_mask[near[winged]] = True
    winged_mask &= big
    concave = np.einsum("ij,ij->i", cross, np.take(newell, ring, axis=0)) < 0
    concave[near[flat]] = False  # a corner of 0 or 180 degrees does not turn
    concave &= big
    normal = unit(cross)
    normal[concave] *= -1.0
    source = np.arange(len(ring), dtype=np.int64)
    if winged_mask.any():
        source = nearest_unwinged(winged_mask, offsets, ring)
        normal = np.where((source >= 0)[:, None], np.take(normal, np.maximum(source, 0), axis=0),
                          0.0)
    face = unit(group_sum(ring, normal, count))
    return RingNormals(normal, face, concave, winged_mask, source)


def _straight(ahead: np.ndarray, behind: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For corners with edge vectors ``ahead`` and ``behind`` (``(n, 3)`` each):
    ``(winged, flat)``, ``(n,)`` bool each: the unit vectors sum to under
    :data:`WINGED`; the sine of the angle is under it."""
    ua, ub = unit(ahead), unit(behind)
    winged = np.linalg.norm(ua + ub, axis=1) < WINGED
    flat = np.linalg.norm(np.cross(ua, ub), axis=1) < WINGED
    return winged, flat


def nearest_unwinged(winged: np.ndarray, offsets: np.ndarray, ring: np.ndarray,
                     forward: bool = False) -> np.ndarray:
    """``(C,)`` for every corner the corner its normal comes from: itself, or for
    a ``winged`` (``(C,)`` bool) one the nearest corner of its ring that is not
    winged (the previous one on a tie), -1 when there is none. With ``forward``
    the first one after it instead (TopMod's ``nextNonWingedCorner``)."""
    source = np.arange(len(winged), dtype=np.int64)
    w = np.flatnonzero(winged)
    start = offsets[ring[w]]
    size = offsets[ring[w] + 1] - start
    place = w - start
    source[w] = -1
    todo = np.arange(len(w))
    reach = size - 1 if forward else size // 2
    step = 1
    while len(todo):
        todo = todo[step <= reach[todo]]
        s, n, p = start[todo], size[todo], place[todo]
        after = s + (p + step) % n
        found = ~winged[after]
        if not forward:
            before = s + (p - step) % n
            found_before = ~winged[before]
            after = np.where(found_before, before, after)
            found |= found_before
        source[w[todo[found]]] = after[found]
        todo = todo[~found]
        step += 1
    return source


def polygon_normal(points: np.ndarray) -> np.ndarray:
    """``(3,)`` unit normal of one polygon given as ``(k, 3)`` points in ring
    order (zero for fewer than three distinct directions)."""
    pts = np.asarray(points, dtype=np.float64)
    if len(pts) < 3:
        return np.zeros(3)
    k = len(pts)
    return ring_normals(pts, np.arange(k), np.array([0, k])).face[0]


def inset_offsets(positions: np.ndarray, corner_vertex: np.ndarray, offsets: np.ndarray,
                  thickness: float, fractional: bool = True,
                  normals: RingNormals | None = None) -> np.ndarray:
    """``(C, 3)`` TopMod's planar-offset move of every corner (``extrudeFacePlanarOffset``,
    the checkerboard's inset), in the rings' layout (see :func:`ring_normals`).

    A corner ``p`` moves by ``thickness (pvec + nvec)``, ``pvec`` and ``nvec`` its
    edge vectors to its neighbours (unit vectors unless ``fractional``), the other
    way at a concave corner. A winged corner moves ``thickness`` along
    ``n x nvec``, square to its next edge in the face, where ``n`` is the normal
    of the first corner after it that is not winged (normalised when
    ``fractional``; TopMod did not, which on a non-planar face shortens the move).
    ``normals``: :func:`ring_normals` of the same rings, when the caller has them.
    """
    positions = np.asarray(positions, dtype=np.float64)
    rn = ring_normals(positions, corner_vertex, offsets) if normals is None else normals
    nxt, prv = ring_neighbours(offsets)
    p = np.take(positions, corner_vertex, axis=0)
    nvec = np.take(p, nxt, axis=0) - p
    if not fractional:
        nvec = unit(nvec)
    # the previous corner's next edge reversed: p[prev] - p, exactly
    pvec = -np.take(nvec, prv, axis=0)
    move = thickness * (pvec + nvec)
    move[rn.concave] *= -1.0
    if rn.winged.any():
        ring = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
        after = nearest_unwinged(rn.winged, offsets, ring, forward=True)[rn.winged]
        normal = np.where((after >= 0)[:, None], rn.corner[np.maximum(after, 0)], 0.0)
        side = np.cross(normal, nvec[rn.winged])
        move[rn.winged] = thickness * (unit(side) if fractional else side)
    return move


# -- one small face in plain floats ------------------------------------------------

_NO_NORMAL = (0.0, 0.0, 0.0)
# corner cross products whose length lies strictly between these are measured
# exactly: below 1e-150 the squares fall among the subnormals (or to zero), and
# a square beyond the float range makes the length inf
_EXACT = (1e-150, math.inf)


def small_polygon_normal(points: list[list[float]]) -> tuple[float, float, float]:
    """:func:`polygon_normal` in plain Python floats, for one small face.

    The same rule, several times faster than numpy on the handful of points of
    one face, which is what chained extrusions need. ``points``: ``k`` lists
    ``[x, y, z]``. When a corner's cross product is too large or too small to
    measure (a huge or tiny face, or a straight corner), the face is measured
    again from its first point scaled by a power of two, as :mod:`._vectors`
    does, so that its scale never decides its normal.
    """
    if len(points) < 3:
        return _NO_NORMAL
    normal = _plain_normal(points, _EXACT)
    if normal is None:
        scaled = _rescaled(points)
        normal = _NO_NORMAL if scaled is None else _plain_normal(scaled, (1e-300, math.inf))
    return _NO_NORMAL if normal is None else normal


def _rescaled(points: list[list[float]]) -> list[list[float]] | None:
    """The ``k`` differences ``points[i] - points[0]`` (of a quarter of the points
    when the full ones overflow) times the power of two that brings their largest
    magnitude into [0.5, 1); None when they are all zero or not finite."""
    ox, oy, oz = points[0]
    rel = [[x - ox, y - oy, z - oz] for x, y, z in points]
    top = max(max(map(max, rel)), -min(map(min, rel)))
    if top == math.inf:  # coordinates near the float limit, of opposite signs
        q = 0.25
        rel = [[q * x - q * ox, q * y - q * oy, q * z - q * oz] for x, y, z in points]
        top = max(max(map(max, rel)), -min(map(min, rel)))
    if not 0.0 < top < math.inf:  # NaN fails too
        return None
    e = -math.frexp(top)[1]
    # per coordinate: for a subnormal top, 2**-e alone is beyond the float range
    return [[math.ldexp(x, e), math.ldexp(y, e), math.ldexp(z, e)] for x, y, z in rel]


def _plain_normal(points: list[list[float]], keep: tuple[float, float]
                  ) -> tuple[float, float, float] | None:
    """The rule of :func:`small_polygon_normal` on ``k`` points ``[x, y, z]``.

    A corner's cross product is used when its length lies strictly inside
    ``keep``; when one does not, the result is None (with the first bound above
    1e-300), else that corner's normal is zero."""
    k = len(points)
    ox, oy, oz = points[0]
    wx = wy = wz = 0.0
    corners = []
    near = []
    for i in range(k):
        px, py, pz = points[i]
        nx, ny, nz = points[(i + 1) % k]
        qx, qy, qz = points[i - 1]
        ax, ay, az, bx, by, bz = nx - px, ny - py, nz - pz, qx - px, qy - py, qz - pz
        # sum (p_i - p_0) x (p_{i+1} - p_i): the Newell vector without the
        # cancellation of raw coordinates far from the origin
        rx, ry, rz = px - ox, py - oy, pz - oz
        wx += ry * az - rz * ay
        wy += rz * ax - rx * az
        wz += rx * ay - ry * ax
        cx, cy, cz = ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx
        square = cx * cx + cy * cy + cz * cz
        dot = ax * bx + ay * by + az * bz
        # sin^2 = square / (square + dot^2): near 0 or 180 degrees, which is rare
        if square < _NEAR * (square + dot * dot):
            near.append(i)
        corners.append((cx, cy, cz, square))
    newell = (wx, wy, wz)
    if near:
        return _unit_sum_near(points, corners, newell, near, keep)
    return _unit_sum(corners, newell if k > 3 else None, keep)


def _unit_sum(corners: list[tuple[float, float, float, float]],
              newell: tuple[float, float, float] | None, keep: tuple[float, float]
              ) -> tuple[float, float, float] | None:
    """The normalised sum of the unit ``corners`` (cross products and their
    squared lengths), each flipped where it points against ``newell`` (None: a
    triangle, never flipped); see :func:`_plain_normal` for ``keep``."""
    low, high = keep
    wx, wy, wz = newell if newell is not None else (0.0, 0.0, 0.0)
    tx = ty = tz = 0.0
    for cx, cy, cz, square in corners:
        length = math.sqrt(square)
        if not low < length < high:  # NaN fails too
            if low > 1e-300:
                return None
            continue
        if cx * wx + cy * wy + cz * wz < 0:
            length = -length
        tx += cx / length
        ty += cy / length
        tz += cz / length
    length = math.sqrt(tx * tx + ty * ty + tz * tz)
    if length <= 1e-300:
        return _NO_NORMAL
    return (tx / length, ty / length, tz / length)


def _unit_sum_near(points: list[list[float]], corners: list[tuple[float, float, float, float]],
                   newell: tuple[float, float, float], near: list[int],
                   keep: tuple[float, float]) -> tuple[float, float, float] | None:
    """:func:`_unit_sum` for a face with corners ``near`` 0 or 180 degrees: winged
    ones copy their nearest neighbour's normal, flat ones are never flipped."""
    k = len(corners)
    low, high = keep
    winged = _winged(points, near) if k > 3 else set()
    normals: list[tuple[float, float, float]] = []
    for i, (cx, cy, cz, square) in enumerate(corners):
        length = math.sqrt(square)
        if i in winged:
            normals.append(_NO_NORMAL)  # copied below
            continue
        if not low < length < high:  # NaN fails too
            if low > 1e-300:
                return None
            normals.append(_NO_NORMAL)
            continue
        concave = (k > 3 and cx * newell[0] + cy * newell[1] + cz * newell[2] < 0
                   and (i not in near or not _flat(points, i)))
        if concave:
            length = -length
        normals.append((cx / length, cy / length, cz / length))
    for i in sorted(winged):
        normals[i] = _copied(normals, winged, i)
    tx = sum(n[0] for n in normals)
    ty = sum(n[1] for n in normals)
    tz = sum(n[2] for n in normals)
    length = math.sqrt(tx * tx + ty * ty + tz * tz)
    if length <= 1e-300:
        return _NO_NORMAL
    return (tx / length, ty / length, tz / length)


def _edge_units(points: list[list[float]], i: int) -> tuple[list[float], list[float]]:
    """The unit vectors from point ``i`` to its next and previous points."""
    k = len(points)
    p, n, q = points[i], points[(i + 1) % k], points[i - 1]
    a = [n[0] - p[0], n[1] - p[1], n[2] - p[2]]
    b = [q[0] - p[0], q[1] - p[1], q[2] - p[2]]
    la, lb = math.hypot(*a), math.hypot(*b)
    if not (0.0 < la < math.inf and 0.0 < lb < math.inf):
        return [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
    return [x / la for x in a], [x / lb for x in b]


def _winged(points: list[list[float]], near: list[int]) -> set[int]:
    """The corners of ``near`` whose unit edge directions sum to under :data:`WINGED`."""
    out = set()
    for i in near:
        ua, ub = _edge_units(points, i)
        if ua != [0.0, 0.0, 0.0] and math.hypot(*(x + y for x, y in zip(ua, ub, strict=True))) < WINGED:
            out.add(i)
    return out


def _flat(points: list[list[float]], i: int) -> bool:
    """True when the sine of corner ``i``'s angle is under :data:`WINGED`."""
    (ax, ay, az), (bx, by, bz) = _edge_units(points, i)
    return math.hypot(ay * bz - az * by, az * bx - ax * bz, ax * by - ay * bx) < WINGED


def _copied(normals: list[tuple[float, float, float]], winged: set[int],
            i: int) -> tuple[float, float, float]:
    """The normal of the corner nearest ``i`` that is not ``winged``, the previous
    one on a tie (zero when there is none)."""
    k = len(normals)
    for step in range(1, k // 2 + 1):
        for j in ((i - step) % k, (i + step) % k):
            if j not in winged:
                return normals[j]
    return _NO_NORMAL
