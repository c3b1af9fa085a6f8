"""Menger-sponge remeshing: TopMod's ``createSponge(t=0.67, collapse=0)``.

Every face is cut like a face of a Menger sponge: its edges are trisected, its
middle (the face shrunk to a third about its centroid) is opened, and the ring
left around it is split into one quad per corner and one per side. A tunnel of
quads runs from each opening to the face's disc on an inner shell built as
TopMod builds it (:mod:`._sponge_shell`): one disc per face, offset by
``thickness`` inward and inset as much, joined to its neighbours by quads whose
joining edges TopMod collapses when short or crossed ("Edge Collapse Threshold
Factor", ``collapse``). The discs are all open, so the tunnels meet inside.

On the cube (edge 2) with TopMod's 0.67 every joining edge has no length: the
inner shell merges into the cube offset inward, and what is left of each joining
quad is a 2-gon along an edge of it. That is TopMod's 64/156/84 with its 12
2-gons; ``keep_2gons=False`` gives the clean level-1 Menger sponge surface,
64/144/72, genus 5. Elsewhere the joining quads and vertex faces that do not
collapse stay (the octahedron's at the default, 78/180/90).

TopMod's 0.67 is an absolute length made for its edge-2 cube, whose inner
shell collapses to a point at thickness 1. On a thinner mesh (the unit
tetrahedron's shell collapses at its inradius 1/3) 0.67 would turn the inner
shell inside out, so the default thickness keeps the cube's proportion there:
0.67 times that limit. TopMod trisected the edges at the thickness from each
end and inset the opening by it; livemod cuts at thirds, the Menger sponge's
proportion, which is TopMod's on its cube up to 0.67 against 2/3.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from ._checks import finite_number, positive_number, shown
from ._sponge_shell import (
    InnerShell,
    collapse_length,
    disc_corners,
    inner_shell,
    joining_collapses,
    vertex_faces,
)
from ._vectors import group_sum
from .analysis import face_centroids
from .arrays import MeshArrays, mesh_arrays
from .budget import check_size
from .build import from_corner_arrays
from .errors import DLFLError, GeometryError, InvalidArgumentError
from .mesh import Mesh
from .normals import RingNormals
from .rind import check_not_inverted, crust_offsets, offset_shell, reversed_normals
from .soup import offsets_of

__all__ = ["TOPMOD_THICKNESS", "shell_limit", "sponge"]

#: TopMod's default thickness (``createSponge(t=0.67)``), made for its edge-2
#: cube, whose inner shell collapses at thickness 1.
TOPMOD_THICKNESS = 0.67


def sponge(mesh: Mesh, thickness: float | None = None, *, collapse: float = 0.0,
           keep_2gons: bool = True, max_faces: object = None) -> float:
    """Menger-sponge remeshing of ``mesh`` in place (rebuilt: fresh ids).

    Args:
        thickness: the inward offset of the inner shell, below the mesh's
            :func:`shell_limit`. None (the default) takes TopMod's 0.67 (which
            on the edge-2 cube puts the inner shell at +-0.33), or 0.67 times
            the limit where that is less (a limit below the cube's 1).
        collapse: TopMod's "Edge Collapse Threshold Factor", at least 0: the
            inner shell's joining edges shorter than ``collapse * thickness``
            (0.01 for a factor up to 0.001) or crossed collapse (see
            :mod:`._sponge_shell`). Where faces meet at right angles every
            factor collapses them all.
        keep_2gons: keep TopMod's 2-gons (joining quads both of whose joining
            edges collapsed, vertex faces of two sides).

    Returns:
        The thickness used.

    Raises:
        DLFLError: ``thickness`` not positive, or so large that the inner shell
            collapses or turns over (naming the value and the limit);
            ``collapse`` negative or not a number; point-spheres or faces of
            fewer than three sides; a vertex whose faces have no area (no
            normal to offset it along); the mesh is unchanged.
        BudgetExceededError: the result could pass the face budget: at most
            ``7 E + V`` faces and ``15 C`` corners (``max_faces``; None: the
            session's, see :mod:`livemod.dlfl.budget`).
    """
    factor = finite_number(collapse, "collapse")
    if factor < 0:
        raise InvalidArgumentError(f"collapse must be a number >= 0, got {shown(collapse)}")
    check_size("sponge", 7 * mesh.num_edges + mesh.num_vertices, 15 * mesh.num_corners,
               max_faces=max_faces)
    a = mesh_arrays(mesh)
    _check_input(a)
    backwards = reversed_normals(a)  # the crust's and, turned round, the discs'
    thickness, inner = _inner_shell(a, thickness, backwards)
    discs = disc_corners(a, thickness, backwards)
    collapsed = joining_collapses(a, discs, collapse_length(thickness, factor))
    shell = inner_shell(a, inner, discs, collapsed)
    positions, corner_vertex, mates, offsets = _sponge_polygons(a, shell, keep_2gons)
    # the three faces of a corner lie in (or tunnel through) its face; the inner
    # shell's faces have no one
    origin = np.concatenate([np.tile(a.corner_face, 3), np.full(len(offsets) - 1 -
                                                                3 * len(a.corner_face), -1)])
    mesh.replace_with(from_corner_arrays(positions, offsets, corner_vertex, mates,
                                         face_colors=a.colors_at(origin),
                                         first_ids=mesh.next_ids()))
    return thickness


def _check_input(a: MeshArrays) -> None:
    if (a.corner_edge < 0).any():
        raise InvalidArgumentError("sponge needs a mesh without point-spheres")
    if (a.face_sizes < 3).any():
        f = int(a.face_ids[np.flatnonzero(a.face_sizes < 3)[0]])
        raise InvalidArgumentError(
            f"sponge needs faces of at least three sides; face {f} has fewer")


def _inner_shell(a: MeshArrays, thickness: float | None,
                 backwards: RingNormals) -> tuple[float, np.ndarray]:
    """The thickness :func:`sponge` uses (``thickness``, or the default for None)
    and the ``(V, 3)`` inner shell at it (``backwards``: the normals of ``a``'s
    faces reversed, ``rind.reversed_normals``).

    Raises:
        DLFLError: ``thickness`` not a positive number, or an inner shell that
            overflows, collapses or turns over; past the :func:`shell_limit`,
            the message names it.
    """
    if thickness is None:
        thickness = _default_thickness(shell_limit(a))
    thickness = positive_number(thickness, "thickness")
    inner = offset_shell(a, thickness, uniform=True, reversed_rings_normals=backwards)
    try:
        check_not_inverted(a, inner, f"thickness {thickness}")
    except DLFLError as error:
        # the limit is measured only here: a thickness that works costs nothing more
        limit = shell_limit(a)
        if thickness < limit:
            raise
        raise GeometryError(
            f"thickness {thickness} is too large for this mesh: its inner shell "
            f"collapses or turns over from thickness {limit:.6g} on; use a smaller "
            f"value (the default here is {_default_thickness(limit):.6g})"
        ) from error
    return thickness, inner


def _default_thickness(limit: float) -> float:
    """TopMod's 0.67, or 0.67 times a :func:`shell_limit` below the edge-2 cube's 1."""
    return TOPMOD_THICKNESS * min(1.0, limit)


def shell_limit(a: MeshArrays) -> float:
    """The least thickness at which the uniform inner shell of ``a`` (the crust's
    inward offset, ``positions - t * crust_offsets(a, 1)``) collapses or turns
    over: an edge shrinks to nothing or reverses, or a face's vector area
    vanishes or flips. inf when none ever does (a flat open sheet).

    Args:
        a: a mesh without point-spheres.

    Returns:
        The limit, > 0 (1 for the edge-2 cube, the inradius 1/3 for the unit
        tetrahedron).
    """
    d = crust_offsets(a, 1.0)  # from unit normals: the same at any scale
    top = float(np.abs(a.positions).max(initial=0.0))
    # positions scaled by a power of two (exact) near 1, so products stay in range
    k = int(np.frexp(top)[1]) if 0.0 < top < np.inf else 0
    p = np.ldexp(a.positions, -k)
    limit = min(_edge_limit(a, p, d), _face_limit(a, p, d))
    return float(np.ldexp(limit, k))


def _edge_limit(a: MeshArrays, p: np.ndarray, d: np.ndarray) -> float:
    """Least ``t`` at which an edge of ``p - t d`` (both ``(V, 3)``) shrinks to a
    point or reverses: ``s . (s - t ds) = 0`` for its side ``s``, inf if none."""
    ends = a.corner_vertex[a.edge_corners]
    side = p[ends[:, 1]] - p[ends[:, 0]]
    closing = np.einsum("ij,ij->i", side, d[ends[:, 1]] - d[ends[:, 0]])
    length = np.einsum("ij,ij->i", side, side)
    shrinking = (closing > 0) & (length > 0)
    with np.errstate(over="ignore"):  # a long side closing slowly: never, inf
        return float((length[shrinking] / closing[shrinking]).min(initial=np.inf))


def _face_limit(a: MeshArrays, p: np.ndarray, d: np.ndarray) -> float:
    """Least ``t`` at which a face's Newell vector ``N(t)`` of ``p - t d`` (both
    ``(V, 3)``) stops pointing along ``N(0)``, inf if none.

    ``N(t) = N0 - t N1 + t^2 N2`` (each a sum of cross products along the ring),
    so ``N0 . N(t)`` is a quadratic ``A - B t + C t^2`` with ``A > 0``: its least
    positive root, or where its minimum touches zero (a face shrinking to a point).
    """
    q = p[a.corner_vertex] - face_centroids(replace(a, positions=p))[
        a.corner_face]  # about the centroid: no cancellation between far-off points
    dc, nxt, nf = d[a.corner_vertex], a.corner_next, len(a.face_ids)
    n0 = group_sum(a.corner_face, np.cross(q, q[nxt]), nf)
    n1 = group_sum(a.corner_face, np.cross(q, dc[nxt]) + np.cross(dc, q[nxt]), nf)
    n2 = group_sum(a.corner_face, np.cross(dc, dc[nxt]), nf)
    A = np.einsum("ij,ij->i", n0, n0)  # noqa: N806 - the quadratic's coefficients
    B = np.einsum("ij,ij->i", n0, n1)  # noqa: N806
    C = np.einsum("ij,ij->i", n0, n2)  # noqa: N806
    keep = A > 0
    return float(_least_positive_root(A[keep], B[keep], C[keep]).min(initial=np.inf))


def _least_positive_root(A: np.ndarray, B: np.ndarray, C: np.ndarray) -> np.ndarray:  # noqa: N803
    """``(n,)`` least ``t > 0`` with ``A - B t + C t^2 <= 0`` (all ``(n,)``, ``A > 0``),
    inf where there is none; a minimum within ``1e-9 A`` of zero counts as a root."""
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        disc = B * B - 4 * A * C
        # the stable pair of roots: q / C and A / q, with q = (B + sign(B) sqrt(disc)) / 2
        half = (B + np.copysign(np.sqrt(np.maximum(disc, 0)), B)) / 2
        roots = np.stack([np.where(C != 0, half / C, np.inf),
                          np.where(half != 0, A / half, np.inf)])
        roots = np.where(np.isfinite(roots) & (roots > 0), roots, np.inf).min(axis=0)
        # no real root, but the minimum at B / 2C all but touches zero
        touch = (disc < 0) & (C > 0) & (B > 0) & (A - B * B / (4 * C) <= 1e-9 * A)
        return np.where(touch, B / (2 * C), np.where(disc >= 0, roots, np.inf))


def _sponge_polygons(
    a: MeshArrays, shell: InnerShell, keep_2gons: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Positions, corner vertices, corner mates and face offsets of the sponge.

    Vertex blocks: originals ``P`` (V), trisection points ``T`` (one per corner,
    a third along its edge), inset points ``I`` (one per corner), the inner
    shell's vertices ``Q`` (``shell.positions``; ``Q c``: corner ``c``'s). Face
    blocks, per corner ``c``: A ``[P c, T c, I c, T mate(prev c)]``, B
    ``[T c, T mate(c), I next(c), I c]``, C (tunnel) ``[I c, I next(c), Q next(c),
    Q c]``; then the joining faces (:class:`_JoinFaces`).
    """
    nv, nc = len(a.vertex_ids), len(a.corner_vertex)
    cv, nxt, mate = a.corner_vertex, a.corner_next, a.corner_mate
    p = a.positions
    trisect = p[cv] + (p[cv[nxt]] - p[cv]) / 3
    centre = face_centroids(a)[a.corner_face]
    inset = centre + (p[cv] - centre) / 3
    t_idx, i_idx = nv + np.arange(nc), nv + nc + np.arange(nc)
    q_idx = nv + 2 * nc + shell.corner_class
    join = _JoinFaces.of(a, shell, keep_2gons)
    blocks = [
        np.stack([cv, t_idx, i_idx, t_idx[mate[a.corner_prev]]], 1).ravel(),
        np.stack([t_idx, t_idx[mate], i_idx[nxt], i_idx], 1).ravel(),
        np.stack([i_idx, i_idx[nxt], q_idx[nxt], q_idx], 1).ravel(),
        q_idx[join.corner],
    ]
    sizes = np.concatenate([np.full(3 * nc, 4), join.sizes])
    offsets = offsets_of(sizes)
    positions = np.concatenate([p, trisect, inset, shell.positions])
    return positions, np.concatenate(blocks), _sponge_mates(a, join), offsets


