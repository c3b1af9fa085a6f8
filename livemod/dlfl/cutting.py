"""Sculpting cuts (TopMod's ``DLFLSculpting.cc``): cut vertices, edges and faces; truncate.

Every cut removes a *region* of the surface and closes the opening with one new
face, its *cap*:

* :func:`cut_vertices`: each vertex on its own (a corner cut);
* :func:`cut_edges`: each edge with its two end vertices (a bevel); edges that
  share a vertex form one region, so a path of edges gets one long cap;
* :func:`cut_faces`: each face with its vertices and edges (the face moves in);
* :func:`truncate`: every vertex of the mesh (TopMod's whole-object cut).

The rule is the same for all four. Every edge *leaving* the region (one end in
it, the edge itself not part of it) gets a new vertex ``offset`` of its length
from the region's end: ``(1 - offset) p + offset q`` for ``p`` the region's end
and ``q`` the far end. The cap's corners are these points, in order around the
region. Then everything inside (the region's vertices, its edges, the face of a
face cut, and the end pieces of the split edges) is deleted. A region with
``k`` leaving edge ends, ``nv`` vertices, ``ne`` edges and ``nf`` faces turns
``V/E/F`` into ``V + k - nv``, ``E + k - ne``, ``F + 1 - nf``; the genus stays.
On TopMod's cube (offset 0.25): one vertex 10/15/7, one edge 10/15/7, one face
8/12/6 (a shorter box), truncate 24/36/14.

Everything outside the regions keeps its id; each split edge keeps its id on one
of its parts (see :meth:`Mesh.subdivide_edge`); caps are new faces and ordinary
faces even where a region touched a hole face (the hole loses that corner, as
with ``subdivide("vertex-cut")``).

How this differs from TopMod, which cut by a plane:

* TopMod fitted a plane through the centroid of the same offset points (normal:
  the vertex normal, the mean of the edge's two face normals, or the face normal)
  and moved the new points to where the plane crosses the edges, then removed
  everything on the outer side reachable from one seed vertex. livemod keeps the
  points exactly at ``offset`` along each edge, so the cap is planar only where
  those are coplanar (valence-3 vertices, the cube's edges and faces), and the region is
  exactly the selected elements: a plane beyond the neighbours (TopMod allowed
  offsets up to 2) no longer eats them, and a concave vertex is cut too (TopMod's
  seed lay on the inner side and only split edges).
* All points come from the mesh as it was; TopMod cut one region after another,
  so a later cut could start from a vertex an earlier one had deleted. Regions
  that would overlap are merged (edges) or refused (faces).
* TopMod's face panel set the edge offset while face cuts read the vertex
  offset, so its offset box did nothing; here each call takes its ``offset``.
* TopMod's "global cut" (peel the whole object by each plane, pairing crossing
  points arbitrarily in faces crossed more than twice) is left out.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from ._checks import finite_number, id_list
from ._truncation import check_truncatable, truncation
from .arrays import mesh_arrays
from .budget import check_growth, check_size
from .build import from_corner_arrays
from .errors import DLFLError
from .mesh import Mesh

__all__ = ["DEFAULT_OFFSET", "cut_vertices", "cut_edges", "cut_faces", "truncate"]

DEFAULT_OFFSET = 0.25
"""TopMod's GUI default for every cut (its spin boxes started at 0.25)."""


@dataclass(frozen=True)
class _Region:
    """What one cut removes: ``vertices`` (ids), the ``inner`` edges between them
    (a tree, or the ring of ``face``) and, for a face cut, ``face`` (else -1)."""

    vertices: tuple[int, ...]
    inner: frozenset[int]
    face: int = -1
    name: str = ""


