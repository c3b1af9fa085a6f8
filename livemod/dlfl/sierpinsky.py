"""Sierpinsky-style remeshing: TopMod's ``multiConnectMidpoints``.

Every edge is split at its midpoint; every face has its old corners cut off
(the triangles stay, and so do the old edges); then, at every midpoint, a
self-loop edge joins its two corners in the middle faces of the two faces that
shared the edge. The middle faces fuse through the midpoints into tunnels: the
cube becomes 20/60/32 (24 triangles, 8 hexagons), genus 5.

The result is laid out at once (vectorized, O(C)). Its faces are a triangle
per old corner ``c`` (``m(prev c), v(c), m(c)``, ``m(c)`` the midpoint of c's
edge) and, per old vertex ``v``, the face the middle faces fused into around
it: for each corner ``x`` of ``v`` in ``vnext`` order, the cut side from
``m(prev x)`` to ``m(x)`` and the self-loop at ``m(x)``, which the face of the
vertex at the edge's other end shares. ``V + E`` vertices, ``5E`` edges (two
halves and a self-loop per old edge, a cut per old corner), ``C + V`` faces.
"""

from __future__ import annotations

import numpy as np

from .arrays import MeshArrays, mesh_arrays
from .budget import check_size
from .build import from_corner_arrays
from .errors import InvalidArgumentError
from .mesh import Mesh
from .soup import offsets_of
from .wireframe import vertex_rings

__all__ = ["sierpinsky"]


def sierpinsky(mesh: Mesh, *, max_faces: object = None) -> list[int]:
    """TopMod's ``multiConnectMidpoints()`` (GUI CTRL+K), in place.

    The old vertices keep their ids, and every old edge keeps its id on its
    half from the vertex of its side ``c0`` (as :meth:`Mesh.subdivide_edge`
    splits it); midpoints, the other edges, every face and corner are new.

    Returns:
        The ids of the midpoint vertices, in the order of the old edges.

    Raises:
        DLFLError: the mesh has point-spheres or faces of fewer than three
            sides (a corner cut needs three); the mesh is unchanged.
        BudgetExceededError: the result would pass the face budget: it has
            ``V + C`` faces and ``5 C`` corners (``max_faces``; None: the
            session's, see :mod:`livemod.dlfl.budget`).
    """
    corners = mesh.num_corners
    check_size("sierpinsky", mesh.num_vertices + corners, 5 * corners, max_faces=max_faces)
    a = mesh_arrays(mesh)
    _check_input(a)
    first = mesh.next_ids()
    nv, ne = len(a.vertex_ids), len(a.edge_ids)
    vertex_ids = np.concatenate([a.vertex_ids, first[0] + np.arange(ne)])
    verts, mates, sizes = _layout(a)
    offsets = offsets_of(sizes)
    edge_ids = _edge_ids(a, mates, first[1])
    # a corner's triangle lies in the corner's face; a vertex's face has no one source
    colors = a.colors_at(np.concatenate([a.corner_face, np.full(len(sizes) - len(verts) // 5,
                                                                -1)]))
    mesh.replace_with(from_corner_arrays(
        np.concatenate([a.positions, _midpoints(a)]), offsets, verts, mates,
        face_colors=colors, first_ids=first, ids=(vertex_ids, edge_ids, None, None)))
    return vertex_ids[nv:].tolist()


def _check_input(a: MeshArrays) -> None:
    sizes = a.face_sizes
    if (a.corner_mate < 0).any():
        raise InvalidArgumentError("sierpinsky needs a mesh without point-spheres")
    small = np.flatnonzero(sizes < 3)
    if len(small):
        raise InvalidArgumentError(
            f"sierpinsky needs faces of at least three sides; face {int(a.face_ids[small[0]])} "
            f"has {int(sizes[small[0]])}")


