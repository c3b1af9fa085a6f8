"""The inner shell of TopMod's Menger sponge (``createSponge``) and its edge collapse.

TopMod gives every face an inner *disc*: the face offset ``t`` inward along its
normal and inset in its plane (``duplicateFacePlanarOffset``: a corner moves
``t (pvec + nvec)``, unit edge vectors, the other way at a concave corner). The
discs of two faces that share an edge are joined by a quad (``connectEdges``)
whose two *joining edges* each link the two discs' corners at one end of the
edge; the joining edges around a vertex bound a *vertex face*. Here joining edge
``J(c)`` runs from the disc corner of corner ``c`` to that of ``vnext(c)`` (the
corner across ``c``'s edge, at the same vertex): one per corner.

TopMod then collapses, all at once from the shell as built, every joining edge
shorter than ``factor * t`` (0.01 when the factor is at most 0.001) or part of a
self-intersection: some other edge at one of its ends crosses some other edge at
its other end in a common plane (``checkIntersection``: the four points within
about 0.01 radian of one plane, each edge's ends on either side of the other's
line). Where faces meet at right angles the disc corners at a vertex coincide,
so every factor collapses everything.

TopMod moved each collapsed edge's survivor to the edge's midpoint, one collapse
after another, so a vertex merged from three or more disc corners landed where
the order of its edges put it. livemod places a vertex whose joining edges all
collapse on the crust's inner shell (``rind.crust_offsets``, the disc
corners' common point at right angles) and any other merged group at the mean
of its disc corners (the midpoint, for two).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._graph import cycle_layout
from ._vectors import cross_rows, lengths, scaled_mean, together_in_range
from .arrays import MeshArrays
from .normals import RingNormals, inset_offsets, reversed_rings, ring_normals

__all__ = ["InnerShell", "collapse_length", "disc_corners", "inner_shell", "joining_collapses",
           "vertex_faces"]

#: TopMod's threshold length when the factor is at most :data:`FACTOR_FLOOR`.
DEFAULT_LENGTH = 0.01
#: Factors at most this take :data:`DEFAULT_LENGTH` (TopMod's test, ``> 0.001``).
FACTOR_FLOOR = 0.001
# checkIntersection's limits: |n1 + n2|^2 of two unit normals, and the length
# (TopMod's ZERO, 1e-10, here the sine of an angle) below which a cross
# product is left unnormalised, so that it never matches
_OPPOSITE = 1e-4
_NO_DIRECTION = 1e-10
# the screen's slack: far above the rounding of a difference of two products
_ROUNDING = 1e-9


def collapse_length(thickness: float, factor: float) -> float:
    """TopMod's threshold: ``thickness * factor``, or 0.01 for a factor at most 0.001."""
    return thickness * factor if factor > FACTOR_FLOOR else DEFAULT_LENGTH


def disc_corners(a: MeshArrays, thickness: float,
                 reversed_rings_normals: RingNormals | None = None) -> np.ndarray:
    """``(C, 3)`` the disc corner of every corner: moved ``thickness`` into its face
    (TopMod's planar offset, absolute) and ``thickness`` against the face's normal.

    ``reversed_rings_normals``: the normals of the faces reversed, when the
    caller has them (the crust's, ``rind.reversed_normals``);
    turned round they are the faces' own, to within rounding, unless a corner
    is straight (where ties between neighbours go the other way).
    """
    rn = _forward_normals(a, reversed_rings_normals)
    move = inset_offsets(a.positions, a.corner_vertex, a.face_offsets, thickness,
                         fractional=False, normals=rn)
    return a.positions[a.corner_vertex] + move - thickness * rn.face[a.corner_face]


def _forward_normals(a: MeshArrays, backwards: RingNormals | None) -> RingNormals:
    """TopMod's normals of ``a``'s faces, from those of the reversed faces where
    that gives them: a corner's cross product reversed is exactly its negation."""
    if backwards is None or backwards.winged.any():
        return ring_normals(a.positions, a.corner_vertex, a.face_offsets)
    back = reversed_rings(a.face_offsets)
    return RingNormals(-backwards.corner[back], -backwards.face, backwards.concave[back],
                       backwards.winged[back], np.arange(len(back), dtype=np.int64))