def cut_vertices(mesh: Mesh, vertices: Iterable[int],
                 offset: float = DEFAULT_OFFSET, *, max_faces: object = None) -> list[int]:
    """Cut off each vertex: TopMod's ``cutSelectedVertices`` (Conical > Cut by Vertex).

    A vertex of valence ``k`` becomes a ``k``-gon whose corners lie ``offset``
    along each of its edges. Cube corner, offset 0.25: 10/15/7 (a triangle, three
    pentagons, three squares).

    Args:
        mesh: modified in place.
        vertices: ``(n,)`` vertex ids; repeats count once, none is a no-op.
        offset: in (0, 1), and below 0.5 where two cut vertices share an edge.

    Returns:
        The cap face ids, one per vertex, in the order given.

    Raises:
        DLFLError: an id that is not a live vertex, a point-sphere, a vertex with
            a self-loop or only one edge, or an offset out of range; the mesh is
            unchanged.
    """
    t = _offset(offset)
    ids = list(dict.fromkeys(id_list(vertices, "vertices")))
    regions = [_Region((v,), frozenset(), name=f"vertex {v}") for v in ids]
    for v in ids:
        _check_cuttable(mesh, v)
    return _cut(mesh, regions, t, max_faces)


def cut_edges(mesh: Mesh, edges: Iterable[int], offset: float = DEFAULT_OFFSET, *,
              max_faces: object = None) -> list[int]:
    """Cut off each edge with its end vertices: TopMod's ``cutSelectedEdges``.

    Edges that share a vertex form one region (they must not close a cycle:
    cut the face inside it instead), whose cap's corners lie ``offset`` along
    every other edge at its vertices. Cube edge, offset 0.25: 10/15/7 (the cap and
    four squares, two pentagons).

    Args:
        mesh: modified in place.
        edges: ``(n,)`` edge ids; repeats count once, none is a no-op.
        offset: in (0, 1), and below 0.5 on an edge cut from both ends.

    Returns:
        The cap face ids, one per region, in the order of their first edge.

    Raises:
        DLFLError: an id that is not a live edge, a self-loop, edges closing a
            cycle, a region with fewer than two edges leaving it, or an offset
            out of range; the mesh is unchanged.
    """
    t = _offset(offset)
    ids = list(dict.fromkeys(id_list(edges, "edges")))
    return _cut(mesh, _edge_regions(mesh, ids), t, max_faces)


def cut_faces(mesh: Mesh, faces: Iterable[int], offset: float = DEFAULT_OFFSET, *,
              max_faces: object = None) -> list[int]:
    """Cut off each face with its vertices and edges: TopMod's ``cutSelectedFaces``.

    The cap replaces the face ``offset`` along every edge that leaves it: on a
    convex solid the face moves inwards and its neighbours get shorter. Cube face,
    offset 0.25: 8/12/6, the box a quarter lower.

    Args:
        mesh: modified in place.
        faces: ``(n,)`` face ids, no two sharing a vertex; repeats count once.
        offset: in (0, 1), and below 0.5 on an edge cut from both ends.

    Returns:
        The cap face ids, one per face, in the order given.

    Raises:
        DLFLError: an id that is not a live face, a hole face, a point-sphere's
            face, a face that visits a vertex twice, two faces sharing a vertex,
            a face with fewer than two edges leaving it, or an offset out of
            range; the mesh is unchanged.
    """
    t = _offset(offset)
    ids = list(dict.fromkeys(id_list(faces, "faces")))
    regions = [_face_region(mesh, f) for f in ids]
    _check_disjoint(regions)
    return _cut(mesh, regions, t, max_faces)


