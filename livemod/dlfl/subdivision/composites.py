"""GUI composite schemes (dual, scheme, dual) computed in one step.

A dual, a scheme and a dual again give a mesh whose elements are the mesh's own
vertices, edges, faces and corners: the final dual's vertices are the middle
scheme's faces and its faces the middle scheme's vertices. Each function here
lays out that final mesh over the old corners (mates computed directly) and puts
each vertex at the centroid of its face of the middle step, worked out from the
first dual's geometry (its vertices are the face centroids; its face of vertex
v has the mean ``Cv`` of v's face centroids as centroid). Same meshes as the
three steps up to the order of elements, positions to rounding; no face is a
hole (a dual makes none); point-spheres survive.

Conventions (``t`` the mesh): the first dual's corner of corner c sits at
``face(c)``'s centroid, in v = ``cv(c)``'s ring, its edge crossing the edge of
``prev c``; the next corner of that ring is ``vprev(c) = mate(prev c)``.
"""

from __future__ import annotations

import numpy as np

from ..mesh import Mesh
from ._layout import (
    Topology,
    build_paired,
    check_number,
    cos_weights,
    no_origin,
    read_topology,
    ring_sums,
    ring_weighted,
    rows,
    vertex_mean,
)
from ._sizes import check_steps
from .convert import HONEYCOMB_ALPHA, root4_layout
from .smooth import corner_cut_layout


def _vertex_centres(t: Topology, cen: np.ndarray) -> np.ndarray:
    """``(V, 3)`` ``Cv``: the mean of each vertex's face centroids (one per corner),
    the centroid of the first dual's face of v. ``cen``: ``(F, 3)`` centroids."""
    return vertex_mean(t, rows(cen, t.face))


def twelve_six_four(mesh: Mesh, *, scale: float = 0.7, max_faces: int | None = None) -> None:
    """GUI "12.6.4" (TopMod: dual, dual-12.6.4(sf), dual), in one step.

    The result has a vertex per old vertex, edge and face, and two triangles per
    old corner c (vertex, midpoint of c's edge, face; vertex, face, midpoint of
    the previous edge). Positions: the centroids of dual-12.6.4's faces on the
    dual: ``Cv`` per vertex, per edge ``(1 - s) mean(Cv of its ends) + s
    mean(its faces' centroids)``, per face ``(1 - s) mean(Cv of its corners) + s
    (2 centroid + mean(centroids across its edges)) / 3`` (``s = |scale|``; 1
    when it is 0 or 1, as dual-12.6.4 then does not scale). Cube: 26/72/48.

    Raises:
        DLFLError: a bad ``scale``, or the face budget.
    """
    scale = abs(check_number("scale", scale))
    check_steps(mesh, ("dual", "dual-12.6.4", "dual"), max_faces)
    t = read_topology(mesh)
    s = 1.0 if scale in (0.0, 1.0) else scale
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        positions = _points_1264(t, s)
    verts, mates = _triangles_1264(t)
    build_paired(mesh, t, positions, verts, mates, np.full(2 * t.nc, 3, dtype=np.int64),
                 no_origin(2 * t.nc))


def _points_1264(t: Topology, s: float) -> np.ndarray:
    """``(V + E + F, 3)``: the vertex, edge and face points of :func:`twelve_six_four`."""
    cen = t.centroids()
    centre = _vertex_centres(t, cen)
    faces = t.face[t.edge_corners]
    edge_points = 0.5 * (rows(cen, faces[:, 0]) + rows(cen, faces[:, 1]))
    sizes = np.maximum(t.sizes, 1)[:, None]
    across = ring_sums(t.offsets, cen, t.face[t.mate]) / sizes
    face_points = (2.0 * cen + across) / 3.0
    if s != 1.0:
        ends = t.cv[t.edge_corners]
        edge_points *= s
        edge_points += (0.5 * (1 - s)) * (rows(centre, ends[:, 0]) + rows(centre, ends[:, 1]))
        face_points *= s
        face_points += (1 - s) * (ring_sums(t.offsets, centre, t.cv) / sizes)
    return np.concatenate([centre, edge_points, face_points])


