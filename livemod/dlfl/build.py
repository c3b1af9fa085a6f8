"""Bulk construction of a DLFL mesh from polygons, vectorized with numpy.

:func:`from_polygons` takes a polygon soup (positions plus vertex indices per
face), pairs every directed side ``u -> w`` with its reverse ``w -> u``, closes
every boundary loop with a hole face, turns unused vertices into point-spheres and
refuses what is not an oriented 2-manifold, naming the element and, when given,
the file and line it came from. :func:`from_corner_arrays` is the trusted fast
path used by bulk operations that already know how corners pair up.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np

from ._checks import first_not_finite
from ._graph import cycle_labels, one_cycle_each
from ._multi_edges import pair_multi_edges
from .errors import DLFLRepairWarning, GeometryError, InvalidArgumentError, NonManifoldError
from .mesh import Mesh
from .soup import Polygons, SoupNames, as_polygons


def from_polygons(
    positions: Any,
    faces: Any,
    offsets: Any = None,
    *,
    source: str | None = None,
    face_lines: Any = None,
    vertex_base: int = 0,
    first_ids: tuple[int, int, int, int] = (0, 0, 0, 0),
    face_colors: Any = None,
) -> Mesh:
    """Build a DLFL mesh from a polygon soup.

    Face ``i`` of the soup becomes the face with id ``first_ids[2] + i``; vertex
    ``j`` gets id ``first_ids[0] + j``. Then come one hole face per boundary loop
    (flagged, see :meth:`Mesh.is_hole`) and one point-sphere face per vertex no
    face uses. A component whose faces are not consistently oriented is
    re-oriented when that is unambiguous; the repair is reported in
    ``mesh.notes`` and as a :class:`DLFLRepairWarning`.

    Args:
        positions: ``(V, 3)`` vertex positions.
        faces: see :func:`as_polygons`.
        offsets: see :func:`as_polygons`.
        source: a file name for error messages.
        face_lines: ``(F,)`` source line of each face, for error messages.
        vertex_base: what the source calls vertex index 0, for error messages
            (1 for OBJ, whose ``f`` lines count vertices from 1).
        first_ids: first vertex, edge, face and corner id to hand out.
        face_colors: ``(F,)`` rows of ``(r, g, b)`` in ``[0, 1]`` for the soup's
            faces, NaN for a face without one (see :meth:`Mesh.face_colors`);
            the hole and point-sphere faces added get none.

    Raises:
        InvalidArgumentError: an index out of range, a position that is not
            finite, a face with fewer than one corner or a repeated consecutive
            vertex.
        NonManifoldError: an edge used by more than two faces, a non-manifold
            vertex, or a non-orientable component.
    """
    soup = as_polygons(positions, faces, offsets)
    where = SoupNames(source, None if face_lines is None else np.asarray(face_lines), vertex_base)
    far = _check_soup(soup, where)
    notes: list[str] = []
    soup, mate = _pair_sides(soup, where, notes, far)
    del far  # 8 bytes a corner, not to be held through the rest of the build
    soup, mate, holes = _close_boundaries(soup, mate, where)
    soup, mate, num_ps = _add_point_spheres(soup, mate)
    _check_vertex_fans(soup, mate, where)
    # uint8, as the face table keeps them: no cast of a copy in from_corner_arrays
    hole_flags = np.zeros(len(soup.offsets) - 1, dtype=np.uint8)
    real = len(hole_flags) - holes - num_ps
    hole_flags[real : real + holes] = 1
    colors = None
    if face_colors is not None:
        colors = np.full((len(hole_flags), 3), np.nan, np.float32)
        colors[:real] = np.asarray(face_colors, dtype=np.float32).reshape(real, 3)
    mesh = from_corner_arrays(
        soup.positions, soup.offsets, soup.indices, mate, hole_flags, face_colors=colors,
        first_ids=first_ids,
    )
    mesh.notes = notes
    for note in notes:
        warnings.warn(note, DLFLRepairWarning, stacklevel=2)
    return mesh


def _check_soup(soup: Polygons, where: SoupNames) -> np.ndarray:
    """Refuse empty faces, indices out of range, positions that are not finite and
    zero-length sides; returns the ``(C,)`` far vertex of every corner's side
    (``indices[next_corner]``), which the pairing needs too."""
    nv = len(soup.positions)
    sizes = soup.sizes
    if (sizes < 1).any():
        f = int(np.flatnonzero(sizes < 1)[0])
        raise InvalidArgumentError(f"{where.prefix([f])}{where.face(f)} has no vertices")
    if len(soup.indices) and (soup.indices.min() < 0 or soup.indices.max() >= nv):
        c = int(np.flatnonzero((soup.indices < 0) | (soup.indices >= nv))[0])
        f = int(np.searchsorted(soup.offsets, c, side="right") - 1)
        raise InvalidArgumentError(
            f"{where.prefix([f])}{where.face(f)} uses vertex index {where.vertex(soup.indices[c])}, "
            f"but there are {nv} vertices"
        )
    v = first_not_finite(soup.positions)
    if v is not None:
        raise InvalidArgumentError(
            f"{where.prefix()}vertex {where.vertex(v)} has a position that is not finite")
    far = soup.indices[soup.next_corner]
    same = soup.indices == far
    if len(sizes) and sizes.min() == 1:
        same &= np.repeat(sizes, sizes) > 1
    if same.any():
        c = int(np.flatnonzero(same)[0])
        f = int(np.searchsorted(soup.offsets, c, side="right") - 1)
        raise InvalidArgumentError(
            f"{where.prefix([f])}{where.face(f)} visits vertex {where.vertex(soup.indices[c])} "
            "twice in a row (a zero-length side)"
        )
    return far


def _face_of_corner(offsets: np.ndarray) -> np.ndarray:
    sizes = np.diff(offsets)
    return np.repeat(np.arange(len(sizes), dtype=np.int64), sizes)


def _pair_sides(
    soup: Polygons, where: SoupNames, notes: list[str], far: np.ndarray | None = None
) -> tuple[Polygons, np.ndarray]:
    """Pair each side ``u -> w`` with a side ``w -> u``; -1 where none exists.

    ``far`` is the ``(C,)`` far vertex ``w`` of every side, when already known.
    Returns the (possibly re-oriented) soup and the ``(C,)`` mate of each corner.
    """
    nv = max(len(soup.positions), 1)
    nxt = soup.next_corner
    u = soup.indices
    w = u[nxt] if far is None else far
    single = soup.single_corners
    key = np.minimum(u, w) * nv + np.maximum(u, w)
    key[single] = -1 - np.flatnonzero(single)  # point-sphere corners pair with nothing
    if len(key) == 0:
        return soup, np.zeros(0, dtype=np.int64)
    order, skey = _sort_keys(key)
    mate = _pair_simple(u, w, order, skey)
    if mate is not None:
        return soup, mate
    starts = np.flatnonzero(np.concatenate([[True], skey[1:] != skey[:-1]]))
    counts = np.diff(np.concatenate([starts, [len(skey)]]))
    forward = (u < w)[order]
    fwd_count = np.add.reduceat(forward.astype(np.int64), starts) if len(starts) else starts
    real = skey[starts] >= 0
    _refuse_crowded_edges(soup, order, starts, counts, fwd_count, real, where)
    same_dir = real & (counts == 2) & ((fwd_count == 2) | (fwd_count == 0))
    if same_dir.any():
        soup = _reorient(soup, where, notes)
        return _pair_sides(soup, where, [])
    mate = np.full(len(u), -1, dtype=np.int64)
    pairs = real & (counts == 2)
    a, b = order[starts[pairs]], order[starts[pairs] + 1]
    mate[a], mate[b] = b, a
    multi = np.flatnonzero(real & (counts > 2))
    if len(multi):
        pair_multi_edges(soup, mate, order, starts[multi], counts[multi], u, w, nxt, where)
    return soup, mate


def _sort_keys(key: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(order, key[order])``: the corners sorted by key, ties by index.

    Packs key and index into one int64 when they fit, because sorting values
    is several times faster than ``argsort`` on millions of keys.
    """
    n = len(key)
    index_bits = max(int(n).bit_length(), 1)
    lowest = int(key.min()) if n else 0
    span = int(key.max()) - lowest + 1 if n else 1
    if span.bit_length() + index_bits > 62:
        order = np.argsort(key, kind="stable")
        return order, key[order]
    packed = (key - lowest) << index_bits
    packed |= np.arange(n, dtype=np.int64)
    packed.sort()
    order = packed & ((1 << index_bits) - 1)
    packed >>= index_bits
    packed += lowest
    return order, packed


