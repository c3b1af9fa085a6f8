"""Interpolating and conversion schemes: splits, fans, cuts, duals.

Each function remeshes ``mesh`` in place (every element gets a fresh id) and
returns ``None``. Unless a docstring says otherwise, hole faces are treated as
faces by the rules and the faces made from a hole face are holes again; faces
made around old vertices or edges are ordinary faces. Point-spheres survive
unchanged. ``max_faces`` overrides the face budget (:mod:`livemod.dlfl.budget`).
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from .._checks import id_list
from .._vectors import in_range, lengths, range_exponent
from .._vectors import unit as normalize
from ..errors import UnknownIdError
from ..mesh import Mesh
from ._blocks import (
    corner_triangles,
    face_rings,
    fan_triangles,
    inner_polygons,
    split_quads,
    vertex_rings,
)
from ._layout import (
    NO_ORIGIN,
    Faces,
    Pending,
    Topology,
    budgeted_topology,
    build,
    build_paired,
    check_number,
    cos_weights,
    face_weighted,
    no_origin,
    read_topology,
    rows,
    vertex_mean,
)
from ._sizes import EXACT, SIZES, check_steps

HONEYCOMB_ALPHA = 2 ** -0.5 - 0.25


def subdivide_all_edges(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """Split every edge at its midpoint (TopMod ``subdivideAllEdges(2)``).

    Faces keep their number and gain one corner per side. Cube: 20/24/6.
    """
    t = budgeted_topology(mesh, "subdivide-all-edges", max_faces, SIZES["subdivide-all-edges"])
    positions = np.concatenate([t.pos, t.midpoints()])
    verts = np.stack([t.cv, t.nv + t.edge], axis=1)
    labels = np.stack([np.arange(t.nc), t.mate], axis=1)
    faces = Faces()
    faces.add(verts, labels, t.origin, 2 * t.sizes)
    build(mesh, t, positions, faces)


def _selected_faces(t: Topology, face_ids: Iterable[int]) -> np.ndarray:
    """``(F,)`` bool mask of the faces named by id.

    Raises:
        DLFLError: an entry that is not an integer, or an id that is not a face
            with at least one edge.
    """
    ids = id_list(face_ids, "face_ids")
    where = np.searchsorted(t.face_ids, ids)
    for f, w in zip(ids, where.tolist(), strict=True):
        if w >= len(t.face_ids) or t.face_ids[w] != f:
            raise UnknownIdError(f"face id {f} is not a face of the mesh (or is a point-sphere)")
    mask = np.zeros(t.nf, dtype=bool)
    mask[where] = True
    return mask


def subdivide_faces(mesh: Mesh, face_ids: Iterable[int], *, usequads: bool = True,
                    max_faces: int | None = None) -> None:
    """Split the given faces about their centroids (TopMod ``subdivideFaces``).

    With ``usequads`` every edge of a selected face is split once at its
    midpoint (neighbouring faces gain that corner) and each selected n-gon
    becomes n quads; otherwise each selected n-gon becomes a fan of n triangles.
    No smoothing. Differences from TopMod: a single face honours ``usequads``
    (TopMod always used quads for a list of one face).

    Raises:
        DLFLError: an unknown face id, or the face budget.
    """
    t = budgeted_topology(mesh, "subdivide-faces", max_faces,
                          lambda c: (c.nf + c.nc, 4 * c.nc),
                          lambda t: _split_size(t, _selected_faces(t, face_ids), usequads))
    selected = _selected_faces(t, face_ids)
    if usequads:
        _quad_split(mesh, t, selected)
    else:
        _fan_split(mesh, t, selected)


def _split_size(t: Topology, selected: np.ndarray, usequads: bool) -> tuple[int, int]:
    """``(faces, corners)`` of :func:`subdivide_faces`: ``n`` quads or triangles per
    selected ``n``-gon; with ``usequads`` a kept corner gains one where its edge
    is split."""
    chosen = np.repeat(selected, t.sizes)
    split = int(np.count_nonzero(chosen))
    faces = t.nf - int(np.count_nonzero(selected)) + split
    if not usequads:
        return faces, 3 * split + t.nc - split
    split_edge = np.zeros(t.ne, dtype=bool)
    split_edge[t.edge[chosen]] = True
    gained = int(np.count_nonzero(split_edge[t.edge[~chosen]]))
    return faces, 4 * split + t.nc - split + gained


def _quad_split(mesh: Mesh, t: Topology, selected: np.ndarray) -> None:
    chosen = np.repeat(selected, t.sizes)
    split = np.zeros(t.ne, dtype=bool)
    split[t.edge[chosen]] = True
    edge_point = np.full(t.ne, -1, dtype=np.int64)
    edge_point[split] = t.nv + np.arange(int(split.sum()))
    face_point = np.full(t.nf, -1, dtype=np.int64)
    face_point[selected] = t.nv + int(split.sum()) + np.arange(int(selected.sum()))
    positions = np.concatenate([t.pos, t.midpoints()[split], t.centroids()[selected]])
    faces = Faces()
    split_quads(t, np.flatnonzero(chosen), edge_point, face_point, faces)
    _keep_faces(t, ~selected, faces, edge_point)
    build(mesh, t, positions, faces)


def _keep_faces(t: Topology, keep: np.ndarray, faces: Faces,
                edge_point: np.ndarray | None = None) -> None:
    """Unchanged faces, gaining a corner on every split edge (``edge_point >= 0``).

    Labels: halves ``[0, C)`` on split edges, ``2C + edge`` on the others.
    """
    corners = np.flatnonzero(np.repeat(keep, t.sizes))
    if edge_point is None:
        edge_point = np.full(t.ne, -1, dtype=np.int64)
    point = edge_point[t.edge[corners]]
    is_split = point >= 0
    extra = is_split.astype(np.int64)
    slots = np.arange(len(corners)) + np.concatenate([[0], np.cumsum(extra)[:-1]])
    total = len(corners) + int(extra.sum())
    verts = np.empty(total, dtype=np.int64)
    labels = np.empty(total, dtype=np.int64)
    verts[slots] = t.cv[corners]
    labels[slots] = np.where(is_split, corners, 2 * t.nc + t.edge[corners])
    verts[slots[is_split] + 1] = point[is_split]
    labels[slots[is_split] + 1] = t.mate[corners[is_split]]
    sizes = np.bincount(t.face[corners], weights=1 + extra, minlength=t.nf)[keep]
    faces.add(verts, labels, t.origin[keep], sizes.astype(np.int64))


def _fan_split(mesh: Mesh, t: Topology, selected: np.ndarray) -> None:
    face_point = np.full(t.nf, -1, dtype=np.int64)
    face_point[selected] = t.nv + np.arange(int(selected.sum()))
    positions = np.concatenate([t.pos, t.centroids()[selected]])
    faces = Faces()
    fan_triangles(t, np.flatnonzero(np.repeat(selected, t.sizes)), face_point, faces)
    _keep_faces_edges(t, ~selected, faces)
    build(mesh, t, positions, faces)


def _keep_faces_edges(t: Topology, keep: np.ndarray, faces: Faces) -> None:
    """Unchanged faces whose sides carry the old edge labels ``[0, E)``."""
    corners = np.flatnonzero(np.repeat(keep, t.sizes))
    faces.add(t.cv[corners], t.edge[corners], t.origin[keep], t.sizes[keep])


def linear_vertex(mesh: Mesh, *, usequads: bool = True, max_faces: int | None = None) -> None:
    """Linear vertex insertion (TopMod ``subdivideAllFaces(usequads)``,
    "linear-vertex", Python "allfaces").

    Rule: every face gets its centroid; with ``usequads`` (default) every edge
    its midpoint and an n-gon becomes n quads (Catmull-Clark's topology without
    smoothing, cube 26/48/24); without, an n-gon becomes a fan of n triangles
    (GUI "Stellate", cube 14/36/24).
    """
    t = budgeted_topology(mesh, "linear-vertex", max_faces,
                          lambda c: (c.nc, (4 if usequads else 3) * c.nc))
    everything = np.ones(t.nf, dtype=bool)
    if usequads:
        _quad_split(mesh, t, everything)
    else:
        _fan_split(mesh, t, everything)


def triangulate(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """Triangulate (TopMod ``triangulateAllFaces``, "triangulate").

    Rule: every face that is not a triangle becomes a fan of triangles about its
    centroid (not ear clipping). Cube: 14/36/24.
    """
    t = budgeted_topology(mesh, "triangulate", max_faces, SIZES["triangulate"],
                          EXACT["triangulate"])
    _fan_split(mesh, t, t.sizes != 3)


def simplest(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """Simplest subdivision, rectification (TopMod ``simplestSubdivide``, "simplest").

    Rule: the edge midpoints are the new vertices; each face becomes the polygon
    of its midpoints and each vertex the polygon of the midpoints around it.
    Cube: 12/24/14 (8 triangles, 6 quads).
    """
    t = budgeted_topology(mesh, "simplest", max_faces, SIZES["simplest"])
    faces = Faces()
    inner_polygons(t, 0, faces)
    vertex_rings(t, t.edge, t.nc + np.arange(t.nc), faces)
    build(mesh, t, t.midpoints(), faces)


def vertex_cut(mesh: Mesh, *, offset: float = 0.25, max_faces: int | None = None) -> None:
    """Vertex truncation (TopMod ``vertexCuttingSubdivide(offset)``, "vertex-cut").

    Rule: each edge p1-p2 gets p1 + offset (p2 - p1) and p2 + offset (p1 - p2);
    each n-gon becomes a 2n-gon and each vertex a polygon. ``offset`` 0.5 is
    :func:`simplest`, 0 leaves the mesh unchanged (as in TopMod). GUI default
    0.25. Cube: 24/36/14 (8 triangles, 6 octagons).

    Raises:
        DLFLError: ``offset`` outside [0, 0.5], or the face budget.
    """
    offset = check_number("offset", offset, 0.0, 0.5)
    if offset == 0.5:
        simplest(mesh, max_faces=max_faces)
        return
    if offset == 0.0:
        return
    t = budgeted_topology(mesh, "vertex-cut", max_faces, SIZES["vertex-cut"])
    p = rows(t.pos, t.cv)
    points = p + offset * (rows(t.pos, t.cv[t.nxt]) - p)
    corners = np.arange(t.nc)
    verts = np.stack([corners, t.mate], axis=1)
    labels = np.stack([t.edge, t.ne + t.nxt], axis=1)
    faces = Faces()
    faces.add(verts, labels, t.origin, 2 * t.sizes)
    vertex_rings(t, corners, t.ne + corners, faces)
    build(mesh, t, points, faces)


def honeycomb(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """Honeycomb (TopMod ``honeycombSubdivide``, "honeycomb").

    Rule: per n-gon, p_i = sum_j w_ij m_j over its edge midpoints with
    alpha = 1/sqrt(2) - 1/4 + 5/(4n), w_ii = alpha,
    w_ij = (1 - alpha)(3 + 2 cos(2 pi (i - j)/n)) / (3n - 5); each face becomes
    the polygon of its p_i, the two points of each old edge are joined, and each
    old vertex of valence k becomes a 2k-gon. Cube: 24/36/14 (6 quads, 8 hexagons).
    """
    t = budgeted_topology(mesh, "honeycomb", max_faces, SIZES["honeycomb"])
    mids = rows(t.midpoints(), t.edge)
    points = face_weighted(t, mids, lambda n: cos_weights(n, HONEYCOMB_ALPHA + 1.25 / n))
    faces = Faces()
    face_rings(t, 0, 0, faces)
    order, offsets = t.vertex_rings()
    prev = t.prv[order]
    verts = np.stack([order, prev], axis=1)
    labels = np.stack([prev, t.nc + t.edge[prev]], axis=1)
    faces.add(verts, labels, NO_ORIGIN, 2 * np.diff(offsets))
    build(mesh, t, points, faces)


def root4(mesh: Mesh, *, weight: float = 0.0, twist: float = 0.0,
          max_faces: int | None = None) -> None:
    """Root-4 (TopMod ``root4Subdivide(a, twist)``, "root4"; GUI "Dual Loop Style").

    Rule: per n-gon, m_i = (1 - twist) p_i + twist p_(i+1), the honeycomb
    weights on m give an inner polygon; each face becomes its inner polygon and
    each old edge a hexagon (its two ends and two inner points on each side).
    Old vertices keep their place moved to v' = (1 - weight) v +
    weight * mean(inner points around v) (TopMod's "2 mid - v" over the edges
    left at v). GUI defaults 0, 0. Cube: 32/48/18 (6 quads, 12 hexagons).

    Raises:
        DLFLError: a bad option value, or the face budget.
    """
    weight = check_number("weight", weight)
    twist = check_number("twist", twist)
    t = budgeted_topology(mesh, "root4", max_faces, SIZES["root4"])
    p = rows(t.pos, t.cv)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        m = (1 - twist) * p + twist * rows(t.pos, t.cv[t.nxt])
        inner = face_weighted(t, m, lambda n: cos_weights(n, HONEYCOMB_ALPHA + 1.25 / n))
        around = vertex_mean(t, inner)
        vertices = (1 - weight) * t.pos + weight * around
    build_paired(mesh, t, np.concatenate([vertices, inner]), *root4_layout(t))


def root4_layout(t: Topology) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Root-4's corners with mates computed directly.

    Points: vertices, then corner c's at V + c. Layout: face polygons (corner c
    at c), edge hexagons (edge k at C + 6k: end of a, next a, a, start of a,
    next b, b, for its sides a, b). Also the layout of the GUI's dual-loop.
    Returns the new corners' vertices and mates, the face sizes and origins.
    """
    nc, v, c = t.nc, t.nv, np.arange(t.nc)
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    na, nb, prv = t.nxt[a], t.nxt[b], t.prv
    is_a = a[t.edge] == c
    hexagon = nc + 6 * t.edge
    leaving = hexagon + np.where(is_a, 2, 5)  # the spoke from c's point to c's vertex
    arriving = hexagon[prv] + np.where(is_a[prv], 0, 3)  # from c's vertex to c's point
    verts = np.stack([t.cv[na], v + na, v + a, t.cv[a], v + nb, v + b], axis=1)
    mates = np.stack([leaving[na], a, arriving[a], leaving[nb], b, arriving[b]], axis=1)
    sizes = np.concatenate([t.sizes, np.full(t.ne, 6, dtype=np.int64)])
    origin = np.concatenate([t.origin, no_origin(t.ne)])
    return (np.concatenate([v + c, verts.ravel()]),
            np.concatenate([hexagon + np.where(is_a, 1, 4), mates.ravel()]), sizes, origin)


