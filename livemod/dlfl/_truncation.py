"""The arrays of :func:`livemod.dlfl.cutting.truncate`, every vertex cut at once.

Each corner ``c`` with an edge gets the point ``offset`` of the way along its
edge from its vertex. Every face becomes the polygon that visits, per corner
``c``, its point and the point of the corner across its edge (``mate c``);
every vertex becomes a cap through its corners' points, in ``vprev`` order.
Point-spheres come through as they are, with their ids; the faces keep theirs.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .arrays import MeshArrays
from .errors import InvalidArgumentError
from .wireframe import vertex_rings


@dataclass(frozen=True)
class Truncation:
    """A truncated mesh, laid out for :func:`.build.from_corner_arrays`: the
    faces (the old ones, then one cap per vertex, then the point-spheres')
    corner by corner, and the ids the kept elements keep.

    Attributes:
        positions: ``(K + S, 3)`` a point per corner with an edge, then the
            point-spheres' vertices.
        offsets, corner_vertex, corner_mate, face_hole: the new faces.
        vertex_ids, face_ids, corner_ids: ``(V',)``, ``(F',)``, ``(C',)`` the id of
            every element, -1 for the new ones (numbered in order by the caller);
            None for a kind with no id kept (no point-sphere).
        caps: ``(V,)`` dense face index of each cap, in vertex order.
    """

    positions: np.ndarray
    offsets: np.ndarray
    corner_vertex: np.ndarray
    corner_mate: np.ndarray
    face_hole: np.ndarray
    vertex_ids: np.ndarray | None
    face_ids: np.ndarray
    corner_ids: np.ndarray | None
    caps: np.ndarray


def check_truncatable(a: MeshArrays, nxt: np.ndarray) -> None:
    """Refuse a mesh with a self-loop, or a vertex with one edge (its cap would
    have one side), naming the first such vertex (by id). ``nxt``: ``(C,)``
    ``a.corner_next``.

    Raises:
        InvalidArgumentError: as said, the self-loops first.
    """
    cv = a.corner_vertex
    solid = np.flatnonzero(a.corner_mate >= 0)
    loops = solid[cv[solid] == cv[nxt[solid]]]
    if len(loops):
        first = loops[np.argmin(cv[loops])]
        v = cv[first]
        edge = int(a.edge_ids[a.corner_edge[loops[cv[loops] == v]]].min())
        raise InvalidArgumentError(f"vertex {int(a.vertex_ids[v])} has a self-loop (edge {edge}); "
                                   "a cut needs edges to other vertices")
    valence = np.bincount(cv[solid], minlength=len(a.vertex_ids))
    lone = np.flatnonzero(valence == 1)
    if len(lone):
        raise InvalidArgumentError(
            f"vertex {int(a.vertex_ids[lone[0]])}: only 1 edge(s) leave it, and a cut needs at "
            "least two (the sides of its new face)")


def truncation(a: MeshArrays, nxt: np.ndarray, offset: float) -> Truncation:
    """:class:`Truncation` of the (checked, :func:`check_truncatable`) mesh ``a``
    at ``offset`` in (0, 0.5); ``nxt``: ``(C,)`` ``a.corner_next``."""
    cv, mate = a.corner_vertex, a.corner_mate
    solid = mate >= 0
    every = bool(solid.all())  # no point-sphere: corner c is point c
    corners = np.arange(len(cv)) if every else np.flatnonzero(solid)
    k = len(corners)
    rank = None if every else np.full(len(cv), -1, dtype=np.int64)
    if rank is not None:
        rank[corners] = np.arange(k)

    def point(x: np.ndarray) -> np.ndarray:  # the new vertex of old corners x
        return x if rank is None else rank[x]

    order, _ = vertex_rings(a)
    ring = order if every else order[solid[order]]  # the caps' corners, vertex after vertex
    cap_corner = np.empty(len(cv), dtype=np.int64)
    cap_corner[ring] = 2 * k + np.arange(k)
    verts = np.empty(3 * k, dtype=np.int64)
    mates = np.empty(3 * k, dtype=np.int64)
    # corner 2r of old corner c (point r) runs from its point to mate c's, along
    # c's edge; 2r + 1 from mate c's point to next c's, along next c's vertex's cap
    across = mate if every else mate[corners]
    verts[0 : 2 * k : 2] = point(corners)
    verts[1 : 2 * k : 2] = point(across)
    mates[0 : 2 * k : 2] = 2 * point(across)
    mates[1 : 2 * k : 2] = cap_corner[nxt if every else nxt[corners]]
    # a cap's side from x's point runs to vprev x = mate(prev x)'s point
    verts[2 * k :] = point(ring)
    mates[2 * k :] = 2 * point(a.corner_prev[ring]) + 1
    ring_sizes = np.bincount(cv[ring], minlength=len(a.vertex_ids))
    points = _points(a, cv[corners] if not every else cv, cv[nxt[corners]], offset)
    return _with_point_spheres(a, points, verts, mates, ring_sizes[ring_sizes > 0])


def _with_point_spheres(a: MeshArrays, points: np.ndarray, verts: np.ndarray,
                        mates: np.ndarray, cap_sizes: np.ndarray) -> Truncation:
    """The :class:`Truncation`: the faces and caps of ``verts``/``mates`` ``(3K,)``
    over the ``(K, 3)`` ``points``, then the point-spheres of ``a`` as they were."""
    sizes = a.face_sizes
    lone = np.flatnonzero(a.corner_mate < 0)  # a point-sphere's corner, its face's only one
    if len(lone) == 0:
        offsets = np.zeros(len(sizes) + len(cap_sizes) + 1, dtype=np.int64)
        np.cumsum(np.concatenate([2 * sizes, cap_sizes]), out=offsets[1:])
        return Truncation(points, offsets, verts, mates,
                          np.concatenate([a.face_hole, np.zeros(len(cap_sizes), bool)]),
                          None, np.concatenate([a.face_ids, np.full(len(cap_sizes), -1)]), None,
                          len(sizes) + np.arange(len(cap_sizes)))
    sphere_face, sphere_vertex = a.corner_face[lone], a.corner_vertex[lone]
    solid_face = np.ones(len(sizes), dtype=bool)
    solid_face[sphere_face] = False
    k, s = len(points), len(lone)
    all_sizes = np.concatenate([2 * sizes[solid_face], cap_sizes, np.ones(s, dtype=np.int64)])
    offsets = np.zeros(len(all_sizes) + 1, dtype=np.int64)
    np.cumsum(all_sizes, out=offsets[1:])
    new_faces = int(np.count_nonzero(solid_face))
    return Truncation(
        positions=np.concatenate([points, a.positions[sphere_vertex]]),
        offsets=offsets,
        corner_vertex=np.concatenate([verts, k + np.arange(s)]),
        corner_mate=np.concatenate([mates, np.full(s, -1, dtype=np.int64)]),
        face_hole=np.concatenate([a.face_hole[solid_face], np.zeros(len(cap_sizes) + s, bool)]),
        vertex_ids=np.concatenate([np.full(k, -1), a.vertex_ids[sphere_vertex]]),
        face_ids=np.concatenate([a.face_ids[solid_face], np.full(len(cap_sizes), -1),
                                 a.face_ids[sphere_face]]),
        corner_ids=np.concatenate([np.full(3 * k, -1), a.corner_ids[lone]]),
        caps=new_faces + np.arange(len(cap_sizes)),
    )


def _points(a: MeshArrays, near_v: np.ndarray, far_v: np.ndarray, offset: float
            ) -> np.ndarray:
    """``(K, 3)``: ``offset`` of the way from vertex ``near_v`` to ``far_v`` (both
    ``(K,)``), as weighted ends clamped to their box (no coordinate overflows).
    Axis by axis: 1-D gathers of contiguous columns are several times faster
    than gathering rows."""
    out = np.empty((len(near_v), 3))
    for axis in range(3):
        column = np.ascontiguousarray(a.positions[:, axis])
        near, far = column[near_v], column[far_v]
        with np.errstate(over="ignore"):
            point = (1.0 - offset) * near + offset * far
        np.maximum(point, np.minimum(near, far), out=point)
        np.minimum(point, np.maximum(near, far), out=out[:, axis])
    return out
