"""Shared machinery of the vectorized remeshing schemes.

Every scheme follows one pattern:

1. :func:`read_topology` lays the mesh out as dense arrays (point-spheres set
   aside: they survive every scheme unchanged);
2. the scheme computes the new positions with numpy and describes the new faces as
   blocks of corners, each corner carrying the dense index of its new vertex and
   the *label* of its outgoing edge: the two sides of one new edge carry the same
   label, every label exactly twice;
3. :func:`build` pairs the sides by label (O(C), no sort), appends the
   point-spheres, builds the mesh in one step with ``from_corner_arrays`` and
   swaps it in. Ids are never reused: every element of the result gets a fresh id.

Each new face records its *origin*: the input face it is made inside (a child
of that face, its inset, its shrunk copy), or :data:`NO_ORIGIN` for a face made
around an old vertex or edge, which has no single source. The build gives every
face its origin's hole flag and colour (:class:`FaceSource`), so one rule carries
both through every scheme, and through every step of a composite.

A scheme checks the face budget (:mod:`livemod.dlfl.budget`) from the mesh's
counts before it allocates (:func:`budgeted_topology`).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np

from .._checks import finite_number
from .._graph import cycle_layout, walk_rings
from .._vectors import group_sum
from ..arrays import colors_at, mesh_arrays
from ..budget import check_size, fits
from ..build import from_corner_arrays
from ..errors import InvalidArgumentError
from ..mesh import Mesh
from ..normals import ring_normals
from ..soup import offsets_of

# the origin of a face made around an old vertex or edge: no hole, no colour
NO_ORIGIN = -1


def no_origin(count: int) -> np.ndarray:
    """``(count,)`` :data:`NO_ORIGIN`: faces without a source face (int8: joined to
    origins, numpy widens it no further than they need)."""
    return np.full(count, NO_ORIGIN, dtype=np.int8)


class FaceSource(NamedTuple):
    """What a new face takes from its origin, an input face of the scheme.

    Attributes:
        hole: ``(R,)`` bool hole flags of the input faces.
        colors: ``(R, 3)`` float32 colours (NaN rows: none), or None.
    """

    hole: np.ndarray
    colors: np.ndarray | None

    @property
    def tracked(self) -> bool:
        """Whether a face's origin matters: some input face is a hole or has a
        colour. Untracked, the origins are all 0 (:func:`read_topology`'s uint8
        placeholder, as cheap to carry as the hole flags it replaced)."""
        return self.colors is not None or bool(self.hole.any())

    def of(self, origin: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
        """The ``(F,)`` hole flags and ``(F, 3)`` colours (or None) of faces whose
        ``(F,)`` int origins are ``origin`` (:data:`NO_ORIGIN`: no hole, no colour)."""
        if not self.tracked:
            return np.zeros(len(origin), dtype=bool), None
        has = origin >= 0
        # most schemes make every face inside an old one: no mask to apply
        hole = self.hole[origin] if has.all() else self.hole[np.where(has, origin, 0)] & has
        return hole, None if self.colors is None else colors_at(self.colors, origin)


# ``size(counts)``: a scheme's result ``(faces, corners)`` from the counts of its
# input without point-spheres (``nv``, ``ne``, ``nf``, ``nc`` of a Counts or a
# Topology), point-spheres left out too
Size = Callable[[Any], tuple[int, int]]


class Counts(NamedTuple):
    """The element counts of a mesh without its ``ns`` point-spheres."""

    nv: int
    ne: int
    nf: int
    nc: int
    ns: int = 0

    def dual(self) -> Counts:
        """The counts of the dual (faces and vertices swap)."""
        return Counts(self.nf, self.ne, self.nv, self.nc, self.ns)

    def after(self, size: tuple[int, int]) -> Counts:
        """The counts of a result of ``size`` ``(faces, corners)`` with the same
        Euler characteristic (every scheme of a composite keeps it)."""
        faces, corners = size
        edges = corners // 2
        return Counts(self.nv - self.ne + self.nf + edges - faces, edges, faces, corners, self.ns)


def counts_of(mesh: Mesh) -> Counts:
    """The :class:`Counts` of ``mesh`` in O(1): every corner but a point-sphere's
    is one of the two sides of an edge, so there are ``C - 2E`` point-spheres."""
    if isinstance(mesh, Pending):
        t = mesh.topology
        return Counts(t.nv, t.ne, t.nf, t.nc, t.ns)
    v, e, f = mesh.counts()
    spheres = mesh.num_corners - 2 * e
    return Counts(v - spheres, e, f - spheres, 2 * e, spheres)


class Topology:
    """Dense arrays of a mesh without its point-spheres.

    Given (``C`` corners, ``F`` faces, ``E`` edges, ``V`` vertices, all dense):
        pos: ``(V, 3)`` positions. cv: ``(C,)`` vertex of each corner.
        mate: ``(C,)`` the corner on the other side of the corner's edge (at the
            other end). offsets: ``(F + 1,)`` face starts (corners are laid out
            face after face). origin: ``(F,)`` int32 the input face each face
            comes from, :data:`NO_ORIGIN` for none (see the module docstring).
        spheres: ``(S, 3)`` positions of the point-spheres set aside.
        sphere_colors: ``(S, 3)`` float32 colours of their faces (NaN rows:
            none), or None when no face of the input has a colour.
        face_ids: ``(F,)`` id of each (kept) face.
        source: the hole flags and colours of the input faces ``origin`` names.

    Derived on first use and kept (a step reads only what it needs; the middle
    steps of a composite never need some of them): ``nxt``, ``prv`` ``(C,)``
    corner links; ``face``, ``edge`` ``(C,)`` face and edge of each corner;
    ``edge_corners`` ``(E, 2)`` the two sides of each edge (given by
    :func:`read_topology`, else numbered by their lower corner).
    """

    def __init__(self, pos: np.ndarray, cv: np.ndarray, mate: np.ndarray, offsets: np.ndarray,
                 origin: np.ndarray, spheres: np.ndarray, face_ids: np.ndarray,
                 source: FaceSource, edge_corners: np.ndarray | None = None,
                 sphere_colors: np.ndarray | None = None) -> None:
        self.pos, self.cv, self.mate, self.offsets = pos, cv, mate, offsets
        self.origin, self.spheres, self.face_ids = origin, spheres, face_ids
        self.sphere_colors = sphere_colors
        self.source = source
        if edge_corners is not None:
            self.__dict__["edge_corners"] = edge_corners
        self._cache: dict[str, np.ndarray] = {}

    @property
    def nv(self) -> int:
        return len(self.pos)

    @property
    def nc(self) -> int:
        return len(self.cv)

    @property
    def ns(self) -> int:
        return len(self.spheres)

    @property
    def nf(self) -> int:
        return len(self.offsets) - 1

    @property
    def ne(self) -> int:
        return len(self.edge_corners)

    @functools.cached_property
    def sizes(self) -> np.ndarray:
        """``(F,)`` face sizes."""
        return np.diff(self.offsets)

    @functools.cached_property
    def nxt(self) -> np.ndarray:
        """``(C,)`` the next corner of the same face."""
        nxt = np.arange(1, self.nc + 1, dtype=np.int64)
        nxt[self.offsets[1:] - 1] = self.offsets[:-1]
        return nxt

    @functools.cached_property
    def prv(self) -> np.ndarray:
        """``(C,)`` the previous corner of the same face."""
        prv = np.arange(-1, self.nc - 1, dtype=np.int64)
        prv[self.offsets[:-1]] = self.offsets[1:] - 1
        return prv

    @functools.cached_property
    def face(self) -> np.ndarray:
        """``(C,)`` face of each corner."""
        return np.repeat(np.arange(self.nf, dtype=np.int64), self.sizes)

    @functools.cached_property
    def edge_corners(self) -> np.ndarray:
        """``(E, 2)`` the two sides of each edge, edges in order of their lower side."""
        lower = np.flatnonzero(self.mate > np.arange(self.nc))
        return np.stack([lower, self.mate[lower]], axis=1)

    @functools.cached_property
    def edge(self) -> np.ndarray:
        """``(C,)`` edge of each corner (the edge to the next corner)."""
        edge = np.empty(self.nc, dtype=np.int64)
        numbers = np.arange(self.ne, dtype=np.int64)
        edge[self.edge_corners[:, 0]] = numbers
        edge[self.edge_corners[:, 1]] = numbers
        return edge

    @functools.cached_property
    def valence(self) -> np.ndarray:
        """``(V,)`` number of corners (= edges, counting a self-loop twice) per vertex."""
        return np.bincount(self.cv, minlength=self.nv)

    @property
    def vprev(self) -> np.ndarray:
        """``(C,)`` the next corner around the same vertex, counter-clockwise seen
        from outside: ``mate(prev(c))`` (TopMod's vprev)."""
        return self.mate[self.prv]

    def centroids(self) -> np.ndarray:
        """``(F, 3)`` mean of each face's corner positions (TopMod's centroid)."""
        if "centroids" not in self._cache:
            sums = ring_sums(self.offsets, self.pos, self.cv)
            self._cache["centroids"] = sums / np.maximum(self.sizes, 1)[:, None]
        return self._cache["centroids"]

    def midpoints(self) -> np.ndarray:
        """``(E, 3)`` midpoint of each edge."""
        ends = self.cv[self.edge_corners]
        with np.errstate(over="ignore"):  # inf near the float maximum: build refuses it
            return 0.5 * (rows(self.pos, ends[:, 0]) + rows(self.pos, ends[:, 1]))

    def neighbour_mean(self) -> np.ndarray:
        """``(V, 3)`` mean position of each vertex's neighbours (one per corner)."""
        return vertex_mean(self, rows(self.pos, self.cv[self.nxt]))

    def face_normals(self) -> np.ndarray:
        """``(F, 3)`` TopMod's unit face normal of each face (zero when degenerate;
        :mod:`livemod.dlfl.normals`)."""
        if "normals" not in self._cache:
            self._cache["normals"] = ring_normals(self.pos, self.cv, self.offsets).face
        return self._cache["normals"]

    def vertex_rings(self) -> tuple[np.ndarray, np.ndarray]:
        """Corners grouped by vertex, counter-clockwise (``vprev`` order).

        Returns:
            ``(order, offsets)``: ``order`` ``(C,)`` lists the corners ring after
            ring; ring ``k`` is ``order[offsets[k]:offsets[k + 1]]``. Rings come in
            order of their smallest corner, each starting there. A vertex visited
            by one fan has one ring.
        """
        if "rings" not in self._cache:
            perm = self.vprev
            rings = walk_rings(perm, self.cv, self.valence)
            order, offsets = cycle_layout(perm) if rings is None else rings
            self._cache["rings"], self._cache["ring_offsets"] = order, offsets
        return self._cache["rings"], self._cache["ring_offsets"]


def rows(values: np.ndarray, index: np.ndarray) -> np.ndarray:
    """``values[index]`` for ``(N, k)`` ``values`` and an ``(M,)`` ``index``: ``(M, k)``.

    ``np.take`` along axis 0: three to four times faster than fancy indexing of rows.
    """
    return np.take(values, index, axis=0)


def vertex_sum(t: Topology, per_corner: np.ndarray) -> np.ndarray:
    """``(V, 3)`` sum of a ``(C, 3)`` per-corner quantity over each vertex's corners."""
    return group_sum(t.cv, per_corner, t.nv)


def vertex_mean(t: Topology, per_corner: np.ndarray) -> np.ndarray:
    """``(V, 3)`` mean of a ``(C, 3)`` per-corner quantity over each vertex's corners
    (zero at a vertex without corners)."""
    return vertex_sum(t, per_corner) / np.maximum(t.valence, 1)[:, None]


# above this many runs of equal ring size, ring_sums goes by bincount
MAX_RUNS = 32


def ring_sums(offsets: np.ndarray, values: np.ndarray,
              index: np.ndarray | None = None) -> np.ndarray:
    """``(R, 3)``: ``values[index]`` summed over each ring (bitwise as :func:`group_sum`).

    Args:
        offsets: ``(R + 1,)`` ring starts in ``index``; every ring non-empty.
        values: ``(N, 3)``. index: ``(offsets[-1],)`` rows of ``values``
            (None: ``values`` itself is laid out ring after ring).

    Scheme outputs come in blocks of equal ring size: each run of equal sizes is
    summed column by column in ring order, a few gathers and adds instead of
    bincount's per-element scatter.
    """
    sizes = np.diff(offsets)
    cuts = np.flatnonzero(sizes[1:] != sizes[:-1]) + 1
    if len(cuts) > MAX_RUNS:
        ring = np.repeat(np.arange(len(sizes), dtype=np.int64), sizes)
        return group_sum(ring, values if index is None else rows(values, index), len(sizes))
    bounds = [0, *cuts.tolist(), len(sizes)]
    out = np.empty((len(sizes), 3))
    # sums of points near the float maximum overflow: inf, which the scheme's
    # build refuses (bincount above sums without a warning)
    with np.errstate(over="ignore", invalid="ignore"):
        _add_runs(out, bounds, offsets, values, index)
    return out


def _add_runs(out: np.ndarray, bounds: list[int], offsets: np.ndarray, values: np.ndarray,
              index: np.ndarray | None) -> None:
    """Write into ``out`` ``(R, 3)`` the sums of :func:`ring_sums` (same arguments),
    one run of rings of equal size (``bounds[i]:bounds[i + 1]``) at a time."""
    for start, stop in zip(bounds[:-1], bounds[1:], strict=True):
        n = int(offsets[start + 1] - offsets[start]) if stop > start else 1
        block = slice(offsets[start], offsets[stop])
        if index is None:
            columns = values[block].reshape(-1, n, 3)
            out[start:stop] = columns[:, 0]
            for j in range(1, n):
                out[start:stop] += columns[:, j]
        else:
            block_index = index[block].reshape(-1, n)
            out[start:stop] = rows(values, block_index[:, 0])
            for j in range(1, n):
                out[start:stop] += rows(values, block_index[:, j])


class Pending(Mesh):
    """A stand-in mesh that holds a scheme's result as a :class:`Topology`.

    Chained schemes (the GUI composites) pass one of these between their steps:
    each step reads the previous step's arrays (:func:`read_topology`) and leaves
    its own (:func:`build_paired`), and only the last result is built into a real
    mesh.
    """

    def __init__(self, topology: Topology) -> None:  # no tables: never used as a mesh
        self.topology = topology


def read_topology(mesh: Mesh) -> Topology:
    """Lay ``mesh`` out for a scheme, setting its point-spheres aside."""
    if isinstance(mesh, Pending):
        return mesh.topology
    a = mesh_arrays(mesh)
    mate, offsets, cv = a.corner_mate, a.face_offsets, a.corner_vertex
    positions, hole, edge_corners = a.positions, a.face_hole, a.edge_corners
    spheres = np.zeros((0, 3))
    sphere_colors = None
    face_ids = a.face_ids
    source = FaceSource(hole, a.face_colors)
    # the usual mesh, of no hole and no colour, needs no origins: a 1-byte placeholder
    origin = (np.arange(len(hole), dtype=np.int32) if source.tracked
              else np.zeros(len(hole), dtype=np.uint8))
    sphere_corner = mate < 0
    if sphere_corner.any():
        keep_face = np.ones(len(hole), dtype=bool)
        keep_face[a.corner_face[sphere_corner]] = False
        keep_vertex = np.ones(len(positions), dtype=bool)
        keep_vertex[cv[sphere_corner]] = False
        spheres = positions[~keep_vertex]
        if a.face_colors is not None:
            face_of_vertex = np.zeros(len(positions), dtype=np.int64)
            face_of_vertex[cv[sphere_corner]] = a.corner_face[sphere_corner]
            sphere_colors = a.face_colors[face_of_vertex[~keep_vertex]]
        cmap = np.cumsum(~sphere_corner) - 1
        vmap = np.cumsum(keep_vertex) - 1
        sizes = np.diff(offsets)[keep_face]
        offsets = offsets_of(sizes)
        mate = cmap[mate[~sphere_corner]]
        cv = vmap[cv[~sphere_corner]]
        positions, origin = positions[keep_vertex], origin[keep_face]
        face_ids = face_ids[keep_face]
        edge_corners = cmap[edge_corners]
    return Topology(positions, cv, mate, offsets, origin, spheres, face_ids, source,
                    edge_corners, sphere_colors)


def topology_of(positions: np.ndarray, cv: np.ndarray, mate: np.ndarray, sizes: np.ndarray,
                origin: np.ndarray, t: Topology) -> Topology:
    """The :class:`Topology` of a scheme's output arrays (for repeated levels);
    ``origin`` names faces of ``t``'s input, whose point-spheres and source it keeps."""
    return Topology(positions, cv, mate, offsets_of(sizes), origin, t.spheres,
                    np.zeros(len(sizes), dtype=np.int64), t.source,
                    sphere_colors=t.sphere_colors)


def check_levels(levels: object) -> int:
    """``levels`` as a positive int.

    Raises:
        InvalidArgumentError: anything else.
    """
    if isinstance(levels, bool) or not isinstance(levels, int | np.integer) or levels < 1:
        raise InvalidArgumentError(f"option levels must be a positive integer, got {levels!r}")
    return int(levels)


def check_budget(t: Counts | Topology, faces: int, corners: int, scheme: str,
                 max_faces: object) -> None:
    """Refuse a result of ``faces`` faces and ``corners`` corners (point-spheres
    of ``t`` left out: they come through every scheme) over the face budget.

    Raises:
        BudgetExceededError: naming the count and the budget.
    """
    check_size(scheme, faces + t.ns, corners + t.ns, max_faces=max_faces)


def budgeted_topology(mesh: Mesh, scheme: str, max_faces: object, size: Size,
                      exact: Size | None = None) -> Topology:
    """:func:`read_topology`, once the face budget allows the result.

    ``size`` gives the result's ``(faces, corners)`` from the counts (exact, or
    an upper bound when ``exact`` gives them exactly from the topology): the
    budget is checked before anything is allocated, and read from the topology
    only when the bound passes it.

    Raises:
        BudgetExceededError: the result passes the budget.
    """
    counts = counts_of(mesh)
    bound = size(counts)
    if exact is None or fits(bound[0] + counts.ns, bound[1] + counts.ns, max_faces=max_faces):
        check_budget(counts, *bound, scheme, max_faces)
        return read_topology(mesh)
    t = read_topology(mesh)
    check_budget(t, *exact(t), scheme, max_faces)
    return t


class Faces:
    """New faces, accumulated block by block.

    A block is either ``k`` faces of ``m`` corners (``(k, m)`` arrays) or faces of
    varying size (flat arrays plus sizes). Each corner holds its new vertex and the
    label of its outgoing edge; each face its origin (see the module docstring).
    """

    def __init__(self) -> None:
        self.verts: list[np.ndarray] = []
        self.labels: list[np.ndarray] = []
        self.sizes: list[np.ndarray] = []
        self.origins: list[np.ndarray] = []

    def add(self, verts: np.ndarray, labels: np.ndarray, origin: np.ndarray | int,
            sizes: np.ndarray | None = None) -> None:
        """Add faces: ``(k, m)`` ``verts``/``labels`` or flat ones with ``sizes``;
        ``origin``: ``(k,)`` their origins, or one for all (:data:`NO_ORIGIN`)."""
        if sizes is None:
            k, m = verts.shape
            sizes = np.full(k, m, dtype=np.int64)
        self.verts.append(np.asarray(verts, dtype=np.int64).ravel())
        self.labels.append(np.asarray(labels, dtype=np.int64).ravel())
        self.sizes.append(np.asarray(sizes, dtype=np.int64))
        one = np.int8(origin) if isinstance(origin, int) else origin  # as no_origin's
        self.origins.append(np.broadcast_to(one, sizes.shape))


def pair_by_label(labels: np.ndarray, num_labels: int) -> np.ndarray:
    """``(C,)`` mate of each corner: the other corner carrying the same label.

    Precondition: every label in use occurs exactly twice.
    """
    # int32 halves the memory traffic of the scatters (corner counts stay < 2**31)
    idx = np.arange(len(labels), dtype=np.int32)
    labels = labels.astype(np.int32)
    first = np.full(num_labels, -1, dtype=np.int32)
    first[labels] = idx
    other = first[labels]
    loser = other != idx  # exactly one per label: the side that lost the write
    mate = np.empty(len(labels), dtype=np.int64)
    mate[idx[loser]] = other[loser]
    mate[other[loser]] = idx[loser]
    return mate


def build(mesh: Mesh, t: Topology, positions: np.ndarray, faces: Faces) -> None:
    """Pair the new faces' sides by label, then :func:`build_paired`."""
    cv = np.concatenate(faces.verts)
    labels = np.concatenate(faces.labels)
    num_labels = int(labels.max()) + 1 if len(labels) else 0
    mate = pair_by_label(labels, num_labels)
    build_paired(mesh, t, positions, cv, mate, np.concatenate(faces.sizes),
                 np.concatenate(faces.origins))


def build_paired(mesh: Mesh, t: Topology, positions: np.ndarray, cv: np.ndarray,
                 mate: np.ndarray, sizes: np.ndarray, origin: np.ndarray) -> None:
    """Append the point-spheres, build the new mesh in one step and swap it in.

    Args:
        cv, mate: ``(C',)`` new vertex and mate of every new corner, face by face.
        sizes, origin: ``(F',)`` size and origin of every new face; the face takes
            its origin's hole flag and colour (:class:`FaceSource`).
    """
    if isinstance(mesh, Pending):
        mesh.topology = topology_of(positions, cv, mate, sizes, origin, t)
        return
    hole, colors = t.source.of(origin)
    s = len(t.spheres)
    if s:
        base_v = len(positions)
        positions = np.concatenate([positions, t.spheres])
        cv = np.concatenate([cv, base_v + np.arange(s)])
        mate = np.concatenate([mate, np.full(s, -1, dtype=mate.dtype)])
        sizes = np.concatenate([sizes, np.ones(s, dtype=np.int64)])
        hole = np.concatenate([hole, np.zeros(s, dtype=bool)])
        if colors is not None:
            # the input had colours, so read_topology kept the spheres' too
            assert t.sphere_colors is not None
            colors = np.concatenate([colors, t.sphere_colors])
    new = from_corner_arrays(positions, offsets_of(sizes), cv, mate, hole, face_colors=colors,
                             first_ids=mesh.next_ids())
    mesh.replace_with(new)


def face_weighted(
    t: Topology, values: np.ndarray, weight: Callable[[int], np.ndarray]
) -> np.ndarray:
    """``(C, 3)``: per face of size n, ``out[c_i] = sum_j W[i, j] values[c_j]``.

    ``weight(n)`` gives the ``(n, n)`` matrix; faces are processed by size.
    """
    return ring_weighted(t.offsets, values, weight)


def ring_weighted(
    offsets: np.ndarray, values: np.ndarray, weight: Callable[[int], np.ndarray]
) -> np.ndarray:
    """:func:`face_weighted` over any ring layout given by ``offsets``."""
    sizes = np.diff(offsets)
    # weighted sums of points near the float maximum overflow: inf / NaN, which
    # the scheme's build refuses
    with np.errstate(over="ignore", invalid="ignore"):
        if len(sizes) and sizes[0] == sizes.min() == sizes.max():
            # one face size (all quads, all triangles): reshape instead of gathering
            n = int(sizes[0])
            return np.matmul(weight(n), values.reshape(-1, n, 3)).reshape(-1, 3)
        out = np.empty_like(values)
        for n in np.unique(sizes).tolist():
            rings = np.flatnonzero(sizes == n)
            corners = offsets[rings][:, None] + np.arange(n)  # (K, n)
            out[corners] = np.matmul(weight(n), values[corners])
    return out


def circulant(n: int, row: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
    """``(n, n)`` matrix ``W[i, j] = row((i - j) mod n)``."""
    k = (np.arange(n)[:, None] - np.arange(n)[None, :]) % n
    return row(k)


def cos_weights(n: int, alpha: float) -> np.ndarray:
    """The Doo-Sabin family's weights: ``w_ii = alpha``,
    ``w_ij = (1 - alpha)(3 + 2cos(2pi(i - j)/n)) / (3n - 5)``."""
    if n < 2:
        return np.ones((n, n))

    def row(k: np.ndarray) -> np.ndarray:
        w = (1 - alpha) * (3 + 2 * np.cos(2 * math.pi * k / n)) / (3 * n - 5)
        return np.where(k == 0, alpha, w)

    return circulant(n, row)


def check_number(name: str, value: object, low: float | None = None,
                 high: float | None = None) -> float:
    """``value`` as a finite float within ``[low, high]``.

    Raises:
        DLFLError: not a number, not finite, or out of range (naming the option).
    """
    number = finite_number(value, f"option {name}")
    if (low is not None and number < low) or (high is not None and number > high):
        raise InvalidArgumentError(f"option {name} must be in [{low}, {high}], got {value!r}")
    return number
