"""Vectors brought into range before their products are taken.

Cross products of raw coordinates overflow beyond about 1e77 (a norm squares
them once more) and underflow below about 1e-77, and a Newell sum of raw
positions cancels far from the origin. The helpers here shift each ring to one
of its own points and scale by powers of two, which is exact: inside the band
nothing changes bit for bit, outside it directions (and areas, scaled back)
come out right.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

# coordinates within [1 / BAND, BAND]: products of four of them (a squared
# cross product) stay normal floats, so arrays inside it are left as they are
BAND = 2.0 ** 120


def in_band(values: np.ndarray) -> bool:
    """True when the largest magnitude in ``values`` lies in the band (or is 0)."""
    if values.size == 0:
        return True
    top = max(float(values.max()), -float(values.min()))
    return top == 0.0 or 1.0 / BAND <= top <= BAND


def in_range(vectors: np.ndarray) -> np.ndarray:
    """``vectors`` ``(N, 3)`` with each row scaled by a power of two to a largest
    magnitude in [0.5, 1) when the array leaves the band, else ``vectors`` itself.

    For directions only: a row keeps its direction and its unit vector.
    """
    if in_band(vectors):
        return vectors
    top = np.abs(vectors).max(axis=-1, keepdims=True)
    return np.ldexp(vectors, -np.frexp(top)[1])


def together_in_range(values: np.ndarray) -> np.ndarray:
    """``values`` (any shape) times one power of two that brings its largest
    magnitude into [0.5, 1) when it leaves the band, else ``values`` itself.

    Unlike :func:`in_range` every row gets the same factor, so lengths of
    different rows still compare; NaN, inf and all-zero arrays are left as they are.
    """
    exponent = range_exponent(values)
    return values if exponent == 0 else np.ldexp(values, -exponent)


def range_exponent(values: np.ndarray) -> int:
    """The power of two :func:`together_in_range` divides ``values`` (any shape)
    by: 0 inside the band and for NaN, inf and all-zero arrays."""
    if in_band(values):
        return 0
    top = float(np.abs(values).max())
    return int(np.frexp(top)[1]) if 0.0 < top < np.inf else 0


def scaled_mean(values: np.ndarray, index: np.ndarray, count: int,
                sizes: np.ndarray) -> np.ndarray:
    """``(count, 3)`` mean of the rows of ``values`` ``(N, 3)`` grouped by ``index``
    ``(N,)`` (``sizes`` ``(count,)`` rows each, 0 for none), summed scaled by one
    power of two when ``values`` leaves the band: sums of coordinates near the
    float maximum overflow though their means do not. Unscaled, it is the
    ``np.add.at`` sum divided, bit for bit."""
    exponent = range_exponent(values)
    sums = np.zeros((count, 3))
    np.add.at(sums, index, values if exponent == 0 else np.ldexp(values, -exponent))
    means = sums / np.maximum(sizes, 1)[:, None]
    return means if exponent == 0 else np.ldexp(means, exponent)


def centroid(points: np.ndarray) -> np.ndarray:
    """``(3,)`` mean of ``(n, 3)`` ``points``, taken scaled by one power of two when
    they leave the band: the sum of coordinates near the float maximum overflows
    though their mean does not. Inside the band, ``points.mean(axis=0)`` itself.
    Points with a NaN or infinite coordinate (a caller's overflow, for it to
    refuse) give a non-finite mean, quietly."""
    exponent = range_exponent(points)
    if exponent == 0:
        with np.errstate(over="ignore", invalid="ignore"):  # only with NaN or inf in it
            return points.mean(axis=0)
    return np.ldexp(np.ldexp(points, -exponent).mean(axis=0), exponent)


def shifted_in_range(points: np.ndarray) -> np.ndarray:
    """``(k, 3)`` ``points`` themselves when they and their differences lie in the
    band, else their differences from the first point times one power of two
    (:func:`together_in_range`), for shapes that depend only on where the points
    lie relative to each other (hulls, planes): the same shape, with no product
    of huge or tiny coordinates. A difference beyond the float range comes out
    inf, for the caller to refuse (it must check the result is finite)."""
    with np.errstate(over="ignore", invalid="ignore"):  # the caller refuses inf / NaN
        rel = points - points[:1]
    return points if in_band(points) and in_band(rel) else together_in_range(rel)


def lengths(vectors: np.ndarray) -> np.ndarray:
    """``(N,)`` Euclidean lengths of the rows of ``vectors`` ``(N, 3)``, each row
    measured scaled by a power of two when the array leaves the band (inf only
    where the true length is beyond the float range)."""
    if in_band(vectors):
        return np.linalg.norm(vectors, axis=-1)
    exponent = np.frexp(np.abs(vectors).max(axis=-1))[1]
    norm = np.linalg.norm(np.ldexp(vectors, -exponent[..., None]), axis=-1)
    with np.errstate(over="ignore"):  # documented: beyond the float range is inf
        return np.ldexp(norm, exponent)


def cross_rows(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``(N, 3)`` ``np.cross(a, b)`` of ``(N, 3)`` rows, bit for bit, in a third
    of its time (np.cross moves axes and makes a temporary per product)."""
    out = np.empty(np.broadcast_shapes(a.shape, b.shape))
    for k, (i, j) in enumerate(((1, 2), (2, 0), (0, 1))):
        np.multiply(a[:, i], b[:, j], out=out[:, k])
        out[:, k] -= a[:, j] * b[:, i]
    return out