def _pair_simple(
    u: np.ndarray, w: np.ndarray, order: np.ndarray, skey: np.ndarray
) -> np.ndarray | None:
    """The mates when every edge has exactly two opposite sides, else None.

    The fast path for closed, consistently oriented meshes without 2-gon
    multi-edges or point-spheres; anything else goes the general way.
    """
    n = len(skey)
    if n % 2 or n == 0 or skey[0] < 0:
        return None
    first, second = order[0::2], order[1::2]
    if not np.array_equal(skey[0::2], skey[1::2]):
        return None
    if n > 2 and not (skey[2::2] != skey[1:-1:2]).all():
        return None
    # same edge, so opposite sides exactly when one runs up and the other down;
    # gathering bools moves an eighth of the bytes of gathering the vertices
    upward = (u < w)[order]
    if (upward[0::2] == upward[1::2]).any():
        return None
    mate = np.empty(n, dtype=np.int64)
    mate[first] = second
    mate[second] = first
    return mate


def _refuse_crowded_edges(
    soup: Polygons, order: np.ndarray, starts: np.ndarray, counts: np.ndarray,
    fwd_count: np.ndarray, real: np.ndarray, where: SoupNames,
) -> None:
    """Refuse an undirected edge whose sides cannot all be paired up."""
    unbalanced = real & (counts > 2) & (2 * fwd_count != counts)
    if not unbalanced.any():
        return
    g = int(np.flatnonzero(unbalanced)[0])
    corners = order[starts[g] : starts[g] + counts[g]]
    faces = sorted({int(f) for f in _face_of_corner(soup.offsets)[corners]})
    u = int(soup.indices[corners[0]])
    w = int(soup.indices[soup.next_corner[corners[0]]])
    used = ", ".join(where.face(f) for f in faces)
    raise NonManifoldError(
        f"{where.prefix(faces)}edge ({where.vertex(u)}, {where.vertex(w)}) is used by {int(counts[g])} face sides "
        f"({used}); a manifold edge has two"
    )




