"""The triangle lookup of :mod:`.hull` for large point sets: a batched quickhull.

Turning a plane about each hull edge (:mod:`.hull`'s gift wrapping) passes
over every point once per face: 38 s for 24,600 points. Here a triangulated
hull is built in rounds, every step a numpy pass:

1. each facet with points above it (more than ``eps``: its *conflicts*) offers
   the farthest of them;
2. the offers claim the facets they see, each facet going to the least in a
   fixed random rank; the offers whose regions are whole and apart are taken,
   all at once (:func:`_claims`);
3. each taken point replaces its visible facets by a fan to their horizon;
   the conflicts of a new facet are among those of the two facets beside its
   horizon edge (the conflict graph of the randomized incremental hull).

Its triangles are then checked as :func:`._hull_table.triangle_table` checks
the triples it tries, only against the points that can matter (see
:func:`verified_triangles`), and the ones that pass are what turning would
reach across their sides: :mod:`.hull` takes them as they are and turns only
to the others (faces with coplanar points, points on edges, thin triangles),
so the faces are turning's, polygon for polygon.

Arrays of floats are kept and gathered as columns (one array per coordinate),
and cross products taken by columns: gathering rows of an ``(n, 3)`` array, or
``numpy.cross``, is several times slower at these sizes.
"""

from __future__ import annotations

import numpy as np

from ._hull_table import _WIDE

# a batch round that does not close up (rounding near the tolerance) gives up
# after this many rounds more than the points would ever need
_ROUNDS = 64
# pairs measured at a time in _clear (their temporaries stay in cache)
_BLOCK = 1 << 15


# the per-facet scratch arrays of _Facets and their types
_SCRATCH = (("top", np.float64), ("least", np.int64), ("holder", np.int64), ("owner", np.int64))


