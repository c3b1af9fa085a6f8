"""Rind modeling: a crust (the mesh plus a reversed inner copy) with faces punched open.

TopMod's ``DLFLCrust.cc``: ``createCrust`` writes the object as a reversed DLFL,
reads it back appended and moves the copy inward; ``cmMakeHole`` joins an outer
face with its inner twin by ``connectFaces`` (a tube of quads). livemod builds
the whole result in one vectorized pass: the outer shell without the punched
faces, the inner copy (each face's ring reversed) without their twins, and one
quad per side of every punched face, with every edge pairing computed directly.

Every function here rebuilds the mesh, so all elements get fresh ids (outer
vertices, edges and faces keep their relative order; the inner copy follows).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, replace

import numpy as np

from ._checks import finite_number, first_not_finite, id_list, shown
from ._vectors import centroid, face_ring_vectors, lengths, newell, unit
from .analysis import corner_normals, face_normals
from .arrays import MeshArrays, mesh_arrays
from .budget import check_growth, check_size
from .build import from_corner_arrays
from .connect import connect_faces
from .errors import GeometryError, InvalidArgumentError, UnknownIdError
from .mesh import Mesh
from .normals import RingNormals, reversed_rings, ring_normals

__all__ = ["CrustTwins", "Shell", "crust", "crust_offsets", "punch", "rind", "shell_arrays"]


@dataclass(frozen=True)
class Shell:
    """Corner arrays of a rebuilt mesh, ready for :func:`from_corner_arrays`.

    Attributes:
        positions: ``(V, 3)`` float64.
        offsets: ``(F + 1,)`` int64 face offsets into the corner arrays.
        corner_vertex: ``(C,)`` int64 vertex index of each corner.
        corner_mate: ``(C,)`` int64 corner on the other side of each corner's edge.
        face_hole: ``(F,)`` bool hole flags.
        face_colors: ``(F, 3)`` float32 colours (NaN: none), or None.
    """

    positions: np.ndarray
    offsets: np.ndarray
    corner_vertex: np.ndarray
    corner_mate: np.ndarray
    face_hole: np.ndarray
    face_colors: np.ndarray | None = None

    def build(self, mesh: Mesh) -> Mesh:
        """The mesh these arrays describe, with ids following ``mesh``'s counters."""
        return from_corner_arrays(
            self.positions, self.offsets, self.corner_vertex, self.corner_mate,
            self.face_hole, face_colors=self.face_colors, first_ids=mesh.next_ids(),
        )


def crust_offsets(a: MeshArrays, thickness: float, uniform: bool = True) -> np.ndarray:
    """``(V, 3)`` outward displacement that offsets each vertex by ``thickness``.

    TopMod's rule: with the corner normals ``n_i`` at a vertex and their raw
    mean ``m``, the displacement is ``m * mean(t / (m . n_i))`` when ``uniform``
    (an exact offset ``t`` from every face plane of a cube corner), otherwise
    ``t * normalize(m)``. The corner normals are TopMod's (:mod:`.normals`): a
    straight ("winged") corner copies its nearest neighbour's, the previous one
    on a tie. For ``thickness > 0`` the moved copy is the reversed inner shell,
    whose normals TopMod computed on its reversed faces, where that tie goes to
    the other neighbour: so do these. A vertex none of whose corners has a
    normal takes its faces' normals instead.

    Raises:
        DLFLError: a vertex with no normal at all (its faces have no area).
    """
    return _scaled_offsets(a, _normal_means(a, thickness > 0), thickness, uniform)


@dataclass(frozen=True)
class _NormalMeans:
    """The corner normals a crust offset uses, and their mean at each vertex."""

    has: np.ndarray  # (C,) bool: corners with a normal, on faces that are not holes
    normals: np.ndarray  # (C, 3) unit corner normals
    count: np.ndarray  # (V,) float64 number of such corners at each vertex
    mean: np.ndarray  # (V, 3) their raw mean


