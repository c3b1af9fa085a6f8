"""Wireframe sculptures: modified corner cutting, the wireframe crust and columns.

TopMod's ``makeWireframe(t, split)``: ``modifiedCornerCuttingSubdivide(t)`` makes
an inner polygon per face whose corners sit ``t/2`` from both neighbouring edges
(the "front copies", typed FTHole), then ``createCrustForWireframe`` duplicates
the object reversed and places each copied vertex from the planes of the two
bevel quads beside it, and ``punchHoles`` opens every front copy into a tube.
The result is a solid wire of thickness ``t`` along every edge. livemod builds
each stage in one vectorized pass over corner arrays (see :mod:`.rind`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._checks import first_not_finite, is_id, positive_number, shown
from ._column_joints import joint_polygons
from ._vectors import in_range, lengths, together_in_range
from ._vectors import unit as _unit
from .analysis import face_centroids
from .arrays import MeshArrays, mesh_arrays
from .budget import check_size
from .build import from_corner_arrays
from .errors import GeometryError, InvalidArgumentError, NonManifoldError
from .mesh import Mesh
from .rind import shell_arrays
from .soup import offsets_of

__all__ = [
    "CornerCut", "corner_cut_arrays", "modified_corner_cut", "vertex_rings", "wireframe",
    "wireframe_inner_positions",
]


@dataclass(frozen=True)
class CornerCut:
    """The modified-corner-cut mesh as corner arrays.

    Attributes:
        positions: ``(C, 3)`` one new vertex per original corner, in corner order.
        offsets: ``(F + E + V + 1,)`` face offsets: the inner polygon of every
            original face (the front copies), then one quad per original edge,
            then one polygon per original vertex.
        corner_vertex: ``(4E + C + C,)`` int64 vertex of each corner.
        corner_mate: the other side of each corner's edge.
        face_hole: hole flags (an inner polygon keeps its face's flag).
        num_front: number of front copies: faces ``0..num_front-1``.
        face_colors: ``(F, 3)`` colours (an inner polygon keeps its face's, the
            others have none: NaN), or None.
    """

    positions: np.ndarray
    offsets: np.ndarray
    corner_vertex: np.ndarray
    corner_mate: np.ndarray
    face_hole: np.ndarray
    num_front: int
    face_colors: np.ndarray | None = None


def vertex_rings(a: MeshArrays) -> tuple[np.ndarray, np.ndarray]:
    """Corners around every vertex, each ring walked against ``vnext``.

    Returns:
        ``(order (C,), offsets (V + 1,))``: vertex ``v``'s corners are
        ``order[offsets[v]:offsets[v + 1]]``, each followed by its ``vprev``, so
        a polygon through them faces outward. Pointer doubling, O(C log valence).

    Raises:
        DLFLError: a vertex whose corners form more than one cycle.
    """
    vnext = a.corner_vnext
    n = len(vnext)
    counts = np.bincount(a.corner_vertex, minlength=len(a.vertex_ids))
    offsets = offsets_of(counts)
    # the root of each vertex's cycle is its first corner in corner order
    first = np.full(len(counts), n, np.int64)
    np.minimum.at(first, a.corner_vertex, np.arange(n))
    is_root = np.zeros(n, bool)
    is_root[first[counts > 0]] = True
    dist, last = _distance_to_cycle_end(vnext, is_root)
    size = counts[a.corner_vertex]
    cycles = np.bincount(a.corner_vertex[last], minlength=len(counts))
    if (dist >= size).any() or not np.array_equal(cycles, (counts > 0).astype(np.int64)):
        raise NonManifoldError(
            "a vertex's corners form several fans; the mesh is not manifold there")
    order = np.empty(n, np.int64)
    order[offsets[a.corner_vertex] + (dist + 1) % size] = np.arange(n)
    return order, offsets


def _distance_to_cycle_end(succ: np.ndarray, is_root: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Steps along ``succ`` from each element to the one just before a root, and
    which elements are those (pointer doubling, O(n log cycle length)).

    An element on a cycle without a root gets a distance beyond every cycle's
    length (its doubling never settles, so it stops after as many rounds as any
    path to a root can need).
    """
    last = is_root[succ]
    succ = np.where(last, np.arange(len(succ)), succ)
    dist = (~last).astype(np.int64)
    for _ in range(len(succ).bit_length() + 1):
        dist += dist[succ]
        jumped = succ[succ]
        if np.array_equal(jumped, succ):
            break
        succ = jumped
    return dist, last


def _cut_points(a: MeshArrays, thickness: float, variant: int = 1) -> np.ndarray:
    """``(C, 3)`` TopMod's corner-cut point: ``t/2`` from both edges at the corner.

    ``v + x (n1 + n2)`` with ``n1, n2`` unit vectors to the previous and next
    corner and ``x = sqrt(t^2 / (1 - (n1.n2)^2))``, ``t = thickness / 2``. When the
    neighbours coincide (a 2-gon) the corner after next stands in for the next;
    at a straight corner the point moves ``t`` toward the face centroid.
    ``variant`` 2 is TopMod's ``modifiedCornerCuttingSubdivide2``: ``x = thickness``
    at every corner, so the point moves ``thickness |n1 + n2|`` along the
    bisector (not at all at a straight corner).

    Raises:
        DLFLError: ``thickness`` is so large that a point's coordinates overflow.
    """
    t = thickness / 2.0
    p = a.positions
    cv = a.corner_vertex
    nxt, prv = a.corner_next, a.corner_prev
    v0, v1, v2 = p[cv], p[cv[prv]], p[cv[nxt]]
    # differences of coordinates near the float maximum overflow, and so can
    # the points: inf and NaN come out as points _finite_cut refuses
    with np.errstate(over="ignore", invalid="ignore"):
        # relative to the corner's edges: an absolute 1e-3 took every corner of a
        # mesh below about 1e-3 across for a 2-gon's
        reach = np.maximum(lengths(v1 - v0), lengths(v2 - v0))
        close = lengths(v1 - v2) < 5e-4 * reach
        v2[close] = p[cv[nxt[nxt[close]]]]
        n1, n2 = _unit(v1 - v0), _unit(v2 - v0)
        dot = np.einsum("ij,ij->i", n1, n2)
        denom = 1.0 - dot * dot
        if variant == 2:
            return _finite_cut(a, v0 + thickness * (n1 + n2), thickness)
        straight = denom < 1e-12
        toward = _unit(face_centroids(a)[a.corner_face[straight]] - v0[straight])
        x = _cut_distance(t, np.where(straight, 1.0, denom))
        points = v0 + x[:, None] * (n1 + n2)
        points[straight] = v0[straight] + t * toward
    return _finite_cut(a, points, thickness)


def _cut_distance(t: float, denom: np.ndarray) -> np.ndarray:
    """``(C,)`` ``sqrt(t^2 / denom)`` for ``(C,)`` ``denom`` in (0, 1]; inf (unwarned
    only inside the caller's errstate) where it overflows.

    ``t * t`` overflows from ``t ~ 1e154`` though the root does not: past 2**500
    ``t`` comes out of the root (the same value, rounded differently).
    """
    return np.sqrt(t * t / denom) if t < 2.0 ** 500 else t / np.sqrt(denom)


def _finite_cut(a: MeshArrays, points: np.ndarray, thickness: float) -> np.ndarray:
    """``points`` (``(C, 3)``, one per corner), checked.

    Raises:
        DLFLError: a coordinate overflowed; names the first such corner's vertex.
    """
    c = first_not_finite(points)
    if c is None:
        return points
    v = int(a.vertex_ids[a.corner_vertex[c]])
    raise GeometryError(f"cutting corners by {thickness} would put a point at vertex {v} at "
                        f"{points[c].tolist()}: its numbers overflow; use a smaller thickness "
                        "(or width)")


def corner_cut_arrays(a: MeshArrays, thickness: float, variant: int = 1) -> CornerCut:
    """Modified corner cutting of ``a`` as corner arrays (see :class:`CornerCut`);
    ``variant`` picks the corner points' rule (see :func:`modified_corner_cut`).

    Edge ``e`` with sides ``c0`` (in face f0) and ``c1`` (in f1) becomes the quad
    ``[q(next c0), q(c0), q(next c1), q(c1)]``; vertex ``v`` becomes the polygon
    of the points of its corners, walked against ``vnext``.
    """
    _check_cut_input(a, thickness)
    nc, ne = len(a.corner_vertex), len(a.edge_ids)
    nxt = a.corner_next
    c0, c1 = a.edge_corners[:, 0], a.edge_corners[:, 1]
    ring, ring_offsets = vertex_rings(a)
    quads = np.stack([nxt[c0], c0, nxt[c1], c1], axis=1).ravel()
    corner_vertex = np.concatenate([np.arange(nc), quads, ring])
    quad_start = nc
    ring_start = nc + 4 * ne
    # output index of the vertex-polygon corner of each original corner
    ring_pos = np.empty(nc, np.int64)
    ring_pos[ring] = ring_start + np.arange(nc)
    mate = np.empty(nc + 4 * ne + nc, np.int64)
    e_ids = np.arange(ne)
    mate[c0] = quad_start + 4 * e_ids
    mate[c1] = quad_start + 4 * e_ids + 2
    mate[quad_start + 4 * e_ids] = c0
    mate[quad_start + 4 * e_ids + 2] = c1
    mate[quad_start + 4 * e_ids + 1] = ring_pos[nxt[c1]]
    mate[quad_start + 4 * e_ids + 3] = ring_pos[nxt[c0]]
    mate[ring_pos[nxt[c1]]] = quad_start + 4 * e_ids + 1
    mate[ring_pos[nxt[c0]]] = quad_start + 4 * e_ids + 3
    sizes = np.concatenate([a.face_sizes, np.full(ne, 4), np.diff(ring_offsets)])
    offsets = offsets_of(sizes)
    hole = np.concatenate([a.face_hole, np.zeros(ne + len(a.vertex_ids), bool)])
    # an inner polygon keeps its face's colour; edge and vertex faces have no one source
    colors = a.colors_at(np.concatenate([np.arange(len(a.face_ids)),
                                         np.full(ne + len(a.vertex_ids), -1)]))
    return CornerCut(_cut_points(a, thickness, variant), offsets, corner_vertex, mate, hole,
                     len(a.face_ids), colors)


def _check_cut_input(a: MeshArrays, thickness: float) -> None:
    positive_number(thickness, "thickness")
    if len(a.face_ids) == 0:
        raise InvalidArgumentError("corner cutting needs a mesh with faces; this one is empty")
    if (a.corner_edge < 0).any():
        v = int(a.vertex_ids[a.corner_vertex[np.flatnonzero(a.corner_edge < 0)[0]]])
        raise InvalidArgumentError(
            f"corner cutting needs a mesh without point-spheres; vertex {v} is one")


def modified_corner_cut(mesh: Mesh, thickness: float = 0.25, variant: int = 1, *,
                        max_faces: object = None) -> list[int]:
    """TopMod's ``modifiedCornerCuttingSubdivide(thickness)`` (GUI 0.25).

    Every face gets an inner polygon whose corners are ``thickness / 2`` from
    both edges at that corner; every edge becomes a quad and every vertex a
    polygon of its valence. Cube: 24/48/26 (8x3, 18x4). The mesh is rebuilt
    (fresh ids). livemod computes in double precision (TopMod used floats).
    ``variant=2`` is TopMod's ``modifiedCornerCuttingSubdivide2(thickness)``
    (in neither its GUI nor its Python module): the corner at ``v`` between
    unit edge directions ``n1, n2`` goes to ``v + thickness (n1 + n2)``, the
    same distance along both edges whatever the corner's angle (cube, 0.25:
    the same counts, points 0.25 from the corner along each edge).

    Returns:
        The ids of the inner polygons (TopMod's front copies, typed FTHole), in
        the order of the original faces: the faces :func:`wireframe` punches.

    Raises:
        DLFLError: ``thickness`` not positive, point-spheres; the mesh is unchanged.
        BudgetExceededError: the result would pass the face budget
            (``max_faces``; None: the session's, see :mod:`livemod.dlfl.budget`).
    """
    if not is_id(variant) or variant not in (1, 2):
        raise InvalidArgumentError(f"variant must be 1 (TopMod's modifiedCornerCutting"
                                   f"Subdivide) or 2 (...Subdivide2), got {shown(variant)}")
    v, e, f = mesh.counts()
    check_size("modified corner cut", f + e + v, 4 * mesh.num_corners, max_faces=max_faces)
    cut = corner_cut_arrays(mesh_arrays(mesh), thickness, int(variant))
    first = mesh.next_ids()
    new = from_corner_arrays(cut.positions, cut.offsets, cut.corner_vertex, cut.corner_mate,
                             cut.face_hole, face_colors=cut.face_colors, first_ids=first)
    mesh.replace_with(new)
    return list(range(first[2], first[2] + cut.num_front))


def wireframe_inner_positions(a: MeshArrays, front: np.ndarray, thickness: float) -> np.ndarray:
    """``(V, 3)`` TopMod's ``createCrustForWireframe`` placement of the inner copy.

    Each vertex ``v0`` lies on exactly one front face; ``v1``/``v2`` are its next
    and previous corners there, ``v3`` the corner after ``v0`` in the bevel quad
    across ``v0 v1`` and ``v4`` the corner before ``v0`` in the bevel across
    ``v2 v0``. With ``n2`` in the first bevel's plane perpendicular to ``v0 v1``
    and ``n4`` likewise in the second, the copy sits at
    ``v0 - t * normalize(n2 x n4)``.

    Args:
        a: the corner-cut mesh.
        front: ``(F,)`` bool, the front copies.
        thickness: ``t``.
    """
    nxt, prv, mate, cv = a.corner_next, a.corner_prev, a.corner_mate, a.corner_vertex
    c0 = np.full(len(a.vertex_ids), -1, np.int64)
    on_front = np.flatnonzero(front[a.corner_face])
    c0[cv[on_front]] = on_front
    if (c0 < 0).any():
        raise InvalidArgumentError(
            "every vertex must lie on a front face (run modified_corner_cut first)")
    p = a.positions
    v0 = p[cv[c0]]
    # a huge cut puts points whose differences overflow: inf / NaN, refused below
    with np.errstate(over="ignore", invalid="ignore"):
        e1, e2 = in_range(p[cv[nxt[c0]]] - v0), in_range(p[cv[prv[c0]]] - v0)
        e3 = in_range(p[cv[nxt[nxt[mate[c0]]]]] - v0)
        e4 = in_range(p[cv[prv[mate[prv[c0]]]]] - v0)
        # TopMod normalises n1..n4 on the way; only their directions reach the result
        # (so each e may be scaled into range: raw, the cubes overflow beyond ~1e100)
        n2 = np.cross(np.cross(e1, e3), e1)
        n4 = np.cross(e2, np.cross(e2, e4))
        inner = v0 - thickness * _unit(np.cross(_unit(n2), _unit(n4)))
    v = first_not_finite(inner)
    if v is not None:
        raise GeometryError(f"a crust {thickness} thick would put the inner copy of vertex "
                            f"{int(a.vertex_ids[v])} at {inner[v].tolist()}: its numbers "
                            "overflow; use a smaller thickness")
    return inner


def wireframe(
    mesh: Mesh, thickness: float = 0.1, split: bool = True, *, width: float | None = None,
    max_faces: object = None,
) -> None:
    """TopMod's ``makeWireframe(t, split)`` (API default 0.1, GUI 0.25).

    With ``width``, TopMod's ``makeWireframe2(t, width, split)``: the corners are
    cut by ``width`` and the crust is ``thickness`` deep.

    Modified corner cutting at ``thickness``, then (with ``split``) TopMod's
    ``splitValence2Vertices(-1)`` where the cut left valence-2 vertices, then
    the wireframe crust and every front copy punched into a tube. Cube at any
    thickness: 48/120/64 (16x3, 48x4), genus 5. The mesh is rebuilt (fresh ids).

    Raises:
        DLFLError: ``thickness`` not positive, point-spheres; the mesh is unchanged.
        BudgetExceededError: the result would pass the face budget: it has
            ``2E + 2V + C`` faces and ``10 C`` corners (``max_faces``; None: the
            session's, see :mod:`livemod.dlfl.budget`).
    """
    thickness = positive_number(thickness, "thickness")
    if width is not None:
        width = positive_number(width, "width")
    v, e, _ = mesh.counts()
    corners = mesh.num_corners
    check_size("wireframe", 2 * (e + v) + corners, 10 * corners, max_faces=max_faces)
    cut = corner_cut_arrays(mesh_arrays(mesh), thickness if width is None else width)
    a = _arrays_of(cut)
    front = np.zeros(len(a.face_ids), bool)
    front[: cut.num_front] = True
    if split and (np.bincount(a.corner_vertex) == 2).any():
        work = from_corner_arrays(cut.positions, cut.offsets, cut.corner_vertex,
                                  cut.corner_mate, cut.face_hole, face_colors=cut.face_colors)
        front = _split_valence2(work, a, front)
        a = mesh_arrays(work)
    inner = wireframe_inner_positions(a, front, thickness)
    shell = shell_arrays(a, a.positions, inner, front, cleanup=False)
    mesh.replace_with(shell.build(mesh))


def _arrays_of(cut: CornerCut) -> MeshArrays:
    """The :class:`MeshArrays` of the mesh ``cut`` describes, without building it
    (ids are dense indices; edges numbered by their lower corner)."""
    nc = len(cut.corner_vertex)
    lower = np.flatnonzero(cut.corner_mate > np.arange(nc))
    corner_edge = np.empty(nc, np.int64)
    corner_edge[lower] = np.arange(len(lower))
    corner_edge[cut.corner_mate[lower]] = np.arange(len(lower))
    sizes = np.diff(cut.offsets)
    return MeshArrays(
        positions=cut.positions, vertex_ids=np.arange(len(cut.positions)),
        face_ids=np.arange(len(sizes)), face_offsets=cut.offsets, face_hole=cut.face_hole,
        corner_ids=np.arange(nc), corner_vertex=cut.corner_vertex,
        corner_face=np.repeat(np.arange(len(sizes)), sizes), corner_edge=corner_edge,
        corner_mate=cut.corner_mate, edge_ids=np.arange(len(lower)),
        edge_corners=np.stack([lower, cut.corner_mate[lower]], axis=1),
        face_colors=cut.face_colors,
    )


def _split_valence2(work: Mesh, a: MeshArrays, front: np.ndarray) -> np.ndarray:
    """Split valence-2 vertices of the cut mesh (rare: only where the input had
    valence-1 or valence-2 vertices); returns the front mask of the new layout."""
    valence = np.bincount(a.corner_vertex, minlength=len(a.vertex_ids))
    if not (valence == 2).any():
        return front
    from .geometry import split_valence2_vertices

    front_ids = set(a.face_ids[front].tolist())
    split_valence2_vertices(work, -1.0)
    ids = work.face_ids()
    return np.isin(ids, list(front_ids))


# -- columns ------------------------------------------------------------------


_HALF_MAX = float(np.finfo(np.float64).max) / 2


def column_rings(a: MeshArrays, thickness: float, segments: int) -> np.ndarray:
    """``(C, segments, 3)`` the ring of points around each corner's edge, at its vertex.

    TopMod's ``createWireframeWithSegments`` placement: at a vertex the rings sit
    at one axial distance ``L`` beyond every ``t / tan(theta/2) + |cos theta| t``
    (``theta`` the angle between two of its edges, plus ``0.001 t``), plus
    ``4e-4 t`` (TopMod: an absolute 1e-4, made for its GUI thickness 0.25), radius
    ``t``; the first point lies toward the sum of the two corner normals at the
    vertex in the faces beside the edge (a hole face's left out; any
    perpendicular when nothing is left), the others follow at steps of
    ``2 pi / segments`` about the edge (TopMod stepped by ``2 * 3.15 / segments``,
    a QUIRK livemod fixes).

    Raises:
        DLFLError: two edges at a vertex point the same way, or a point of a
            ring is beyond the float range (the thickness overflows).
    """
    p, cv = a.positions, a.corner_vertex
    with np.errstate(over="ignore", invalid="ignore"):  # refused just below
        along = p[cv[a.corner_next]] - p[cv]
    if not np.isfinite(along).all():
        raise GeometryError("columns need edges shorter than the float range; an edge's "
                            "ends lie too far apart (coordinates near 1e308)")
    axis = _unit(along)
    # TopMod's extra 1e-4 is for its GUI thickness 0.25: kept in proportion
    # (4e-4 t), or on a mesh 1e-150 across the rings, 1e-4 away, round to points
    length = _joint_lengths(a, axis, thickness)[cv] + 4e-4 * thickness
    u = _ring_starts(a, axis)
    w = np.cross(axis, u)
    angle = 2 * np.pi * np.arange(segments) / segments
    with np.errstate(over="ignore", invalid="ignore"):  # refused just below
        centre = p[cv] + length[:, None] * axis
        rings = centre[:, None, :] + thickness * (np.cos(angle)[None, :, None] * u[:, None, :]
                                                  + np.sin(angle)[None, :, None] * w[:, None, :])
    # beyond half the float range the differences the joints' hulls take overflow
    if not np.abs(rings).max(initial=0.0) <= _HALF_MAX:  # NaN fails too
        raise GeometryError(f"the thickness overflows: columns of thickness {thickness!r} would "
                            "put points beyond the float range; use a smaller thickness")
    return rings


def _joint_lengths(a: MeshArrays, axis: np.ndarray, t: float) -> np.ndarray:
    """``(V,)`` how far along its edges each vertex's rings must sit to clear each other."""
    order, offsets = vertex_rings(a)
    valence = np.diff(offsets)
    width = int(valence.max())
    slot = np.arange(width)
    valid = slot[None, :] < valence[:, None]
    idx = np.where(valid, offsets[:-1, None] + slot[None, :], 0)
    axes = axis[order[idx]]
    cos = np.clip(np.einsum("vid,vjd->vij", axes, axes), -1.0, 1.0)
    pair = valid[:, :, None] & valid[:, None, :] & ~np.eye(width, dtype=bool)[None]
    half = np.arccos(cos) / 2
    if (pair & (half < 1e-9)).any():
        raise GeometryError("two edges at one vertex point the same way; no column fits")
    # a huge t overflows to inf here, which column_rings refuses
    with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
        need = t / np.tan(np.where(pair, half, 1.0)) + np.abs(cos) * t + 0.001 * t
    return np.where(pair, need, 0.0).max(axis=(1, 2), initial=0.0)


def _ring_starts(a: MeshArrays, axis: np.ndarray) -> np.ndarray:
    """``(C, 3)`` unit direction of each ring's first point, perpendicular to ``axis``."""
    p, cv, nxt, prv = a.positions, a.corner_vertex, a.corner_next, a.corner_prev
    raw = _unit(np.cross(in_range(p[cv[nxt]] - p[cv]), in_range(p[cv[prv]] - p[cv])))
    raw[a.face_hole[a.corner_face]] = 0.0
    other = nxt[a.corner_mate]  # the same vertex's corner across the edge
    start = raw + raw[other]
    start -= np.einsum("ij,ij->i", start, axis)[:, None] * axis
    weak = np.linalg.norm(start, axis=1) <= 1e-9
    helper = np.zeros((int(weak.sum()), 3))
    along_x = np.abs(np.abs(axis[weak, 0]) - 1.0) < 1e-12
    helper[~along_x, 0] = 1.0
    helper[along_x, 1] = 1.0
    start[weak] = np.cross(axis[weak], helper)
    return _unit(start)


def columns(mesh: Mesh, thickness: float = 0.25, segments: int = 4, *,
            max_faces: object = None) -> None:
    """TopMod's ``makeWireframeWithColumns(t=0.25, segs=4)``: a tube of ``segments``
    quads around every edge, joined at every vertex by the convex hull of the
    tube ends, its faces as TopMod's hull cleanup leaves them
    (:mod:`._column_joints`: the hull cut into triangles, for an even
    ``segments`` TopMod's parity rule pairing them into quads, then faces in one
    plane merged).

    Rings as :func:`column_rings` (pi, not TopMod's 3.15); the tube of an edge
    pairs its two rings at their closest rotation (TopMod's ``connectFaces`` with
    closest corners). A valence-1 vertex ends its tube with a flat cap. Cube: 4
    segments 96/216/112, 6 segments 144/312/160, genus 5; a 4 x 4 torus
    256/560/272 ({4: 248, 5: 16, 6: 8}); the soccer ball 720/1620/840; TopMod's
    counts on each. A mesh whose vertices all have valence 3 gets ``8E``
    vertices and ``{3: 2V, 4: 6V + 4E}`` faces. For an odd ``segments`` the
    joints keep their hull's planar faces (TopMod's parity rule merged whole
    bands into 9- to 15-gons there). The mesh is rebuilt (fresh ids).

    Raises:
        DLFLError: ``thickness`` not positive, ``segments`` below 3, an empty
            mesh, point-spheres, self-loops, or rings that do not clear each
            other; the mesh is unchanged.
        BudgetExceededError: the result could pass the face budget
            (``max_faces``; None: the session's, see :mod:`livemod.dlfl.budget`).
    """
    thickness, segments = _check_columns_input(mesh, thickness, segments, max_faces)
    a = mesh_arrays(mesh)
    points = column_rings(a, thickness, segments).reshape(-1, 3)
    order, offsets = vertex_rings(a)
    polygons: list[list[int]] = []
    for v in range(len(a.vertex_ids)):
        ring = order[offsets[v]:offsets[v + 1]]
        polygons.extend(_joint(points, (ring * segments).tolist(), segments))
    polygons.extend(_tubes(points, a.edge_corners * segments, segments).tolist())
    from .build import from_polygons

    mesh.replace_with(from_polygons(points, polygons, first_ids=mesh.next_ids()))


def _check_columns_input(mesh: Mesh, thickness: float, segments: int,
                         max_faces: object) -> tuple[float, int]:
    """The checked ``(thickness, segments)``; see :func:`columns` for what is refused.

    The face budget is checked before any ring point exists: ``E`` tubes of
    ``s = segments`` quads, and at each vertex of valence ``k`` a joint of at
    most ``2ks`` faces (a hull of its ``ks`` ring points) and ``6ks`` corners
    less its ``k`` ring caps: at most ``5Es`` faces and ``14Es`` corners.
    """
    thickness = positive_number(thickness, "thickness")
    # 4.0 is a whole number too; a string, NaN or 3.5 is not
    whole = isinstance(segments, int | np.integer) or (
        isinstance(segments, float) and segments.is_integer())
    if isinstance(segments, bool) or not whole or segments < 3:
        raise InvalidArgumentError(
            f"segments must be a whole number of at least 3, got {segments!r}")
    if mesh.num_faces == 0:
        raise InvalidArgumentError("columns need a mesh with faces; this one is empty")
    tubes = mesh.num_edges * int(segments)
    check_size("columns", 5 * tubes, 14 * tubes, max_faces=max_faces)
    for v in mesh.vertex_ids().tolist():
        if mesh.is_point_sphere(v):
            raise InvalidArgumentError(
                f"columns need a mesh without point-spheres; vertex {v} is one")
    for e in mesh.edge_ids().tolist():
        u, w = mesh.edge_vertices(e)
        if u == w:
            raise InvalidArgumentError(f"columns cannot follow the self-loop edge {e}")
    return thickness, int(segments)


def _joint(points: np.ndarray, starts: list[int], segments: int) -> list[list[int]]:
    """The faces joining the rings that start at ``starts``: TopMod's joint
    (:mod:`._column_joints`) without the ring caps, or a flat end cap for a
    single ring."""
    if len(starts) == 1:
        return [list(range(starts[0] + segments - 1, starts[0] - 1, -1))]
    members = np.concatenate([np.arange(s, s + segments) for s in starts])
    polygons = joint_polygons(points[members], len(starts), segments)
    faces = [[int(members[i]) for i in f] for f in polygons]
    caps = {frozenset(range(s, s + segments)) for s in starts}
    joint = [f for f in faces if frozenset(f) not in caps]
    if len(faces) - len(joint) != len(starts):
        raise GeometryError("the column rings at a vertex overlap; use a smaller thickness")
    return joint


def _tubes(points: np.ndarray, starts: np.ndarray, segments: int) -> np.ndarray:
    """``(E * segments, 4)`` quads joining, per edge, ring ``starts[:, 0]`` (turning
    one way) to ring ``starts[:, 1]`` (the other way) at the rotation that pairs
    the closest points (TopMod's ``connectFaces`` with closest corners)."""
    j = np.arange(segments)
    k = np.arange(segments)
    a0, b0 = starts[:, :1, None], starts[:, 1:, None]
    # cost[e, k] = sum_j |A[j] - B[(k - j) % s]|
    pa = points[a0 + j[None, None, :]]
    pb = points[b0 + (k[None, :, None] - j[None, None, :]) % segments]
    # quarters cannot overflow in a difference, and one common power of two
    # keeps the norms in range without changing which rotation is closest
    gap = together_in_range(pa * 0.25 - pb * 0.25)
    best = np.linalg.norm(gap, axis=-1).sum(axis=-1).argmin(axis=1)[:, None]
    a, b = starts[:, :1], starts[:, 1:]
    quads = np.stack([a + j, a + (j + 1) % segments, b + (best - j - 1) % segments,
                      b + (best - j) % segments], axis=-1)
    return quads.reshape(-1, 4)
