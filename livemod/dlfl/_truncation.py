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
            every element, -1 for the new ones (numbered in order by the caller).
        caps: ``(V,)`` dense face index of each cap, in vertex order.
    """

    positions: np.ndarray
    offsets: np.ndarray
    corner_vertex: np.ndarray
    corner_mate: np.ndarray
    face_hole: np.ndarray
    vertex_ids: np.ndarray
    face_ids: np.ndarray
    corner_ids: np.ndarray
    caps: np.ndarray


def check_truncatable(a: MeshArrays) -> None:
    """Refuse a mesh with a self-loop, or a vertex with one edge (its cap would
    have one side), naming the first such vertex (by id).

    Raises:
        InvalidArgumentError: as said, the self-loops first.
    """
    cv, nxt = a.corner_vertex, a.corner_next
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


def truncation(a: MeshArrays, offset: float) -> Truncation:
    """:class:`Truncation` of the (checked, :func:`check_truncatable`) mesh ``a``
    at ``offset`` in (0, 0.5)."""
    cv, mate, nxt, prv = a.corner_vertex, a.corner_mate, a.corner_next, a.corner_prev
    solid = mate >= 0
    corners = np.flatnonzero(solid)  # the faces with edges, face after face
    k = len(corners)
    rank = np.full(len(cv), -1, dtype=np.int64)
    rank[corners] = np.arange(k)
    order, ring_offsets = vertex_rings(a)
    ring = order[solid[order]]  # the caps' corners, vertex after vertex
    ring_sizes = np.bincount(cv[ring], minlength=len(a.vertex_ids))
    cap_corner = np.empty(len(cv), dtype=np.int64)
    cap_corner[ring] = 2 * k + np.arange(k)
    verts = np.empty(3 * k, dtype=np.int64)
    mates = np.empty(3 * k, dtype=np.int64)
    # corner 2r of old corner c (rank r) runs from its point to mate c's, along
    # c's edge; 2r + 1 from mate c's point to next c's, along next c's vertex's cap
    verts[0 : 2 * k : 2] = rank[corners]
    verts[1 : 2 * k : 2] = rank[mate[corners]]
    mates[0 : 2 * k : 2] = 2 * rank[mate[corners]]
    mates[1 : 2 * k : 2] = cap_corner[nxt[corners]]
    # a cap's side from x's point runs to vprev x = mate(prev x)'s point
    verts[2 * k :] = rank[ring]
    mates[2 * k :] = 2 * rank[prv[ring]] + 1
    return _with_point_spheres(a, offset, corners, verts, mates, ring_sizes)


def _with_point_spheres(a: MeshArrays, offset: float, corners: np.ndarray, verts: np.ndarray,
                        mates: np.ndarray, ring_sizes: np.ndarray) -> Truncation:
    """The :class:`Truncation`: the faces and caps of ``verts``/``mates`` ``(3K,)``,
    then the point-spheres of ``a`` as they were."""
    sizes = a.face_sizes
    lone = np.flatnonzero(a.corner_mate < 0)  # a point-sphere's corner, its face's only one
    sphere_face, sphere_vertex = a.corner_face[lone], a.corner_vertex[lone]
    solid_face = np.ones(len(sizes), dtype=bool)
    solid_face[sphere_face] = False
    cap_sizes = ring_sizes[ring_sizes > 0]
    k, s = len(corners), len(lone)
    all_sizes = np.concatenate([2 * sizes[solid_face], cap_sizes, np.ones(s, dtype=np.int64)])
    offsets = np.zeros(len(all_sizes) + 1, dtype=np.int64)
    np.cumsum(all_sizes, out=offsets[1:])
    new_faces = int(np.count_nonzero(solid_face))
    return Truncation(
        positions=np.concatenate([_points(a, corners, offset), a.positions[sphere_vertex]]),
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


def _points(a: MeshArrays, corners: np.ndarray, offset: float) -> np.ndarray:
    """``(K, 3)``: ``offset`` of the way along each corner's edge from its vertex,
    as weighted ends clamped to their box (no coordinate overflows)."""
    near = a.positions[a.corner_vertex[corners]]
    far = a.positions[a.corner_vertex[a.corner_next[corners]]]
    with np.errstate(over="ignore"):
        points = (1.0 - offset) * near + offset * far
    return np.clip(points, np.minimum(near, far), np.maximum(near, far))
