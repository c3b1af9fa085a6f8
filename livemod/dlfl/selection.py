"""Selection helpers for scripts: faces, edges and vertices picked by a rule.

Each returns a list of ids in increasing id order (loops and rings in walk
order). The TopMod counterparts are ``selectMatchingFaces`` (same size),
``selectMatchingEdges`` (same end valences), ``selectMatchingVertices``,
``selectFacesByArea`` (within 0.05), checkerboard (SHIFT+K), edge loop (SHIFT+L,
only through valence-4 vertices), edge ring (SHIFT+R) and face loop (SHIFT+P,
through quads).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from ._checks import finite_number, finite_vector, id_list, is_id
from ._vectors import unit
from .analysis import face_areas, face_normals
from .arrays import mesh_arrays
from .errors import InvalidArgumentError
from .mesh import Mesh

__all__ = [
    "checkerboard", "edge_loop", "edge_ring", "face_loop", "faces_by_area",
    "faces_by_normal", "faces_by_size", "faces_by_vertex_valence", "faces_where",
    "matching_edges", "matching_faces", "matching_vertices", "vertex_valences",
]


def faces_by_size(mesh: Mesh, sizes: int | Iterable[int]) -> list[int]:
    """Faces with ``sizes`` corners (one size or several); holes left out."""
    wanted = [int(sizes)] if is_id(sizes) else id_list(sizes, "sizes")
    a = mesh_arrays(mesh)
    keep = np.isin(a.face_sizes, wanted) & ~a.face_hole
    return a.face_ids[keep].tolist()


def vertex_valences(mesh: Mesh) -> dict[int, int]:
    """Vertex id -> valence, for every vertex."""
    a = mesh_arrays(mesh)
    valence = np.bincount(a.corner_vertex[a.corner_edge >= 0], minlength=len(a.vertex_ids))
    return dict(zip(a.vertex_ids.tolist(), valence.tolist(), strict=True))


def faces_by_vertex_valence(mesh: Mesh, valence: int, *, every: bool = True) -> list[int]:
    """Faces whose vertices all have ``valence`` (``every=False``: at least one does)."""
    a = mesh_arrays(mesh)
    val = np.bincount(a.corner_vertex[a.corner_edge >= 0], minlength=len(a.vertex_ids))
    hit = (val[a.corner_vertex] == valence).astype(np.int64)
    per_face = np.bincount(a.corner_face, weights=hit, minlength=len(a.face_ids))
    keep = per_face == a.face_sizes if every else per_face > 0
    return a.face_ids[keep & ~a.face_hole].tolist()


def faces_by_normal(mesh: Mesh, direction: Any, max_angle: float = 1.0) -> list[int]:
    """Faces whose normal lies within ``max_angle`` degrees of ``direction``.

    Raises:
        DLFLError: ``direction`` is not three finite numbers or is zero, or
            ``max_angle`` is not a finite number.
    """
    d = _direction(direction)
    angle = finite_number(max_angle, "max_angle")
    a = mesh_arrays(mesh)
    cosine = face_normals(a) @ d
    keep = (cosine >= np.cos(np.radians(angle)) - 1e-12) & ~a.face_hole
    return a.face_ids[keep].tolist()


def _direction(direction: Any) -> np.ndarray:
    """``(3,)`` unit vector along ``direction`` (three finite numbers, not all zero).

    Raises:
        DLFLError: anything else, naming ``direction``.
    """
    d = finite_vector(direction, "direction")
    if not np.abs(d).max() > 0.0:
        raise InvalidArgumentError("direction must not be zero")
    return unit(d[None])[0]  # brought into range first: (1e308, 1e308, 0) has a norm


def faces_where(mesh: Mesh, predicate: Callable[[int], bool]) -> list[int]:
    """Faces for which ``predicate(face_id)`` is true (holes left out)."""
    return [f for f in mesh.face_ids().tolist() if not mesh.is_hole(f) and predicate(f)]


def matching_faces(mesh: Mesh, face: int) -> list[int]:
    """TopMod's ``selectMatchingFaces``: every face of the same size as ``face``."""
    return faces_by_size(mesh, mesh.face_size(face))


def matching_edges(mesh: Mesh, edge: int) -> list[int]:
    """TopMod's ``selectMatchingEdges``: edges whose end valences equal ``edge``'s
    (in either order).

    Raises:
        DLFLError: ``edge`` is not a live edge.
    """
    mesh.edge_vertices(edge)  # raises naming the edge (deleted or never made)
    a = mesh_arrays(mesh)
    valence = np.bincount(a.corner_vertex[a.corner_edge >= 0], minlength=len(a.vertex_ids))
    ends = np.sort(valence[a.edge_vertices], axis=1)  # (E, 2): either order matches
    key = ends[int(np.searchsorted(a.edge_ids, edge))]
    return a.edge_ids[(ends == key).all(axis=1)].tolist()


