"""Schemes built from insets and Doo-Sabin extrusions: checker (and its GUI dual
composite), doo-sabin-bc-new, dome.

Each function remeshes ``mesh`` in place (every element gets a fresh id) and
returns ``None``; hole faces are treated as faces and the faces made inside a
hole face are holes again; point-spheres survive. ``max_faces`` overrides the
face budget (:mod:`livemod.dlfl.budget`).
"""

from __future__ import annotations

import numpy as np

from ..errors import InvalidArgumentError
from ..mesh import Mesh
from ..normals import inset_offsets, ring_layout, ring_normals
from ._layout import (
    Faces,
    Topology,
    budgeted_topology,
    build,
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
from ._sizes import SIZES, check_steps


def _checker_thickness(thickness: object) -> float:
    """The checkerboards' ``thickness`` as a float in (0, 0.5].

    Raises:
        DLFLError: not a finite number in (0, 0.5] (0 puts every new corner on an
            old vertex).
    """
    checked = check_number("thickness", thickness, 0.0, 0.5)
    if checked == 0.0:
        raise InvalidArgumentError(
            "option thickness must be in (0, 0.5]: 0 puts the new corners on "
            "the old vertices")
    return checked


def checker(mesh: Mesh, *, thickness: float = 0.33, max_faces: int | None = None) -> None:
    """Checkerboard remeshing (TopMod ``checkerBoardRemeshing(t)``, "checker").

    Rule: each face gets an inset copy whose corner p moves by
    t * ((prev - p) + (next - p)) (flipped at concave corners; a straight
    corner moves t square to its next edge, TopMod's planar offset,
    :func:`livemod.dlfl.normals.inset_offsets`); each edge gets
    the points at t * its length from both ends; around every old vertex the
    corners are cut and the inset spokes removed. An n-gon becomes its inset
    n-gon, n quads along its sides and, with its neighbours, one quad per corner
    at every old vertex. GUI default 0.33. Cube: 56/108/54 quads.
    Differences from TopMod: thickness outside (0, 0.5] is refused (TopMod took
    a negative value as 0.25 and clamped above 0.5).

    Raises:
        DLFLError: a bad ``thickness``, or the face budget.
    """
    thickness = _checker_thickness(thickness)
    t = budgeted_topology(mesh, "checker", max_faces, SIZES["checker"])
    p, next_p = rows(t.pos, t.cv), rows(t.pos, t.cv[t.nxt])
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        inset = p + inset_offsets(t.pos, t.cv, t.offsets, thickness)
        near = p + thickness * (next_p - p)
    positions = np.concatenate([t.pos, near, inset])
    _checker_faces(mesh, t, positions, t.origin)


def dual_checkerboard(mesh: Mesh, *, thickness: float = 0.33,
                      max_faces: int | None = None) -> None:
    """GUI "Dual Checkerboard" (TopMod: dual, checker(t), dual), in one step.

    The dual of ``checker`` on the dual has checker's own topology on the mesh
    (old vertex v <-> the dual's inset face of v, near(c) <-> the dual's side
    quad along the edge of c, inset(c) <-> the dual's corner quad of c), so
    this lays out :func:`checker`'s faces and puts each vertex at the centroid
    of its face of checker-on-the-dual, computed from the dual's geometry over
    the mesh's own corners. No face is a hole (a dual makes none). Cube:
    56/108/54 quads.

    Raises:
        DLFLError: a bad ``thickness``, or the face budget.
    """
    thickness = _checker_thickness(thickness)
    check_steps(mesh, ("dual", "checker", "dual"), max_faces)
    t = read_topology(mesh)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        inset, near = _checker_on_dual(t, thickness)
        nxt = t.nxt
        side = nxt[t.mate]  # the dual's corner whose side quad lies along the edge of c
        at_vertex = vertex_mean(t, inset)
        at_near = (rows(near, side) + rows(near, nxt) + inset + rows(inset, side)) / 4.0
        at_inset = (rows(t.centroids(), t.face) + near + inset + rows(near, nxt)) / 4.0
    positions = np.concatenate([at_vertex, at_near, at_inset])
    _checker_faces(mesh, t, positions, no_origin(t.nf))


def _checker_on_dual(t: Topology, thickness: float) -> tuple[np.ndarray, np.ndarray]:
    """``(C, 3)`` inset and near points of :func:`checker` on the dual of ``t``.

    The dual's corner of mesh corner c sits at the centroid of face(c); its
    face is c's vertex ring (:meth:`Topology.vertex_rings`, in the dual's ring
    order: its next corner is ``mate(prev c)``, its previous one ``next(mate c)``).
    """
    cen = t.centroids()
    p = rows(cen, t.face)
    next_p = rows(cen, t.face[t.mate[t.prv]])
    order, offsets = t.vertex_rings()
    move = np.empty((t.nc, 3))
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        move[order] = inset_offsets(cen, t.face[order], offsets, thickness)
        return p + move, p + thickness * (next_p - p)


def _checker_faces(mesh: Mesh, t: Topology, positions: np.ndarray, origin: np.ndarray) -> None:
    """Inset faces (corner c at c), side quads (at C + 4c: near(c), near(mate c),
    inset(next c), inset(c)) and corner quads (at 5C + 4c: vertex, near(c),
    inset(c), near(mate(prev c)))), their mates computed directly.

    ``origin`` ``(F,)``: the old faces' origins, given to their inset faces and side quads.
    """
    v, nc, c = t.nv, t.nc, np.arange(t.nc)
    nxt, prv, mate = t.nxt, t.prv, t.mate
    near, inset = v + c, v + nc + c
    side = np.stack([near, v + mate, v + nc + nxt, inset], axis=1)
    side_mate = np.stack([nc + 4 * mate, 5 * nc + 4 * nxt + 2, c, 5 * nc + 4 * c + 1], axis=1)
    corner = np.stack([t.cv, near, inset, v + mate[prv]], axis=1)
    corner_mate = np.stack([5 * nc + 4 * nxt[mate] + 3, nc + 4 * c + 3, nc + 4 * prv + 1,
                            5 * nc + 4 * mate[prv]], axis=1)
    verts = np.concatenate([inset, side.ravel(), corner.ravel()])
    mates = np.concatenate([nc + 4 * c + 2, side_mate.ravel(), corner_mate.ravel()])
    sizes = np.concatenate([t.sizes, np.full(2 * nc, 4, dtype=np.int64)])
    origins = np.concatenate([origin, origin[t.face], no_origin(nc)])
    build_paired(mesh, t, positions, verts, mates, sizes, origins)


def _split_face_values(t: Topology) -> tuple[np.ndarray, np.ndarray]:
    """Corners of every face with its edges split at midpoints, interleaved.

    Returns ``(values, offsets)``: ``(2C, 3)`` positions (corner, midpoint of its
    side, ...) face after face, and the ``(F + 1,)`` ring offsets.
    """
    values = np.stack([rows(t.pos, t.cv), rows(t.midpoints(), t.edge)], axis=1).reshape(-1, 3)
    return values, 2 * t.offsets


def _ring_centroids(values: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """``(N, 3)``: the mean of each ring of ``values`` ``(N, 3)``, repeated per ring corner."""
    sizes = np.diff(offsets)
    means = ring_sums(offsets, values) / np.maximum(sizes, 1)[:, None]
    return np.repeat(means, sizes, axis=0)


def _ds_ring(values: np.ndarray, offsets: np.ndarray, shift: np.ndarray | float,
             scale: float) -> np.ndarray:
    """TopMod's ``extrudeFaceDS`` ring: shift, Doo-Sabin weights, scale about centroid."""
    moved = values + shift
    ring = ring_weighted(offsets, moved, lambda n: cos_weights(n, 0.25 + 1.25 / n))
    if scale not in (0.0, 1.0):
        cen = _ring_centroids(ring, offsets)
        ring = cen + abs(scale) * (ring - cen)
    return ring


def doo_sabin_bc_new(mesh: Mesh, *, length: float = 1.0, scale: float = 1.0,
                     max_faces: int | None = None) -> None:
    """Doo-Sabin BC New (TopMod ``dooSabinSubdivideBCNew(sf, len)``, "doo-sabin-bc-new").

    The options come in the thesis's order, length first (TopMod's module passed
    its first number to ``sf``).

    Rule: split every edge at its midpoint; every (split) face gets a Doo-Sabin
    extrusion of distance 0 scaled by ``scale``; the old edges and the midpoints
    go: each half edge becomes a pentagon (old vertex, two inner points on each
    side) and each face its 2n-gon; old vertices move to
    length * v + (1 - length) * mean(their new neighbours). GUI defaults 1, 1.
    Cube: 56/84/30 (24 pentagons, 6 octagons).

    Raises:
        DLFLError: a bad option value, or the face budget.
    """
    scale = check_number("scale", scale)
    length = check_number("length", length)
    t = budgeted_topology(mesh, "doo-sabin-bc-new", max_faces, SIZES["doo-sabin-bc-new"])
    values, offsets = _split_face_values(t)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        ring = _ds_ring(values, offsets, np.zeros(1), scale)
        at_vertex, at_mid = ring[0::2], ring[1::2]
        vertices = length * t.pos + (1 - length) * vertex_mean(t, at_vertex)
    positions = np.concatenate([vertices, at_vertex, at_mid])
    _bc_new_faces(mesh, t, positions)


def _bc_new_faces(mesh: Mesh, t: Topology, positions: np.ndarray) -> None:
    v, nc, c = t.nv, t.nc, np.arange(t.nc)
    rv, rm = v + c, v + nc + c
    b = t.mate
    nb = t.nxt[b]
    # labels: ring sides vertex->mid c, mid->vertex nc + c, spokes 2nc + c,
    # midpoint links 3nc + edge
    faces = Faces()
    faces.add(np.stack([rv, rm], axis=1), np.stack([c, nc + c], axis=1), t.origin, 2 * t.sizes)
    verts = np.stack([t.cv, v + nb, v + nc + b, rm, rv], axis=1)
    labels = np.stack([2 * nc + nb, nc + b, 3 * nc + t.edge, c, 2 * nc + c], axis=1)
    faces.add(verts, labels, no_origin(nc))
    build(mesh, t, positions, faces)


DOME_DISTANCES = (0.0, 0.3, 0.18, 0.1, 0.05, 0.025, 0.01)
DOME_SCALES = (1.6, 1.7, 1.6, 1.4, 1.2, 1.1, 0.01)


def dome(mesh: Mesh, *, length: float = 1.0, scale: float = 1.0,
         max_faces: int | None = None) -> None:
    """Dome (TopMod ``domeSubdivide(len, sf)``, "dome").

    Rule: split every edge into 4; every face then gets 7 Doo-Sabin extrusions
    (distance d along the face normal, Doo-Sabin weights, scale s about the
    centroid) with d = (0, .3, .18, .1, .05, .025, .01) * length and
    s = (1.6, 1.7, 1.6, 1.4, 1.2, 1.1, .01) * scale. GUI defaults 1, 1.
    Each step moves along the normal of the ring it extrudes, as TopMod's.
    Cube: 716/1392/678 (672 quads, 6 16-gons).

    Raises:
        DLFLError: a bad option value, or the face budget.
    """
    length = check_number("length", length)
    scale = check_number("scale", scale)
    t = budgeted_topology(mesh, "dome", max_faces, SIZES["dome"])
    steps = len(DOME_DISTANCES)
    split_pos, corner_vertex, across, offsets = _split_in_four(t)
    with np.errstate(over="ignore", invalid="ignore"):  # build refuses what overflows
        rings = _dome_rings(t, rows(split_pos, corner_vertex), offsets, length, scale)
    positions = np.concatenate([split_pos, rings.reshape(-1, 3)])
    verts, mates = _dome_corners(corner_vertex, across, offsets, len(split_pos), steps)
    split_origin = np.repeat(t.origin, 4 * t.sizes)
    sizes = np.concatenate([np.full(steps * len(across), 4, dtype=np.int64), 4 * t.sizes])
    origin = np.concatenate([np.tile(split_origin, steps), t.origin])
    build_paired(mesh, t, positions, verts, mates, sizes, origin)


def _dome_rings(t: Topology, first: np.ndarray, offsets: np.ndarray, length: float,
                scale: float) -> np.ndarray:
    """``(steps, N, 3)``: the point of every split corner on every extruded ring.

    ``first`` ``(N, 3)``: the split faces' corners; ``offsets`` their ring starts.
    Each step moves along its own ring's normal (TopMod extruded the end face of
    the step before, whose normal it computed afresh). A flat ring stays flat
    and keeps its normal through the steps (each one moves it along that normal,
    mixes its points and scales them about their centroid), so only the rings
    that are not flat get their normals measured again.
    """
    rings = np.empty((len(DOME_DISTANCES), len(first), 3))
    sizes = np.diff(offsets)
    normals = _StepNormals(offsets)
    previous = first
    for k, (d, s) in enumerate(zip(DOME_DISTANCES, DOME_SCALES, strict=True)):
        shift: np.ndarray | float = 0.0
        if d:
            shift = np.repeat(d * length * normals.of(previous), sizes, axis=0)
        rings[k] = _ds_ring(previous, offsets, shift, s * scale)
        previous = rings[k]
    return rings


# a ring whose points all lie this close to the plane through its first point
# along its normal (relative to its size) is flat: the steps keep its normal,
# which TopMod measured afresh to within rounding (about 1e-13 on the nearly
# straight corners of a dome ring)
_FLAT = 1e-14


class _StepNormals:
    """TopMod's face normals of the same rings at one step after another,
    re-measured only on the rings that were not flat the first time."""

    def __init__(self, offsets: np.ndarray) -> None:
        self.offsets = offsets
        self.layout = ring_layout(offsets)  # the same rings at every step
        self.normals: np.ndarray | None = None
        self.bent: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None

    def of(self, points: np.ndarray) -> np.ndarray:
        """``(R, 3)`` the face normals of the rings at ``points`` ``(N, 3)``."""
        if self.normals is None:
            self.normals = ring_normals(points, np.arange(len(points)), self.offsets,
                                        self.layout).face
            self._find_bent(points)
            return self.normals
        assert self.bent is not None
        rings, corners, offsets = self.bent
        if len(rings):
            self.normals = self.normals.copy()
            self.normals[rings] = ring_normals(points[corners], np.arange(len(corners)),
                                               offsets).face
        return self.normals

    def _find_bent(self, points: np.ndarray) -> None:
        """Keep the rings that are not flat (or have no normal), their corners and offsets."""
        assert self.normals is not None
        ring, count = self.layout.ring, len(self.offsets) - 1
        rel = points - np.repeat(points[self.offsets[:-1]], np.diff(self.offsets), axis=0)
        height = np.zeros(count)
        np.maximum.at(height, ring, np.abs(np.einsum("ij,ij->i", rel, self.normals[ring])))
        size = np.zeros(count)
        np.maximum.at(size, ring, np.abs(rel).max(axis=1))
        bent = ~(height <= _FLAT * size) | ~self.normals.any(axis=1)
        rings = np.flatnonzero(bent)
        sizes = np.diff(self.offsets)[rings]
        starts = np.repeat(self.offsets[rings] - np.concatenate([[0], np.cumsum(sizes)[:-1]]), sizes)
        self.bent = rings, starts + np.arange(int(sizes.sum())), np.concatenate([[0], np.cumsum(sizes)])


def _split_in_four(t: Topology) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Every edge split into 4 equal parts.

    Returns positions ``(V + 3E, 3)``; per split corner (4 per old corner,
    face after face) its vertex ``(N,)`` and the split corner across its side
    ``(N,)``; and the split ring offsets ``(F + 1,)``.
    """
    ends = t.cv[t.edge_corners]
    start, stop = rows(t.pos, ends[:, 0]), rows(t.pos, ends[:, 1])
    fractions = np.array([0.25, 0.5, 0.75])
    points = start[:, None, :] + fractions[None, :, None] * (stop - start)[:, None, :]
    positions = np.concatenate([t.pos, points.reshape(-1, 3)])
    forward = t.edge_corners[t.edge, 0] == np.arange(t.nc)
    j = np.arange(3)
    along = np.where(forward[:, None], j[None, :], 2 - j[None, :])
    inner = t.nv + 3 * t.edge[:, None] + along
    corner_vertex = np.concatenate([t.cv[:, None], inner], axis=1).ravel()
    # segment s of corner c runs the other way as segment 3 - s of mate(c)
    across = (4 * t.mate[:, None] + np.arange(3, -1, -1)).ravel()
    return positions, corner_vertex, across, 4 * t.offsets


def _dome_corners(corner_vertex: np.ndarray, across: np.ndarray, offsets: np.ndarray,
                  base: int, steps: int) -> tuple[np.ndarray, np.ndarray]:
    """Corners of ``steps`` stacked extrusions of every split face, mates computed directly.

    Layer ``k`` quad of split corner ``i`` (corners ``4(kN + i) + j``): lower(i),
    lower(next i), upper(next i), upper(i), where ring ``k`` point of ``i`` is
    ``base + kN + i`` and layer 0's lower points are the split corners; then the
    end faces (corner ``4 steps N + i``). Returns ``(4 steps N + N,)`` vertices and mates.
    """
    n = len(corner_vertex)
    i = np.arange(n, dtype=np.int64)
    nxt = i + 1
    nxt[offsets[1:] - 1] = offsets[:-1]
    prv = np.empty(n, dtype=np.int64)
    prv[nxt] = i
    verts = np.empty((steps, n, 4), dtype=np.int32)  # the builder's own dtype
    mates = np.empty((steps, n, 4), dtype=np.int64)
    for k in range(steps):
        lower = corner_vertex if k == 0 else base + (k - 1) * n + i
        upper = base + k * n + i
        verts[k] = np.stack([lower, lower[nxt], upper[nxt], upper], axis=1)
        mates[k, :, 0] = 4 * across + 0 if k == 0 else 4 * ((k - 1) * n + i) + 2
        mates[k, :, 1] = 4 * (k * n + nxt) + 3
        mates[k, :, 2] = 4 * ((k + 1) * n + i) if k < steps - 1 else 4 * steps * n + i
        mates[k, :, 3] = 4 * (k * n + prv) + 1
    end_verts = (base + (steps - 1) * n + i).astype(np.int32)
    end_mates = 4 * ((steps - 1) * n + i) + 2
    return (np.concatenate([verts.ravel(), end_verts]),
            np.concatenate([mates.ravel(), end_mates]))