def _normal_means(a: MeshArrays, reverse: bool,
                  reversed_rings_normals: RingNormals | None = None) -> _NormalMeans:
    """The corner normals of ``a`` and their means at each vertex; with
    ``reverse``, those of the reversed faces, turned back (see :func:`crust_offsets`;
    ``reversed_rings_normals``: :func:`reversed_normals` of ``a``, when the caller
    has them).

    A vertex all of whose corners are straight (one added on an edge, as
    ``subdivideEdge`` does) takes its faces' normals instead, so that it moves
    with the edge it lies on rather than staying on the outer shell.

    Raises:
        DLFLError: a vertex with no normal at all: its faces have no area.
    """
    if reverse:
        back = reversed_rings(a.face_offsets)
        rings = reversed_normals(a) if reversed_rings_normals is None else reversed_rings_normals
        normals = -rings.corner[back]
    else:
        normals = corner_normals(a)
    # hole faces (boundaries of open meshes) face the other way: leave them out
    solid = ~a.face_hole[a.corner_face]
    has = (np.linalg.norm(normals, axis=1) > 0.5) & solid
    nv = len(a.vertex_ids)
    count = np.bincount(a.corner_vertex[has], minlength=nv).astype(np.float64)
    if (count == 0).any():
        normals, has, count = _straight_vertex_normals(a, normals, has, count, solid)
    mean = np.zeros((nv, 3))
    np.add.at(mean, a.corner_vertex[has], normals[has])
    mean /= np.maximum(count, 1)[:, None]
    return _NormalMeans(has, normals, count, mean)


def reversed_normals(a: MeshArrays) -> RingNormals:
    """TopMod's normals of ``a``'s faces reversed (each ring read backwards from
    its last corner, :func:`livemod.dlfl.normals.reversed_rings`): those the inner
    shell of a crust is offset along."""
    back = reversed_rings(a.face_offsets)
    return ring_normals(a.positions, a.corner_vertex[back], a.face_offsets)