def pentagon_preserve(mesh: Mesh, *, scale: float = 0.75,
                      max_faces: int | None = None) -> None:
    """Pentagon preserving / dual pentagon (TopMod ``pentagonalSubdivide2(sf)``,
    "dual-pentagon", Python "pentagon-preserve").

    Rule: split edges at midpoints; each face gets a copy of its midpoint polygon
    scaled by ``scale`` about its centroid, every midpoint joined to its copy:
    an n-gon becomes an n-gon plus n pentagons. GUI default 0.75. Cube: 44/72/30.
    Differences from TopMod: 2-gons are treated like other faces (TopMod skipped
    faces with fewer than 3 sides).

    Raises:
        DLFLError: a bad ``scale``, or the face budget.
    """
    scale = check_number("scale", scale)
    t = budgeted_topology(mesh, "pentagon-preserve", max_faces, SIZES["pentagon-preserve"])
    cen = rows(t.centroids(), t.face)
    mids = t.midpoints()
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        inner = cen + scale * (rows(mids, t.edge) - cen)
    positions = np.concatenate([t.pos, mids, inner])
    build_paired(mesh, t, positions, *_pentagon_preserve_layout(t))


def _pentagon_preserve_layout(t: Topology) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                      np.ndarray]:
    """Pentagon preserving's corners with mates computed directly.

    Points: vertices, edge midpoints at V + e, inner copies at V + E + c. Layout:
    inner faces (corner c at c), then per corner c the pentagon at C + 5c:
    vertex, midpoint(edge c), inner(c), inner(prev c), midpoint(edge prev c).
    Returns the new corners' vertices and mates, the face sizes and origins.
    """
    base, nc, prev, nxt, mate = t.nv + t.ne, t.nc, t.prv, t.nxt, t.mate
    c = np.arange(nc)
    verts = np.stack([t.cv, t.nv + t.edge, base + c, base + prev, t.nv + t.edge[prev]], axis=1)
    pent = nc + 5 * np.stack([nxt[mate], nxt, np.zeros(nc, dtype=np.int64), prev, mate[prev]],
                             axis=1)
    pent += np.array([4, 3, 0, 1, 0])
    pent[:, 2] = prev  # the inner face's side from inner(prev c) to inner(c)
    mates = np.concatenate([nc + 5 * nxt + 2, pent.ravel()])
    sizes = np.concatenate([t.sizes, np.full(nc, 5, dtype=np.int64)])
    origin = np.concatenate([t.origin, t.origin[t.face]])
    return np.concatenate([base + c, verts.ravel()]), mates, sizes, origin