def matching_vertices(mesh: Mesh, vertex: int) -> list[int]:
    """TopMod's ``selectMatchingVertices``: vertices of the same valence."""
    target = mesh.valence(vertex)  # raises DLFLError for a vertex that is gone
    return [v for v, k in vertex_valences(mesh).items() if k == target]


def faces_by_area(mesh: Mesh, face: int, delta: float = 0.05) -> list[int]:
    """TopMod's ``selectFacesByArea``: faces whose area is within ``delta`` of ``face``'s.

    Raises:
        DLFLError: ``face`` is not a live face, or ``delta`` is not a finite number.
    """
    delta = finite_number(delta, "delta")
    mesh.face_size(face)  # raises naming the face (deleted or never made)
    a = mesh_arrays(mesh)
    areas = face_areas(a)
    target = areas[int(np.searchsorted(a.face_ids, face))]
    keep = (np.abs(areas - target) <= delta) & ~a.face_hole
    return a.face_ids[keep].tolist()


def checkerboard(mesh: Mesh, face: int) -> list[int]:
    """TopMod's checkerboard selection (SHIFT+K): from ``face``, spread to faces that
    share exactly one vertex and no edge with a selected face. On a quad grid or
    a cube subdivided into quads this picks every other face.

    Raises:
        DLFLError: ``face`` is not a live face (the message says whether it was
            deleted).
    """
    mesh.face_size(face)  # raises naming the face
    chosen = {face}
    todo = [face]
    while todo:
        f = todo.pop()
        for g in _vertex_only_neighbours(mesh, f):
            if g not in chosen and not mesh.is_hole(g):
                chosen.add(g)
                todo.append(g)
    return sorted(chosen)


def _vertex_only_neighbours(mesh: Mesh, face: int) -> set[int]:
    """Faces meeting ``face`` at exactly one vertex and along no edge."""
    edge_neighbours = {g for e in mesh.face_edges(face) for g in mesh.edge_faces(e)}
    counts: dict[int, int] = {}
    for v in set(mesh.face_vertices(face)):
        for g in set(mesh.vertex_faces(v)):
            counts[g] = counts.get(g, 0) + 1
    return {g for g, k in counts.items() if k == 1 and g not in edge_neighbours}


def edge_loop(mesh: Mesh, edge: int) -> list[int]:
    """The edge loop through ``edge`` (SHIFT+L): at every valence-4 vertex the walk
    goes on along the opposite edge; it stops at other vertices or when closed."""
    loop = [edge]
    for end in mesh.edge_vertices(edge):
        loop = _walk_loop(mesh, edge, end, loop)
        if len(loop) > 1 and loop[0] == loop[-1]:
            return loop[:-1]
        loop = loop[::-1]
    return loop


def _walk_loop(mesh: Mesh, edge: int, vertex: int, loop: list[int]) -> list[int]:
    """Extend ``loop`` (ending at ``edge``) past ``vertex`` while vertices have valence 4."""
    seen = set(loop)
    while mesh.valence(vertex) == 4:
        around = mesh.vertex_edges(vertex)
        if around.count(edge) != 1:
            break
        edge = around[(around.index(edge) + 2) % 4]
        if edge in seen:
            if edge == loop[0]:
                loop.append(edge)
            break
        loop.append(edge)
        seen.add(edge)
        u, w = mesh.edge_vertices(edge)
        vertex = w if u == vertex else u
    return loop


def edge_ring(mesh: Mesh, edge: int) -> list[int]:
    """The edge ring through ``edge`` (SHIFT+R): across every quad to the opposite
    edge, both ways, stopping at faces that are not quads."""
    return _ring(mesh, edge)[0]


def face_loop(mesh: Mesh, edge: int) -> list[int]:
    """The face loop across ``edge`` (SHIFT+P): the quads its edge ring crosses."""
    return _ring(mesh, edge)[1]


def _ring(mesh: Mesh, edge: int) -> tuple[list[int], list[int]]:
    edges, faces = [edge], []
    for face in dict.fromkeys(mesh.edge_faces(edge)):
        e = edge
        while mesh.face_size(face) == 4 and face not in faces and not mesh.is_hole(face):
            faces.append(face)
            ring = mesh.face_edges(face)
            e = ring[(ring.index(e) + 2) % 4]
            if e in edges:
                return edges, faces
            edges.append(e)
            f1, f2 = mesh.edge_faces(e)
            face = f2 if f1 == face else f1
        edges = edges[::-1]
        faces = faces[::-1]
    return edges, faces