def truncate(mesh: Mesh, offset: float = DEFAULT_OFFSET, *,
             max_faces: object = None) -> list[int]:
    """Cut off every vertex at once (TopMod's cut with nothing selected).

    The positions and counts of ``subdivide("vertex-cut", offset)`` (cube:
    24/36/14, 8 triangles and 6 octagons), but the old faces keep their ids
    (every other element is new: the mesh is rebuilt at once, see
    :mod:`._truncation`). Point-spheres stay as they are, ids and all.

    Returns:
        The cap face ids, one per vertex, in vertex id order.

    Raises:
        DLFLError: ``offset`` not in (0, 0.5), or a vertex with a self-loop or
            only one edge; the mesh is unchanged.
        BudgetExceededError: the result would pass the face budget: a face
            per vertex more, three corners per corner (``max_faces``; None: the
            session's, see :mod:`livemod.dlfl.budget`).
    """
    t = _offset(offset)
    if t >= 0.5:
        raise DLFLError(f"truncate cuts every edge from both ends: offset must be below 0.5, "
                        f"got {offset!r}")
    v, e, f = mesh.counts()
    spheres = mesh.num_corners - 2 * e  # they stay as they are
    check_size("truncate", f + v - spheres, 6 * e + spheres, max_faces=max_faces)
    a = mesh_arrays(mesh)
    nxt = a.corner_next
    check_truncatable(a, nxt)
    if not e:  # nothing but point-spheres: nothing to cut, every id kept
        return []
    cut = truncation(a, nxt, t)
    first = mesh.next_ids()
    face_ids = cut.face_ids.copy()
    face_ids[face_ids < 0] = first[2] + np.arange(len(cut.caps))  # the caps, in vertex order
    ids = (_numbered(cut.vertex_ids, first[0]), None, face_ids,
           _numbered(cut.corner_ids, first[3]))
    mesh.replace_with(from_corner_arrays(cut.positions, cut.offsets, cut.corner_vertex,
                                         cut.corner_mate, cut.face_hole, first_ids=first,
                                         ids=ids))
    return face_ids[cut.caps].tolist()


def _numbered(ids: np.ndarray | None, first: int) -> np.ndarray | None:
    """``ids`` with each -1 replaced by the next fresh id from ``first``, in order
    (None: all fresh, numbered by the builder)."""
    if ids is None:
        return None
    fresh = ids < 0
    out = ids.copy()
    out[fresh] = first + np.arange(int(np.count_nonzero(fresh)))
    return out


# -- checks --------------------------------------------------------------------------

def _offset(offset: object) -> float:
    """``offset`` as a float in (0, 1).

    Raises:
        DLFLError: not a finite number, or not strictly between 0 and 1.
    """
    t = finite_number(offset, "offset")
    if not 0.0 < t < 1.0:
        raise DLFLError(f"offset must lie strictly between 0 and 1 (a fraction of each edge), "
                        f"got {offset!r}")
    return t


def _check_cuttable(mesh: Mesh, vertex: int) -> None:
    """Refuse a point-sphere or a vertex with a self-loop (its points would
    coincide with it).

    Raises:
        DLFLError: naming the vertex (or its missing id).
    """
    if mesh.is_point_sphere(vertex):
        raise DLFLError(f"vertex {vertex} is a point-sphere (no edges): there is nothing to cut")
    for c in mesh.vertex_corners(vertex):
        if mesh.corner_vertex(mesh.corner_next(c)) == vertex:
            raise DLFLError(f"vertex {vertex} has a self-loop (edge {mesh.corner_edge(c)}); "
                            "a cut needs edges to other vertices")


def _edge_regions(mesh: Mesh, edges: list[int]) -> list[_Region]:
    """The regions of ``edges``: one per set of edges joined through vertices.

    Raises:
        DLFLError: a missing edge, a self-loop, edges closing a cycle.
    """
    group: dict[int, int] = {}  # vertex -> index of its group in members
    members: list[tuple[list[int], list[int]]] = []  # (vertices, edges) per group
    for e in edges:
        a, b = mesh.edge_vertices(e)
        if a == b:
            raise DLFLError(f"edge {e} is a self-loop (both ends at vertex {a}); it cannot be cut")
        _join(group, members, a, b, e)
    regions = []
    for verts, inner in (m for m in members if m[1]):
        if len(inner) != len(verts) - 1:
            raise DLFLError(f"edges {', '.join(map(str, inner))} close a cycle: a cut of edges "
                            "needs them to form paths or trees (cut the face inside instead)")
        for v in verts:
            _check_cuttable(mesh, v)
        name = f"edge {inner[0]}" if len(inner) == 1 else f"edges {', '.join(map(str, inner))}"
        regions.append(_Region(tuple(verts), frozenset(inner), name=name))
    return regions


