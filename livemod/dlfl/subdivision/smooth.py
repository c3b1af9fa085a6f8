"""Approximating schemes: Catmull-Clark, Loop and the Doo-Sabin family.

Each function remeshes ``mesh`` in place (every element gets a fresh id) and
returns ``None``. Hole faces are treated as faces by the rules (in TopMod a hole
is an ordinary face) and every new face made from a hole face is a hole again;
point-spheres survive unchanged. ``max_faces`` overrides the face budget
(:mod:`livemod.dlfl.budget`).
"""

from __future__ import annotations

import math

import numpy as np

from ..mesh import Mesh
from ._blocks import doo_sabin_faces
from ._layout import (
    Faces,
    Topology,
    budgeted_topology,
    build,
    build_paired,
    check_levels,
    check_number,
    cos_weights,
    face_weighted,
    no_origin,
    topology_of,
)
from ._sizes import EXACT, SIZES, catmull_clark_size


def catmull_clark(mesh: Mesh, *, levels: int = 1, max_faces: int | None = None) -> None:
    """Catmull-Clark subdivision (TopMod ``catmullClarkSubdivide``, "catmull-clark").

    Rule: face point = centroid; edge point = (sum of both ends and both face
    points) / 4; vertex = (Q + 2R + (n - 3)v) / n with Q the mean adjacent face
    point, R the mean incident edge midpoint, n the valence. Every n-gon becomes n
    quads (vertex, edge point, face point, edge point). Cube: 26/48/24, 24 quads.
    ``levels`` (a livemod addition, default 1) repeats the step on the arrays and
    builds the mesh once.

    Raises:
        DLFLError: ``levels`` not a positive integer, or the result would exceed
            the face budget.
    """
    levels = check_levels(levels)
    t = budgeted_topology(mesh, "catmull-clark", max_faces,
                          lambda c: catmull_clark_size(c, levels))
    for level in range(levels):
        with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
            positions = _cc_points(t, t.centroids())
        verts, mates = _cc_faces(t)
        sizes = np.full(t.nc, 4, dtype=np.int64)
        origin = np.repeat(t.origin, t.sizes)
        if level == levels - 1:
            build_paired(mesh, t, positions, verts, mates, sizes, origin)
        else:
            t = topology_of(positions, verts, mates, sizes, origin, t)


def _cc_faces(t: Topology) -> tuple[np.ndarray, np.ndarray]:
    """One quad per old corner c (corners 4c..4c+3), mates computed directly:
    the half at c's vertex meets quad next(mate c), the spokes quads next/prev c.

    Returns the ``(4C,)`` vertex and mate of every new corner.
    """
    nxt, prv, mate = t.nxt, t.prv, t.mate
    verts = np.empty((t.nc, 4), dtype=np.int64)
    verts[:, 0] = t.cv
    verts[:, 1] = t.nv + t.edge
    verts[:, 2] = t.nv + t.ne + t.face
    verts[:, 3] = t.nv + t.edge[prv]
    mates = np.empty((t.nc, 4), dtype=np.int64)
    mates[:, 0] = 4 * nxt[mate] + 3
    mates[:, 1] = 4 * nxt + 2
    mates[:, 2] = 4 * prv + 1
    mates[:, 3] = 4 * mate[prv]
    return verts.ravel(), mates.ravel()


def _cc_points(t: Topology, centroids: np.ndarray) -> np.ndarray:
    """``(V + E + F, 3)`` Catmull-Clark points: vertex points, edge points, centroids.

    Computed axis by axis on contiguous columns: 1-D gathers and bincounts are
    several times faster than gathering ``(N, 3)`` rows.
    """
    nv, ne = t.nv, t.ne
    out = np.empty((nv + ne + t.nf, 3))
    out[nv + ne :] = centroids
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    ends, sides = (t.cv[a], t.cv[b]), (t.face[a], t.face[b])
    n = np.maximum(t.valence, 1).astype(np.float64)
    ahead = t.cv[t.nxt]
    for axis in range(3):
        x = np.ascontiguousarray(t.pos[:, axis])
        c = np.ascontiguousarray(centroids[:, axis])
        out[nv : nv + ne, axis] = 0.25 * (x[ends[0]] + x[ends[1]] + c[sides[0]] + c[sides[1]])
        q = np.bincount(t.cv, weights=c[t.face], minlength=nv) / n
        r = np.bincount(t.cv, weights=0.5 * (x[t.cv] + x[ahead]), minlength=nv) / n
        out[:nv, axis] = (q + 2 * r + (n - 3) * x) / n
    return out


