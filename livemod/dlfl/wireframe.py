"""Wireframe sculptures: modified corner cutting, the wireframe crust and columns.

TopMod's ``makeWireframe(t, split)``: ``modifiedCornerCuttingSubdivide(t)`` makes
an inner polygon per face whose corners sit ``t/2`` from both neighbouring edges
(the "front copies", typed FTHole), then ``createCrustForWireframe`` duplicates
the object reversed and places each copied vertex from the planes of the two
bevel quads beside it, and ``punchHoles`` opens every front copy into a tube.
The result is a solid wire of thickness ``t`` along every edge. livemod builds
each stage in one vectorized pass over corner arrays (see :mod:`.rind`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .analysis import face_centroids
from .arrays import MeshArrays, mesh_arrays
from .build import from_corner_arrays
from .errors import DLFLError
from .mesh import Mesh
from .rind import shell_arrays

__all__ = [
    "CornerCut", "corner_cut_arrays", "modified_corner_cut", "vertex_rings", "wireframe",
    "wireframe_inner_positions",
]


@dataclass(frozen=True)
class CornerCut:
    """The modified-corner-cut mesh as corner arrays.

    Attributes:
        positions: ``(C, 3)`` one new vertex per original corner, in corner order.
        offsets: ``(F + E + V + 1,)`` face offsets: the inner polygon of every
            original face (the front copies), then one quad per original edge,
            then one polygon per original vertex.
        corner_vertex: ``(4E + C + C,)`` int64 vertex of each corner.
        corner_mate: the other side of each corner's edge.
        face_hole: hole flags (an inner polygon keeps its face's flag).
        num_front: number of front copies: faces ``0..num_front-1``.
    """

    positions: np.ndarray
    offsets: np.ndarray
    corner_vertex: np.ndarray
    corner_mate: np.ndarray
    face_hole: np.ndarray
    num_front: int


def vertex_rings(a: MeshArrays) -> tuple[np.ndarray, np.ndarray]:
    """Corners around every vertex, each ring walked against ``vnext``.

    Returns:
        ``(order (C,), offsets (V + 1,))``: vertex ``v``'s corners are
        ``order[offsets[v]:offsets[v + 1]]``, each followed by its ``vprev``, so
        a polygon through them faces outward. Pointer doubling, O(C log valence).

    Raises:
        DLFLError: a vertex whose corners form more than one cycle.
    """
    vnext = a.corner_vnext
    n = len(vnext)
    counts = np.bincount(a.corner_vertex, minlength=len(a.vertex_ids))
    offsets = np.zeros(len(counts) + 1, np.int64)
    np.cumsum(counts, out=offsets[1:])
    # the root of each vertex's cycle is its first corner in corner order
    first = np.full(len(counts), n, np.int64)
    np.minimum.at(first, a.corner_vertex, np.arange(n))
    is_root = np.zeros(n, bool)
    is_root[first[counts > 0]] = True
    # distance along vnext to the corner just before the root
    last = is_root[vnext]
    succ = np.where(last, np.arange(n), vnext)
    dist = (~last).astype(np.int64)
    while True:
        dist += dist[succ]
        jumped = succ[succ]
        if np.array_equal(jumped, succ):
            break
        succ = jumped
    size = counts[a.corner_vertex]
    if (dist >= size).any() or not np.array_equal(np.bincount(a.corner_vertex[last],
                                                              minlength=len(counts)),
                                                  (counts > 0).astype(np.int64)):
        raise DLFLError("a vertex's corners form several fans; the mesh is not manifold there")
    order = np.empty(n, np.int64)
    order[offsets[a.corner_vertex] + (dist + 1) % size] = np.arange(n)
    return order, offsets


def _cut_points(a: MeshArrays, thickness: float) -> np.ndarray:
    """``(C, 3)`` TopMod's corner-cut point: ``t/2`` from both edges at the corner.

    ``v + x (n1 + n2)`` with ``n1, n2`` unit vectors to the previous and next
    corner and ``x = sqrt(t^2 / (1 - (n1.n2)^2))``, ``t = thickness / 2``. When the
    neighbours coincide (a 2-gon) the corner after next stands in for the next;
    at a straight corner the point moves ``t`` toward the face centroid.
    """
    t = thickness / 2.0
    p = a.positions
    cv = a.corner_vertex
    nxt, prv = a.corner_next, a.corner_prev
    v0, v1, v2 = p[cv], p[cv[prv]], p[cv[nxt]]
    close = np.linalg.norm(v1 - v2, axis=1) < 1e-3
    v2[close] = p[cv[nxt[nxt[close]]]]
    n1, n2 = _unit(v1 - v0), _unit(v2 - v0)
    dot = np.einsum("ij,ij->i", n1, n2)
    denom = 1.0 - dot * dot
    straight = denom < 1e-12
    x = np.sqrt(t * t / np.where(straight, 1.0, denom))
    points = v0 + x[:, None] * (n1 + n2)
    centre = face_centroids(a)[a.corner_face[straight]]
    points[straight] = v0[straight] + t * _unit(centre - v0[straight])
    return points


def _unit(vectors: np.ndarray) -> np.ndarray:
    length = np.linalg.norm(vectors, axis=-1, keepdims=True)
    return np.divide(vectors, length, out=np.zeros_like(vectors), where=length > 1e-300)


def corner_cut_arrays(a: MeshArrays, thickness: float) -> CornerCut:
    """Modified corner cutting of ``a`` as corner arrays (see :class:`CornerCut`).

    Edge ``e`` with sides ``c0`` (in face f0) and ``c1`` (in f1) becomes the quad
    ``[q(next c0), q(c0), q(next c1), q(c1)]``; vertex ``v`` becomes the polygon
    of the points of its corners, walked against ``vnext``.
    """
    _check_cut_input(a, thickness)
    nc, ne = len(a.corner_vertex), len(a.edge_ids)
    nxt = a.corner_next
    c0, c1 = a.edge_corners[:, 0], a.edge_corners[:, 1]
    ring, ring_offsets = vertex_rings(a)
    quads = np.stack([nxt[c0], c0, nxt[c1], c1], axis=1).ravel()
    corner_vertex = np.concatenate([np.arange(nc), quads, ring])
    quad_start = nc
    ring_start = nc + 4 * ne
    # output index of the vertex-polygon corner of each original corner
    ring_pos = np.empty(nc, np.int64)
    ring_pos[ring] = ring_start + np.arange(nc)
    mate = np.empty(nc + 4 * ne + nc, np.int64)
    e_ids = np.arange(ne)
    mate[c0] = quad_start + 4 * e_ids
    mate[c1] = quad_start + 4 * e_ids + 2
    mate[quad_start + 4 * e_ids] = c0
    mate[quad_start + 4 * e_ids + 2] = c1
    mate[quad_start + 4 * e_ids + 1] = ring_pos[nxt[c1]]
    mate[quad_start + 4 * e_ids + 3] = ring_pos[nxt[c0]]
    mate[ring_pos[nxt[c1]]] = quad_start + 4 * e_ids + 1
    mate[ring_pos[nxt[c0]]] = quad_start + 4 * e_ids + 3
    sizes = np.concatenate([a.face_sizes, np.full(ne, 4), np.diff(ring_offsets)])
    offsets = np.zeros(len(sizes) + 1, np.int64)
    np.cumsum(sizes, out=offsets[1:])
    hole = np.concatenate([a.face_hole, np.zeros(ne + len(a.vertex_ids), bool)])
    return CornerCut(_cut_points(a, thickness), offsets, corner_vertex, mate, hole,
                     len(a.face_ids))


def _check_cut_input(a: MeshArrays, thickness: float) -> None:
    if not np.isfinite(thickness) or thickness <= 0:
        raise DLFLError(f"thickness must be a positive number, got {thickness}")
    if len(a.face_ids) == 0:
        raise DLFLError("corner cutting needs a mesh with faces; this one is empty")
    if (a.corner_edge < 0).any():
        v = int(a.vertex_ids[a.corner_vertex[np.flatnonzero(a.corner_edge < 0)[0]]])
        raise DLFLError(f"corner cutting needs a mesh without point-spheres; vertex {v} is one")
    if (a.edge_corners[:, 0] == a.corner_next[a.edge_corners[:, 1]]).any() and (
        a.corner_vertex[a.edge_corners[:, 0]] == a.corner_vertex[a.edge_corners[:, 1]]
    ).any():
        raise DLFLError("corner cutting cannot cut a self-loop edge")


def modified_corner_cut(mesh: Mesh, thickness: float = 0.25) -> list[int]:
    """TopMod's ``modifiedCornerCuttingSubdivide(thickness)`` (GUI 0.25).

    Every face gets an inner polygon whose corners are ``thickness / 2`` from
    both edges at that corner; every edge becomes a quad and every vertex a
    polygon of its valence. Cube: 24/48/26 (8x3, 18x4). The mesh is rebuilt
    (fresh ids). livemod computes in double precision (TopMod used floats).

    Returns:
        The ids of the inner polygons (TopMod's front copies, typed FTHole), in
        the order of the original faces: the faces :func:`wireframe` punches.

    Raises:
        DLFLError: ``thickness`` not positive, point-spheres, self-loops; the
            mesh is unchanged.
    """
    cut = corner_cut_arrays(mesh_arrays(mesh), thickness)
    first = mesh.next_ids()
    new = from_corner_arrays(cut.positions, cut.offsets, cut.corner_vertex, cut.corner_mate,
                             cut.face_hole, first_ids=first)
    mesh.replace_with(new)
    return list(range(first[2], first[2] + cut.num_front))


def wireframe_inner_positions(a: MeshArrays, front: np.ndarray, thickness: float) -> np.ndarray:
    """``(V, 3)`` TopMod's ``createCrustForWireframe`` placement of the inner copy.

    Each vertex ``v0`` lies on exactly one front face; ``v1``/``v2`` are its next
    and previous corners there, ``v3`` the corner after ``v0`` in the bevel quad
    across ``v0 v1`` and ``v4`` the corner before ``v0`` in the bevel across
    ``v2 v0``. With ``n2`` in the first bevel's plane perpendicular to ``v0 v1``
    and ``n4`` likewise in the second, the copy sits at
    ``v0 - t * normalize(n2 x n4)``.

    Args:
        a: the corner-cut mesh.
        front: ``(F,)`` bool, the front copies.
        thickness: ``t``.
    """
    nxt, prv, mate, cv = a.corner_next, a.corner_prev, a.corner_mate, a.corner_vertex
    c0 = np.full(len(a.vertex_ids), -1, np.int64)
    on_front = np.flatnonzero(front[a.corner_face])
    c0[cv[on_front]] = on_front
    if (c0 < 0).any():
        raise DLFLError("every vertex must lie on a front face (run modified_corner_cut first)")
    p = a.positions
    v0, v1, v2 = p[cv[c0]], p[cv[nxt[c0]]], p[cv[prv[c0]]]
    v3 = p[cv[nxt[nxt[mate[c0]]]]]
    v4 = p[cv[prv[mate[prv[c0]]]]]
    n1 = _unit(np.cross(v1 - v0, v3 - v0))
    n2 = _unit(np.cross(n1, v1 - v0))
    n3 = _unit(np.cross(v2 - v0, v4 - v0))
    n4 = _unit(np.cross(v2 - v0, n3))
    return v0 - thickness * _unit(np.cross(n2, n4))


def wireframe(mesh: Mesh, thickness: float = 0.1, split: bool = True) -> None:
    """TopMod's ``makeWireframe(t, split)`` (API default 0.1, GUI 0.25).

    Modified corner cutting at ``thickness``, then (with ``split``) TopMod's
    ``splitValence2Vertices(-1)`` where the cut left valence-2 vertices, then
    the wireframe crust and every front copy punched into a tube. Cube at any
    thickness: 48/120/64 (16x3, 48x4), genus 5. The mesh is rebuilt (fresh ids).

    Raises:
        DLFLError: ``thickness`` not positive, point-spheres, self-loops; the
            mesh is unchanged.
    """
    cut = corner_cut_arrays(mesh_arrays(mesh), thickness)
    work = from_corner_arrays(cut.positions, cut.offsets, cut.corner_vertex, cut.corner_mate,
                              cut.face_hole)
    a = mesh_arrays(work)
    front = np.zeros(len(a.face_ids), bool)
    front[: cut.num_front] = True
    if split:
        front = _split_valence2(work, a, front)
        a = mesh_arrays(work)
    inner = wireframe_inner_positions(a, front, thickness)
    shell = shell_arrays(a, a.positions, inner, front, cleanup=False)
    mesh.replace_with(shell.build(mesh))


def _split_valence2(work: Mesh, a: MeshArrays, front: np.ndarray) -> np.ndarray:
    """Split valence-2 vertices of the cut mesh (rare: only where the input had
    valence-1 or valence-2 vertices); returns the front mask of the new layout."""
    valence = np.bincount(a.corner_vertex, minlength=len(a.vertex_ids))
    if not (valence == 2).any():
        return front
    from .geometry import split_valence2_vertices

    front_ids = set(a.face_ids[front].tolist())
    split_valence2_vertices(work, -1.0)
    ids = work.face_ids()
    return np.isin(ids, list(front_ids))