def _join(group: dict[int, int], members: list[tuple[list[int], list[int]]],
          a: int, b: int, edge: int) -> None:
    """Add ``edge`` from ``a`` to ``b`` to the groups, merging the later group it
    joins into the earlier one (the later is left empty)."""
    for v in (a, b):
        if v not in group:
            group[v] = len(members)
            members.append(([v], []))
    ga, gb = sorted((group[a], group[b]))
    if ga != gb:
        verts, inner = members[gb]
        members[ga][0].extend(verts)
        members[ga][1].extend(inner)
        members[gb] = ([], [])
        for v in verts:
            group[v] = ga
    members[ga][1].append(edge)


def _face_region(mesh: Mesh, face: int) -> _Region:
    """The region of a face cut.

    Raises:
        DLFLError: a missing or hole face, a point-sphere's face, a face that
            visits a vertex twice.
    """
    verts = mesh.face_vertices(face)
    if mesh.is_hole(face):
        raise DLFLError(f"face {face} is a hole (a boundary of an open mesh): there is no "
                        "surface to cut")
    if len(verts) == 1:
        raise DLFLError(f"face {face} is the face of point-sphere {verts[0]}: there is "
                        "nothing to cut")
    twice = [v for v, n in Counter(verts).items() if n > 1]
    if twice:
        raise DLFLError(f"face {face} visits vertex {twice[0]} more than once; a face cut "
                        "needs a face that visits each vertex once")
    for v in verts:
        _check_cuttable(mesh, v)
    return _Region(tuple(verts), frozenset(mesh.face_edges(face)), face, f"face {face}")


def _check_disjoint(regions: list[_Region]) -> None:
    """Raises DLFLError naming two regions that share a vertex."""
    owner: dict[int, _Region] = {}
    for r in regions:
        for v in r.vertices:
            if v in owner:
                raise DLFLError(f"{owner[v].name} and {r.name} share vertex {v}: cut them in "
                                "separate calls")
            owner[v] = r


# -- the cut -------------------------------------------------------------------------

def _cut(mesh: Mesh, regions: list[_Region], t: float, max_faces: object) -> list[int]:
    """Cut every region (vertex-disjoint) at offset ``t``; return their caps.

    Everything that can fail is checked before the first change; the face
    budget too: a cap per region, and per leaving edge end at most a cap corner
    and the two corners of its split.
    """
    ends = [_leaving_ends(mesh, r) for r in regions]
    flat = [c for region_ends in ends for c in region_ends]
    check_growth(mesh, "cut", faces=len(regions), corners=3 * len(flat), max_faces=max_faces)
    _check_two_sided(mesh, flat, t)
    points = _end_points(mesh, flat, t)
    # from here on nothing can fail: all checks are done
    _split(mesh, flat, points)
    runs = [_run_pairs(mesh, r) for r in regions]
    return [_close(mesh, r, pairs) for r, pairs in zip(regions, runs, strict=True)]


def _leaving_ends(mesh: Mesh, region: _Region) -> list[int]:
    """Corner ids at the region's vertices whose edges leave the region.

    A corner is one end of its edge (the edge runs from its vertex to the next
    corner's), so these are the edge ends the cap's corners go on.

    Raises:
        DLFLError: fewer than two of them (the cap would have under two sides).
    """
    ends = [c for v in region.vertices for c in mesh.vertex_corners(v)
            if mesh.corner_edge(c) not in region.inner]
    if len(ends) < 2:
        raise DLFLError(f"{region.name}: only {len(ends)} edge(s) leave it, and a cut needs "
                        "at least two (the sides of its new face)")
    return ends


def _check_two_sided(mesh: Mesh, ends: list[int], t: float) -> None:
    """Raises DLFLError when an edge cut from both ends would get crossing points."""
    if t < 0.5:
        return
    both = [e for e, n in Counter(mesh.corner_edge(c) for c in ends).items() if n == 2]
    if both:
        raise DLFLError(f"edge {both[0]} is cut from both ends: offset must be below 0.5 "
                        f"(the two new points would cross), got {t!r}")


