"""Thesis-style commands of TopMod's sculpting cuts: cutVertices, cutEdges, cutFaces, truncate.

livemod additions (TopMod's Python module had no cutting commands), named after
its ``cutSelectedVertices``, ``cutSelectedEdges`` and ``cutSelectedFaces``: thin
wrappers over :mod:`livemod.dlfl.cutting` acting on the current object. As in
TopMod's GUI the ids default to the current selection; ``offset`` defaults to
TopMod's 0.25. Each returns the ids of the new faces (TopMod returned nothing).
"""

from __future__ import annotations

from typing import Any

from .. import cutting as _cutting
from ._base import id_arguments, mesh, modeling_command, scene

__all__ = ["cutVertices", "cutEdges", "cutFaces", "truncate"]


@modeling_command
def cutVertices(vertexids: Any = None, offset: float = _cutting.DEFAULT_OFFSET) -> list[int]:
    """Cut off vertices (default: the selected ones), each by a new face through
    the points ``offset`` along its edges. Cube corner: 10/15/7.

    Returns:
        The new face ids, one per vertex.

    Raises:
        DLFLError: an id that is not a vertex, a point-sphere, a vertex with a
            self-loop or one edge, ``offset`` not in (0, 1) (below 0.5 where two
            cut vertices share an edge); the mesh is unchanged.
    """
    return _cutting.cut_vertices(mesh(), id_arguments(vertexids, "vertexids", "vertices"), offset,
                                 max_faces=scene().face_budget)


@modeling_command
def cutEdges(edgeids: Any = None, offset: float = _cutting.DEFAULT_OFFSET) -> list[int]:
    """Cut off edges (default: the selected ones) with their end vertices: a bevel.
    Edges that share a vertex get one new face. Cube edge: 10/15/7.

    Returns:
        The new face ids, one per group of connected edges.

    Raises:
        DLFLError: an id that is not an edge, a self-loop, edges closing a cycle,
            ``offset`` not in (0, 1); the mesh is unchanged.
    """
    return _cutting.cut_edges(mesh(), id_arguments(edgeids, "edgeids", "edges"), offset,
                              max_faces=scene().face_budget)


@modeling_command
def cutFaces(faceids: Any = None, offset: float = _cutting.DEFAULT_OFFSET) -> list[int]:
    """Cut off faces (default: the selected ones): each is replaced by a new face
    ``offset`` along the edges leaving it. Cube face: 8/12/6, a lower box.

    Returns:
        The new face ids, one per face.

    Raises:
        DLFLError: an id that is not a face, a hole, a face visiting a vertex
            twice, two faces sharing a vertex, ``offset`` not in (0, 1); the mesh
            is unchanged.
    """
    return _cutting.cut_faces(mesh(), id_arguments(faceids, "faceids", "faces"), offset,
                              max_faces=scene().face_budget)


@modeling_command
def truncate(offset: float = _cutting.DEFAULT_OFFSET) -> list[int]:
    """Cut off every vertex of the current object (cube: 24/36/14, as
    ``subdivide("vertex-cut")`` but keeping the old faces' ids).

    Returns:
        The new face ids, one per vertex.

    Raises:
        DLFLError: ``offset`` not in (0, 0.5), or a vertex with a self-loop or
            one edge; the mesh is unchanged.
    """
    return _cutting.truncate(mesh(), offset, max_faces=scene().face_budget)