@dataclass(frozen=True)
class _JoinFaces:
    """The faces the inner shell adds: one per edge (its joining quad: the 2-gon
    ``[Q c0, Q c1]`` where both joining edges collapsed, a triangle where one
    did), then the vertex faces; 2-gons left out unless kept.

    Attributes:
        corner: ``(k,)`` for each of their corners, the corner whose shell vertex it is.
        sizes: ``(n,)`` corners of each face.
        mates: ``(k,)`` the corner across each one's edge, in the sponge's layout.
        tunnel_mates: ``(C,)`` the corner across tunnel ``c``'s inner edge.
    """

    corner: np.ndarray
    sizes: np.ndarray
    mates: np.ndarray
    tunnel_mates: np.ndarray

    @staticmethod
    def of(a: MeshArrays, shell: InnerShell, keep_2gons: bool) -> _JoinFaces:
        """The joining faces of ``a``'s sponge with inner shell ``shell``.

        Per edge ``(c0, c1)``, four slots: ``Q c0`` (its edge is tunnel ``c0``'s),
        ``Q next(c0)`` (there while ``J(c1)`` is), ``Q c1``, ``Q next(c1)`` (while
        ``J(c0)`` is); a vertex face's corner ``c`` carries ``J(c)``.
        """
        nc, kept = len(a.corner_vertex), shell.kept
        c0, c1 = a.edge_corners[:, 0], a.edge_corners[:, 1]
        tunnel = 8 * nc + 4 * np.arange(nc) + 2  # each tunnel's corner at Q next(c)
        if not kept.any():
            return _JoinFaces.merged(a, tunnel, keep_2gons)
        present = np.stack([np.ones_like(kept[c0]), kept[c1], np.ones_like(kept[c0]), kept[c0]], 1)
        if not keep_2gons:
            present &= (kept[c0] | kept[c1])[:, None]
        slot = np.full(present.shape, -1, dtype=np.int64)
        slot[present] = 12 * nc + np.arange(int(present.sum()))
        first = a.edge_corners[a.corner_edge, 0] == np.arange(nc)
        edge = a.corner_edge
        tunnel_slot = np.where(first, slot[edge, 0], slot[edge, 2])
        join_slot = np.where(first, slot[edge, 3], slot[edge, 1])
        ring, ring_sizes, join_mate = _vertex_rings(a, shell, keep_2gons, join_slot,
                                                    12 * nc + len(slot[present]))
        corners = np.stack([c0, a.corner_next[c0], c1, a.corner_next[c1]], 1)[present]
        mates = np.stack([tunnel[c0], join_mate[c1], tunnel[c1], join_mate[c0]], 1)[present]
        rows = present.sum(axis=1)
        return _JoinFaces(
            np.concatenate([corners, ring]),
            np.concatenate([rows[rows > 0], ring_sizes]),
            np.concatenate([mates, join_slot[ring]]),
            np.where(tunnel_slot >= 0, tunnel_slot, tunnel[a.corner_mate]))


    @staticmethod
    def merged(a: MeshArrays, tunnel: np.ndarray, keep_2gons: bool) -> _JoinFaces:
        """The joining faces where every joining edge collapsed: a 2-gon
        ``[Q c0, Q c1]`` per edge (none without ``keep_2gons``). ``tunnel``:
        ``(C,)`` each tunnel's corner at ``Q next(c)``."""
        nc, ne = len(a.corner_vertex), len(a.edge_ids)
        if not keep_2gons:
            none = np.zeros(0, np.int64)
            return _JoinFaces(none, none, none, tunnel[a.corner_mate])
        tunnel_mates = np.empty(nc, np.int64)
        tunnel_mates[a.edge_corners.ravel()] = 12 * nc + np.arange(2 * ne)
        return _JoinFaces(a.edge_corners.ravel(), np.full(ne, 2),
                          tunnel[a.edge_corners].ravel(), tunnel_mates)


