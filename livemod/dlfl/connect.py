"""Connecting faces and edges: the operations that add handles and tubes."""

from __future__ import annotations

from .errors import DLFLError
from .mesh import Mesh


def connect_faces(mesh: Mesh, corner1: int, corner2: int) -> list[int]:
    """Join two faces with a ring of quads, matching ``corner1``'s vertex to ``corner2``'s.

    TopMod's ``connectFaces``: one edge merges the faces, then quads are cut off
    the merged face while it has more than four sides. Faces of equal size ``n``
    give ``n`` quads (genus +1 within one component, or two components joined);
    unequal sizes end in a triangle or a larger polygon.

    Returns:
        The ids of the new edges, the first one joining the two corners.

    Raises:
        DLFLError: a corner is not live, or both corners are in the same face.
    """
    face1, face2 = mesh.corner_face(corner1), mesh.corner_face(corner2)
    if face1 == face2:
        raise DLFLError(
            f"connect_faces needs corners of two different faces, both are in face {face1}"
        )
    new_edges = [mesh.insert_edge(corner1, corner2)]
    side = corner1
    while mesh.face_size(mesh.corner_face(side)) > 4:
        before = mesh.corner_prev(side)
        across = mesh.corner_next(mesh.corner_next(side))
        new_edges.append(mesh.insert_edge(before, across))
        side = before
    return new_edges
