"""Thesis-style commands of TopMod's sculpting cuts: cutVertices, cutEdges, cutFaces,
cutPlane, truncate.

livemod additions (TopMod's Python module had no cutting commands), named after
its ``cutSelectedVertices``, ``cutSelectedEdges``, ``cutSelectedFaces`` and
``peelByPlane``: thin wrappers over :mod:`livemod.dlfl.cutting` acting on the
current object. As in TopMod's GUI the ids default to the current selection;
``offset`` defaults to TopMod's 0.25, and the new points lie where each
element's plane crosses the edges (TopMod's rule); ``placement="offset"`` puts
them ``offset`` along each edge leaving the element instead, and ``peel=True``
cuts the whole object by each plane (TopMod's Global Cut). Each returns the ids
of the new faces (TopMod returned nothing).
"""

from __future__ import annotations

from typing import Any

from .. import cutting as _cutting
from ..errors import InvalidArgumentError
from ._base import id_arguments, mesh, modeling_command, scene

__all__ = ["cutVertices", "cutEdges", "cutFaces", "cutPlane", "truncate"]


@modeling_command
def cutVertices(vertexids: Any = None, offset: float = _cutting.DEFAULT_OFFSET,
                placement: str = "plane", peel: bool = False) -> list[int]:
    """Cut off vertices (default: the selected ones), each by a plane through the
    mean of the points ``offset`` along its edges, square to its normal; the new
    points lie where the plane crosses the edges. Cube corner: 10/15/7.

    ``placement="offset"``: the new points lie ``offset`` along the vertex's own
    edges. ``peel=True``: each plane cuts the whole object (TopMod's Global Cut).

    Returns:
        The new face ids.

    Raises:
        DLFLError: an id that is not a vertex, a point-sphere, a vertex with a
            self-loop or one edge, ``offset`` not > 0 (offset placement: not in
            (0, 1), below 0.5 where two cut vertices share an edge), a vertex on
            the near side of its plane; the mesh is unchanged.
    """
    return _cutting.cut_vertices(mesh(), id_arguments(vertexids, "vertexids", "vertices"), offset,
                                 placement=placement, peel=peel, max_faces=scene().face_budget)


@modeling_command
def cutEdges(edgeids: Any = None, offset: float = _cutting.DEFAULT_OFFSET,
             placement: str = "plane", peel: bool = False) -> list[int]:
    """Cut off edges (default: the selected ones) with their end vertices: a bevel,
    by a plane through the mean of the points ``offset`` along the other edges
    at its ends, square to the mean of its faces' normals. Cube edge: 10/15/7.

    ``placement="offset"``: edges that share a vertex get one new face, whose
    corners lie ``offset`` along the edges leaving them. ``peel``: as cutVertices.

    Returns:
        The new face ids.

    Raises:
        DLFLError: an id that is not an edge, a self-loop, ``offset`` out of range,
            offset placement: edges closing a cycle; the mesh is unchanged.
    """
    return _cutting.cut_edges(mesh(), id_arguments(edgeids, "edgeids", "edges"), offset,
                              placement=placement, peel=peel, max_faces=scene().face_budget)


@modeling_command
def cutFaces(faceids: Any = None, offset: float = _cutting.DEFAULT_OFFSET,
             placement: str = "plane", peel: bool = False) -> list[int]:
    """Cut off faces (default: the selected ones), each by a plane square to its
    normal through the mean of the points ``offset`` along the edges leaving it.
    Cube face: 8/12/6, a lower box.

    ``placement="offset"``: the new points lie ``offset`` along the edges
    leaving the face (faces must not share a vertex). ``peel``: as cutVertices.

    Returns:
        The new face ids.

    Raises:
        DLFLError: an id that is not a face, a hole, a face visiting a vertex
            twice, ``offset`` out of range, offset placement: two faces sharing a
            vertex; the mesh is unchanged.
    """
    return _cutting.cut_faces(mesh(), id_arguments(faceids, "faceids", "faces"), offset,
                              placement=placement, peel=peel, max_faces=scene().face_budget)


@modeling_command
def cutPlane(point: Any = None, normal: Any = None, faceid: int | None = None,
             vertexid: int | None = None) -> list[int]:
    """Cut off everything beyond a plane (TopMod's Global Cut, ``peelByPlane``):
    the plane through ``point`` square to ``normal``, or with ``faceid`` the
    plane through that face (its centroid and normal). With ``vertexid`` only
    the part beyond the plane joined to that vertex goes. The new points lie
    where the plane crosses the edges; each opening gets a new face in the
    plane. Cube, ``cutPlane((0, 0.5, 0), (0, 1, 0))``: 8/12/6.

    Returns:
        The new face ids.

    Raises:
        DLFLError: neither a plane nor ``faceid`` given, or both; ``point`` or
            ``normal`` not three numbers, a zero normal, a face with no normal,
            a ``vertexid`` not beyond the plane; the mesh is unchanged.
    """
    m = mesh()
    if faceid is not None:
        if point is not None or normal is not None:
            raise InvalidArgumentError("give the plane either as point and normal or "
                                                "as faceid, not both")
        point, normal = _cutting.plane_of_face(m, id_arguments(faceid, "faceid")[0])
    elif point is None or normal is None:
        raise InvalidArgumentError("cutPlane needs point and normal, or faceid")
    seed = None if vertexid is None else id_arguments(vertexid, "vertexid")[0]
    return _cutting.cut_plane(m, point, normal, seed=seed, max_faces=scene().face_budget)


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