def _reorient(soup: Polygons, where: SoupNames, notes: list[str]) -> Polygons:
    """Flip faces so that each component is consistently oriented.

    Each component keeps the orientation most of its faces have (so one flipped
    face in a file is the one turned round, not all the others); on a tie, that
    of its first face in soup order.

    Raises:
        NonManifoldError: a component is non-orientable (a Moebius band, say).
    """
    flip = _orientation_flips(soup, where)
    flipped = np.flatnonzero(flip == 1)
    shown = ", ".join(where.face(int(f)) for f in flipped[:10])
    more = "" if len(flipped) <= 10 else f" and {len(flipped) - 10} more"
    notes.append(
        f"{where.prefix()}re-oriented {len(flipped)} faces ({shown}{more}) to match "
        "their neighbours"
    )
    return Polygons(soup.positions, soup.indices[_flip_order(soup, flip)], soup.offsets)


def _flip_order(soup: Polygons, flip: np.ndarray) -> np.ndarray:
    """``(C,)`` corner order that reverses the flagged faces, keeping their first corner."""
    face = _face_of_corner(soup.offsets)
    start = soup.offsets[:-1][face]
    local = np.arange(len(face), dtype=np.int64) - start
    size = np.diff(soup.offsets)[face]
    reverse = (flip[face] == 1) & (local > 0)
    return np.where(reverse, start + size - local, start + local)


