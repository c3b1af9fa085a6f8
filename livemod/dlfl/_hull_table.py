"""The triangle lookup of :mod:`.hull` for small point sets.

Once turning has found one triangle of a hull of up to ``hull._SMALL`` points,
the hull's other triangles are looked up instead of turned to: the planes
through every three points are tried in one array pass, and a plane with every
point on one side and only its three on it is the triangle turning would reach
across each of its sides. Everything here is in the hull's frame and tolerance
(``eps``, absolute in the framed points' units, is the caller's relative
tolerance times their largest extent), so it does not depend on the scale.
"""

from __future__ import annotations

import functools
import itertools
from collections import Counter

import numpy as np

# a plane through three points counts for the lookup when the third lies more
# than this many tolerances off the line through the other two (a thinner
# triangle's normal is too inexact to tell which points lie on its plane)
_WIDE = 16.0


def triangle_table(pts: np.ndarray, eps: float, extent: float
                    ) -> dict[tuple[int, int], tuple[list[int], int]]:
    """The hull's triangle faces by side: ``(u, v) -> (polygon, third corner)`` for
    every side ``u -> v`` of every triangle of :func:`_supporting_triangles`
    (a side two of them claim is left out, for turning to decide)."""
    triangles = _supporting_triangles(pts, eps, extent).tolist()
    table: dict[tuple[int, int], tuple[list[int], int]] = {}
    for p, q, r in triangles:
        tri = [p, q, r]
        table[p, q], table[q, r], table[r, p] = (tri, r), (tri, p), (tri, q)
    if len(table) < 3 * len(triangles):
        claims = Counter(side for p, q, r in triangles for side in ((p, q), (q, r), (r, p)))
        for side in [side for side, count in claims.items() if count > 1]:
            del table[side]
    return table


def _supporting_triangles(pts: np.ndarray, eps: float, extent: float) -> np.ndarray:
    """``(m, 3)`` hull faces of ``(n, 3)`` points that are triangles, as turning
    finds them: every ``i < j < k`` with every point on one side of its plane and
    no other within ``eps`` of it, as ``[i, j, k]`` or ``[i, k, j]``,
    counter-clockwise seen from outside. ``extent`` is the points' largest
    extent along an axis.

    Left out, for turning to decide: three points nearly in line (a third within
    ``_WIDE`` tolerances of the line through the other two), whose plane is too
    inexact to tell which points lie on it, and triangles with a side whose
    ends are nearly in line with a third point (near its line, the angle
    turning takes is inexact).
    """
    ijk, firsts = _triples(len(pts))
    w = pts - pts[0]
    corner = np.take(w.T, ijk, axis=1)  # (3 coordinates, 3 corners, T), T = n choose 3
    a, b = (corner[:, 1:] - corner[:, :1]).transpose(1, 0, 2)  # j - i, k - i: (3, T) each
    normal = np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                       a[0] * b[1] - a[1] * b[0]])
    area2 = np.einsum("ij,ij->j", normal, normal)
    # twice the area over a side (at most 2 extents long) is a corner's distance
    # from the line through the other two
    wide = area2 > (_WIDE * 2.0 * eps * extent) ** 2
    with np.errstate(divide="ignore"):
        unit = normal * np.where(wide, 1.0 / np.sqrt(area2), 0.0)  # thin: 0, all on it
    # the height of every point above every plane: (n, T) (einsum: a matrix
    # product this size would wake BLAS threads, slow on a busy machine)
    height = np.einsum("ic,ct->it", w, unit)
    height -= np.take(height, firsts)
    below, above = height.max(axis=0) <= eps, height.min(axis=0) >= -eps
    support = np.flatnonzero(below | above)
    alone = support[(np.abs(np.take(height, support, axis=1)) <= eps).sum(axis=0) == 3]
    tri = np.take(ijk, alone, axis=1).T
    # outward is the normal (j - i) x (k - i) when every point is below the plane
    tri = np.where(below[alone][:, None], tri, tri[:, [0, 2, 1]])
    if wide.all():
        return tri
    thin = _in_line_pairs(len(pts), np.take(ijk, np.flatnonzero(~wide), axis=1))
    return tri[~thin[tri, np.roll(tri, -1, axis=1)].any(axis=1)]


def _in_line_pairs(n: int, triples: np.ndarray) -> np.ndarray:
    """``(n, n)`` bool, symmetric: which pairs of ``n`` points are two of the
    ``(3, m)`` ``triples`` (of points nearly in line)."""
    pairs = np.zeros((n, n), dtype=bool)
    i, j, k = triples
    pairs[i, j] = pairs[i, k] = pairs[j, k] = True
    return pairs | pairs.T


@functools.cache
def _triples(n: int) -> tuple[np.ndarray, np.ndarray]:
    """``(ijk, firsts)``: ``(3, T)`` int, every ``i < j < k < n`` (``T = n choose 3``),
    and ``(T,)`` where ``i`` is in an ``(n, T)`` array raveled (``i T + column``)."""
    ijk = np.array(list(itertools.combinations(range(n), 3)), dtype=np.intp).reshape(-1, 3).T
    ijk = np.ascontiguousarray(ijk)
    firsts = ijk[0] * ijk.shape[1] + np.arange(ijk.shape[1])
    for array in (ijk, firsts):
        array.flags.writeable = False
    return ijk, firsts