def _layout(a: MeshArrays) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(vertex, mate)`` ``(5C,)`` of every new corner and ``(C + V,)`` face sizes.

    Triangle of old corner ``c``: corners ``3c`` (at ``m(prev c)``), ``3c + 1`` (at
    ``v(c)``), ``3c + 2`` (at ``m(c)``, its side the cut). Then the faces of the
    vertices, ring after ring: corner ``x`` of the ring gives ``A(x)`` at
    ``m(prev x)`` (the cut to ``m(x)``) and ``B(x)`` at ``m(x)`` (the self-loop).
    """
    nc, nv = len(a.corner_vertex), len(a.vertex_ids)
    nxt, prv, mate = a.corner_next, a.corner_prev, a.corner_mate
    midpoint = nv + a.corner_edge
    order, ring_offsets = vertex_rings(a)
    ring = _reversed_rings(order, ring_offsets)  # vnext order: A(x), B(x), A(vnext x), ...
    place = np.empty(nc, dtype=np.int64)
    place[ring] = 3 * nc + 2 * np.arange(nc)  # where A(x) is; B(x) follows it
    verts = np.empty(5 * nc, dtype=np.int64)
    mates = np.empty(5 * nc, dtype=np.int64)
    tri_v, tri_m = verts[: 3 * nc].reshape(-1, 3), mates[: 3 * nc].reshape(-1, 3)
    tri_v[:, 0], tri_v[:, 1], tri_v[:, 2] = midpoint[prv], a.corner_vertex, midpoint
    tri_m[:, 0] = 3 * mate[prv] + 1
    tri_m[:, 1] = 3 * nxt[mate]
    tri_m[:, 2] = place
    ring_v, ring_m = verts[3 * nc :].reshape(-1, 2), mates[3 * nc :].reshape(-1, 2)
    ring_v[:, 0], ring_v[:, 1] = midpoint[prv[ring]], midpoint[ring]
    ring_m[:, 0] = 3 * ring + 2
    ring_m[:, 1] = place[mate[ring]] + 1
    sizes = np.concatenate([np.full(nc, 3, dtype=np.int64), 2 * np.diff(ring_offsets)])
    return verts, mates, sizes


def _reversed_rings(order: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """``order`` with each ring ``order[offsets[v]:offsets[v + 1]]`` reversed."""
    ends = np.repeat(offsets[1:] + offsets[:-1] - 1, np.diff(offsets))
    return order[ends - np.arange(len(order))]


def _edge_ids(a: MeshArrays, mates: np.ndarray, first: int) -> np.ndarray:
    """``(5E,)`` the id of every new edge, numbered in order of its lower corner
    (as :func:`.build.from_corner_arrays` numbers them): old edge ``e`` on its
    half from side ``c0``'s vertex (corner ``3 c0 + 1``), fresh ids from
    ``first`` for the rest, in order."""
    lower = np.flatnonzero(mates > np.arange(len(mates)))
    kept = np.full(len(mates), -1, dtype=np.int64)
    c0 = a.edge_corners[:, 0]
    half = 3 * c0 + 1
    kept[np.minimum(half, mates[half])] = a.edge_ids
    ids = kept[lower]
    fresh = ids < 0
    ids[fresh] = first + np.arange(int(np.count_nonzero(fresh)))
    return ids


def _midpoints(a: MeshArrays) -> np.ndarray:
    """``(E, 3)``: ``p0 + (p1 - p0) / 2`` from side ``c0``'s vertex ``p0``, as
    :meth:`Mesh.subdivide_edge` places it (weighted ends clamped to their box
    where ``p1 - p0`` overflows)."""
    p0, p1 = (a.positions[a.corner_vertex[a.edge_corners[:, k]]] for k in (0, 1))
    with np.errstate(over="ignore", invalid="ignore"):
        out = p0 + (p1 - p0) * 0.5
        far = ~np.isfinite(p1 - p0).all(axis=1)
    if far.any():
        near_end, far_end = p0[far], p1[far]
        out[far] = np.clip(near_end * 0.5 + far_end * 0.5, np.minimum(near_end, far_end),
                           np.maximum(near_end, far_end))
    return out