def _vertex_rings(a: MeshArrays, shell: InnerShell, keep_2gons: bool, join_slot: np.ndarray,
                  base: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The vertex faces from corner ``base`` on: ``(corners (k,), sizes (n,),
    join_mate (C,))``, ``join_mate[c]`` the corner across ``J(c)`` from its
    joining quad (the other quad's, where a 2-gon vertex face is left out)."""
    join_mate = np.full(len(shell.kept), -1, dtype=np.int64)
    if not shell.kept.any():
        return np.zeros(0, np.int64), np.zeros(0, np.int64), join_mate
    ring, offsets = vertex_faces(a, shell)
    sizes = np.diff(offsets)
    if not keep_2gons and (sizes == 2).any():
        pairs = ring[offsets[:-1][sizes == 2, None] + np.arange(2)]
        join_mate[pairs[:, 0]], join_mate[pairs[:, 1]] = join_slot[pairs[:, 1]], join_slot[pairs[:, 0]]
        keep = np.repeat(sizes != 2, sizes)
        ring, sizes = ring[keep], sizes[sizes != 2]
    join_mate[ring] = base + np.arange(len(ring))
    return ring, sizes, join_mate


def _sponge_mates(a: MeshArrays, join: _JoinFaces) -> np.ndarray:
    """``(C_out,)`` the other side of every corner's edge in the layout above."""
    nc = len(a.corner_vertex)
    nxt, prv, mate = a.corner_next, a.corner_prev, a.corner_mate
    c = np.arange(nc)
    A, B, C = 0, 4 * nc, 8 * nc  # noqa: N806 - block bases
    out = np.empty(12 * nc + len(join.mates), np.int64)
    out[A + 4 * c] = A + 4 * nxt[mate] + 3
    out[A + 4 * c + 1] = B + 4 * c + 3
    out[A + 4 * c + 2] = B + 4 * prv + 1
    out[A + 4 * c + 3] = A + 4 * mate[prv]
    out[B + 4 * c] = B + 4 * mate
    out[B + 4 * c + 1] = A + 4 * nxt + 2
    out[B + 4 * c + 2] = C + 4 * c
    out[B + 4 * c + 3] = A + 4 * c + 1
    out[C + 4 * c] = B + 4 * c + 2
    out[C + 4 * c + 1] = C + 4 * nxt + 3
    out[C + 4 * c + 2] = join.tunnel_mates
    out[C + 4 * c + 3] = C + 4 * prv + 1
    out[12 * nc:] = join.mates
    return out