def _triangles_1264(t: Topology) -> tuple[np.ndarray, np.ndarray]:
    """Two triangles per corner c, mates computed directly: at 6c (vertex, edge
    point of c, face point) and at 6c + 3 (vertex, face point, edge point of prev c).

    Returns the ``(6C,)`` vertex and mate of every new corner.
    """
    nxt, prv, mate, nc = t.nxt, t.prv, t.mate, t.nc
    edge_point, face_point = t.nv + t.edge, t.nv + t.ne + t.face
    verts = np.empty((nc, 6), dtype=np.int64)
    verts[:, 0] = verts[:, 3] = t.cv
    verts[:, 1] = edge_point
    verts[:, 2] = verts[:, 4] = face_point
    verts[:, 5] = edge_point[prv]
    six = 6 * np.arange(nc)
    mates = np.empty((nc, 6), dtype=np.int64)
    mates[:, 0] = 6 * nxt[mate] + 5
    mates[:, 1] = 6 * nxt + 4
    mates[:, 2] = six + 3
    mates[:, 3] = six + 2
    mates[:, 4] = 6 * prv + 1
    mates[:, 5] = 6 * mate[prv]
    return verts.ravel(), mates.ravel()


def dual_pentagon_preserving(mesh: Mesh, *, scale: float = 0.75,
                             max_faces: int | None = None) -> None:
    """GUI "Dual Pentagon Preserving" (TopMod: dual, pentagon-preserve(sf), dual),
    in one step.

    The result has a vertex per old vertex (at ``Cv``) and per old corner c (at
    the centroid of pentagon-preserve's pentagon of c on the dual), and per old
    face the polygon of its corners' points, per old edge the quad of the points
    of its four corners, per old corner c the triangle (vertex, c, vprev(c)).
    Cube: 32/72/42 (24 triangles, 18 quads).

    Raises:
        DLFLError: a bad ``scale``, or the face budget.
    """
    scale = check_number("scale", scale)
    check_steps(mesh, ("dual", "pentagon-preserve", "dual"), max_faces)
    t = read_topology(mesh)
    cen = t.centroids()
    centre = _vertex_centres(t, cen)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        points = _pentagon_points(t, cen, centre, scale)
    positions = np.concatenate([centre, points])
    build_paired(mesh, t, positions, *_dual_pentagon_layout(t))


def _pentagon_points(t: Topology, cen: np.ndarray, centre: np.ndarray,
                     scale: float) -> np.ndarray:
    """``(C, 3)``: per corner c, the centroid of pentagon-preserve's pentagon of c
    on the dual: the dual's vertex (face c's centroid), the midpoints m of the
    dual's edges across the edges of prev c and c, and their copies scaled about
    ``Cv``, summed in the pentagon's order."""
    faces = t.face[t.edge_corners]
    mids = rows(0.5 * (rows(cen, faces[:, 0]) + rows(cen, faces[:, 1])), t.edge)
    c_v = rows(centre, t.cv)
    mids_prev = rows(mids, t.prv)
    out = rows(cen, t.face)
    out += mids_prev
    out += c_v + scale * (mids_prev - c_v)
    out += c_v + scale * (mids - c_v)
    out += mids
    out /= 5.0
    return out