class _Facets:
    """Triangles with their planes and neighbours, in growable arrays.

    ``tri[f]`` is counter-clockwise seen from outside; ``nbr[f, j]`` is the
    facet across side ``j`` (from ``tri[f, j]`` to ``tri[f, (j + 1) % 3]``).
    Coordinates and planes are kept as columns (``x``, ``y``, ``z``; ``plane``'s
    rows: unit normal and offset): gathering from 1D arrays is several times
    faster than gathering rows.

    A round's per-facet scratch (:data:`_SCRATCH`: each facet's farthest outside
    height, least claiming rank, holder and owner) is kept here at its fill
    value between uses, and each use puts back the entries it changed: filling
    arrays as long as all the facets, several times a round, cost more than
    the rest of a late round's work.
    """

    def __init__(self, pts: np.ndarray, capacity: int) -> None:
        self.pts = pts
        self.x, self.y, self.z = (np.ascontiguousarray(axis) for axis in pts.T)
        self.tri = np.zeros((capacity, 3), np.int64)
        self.nbr = np.zeros((capacity, 3), np.int64)
        self.plane = np.zeros((4, capacity))
        self.alive = np.zeros(capacity, bool)
        self.unclaimed = len(pts)  # above every rank
        self.top, self.least, self.holder, self.owner = (
            np.full(capacity, self._fill(name), dtype) for name, dtype in _SCRATCH)
        self.n = 0

    def _fill(self, name: str) -> float:
        return {"top": -np.inf, "least": self.unclaimed}.get(name, -1)

    def add(self, tri: np.ndarray, nbr: np.ndarray) -> np.ndarray:
        """Append ``(k, 3)`` triangles with their neighbours; their indices."""
        k = len(tri)
        if self.n + k > len(self.tri):
            self._grow(max(2 * len(self.tri), self.n + k))
        index = np.arange(self.n, self.n + k)
        self.tri[self.n : self.n + k], self.nbr[self.n : self.n + k] = tri, nbr
        self.alive[self.n : self.n + k] = True
        (ax, ay, az), (bx, by, bz), (cx, cy, cz) = (self.coordinates(tri[:, j]) for j in range(3))
        ux, uy, uz, vx, vy, vz = bx - ax, by - ay, bz - az, cx - ax, cy - ay, cz - az
        nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
        length = np.sqrt(nx * nx + ny * ny + nz * nz)
        with np.errstate(divide="ignore", invalid="ignore"):  # a flat one: NaN, checked
            nx, ny, nz = nx / length, ny / length, nz / length
        self.plane[:, self.n : self.n + k] = nx, ny, nz, nx * ax + ny * ay + nz * az
        self.n += k
        return index

    def _grow(self, capacity: int) -> None:
        arrays = [("tri", 0), ("nbr", 0), ("plane", 1), ("alive", 0)]
        for name, axis in arrays + [(name, 0) for name, _ in _SCRATCH]:
            old = getattr(self, name)
            shape = list(old.shape)
            shape[axis] = capacity
            new = np.full(shape, self._fill(name) if (name, axis) not in arrays else 0, old.dtype)
            if axis:
                new[:, : self.n] = old[:, : self.n]
            else:
                new[: self.n] = old[: self.n]
            setattr(self, name, new)

    def coordinates(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(x, y, z)``, ``(k,)`` each: the coordinates of ``points``."""
        return self.x[points], self.y[points], self.z[points]

    def heights(self, points: np.ndarray, facets: np.ndarray) -> np.ndarray:
        """``(k,)`` height of point ``points[i]`` over the plane of ``facets[i]``."""
        nx, ny, nz, offset = np.take(self.plane, facets, axis=1)
        x, y, z = self.coordinates(points)
        return x * nx + y * ny + z * nz - offset

    def neighbours(self, facets: np.ndarray) -> np.ndarray:
        """``(3 k,)``: the facets across the sides of ``facets``, facet by facet."""
        return np.take(self.nbr, facets, axis=0).ravel()


def quickhull(pts: np.ndarray, eps: float) -> tuple[np.ndarray, np.ndarray] | None:
    """``(tri, nbr)``: ``(F, 3)`` triangles of the convex hull of ``(n, 3)`` ``pts``
    (framed as :mod:`.hull` frames them, not flat), counter-clockwise seen from
    outside, with every point at most ``eps`` above each, and ``(F, 3)`` the
    triangle across each side (side ``j`` runs from corner ``j`` to ``j + 1``);
    or None when rounding near the tolerance breaks a round (a horizon that is
    no simple cycle), for the caller to turn every face instead. Points within
    ``eps`` of a facet are no vertices."""
    start = _simplex(pts, eps)
    if start is None:
        return None
    facets = _Facets(pts, 8 * len(pts) + 16)
    first = facets.add(*start)
    height = (pts @ facets.plane[:3, first]) - facets.plane[3, first]
    state = _Outside(np.where(height.max(axis=1) > eps, first[height.argmax(axis=1)], -1),
                     height.max(axis=1))
    rank = np.random.default_rng(len(pts)).permutation(len(pts))
    for _ in range(_ROUNDS + 8 * int(np.log2(len(pts) + 1))):
        points = np.flatnonzero(state.facet >= 0)
        if len(points) == 0:
            alive = np.flatnonzero(facets.alive[: facets.n])
            index = np.full(facets.n, -1, np.int64)
            index[alive] = np.arange(len(alive))
            return facets.tri[alive], index[facets.nbr[alive]]
        if not _round(facets, state, points, rank, eps):
            return None
    return None


class _Outside:
    """Each point's outside facet (one it lies more than ``eps`` above, or -1 for
    none: inside, within ``eps`` of the hull, or a vertex) and its height there.

    One facet is enough (quickhull's outside sets): a point above a facet a new
    point sees is above one of that point's new facets, or inside the grown hull
    (above the facet's plane and below every new one is within the cone from the
    new point over the horizon, cut off by that plane, inside the new hull)."""

    def __init__(self, facet: np.ndarray, height: np.ndarray) -> None:
        self.facet, self.height = facet, height


def _simplex(pts: np.ndarray, eps: float) -> tuple[np.ndarray, np.ndarray] | None:
    """The first tetrahedron: ``(4, 3)`` outward triangles and their neighbours,
    from four extreme points; None when they are too nearly coplanar."""
    a = int(np.argmin(pts[:, 0]))
    b = int(np.argmax(np.einsum("ij,ij->i", pts - pts[a], pts - pts[a])))
    ab = pts[b] - pts[a]
    off_line = np.cross(pts - pts[a], ab)
    c = int(np.argmax(np.einsum("ij,ij->i", off_line, off_line)))
    normal = np.cross(ab, pts[c] - pts[a])
    length = float(np.sqrt(normal @ normal))
    if length == 0.0:
        return None
    side = (pts - pts[a]) @ (normal / length)
    d = int(np.argmax(np.abs(side)))
    if abs(side[d]) <= eps:
        return None
    if side[d] > 0:  # d above (a, b, c): turn that face so that d is below
        b, c = c, b
    tri = np.array([[a, b, c], [a, d, b], [b, d, c], [c, d, a]], np.int64)
    # side j of face f, (tri[f, j], tri[f, j + 1]), meets the face with its reverse
    nbr = np.array([[1, 2, 3], [3, 2, 0], [1, 3, 0], [2, 1, 0]], np.int64)
    return tri, nbr


def _round(facets: _Facets, state: _Outside, points: np.ndarray, rank: np.ndarray,
           eps: float) -> bool:
    """One round: each facet offers its farthest outside point; the offers whose
    visible regions are apart are taken, their fans built, and the outside
    points of the facets they replace handed to those fans. False when a
    horizon is no simple cycle."""
    facet, height = state.facet[points], state.height[points]
    np.maximum.at(facets.top, facet, height)
    offers = points[height == facets.top[facet]]
    facets.top[facet] = -np.inf
    winners, visible = _claims(facets, offers, state.facet[offers], rank, eps)
    horizon = _horizon(facets, visible, facets.owner)
    if horizon is not None:
        facets.alive[visible] = False
        state.facet[winners] = -1
        _hand_on(facets, state, points, facets.owner, horizon, eps)
    facets.owner[visible] = -1
    return horizon is not None


def _claims(facets: _Facets, offers: np.ndarray, start: np.ndarray, rank: np.ndarray,
            eps: float) -> tuple[np.ndarray, np.ndarray]:
    """``(winners, visible)``: the offers taken this round and the facets they
    see; ``facets.owner`` of each of those is the winner whose region it is in
    (the caller puts them back to -1).

    Each offer's visible region (the facets it lies more than ``eps`` above: a
    connected set) is grown from the facet it is outside of, step by step,
    through the neighbours it is above. A facet goes to the least offer in
    ``rank`` (a fixed random permutation) that reached it; an offer that finds
    a facet held by a lesser one, or loses one to it, has lost and stops
    growing. The winners, whose regions are whole and apart (two of them
    meeting on a facet would have made one lose), are Luby's independent set,
    or a larger one (an offer can win beside a lesser one that lost before it
    reached their common facets). Winners whose regions meet along an edge keep it only where each
    lies below the other's new triangle on it (a convex edge, as taking one
    after the other would make it); where not, the later one is given back.
    """
    best, holder = facets.least, facets.holder  # per facet: the least rank to reach it, whose
    lost = np.zeros(len(rank), bool)
    slot = np.empty(facets.n, np.int64)
    held_p, held_f = [], []
    fp, ff = offers, start
    reached = [ff]
    while len(fp):
        r = rank[fp]
        np.minimum.at(best, ff, r)
        least = r == best[ff]
        lost[fp[~least]] = True
        before = holder[ff]  # a holder beaten here has lost
        lost[before[(before >= 0) & (rank[before] > best[ff])]] = True
        holder[ff[least]] = fp[least]
        grow = np.flatnonzero(least & ~lost[fp])
        slot[ff[grow]] = grow  # the same pair reached twice grows once
        grow = grow[slot[ff[grow]] == grow]
        held_p.append(fp[grow])
        held_f.append(ff[grow])
        cp, cf = np.repeat(fp[grow], 3), facets.neighbours(ff[grow])
        fresh = (holder[cf] != cp) & ~lost[cp]
        cp, cf = cp[fresh], cf[fresh]
        seen = facets.heights(cp, cf) > eps
        fp, ff = cp[seen], cf[seen]
        reached.append(ff)
    # each pair is held once (an offer never comes back to a facet it holds)
    hp, hf = np.concatenate(held_p), np.concatenate(held_f)
    kept = (holder[hf] == hp) & ~lost[hp]
    visible, by = hf[kept], hp[kept]
    for facet in reached:
        best[facet], holder[facet] = facets.unclaimed, -1
    owner = facets.owner
    owner[visible] = by
    back = _concave_meetings(facets, by, visible, owner, rank, eps)
    owner[visible[back[by]]] = -1
    return offers[~lost[offers] & ~back[offers]], visible[~back[by]]


def _hand_on(facets: _Facets, state: _Outside, points: np.ndarray, owner: np.ndarray,
             horizon: tuple[np.ndarray, np.ndarray], eps: float) -> None:
    """The outside points of the facets a taken point replaced go to a new facet
    of its fan they lie more than ``eps`` above (first the ones built on their
    old facet's horizon edges, then the whole fan), or are inside."""
    orphan = points[state.facet[points] >= 0]
    orphan = orphan[owner[state.facet[orphan]] >= 0]
    if len(orphan) == 0:
        return
    new, side = horizon
    built = np.zeros(3 * facets.n, np.int64)  # 1 + the new facet on each side, 0: none
    built[side] = new + 1
    candidates = built[3 * state.facet[orphan][:, None] + np.arange(3)].ravel() - 1
    rows = np.flatnonzero(candidates >= 0)
    placed = _move_up(facets, state, orphan, rows // 3, candidates[rows], eps)
    rest = orphan[~placed]
    if len(rest) == 0:
        return
    # the whole fan of the point that took its facet
    apex = facets.tri[new, 2]
    by_apex = np.argsort(apex, kind="stable")
    fans = np.flatnonzero(np.r_[True, apex[by_apex][1:] != apex[by_apex][:-1]])
    first, size = np.zeros(len(facets.pts), np.int64), np.zeros(len(facets.pts), np.int64)
    first[apex[by_apex[fans]]] = fans
    size[apex[by_apex[fans]]] = np.diff(np.r_[fans, len(apex)])
    taker = owner[state.facet[rest]]
    count = size[taker]
    rows = np.repeat(np.arange(len(rest)), count)
    at = np.repeat(first[taker] - (np.cumsum(count) - count), count) + np.arange(len(rows))
    placed = _move_up(facets, state, rest, rows, new[by_apex[at]], eps)
    state.facet[rest[~placed]] = -1


def _move_up(facets: _Facets, state: _Outside, points: np.ndarray, rows: np.ndarray,
             candidates: np.ndarray, eps: float) -> np.ndarray:
    """Move each of ``points`` to the one of its ``candidates`` (facets, paired
    with ``points[rows]``) it lies highest above, if more than ``eps``; ``(k,)``
    bool: which were moved."""
    height = facets.heights(points[rows], candidates)
    top = np.full(len(points), -np.inf)
    np.maximum.at(top, rows, height)
    up = (height == top[rows]) & (height > eps)
    state.facet[points[rows[up]]] = candidates[up]
    state.height[points[rows[up]]] = height[up]
    return top > eps


def _concave_meetings(facets: _Facets, wp: np.ndarray, wf: np.ndarray, owner: np.ndarray,
                      rank: np.ndarray, eps: float) -> np.ndarray:
    """``(n,)`` bool: the taken points ``wp`` (seeing ``wf``) to give back where
    their region meets another's (``owner``) along an edge ``(a, b)`` with one
    lying above the other's new triangle (``a, b``, itself): the later of the
    two in ``rank``."""
    f = np.repeat(wf, 3)
    j = np.tile(np.arange(3), len(wf))
    p = np.repeat(wp, 3)
    q = owner[facets.neighbours(wf)]
    meet = (q >= 0) & (q != p)
    f, j, p, q = f[meet], j[meet], p[meet], q[meet]
    back = np.zeros(len(rank), bool)
    if len(f) == 0:
        return back
    flat = facets.tri.ravel()
    ax, ay, az = facets.coordinates(flat[3 * f + j])
    bx, by, bz = facets.coordinates(flat[3 * f + (j + 1) % 3])
    (px, py, pz), (qx, qy, qz) = facets.coordinates(p), facets.coordinates(q)
    ux, uy, uz, vx, vy, vz = bx - ax, by - ay, bz - az, px - ax, py - ay, pz - az
    nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    with np.errstate(invalid="ignore", divide="ignore"):  # a flat new triangle: given back
        height = ((qx - ax) * nx + (qy - ay) * ny + (qz - az) * nz) / np.sqrt(
            nx * nx + ny * ny + nz * nz)
        above = ~(height <= eps)
    later = np.where(rank[p] > rank[q], p, q)
    back[later[above]] = True
    return back


def _horizon(facets: _Facets, visible: np.ndarray, owner: np.ndarray
             ) -> tuple[np.ndarray, np.ndarray] | None:
    """Build the fan of every taken point over its horizon: ``(new facets, the
    side each is built on)`` (side ``j`` of visible facet ``f`` as ``3 f + j``), or
    None when a horizon is no simple cycle."""
    f = np.repeat(visible, 3)
    j = np.tile(np.arange(3), len(visible))
    g = facets.neighbours(visible)
    edge = owner[g] != owner[f]
    f, j, g = f[edge], j[edge], g[edge]
    apex = owner[f]
    flat = facets.tri.ravel()
    a, b = flat[3 * f + j], flat[3 * f + (j + 1) % 3]
    n = len(facets.pts)
    # where two fans meet (g is in another taken region) they meet each other
    shared = owner[g] >= 0
    # the fan of apex p: the facet on edge (a, b) meets the one from b and the one to a
    start_key, end_key = apex * n + a, apex * n + b
    order = np.argsort(start_key)
    sorted_keys = start_key[order]
    if len(sorted_keys) > 1 and (sorted_keys[1:] == sorted_keys[:-1]).any():
        return None  # two horizon edges leave one vertex: no simple cycle
    after = np.searchsorted(sorted_keys, end_key)
    if (after >= len(sorted_keys)).any() or (sorted_keys[np.minimum(after, len(sorted_keys) - 1)]
                                           != end_key).any():
        return None
    base = facets.n
    next_fan = base + order[after]
    before = np.empty(len(f), np.int64)
    before[order[after]] = np.arange(len(f))
    across = g.copy()
    if shared.any():
        edge_key = a * n + b
        by_edge = np.argsort(edge_key)
        mate = by_edge[np.searchsorted(edge_key[by_edge], b[shared] * n + a[shared])]
        across[shared] = base + mate
    tri = np.stack([a, b, apex], axis=1)
    nbr = np.stack([across, next_fan, base + before], axis=1)
    new = facets.add(tri, nbr)
    # the outer facet's side (b, a) now meets the new facet
    outer, new_outer = g[~shared], new[~shared]
    outer_tri = np.take(facets.tri, outer, axis=0)
    k = np.argmax((outer_tri == b[~shared][:, None])
                  & (np.roll(outer_tri, -1, axis=1) == a[~shared][:, None]), axis=1)
    facets.nbr.ravel()[3 * outer + k] = new_outer
    if not np.isfinite(facets.plane[:, new]).all():
        return None
    return new, 3 * f + j


def verified_triangles(pts: np.ndarray, tri: np.ndarray, eps: float, extent: float
                       ) -> np.ndarray:
    """``(F,)`` bool: which of the hull's ``tri`` turning would reach as they are.

    A triangle passes as :func:`._hull_table.triangle_table` lets a triple in: no
    point but its three within ``eps`` of its plane or above it, wide (its third
    corner more than ``_WIDE`` tolerances off the line of the other two), no
    side nearly in line with another point. Only the points that can matter are
    measured: the vertices joined to its corners (the highest vertex off a face
    of a convex hull is joined to one of its corners: when those lie more than
    ``eps`` below, every vertex does), and the points that are no vertex in the
    box of those, grown by the tolerance (the part of the hull within ``eps`` of
    the plane is the hull of the triangle and of the edges leaving it).
    """
    thin = _WIDE * 2.0 * eps * extent
    a, b, c = (pts[tri[:, j]] for j in range(3))
    area2 = np.cross(b - a, c - a)
    wide = np.einsum("ij,ij->i", area2, area2) > thin * thin
    ring_count, ring = _ring_pairs(tri, *_joined(tri, len(pts)))
    ok = wide & _clear(pts, tri, ring_count, ring, eps, thin)
    loose = np.ones(len(pts), bool)
    loose[tri.ravel()] = False
    if loose.any():
        lo, hi = _boxes(pts, ring_count, ring)
        box_t, box_p = _box_points(pts, np.flatnonzero(loose), lo, hi, 2.0 * eps)
        ok &= _clear(pts, tri, np.bincount(box_t, minlength=len(tri)), box_p, eps, thin)
    return ok


def convex(pts: np.ndarray, tri: np.ndarray, eps: float, extent: float) -> bool:
    """Whether no vertex lies more than ``eps`` above a triangle of ``tri``
    joined to it, slivers aside (a triangle whose corners are within ``_WIDE``
    tolerances of one line has no plane to be above): every edge convex, to
    the tolerance (pass a few: a vertex may end up up to twice the tolerance
    its planes were built with above a neighbour's)."""
    count, p = _ring_pairs(tri, *_joined(tri, len(pts)))
    t = np.repeat(np.arange(len(tri)), count)
    a, b, c = (pts[tri[:, j]] for j in range(3))
    normal = np.cross(b - a, c - a)
    length = np.sqrt(np.einsum("ij,ij->i", normal, normal))
    wide = length > _WIDE * 2.0 * eps * extent
    normal /= np.where(wide, length, 1.0)[:, None]
    height = np.einsum("ij,ij->i", pts[p] - a[t], normal[t])
    return bool((height[wide[t]] <= eps).all())


def _joined(tri: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """``(heads, starts)``: vertex ``v``'s edges lead to ``heads[starts[v]:starts[v + 1]]``."""
    tails = tri.ravel()
    order = np.argsort(tails)
    heads = np.roll(tri, -1, axis=1).ravel()[order]
    return heads, np.searchsorted(tails[order], np.arange(n + 1))


def _ring_pairs(tri: np.ndarray, heads: np.ndarray, starts: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """``(count, p)``: every vertex joined to a corner of each triangle, in
    triangle order, ``count[t]`` of them for triangle ``t``."""
    corner = tri.ravel()
    first = starts[corner]
    count = starts[corner + 1] - first
    p = heads[np.repeat(first - (np.cumsum(count) - count), count) + np.arange(int(count.sum()))]
    return count.reshape(-1, 3).sum(axis=1), p


def _boxes(pts: np.ndarray, count: np.ndarray, ring: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray]:
    """``(lo, hi)`` ``(F, 3)``: the box of each triangle's ring (``count`` and
    ``ring`` as :func:`_ring_pairs`; it holds the corners: each is joined to the
    next)."""
    runs = np.cumsum(count) - count
    around = pts[ring]
    return np.minimum.reduceat(around, runs, axis=0), np.maximum.reduceat(around, runs, axis=0)


def _clear(pts: np.ndarray, tri: np.ndarray, count: np.ndarray, p: np.ndarray, eps: float,
           thin: float) -> np.ndarray:
    """``(F,)`` bool: none of the points ``p`` (the first ``count[0]`` paired with
    triangle 0, the next ``count[1]`` with triangle 1, ...; points of a triangle's
    own three aside) lies within ``eps`` of the triangle's plane or above
    it, or nearly in line (``thin``) with one of its sides (``|side x (p -
    corner)| <= thin``, as ``|side|^2 |p - corner|^2 - (side . (p - corner))^2``).

    A point nearly in line with a side is as near the plane (the side lies in
    it): only the pairs within ``4 max(eps, thin / shortest side)`` of the plane
    (a margin for the rounding of both tests) are measured against the sides.
    The pairs are taken a block of triangles at a time, the triangles' plane
    repeated for their pairs (a copy in order, faster than a gather)."""
    coordinates = [np.ascontiguousarray(axis) for axis in pts.T]
    corners = [[axis[tri[:, j]] for axis in coordinates] for j in range(3)]
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = corners
    ux, uy, uz, vx, vy, vz = bx - ax, by - ay, bz - az, cx - ax, cy - ay, cz - az
    nx, ny, nz = uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx
    length = np.sqrt(nx * nx + ny * ny + nz * nz)
    nx, ny, nz = nx / length, ny / length, nz / length
    plane = [nx, ny, nz, nx * ax + ny * ay + nz * az]
    # per side its start, direction, length^2
    sides = []
    for j in range(3):
        (sx, sy, sz), (ex, ey, ez) = corners[j], corners[(j + 1) % 3]
        dx, dy, dz = ex - sx, ey - sy, ez - sz
        sides.append([sx, sy, sz, dx, dy, dz, dx * dx + dy * dy + dz * dz])
    shortest = np.sqrt(np.minimum(np.minimum(sides[0][6], sides[1][6]), sides[2][6]))
    with np.errstate(divide="ignore"):
        reach = -4.0 * np.maximum(eps, thin / shortest)
    ends = np.cumsum(count)
    failed = np.zeros(len(tri), bool)
    step = max(_BLOCK * len(tri) // max(len(p), 1), 1)  # triangles a block
    own = [np.ascontiguousarray(corner) for corner in tri.T]
    for first in range(0, len(tri), step):
        last = min(first + step, len(tri))
        repeats = count[first:last]
        bp = p[ends[first] - count[first] : ends[last - 1]]
        bx_, by_, bz_ = (axis[bp] for axis in coordinates)
        m = [np.repeat(column[first:last], repeats) for column in (*plane, reach)]
        height = bx_ * m[0] + by_ * m[1] + bz_ * m[2] - m[3]
        near = np.flatnonzero(height >= m[4])
        bt = np.repeat(np.arange(first, last), repeats)[near]
        bp, height = bp[near], height[near]
        others = (bp != own[0][bt]) & (bp != own[1][bt]) & (bp != own[2][bt])
        bt, bp, height = bt[others], bp[others], height[others]
        x, y, z = (axis[bp] for axis in coordinates)
        bad = height >= -eps
        for side in sides:
            sx, sy, sz, dx, dy, dz, length2 = (column[bt] for column in side)
            wx, wy, wz = x - sx, y - sy, z - sz
            along = wx * dx + wy * dy + wz * dz
            bad |= length2 * (wx * wx + wy * wy + wz * wz) - along * along <= thin * thin
        failed[bt[bad]] = True
    return ~failed


def _box_points(pts: np.ndarray, points: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                margin: float) -> tuple[np.ndarray, np.ndarray]:
    """``(t, p)`` pairs: each of ``points`` in the box ``lo[t]``, ``hi[t]`` grown by
    ``margin``, found through a uniform grid of about one of them a cell."""
    low = pts.min(axis=0)
    size = float(np.ptp(pts, axis=0).max()) / max(round(len(points) ** (1 / 3)), 1)
    cells = np.maximum(np.ceil(np.ptp(pts, axis=0) / size).astype(np.int64), 1)
    cell = np.minimum(((pts[points] - low) / size).astype(np.int64), cells - 1)
    flat = (cell[:, 0] * cells[1] + cell[:, 1]) * cells[2] + cell[:, 2]
    by_cell = np.argsort(flat, kind="stable")
    bounds = np.searchsorted(flat[by_cell], np.arange(int(np.prod(cells)) + 1))
    c0 = np.clip(((lo - margin - low) / size).astype(np.int64), 0, cells - 1)
    c1 = np.clip(((hi + margin - low) / size).astype(np.int64), 0, cells - 1)
    span = c1 - c0 + 1
    per = span.prod(axis=1)
    t = np.repeat(np.arange(len(lo)), per)
    k = np.arange(int(per.sum())) - np.repeat(np.cumsum(per) - per, per)
    sy, sz = span[t, 1], span[t, 2]
    box = ((c0[t, 0] + k // (sy * sz)) * cells[1] + c0[t, 1] + (k // sz) % sy) * cells[2] \
        + c0[t, 2] + k % sz
    count = bounds[box + 1] - bounds[box]
    rows = np.repeat(np.arange(len(box)), count)
    offsets = np.cumsum(count) - count
    p = points[by_cell[bounds[box][rows] + np.arange(int(count.sum())) - offsets[rows]]]
    return t[rows], p