def _orientation_flips(soup: Polygons, where: SoupNames) -> np.ndarray:
    """``(F,)`` int8: 1 for the faces to reverse, by breadth-first search per component,
    the fewer faces of each component reversed (see :func:`_reorient`).

    Each search level is one vectorized step over the faces of the frontier.
    """
    num_faces = len(soup.offsets) - 1
    src, dst, same = _face_adjacency(soup)
    order = np.argsort(src, kind="stable")
    src, dst, same = src[order], dst[order], same[order]
    first = np.searchsorted(src, np.arange(num_faces + 1))
    flip = np.full(num_faces, -1, dtype=np.int8)
    flip[first[1:] == first[:-1]] = 0  # faces with no neighbour stay as they are
    while (unset := np.flatnonzero(flip < 0)).size:
        flip[unset[0]] = 0
        frontier = unset[:1]
        levels = [frontier]
        while frontier.size:
            frontier = _search_level(frontier, first, dst, same, flip, where)
            levels.append(frontier)
        component = np.concatenate(levels)
        if 2 * int(flip[component].sum()) > len(component):
            flip[component] ^= 1  # the majority keeps its orientation
    return flip


def _search_level(
    frontier: np.ndarray, first: np.ndarray, dst: np.ndarray, same: np.ndarray,
    flip: np.ndarray, where: SoupNames,
) -> np.ndarray:
    """Orient the neighbours of ``frontier``; return the faces reached for the first time."""
    counts = first[frontier + 1] - first[frontier]
    origin = np.repeat(frontier, counts)
    slot = np.repeat(first[frontier] - np.cumsum(counts) + counts, counts)
    slot += np.arange(len(origin), dtype=np.int64)
    neighbour = dst[slot]
    want = flip[origin] ^ same[slot].astype(np.int8)
    new = flip[neighbour] < 0
    flip[neighbour[new]] = want[new]
    clash = flip[neighbour] != want
    if clash.any():
        f, g = int(origin[clash][0]), int(neighbour[clash][0])
        raise NonManifoldError(
            f"{where.prefix([g])}{where.face(g)} cannot be oriented "
            f"consistently with {where.face(f)}: the surface is not orientable"
        )
    return np.unique(neighbour[new])