def _dual_pentagon_layout(t: Topology) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                  np.ndarray]:
    """:func:`dual_pentagon_preserving`'s corners, mates computed directly.

    Points: vertices, then corner c's at V + c. Layout: face polygons (corner c
    at c), edge quads (edge k at C + 4k: next a, a, next b, b for its sides a, b),
    corner triangles (at 3C + 3c: vertex, c, vprev(c)).
    Returns the new corners' vertices and mates, the face sizes and origins.
    """
    nc, ne, v, c = t.nc, t.ne, t.nv, np.arange(t.nc)
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    na, nb, prv, mate = t.nxt[a], t.nxt[b], t.prv, t.mate
    vprev = mate[prv]
    is_a = a[t.edge] == c
    tri = 3 * nc
    verts = np.concatenate([v + c, (v + np.stack([na, a, nb, b], axis=1)).ravel(),
                            np.stack([t.cv, v + c, v + vprev], axis=1).ravel()])
    quad_mate = np.stack([a, tri + 3 * nb + 1, b, tri + 3 * na + 1], axis=1)
    tri_mate = np.stack([tri + 3 * t.nxt[mate] + 2,
                         nc + 4 * t.edge[prv] + np.where(is_a[prv], 3, 1),
                         tri + 3 * vprev], axis=1)
    mates = np.concatenate([nc + 4 * t.edge + np.where(is_a, 0, 2), quad_mate.ravel(),
                            tri_mate.ravel()])
    sizes = np.concatenate([t.sizes, np.full(ne, 4, dtype=np.int64),
                            np.full(nc, 3, dtype=np.int64)])
    return verts, mates, sizes, no_origin(t.nf + ne + nc)