def _straight_vertex_normals(a: MeshArrays, normals: np.ndarray, has: np.ndarray,
                             count: np.ndarray, solid: np.ndarray,
                             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(normals, has, count)`` of :func:`_normal_means` with the corners of the
    vertices that have no corner normal (``count == 0``) given their face's normal.

    Raises:
        DLFLError: such a vertex none of whose faces has a normal either.
    """
    bare = (count == 0)[a.corner_vertex] & solid
    face_normal = face_normals(a)[a.corner_face]
    normals = np.where(bare[:, None], face_normal, normals)
    has = has | bare & (np.linalg.norm(normals, axis=1) > 0.5)
    count = np.bincount(a.corner_vertex[has], minlength=len(count)).astype(np.float64)
    if (count == 0).any():
        v = int(a.vertex_ids[np.flatnonzero(count == 0)[0]])
        raise GeometryError(f"vertex {v} has no face normal to offset it along: the faces at it "
                            "have no area (their corners are collinear or coincident); the "
                            "crust would have no thickness there")
    return normals, has, count


def _scaled_offsets(a: MeshArrays, m: _NormalMeans, thickness: float,
                    uniform: bool) -> np.ndarray:
    """``(V, 3)`` :func:`crust_offsets` from the vertices' normal means."""
    if not uniform:
        length = np.linalg.norm(m.mean, axis=1, keepdims=True)
        return thickness * np.divide(m.mean, length, out=np.zeros_like(m.mean),
                                     where=length > 0)
    dots = np.einsum("ij,ij->i", m.mean[a.corner_vertex[m.has]], m.normals[m.has])
    inverse = np.zeros(len(dots))
    np.divide(thickness, dots, out=inverse, where=np.abs(dots) > 1e-12)
    factor = np.bincount(a.corner_vertex[m.has], weights=inverse,
                         minlength=len(a.vertex_ids)).astype(np.float64)
    factor = factor / np.maximum(m.count, 1)
    return m.mean * factor[:, None]


def _face_newell(positions: np.ndarray, a: MeshArrays) -> tuple[np.ndarray, np.ndarray]:
    """Newell vector (twice the vector area) of each face at ``positions`` ``(V, 3)``,
    in range: ``(F, 3)`` vectors and ``(F,)`` int exponents ``e``, the true vector
    being ``vector * 4**e``."""
    r = face_ring_vectors(positions, a.corner_vertex, a.face_offsets, a.corner_face)
    sums = newell(r, r.along(a.corner_next), a.corner_face, len(a.face_ids))
    return sums, np.zeros(len(sums), np.int64) if r.exponent is None else r.exponent


def offset_shell(a: MeshArrays, thickness: float, uniform: bool,
                 reversed_rings_normals: RingNormals | None = None) -> np.ndarray:
    """``(V, 3)`` positions moved inward by :func:`crust_offsets`, checked
    (``reversed_rings_normals``: :func:`reversed_normals` of ``a``, when the
    caller has them).

    Raises:
        DLFLError: ``thickness`` is so large that a moved coordinate overflows.
    """
    means = _normal_means(a, thickness > 0, reversed_rings_normals)  # outside the errstate: its overflows are not checked here
    with np.errstate(over="ignore", invalid="ignore"):  # refused just below
        moved = a.positions - _scaled_offsets(a, means, thickness, uniform)
    i = first_not_finite(moved)
    if i is not None:
        raise GeometryError(f"thickness {thickness} would move vertex {int(a.vertex_ids[i])} to "
                            f"{moved[i].tolist()}: its numbers overflow; "
                            "use a smaller value")
    return moved


def check_not_inverted(a: MeshArrays, moved: np.ndarray, what: str) -> None:
    """Refuse a moved copy in which some face collapsed or turned over.

    Args:
        a: the mesh before moving.
        moved: ``(V, 3)`` the moved positions.
        what: names the parameter in the message.

    Raises:
        DLFLError: some face's vector area flips or vanishes, or the products
            that tell overflow (coordinates beyond about 1e154).
    """
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow is refused below
        bad = _inverted_faces(a, moved)
    if bad is None:
        raise GeometryError(f"{what} gives a crust too large to check for faces turning over "
                            "(its edge products overflow); use a smaller value or a smaller mesh")
    if bad.any():
        f = int(a.face_ids[np.flatnonzero(bad)[0]])
        raise GeometryError(
            f"{what} would invert the crust: the moved copy of face {f} "
            f"(and {int(bad.sum()) - 1} more) collapses or turns over; use a smaller value"
        )


def _inverted_faces(a: MeshArrays, moved: np.ndarray) -> np.ndarray | None:
    """``(F,)`` bool: faces whose moved copy collapses or turns over; None when
    the products that tell overflow (coordinates beyond about 1e154)."""
    bad = _flat_faces(a, moved)
    # a copy pushed through the middle keeps its face areas but reverses its sides
    ends = a.corner_vertex[a.edge_corners]
    side_before = a.positions[ends[:, 1]] - a.positions[ends[:, 0]]
    side_after = moved[ends[:, 1]] - moved[ends[:, 0]]
    length = np.einsum("ij,ij->i", side_before, side_before)
    sides = np.einsum("ij,ij->i", side_before, side_after)
    if not (np.isfinite(sides).all() and np.isfinite(length).all()):
        return None
    flipped = _reversed_sides(side_before, side_after)
    bad[a.corner_face[a.edge_corners[flipped, 0]]] = True
    return bad


def _reversed_sides(before: np.ndarray, after: np.ndarray) -> np.ndarray:
    """``(E,)`` bool: ``before . after <= 1e-9 |before|^2`` for ``(E, 3)`` sides,
    left out where ``before`` is far shorter than the longest side.

    Told from unit vectors and range-safe lengths: the raw squares underflow
    on a mesh 1e-160 across, and an absolute cut-off (1e-24) left out every
    side of one 1e-12 across, so an inverted tiny crust passed.
    """
    cos = np.einsum("ij,ij->i", unit(before), unit(after))
    long_before, long_after = lengths(before), lengths(after)
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        shrunk = cos * (long_after / long_before) <= 1e-9  # NaN (0/0) is False
    kept = long_before > 1e-12 * long_before.max(initial=0.0)
    return ((cos <= 0.0) | shrunk) & kept


def _flat_faces(a: MeshArrays, moved: np.ndarray) -> np.ndarray:
    """``(F,)`` bool: faces whose vector area at ``moved`` flips or vanishes
    (``after . before <= 1e-9 |before|^2``), told in range at any scale."""
    before, e_before = _face_newell(a.positions, a)
    after, e_after = _face_newell(moved, a)
    scale = np.linalg.norm(before, axis=1)
    dots = np.einsum("ij,ij->i", before, after)
    # both sides in the after-scale; beyond the float range means "far larger"
    with np.errstate(over="ignore"):
        limit = np.ldexp(1e-9 * scale * scale, 2 * (e_before - e_after))
    # faces of (all but) no area are left out, relative to the largest face: an
    # absolute 1e-12 left out every face of a mesh below about 1e-6 across
    top = int(e_before.max(initial=0))
    area = np.ldexp(scale, 2 * (e_before - top))
    return (area > 1e-12 * area.max(initial=0.0)) & (dots <= limit)


def shell_arrays(
    a: MeshArrays, outer: np.ndarray, inner: np.ndarray, punched: np.ndarray,
    cleanup: bool = True,
) -> Shell:
    """The crust of ``a`` with the faces in ``punched`` opened into tubes.

    Args:
        a: the original mesh (no point-spheres).
        outer: ``(V, 3)`` positions of the outer shell.
        inner: ``(V, 3)`` positions of the inner (reversed) copy.
        punched: ``(F,)`` bool, faces to open; each becomes one quad per side,
            ``[v_c, v_next, v'_next, v'_c]``, joining it to its twin.
        cleanup: drop the zero-thickness double wall that two punched faces
            sharing an edge would leave (TopMod's ``cmMakeHole`` cleanup).

    Returns:
        Outer vertices ``0..V-1`` then inner ``V..2V-1``; faces: kept outer faces,
        kept inner faces, then the tube quads, all in the order of ``a``.

    With ``cleanup``, a vertex whose faces are all punched disappears with its
    inner copy (the walls around it are all removed).
    """
    nc, nv = len(a.corner_vertex), len(a.vertex_ids)
    keep = ~punched
    corner_punched = punched[a.corner_face]
    wall = corner_punched & corner_punched[a.corner_mate] if cleanup else np.zeros(nc, bool)
    kept_c = np.flatnonzero(~corner_punched)
    tube_c = np.flatnonzero(corner_punched & ~wall)
    nk = len(kept_c)
    # dense output index of every original corner in each part
    out_idx = np.full(nc, -1, np.int64)
    out_idx[kept_c] = np.arange(nk)
    reversed_order = _reversed_ring_order(a, keep)
    in_idx = np.full(nc, -1, np.int64)
    in_idx[reversed_order] = nk + np.arange(len(reversed_order))
    quad_base = np.full(nc, -1, np.int64)
    quad_base[tube_c] = 2 * nk + 4 * np.arange(len(tube_c))
    parts = _ShellParts(out_idx, in_idx, quad_base, kept_c, reversed_order, tube_c, wall)
    mate = _shell_mates(a, parts)
    cv, nxt = a.corner_vertex, a.corner_next
    quads = np.stack([cv[tube_c], cv[nxt[tube_c]], cv[nxt[tube_c]] + nv, cv[tube_c] + nv], 1)
    corner_vertex = np.concatenate([cv[kept_c], cv[reversed_order] + nv, quads.ravel()])
    kept_sizes = a.face_sizes[keep]
    all_sizes = np.concatenate([kept_sizes, kept_sizes, np.full(len(tube_c), 4)])
    offsets = np.zeros(len(all_sizes) + 1, np.int64)
    np.cumsum(all_sizes, out=offsets[1:])
    hole = np.concatenate([a.face_hole[keep], a.face_hole[keep], np.zeros(len(tube_c), bool)])
    # both copies of a face take its colour; a tube quad, its punched face's
    kept_f = np.flatnonzero(keep)
    colors = a.colors_at(np.concatenate([kept_f, kept_f, a.corner_face[tube_c]]))
    shell = Shell(np.concatenate([outer, inner]), offsets, corner_vertex, mate, hole, colors)
    return _drop_unused_vertices(shell) if cleanup else shell


def _drop_unused_vertices(shell: Shell) -> Shell:
    """Remove vertices no corner uses: with cleanup, a vertex whose faces were all
    punched loses every face and edge (TopMod's edge deletions remove it as a
    point-sphere), and so does its inner copy."""
    used = np.zeros(len(shell.positions), bool)
    used[shell.corner_vertex] = True
    if used.all():
        return shell
    renumber = np.cumsum(used) - 1
    return replace(shell, positions=shell.positions[used],
                   corner_vertex=renumber[shell.corner_vertex])


@dataclass(frozen=True)
class _ShellParts:
    """Where each original corner went: ``-1`` where it has no copy in that part."""

    out_idx: np.ndarray
    in_idx: np.ndarray
    quad_base: np.ndarray
    kept_c: np.ndarray
    reversed_order: np.ndarray
    tube_c: np.ndarray
    wall: np.ndarray


def _reversed_ring_order(a: MeshArrays, keep: np.ndarray) -> np.ndarray:
    """Original corners of the kept faces in reversed ring order, head first.

    The reversed copy of corner ``c`` sits at ``c``'s vertex and its edge runs to
    ``prev(c)``'s vertex: the twin of ``prev(c)``'s edge.
    """
    sizes = a.face_sizes[keep]
    starts = a.face_offsets[:-1][keep]
    total = int(sizes.sum())
    face_start = np.repeat(starts, sizes)
    local_start = np.repeat(np.cumsum(sizes) - sizes, sizes)
    rank = np.arange(total) - local_start
    size_each = np.repeat(sizes, sizes)
    return face_start + (size_each - rank) % size_each


def _shell_mates(a: MeshArrays, p: _ShellParts) -> np.ndarray:
    """``(C_out,)`` the other side of every output corner's edge (see :func:`shell_arrays`)."""
    mate_in, nxt, prv = a.corner_mate, a.corner_next, a.corner_prev
    total = len(p.kept_c) + len(p.reversed_order) + 4 * len(p.tube_c)
    mate = np.empty(total, np.int64)

    def outer_side(c: np.ndarray) -> np.ndarray:
        # the outer edge c -> next(c): kept corner, or the first side of c's tube quad
        return np.where(p.out_idx[c] >= 0, p.out_idx[c], p.quad_base[c])

    def inner_side(c: np.ndarray) -> np.ndarray:
        # the inner edge v'(next c) -> v'(c): reversed corner next(c), or quad side 2
        return np.where(p.in_idx[nxt[c]] >= 0, p.in_idx[nxt[c]], p.quad_base[c] + 2)

    mate[p.out_idx[p.kept_c]] = outer_side(mate_in[p.kept_c])
    mate[p.in_idx[p.reversed_order]] = inner_side(mate_in[prv[p.reversed_order]])
    tube = p.tube_c
    base = p.quad_base[tube]
    mate[base] = outer_side(mate_in[tube])
    mate[base + 2] = inner_side(mate_in[tube])
    # side edges v -> v': skip round the vertex past removed double walls
    mate[base + 1] = p.quad_base[_skip_walls(nxt[tube], p.wall, nxt, mate_in)] + 3
    mate[base + 3] = p.quad_base[_skip_walls(prv[tube], p.wall, prv, mate_in)] + 1
    return mate


def _skip_walls(
    start: np.ndarray, wall: np.ndarray, step: np.ndarray, mate_in: np.ndarray
) -> np.ndarray:
    """Walk ``x -> step[mate[x]]`` (round a vertex) from ``start`` while ``x`` is a wall."""
    x = start.copy()
    todo = wall[x]
    while todo.any():
        x[todo] = step[mate_in[x[todo]]]
        todo = wall[x]
    return x


def _dense_faces(a: MeshArrays, faces: Iterable[int]) -> np.ndarray:
    """``(F,)`` bool mask of the listed face ids.

    Raises:
        DLFLError: an entry that is not an integer, or an id that is not a face.
    """
    mask = np.zeros(len(a.face_ids), bool)
    wanted = np.asarray(id_list(faces, "faces"), dtype=np.int64)
    if len(wanted) == 0:
        return mask
    where = np.searchsorted(a.face_ids, wanted)
    where = np.minimum(where, len(a.face_ids) - 1)
    missing = a.face_ids[where] != wanted
    if missing.any():
        raise UnknownIdError(f"face {int(wanted[missing][0])} is not a face of this mesh")
    mask[where] = True
    return mask


def _check_shell_input(a: MeshArrays) -> None:
    if (a.corner_edge < 0).any():
        v = int(a.vertex_ids[a.corner_vertex[np.flatnonzero(a.corner_edge < 0)[0]]])
        raise InvalidArgumentError(f"a crust needs a mesh without point-spheres; vertex {v} is one")
    if len(a.face_ids) == 0:
        raise InvalidArgumentError("a crust needs a mesh with faces; this one is empty")


def _shell_positions(
    a: MeshArrays, thickness: float | None, scale: float | None, uniform: bool
) -> tuple[np.ndarray, np.ndarray]:
    """``(outer, inner)`` ``(V, 3)`` positions of the two shells."""
    p = a.positions
    finite_number(scale if scale is not None else thickness,
                  "scale" if scale is not None else "thickness")
    if scale is not None:
        s = _checked_scale(a, scale)
        centre = centroid(p)
        with np.errstate(over="ignore", invalid="ignore"):  # refused just below
            moved = (p - centre) * (s if s > 0 else -1.0 / s) + centre
        v = first_not_finite(moved)
        if v is not None:
            raise GeometryError(f"scale {scale} would put vertex {int(a.vertex_ids[v])} "
                                "beyond the float range; use a scale nearer 1 or a smaller mesh")
        if s > 0:
            check_not_inverted(a, moved, f"scale {scale}")
            return p, moved
        return moved, p
    assert thickness is not None
    if thickness == 0.0:
        raise InvalidArgumentError(
            "thickness 0 gives a crust with no thickness; use a nonzero value")
    moved = offset_shell(a, thickness, uniform)
    # outward (thickness < 0) turns over too where the mesh is concave: the
    # floor of a slot narrower than twice the thickness reverses
    check_not_inverted(a, moved, f"thickness {thickness}")
    return (p, moved) if thickness > 0 else (moved, p)


def _checked_scale(a: MeshArrays, scale: float) -> float:
    """``scale`` (finite, checked by the caller) as a float, if a scaled crust of
    ``a`` can use it.

    Raises:
        DLFLError: ``scale`` 0 or of magnitude 1 or more (checked on the value
            given: TopMod clamped it to [-1, 1]), or a mesh none of whose faces
            has an area (both shells would lie in one line or point).
    """
    s = float(scale)
    if s == 0.0:
        raise InvalidArgumentError(
            "scale 0 would collapse the inner shell to a point; use 0 < |scale| < 1")
    if abs(s) > 1.0:
        raise InvalidArgumentError(
            f"scale {scale} is beyond +-1: a scaled crust needs 0 < |scale| < 1 "
            "(the inner copy smaller than the mesh, or with a negative scale "
            "the outer one larger)")
    if abs(s) == 1.0:  # TopMod clamps to [-1, 1] and builds two coincident shells
        raise InvalidArgumentError(
            f"scale {scale} leaves no thickness between the shells (an inner "
            f"copy of the same size); use 0 < |scale| < 1")
    solid = ~a.face_hole
    if not (np.linalg.norm(face_normals(a)[solid], axis=1) > 0.5).any():
        raise GeometryError("a crust needs a face with an area; every face of this mesh has "
                            "collinear or coincident corners, so the shells would have no "
                            "thickness")
    return s


def rind(
    mesh: Mesh,
    faces: Iterable[int] = (),
    thickness: float = 0.5,
    *,
    use_scaling: bool = False,
    scale: float = 0.9,
    uniform: bool = True,
    cleanup: bool = True,
    max_faces: object = None,
) -> CrustTwins:
    """Make ``mesh`` a crust and punch the listed faces open (rind modeling).

    TopMod's ``createCrust(t, uniform)`` / ``createCrustWithScaling(s)`` followed by
    ``cmMakeHole(f, cleanup)`` for each face; GUI defaults thickness 0.5, scale
    0.9, cleanup on. A positive thickness moves the inner copy inward by that
    distance from every face (exactly, at corners where three faces meet, when
    ``uniform``); a negative one moves the original outward instead. With
    ``use_scaling`` the inner copy is ``scale`` times the mesh about its vertex
    centroid (``0 < |scale| < 1``; negative scales the outer shell by ``-1/scale``
    instead; TopMod clamped it to [-1, 1], where +-1 gave two coincident shells).
    Punching ``k`` faces of a genus-0 shell gives genus ``k - 1``. With ``cleanup``, the zero-thickness double wall left between two
    punched faces that share an edge is removed (TopMod's cleanup), and a vertex
    whose faces are all punched goes with it.

    An open mesh's hole faces (its boundary loops) are always punched, so the
    rind of an open sheet is a closed slab. Cube: crust 16/24/12 (two
    components); one hole 16/28/14; two opposite holes 16/32/16, genus 1. The
    mesh is rebuilt (fresh ids).

    Returns:
        The twins of the faces left unpunched, for :func:`punch` to open later.

    Raises:
        DLFLError: a face id that is not in the mesh, a zero or non-finite
            thickness or scale, a scale of magnitude 1 or more,
            a vertex whose faces have no area (no normal to offset it along;
            with ``use_scaling``: every face without area),
            a moved copy (the inner one, or with a negative thickness the
            outer one) whose faces would collapse or turn over, point-spheres,
            every face punched with cleanup (nothing would be left).
            The mesh is unchanged.
        BudgetExceededError: the two shells and the tubes of the punched faces
            could pass the face budget (``max_faces``; None: the session's,
            see :mod:`livemod.dlfl.budget`).
    """
    # two shells at least, before anything is allocated: a repeated crust doubles
    check_size("rind", 2 * mesh.num_faces, 2 * mesh.num_corners, max_faces=max_faces)
    a = mesh_arrays(mesh)
    _check_shell_input(a)
    # an open mesh's boundary loops are always opened: the rind of a sheet is a slab
    punched = _dense_faces(a, faces) | a.face_hole
    # each punched n-gon and its twin become at most n quads
    sides = int(a.face_sizes[punched].sum())
    check_size("rind", 2 * len(punched) + sides - 2 * int(np.count_nonzero(punched)),
               2 * len(a.corner_vertex) + 2 * sides, max_faces=max_faces)
    outer, inner = _shell_positions(
        a, None if use_scaling else thickness, scale if use_scaling else None, uniform
    )
    shell = shell_arrays(a, outer, inner, punched, cleanup)
    if len(shell.corner_vertex) == 0:
        raise InvalidArgumentError("punching every face with cleanup leaves nothing of the mesh")
    first = mesh.next_ids()
    mesh.replace_with(shell.build(mesh))
    return _crust_twins(shell, int(np.count_nonzero(~punched)), first)


def crust(mesh: Mesh, thickness: float = 0.5, *, uniform: bool = True, use_scaling: bool = False,
          scale: float = 0.9, max_faces: object = None) -> CrustTwins:
    """TopMod's ``createCrust`` (or with ``use_scaling`` ``createCrustWithScaling``):
    :func:`rind` with no face punched (two components); returns the twins that
    :func:`punch` opens later."""
    return rind(mesh, (), thickness, uniform=uniform, use_scaling=use_scaling, scale=scale,
                max_faces=max_faces)


@dataclass
class CrustTwins:
    """Which face and vertex of a crust's inner shell copies which of its outer one.

    :func:`rind` and :func:`crust` return it; :func:`punch` reads it to open an
    outer face and its twin into a tube later, and forgets the pairs it opened
    (TopMod kept the same table in globals for its last crust).

    Attributes:
        faces: outer face id -> inner face id, for the faces not punched yet.
        vertices: outer vertex id -> inner vertex id.
    """

    faces: dict[int, int]
    vertices: dict[int, int]

    def pair(self, face: int) -> tuple[int, int]:
        """``(outer, inner)`` for ``face``, either side of the pair.

        Raises:
            InvalidArgumentError: ``face`` is neither side of an unpunched pair.
        """
        if face in self.faces:
            return face, self.faces[face]
        for outer, inner in self.faces.items():
            if inner == face:
                return outer, inner
        raise InvalidArgumentError(
            f"face {shown(face)} is not a face of the crust still to punch (neither "
            "shell's copy of an unpunched face; punched already, or made after the crust)")


def _crust_twins(shell: Shell, kept: int, first: tuple[int, int, int, int]) -> CrustTwins:
    """The :class:`CrustTwins` of a mesh built from ``shell`` with ids from ``first``:
    its first ``kept`` faces are the outer shell, the next ``kept`` their reversed
    copies, each from the copy of the same head corner."""
    sizes = np.diff(shell.offsets)[:kept]
    outer_start, inner_start = shell.offsets[:kept], shell.offsets[kept:2 * kept]
    rank = np.arange(int(sizes.sum())) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    size = np.repeat(sizes, sizes)
    outer = shell.corner_vertex[np.repeat(outer_start, sizes) + rank]
    inner = shell.corner_vertex[np.repeat(inner_start, sizes) + (size - rank) % size]
    v0, _, f0, _ = first
    faces = dict(zip(range(f0, f0 + kept), range(f0 + kept, f0 + 2 * kept), strict=True))
    vertices = dict(zip((outer + v0).tolist(), (inner + v0).tolist(), strict=True))
    return CrustTwins(faces, vertices)


def punch(mesh: Mesh, twins: CrustTwins, faces: Iterable[int], *,
          cleanup: bool = True, max_faces: object = None) -> list[int]:
    """Open faces of a crust made earlier into tubes: TopMod's ``cmMakeHole``.

    Each face (either shell's copy) is joined to its twin by a tube of quads
    (:func:`livemod.dlfl.connect.connect_faces`, from the copies of one
    vertex); with ``cleanup``, a wall of no thickness left where the tube meets
    an earlier one (two punched faces sharing an edge) is removed, as
    :func:`rind` does when punching the two at once. The other elements keep
    their ids, so a crust made once can be punched in later steps. Cube crust,
    one face: 16/28/14; two opposite faces: 16/32/16, genus 1. The pairs
    punched leave ``twins``.

    Returns:
        The ids of the tubes' faces left after cleanup, face after face.

    Raises:
        BudgetExceededError: the tubes would pass the face budget (``max_faces``;
            None: the session's, see :mod:`livemod.dlfl.budget`).
        InvalidArgumentError: a face that is no unpunched face of this crust
            (punched already, or not of it), faces no longer shaped as their
            twins (changed since the crust was made), or with ``cleanup`` the
            last faces of the crust (nothing would be left); nothing is
            punched then.
    """
    pairs = list(dict.fromkeys(twins.pair(f) for f in id_list(faces, "faces")))
    for outer, inner in pairs:
        _check_twins(mesh, twins, outer, inner)
    if cleanup and pairs and len(pairs) == len(twins.faces):
        raise InvalidArgumentError("punching every face of a crust with cleanup leaves nothing "
                                   "of the mesh (as rind refuses it)")
    sides = sum(mesh.face_size(outer) for outer, _ in pairs)  # a quad per side
    check_growth(mesh, "punch", faces=sides, corners=4 * sides, max_faces=max_faces)
    made: list[int] = []
    for outer, inner in pairs:
        made.extend(_punch_one(mesh, twins, outer, inner, cleanup))
        del twins.faces[outer]
    return [f for f in made if mesh.has_face(f)]


def _check_twins(mesh: Mesh, twins: CrustTwins, outer: int, inner: int) -> None:
    """Raises InvalidArgumentError unless ``outer`` and ``inner`` still are twins:
    both live, and every vertex of ``outer`` has its twin in ``inner``."""
    for face in (outer, inner):
        if not mesh.has_face(face):
            raise InvalidArgumentError(f"face {face} of the crust is gone (changed since the "
                                       "crust was made); it cannot be punched")
    copies = [twins.vertices.get(v, -1) for v in mesh.face_vertices(outer)]
    if sorted(copies) != sorted(mesh.face_vertices(inner)):
        raise InvalidArgumentError(f"faces {outer} and {inner} are no longer twins (changed "
                                   "since the crust was made); they cannot be punched")


def _punch_one(mesh: Mesh, twins: CrustTwins, outer: int, inner: int,
               cleanup: bool) -> list[int]:
    """Join ``outer`` to ``inner`` by a tube and clean up double walls; returns the
    tube's faces."""
    head = mesh.face_corner(outer)
    copy = mesh.corner_at(inner, twins.vertices[mesh.corner_vertex(head)])
    sides = list(zip(mesh.face_edges(outer), _twin_edges(mesh, twins, outer, inner),
                     strict=True))
    new_edges = connect_faces(mesh, head, copy)
    tube = list(dict.fromkeys(f for e in new_edges for f in mesh.edge_faces(e)))
    if cleanup:
        for edge, twin in sides:
            if mesh.has_edge(edge) and mesh.has_edge(twin) and \
                    set(mesh.edge_faces(edge)) == set(mesh.edge_faces(twin)):
                for wall_edge in mesh.face_edges(mesh.edge_faces(edge)[0]):
                    if mesh.has_edge(wall_edge):
                        mesh.delete_edge(wall_edge, cleanup=True)
    return tube


def _twin_edges(mesh: Mesh, twins: CrustTwins, outer: int, inner: int) -> list[int]:
    """For each edge of ``outer`` (from its head), the edge of ``inner`` between the
    twins of its ends."""
    by_ends = {frozenset(mesh.edge_vertices(e)): e for e in mesh.face_edges(inner)}
    ring = mesh.face_vertices(outer)
    return [by_ends[frozenset((twins.vertices[a], twins.vertices[b]))]
            for a, b in zip(ring, ring[1:] + ring[:1], strict=True)]
