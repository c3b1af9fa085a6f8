"""Geometry-only operations (smooth, planarize, spheralize) and TopMod's cleanup helpers.

The geometry operations move vertices and never change the topology (the cube
stays 8/12/6); they are vectorized over :func:`mesh_arrays`. The cleanup helpers
(``edgeCleanup``, ``cleanup2gons``, ``cleanupWingedVertices``,
``splitValence2Vertices``) and TopMod's edge operations ``trisectEdge`` and
``spliceCorners`` change the topology with the minimal operators, in place,
keeping the ids of everything they do not delete.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ._checks import finite_number, first_not_finite, flag, id_list, whole_count
from ._vectors import centroid, lengths, range_exponent, scaled_mean
from ._vectors import unit as _unit
from .analysis import face_centroids, face_normals
from .arrays import MeshArrays, mesh_arrays
from .errors import GeometryError, InvalidArgumentError
from .mesh import Mesh

__all__ = [
    "cleanup_2gons", "cleanup_winged_vertices", "edge_cleanup", "mesh_smooth", "planarize",
    "spheralize", "split_valence2_vertices", "trisect_edge", "splice_corners",
]


def _face_means(a: MeshArrays, per_face: np.ndarray) -> np.ndarray:
    """``(V, 3)`` mean over the corners at each vertex of a per-face ``(F, 3)`` value."""
    count = np.bincount(a.corner_vertex, minlength=len(a.vertex_ids))
    return scaled_mean(per_face[a.corner_face], a.corner_vertex, len(a.vertex_ids), count)


def _write(mesh: Mesh, a: MeshArrays, positions: np.ndarray, what: str) -> None:
    """Set the ``(V, 3)`` ``positions`` of ``a``'s vertices.

    Raises:
        DLFLError: a coordinate overflowed (naming the first such vertex and
            ``what`` moved it); the mesh is unchanged.
    """
    i = first_not_finite(positions)
    if i is not None:
        raise GeometryError(f"{what} would move vertex {int(a.vertex_ids[i])} to "
                            f"{positions[i].tolist()}: its numbers overflow; the mesh is unchanged")
    mesh.set_positions(a.vertex_ids, positions)


def mesh_smooth(mesh: Mesh, iterations: int = 1) -> None:
    """TopMod's ``meshsmooth()`` (GUI CTRL+M): tangential relaxation.

    Each vertex moves to the mean of its faces' centroids, minus the part of
    that move along the normalised mean of its faces' normals, so the surface
    relaxes without shrinking much. TopMod never reset its normal accumulator
    between vertices (QUIRK); livemod does.

    Raises:
        DLFLError: ``iterations`` not a whole number >= 0, or positions that
            overflow; the mesh is unchanged.
    """
    a = mesh_arrays(mesh)
    # smoothing commutes with scaling: a mesh out of the band is smoothed scaled
    # by a power of two (exact), where the moves of coordinates near the float
    # maximum cannot overflow, and scaled back
    k = range_exponent(a.positions)
    positions = np.ldexp(a.positions, -k) if k else a.positions
    for _ in range(whole_count(iterations, "iterations", least=0, each=0)):
        # the topology never changes: only the positions of the arrays move on
        current = replace(a, positions=positions)
        average = _face_means(current, face_centroids(current))
        normal = _unit(_face_means(current, face_normals(current)))
        move = average - positions
        move -= np.einsum("ij,ij->i", move, normal)[:, None] * normal
        positions = positions + move
    with np.errstate(over="ignore"):  # refused by _write
        positions = np.ldexp(positions, k) if k else positions
    # one write at the end: an overflow in a later iteration moves nothing
    _write(mesh, a, positions, "meshsmooth")


def planarize(mesh: Mesh, steps: int = 100) -> None:
    """TopMod's ``planarize()`` (GUI CTRL+P): pull every vertex toward the planes
    of its faces, ``steps`` times, with a weight falling from 0.3 by 0.3/110 a step.

    Each step moves a vertex by the weight times the mean of its offsets to the
    planes (through the face centroid, along the face normal) of its faces.
    Faces flatten; the topology is unchanged.

    Raises:
        DLFLError: ``steps`` not a whole number >= 0, or positions that overflow;
            the mesh is unchanged.
    """
    total = whole_count(steps, "steps", least=0, each=0)
    a = mesh_arrays(mesh)
    positions = a.positions.copy()
    for i in range(total):
        weight = 0.3 - i * 0.3 / 110
        current = replace(a, positions=positions)
        normals = face_normals(current)[a.corner_face]
        centres = face_centroids(current)[a.corner_face]
        p = positions[a.corner_vertex]
        offset = np.einsum("ij,ij->i", centres - p, normals)[:, None] * normals
        sums = np.zeros_like(positions)
        np.add.at(sums, a.corner_vertex, offset)
        count = np.bincount(a.corner_vertex, minlength=len(positions))
        positions = positions + weight * sums / np.maximum(count, 1)[:, None]
    _write(mesh, a, positions, "planarize")


def spheralize(mesh: Mesh) -> None:
    """TopMod's ``spheralize()`` (GUI CTRL+H): ``v = normalize(v - centroid)``.

    Every vertex goes to the unit sphere around the vertex centroid, which then
    sits at the origin (TopMod does not move it back). A vertex at the centroid
    itself stays there.
    """
    a = mesh_arrays(mesh)
    if len(a.positions) == 0:
        return
    centre = centroid(a.positions)
    with np.errstate(over="ignore", invalid="ignore"):  # refused by _write
        moved = a.positions - centre
    _write(mesh, a, _unit(moved), "spheralize")


def edge_cleanup(mesh: Mesh, edges: list[int] | None = None) -> int:
    """TopMod's ``edgeCleanup``: delete every edge (or every one of ``edges`` still
    there, in order) whose two faces are coplanar (``|n1 . n2 - 1| < 1e-5``) or
    are one face. Returns the number deleted.

    Raises:
        DLFLError: ``edges`` is not a list of ids (integers); nothing is deleted.
    """
    todo = mesh.edge_ids().tolist() if edges is None else id_list(edges, "edges")
    deleted = 0
    for e in todo:
        if not mesh.has_edge(e):
            continue
        f1, f2 = mesh.edge_faces(e)
        if f1 == f2 or _coplanar(mesh, f1, f2):
            mesh.delete_edge(e)
            deleted += 1
    return deleted


def _coplanar(mesh: Mesh, f1: int, f2: int) -> bool:
    from .analysis import face_normal

    n1, n2 = face_normal(mesh, f1), face_normal(mesh, f2)
    return bool(abs(float(n1 @ n2) - 1.0) < 1e-5)


def cleanup_2gons(mesh: Mesh) -> int:
    """TopMod's ``cleanup2gons``: delete one edge of every 2-gon. Returns the count.

    The deletion merges the faces on the edge's two sides. A lone edge (a
    component of two vertices whose one face runs along both sides of the
    edge) is kept: deleting its edge splits that face instead of merging two,
    which TopMod's comment rules out, and its cleanup would remove the whole
    component.
    """
    deleted = 0
    for f in mesh.face_ids().tolist():
        if not mesh.has_face(f) or mesh.face_size(f) != 2:
            continue
        edges = mesh.face_edges(f)
        if edges[0] != edges[1]:
            mesh.delete_edge(edges[0])
            deleted += 1
    return deleted


def cleanup_winged_vertices(mesh: Mesh) -> int:
    """TopMod's ``cleanupWingedVertices``: remove every valence-2 vertex.

    For each, an edge joins its two neighbours across one of its faces, then its
    two edges are deleted (the vertex goes with them). A vertex both of whose
    faces are 2-gons is kept: its two neighbours are one corner there, so no edge
    can join them (TopMod's insert then fails). Returns the count removed.
    """
    removed = 0
    for v in mesh.vertex_ids().tolist():
        if not mesh.has_vertex(v) or mesh.valence(v) != 2:
            continue
        # earlier removals can shrink a face to a 2-gon: use a face with room
        wide = [c for c in mesh.vertex_corners(v) if mesh.face_size(mesh.corner_face(c)) > 2]
        if not wide:
            continue
        c = wide[0]
        mesh.insert_edge(mesh.corner_prev(c), mesh.corner_next(c))
        for e in mesh.vertex_edges(v):
            if mesh.has_edge(e):
                mesh.delete_edge(e)
        removed += 1
    return removed


def split_valence2_vertices(mesh: Mesh, offset: float = -0.1) -> list[int]:
    """TopMod's ``splitValence2Vertices(offset=-0.1)``: split every valence-2 vertex.

    The vertex keeps its first edge ``e1``; its second edge ``e2`` is subdivided,
    so the new vertex sits between it and ``e2``'s far end. The pair is then pushed
    apart across the corner, each toward its own neighbour: with ``d1, d2`` the
    unit directions of ``e1, e2`` away from the vertex at ``o``, the vertex moves
    to ``o + s1 normalize(d1 - d2)`` and the new one to ``o + s2 normalize(d2 - d1)``,
    where ``s1 = s2 = offset``, or ``s1, s2`` are ``0.1`` times the lengths of
    ``e1, e2`` when ``offset <= 0``. On a straight edge the two stay on the line,
    in order; at a bent corner they move along the chord of their neighbours.
    Vertices of valence 2 are taken as they stand before any split.

    Returns:
        The ids of the new vertices.

    Raises:
        DLFLError: ``offset`` is not a finite number, or a moved vertex would
            overflow to infinity; the mesh is unchanged.
    """
    offset = finite_number(offset, "offset")
    # each split reads positions earlier splits moved, so an overflow shows only
    # part-way: split a copy and keep it once every split has succeeded
    work = mesh.copy()
    new_vertices = []
    for v in work.vertex_ids().tolist():
        if work.valence(v) != 2:
            continue
        e1, e2 = work.vertex_edges(v)[:2]
        origin = work.position(v)
        d1, d2 = (_direction(work, e, v) for e in (e1, e2))
        s1, s2 = ((offset, offset) if offset > 0
                  else (0.1 * _length(work, e1), 0.1 * _length(work, e2)))
        new = work.subdivide_edge(e2)[0]  # between v and e2's far end
        work.set_position(v, _pushed(v, origin, s1, d1 - d2))
        work.set_position(new, _pushed(v, origin, s2, d2 - d1))
        new_vertices.append(new)
    mesh.replace_with(work)
    return new_vertices


def _pushed(v: int, origin: np.ndarray, size: float, toward: np.ndarray) -> np.ndarray:
    """``(3,)`` ``origin + size * normalize(toward)``, both ``(3,)``.

    Raises:
        DLFLError: a coordinate overflows (splitting vertex ``v``).
    """
    with np.errstate(over="ignore", invalid="ignore"):  # refused just below
        point = origin + size * _unit(toward)
    if not np.isfinite(point).all():
        raise GeometryError(f"splitting valence-2 vertex {v} by {size} would put a vertex at "
                            f"{point.tolist()}, which is not finite: its numbers overflow; use a "
                            "smaller offset; the mesh is unchanged")
    return point


def _direction(mesh: Mesh, edge: int, start: int) -> np.ndarray:
    """``(3,)`` unit direction of ``edge`` away from vertex ``start`` (NaN when the
    difference overflows, which :func:`_pushed` refuses)."""
    a, b = mesh.edge_vertices(edge)
    other = b if a == start else a
    with np.errstate(over="ignore", invalid="ignore"):
        return _unit(mesh.position(other) - mesh.position(start))


def _length(mesh: Mesh, edge: int) -> float:
    """Length of ``edge``, inf beyond the float range."""
    a, b = mesh.edge_vertices(edge)
    with np.errstate(over="ignore"):  # inf: refused by _pushed
        return float(lengths((mesh.position(a) - mesh.position(b))[None])[0])


def trisect_edge(mesh: Mesh, edge: int, num: float, scale: bool) -> list[int]:
    """TopMod's ``trisectEdge(E, num, scale)``: split ``edge`` in three; V+2, E+2.

    With ``p0, p1`` the ends (the vertices of sides ``c0`` and ``c1``) and ``m``
    their midpoint, the new points are ``num p0 + (1 - num) m`` and
    ``num p1 + (1 - num) m`` when ``scale`` is True (``num`` clamped to
    [0.01, 0.99]), else ``num`` from ``p0`` and from ``p1`` along the edge (``num``
    clamped to [0.01, length/2 - 0.01]). The edge keeps its id as the part from
    ``p0``; the middle and last parts are new edges.

    Returns:
        The two new vertex ids, the one near ``p0`` first.

    Raises:
        DLFLError: ``edge`` is not live, ``num`` is not a finite number,
            ``scale`` is not a flag (True, False, 0 or 1), or an offset
            trisection of an edge no longer than 0.04 (no offset fits); the mesh
            is unchanged.
    """
    num = finite_number(num, "num")
    scale = flag(scale, "scale")  # True: num is a scale factor; False: an offset
    p0, p1 = (mesh.position(v) for v in mesh.edge_vertices(edge))
    points = _scaled_trisection(p0, p1, num) if scale else _offset_trisection(edge, p0, p1, num)
    if first_not_finite(points) is not None:  # rounding at the float maximum
        raise GeometryError(f"trisecting edge {edge} would put a vertex at {points.tolist()}: its "
                            "numbers overflow; the mesh is unchanged")
    new = mesh.subdivide_edge(edge, 3)
    mesh.set_positions(new, points)
    return new


def _scaled_trisection(p0: np.ndarray, p1: np.ndarray, num: float) -> np.ndarray:
    """``(2, 3)`` points ``t p + (1 - t) m`` for ``p`` = ``p0``, ``p1`` (``(3,)``
    each), ``m`` their midpoint and ``t`` = ``num`` clamped to [0.01, 0.99]."""
    t = min(max(num, 0.01), 0.99)
    mid = p0 * 0.5 + p1 * 0.5  # halves first: the sum of far-apart points can overflow
    return np.array([t * p0 + (1 - t) * mid, t * p1 + (1 - t) * mid])


def _offset_trisection(edge: int, p0: np.ndarray, p1: np.ndarray, num: float) -> np.ndarray:
    """``(2, 3)`` points ``num`` from ``p0`` and from ``p1`` (``(3,)`` each, the ends
    of ``edge``) toward the other end, ``num`` clamped to [0.01, length/2 - 0.01].

    Raises:
        DLFLError: the edge is no longer than 0.04, so that range is empty.
    """
    half = p1 * 0.5 - p0 * 0.5  # p1 - p0 itself can overflow
    length = 2.0 * float(lengths(half[None])[0])
    if length <= 0.04:
        raise GeometryError(f"edge {edge} is {length:.3g} long: an offset trisection needs an edge "
                            "longer than 0.04 (offsets are clamped to [0.01, length/2 - 0.01]); "
                            "use scale=True; the mesh is unchanged")
    offset = min(max(num, 0.01), length / 2.0 - 0.01)
    step = offset * _unit(half[None])[0]
    return np.array([p0 + step, p1 - step])


def splice_corners(mesh: Mesh, corner1: int, corner2: int) -> int:
    """TopMod's ``spliceCorners``: insert an edge between two corners, then collapse
    it, so the two vertices become one at their midpoint.

    Corners of one face split it and the halves beside the new edge close up
    (their 2-gons are cleaned up, as by :meth:`Mesh.collapse_edge`); corners of
    two faces merge those faces first.

    Returns:
        The surviving vertex id: ``corner1``'s, unless only ``corner1`` is a
        point-sphere's (the new edge dangles from it, and the other end stays).

    Raises:
        DLFLError: a corner id that is not live, or both corners at one vertex
            (nothing to splice); the mesh is unchanged.
    """
    v1, v2 = mesh.corner_vertex(corner1), mesh.corner_vertex(corner2)
    if v1 == v2:
        raise InvalidArgumentError(f"corners {corner1} and {corner2} are both at vertex {v1}: "
                                   "splicing needs corners at two different vertices")
    return mesh.collapse_edge(mesh.insert_edge(corner1, corner2))