def _face_adjacency(soup: Polygons) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Faces sharing an edge used by exactly two sides, both ways round.

    Returns ``(src, dst, same)``: ``(2k,)`` face pairs and whether the two faces
    traverse the shared edge in the same direction (one of them must flip).
    """
    u = soup.indices
    w = u[soup.next_corner]
    sides = np.flatnonzero(u != w)  # one-corner faces have no side
    key = np.minimum(u[sides], w[sides]) * max(len(soup.positions), 1)
    key += np.maximum(u[sides], w[sides])
    order, skey = _sort_keys(key)
    if len(skey) == 0:
        empty = np.zeros(0, dtype=np.int64)
        return empty, empty, np.zeros(0, dtype=bool)
    starts = np.flatnonzero(np.concatenate([[True], skey[1:] != skey[:-1]]))
    counts = np.diff(np.concatenate([starts, [len(skey)]]))
    a = sides[order[starts[counts == 2]]]
    b = sides[order[starts[counts == 2] + 1]]
    face = _face_of_corner(soup.offsets)
    same = (u[a] < w[a]) == (u[b] < w[b])
    return (np.concatenate([face[a], face[b]]), np.concatenate([face[b], face[a]]),
            np.concatenate([same, same]))


def _close_boundaries(
    soup: Polygons, mate: np.ndarray, where: SoupNames
) -> tuple[Polygons, np.ndarray, int]:
    """Add one hole face per boundary loop; returns soup, mate and hole count."""
    single = soup.single_corners
    open_sides = np.flatnonzero((mate < 0) & ~single)
    if len(open_sides) == 0:
        return soup, mate, 0
    nxt = soup.next_corner
    start, end = soup.indices[open_sides], soup.indices[nxt[open_sides]]
    incoming = np.bincount(end, minlength=len(soup.positions))
    if (incoming > 1).any():
        v = int(np.flatnonzero(incoming > 1)[0])
        f = int(_face_of_corner(soup.offsets)[open_sides[end == v][0]])
        raise NonManifoldError(
            f"{where.prefix([f])}vertex {where.vertex(v)} is non-manifold: {int(incoming[v])} boundary "
            "loops pass through it"
        )
    side_ending_at = np.full(len(soup.positions), -1, dtype=np.int64)
    side_ending_at[end] = np.arange(len(open_sides))
    # the hole side reversing open side i is followed by the one reversing the side
    # that ends where side i starts
    follow = side_ending_at[start]
    loops = _cycles(follow)
    hole_idx = np.concatenate([end[loop] for loop in loops])
    hole_corners = np.concatenate([loop for loop in loops])
    base = len(soup.indices)
    hole_sizes = np.array([len(loop) for loop in loops], dtype=np.int64)
    new_mate = np.concatenate([mate, open_sides[hole_corners]])
    new_mate[open_sides[hole_corners]] = base + np.arange(len(hole_corners))
    offsets = np.concatenate([soup.offsets, soup.offsets[-1] + np.cumsum(hole_sizes)])
    indices = np.concatenate([soup.indices, hole_idx])
    return Polygons(soup.positions, indices, offsets), new_mate, len(loops)


def _cycles(perm: np.ndarray) -> list[np.ndarray]:
    """The cycles of a permutation, each as indices in cycle order."""
    seen = np.zeros(len(perm), dtype=bool)
    loops = []
    for s in range(len(perm)):
        if seen[s]:
            continue
        loop = []
        x = s
        while not seen[x]:
            seen[x] = True
            loop.append(x)
            x = int(perm[x])
        loops.append(np.array(loop, dtype=np.int64))
    return loops


def _add_point_spheres(
    soup: Polygons, mate: np.ndarray
) -> tuple[Polygons, np.ndarray, int]:
    """Give every vertex no face uses a one-corner face of its own."""
    used = np.zeros(len(soup.positions), dtype=bool)
    used[soup.indices] = True
    lonely = np.flatnonzero(~used)
    if len(lonely) == 0:
        return soup, mate, 0
    offsets = np.concatenate([soup.offsets, soup.offsets[-1] + 1 + np.arange(len(lonely))])
    indices = np.concatenate([soup.indices, lonely])
    mate = np.concatenate([mate, np.full(len(lonely), -1, dtype=np.int64)])
    return Polygons(soup.positions, indices, offsets), mate, len(lonely)


def _check_vertex_fans(soup: Polygons, mate: np.ndarray, where: SoupNames) -> None:
    """Refuse a vertex whose corners form several fans (a bow-tie)."""
    nxt = soup.next_corner
    has = mate >= 0
    if has.all():  # closed, no point-spheres: the usual mesh
        vnext = nxt[mate]
    else:
        vnext = np.arange(len(mate), dtype=np.int64)
        vnext[has] = nxt[mate[has]]
    valence = np.bincount(soup.indices, minlength=len(soup.positions))
    if one_cycle_each(vnext, soup.indices, valence):
        return  # every vertex's corners are one ring: the quick answer
    labels = cycle_labels(vnext)
    roots = labels == np.arange(len(labels))
    fans = np.bincount(soup.indices[roots], minlength=len(soup.positions))
    if (fans > 1).any():
        v = int(np.flatnonzero(fans > 1)[0])
        f = int(_face_of_corner(soup.offsets)[np.flatnonzero(soup.indices == v)[0]])
        raise NonManifoldError(
            f"{where.prefix([f])}vertex {where.vertex(v)} is non-manifold: its faces form "
            f"{int(fans[v])} separate fans (a bow-tie)"
        )


def from_corner_arrays(
    positions: np.ndarray,
    offsets: np.ndarray,
    corner_vertex: np.ndarray,
    corner_mate: np.ndarray,
    face_hole: np.ndarray | None = None,
    *,
    face_colors: np.ndarray | None = None,
    first_ids: tuple[int, int, int, int] = (0, 0, 0, 0),
    ids: tuple[np.ndarray | None, np.ndarray | None, np.ndarray | None,
               np.ndarray | None] | None = None,
) -> Mesh:
    """Build a mesh from corners laid out face by face, with known pairing.

    Trusted fast path for bulk operations; run :func:`validate` in tests.

    Args:
        positions: ``(V, 3)`` float64 positions; every vertex must have a corner.
        offsets: ``(F + 1,)`` int face start offsets into the corner arrays.
        corner_vertex: ``(C,)`` int vertex index of each corner.
        corner_mate: ``(C,)`` int, the corner on the other side of each corner's
            edge (the corner's edge runs to the next corner); -1 for a point-sphere.
        face_hole: ``(F,)`` bool hole flags.
        face_colors: ``(F, 3)`` float colours in ``[0, 1]``, a row of NaN for a
            face without one (see :meth:`Mesh.face_colors`); None for none.
        first_ids: first vertex, edge, face and corner id.
        ids: per kind (vertex, edge, face, corner), the distinct ids of its
            elements in their order, for an operation that keeps some ids
            (None for a kind numbered from ``first_ids``); later elements get
            ids past the largest.

    Returns:
        The mesh; vertex ``i`` gets id ``first_ids[0] + i``, face ``i`` gets
        ``first_ids[2] + i``, corner ``i`` gets ``first_ids[3] + i`` and edges are
        numbered in order of their lower corner. A vertex's corner is its lowest.

    Raises:
        GeometryError: a position is NaN or infinite.
    """
    positions = np.asarray(positions, dtype=np.float64)
    _check_finite_result(positions)
    offsets = np.asarray(offsets, dtype=np.int64)
    # int64 indices: numpy converts int32 index arrays on every fancy index
    cvert = np.asarray(corner_vertex, dtype=np.int64)
    mate = np.asarray(corner_mate, dtype=np.int64)
    nxt, prv, face = _ring_links(offsets)
    lower, upper, edge = _edge_links(mate)
    num_f = len(offsets) - 1
    hole = np.zeros(num_f, np.uint8) if face_hole is None else np.asarray(face_hole, np.uint8)
    return Mesh.from_tables(
        corners={"next": nxt, "prev": prv, "face": face, "vertex": cvert, "edge": edge},
        edges={"c0": lower, "c1": upper},
        faces={"corner": offsets[:-1], "hole": hole, **face_color_fields(face_colors, num_f)},
        vertices={"corner": _lowest_corners(cvert, len(positions)), "position": positions},
        first_ids=first_ids, ids=ids)


def face_color_fields(face_colors: np.ndarray | None, num_f: int) -> dict[str, np.ndarray]:
    """The face table's ``colored`` ``(F,)`` uint8 and ``color`` ``(F, 3)`` float32
    fields for ``face_colors`` (see :func:`from_corner_arrays`); none when it is
    None: the mesh then has no colour fields until a face gets a colour."""
    if face_colors is None:
        return {}
    color = np.asarray(face_colors, dtype=np.float32).reshape(num_f, 3)
    colored = ~np.isnan(color[:, 0])
    return {"colored": colored.view(np.uint8),
            "color": np.where(colored[:, None], color, np.float32(0))}


def _check_finite_result(positions: np.ndarray) -> None:
    """Refuse NaN or infinite positions before a mesh is built of them.

    Every remeshing operation builds its result here before swapping it in, so
    this one check keeps them all from making a mesh :func:`validate` refuses
    when their numbers overflow or degenerate geometry divides by zero.

    Raises:
        GeometryError: naming the first such vertex (its index in ``positions``).
    """
    v = first_not_finite(positions)
    if v is None:
        return
    raise GeometryError(
        f"the result would put vertex {v} at {positions[v].tolist()}, which is not finite: "
        "the arguments are too large, or the mesh's geometry is degenerate (coincident "
        "points, zero-length edges, zero-area faces); the mesh is unchanged")


def _ring_links(offsets: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(C,)`` int32 next corner, previous corner and face of every corner.

    ``offsets`` is ``(F + 1,)`` int64. Faces of one size (all triangles, all
    quads: most bulk results) take strided slices instead of scatters.
    """
    sizes = np.diff(offsets)
    count, num_f = int(offsets[-1]), len(sizes)
    nxt = np.arange(1, count + 1, dtype=np.int32)
    prv = np.arange(-1, count - 1, dtype=np.int32)
    k = int(sizes[0]) if num_f else 0
    if k and sizes.min() == sizes.max():
        nxt[k - 1 :: k] -= k
        prv[::k] += k
        face = np.repeat(np.arange(num_f, dtype=np.int32), k)
        return nxt, prv, face
    starts, ends = offsets[:-1], offsets[1:] - 1
    if num_f and sizes.min() < 1:  # an empty face owns no corner to link
        starts, ends = starts[sizes > 0], ends[sizes > 0]
    nxt[ends] = starts
    prv[starts] = ends
    return nxt, prv, np.repeat(np.arange(num_f, dtype=np.int32), sizes)


def _edge_links(mate: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Edges numbered in order of their lower corner.

    Args:
        mate: ``(C,)`` int64 mate of each corner, -1 for none.

    Returns:
        ``(lower, upper, edge)``: ``(E,)`` int32 lower and upper corner of each
        edge and ``(C,)`` int32 edge of each corner (-1 for none).
    """
    lower = np.concatenate(
        [np.flatnonzero(mate[part] > np.arange(part.start, part.stop)) + part.start
         for part in _chunks(len(mate))] or [np.zeros(0, dtype=np.int64)], dtype=np.int32)
    upper = mate[lower]
    edge = np.full(len(mate), -1, dtype=np.int32)
    number = np.arange(len(lower), dtype=np.int32)
    edge[lower] = number
    edge[upper] = number
    return lower, upper.astype(np.int32), edge


def _lowest_corners(cvert: np.ndarray, num_v: int) -> np.ndarray:
    """``(V,)`` int32 lowest corner of each vertex, from the ``(C,)`` int64 ``cvert``.

    Corners are scattered in decreasing order, so that the lowest writes last.
    """
    vcorner = np.zeros(num_v, dtype=np.int32)
    for part in reversed(_chunks(len(cvert))):
        vcorner[cvert[part][::-1]] = np.arange(part.stop - 1, part.start - 1, -1, dtype=np.int32)
    return vcorner


CHUNK = 1 << 16


def _chunks(count: int) -> list[slice]:
    """``0..count`` cut into slices of ``CHUNK``: chunk-wise passes over the
    corners keep their temporaries small (fresh pages cost more than the loop)."""
    return [slice(start, min(start + CHUNK, count)) for start in range(0, count, CHUNK)]


def join_meshes(meshes: Sequence[Mesh]) -> Mesh:
    """One mesh holding a copy of each of ``meshes``, as separate components.

    Elements are numbered densely, mesh after mesh (the meshes' own ids are not
    kept); hole faces stay holes.

    Args:
        meshes: the meshes to join, in order (none gives an empty mesh).
    """
    from .arrays import concatenate_arrays, mesh_arrays

    parts = [mesh_arrays(mesh) for mesh in meshes]
    if not parts:
        return Mesh()
    joined = concatenate_arrays(parts)
    return from_corner_arrays(joined.positions, joined.face_offsets, joined.corner_vertex,
                              joined.corner_mate, joined.face_hole,
                              face_colors=joined.face_colors)


def point_cloud(positions: Any) -> Mesh:
    """A mesh of point-spheres, one per position (what a file without faces holds).

    Args:
        positions: ``(V, 3)`` vertex positions; vertex ``j`` gets id ``j``.
    """
    points = np.asarray(positions, dtype=np.float64).reshape(-1, 3)
    count = len(points)
    corners = np.arange(count, dtype=np.int64)
    return from_corner_arrays(points, np.arange(count + 1), corners,
                              np.full(count, -1, dtype=np.int64))
