"""Sierpinsky-style remeshing: TopMod's ``multiConnectMidpoints``.

Every edge is split at its midpoint; every face has its old corners cut off
(the triangles stay, and so do the old edges); then, at every midpoint, a
self-loop edge joins its two corners in the middle faces of the two faces that
shared the edge. The middle faces fuse through the midpoints into tunnels: the
cube becomes 20/60/32 (24 triangles, 8 hexagons), genus 5.
"""

from __future__ import annotations

from .errors import DLFLError
from .mesh import Mesh

__all__ = ["sierpinsky"]


def sierpinsky(mesh: Mesh) -> list[int]:
    """TopMod's ``multiConnectMidpoints()`` (GUI CTRL+K), in place.

    Ids of the existing elements are kept; the midpoints and new edges and
    faces get new ids.

    Returns:
        The ids of the midpoint vertices, in the order of the old edges.

    Raises:
        DLFLError: the mesh has point-spheres or faces of fewer than three
            sides (a corner cut needs three); the mesh is unchanged.
    """
    _check_input(mesh)
    work = mesh.copy()
    old_vertices = set(work.vertex_ids().tolist())
    faces = work.face_ids().tolist()
    midpoints = [work.subdivide_edge(e)[0] for e in work.edge_ids().tolist()]
    for f in faces:
        _cut_old_corners(work, f, old_vertices)
    # corner of each midpoint in the two middle faces, found before any loop fuses them
    pairs = [_middle_corners(work, m, old_vertices) for m in midpoints]
    for c1, c2 in pairs:
        work.insert_edge(c1, c2)
    mesh.replace_with(work)
    return midpoints


def _check_input(mesh: Mesh) -> None:
    for f in mesh.face_ids().tolist():
        if mesh.face_size(f) < 3:
            raise DLFLError(
                f"sierpinsky needs faces of at least three sides; face {f} has "
                f"{mesh.face_size(f)}"
            )
    if any(mesh.is_point_sphere(v) for v in mesh.vertex_ids().tolist()):
        raise DLFLError("sierpinsky needs a mesh without point-spheres")


def _cut_old_corners(mesh: Mesh, face: int, old_vertices: set[int]) -> None:
    """Cut every corner of ``face`` at an old vertex; ``face`` keeps the middle."""
    for c in list(mesh.face_corners(face)):
        if mesh.corner_vertex(c) in old_vertices:
            mesh.insert_edge(mesh.corner_prev(c), mesh.corner_next(c))


def _middle_corners(mesh: Mesh, midpoint: int, old_vertices: set[int]) -> tuple[int, int]:
    """The midpoint's corners in the two middle faces: those with no old vertex."""
    found = [
        c for c in mesh.vertex_corners(midpoint)
        if not any(v in old_vertices for v in mesh.face_vertices(mesh.corner_face(c)))
    ]
    if len(found) != 2:
        raise DLFLError(f"midpoint {midpoint} does not lie on two middle faces")
    return found[0], found[1]
