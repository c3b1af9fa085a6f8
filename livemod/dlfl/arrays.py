"""The GL-free bridge from a DLFL mesh to flat numpy arrays.

:func:`mesh_arrays` lays the live mesh out densely: vertices, faces and edges in
id order, corners face after face in ring order from each face's head. Every
bulk operation (subdivision, export, rendering, picking, analysis) reads this
one layout. Dense indices are positions in these arrays; the ``*_ids`` arrays
map them back to element ids.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._table import Table
from .mesh import Mesh


@dataclass(frozen=True)
class MeshArrays:
    """A dense, read-only snapshot of a mesh's topology and geometry.

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


def mesh_arrays(mesh: Mesh) -> MeshArrays:
    """Lay ``mesh`` out as a :class:`MeshArrays` (vectorized, O(C log max face size))."""
    C, E, F, V = mesh._c, mesh._e, mesh._f, mesh._v
    vslots, eslots, fslots, cslots = (
        V.live_slots(), E.live_slots(), F.live_slots(), C.live_slots(),
    )
    ca, ea = C.arrays, E.arrays
    fdense = _dense_map(fslots, F.n)
    order, offsets = _ring_order(mesh, cslots, fslots, fdense)
    in_slot_order = len(order) == C.n and not C.moved and order is cslots
    cdense = None if in_slot_order else _dense_map(order, C.n)
    edge_slot = ca["edge"][order]
    has = edge_slot >= 0
    corner_edge = _remap(edge_slot, _dense_or_none(E, eslots))
    corner_edge[~has] = -1
    edge_corners = np.empty((len(eslots), 2), dtype=np.int64)
    edge_corners[:, 0] = _remap(ea["c0"][eslots], cdense)
    edge_corners[:, 1] = _remap(ea["c1"][eslots], cdense)
    mate = np.full(len(order), -1, dtype=np.int64)
    mate[edge_corners[:, 0]] = edge_corners[:, 1]
    mate[edge_corners[:, 1]] = edge_corners[:, 0]
    return MeshArrays(
        positions=V.arrays["position"][vslots],
        vertex_ids=V.ids[vslots],
        face_ids=F.ids[fslots],
        face_offsets=offsets,
        face_hole=F.arrays["hole"][fslots].astype(bool),
        corner_ids=C.ids[order],
        corner_vertex=_remap(ca["vertex"][order], _dense_or_none(V, vslots)),
        corner_face=np.repeat(np.arange(len(fslots), dtype=np.int64), np.diff(offsets)),
        corner_edge=corner_edge,
        corner_mate=mate,
        edge_ids=E.ids[eslots],
        edge_corners=edge_corners,
    )


def _dense_or_none(table: Table, slots: np.ndarray) -> np.ndarray | None:
    """:func:`_dense_map` of ``slots``, or None when every slot ``0..n-1`` is live
    in id order (a freshly built table), where the map is the identity."""
    if len(slots) == table.n and not table.moved:
        return None
    return _dense_map(slots, table.n)


def _remap(slots: np.ndarray, dense: np.ndarray | None) -> np.ndarray:
    """``(k,)`` int64 dense indices of ``slots`` (``dense`` None: the identity)."""
    if dense is None:
        return slots.astype(np.int64)
    return dense[slots]


def _dense_map(slots: np.ndarray, n: int) -> np.ndarray:
    """``(n,)`` int64: the dense index of each slot, -1 for slots not listed."""
    dense = np.full(max(n, 1), -1, dtype=np.int64)
    dense[slots] = np.arange(len(slots), dtype=np.int64)
    return dense


def _ring_order(
    mesh: Mesh, cslots: np.ndarray, fslots: np.ndarray, fdense: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Corner slots face after face in ring order, and the face offsets."""
    ca = mesh._c.arrays
    face_of = fdense[ca["face"][cslots]]
    sizes = np.bincount(face_of, minlength=len(fslots)).astype(np.int64)
    offsets = np.zeros(len(fslots) + 1, dtype=np.int64)
    np.cumsum(sizes, out=offsets[1:])
    if _already_in_ring_order(mesh, cslots, offsets, fslots):
        return cslots, offsets
    rank = _rank_from_head(mesh, cslots, fslots, face_of, sizes)
    order = np.empty(len(cslots), dtype=np.int64)
    order[offsets[face_of] + rank] = cslots
    return order, offsets


def _already_in_ring_order(
    mesh: Mesh, cslots: np.ndarray, offsets: np.ndarray, fslots: np.ndarray
) -> bool:
    """Cheap test for a freshly built mesh, whose slots are laid out face by face."""
    ca = mesh._c.arrays
    n = len(cslots)
    # without moved ids and free slots, id order is slot order: cslots == 0..n-1
    if n == 0 or n != mesh._c.n or mesh._c.moved:
        return False
    heads = mesh._f.arrays["corner"][fslots]
    if not np.array_equal(heads, offsets[:-1]):
        return False
    expected = np.arange(1, n + 1, dtype=np.int64)
    expected[offsets[1:] - 1] = offsets[:-1]
    return bool(np.array_equal(ca["next"][:n], expected))


def _rank_from_head(
    mesh: Mesh, cslots: np.ndarray, fslots: np.ndarray, face_of: np.ndarray,
    sizes: np.ndarray,
) -> np.ndarray:
    """``(C,)`` position of each corner in its face ring, the head at 0.

    List ranking by pointer doubling: each corner learns its distance to the last
    corner of its ring (the one before the head), in O(log max face size) passes.
    """
    ca = mesh._c.arrays
    dense = _dense_map(cslots, mesh._c.n)
    succ = dense[ca["next"][cslots]]
    is_head = np.zeros(len(cslots), dtype=bool)
    is_head[dense[mesh._f.arrays["corner"][fslots]]] = True
    last = is_head[succ]
    succ = np.where(last, np.arange(len(cslots), dtype=np.int64), succ)
    dist = (~last).astype(np.int64)
    while True:
        dist += dist[succ]
        jumped = succ[succ]
        if np.array_equal(jumped, succ):
            return sizes[face_of] - 1 - dist
        succ = jumped