def pentagon(mesh: Mesh, *, offset: float = 0.0, max_faces: int | None = None) -> None:
    """Pentagonalization (TopMod ``pentagonalSubdivide(offset)``, "pentagon").

    Rule: each edge is trisected; per face, its centroid is joined to the
    trisection point after each corner (the one a third along the side from
    it), and that point moves by offset * (centroid - point): an n-gon becomes n
    pentagons (centroid, the far trisection points of the previous side, the
    corner, the near point of the next side). Cube (offset 0): 38/60/24.
    Differences from TopMod (QUIRK): TopMod did not move the last joined point
    of each face; livemod moves all of them.

    Raises:
        DLFLError: a bad ``offset``, or the face budget.
    """
    offset = check_number("offset", offset)
    t = budgeted_topology(mesh, "pentagon", max_faces, SIZES["pentagon"])
    cen = t.centroids()
    p = rows(t.pos, t.cv)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        near = p + (rows(t.pos, t.cv[t.nxt]) - p) / 3.0
        near += offset * (rows(cen, t.face) - near)
    positions = np.concatenate([t.pos, near, cen])
    v, nc, prev, nxt, mate = t.nv, t.nc, t.prv, t.nxt, t.mate
    c = np.arange(nc)
    verts = np.stack([v + nc + t.face, v + prev, v + mate[prev], t.cv, v + c], axis=1)
    # pentagon of c at 5c: its sides meet pentagons prev c, next(mate(prev c)),
    # mate(prev c), next(mate c) and next c
    mates = 5 * np.stack([prev, nxt[mate[prev]], mate[prev], nxt[mate], nxt], axis=1)
    mates += np.array([4, 1, 3, 2, 0])
    build_paired(mesh, t, positions, verts.ravel(), mates.ravel(),
                 np.full(nc, 5, dtype=np.int64), t.origin[t.face])