def unit(vectors: np.ndarray) -> np.ndarray:
    """``(N, 3)`` unit vectors along the rows of ``vectors`` (rows too short to have
    a direction, below 1e-300 once in range, stay zero)."""
    vectors = in_range(vectors)
    length = np.linalg.norm(vectors, axis=-1, keepdims=True)
    return np.divide(vectors, length, out=np.zeros_like(vectors), where=length > 1e-300)


def group_sum(index: np.ndarray, values: np.ndarray, count: int) -> np.ndarray:
    """``(count, 3)``: ``values`` ``(N, 3)`` summed by ``index`` ``(N,)``, in index
    order (bincount, not add.at: several times faster, the same sums)."""
    out = np.empty((count, 3))
    for axis in range(3):
        out[:, axis] = np.bincount(index, weights=values[:, axis], minlength=count)
    return out


class RingVectors(NamedTuple):
    """Corner points of rings (faces) made ready for cross products.

    Attributes:
        points: ``(C, 3)`` the corner points, times 1/4 when scaled (so that a
            difference of two cannot overflow), else the input itself.
        rel: ``(C, 3)`` each point minus its ring's origin, times ``2**shift``.
        shift: ``(C, 1)`` int power of two per corner (its ring's), or None for 0.
            Applied with ``ldexp``: a ring of denormal coordinates needs a shift
            past 1024, whose power of two alone is no float.
        exponent: ``(R,)`` int: the true ``rel`` of ring r is ``rel * 2**exponent[r]``;
            None when 0.
    """

    points: np.ndarray
    rel: np.ndarray
    shift: np.ndarray | None
    exponent: np.ndarray | None

    def along(self, other: np.ndarray) -> np.ndarray:
        """``(C, 3)`` the point of corner ``other[c]`` (same ring) minus that of
        ``c``, scaled like ``rel``. ``other``: ``(C,)`` corner indices."""
        d = np.take(self.points, other, axis=0) - self.points
        return d if self.shift is None else np.ldexp(d, self.shift)


def ring_vectors(points: np.ndarray, origin: np.ndarray, ring: np.ndarray,
                 count: int) -> RingVectors:
    """Shift ``(C, 3)`` corner ``points`` to their ring's ``origin`` ``(C, 3)`` (one
    point per ring, repeated on its corners) and, when the coordinates leave the
    band, scale each ring by a power of two. ``ring``: ``(C,)`` ring of each
    corner, of ``count`` rings."""
    if in_band(points) and in_band(origin):
        rel = points - origin
        if in_band(rel):
            return RingVectors(points, rel, None, None)
    points, rel = points * 0.25, origin * -0.25
    rel += points
    top = np.zeros(count)
    np.maximum.at(top, ring, np.abs(rel).max(axis=1))
    exponent = np.frexp(top)[1]
    shift = -exponent[ring][:, None]
    return RingVectors(points, np.ldexp(rel, shift), shift, exponent + 2)


def face_ring_vectors(positions: np.ndarray, corner_vertex: np.ndarray,
                      face_offsets: np.ndarray, corner_face: np.ndarray) -> RingVectors:
    """:func:`ring_vectors` of the faces of a mesh: the corner points of
    ``positions`` ``(V, 3)`` (``corner_vertex`` ``(C,)``), each relative to its
    face's first corner. Faces own corners ``face_offsets[f]:face_offsets[f + 1]``
    (``(F + 1,)``); ``corner_face`` ``(C,)`` is the face of each corner."""
    p = np.take(positions, corner_vertex, axis=0)
    origin = np.repeat(p[face_offsets[:-1]], np.diff(face_offsets), axis=0)
    return ring_vectors(p, origin, corner_face, len(face_offsets) - 1)


def newell(r: RingVectors, edge: np.ndarray, ring: np.ndarray, count: int) -> np.ndarray:
    """``(count, 3)`` Newell vector (twice the vector area) of each ring, in the
    scale of ``r`` (times ``2**-exponent``). ``edge``: ``r.along(next corner)``.

    ``sum (p_i - o) x (p_{i+1} - o)`` is the same for every origin ``o``, and
    ``(p_i - o) x (p_{i+1} - p_i)`` equals its term.
    """
    return group_sum(ring, cross_rows(r.rel, edge), count)


def true_lengths(lengths: np.ndarray, r: RingVectors, power: int) -> np.ndarray:
    """``(R,)`` ``lengths`` of per-ring quantities of degree ``power`` in ``r``'s
    scale, scaled back; inf where the true value is beyond the float range."""
    if r.exponent is None:
        return lengths
    with np.errstate(over="ignore"):  # documented: beyond the float range is inf
        return np.ldexp(lengths, power * r.exponent)