def loop(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """Loop subdivision (TopMod ``loopSubdivide``, "loop"), meant for triangles.

    Rule: edge point = 3/8 (ends) + 1/16 (prev and next-next corner of each side;
    the opposite vertex with weight 1/8 on triangles); vertex = (1 - n beta) v +
    beta * sum(neighbours), beta = (5/8 - (3/8 + cos(2 pi / n) / 4)^2) / n. Each
    old corner becomes a triangle and each n-gon an inner n-gon of edge points.
    Cube: 20/48/30 (24 triangles, 6 quads).

    Raises:
        DLFLError: the result would exceed the face budget.
    """
    t = budgeted_topology(mesh, "loop", max_faces, SIZES["loop"])
    # one contiguous column per axis: 1-D gathers and bincounts are the fast ones
    columns = np.ascontiguousarray(t.pos.T)
    positions = np.empty((t.nv + t.ne, 3))
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        _loop_vertices(t, columns, positions[: t.nv])
        _loop_edge_points(t, columns, positions[t.nv :])
    _corner_cut_faces(mesh, t, positions)


def _corner_cut_faces(mesh: Mesh, t: Topology, positions: np.ndarray) -> None:
    """Build Loop's topology (:func:`corner_cut_layout`); faces made from a hole
    face are holes. ``positions``: ``(V + E, 3)``, the old vertices' new points,
    then the edge points."""
    verts, mates, sizes = corner_cut_layout(t)
    origin = np.concatenate([np.repeat(t.origin, t.sizes), t.origin])
    build_paired(mesh, t, positions, verts, mates, sizes, origin)


def corner_cut_layout(t: Topology) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Loop's topology, mates computed directly: corner triangle of c at 3c..3c+2
    (vertex, edge point V + edge(c), edge point of prev c), then the inner
    polygons of edge points in the old corner layout (corner 3C + c).

    Returns the ``(4C,)`` vertex and mate of every new corner and the
    ``(C + F,)`` face sizes.
    """
    nxt, prv, mate, nc = t.nxt, t.prv, t.mate, t.nc
    # filled in place: no int32 -> int64 concatenation of ~4C entries
    verts = np.empty(4 * nc, dtype=np.int64)
    tri = verts[: 3 * nc].reshape(nc, 3)
    tri[:, 0] = t.cv
    np.add(t.edge, t.nv, out=verts[3 * nc :])
    tri[:, 1] = verts[3 * nc :]
    tri[:, 2] = verts[3 * nc :][prv]
    mates = np.empty(4 * nc, dtype=np.int64)
    tri_mate = mates[: 3 * nc].reshape(nc, 3)
    tri_mate[:, 0] = 3 * nxt[mate] + 2
    tri_mate[:, 1] = 3 * nc + prv
    tri_mate[:, 2] = 3 * mate[prv]
    mates[3 * nc :] = 3 * nxt + 1
    return verts, mates, np.concatenate([np.full(nc, 3, dtype=np.int64), t.sizes])


def _loop_edge_points(t: Topology, columns: np.ndarray, out: np.ndarray) -> None:
    """Write the ``(E, 3)`` Loop edge points into ``out``; ``columns`` is ``(3, V)``."""
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    cv, prv = t.cv, t.prv
    ends = (cv[a], cv[b])
    if len(t.sizes) and t.sizes.min() == t.sizes.max() == 3:
        # triangles: prev and next-next are the same opposite corner
        opposite = (cv[prv[a]], cv[prv[b]])
        for axis, x in enumerate(columns):
            out[:, axis] = 0.375 * (x[ends[0]] + x[ends[1]]) + 0.125 * (
                x[opposite[0]] + x[opposite[1]])
        return
    nxt2 = t.nxt[t.nxt]
    wings = (cv[prv[a]], cv[nxt2[a]], cv[prv[b]], cv[nxt2[b]])
    for axis, x in enumerate(columns):
        out[:, axis] = 0.375 * (x[ends[0]] + x[ends[1]]) + 0.0625 * (
            x[wings[0]] + x[wings[1]] + x[wings[2]] + x[wings[3]])


def _loop_vertices(t: Topology, columns: np.ndarray, out: np.ndarray) -> None:
    """Write the ``(V, 3)`` Loop vertex points into ``out``; ``columns`` is ``(3, V)``."""
    n = np.maximum(t.valence, 1).astype(np.float64)
    beta = (0.625 - (0.375 + 0.25 * np.cos(2 * math.pi / n)) ** 2) / n
    keep = 1 - n * beta
    neighbour = t.cv[t.nxt]
    for axis, x in enumerate(columns):
        sums = np.bincount(t.cv, weights=x[neighbour], minlength=t.nv)
        out[:, axis] = keep * x + beta * sums


def loop_style(mesh: Mesh, *, length: float = 1.0, max_faces: int | None = None) -> None:
    """Loop-style remeshing (TopMod ``loopStyleSubdivide(len)``, "loop-style").

    Rule: Loop's topology with edge midpoints; old vertex
    v' = length * v + (1 - length) * mean(neighbours). GUI default 1 (no smoothing).
    Cube: 20/48/30.

    Raises:
        DLFLError: a bad ``length`` or the face budget.
    """
    length = check_number("length", length)
    t = budgeted_topology(mesh, "loop-style", max_faces, SIZES["loop-style"])
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        vertices = length * t.pos + (1 - length) * t.neighbour_mean()
    _corner_cut_faces(mesh, t, np.concatenate([vertices, t.midpoints()]))


def _doo_sabin_like(mesh: Mesh, t: Topology, points: np.ndarray) -> None:
    """Build Doo-Sabin's topology over the ``(C, 3)`` per-corner ``points``."""
    order, offsets = t.vertex_rings()
    ring_sizes = np.diff(offsets)
    if len(ring_sizes) and ring_sizes.min() < 2:
        faces = Faces()  # valence 1: the general path
        doo_sabin_faces(t, faces)
        build(mesh, t, points, faces)
        return
    kept = ring_sizes >= 3
    _doo_sabin_build(mesh, t, points, order[np.repeat(kept, ring_sizes)], ring_sizes[kept])


def _doo_sabin_build(mesh: Mesh, t: Topology, points: np.ndarray, order: np.ndarray,
                     ring_sizes: np.ndarray) -> None:
    """Doo-Sabin's faces with mates computed directly, then :func:`build_paired`.

    ``order`` ``(R,)``: the corners of the vertex rings of three corners or more,
    ring after ring (as :meth:`Topology.vertex_rings` lays them out); their
    sizes ``ring_sizes``. Precondition: every other corner lies in a ring of two.
    """
    verts, mates = _doo_sabin_paired(t, order)
    sizes = np.concatenate([t.sizes, np.full(t.ne, 4, dtype=np.int64), ring_sizes])
    origin = np.concatenate([t.origin, no_origin(t.ne + len(ring_sizes))])
    build_paired(mesh, t, points, verts, mates, sizes, origin)


def _doo_sabin_paired(t: Topology, order: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Doo-Sabin's corners with mates computed directly.

    Layout: F-faces (corner c at c), edge quads (edge k at C + 4k:
    next(a), a, next(b), b for its sides a, b), V-faces (``order[q]`` at C + 4E + q).
    ``order``: the corners of the V-faces (see :func:`_doo_sabin_build`); a
    valence-2 vertex gets no 2-gon: the two quad sides that would meet it meet
    each other (one edge, as TopMod leaves them).
    Returns the ``(C + 4E + R,)`` int64 vertex and mate of every new corner, each
    filled block by block in place (no stacking and concatenating).
    """
    nc, c = t.nc, np.arange(t.nc)
    ring_base = nc + 4 * t.ne
    a, b = t.edge_corners[:, 0], t.edge_corners[:, 1]
    is_a = a[t.edge] == c
    prv = t.prv
    side = nc + 4 * t.edge[prv] + np.where(is_a[prv], 3, 1)  # the quad side meeting c's V-corner
    target = _ring_targets(t, order, side, ring_base)
    verts = np.empty(ring_base + len(order), dtype=np.int64)
    verts[:nc] = c
    _columns(verts[nc:ring_base], t.nxt[a], a, t.nxt[b], b)
    verts[ring_base:] = order
    mates = np.empty(ring_base + len(order), dtype=np.int64)
    mates[:nc] = nc + 4 * t.edge + np.where(is_a, 0, 2)
    _columns(mates[nc:ring_base], a, target[t.nxt[b]], b, target[t.nxt[a]])
    mates[ring_base:] = side[order]
    return verts, mates


def _ring_targets(t: Topology, order: np.ndarray, side: np.ndarray,
                  ring_base: int) -> np.ndarray:
    """``(C,)``: what meets the quad side ``side[r]`` of each corner r: r's V-corner
    (at ``ring_base`` + its place in ``order``), or, for r in a ring of two, the
    quad side of the other corner of the ring (``vprev(r)``)."""
    if len(order) == t.nc:
        target = np.empty(t.nc, dtype=np.int64)
        target[order] = ring_base + np.arange(t.nc)
        return target
    target = side[t.vprev]
    target[order] = ring_base + np.arange(len(order))
    return target


def _columns(out: np.ndarray, *columns: np.ndarray) -> None:
    """Interleave the ``(k,)`` ``columns`` into the flat ``out`` (``(k * len(columns),)``)."""
    rows = out.reshape(-1, len(columns))
    for i, column in enumerate(columns):
        rows[:, i] = column


def doo_sabin(mesh: Mesh, *, check: bool = True, max_faces: int | None = None) -> None:
    """Doo-Sabin subdivision (TopMod ``dooSabinSubdivide(check)``, "doo-sabin").

    Rule: each corner i of an n-gon gets the point sum_j w_ij v_j with
    w_ii = 1/4 + 5/(4n), w_ij = (3 + 2 cos(2 pi (i - j)/n)) / (4n) (quads:
    9/16, 3/16, 3/16, 1/16). New faces: one per face, one quad per edge, one per
    vertex of valence >= 3 (a valence-2 vertex joins its two quads by one edge;
    at a valence-1 vertex, the end of a dangling edge, the edge's quad is a
    triangle). Cube: 24/48/26. ``check`` (TopMod: skip corners already adjacent when joining)
    is accepted for compatibility; the vectorized joins never need it.

    Raises:
        DLFLError: the face budget.
    """
    del check
    t = budgeted_topology(mesh, "doo-sabin", max_faces, SIZES["doo-sabin"],
                          EXACT["doo-sabin"])
    points = face_weighted(t, np.take(t.pos, t.cv, axis=0),
                           lambda n: cos_weights(n, 0.25 + 1.25 / n))
    _doo_sabin_like(mesh, t, points)


def corner_cut(mesh: Mesh, *, alpha: float = 9 / 16, max_faces: int | None = None) -> None:
    """Corner cutting (TopMod ``cornerCuttingSubdivide(alpha)``, "corner-cut").

    Rule: Doo-Sabin's topology with w_ii = alpha,
    w_ij = (1 - alpha)(3 + 2 cos(2 pi (i - j)/n)) / (3n - 5). GUI default 9/16,
    range [1/3, 0.999] (the GUI's; livemod refuses values outside it).
    Cube: 24/48/26.

    Raises:
        DLFLError: ``alpha`` outside [1/3, 0.999], or the face budget.
    """
    alpha = check_number("alpha", alpha, 0.333, 0.999)
    t = budgeted_topology(mesh, "corner-cut", max_faces, SIZES["corner-cut"],
                          EXACT["corner-cut"])
    points = face_weighted(t, np.take(t.pos, t.cv, axis=0), lambda n: cos_weights(n, alpha))
    _doo_sabin_like(mesh, t, points)


def doo_sabin_bc(mesh: Mesh, *, check: bool = True, max_faces: int | None = None) -> None:
    """Doo-Sabin with boundary curves (TopMod "doo-sabin-bc"): split every edge at
    its midpoint, then :func:`doo_sabin`. Cube: 48/84/38 (8 triangles, 24 quads,
    6 octagons). ``check`` is accepted and, as in TopMod, has no effect.

    Raises:
        DLFLError: the face budget.
    """
    del check
    t = budgeted_topology(mesh, "doo-sabin-bc", max_faces, SIZES["doo-sabin-bc"],
                          EXACT["doo-sabin-bc"])
    order, offsets = t.vertex_rings()
    ring_sizes = np.diff(offsets)
    split = _split_edges(t)
    points = face_weighted(split, np.take(split.pos, split.cv, axis=0),
                           lambda n: cos_weights(n, 0.25 + 1.25 / n))
    if len(ring_sizes) and ring_sizes.min() < 2:
        _doo_sabin_like(mesh, split, points)  # valence 1: the general path
        return
    # the split mesh's rings of three corners or more are the old ones (corner c
    # is its corner 2c), in the same order; every midpoint has a ring of two
    kept = ring_sizes >= 3
    _doo_sabin_build(mesh, split, points, 2 * order[np.repeat(kept, ring_sizes)],
                     ring_sizes[kept])


def _split_edges(t: Topology) -> Topology:
    """The arrays of :func:`subdivide_all_edges` on ``t``, without pairing by label.

    Corner c becomes corners 2c (at its vertex) and 2c + 1 (at its edge's
    midpoint, vertex V + edge); the side from 2c meets 2 mate(c) + 1.
    """
    cv = np.empty(2 * t.nc, dtype=np.int64)
    cv[0::2] = t.cv
    cv[1::2] = t.nv + t.edge
    mate = np.empty(2 * t.nc, dtype=np.int64)
    mate[0::2] = 2 * t.mate + 1
    mate[1::2] = 2 * t.mate
    return Topology(np.concatenate([t.pos, t.midpoints()]), cv, mate, 2 * t.offsets, t.origin,
                    t.spheres, np.zeros(t.nf, dtype=np.int64), t.source,
                    sphere_colors=t.sphere_colors)
