"""Bands of faces between two faces: what connections and extrusions are built of.

Both operations merge two faces with one edge (:meth:`Mesh.insert_edge` between
corners of different faces) and then cut the merged face into a band of small
faces, as TopMod's ``connectFaces`` (quads) and ``dualConnectFaces``
(triangles) do. :mod:`livemod.dlfl.connect`, :mod:`livemod.dlfl.extrusion` and
:mod:`livemod.dlfl.multihandle` share them, and :func:`edges_since`, which
lists the edges an operation made.

These are building blocks: they check nothing, so callers check their
arguments first (both corners live, in different faces).
"""

from __future__ import annotations

from .mesh import Mesh


def edges_since(mesh: Mesh, first_id: int) -> list[int]:
    """Live edges created since the edge counter stood at ``first_id``, in
    creation order (ids are never reused, so these are exactly the new ones left)."""
    return [e for e in range(first_id, mesh.next_ids()[1]) if mesh.has_edge(e)]


def quad_band(mesh: Mesh, corner1: int, corner2: int) -> None:
    """TopMod's ``connectFaces``: one merging edge from ``corner1`` to ``corner2``
    (corners of two different faces), then quads cut off the merged face until
    it has 4 sides or fewer (two faces of ``n`` sides: a ring of ``n`` quads)."""
    mesh.insert_edge(corner1, corner2)
    side = corner1
    # each cut moves two corners of the merged face into a quad; counting them
    # saves a walk around the merged face per cut
    size = mesh.face_size(mesh.corner_face(side))
    while size > 4:
        before = mesh.corner_prev(side)
        mesh.insert_edge(before, mesh.corner_next(mesh.corner_next(side)))
        side = before
        size -= 2


def triangle_band(mesh: Mesh, corner1: int, corner2: int) -> None:
    """TopMod's ``dualConnectFaces``: one merging edge from ``corner1`` to
    ``corner2`` (corners of two different faces), then triangles cut off the
    merged face on alternating sides (faces of ``n`` and ``m`` sides: ``n + m``
    triangles)."""
    mesh.insert_edge(corner1, corner2)
    side, parity = corner1, True
    size = mesh.face_size(mesh.corner_face(side))  # each cut takes one corner away
    while size > 3:
        size -= 1
        if parity:
            mesh.insert_edge(side, mesh.corner_next(mesh.corner_next(side)))
        else:
            before = mesh.corner_prev(side)
            mesh.insert_edge(before, mesh.corner_next(side))
            side = before
        parity = not parity
