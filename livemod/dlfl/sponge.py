"""Menger-sponge remeshing: TopMod's ``createSponge(t=0.67)``.

Every face is cut like a face of a Menger sponge: its edges are trisected, its
middle (the face shrunk to a third about its centroid) is opened, and the ring
left around it is split into one quad per corner and one per side. A tunnel of
quads runs from each opening to the matching face of an inner shell (the mesh
offset inward by ``thickness``), whose faces are all open, so the tunnels meet
inside. On the cube (edge 2) with the default 0.67 this is the level-1 Menger
sponge surface: 64 vertices, 72 quads, genus 5.

TopMod's result, 64/156/84, also holds 12 two-sided faces that its edge
collapses left behind. livemod reproduces the counts by default, with one
2-gon along every edge of the inner shell, where TopMod's collapsed inner
insets lay (the source was not available to confirm the exact place);
``keep_2gons=False`` gives the clean surface, 64/144/72.
"""

from __future__ import annotations

import numpy as np

from ._checks import positive_number
from .analysis import face_centroids
from .arrays import MeshArrays, mesh_arrays
from .build import from_corner_arrays
from .errors import DLFLError
from .mesh import Mesh
from .rind import check_not_inverted, offset_shell

__all__ = ["sponge"]


def sponge(mesh: Mesh, thickness: float = 0.67, *, keep_2gons: bool = True) -> None:
    """Menger-sponge remeshing of ``mesh`` in place (rebuilt: fresh ids).

    Args:
        thickness: the inward offset of the inner shell (TopMod's default 0.67,
            which on the edge-2 cube puts the inner shell at +-0.33).
        keep_2gons: add TopMod's 2-gons along the inner shell's edges.

    Raises:
        DLFLError: ``thickness`` not positive or so large that the inner shell
            turns over, point-spheres or faces of fewer than three sides; the
            mesh is unchanged.
    """
    a = mesh_arrays(mesh)
    _check_input(a, thickness)
    inner = offset_shell(a, thickness, uniform=True)
    check_not_inverted(a, inner, f"thickness {thickness}")
    positions, corner_vertex, mates, offsets = _sponge_polygons(a, inner, keep_2gons)
    mesh.replace_with(from_corner_arrays(positions, offsets, corner_vertex, mates,
                                         first_ids=mesh.next_ids()))


def _check_input(a: MeshArrays, thickness: float) -> None:
    positive_number(thickness, "thickness")
    if (a.corner_edge < 0).any():
        raise DLFLError("sponge needs a mesh without point-spheres")
    if (a.face_sizes < 3).any():
        f = int(a.face_ids[np.flatnonzero(a.face_sizes < 3)[0]])
        raise DLFLError(f"sponge needs faces of at least three sides; face {f} has fewer")


def _sponge_polygons(
    a: MeshArrays, inner: np.ndarray, keep_2gons: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Positions, corner vertices, corner mates and face offsets of the sponge.

    Vertex blocks: originals ``P`` (V), trisection points ``T`` (one per corner,
    a third along its edge), inset points ``I`` (one per corner), inner shell
    ``Q`` (V). Face blocks, per corner ``c``: A ``[P c, T c, I c, T mate(prev c)]``,
    B ``[T c, T mate(c), I next(c), I c]``, C (tunnel)
    ``[I c, I next(c), Q next(c), Q c]``; then D, one 2-gon ``[Q u, Q w]`` per edge.
    """
    nv, nc = len(a.vertex_ids), len(a.corner_vertex)
    cv, nxt, prv, mate = a.corner_vertex, a.corner_next, a.corner_prev, a.corner_mate
    p = a.positions
    trisect = p[cv] + (p[cv[nxt]] - p[cv]) / 3
    centre = face_centroids(a)[a.corner_face]
    inset = centre + (p[cv] - centre) / 3
    t_idx, i_idx, q_idx = nv + np.arange(nc), nv + nc + np.arange(nc), nv + 2 * nc + cv
    blocks = [
        np.stack([cv, t_idx, i_idx, t_idx[mate[prv]]], 1),
        np.stack([t_idx, t_idx[mate], i_idx[nxt], i_idx], 1),
        np.stack([i_idx, i_idx[nxt], q_idx[nxt], q_idx], 1),
    ]
    corner_vertex = np.concatenate(blocks).ravel()
    mates = _sponge_mates(a, keep_2gons)
    sizes = np.full(3 * nc, 4)
    if keep_2gons:
        ends = q_idx[a.edge_corners]
        corner_vertex = np.concatenate([corner_vertex, ends.ravel()])
        sizes = np.concatenate([sizes, np.full(len(a.edge_ids), 2)])
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    positions = np.concatenate([p, trisect, inset, inner])
    return positions, corner_vertex, mates, offsets


def _sponge_mates(a: MeshArrays, keep_2gons: bool) -> np.ndarray:
    """``(C_out,)`` the other side of every corner's edge in the layout above."""
    nc, ne = len(a.corner_vertex), len(a.edge_ids)
    nxt, prv, mate = a.corner_next, a.corner_prev, a.corner_mate
    c = np.arange(nc)
    A, B, C, D = 0, 4 * nc, 8 * nc, 12 * nc  # noqa: N806 - block bases
    out = np.empty(12 * nc + (2 * ne if keep_2gons else 0), np.int64)
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
    out[C + 4 * c + 3] = C + 4 * prv + 1
    if not keep_2gons:
        out[C + 4 * c + 2] = C + 4 * mate + 2
        return out
    # the tunnels on both sides of an inner edge each meet one side of its 2-gon
    e = np.arange(ne)
    c0, c1 = a.edge_corners[:, 0], a.edge_corners[:, 1]
    out[D + 2 * e], out[C + 4 * c0 + 2] = C + 4 * c0 + 2, D + 2 * e
    out[D + 2 * e + 1], out[C + 4 * c1 + 2] = C + 4 * c1 + 2, D + 2 * e + 1
    return out
