"""The GL-free bridge from a DLFL mesh to flat numpy arrays.

:func:`mesh_arrays` lays the live mesh out densely: vertices, faces and edges in
id order, corners face after face in ring order from each face's head. Every
bulk operation (subdivision, export, rendering, picking, analysis) reads this
one layout. Dense indices are positions in these arrays; the ``*_ids`` arrays
map them back to element ids.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, fields

import numpy as np

from ._table import Table
from .errors import InvalidArgumentError
from .mesh import Mesh
from .soup import offsets_of


@dataclass(frozen=True)
class MeshArrays:
    """A dense, read-only snapshot of a mesh's topology and geometry.

    Every array given is marked read-only on construction (a snapshot is shared
    between threads and must not change behind their backs), so give it arrays
    nothing else writes to; :func:`mesh_arrays` makes fresh copies, so later
    changes to the mesh do not show. ``np.array(arrays.positions)`` gives a
    writable copy.

    Attributes:
        positions: ``(V, 3)`` float64 vertex positions.
        vertex_ids: ``(V,)`` int64 id of each vertex.
        face_ids: ``(F,)`` int64 id of each face (holes included).
        face_offsets: ``(F + 1,)`` int64; face ``i`` owns corners
            ``face_offsets[i]:face_offsets[i + 1]``, in ring order from its head.
        face_hole: ``(F,)`` bool, True for hole faces.
        corner_ids: ``(C,)`` int64 id of each corner.
        corner_vertex: ``(C,)`` int64 dense vertex index of each corner.
        corner_face: ``(C,)`` int64 dense face index of each corner.
        corner_edge: ``(C,)`` int64 dense index of the edge to the next corner, -1
            for a point-sphere.
        corner_mate: ``(C,)`` int64 dense index of the corner on the other side of
            that edge, -1 for a point-sphere.
        edge_ids: ``(E,)`` int64 id of each edge.
        edge_corners: ``(E, 2)`` int64 dense indices of each edge's sides (c0, c1).
        face_colors: ``(F, 3)`` float32 colour of each face in ``[0, 1]``, a row
            of NaN for a face without one; None when no face has a colour.
    """

    positions: np.ndarray
    vertex_ids: np.ndarray
    face_ids: np.ndarray
    face_offsets: np.ndarray
    face_hole: np.ndarray
    corner_ids: np.ndarray
    corner_vertex: np.ndarray
    corner_face: np.ndarray
    corner_edge: np.ndarray
    corner_mate: np.ndarray
    edge_ids: np.ndarray
    edge_corners: np.ndarray
    face_colors: np.ndarray | None = None

    def __post_init__(self) -> None:
        for field in fields(self):
            value = getattr(self, field.name)
            if value is not None:
                value.flags.writeable = False

    def colors_at(self, faces: np.ndarray) -> np.ndarray | None:
        """``(k, 3)`` float32 colours of the dense ``(k,)`` ``faces`` (-1: no face,
        no colour: NaN), for the faces a bulk operation makes from them; None
        when this mesh has no colours."""
        return None if self.face_colors is None else colors_at(self.face_colors, faces)

    @property
    def face_sizes(self) -> np.ndarray:
        """``(F,)`` int64 number of corners of each face."""
        return np.diff(self.face_offsets)

    @property
    def face_is_surface(self) -> np.ndarray:
        """``(F,)`` bool: faces of the surface, neither holes nor point-spheres.

        These are the faces exporters write and renderers draw.
        """
        sizes = self.face_sizes
        point_sphere = (sizes == 1) & (self.corner_edge[self.face_offsets[:-1]] < 0)
        return ~self.face_hole & ~point_sphere

    def surface_polygons(self) -> tuple[np.ndarray, np.ndarray]:
        """The polygons a file writes (see :attr:`face_is_surface`).

        Returns:
            ``(sizes, vertices)``: ``(S,)`` int64 corner count of each surface
            face and ``(sum of sizes,)`` dense vertex index of their corners,
            face after face from each head corner.
        """
        sizes, written = self.face_sizes, self.face_is_surface
        return sizes[written], self.corner_vertex[np.repeat(written, sizes)]

    def fan_triangles(self) -> tuple[np.ndarray, np.ndarray]:
        """Every face that is not a hole, triangulated as a fan from its head corner.

        A face of ``n >= 3`` corners gives ``n - 2`` triangles ``(head, head + k + 1,
        head + k + 2)`` for ``k = 0 .. n - 3``, in face order; holes, 2-gons and
        point-spheres give none. The renderer, picking and the STL writer all draw
        these same triangles.

        Returns:
            ``(corners, faces)``: ``(T, 3)`` int64 dense corner indices of each
            triangle and ``(T,)`` int64 dense index of its face. Its side from
            corner 0 to corner 1 is an edge of the face when ``corners[:, 1] ==
            corners[:, 0] + 1`` (the first triangle), from corner 2 to corner 0
            when ``corners[:, 2]`` is the face's last corner (the last one).
        """
        sizes = self.face_sizes
        count = np.where(self.face_hole, 0, np.maximum(sizes - 2, 0))
        faces = np.repeat(np.arange(len(sizes), dtype=np.int64), count)
        heads = self.face_offsets[:-1]
        # triangle t of a face whose first triangle is number s has corner
        # head + (t - s) + 1 second: one gather per triangle instead of two
        second = np.arange(len(faces), dtype=np.int64)
        second += (heads + 1 - (np.cumsum(count) - count))[faces]
        corners = np.empty((len(faces), 3), dtype=np.int64)
        corners[:, 0] = heads[faces]
        corners[:, 1] = second
        corners[:, 2] = second + 1
        return corners, faces

    def triangles(self) -> tuple[np.ndarray, np.ndarray]:
        """The triangles of :meth:`fan_triangles` by vertex, for other mesh libraries.

        Returns:
            ``(vertices, faces)``: ``(T, 3)`` int64 dense vertex indices of each
            triangle (rows of :attr:`positions`; counter-clockwise seen from outside)
            and ``(T,)`` int64 dense index of the face it came from
            (``face_ids[faces]`` are the faces' ids).
        """
        corners, faces = self.fan_triangles()
        return self.corner_vertex[corners], faces

    @property
    def corner_next(self) -> np.ndarray:
        """``(C,)`` int64 dense index of the next corner in the same face."""
        nxt = np.arange(1, len(self.corner_vertex) + 1, dtype=np.int64)
        nxt[self.face_offsets[1:] - 1] = self.face_offsets[:-1]
        return nxt

    @property
    def corner_prev(self) -> np.ndarray:
        """``(C,)`` int64 dense index of the previous corner in the same face."""
        prv = np.arange(-1, len(self.corner_vertex) - 1, dtype=np.int64)
        prv[self.face_offsets[:-1]] = self.face_offsets[1:] - 1
        return prv

    @property
    def edge_vertices(self) -> np.ndarray:
        """``(E, 2)`` int64 dense vertex indices of each edge's ends."""
        return self.corner_vertex[self.edge_corners]

    @property
    def corner_vnext(self) -> np.ndarray:
        """``(C,)`` int64: the next corner around the same vertex (TopMod's vnext)."""
        out = np.arange(len(self.corner_vertex), dtype=np.int64)
        has = self.corner_mate >= 0
        out[has] = self.corner_next[self.corner_mate[has]]
        return out

    @property
    def counts(self) -> tuple[int, int, int]:
        """``(V, E, F)``."""
        return len(self.vertex_ids), len(self.edge_ids), len(self.face_ids)


def colors_at(colors: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """``(k, 3)`` float32 rows of the ``(F, 3)`` ``colors`` at the ``(k,)`` int
    ``faces``, NaN where a face is negative (none)."""
    faces = np.asarray(faces)
    has = faces >= 0
    if has.all():
        return np.take(colors, faces, axis=0)
    picked = np.take(colors, np.where(has, faces, 0), axis=0)
    picked[~has] = np.nan
    return picked


def mesh_arrays(mesh: Mesh) -> MeshArrays:
    """Lay ``mesh`` out as a :class:`MeshArrays` (vectorized, O(C log max face size)).

    A freshly built mesh (tables without free slots or moved ids, corners laid
    out face by face: the result of every bulk operation) is copied slice by
    slice, without index arrays.
    """
    C, E, F, V = mesh._c, mesh._e, mesh._f, mesh._v
    vslots, eslots, fslots = _slots(V), _slots(E), _slots(F)
    order, offsets = _ring_order(mesh, fslots)
    num_c = int(offsets[-1])
    cdense = None if order is None else _dense_map(order, C.n)
    edge_corners = np.empty((E.count, 2), dtype=np.int64)
    edge_corners[:, 0] = _remap(_at(E.arrays["c0"], eslots, E.count), cdense)
    edge_corners[:, 1] = _remap(_at(E.arrays["c1"], eslots, E.count), cdense)
    return MeshArrays(
        positions=_rows(V.arrays["position"], vslots, V.count),
        vertex_ids=_rows(V.ids, vslots, V.count),
        face_ids=_rows(F.ids, fslots, F.count),
        face_offsets=offsets,
        face_hole=_rows(F.arrays["hole"], fslots, F.count, bool),
        corner_ids=_rows(C.ids, order, num_c),
        corner_vertex=_remap(_at(C.arrays["vertex"], order, num_c), _dense(V, vslots)),
        corner_face=np.repeat(np.arange(F.count, dtype=np.int64), np.diff(offsets)),
        corner_edge=_remap(_at(C.arrays["edge"], order, num_c), _dense(E, eslots)),
        corner_mate=_mates(edge_corners, num_c),
        edge_ids=_rows(E.ids, eslots, E.count),
        edge_corners=edge_corners,
        face_colors=mesh.face_colors(),
    )


def concatenate_arrays(parts: Sequence[MeshArrays]) -> MeshArrays:
    """Several snapshots as one, for drawing several objects at once.

    Dense indices (``corner_vertex``, ``corner_face``, ``corner_edge``,
    ``corner_mate``, ``edge_corners``, ``face_offsets``) are shifted so that each
    part refers to its own elements; ``-1`` entries stay ``-1``. Ids are copied
    as they are, so different parts may share ids: the result is for drawing,
    not for naming elements.

    Args:
        parts: one or more snapshots (see :func:`mesh_arrays`).

    Raises:
        InvalidArgumentError: ``parts`` is empty.
    """
    if not parts:
        raise InvalidArgumentError("concatenate_arrays needs at least one MeshArrays")
    sizes = np.array([(len(p.positions), len(p.face_ids), len(p.corner_ids), len(p.edge_ids))
                      for p in parts], dtype=np.int64)
    v0, f0, c0, e0 = (np.concatenate([[0], np.cumsum(sizes[:, k])[:-1]]) for k in range(4))

    def joined(name: str, shift: np.ndarray | None = None) -> np.ndarray:
        arrays = [getattr(p, name) for p in parts]
        if shift is not None:
            arrays = [np.where(a >= 0, a + k, a) for a, k in zip(arrays, shift, strict=True)]
        return np.concatenate(arrays)

    offsets = np.concatenate([[0]] + [p.face_offsets[1:] + k for p, k in zip(parts, c0,
                                                                           strict=True)])
    return MeshArrays(
        positions=joined("positions"), vertex_ids=joined("vertex_ids"),
        face_ids=joined("face_ids"), face_offsets=offsets.astype(np.int64),
        face_hole=joined("face_hole"), corner_ids=joined("corner_ids"),
        corner_vertex=joined("corner_vertex", v0), corner_face=joined("corner_face", f0),
        corner_edge=joined("corner_edge", e0), corner_mate=joined("corner_mate", c0),
        edge_ids=joined("edge_ids"), edge_corners=joined("edge_corners", c0),
        face_colors=_joined_colors(parts))


def _joined_colors(parts: Sequence[MeshArrays]) -> np.ndarray | None:
    """The parts' face colours one after the other (NaN rows for a part without
    any), or None when no part has any."""
    if all(p.face_colors is None for p in parts):
        return None
    return np.concatenate([
        np.full((len(p.face_ids), 3), np.nan, np.float32) if p.face_colors is None
        else p.face_colors for p in parts])


def _slots(table: Table) -> np.ndarray | None:
    """The live slots of ``table`` in id order, or None when they are ``0..n-1``
    (no free slot and no moved id: a freshly built table)."""
    if not table.free and not table.moved:
        return None
    return table.live_slots()


def _at(array: np.ndarray, slots: np.ndarray | None, count: int) -> np.ndarray:
    """``array``'s rows at ``slots``: a view of the first ``count`` rows for None."""
    if slots is None:
        return array[:count]
    return np.take(array, slots, axis=0)  # several times faster than array[slots] on 2-D


def _rows(array: np.ndarray, slots: np.ndarray | None, count: int,
          dtype: type | None = None) -> np.ndarray:
    """:func:`_at` as a fresh array (never a view of the table), of ``dtype``."""
    return _at(array, slots, count).astype(dtype or array.dtype, copy=slots is None)


def _dense(table: Table, slots: np.ndarray | None) -> np.ndarray | None:
    """:func:`_dense_map` of ``slots``, None for the identity."""
    return None if slots is None else _dense_map(slots, table.n)


def _remap(slots: np.ndarray, dense: np.ndarray | None) -> np.ndarray:
    """``(k,)`` int64 dense indices of ``slots`` (``dense`` None: the identity);
    slot -1 (no element) stays -1."""
    if dense is None:
        return slots.astype(np.int64)
    return dense[slots]


def _dense_map(slots: np.ndarray, n: int) -> np.ndarray:
    """``(n + 1,)`` int64: the dense index of each slot, -1 for slots not listed.

    The extra last entry is -1, so that slot -1 (no element) maps to -1.
    """
    dense = np.full(n + 1, -1, dtype=np.int64)
    dense[slots] = np.arange(len(slots), dtype=np.int64)
    return dense


def _mates(edge_corners: np.ndarray, num_c: int) -> np.ndarray:
    """``(C,)`` int64 the corner across each corner's edge, -1 for none."""
    mate = np.full(num_c, -1, dtype=np.int64)
    c0, c1 = edge_corners[:, 0], edge_corners[:, 1]
    mate[c0] = c1
    mate[c1] = c0
    return mate


def _ring_order(mesh: Mesh, fslots: np.ndarray | None) -> tuple[np.ndarray | None, np.ndarray]:
    """Corner slots face after face in ring order, and the ``(F + 1,)`` face offsets.

    The order is None when slots ``0..n-1`` already are in ring order (a freshly
    built mesh); ``fslots`` None stands for faces in slots ``0..n-1``.
    """
    C, F = mesh._c, mesh._f
    heads = _at(F.arrays["corner"], fslots, F.count)
    if not C.free and not C.moved:
        # laid out face by face, the faces start at their heads
        offsets = np.append(heads, C.n).astype(np.int64)
        if _in_ring_order(C.arrays["next"][: C.n], offsets):
            return None, offsets
    cslots = C.live_slots()
    face_of = _remap(C.arrays["face"][cslots], _dense(F, fslots))
    sizes = np.bincount(face_of, minlength=F.count)
    offsets = offsets_of(sizes)
    rank = _rank_from_head(mesh, cslots, heads, face_of, sizes)
    order = np.empty(len(cslots), dtype=np.int64)
    order[offsets[face_of] + rank] = cslots
    return order, offsets


def _in_ring_order(nxt: np.ndarray, offsets: np.ndarray) -> bool:
    """True when ``offsets`` cut slots ``0..n-1`` into blocks of at least one
    corner, each one face ring in slot order (``nxt``: the ``(n,)`` next links)."""
    if offsets[0] != 0 or (len(offsets) > 1 and np.diff(offsets).min() < 1):
        return False
    expected = np.arange(1, len(nxt) + 1, dtype=nxt.dtype)
    expected[offsets[1:] - 1] = offsets[:-1]
    return bool(np.array_equal(nxt, expected))


def _rank_from_head(
    mesh: Mesh, cslots: np.ndarray, heads: np.ndarray, face_of: np.ndarray,
    sizes: np.ndarray,
) -> np.ndarray:
    """``(C,)`` position of each corner in its face ring, the head at 0.

    List ranking by pointer doubling: each corner learns its distance to the last
    corner of its ring (the one before the head), in O(log max face size) passes.
    ``heads`` are the head corner slots of the faces.
    """
    ca = mesh._c.arrays
    dense = _dense_map(cslots, mesh._c.n)
    succ = dense[ca["next"][cslots]]
    is_head = np.zeros(len(cslots), dtype=bool)
    is_head[dense[heads]] = True
    last = is_head[succ]
    succ = np.where(last, np.arange(len(cslots), dtype=np.int64), succ)
    dist = (~last).astype(np.int64)
    while True:
        dist += dist[succ]
        jumped = succ[succ]
        if np.array_equal(jumped, succ):
            return sizes[face_of] - 1 - dist
        succ = jumped