def cubic_pentagonalization(mesh: Mesh, *, offset: float = 0.0,
                            max_faces: int | None = None) -> None:
    """GUI "Cubic Pentagonalization" (TopMod: pentagon(offset), dual, dual), in one step.

    A dual of a dual has the mesh's own topology, each vertex moved to the mean
    of the centroids of its faces (one per corner): this is :func:`pentagon`
    with that move and no hole faces (a dual makes none). Cube: 38/60/24.

    Raises:
        DLFLError: a bad ``offset``, or the face budget.
    """
    check_steps(mesh, ("pentagon", "dual", "dual"), max_faces)
    work = Pending(read_topology(mesh))
    pentagon(work, offset=offset, max_faces=max_faces)
    x = work.topology
    moved = vertex_mean(x, rows(x.centroids(), x.face))
    build_paired(mesh, x, moved, x.cv, x.mate, x.sizes, no_origin(x.nf))


def dual_1264(mesh: Mesh, *, scale: float = 0.7, max_faces: int | None = None) -> None:
    """Dual 12.6.4 (TopMod ``dual1264Subdivide(sf)``, "dual-12.6.4").

    Rule: per n-gon, the points at 1/3 and 2/3 of each side form a 2n-gon,
    scaled about its centroid by |scale| unless that is 0 or 1; joined as in
    Doo-Sabin: a quad per old edge and a 2k-gon per old vertex of valence k.
    GUI default 0.7. Cube: 48/72/26 (12 quads, 8 hexagons, 6 octagons).

    Raises:
        DLFLError: a bad ``scale``, or the face budget.
    """
    scale = abs(check_number("scale", scale))
    t = budgeted_topology(mesh, "dual-12.6.4", max_faces, SIZES["dual-12.6.4"])
    p, q = rows(t.pos, t.cv), rows(t.pos, t.cv[t.nxt])
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        first, second = (2 * p + q) / 3.0, (p + 2 * q) / 3.0
    if scale not in (0.0, 1.0):
        cen = rows(t.centroids(), t.face)
        with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
            first, second = cen + scale * (first - cen), cen + scale * (second - cen)
    build_paired(mesh, t, np.concatenate([first, second]), *_dual_1264_layout(t))