def dual_loop(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """GUI "Dual Loop Subdivision" (TopMod: dual, loop, dual), in one step.

    The result has :func:`root4`'s topology: a point per old vertex (the mean of
    Loop's edge points on the dual around it) and per old corner c (the
    centroid of Loop's corner triangle of c on the dual: the dual's vertex of
    face c, smoothed, and the edge points across the edges of prev c and c).
    Cube: 32/48/18 (6 quads, 12 hexagons).

    Raises:
        DLFLError: the face budget.
    """
    check_steps(mesh, ("dual", "loop", "dual"), max_faces)
    t = read_topology(mesh)
    cen = t.centroids()
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        edge_points = rows(_loop_edge_points_on_dual(t, cen), t.edge)
        corner_points = rows(_loop_vertices_on_dual(t, cen), t.face)
        corner_points += rows(edge_points, t.prv)
        corner_points += edge_points
        corner_points /= 3.0
    centre = vertex_mean(t, edge_points)
    verts, mates, sizes, _ = root4_layout(t)
    build_paired(mesh, t, np.concatenate([centre, corner_points]), verts, mates, sizes,
                 no_origin(len(sizes)))


def _loop_vertices_on_dual(t: Topology, cen: np.ndarray) -> np.ndarray:
    """``(F, 3)`` Loop's vertex points on the dual: the dual's vertex of face f has
    valence ``size(f)`` and the centroids across f's edges as neighbours."""
    n = np.maximum(t.sizes, 1).astype(np.float64)
    beta = (0.625 - (0.375 + 0.25 * np.cos(2 * np.pi / n)) ** 2) / n
    sums = ring_sums(t.offsets, cen, t.face[t.mate])
    return (1 - n * beta)[:, None] * cen + beta[:, None] * sums


def _loop_edge_points_on_dual(t: Topology, cen: np.ndarray) -> np.ndarray:
    """``(E, 3)`` Loop's edge points on the dual, for the dual's edge across each
    edge (sides a, b): its ends are faces a and b; the wings are the faces across
    the edges next to a and b (on triangles, all valences 3, the opposite ones)."""
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    face, mate, nxt, prv = t.face, t.mate, t.nxt, t.prv
    ends = rows(cen, face[a]) + rows(cen, face[b])
    if len(t.valence) and t.valence.min() == t.valence.max() == 3:
        opposite = rows(cen, face[mate[nxt[a]]]) + rows(cen, face[mate[nxt[b]]])
        return 0.375 * ends + 0.125 * opposite
    wings = rows(cen, face[mate[nxt[a]]]) + rows(cen, face[mate[prv[b]]])
    wings += rows(cen, face[mate[nxt[b]]])
    wings += rows(cen, face[mate[prv[a]]])
    return 0.375 * ends + 0.0625 * wings


def _honeycomb_on_dual(t: Topology, values: np.ndarray) -> np.ndarray:
    """``(C, 3)``: honeycomb's per-corner weights (as :func:`honeycomb` and
    :func:`root4` apply them) over the dual's faces, the vertex rings; ``values``
    ``(C, 3)`` holds the dual's per-corner values at the old corners."""
    order, offsets = t.vertex_rings()
    out = np.empty_like(values)
    out[order] = ring_weighted(offsets, rows(values, order),
                               lambda n: cos_weights(n, HONEYCOMB_ALPHA + 1.25 / n))
    return out


def root3(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """GUI "Root-3" (TopMod: dual, honeycomb, dual), in one step.

    The result has :func:`sqrt3`'s topology (per old corner c the triangle of
    its vertex and the faces on both sides of the edge of prev c): a point per
    old vertex (``Cv``) and per old face (the centroid of honeycomb's polygon of
    the dual's vertex of f: the honeycomb points of f's corners and of the
    corners after their mates). Cube: 14/36/24 triangles.

    Raises:
        DLFLError: the face budget.
    """
    check_steps(mesh, ("dual", "honeycomb", "dual"), max_faces)
    t = read_topology(mesh)
    cen = t.centroids()
    faces = t.face[t.edge_corners]
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        mids = 0.5 * (rows(cen, faces[:, 0]) + rows(cen, faces[:, 1]))
        points = _honeycomb_on_dual(t, rows(mids, t.edge[t.prv]))
        around = ring_sums(t.offsets, points)
        around += ring_sums(t.offsets, points, t.nxt[t.mate])
        around /= 2.0 * np.maximum(t.sizes, 1)[:, None]
    positions = np.concatenate([_vertex_centres(t, cen), around])
    verts, mates = _root3_triangles(t)
    build_paired(mesh, t, positions, verts, mates, np.full(t.nc, 3, dtype=np.int64),
                 no_origin(t.nc))


def _root3_triangles(t: Topology) -> tuple[np.ndarray, np.ndarray]:
    """One triangle per corner c at 3c (vertex, face c, face vprev(c)), mates
    computed directly. Returns the ``(3C,)`` vertex and mate of every new corner."""
    nxt, mate, vprev = t.nxt, t.mate, t.vprev
    verts = np.empty((t.nc, 3), dtype=np.int64)
    verts[:, 0] = t.cv
    verts[:, 1] = t.nv + t.face
    verts[:, 2] = verts[:, 1][vprev]
    mates = np.empty((t.nc, 3), dtype=np.int64)
    mates[:, 0] = 3 * nxt[mate] + 2
    mates[:, 1] = 3 * nxt[vprev] + 1
    mates[:, 2] = 3 * vprev
    return verts.ravel(), mates.ravel()


def six_preserving_loop_style(mesh: Mesh, *, weight: float = 0.0, twist: float = 0.0,
                              max_faces: int | None = None) -> None:
    """GUI six-preservation "Loop Style" (TopMod: dual, root4(a, twist), dual), in
    one step.

    The result has Loop's topology (a triangle per old corner, the polygon of
    its edges' points per old face): a point per old vertex (``Cv``) and per old
    edge (the centroid of root4's hexagon on the dual: the dual's vertices of
    its two faces, moved by ``weight``, and root4's inner points of its four
    corners). Cube: 20/48/30.

    Raises:
        DLFLError: a bad option value, or the face budget.
    """
    weight = check_number("weight", weight)
    twist = check_number("twist", twist)
    check_steps(mesh, ("dual", "root4", "dual"), max_faces)
    t = read_topology(mesh)
    cen = t.centroids()
    p = rows(cen, t.face)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        inner = _honeycomb_on_dual(t, (1 - twist) * p + twist * rows(p, t.vprev))
        around = ring_sums(t.offsets, inner) / np.maximum(t.sizes, 1)[:, None]
        moved = (1 - weight) * cen + weight * around
        hexagons = _hexagon_centres(t, moved, inner)
    positions = np.concatenate([_vertex_centres(t, cen), hexagons])
    verts, mates, sizes = corner_cut_layout(t)
    build_paired(mesh, t, positions, verts, mates, sizes, no_origin(len(sizes)))


def _hexagon_centres(t: Topology, moved: np.ndarray, inner: np.ndarray) -> np.ndarray:
    """``(E, 3)``: per edge (sides a, b), the centroid of root4's hexagon on the
    dual, summed in its order: the dual's vertices ``moved`` ``(F, 3)`` of faces
    a and b, the ``inner`` ``(C, 3)`` points of a, b and the corners after them."""
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    na, nb = t.nxt[a], t.nxt[b]
    out = rows(moved, t.face[b])
    out += rows(inner, b)
    out += rows(inner, na)
    out += rows(moved, t.face[a])
    out += rows(inner, a)
    out += rows(inner, nb)
    out /= 6.0
    return out


def dual_pentagonalization(mesh: Mesh, *, offset: float = 0.0,
                           max_faces: int | None = None) -> None:
    """GUI "Dual Pentagonalization" (TopMod: dual, pentagon(offset), dual), in one step.

    The result has a vertex per old corner c (the centroid of pentagon's
    pentagon of c on the dual) and per old face the polygon of its corners'
    points, per old corner c the triangle (c, prev c, vprev(c)) and per old
    vertex the polygon of its ring. Cube: 24/60/38 (32 triangles, 6 quads).

    Raises:
        DLFLError: a bad ``offset``, or the face budget.
    """
    offset = check_number("offset", offset)
    check_steps(mesh, ("dual", "pentagon", "dual"), max_faces)
    t = read_topology(mesh)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        centres = _pentagon_centres(t, offset)
    build_paired(mesh, t, centres, *_dual_pentagonalization_layout(t))


def _pentagon_centres(t: Topology, offset: float) -> np.ndarray:
    """``(C, 3)``: per corner c, the centroid of :func:`pentagon`'s pentagon of c
    on the dual: the dual's face centroid ``Cv``, its trisection points ("near")
    of next(mate c) and next c, its vertex (face c's centroid) and near(c),
    summed in the pentagon's order."""
    cen = t.centroids()
    c_v = rows(_vertex_centres(t, cen), t.cv)
    p = rows(cen, t.face)
    near = p + (rows(p, t.vprev) - p) / 3.0
    near += offset * (c_v - near)
    out = c_v
    out += rows(near, t.nxt[t.mate])
    out += rows(near, t.nxt)
    out += p
    out += near
    out /= 5.0
    return out


def _dual_pentagonalization_layout(t: Topology) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                           np.ndarray]:
    """:func:`dual_pentagonalization`'s corners, mates computed directly.

    Layout: face polygons (corner c at c), triangles (at C + 3c: c, prev c,
    vprev(c)), vertex polygons (ring position q at 4C + q, in
    :meth:`Topology.vertex_rings` order). Returns the new corners' vertices and
    mates, the face sizes and origin flags.
    """
    nc, c, vprev = t.nc, np.arange(t.nc), t.vprev
    order, offsets = t.vertex_rings()
    position = np.empty(nc, dtype=np.int64)
    position[order] = 4 * nc + c
    verts = np.concatenate([c, np.stack([c, t.prv, vprev], axis=1).ravel(), order])
    tri_mate = np.stack([t.prv, nc + 3 * t.nxt[vprev] + 1, position], axis=1)
    mates = np.concatenate([nc + 3 * t.nxt, tri_mate.ravel(), nc + 3 * order + 2])
    sizes = np.concatenate([t.sizes, np.full(nc, 3, dtype=np.int64), np.diff(offsets)])
    return verts, mates, sizes, no_origin(len(sizes))