def _end_points(mesh: Mesh, ends: list[int], t: float) -> np.ndarray:
    """``(k, 3)`` new points, ``t`` of the way along each end's edge from its vertex.

    Weighted ends clamped to their box, so no coordinate overflows.
    """
    near = np.array([mesh.position(mesh.corner_vertex(c)) for c in ends]).reshape(-1, 3)
    far = np.array([mesh.position(mesh.corner_vertex(mesh.corner_next(c)))
                    for c in ends]).reshape(-1, 3)
    with np.errstate(over="ignore"):
        points = (1.0 - t) * near + t * far
    return np.clip(points, np.minimum(near, far), np.maximum(near, far))


def _split(mesh: Mesh, ends: list[int], points: np.ndarray) -> None:
    """Split each edge of ``ends`` (``(k,)`` corners) once per end, placing the new
    vertex of each end at its row of ``points`` ``(k, 3)``."""
    by_edge: dict[int, list[int]] = {}
    for i, c in enumerate(ends):
        by_edge.setdefault(mesh.corner_edge(c), []).append(i)
    for e, rows in by_edge.items():
        # new vertices come in order from side c0's vertex
        if ends[rows[0]] != mesh.edge_corners(e)[0]:
            rows.reverse()
        new = mesh.subdivide_edge(e, len(rows) + 1)
        mesh.set_positions(new, points[rows])


def _run_pairs(mesh: Mesh, region: _Region) -> list[tuple[int, int]]:
    """For each run of region corners in a face ring (after the split), the new
    vertices' corners just before and after it: where the cap's sides go."""
    inside = set(region.vertices)
    pairs = []
    for v in region.vertices:
        for c in mesh.vertex_corners(v):
            before = mesh.corner_prev(c)
            if mesh.corner_face(c) == region.face or mesh.corner_vertex(before) in inside:
                continue
            after = mesh.corner_next(c)
            while mesh.corner_vertex(after) in inside:
                after = mesh.corner_next(after)
            pairs.append((before, after))
    return pairs


def _close(mesh: Mesh, region: _Region, pairs: list[tuple[int, int]]) -> int:
    """Cut each run off its face, delete the region's inside; return the cap."""
    outer = mesh.corner_face(pairs[0][0])
    sides = [mesh.insert_edge(before, after) for before, after in pairs]
    inner = set(region.inner)
    if region.face >= 0:
        # the face merges into the piece across one of its edges; the rest is a path
        opened = mesh.face_edges(region.face)[0]
        mesh.delete_edge(opened)
        inner.discard(opened)
    _delete_tree(mesh, region.vertices, inner)
    f0, f1 = mesh.edge_faces(sides[0])
    cap = f1 if f0 == outer else f0
    mesh.set_hole(cap, False)
    return cap


def _delete_tree(mesh: Mesh, vertices: tuple[int, ...], inner: set[int]) -> None:
    """Delete the ``inner`` edges (a tree on ``vertices``) and the stubs from its
    vertices to the new points, leaves first.

    Each vertex goes when its subtree is gone: its stubs first (each merges two
    pieces, as the vertex still reaches the cap through its parent), then the
    edge to its parent, which leaves it alone, so cleanup removes it. The root
    has a stub, so the last of its stubs removes it.
    """
    root = next(v for v in vertices if any(e not in inner for e in mesh.vertex_edges(v)))
    for v, parent_edge in _post_order(mesh, root, inner):
        for e in mesh.vertex_edges(v):
            if e != parent_edge:
                mesh.delete_edge(e)
        if parent_edge >= 0:
            mesh.delete_edge(parent_edge)


def _post_order(mesh: Mesh, root: int, inner: set[int]) -> list[tuple[int, int]]:
    """``(vertex, edge to its parent or -1)`` of the tree of ``inner`` edges from
    ``root``, children before parents."""
    order = [(root, -1)]
    for v, parent_edge in order:  # grows while walked: breadth first
        for c in mesh.vertex_corners(v):
            e = mesh.corner_edge(c)
            if e in inner and e != parent_edge:
                order.append((mesh.corner_vertex(mesh.corner_next(c)), e))
    return order[::-1]
