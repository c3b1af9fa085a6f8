"""TopMod's cutting planes (``DLFLSculpting.cc``) and the side of a plane each vertex is on.

``performCutting`` and ``cutSelected{Vertices,Edges,Faces}`` fit one plane per
selected element, through the mean of points ``offset`` along edges:

* a vertex: the points along each of its edges; normal: the vertex normal (the
  normalised mean of its corners' normals);
* an edge: the points along every other edge at its two ends; normal: the
  normalised sum of its two faces' normals;
* a face: the points along every edge at its vertices that is not a side of the
  face; normal: the face normal.

Normals are TopMod's (:mod:`.normals`).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from ._vectors import unit
from .analysis import face_normal, face_points
from .errors import GeometryError
from .mesh import Mesh
from .normals import ring_normals

# a vertex within this many times the mesh's extent of a plane lies on it
ON_PLANE = 1e-9


class Plane(NamedTuple):
    """A cutting plane: ``point`` and unit ``normal``, both ``(3,)``; the part the
    normal points into is cut off. ``name`` says what it was fitted to."""

    point: np.ndarray
    normal: np.ndarray
    name: str


def vertex_normal(mesh: Mesh, vertex: int) -> np.ndarray:
    """``(3,)`` TopMod's vertex normal: the normalised mean of the normals of the
    vertex's corners, each in its own face (zero when they cancel)."""
    normals = []
    for c in mesh.vertex_corners(vertex):
        ring = [c]
        while (nxt := mesh.corner_next(ring[-1])) != c:
            ring.append(nxt)
        points = np.array([mesh.position(mesh.corner_vertex(r)) for r in ring])
        normals.append(ring_normals(points, np.arange(len(ring)), np.array([0, len(ring)]))
                       .corner[0])
    return unit(np.sum(normals, axis=0)[None])[0]


def _along(mesh: Mesh, vertex: int, edges: list[int], offset: float) -> list[np.ndarray]:
    """The points ``offset`` of the way along ``edges`` from ``vertex``."""
    p = mesh.position(vertex)
    out = []
    for e in edges:
        a, b = mesh.edge_vertices(e)
        far = mesh.position(b if a == vertex else a)
        # a weighted sum, not p + offset * (far - p): the difference of two points
        # near the float maximum overflows where the sum of their parts does not
        out.append((1.0 - offset) * p + offset * far)
    return out


def _plane(points: list[np.ndarray], normal: np.ndarray, name: str) -> Plane:
    """The plane through the mean of ``points`` square to ``normal``.

    Raises:
        GeometryError: no points, or no normal (it is zero).
    """
    if not points:
        raise GeometryError(f"{name} has no edge to fit its cutting plane through: "
                            "use placement='offset'")
    if not np.linalg.norm(normal) > 0.5:
        raise GeometryError(f"{name} has no normal (its faces have no area, or their normals "
                            "cancel): there is no cutting plane; use placement='offset'")
    # each point scaled first: a sum of coordinates near the float maximum overflows
    return Plane((np.asarray(points) / len(points)).sum(axis=0), normal, name)


def vertex_plane(mesh: Mesh, vertex: int, offset: float) -> Plane:
    """TopMod's plane for cutting ``vertex``.

    Raises:
        GeometryError: the vertex has no normal.
    """
    points = _along(mesh, vertex, mesh.vertex_edges(vertex), offset)
    return _plane(points, vertex_normal(mesh, vertex), f"vertex {vertex}")


def edge_plane(mesh: Mesh, edge: int, offset: float) -> Plane:
    """TopMod's plane for cutting ``edge`` (with its end vertices).

    Raises:
        GeometryError: its ends have no other edges, or its faces' normals cancel.
    """
    ends = mesh.edge_vertices(edge)
    points = [p for v in ends
              for p in _along(mesh, v, [e for e in mesh.vertex_edges(v) if e != edge], offset)]
    f1, f2 = mesh.edge_faces(edge)
    normal = unit((face_normal(mesh, f1) + face_normal(mesh, f2))[None])[0]
    return _plane(points, normal, f"edge {edge}")


def face_plane(mesh: Mesh, face: int, offset: float | None = None) -> Plane:
    """The plane through ``face`` (its centroid, its normal) for ``offset`` None,
    else TopMod's plane for cutting the face off.

    Raises:
        GeometryError: the face has no normal, or (with an offset) no edge leaves it.
    """
    normal = face_normal(mesh, face)
    if offset is None:
        return _plane([face_points(mesh, face).mean(axis=0)], normal, f"face {face}")
    sides = set(mesh.face_edges(face))
    points = [p for v in mesh.face_vertices(face)
              for p in _along(mesh, v, [e for e in mesh.vertex_edges(v) if e not in sides],
                              offset)]
    return _plane(points, normal, f"face {face}")


def sides(mesh: Mesh, plane: Plane) -> dict[int, int]:
    """Vertex id -> 1 beyond ``plane`` (where its normal points), -1 before it, 0
    on it: within :data:`ON_PLANE` times the mesh's extent, or of a millionth of
    its distance from the origin, where rounding is larger."""
    ids = mesh.vertex_ids().tolist()
    positions = np.array([mesh.position(v) for v in ids]).reshape(-1, 3)
    if not ids:
        return {}
    size = max(float(np.ptp(positions, axis=0).max()), 1e-6 * float(np.abs(positions).max()))
    distance = (positions - plane.point) @ plane.normal
    eps = ON_PLANE * size
    side = np.where(distance > eps, 1, np.where(distance < -eps, -1, 0))
    return dict(zip(ids, side.tolist(), strict=True))


def beyond(mesh: Mesh, side: dict[int, int], seeds: list[int] | None) -> set[int]:
    """The vertices beyond the plane (``side`` 1): all of them for ``seeds``
    None, else those joined to a seed beyond it through vertices beyond it."""
    if seeds is None:
        return {v for v, s in side.items() if s > 0}
    region = {v for v in seeds if side.get(v) == 1}
    todo = list(region)
    while todo:
        v = todo.pop()
        for c in mesh.vertex_corners(v):
            w = mesh.corner_vertex(mesh.corner_next(c))
            if side[w] == 1 and w not in region:
                region.add(w)
                todo.append(w)
    return region