def _dual_1264_layout(t: Topology) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Dual 12.6.4's corners with mates computed directly.

    Points: first(c) = c, second(c) = C + c. Layout: 2n-gons (2c, 2c + 1: first(c),
    second(c)), edge quads (2C + 4k: second(a), first(a), second(b), first(b)),
    vertex 2k-gons (2C + 4E + 2q, + 1: first(r), second(prev r) for ring corner r).
    Returns the new corners' vertices and mates, the face sizes and origins.
    """
    nc, c = t.nc, np.arange(t.nc)
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    order, offsets = t.vertex_rings()
    position = np.empty(nc, dtype=np.int64)
    position[order] = c
    ring = 2 * nc + 4 * t.ne
    is_a = a[t.edge] == c
    face_mate = np.stack([2 * nc + 4 * t.edge + np.where(is_a, 0, 2),
                          ring + 2 * position[t.nxt]], axis=1)
    quad_mate = np.stack([2 * a, ring + 2 * position[t.nxt[b]] + 1, 2 * b,
                          ring + 2 * position[t.nxt[a]] + 1], axis=1)
    prev = t.prv[order]
    ring_mate = np.stack([2 * prev + 1, 2 * nc + 4 * t.edge[prev] + np.where(is_a[prev], 3, 1)],
                         axis=1)
    verts = np.concatenate([np.stack([c, nc + c], axis=1).ravel(),
                            np.stack([nc + a, a, nc + b, b], axis=1).ravel(),
                            np.stack([order, nc + prev], axis=1).ravel()])
    mates = np.concatenate([face_mate.ravel(), quad_mate.ravel(), ring_mate.ravel()])
    sizes = np.concatenate([2 * t.sizes, np.full(t.ne, 4, dtype=np.int64), 2 * np.diff(offsets)])
    origin = np.concatenate([t.origin, no_origin(t.ne + len(offsets) - 1)])
    return verts, mates, sizes, origin


def _stellate_centres(t: Topology, offset: float) -> np.ndarray:
    """``(F, 3)`` centroid + offset * unit face normal."""
    cen = t.centroids()
    return cen + offset * t.face_normals() if offset else cen


def stellate(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """Stellate with edge removal (TopMod ``stellateSubdivide``, "stellate").

    Rule: a centroid fan on every face, then the old edges deleted: every old
    edge becomes a quad (its ends and the two face centroids). Cube: 14/24/12
    (the rhombic dodecahedron's topology).
    """
    t = budgeted_topology(mesh, "stellate", max_faces, SIZES["stellate"])
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    na, nb, v = t.nxt[a], t.nxt[b], t.nv
    verts = np.stack([t.cv[na], v + t.face[a], t.cv[a], v + t.face[b]], axis=1)
    labels = np.stack([na, a, nb, b], axis=1)
    faces = Faces()
    faces.add(verts, labels, no_origin(len(a)))
    build(mesh, t, np.concatenate([t.pos, t.centroids()]), faces)


def sqrt3(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """Root-3 topology (TopMod ``sqrt3Subdivide``, "sqrt3"; GUI "Dual Vertex
    Truncation").

    Rule: a centroid fan on every face, the old edges deleted and each merged
    quad split by its centroid-centroid diagonal (an edge flip); no smoothing.
    Cube: 14/36/24.
    """
    t = budgeted_topology(mesh, "sqrt3", max_faces, SIZES["sqrt3"])
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    na, nb, v = t.nxt[a], t.nxt[b], t.nv
    fa, fb, diagonal = v + t.face[a], v + t.face[b], t.nc + np.arange(t.ne)
    faces = Faces()
    faces.add(np.stack([t.cv[na], fa, fb], axis=1), np.stack([na, diagonal, b], axis=1),
              no_origin(len(a)))
    faces.add(np.stack([fa, t.cv[a], fb], axis=1), np.stack([a, nb, diagonal], axis=1),
              no_origin(len(a)))
    build(mesh, t, np.concatenate([t.pos, t.centroids()]), faces)


def star(mesh: Mesh, *, offset: float = 0.0, max_faces: int | None = None) -> None:
    """Star / double stellation (TopMod ``starSubdivide(offset)``, "star"; GUI
    "Double Stellate" in the three-conversion menu).

    Rule: a centroid fan on every face, a centroid fan on every triangle of it,
    then the first-level centres move by offset * the original unit face normal.
    Every n-gon becomes 3n triangles. Cube: 38/108/72.

    Raises:
        DLFLError: a bad ``offset``, or the face budget.
    """
    offset = check_number("offset", offset)
    t = budgeted_topology(mesh, "star", max_faces, SIZES["star"])
    cen = t.centroids()
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        second = (rows(t.pos, t.cv) + rows(t.pos, t.cv[t.nxt]) + rows(cen, t.face)) / 3.0
    positions = np.concatenate([t.pos, _stellate_centres(t, offset), second])
    e, nc, c, nxt = t.ne, t.nc, np.arange(t.nc), t.nxt
    centre, mid = t.nv + t.face, t.nv + t.nf + c
    k0, k1, k2 = e + nc + c, e + 2 * nc + c, e + 3 * nc + c
    origin = t.origin[t.face]
    faces = Faces()
    faces.add(np.stack([t.cv, t.cv[nxt], mid], axis=1), np.stack([t.edge, k1, k0], axis=1), origin)
    faces.add(np.stack([t.cv[nxt], centre, mid], axis=1), np.stack([e + nxt, k2, k1], axis=1),
              origin)
    faces.add(np.stack([centre, t.cv, mid], axis=1), np.stack([e + c, k0, k2], axis=1), origin)
    build(mesh, t, positions, faces)


def double_stellate(mesh: Mesh, *, offset: float = 0.0, curve: float = 0.0,
                    max_faces: int | None = None) -> None:
    """Double stellate (TopMod ``twostellateSubdivide(offset, curve)``,
    "double-stellate"; GUI "Double Stellate" in the misc menu).

    Rule: a fan on every face about centroid + offset * unit normal, a fan on
    every triangle about its centroid + curve * its unit normal, then the edges
    of the first pass deleted: every old edge and every first-pass spoke becomes
    a quad. GUI defaults 0, 0. Cube: 38/72/36.

    Raises:
        DLFLError: a bad option value, or the face budget.
    """
    offset = check_number("offset", offset)
    curve = check_number("curve", curve)
    t = budgeted_topology(mesh, "double-stellate", max_faces, SIZES["double-stellate"])
    centres = _stellate_centres(t, offset)
    p, q, r = rows(t.pos, t.cv), rows(t.pos, t.cv[t.nxt]), rows(centres, t.face)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        second = (p + q + r) / 3.0
        if curve:
            second += curve * normalize(np.cross(in_range(q - p), in_range(r - p)))
    positions = np.concatenate([t.pos, centres, second])
    nc, c, prev, base = t.nc, np.arange(t.nc), t.prv, t.nv + t.nf
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    na = t.nxt[a]
    faces = Faces()
    faces.add(np.stack([t.cv[na], base + a, t.cv[a], base + b], axis=1),
              np.stack([nc + a, a, nc + b, b], axis=1), no_origin(len(a)))
    faces.add(np.stack([t.cv, base + c, t.nv + t.face, base + prev], axis=1),
              np.stack([c, 2 * nc + c, 2 * nc + prev, nc + prev], axis=1), t.origin[t.face])
    build(mesh, t, positions, faces)


def fractal(mesh: Mesh, *, offset: float = 1.0, max_faces: int | None = None) -> None:
    """Fractal (TopMod ``fractalSubdivide(offset)``, "fractal").

    Rule: edge midpoints; per face a centre at centroid + d * unit normal with
    d = offset * sqrt(L2^2 - L1^2), L2 the distance between the first two
    midpoints, L1 half the distance from the first midpoint to the point half
    way round the split face (the opposite midpoint, or the opposite vertex of
    an odd face); corners are cut off and the centre fanned to the midpoints.
    Cube: 26/72/48. Differences from TopMod: where L1 > L2 (faces of 7 sides or
    more) d is 0 instead of NaN.

    Raises:
        DLFLError: a bad ``offset``, or the face budget.
    """
    offset = check_number("offset", offset)
    t = budgeted_topology(mesh, "fractal", max_faces, SIZES["fractal"])
    mids = t.midpoints()
    heights = _fractal_heights(t, mids)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        centres = t.centroids() + (offset * heights)[:, None] * t.face_normals()
    positions = np.concatenate([t.pos, mids, centres])
    faces = Faces()
    corner_triangles(t, t.nv, faces)
    nc, nxt = t.nc, t.nxt
    verts = np.stack([t.nv + t.edge, t.nv + t.edge[nxt], t.nv + t.ne + t.face], axis=1)
    labels = np.stack([nc + nxt, 2 * nc + nxt, 2 * nc + np.arange(nc)], axis=1)
    faces.add(verts, labels, t.origin[t.face])
    build(mesh, t, positions, faces)


def _fractal_heights(t: Topology, mids: np.ndarray) -> np.ndarray:
    """``(F,)`` sqrt(L2^2 - L1^2) of each face (0 where negative; inf where a
    length is beyond the float range)."""
    head = t.offsets[:-1]
    first = rows(mids, t.edge[head])
    second = rows(mids, t.edge[t.nxt[head]])
    n = t.sizes
    # n steps round the 2n-corner split face from the first midpoint land on
    # midpoint n/2 (n even) or on corner (n + 1)/2 (n odd)
    odd = (n % 2).astype(bool)
    step = np.where(odd, (n + 1) // 2, n // 2) % np.maximum(n, 1)
    corner = head + step
    opposite = np.where(odd[:, None], rows(t.pos, t.cv[corner]), rows(mids, t.edge[corner]))
    with np.errstate(over="ignore", invalid="ignore"):  # inf: refused by build
        l1 = 0.5 * lengths(first - opposite)
        l2 = lengths(first - second)
        # squares of lengths past ~1e154 overflow: take them scaled by a power
        # of two (exact; none inside the band) and scale the root back
        k = range_exponent(l2)
        l1, l2 = (np.ldexp(l1, -k), np.ldexp(l2, -k)) if k else (l1, l2)
        height = np.sqrt(np.maximum(l2 * l2 - l1 * l1, 0.0))
        return np.ldexp(height, k) if k else height


def dual(mesh: Mesh, *, accurate: bool = False, max_faces: int | None = None) -> None:
    """Dual (TopMod ``createDual(accurate)``, "dual").

    Rule: face centroids become the vertices and every vertex's fan of faces a
    face, counter-clockwise seen from outside. Both of TopMod's methods give
    this mesh; ``accurate`` is accepted for compatibility (TopMod's fast method
    rounded positions to 6 digits, livemod keeps full precision). Hole faces
    become ordinary vertices. Cube: 6/12/8.
    """
    del accurate
    t = budgeted_topology(mesh, "dual", max_faces, SIZES["dual"])
    order, offsets = t.vertex_rings()
    position = np.empty(t.nc, dtype=np.int64)
    position[order] = np.arange(t.nc)
    # the side across edge(prev r) is in the ring of the edge's other end, at the
    # corner after that edge's other side; mate(prev r) is r's successor in its ring
    after = np.arange(1, t.nc + 1, dtype=np.int64)
    after[offsets[1:] - 1] = offsets[:-1]
    mates = position[t.nxt[order[after]]]
    build_paired(mesh, t, t.centroids(), t.face[order], mates, np.diff(offsets),
                 no_origin(len(offsets) - 1))
