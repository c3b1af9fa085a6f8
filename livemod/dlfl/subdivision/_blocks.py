"""Face blocks the schemes share, expressed over old corners.

Conventions (``t`` the old topology, ``C`` its corner count): a "half" label
``c`` names the half of edge ``edge[c]`` at corner ``c``'s vertex, so the half at
the other end is ``mate[c]``. Per-corner points are numbered ``base + c``.
"""

from __future__ import annotations

import numpy as np

from ._layout import NO_ORIGIN, Faces, Topology


def split_quads(t: Topology, corners: np.ndarray, edge_point: np.ndarray,
                face_point: np.ndarray, faces: Faces) -> None:
    """One quad per old corner ``c``: vertex, edge point, face point, edge point.

    ``edge_point`` ``(E,)`` and ``face_point`` ``(F,)`` give the new vertex of each
    old edge's and face's point. Labels: halves ``[0, C)``, face spokes ``[C, 2C)``.
    """
    c, p = corners, t.prv[corners]
    verts = np.stack([t.cv[c], edge_point[t.edge[c]], face_point[t.face[c]],
                      edge_point[t.edge[p]]], axis=1)
    labels = np.stack([c, t.nc + c, t.nc + p, t.mate[p]], axis=1)
    faces.add(verts, labels, t.origin[t.face[c]])


def fan_triangles(t: Topology, corners: np.ndarray, face_point: np.ndarray,
                  faces: Faces) -> None:
    """One triangle per old corner ``c``: its side and the face point.

    ``face_point`` ``(F,)``: new vertex of each face's point. Labels: old edges
    ``[0, E)``, spokes ``E + c``.
    """
    c, n = corners, t.nxt[corners]
    verts = np.stack([t.cv[c], t.cv[n], face_point[t.face[c]]], axis=1)
    labels = np.stack([t.edge[c], t.ne + n, t.ne + c], axis=1)
    faces.add(verts, labels, t.origin[t.face[c]])


def corner_triangles(t: Topology, edge_base: int, faces: Faces) -> None:
    """One triangle per old corner: vertex and the two edge points beside it.

    Labels: halves ``[0, C)``, cut edges ``C + c``.
    """
    c, p = np.arange(t.nc), t.prv
    verts = np.stack([t.cv, edge_base + t.edge, edge_base + t.edge[p]], axis=1)
    labels = np.stack([c, t.nc + c, t.mate[p]], axis=1)
    faces.add(verts, labels, t.origin[t.face])


def inner_polygons(t: Topology, edge_base: int, faces: Faces) -> None:
    """Per old face, the polygon of its edge points (label of a side: ``C + next``)."""
    faces.add(edge_base + t.edge, t.nc + t.nxt, t.origin, t.sizes)


def face_rings(t: Topology, base: int, label_base: int, faces: Faces) -> None:
    """Per old face, the polygon of its per-corner points ``base + c``.

    The side from corner ``c``'s point to the next one has label ``label_base + c``.
    """
    corners = np.arange(t.nc)
    faces.add(base + corners, label_base + corners, t.origin, t.sizes)


def vertex_rings(t: Topology, point_of: np.ndarray, label_of: np.ndarray, faces: Faces,
                 min_size: int = 1) -> None:
    """Per old vertex, the polygon of its corners' points, counter-clockwise.

    Corner ``c`` of the ring contributes ``point_of[c]``; the side from it to
    ``vprev(c)``'s point has label ``label_of[c]``. Rings shorter than
    ``min_size`` are left out.
    """
    order, offsets = t.vertex_rings()
    ring_sizes = np.diff(offsets)
    keep = np.repeat(ring_sizes >= min_size, ring_sizes)
    kept = order[keep]
    faces.add(point_of[kept], label_of[kept], NO_ORIGIN,
              ring_sizes[ring_sizes >= min_size])


def merge_two_rings(t: Topology) -> np.ndarray:
    """``(C,)`` corner relabelling that identifies the two corners of each 2-ring.

    Used where a scheme's vertex face would be a 2-gon (a valence-2 vertex): the
    two sides it would have are one edge instead (as TopMod leaves them).
    """
    order, offsets = t.vertex_rings()
    ring_sizes = np.diff(offsets)
    rep = np.arange(t.nc)
    two = offsets[:-1][ring_sizes == 2]
    rep[order[two + 1]] = order[two]
    return rep


def doo_sabin_faces(t: Topology, faces: Faces) -> None:
    """Doo-Sabin topology over per-corner points ``0..C-1``.

    F-faces (labels ``[0, C)``), one quad per edge, and a V-face per vertex
    (labels ``[C, 2C)``); a valence-2 vertex gets no 2-gon: its two sides merge.
    At a valence-1 vertex the quad's two corners would share the vertex's one
    point, so the quad loses one of them and becomes a triangle (an edge
    dangling from both ends gives a 2-gon).
    """
    face_rings(t, 0, 0, faces)
    rep = merge_two_rings(t)
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    na, nb = t.nxt[a], t.nxt[b]
    verts = np.stack([na, a, nb, b], axis=1)
    labels = np.stack([a, t.nc + rep[nb], b, t.nc + rep[na]], axis=1)
    # na == b: b's vertex has one corner, so the side b -> na is empty (likewise a)
    drop = np.zeros(verts.shape, dtype=bool)
    drop[:, 0], drop[:, 2] = na == b, nb == a
    labels[drop[:, 0], 3] = labels[drop[:, 0], 0]
    labels[drop[:, 2], 1] = labels[drop[:, 2], 2]
    faces.add(verts[~drop], labels[~drop], NO_ORIGIN, 4 - drop.sum(axis=1))
    corners = np.arange(t.nc)
    vertex_rings(t, corners, t.nc + corners, faces, min_size=3)