def joining_collapses(a: MeshArrays, discs: np.ndarray, length: float) -> np.ndarray:
    """``(C,)`` bool: TopMod collapses ``J(c)`` (shorter than ``length``, or crossed).

    Args:
        a: the mesh (closed, no point-spheres).
        discs: ``(C, 3)`` :func:`disc_corners`.
        length: :func:`collapse_length`.
    """
    vnext = a.corner_vnext
    collapsed = lengths(discs[vnext] - discs) < length
    rows = np.flatnonzero(~collapsed)
    if len(rows):
        collapsed[rows] = _crossed(a, together_in_range(discs), rows)
    return collapsed


def _crossed(a: MeshArrays, p: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """``(k,)`` bool: for ``J(c)``, ``c`` in ``rows``, whether one of the three other
    edges at its start crosses one of the three other edges at its end
    (``p``: ``(C, 3)`` disc corners, in range).

    Each pair is first screened by the signs of TopMod's two pairs of normals,
    taken from dot products alone (Binet-Cauchy: ``(a x b) . (a x c) =
    (a . a)(b . c) - (a . b)(a . c)``): edges cross only where each one's ends
    lie on either side of the other's line, which on a smooth mesh few pairs
    do. Those left get the full test.
    """
    nxt, prv, vnext = a.corner_next, a.corner_prev, a.corner_vnext
    vprev = a.corner_mate[prv]
    side = p[nxt] - p  # each disc's sides, from each corner to the next
    join = p[vnext] - p
    c, w = rows, vnext[rows]
    j = join[c]
    at_start = (side[c], -side[prv[c]], -join[vprev[c]])
    at_end = (side[w], -side[prv[w]], join[w])
    jj = _dots(j, j)
    start_j = [_dots(dx, j) for dx in at_start]
    start_sq = [_dots(dx, dx) for dx in at_start]
    end_j = [_dots(dy, j) for dy in at_end]
    end_sq = [_dots(dy, dy) for dy in at_end]
    # at a vertex of two corners, J(vprev c) = J(vnext c) is at both ends: no pair
    twin = vprev[c] == w
    hit = np.zeros(len(rows), dtype=bool)
    for k, dy in enumerate(at_end):
        for i, dx in enumerate(at_start):
            xy = _dots(dx, dy)
            # n1 . n2 for n1 = dx x j, n2 = dx x (j + dy) and m1 . m2 for
            # m1 = j x dy, m2 = dy x (dx - j): each pair must point apart
            found = np.flatnonzero(
                _apart(start_sq[i] * (jj + end_j[k]), start_j[i] * (start_j[i] + xy))
                & ~((hit | twin) if i == k == 2 else hit))
            sj, ej, x = start_j[i][found], end_j[k][found], xy[found]
            found = found[_apart(end_sq[k][found] * (jj[found] - sj), ej * (ej - x))]
            if len(found):
                hit[found] = _pair_crosses(dx[found], j[found], dy[found])
    return hit


def _pair_crosses(dx: np.ndarray, j: np.ndarray, dy: np.ndarray) -> np.ndarray:
    """``(k,)`` bool: TopMod's ``checkIntersection`` of the edges ``u -> u + dx`` and
    ``w -> w + dy`` (rows ``(k, 3)``, in range, ``j = w - u``), scale-free: the
    ends of each lie on either side of the other's line, in one plane within
    about 0.01 radian. A cross product whose sine is below 1e-10 has no
    direction and matches nothing (an end on the other edge's line: no crossing)."""
    return (_opposite(_normal(dx, j), _normal(dx, j + dy))
            & _opposite(_normal(j, dy), _normal(dy, dx - j)))


def _normal(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``(k, 3)`` unit ``a x b`` (rows in range), zero where the sine of their
    angle is below 1e-10."""
    cross = cross_rows(a, b)
    size = np.sqrt(_dots(cross, cross))
    scale = np.sqrt(_dots(a, a) * _dots(b, b))
    return np.divide(cross, size[:, None], out=np.zeros_like(cross),
                     where=(size > _NO_DIRECTION * scale)[:, None])


def _opposite(n1: np.ndarray, n2: np.ndarray) -> np.ndarray:
    """``(k,)`` bool: unit normals (or zero rows) summing to within 0.01 of zero."""
    total = n1 + n2
    both = (n1 != 0).any(axis=1) & (n2 != 0).any(axis=1)
    return both & (_dots(total, total) < _OPPOSITE)


def _apart(first: np.ndarray, second: np.ndarray) -> np.ndarray:
    """``(k,)`` bool: ``first - second`` (two normals' dot product) is not clearly
    positive, allowing for the rounding of its two terms."""
    return first - second <= _ROUNDING * (np.abs(first) + np.abs(second))


def _dots(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """``(k,)`` row-wise dot products of ``(k, 3)`` arrays."""
    return np.einsum("ij,ij->i", u, v)


@dataclass(frozen=True)
class InnerShell:
    """The inner shell after the collapse.

    Attributes:
        corner_class: ``(C,)`` int64, the shell vertex each corner's disc corner
            became; shell vertices come vertex by vertex (one per vertex where
            every joining edge collapsed: then ``corner_class`` is the corner's
            vertex).
        positions: ``(K, 3)`` the shell vertices.
        kept: ``(C,)`` bool, the joining edges ``J(c)`` left as edges.
        tail: ``(C,)`` int64, the corner whose kept ``J`` leaves each corner's
            shell vertex (the first one along ``vnext``); the corner itself at a
            vertex where every joining edge collapsed.
    """

    corner_class: np.ndarray
    positions: np.ndarray
    kept: np.ndarray
    tail: np.ndarray


def inner_shell(a: MeshArrays, inner: np.ndarray, discs: np.ndarray,
                collapsed: np.ndarray) -> InnerShell:
    """The shell left when the joining edges ``collapsed`` (``(C,)`` bool) go.

    A vertex left with one joining edge would make it a loop: it goes too (TopMod
    kept it). ``inner``: ``(V, 3)`` the crust's inner points, where a vertex all of
    whose joining edges go is placed; ``discs``: ``(C, 3)`` :func:`disc_corners`.
    """
    cv, nv = a.corner_vertex, len(a.vertex_ids)
    kept = ~collapsed
    open_vertex = np.bincount(cv[kept], minlength=nv) >= 2
    kept &= open_vertex[cv]
    if not kept.any():
        return InnerShell(cv, inner, kept, np.arange(len(cv)))
    tail = _run_tails(a.corner_vnext, kept | ~open_vertex[cv])
    # one class per run at an open vertex, one per closed vertex, vertex by vertex
    key = cv * (len(cv) + 1) + np.where(open_vertex[cv], tail + 1, 0)
    _, first, corner_class = np.unique(key, return_index=True, return_inverse=True)
    class_vertex = cv[first]
    sizes = np.bincount(corner_class, minlength=len(first))
    positions = scaled_mean(discs, corner_class, len(first), sizes)
    closed = ~open_vertex[class_vertex]
    positions[closed] = inner[class_vertex[closed]]
    return InnerShell(corner_class.astype(np.int64), positions, kept, tail)


def _run_tails(vnext: np.ndarray, stop: np.ndarray) -> np.ndarray:
    """``(C,)`` for every corner the first corner from it along ``vnext`` (itself
    included) where ``stop`` holds (pointer doubling; every cycle has a stop)."""
    tail = np.where(stop, np.arange(len(vnext)), vnext)
    while True:
        jumped = tail[tail]
        if np.array_equal(jumped, tail):
            return tail
        tail = jumped


def vertex_faces(a: MeshArrays, shell: InnerShell) -> tuple[np.ndarray, np.ndarray]:
    """The vertex faces: ``(corners (k,), offsets (n + 1,))``, each face's kept
    joining edges ``J(c)`` by their ``c``, in ring order (``J(c)`` runs from
    ``c``'s shell vertex to the next corner's)."""
    tails = np.flatnonzero(shell.kept)
    local = np.full(len(shell.kept), -1, dtype=np.int64)
    local[tails] = np.arange(len(tails))
    following = shell.tail[a.corner_vnext[tails]]
    order, offsets = cycle_layout(local[following])
    return tails[order], offsets
