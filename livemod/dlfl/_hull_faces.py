"""A hull's faces as flat arrays: the check that they close a sphere, and the
ring of faces around each vertex (the faces of :func:`.hull.dual_convex_hull`).

Faces are given as ``corners`` (``(C,)`` point indices, face after face, each
counter-clockwise seen from outside) and ``offsets`` (``(F + 1,)``: face ``f`` is
``corners[offsets[f]:offsets[f + 1]]``). Corner ``c`` of face ``f`` at point ``p``
is also the side from ``p`` to the next corner of ``f``. Around ``p``, seen from
outside, the face after ``f`` is the one across the side from ``p`` to its
predecessor in ``f``: a permutation of the corners (:func:`_next_around`) whose
cycles are the fans of faces around each point. Every step is a numpy pass (a
hull of 25,000 points has 150,000 corners).
"""

from __future__ import annotations

from itertools import chain

import numpy as np

from .errors import GeometryError
from .soup import offsets_of


def flat_faces(polygons: list[list[int]]) -> tuple[np.ndarray, np.ndarray]:
    """``(corners, offsets)`` of ``polygons`` (lists of point indices)."""
    sizes = np.fromiter(map(len, polygons), np.int64, count=len(polygons))
    offsets = offsets_of(sizes)
    corners = np.fromiter(chain.from_iterable(polygons), np.int64, count=int(offsets[-1]))
    return corners, offsets


def not_closed() -> GeometryError:
    """The error for faces that do not make a closed surface."""
    return GeometryError("the convex hull does not close up (its points are too nearly "
                         "coplanar for the tolerance)")


def check_closed(corners: np.ndarray, offsets: np.ndarray) -> None:
    """Refuse faces that are not a closed genus-0 surface with one fan per point.

    Raises:
        GeometryError: a repeated side, a side without its reverse, a point with
            two fans, or an Euler characteristic other than 2.
    """
    if len(corners) == 0:
        raise not_closed()
    start = _fan_starts(_next_around(corners, offsets))
    points = int(np.count_nonzero(np.bincount(corners)))
    fans = int(np.count_nonzero(start == np.arange(len(corners))))
    if fans != points or points - len(corners) // 2 + len(offsets) - 1 != 2:
        raise not_closed()


def vertex_face_rings(corners: np.ndarray, offsets: np.ndarray
                      ) -> tuple[np.ndarray, np.ndarray]:
    """``(faces, ring_offsets)``: for each point of the faces (ascending), the
    faces around it counter-clockwise seen from outside, from the first face
    (least index) it is a corner of; ring ``k`` is
    ``faces[ring_offsets[k]:ring_offsets[k + 1]]``.

    Raises:
        GeometryError: the faces do not close up (see :func:`check_closed`).
    """
    succ = _next_around(corners, offsets)
    start = _fan_starts(succ)
    steps = _steps_to(succ, start)
    fan_size = np.bincount(start, minlength=len(corners))[start]
    position = (fan_size - steps) % fan_size  # 0 at the fan's first corner
    order = np.argsort(corners * int(fan_size.max()) + position)
    face = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    sizes = np.bincount(corners)
    sizes = sizes[sizes > 0]
    return face[order], offsets_of(sizes)


def _next_around(corners: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """``(C,)``: for each corner, the corner of the same point in the face after
    its own around that point (seen from outside, counter-clockwise).

    Raises:
        GeometryError: a side repeated, or without its reverse.
    """
    index = np.arange(len(corners))
    sizes = np.diff(offsets)
    first = np.repeat(offsets[:-1], sizes)
    last = np.repeat(offsets[1:] - 1, sizes)
    tails = corners[np.where(index == last, first, index + 1)]
    n = int(corners.max()) + 1
    sides, reverse = corners * n + tails, tails * n + corners
    # sorted alike, the sides and their reverses pair off (both sorts unstable: the
    # sides are distinct, or refused)
    order, by_reverse = np.argsort(sides), np.argsort(reverse)
    ordered = sides[order]
    if (ordered[1:] == ordered[:-1]).any() or not np.array_equal(ordered, reverse[by_reverse]):
        raise not_closed()
    mate = np.empty_like(order)  # the corner whose side is the reverse of each one's
    mate[by_reverse] = order
    # after the face of corner (p, q) with predecessor o comes the face of (p, o),
    # the reverse of the side (o, p) of the corner before
    return mate[np.where(index == first, last, index - 1)]


def _fan_starts(succ: np.ndarray) -> np.ndarray:
    """``(C,)``: the least corner of each corner's cycle of ``succ``, by doubling
    (min over 1, 2, 4, ... corners ahead, until nothing changes: a few passes
    for the fans of a hull, ``log2`` of the largest for any)."""
    least = np.minimum(np.arange(len(succ)), succ)
    ahead = succ[succ]
    while True:
        joined = np.minimum(least, least[ahead])
        if (joined == least).all():
            return least
        least = joined
        ahead = ahead[ahead]


def _steps_to(succ: np.ndarray, start: np.ndarray) -> np.ndarray:
    """``(C,)``: how many steps of ``succ`` lead from each corner to its cycle's
    ``start`` (list ranking by pointer doubling)."""
    index = np.arange(len(succ))
    ahead = np.where(index == start, index, succ)  # the start ends each list
    steps = (index != start).astype(np.int64)
    while (ahead != start).any():
        steps += np.where(ahead != start, steps[ahead], 0)
        ahead = ahead[ahead]
    return steps
