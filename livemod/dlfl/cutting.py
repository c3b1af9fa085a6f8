"""Sculpting cuts (TopMod's ``DLFLSculpting.cc``): cut vertices, edges and faces off,
peel a mesh by a plane, truncate.

Every cut removes a *region* of the surface and closes each opening it leaves
with a new face, a *cap*:

* :func:`cut_vertices`: each vertex (a corner cut);
* :func:`cut_edges`: each edge with its two end vertices (a bevel);
* :func:`cut_faces`: each face with its vertices and edges (the face moves in);
* :func:`cut_plane`: everything beyond a plane (TopMod's global cut), or the
  part beyond it joined to one vertex;
* :func:`truncate`: every vertex of the mesh (TopMod's whole-object cut).

**Plane placement** (``placement="plane"``, TopMod's): each element gets a
plane, fitted as TopMod fits it (:mod:`._cut_planes`: through the mean of the
points ``offset`` along the edges around it, square to its normal), and the
cut removes the vertices beyond the plane joined to the element through
vertices beyond it (with ``peel``, every vertex beyond the plane: TopMod's
"Global Cut"). Every edge from a removed vertex to one before the plane gets
a new vertex where the plane crosses it; a vertex on the plane stays and is a
corner of the cap. The caps lie in the plane. An offset past the element's
neighbours takes them too. Cuts are made one after another, each by its plane
fitted on the mesh before the first: a cut whose element an earlier one took
away does nothing.

**Offset placement** (``placement="offset"``): the region is exactly the
element, and every edge *leaving* it gets a new vertex ``offset`` of its length
from the region's end, ``(1 - offset) p + offset q`` for ``p`` the region's end
and ``q`` the far end. All points come from the mesh as it was, so the regions
must not overlap (edges that share a vertex form one region, faces must not
share a vertex). A cap is planar only where its points are.

Either way, a region of ``nv`` vertices, ``ne`` edges (at them) and ``nf``
faces (wholly inside it) with ``k`` edges crossed turns ``V/E/F`` into
``V + k - nv``, ``E + k + s - ne``, ``F + c - nf``, where ``s`` is the number of
new cap sides (one per run of removed corners in a face that keeps other
corners) and ``c`` the number of caps (one per closed loop of cap sides; one
for a region inside a closed surface, two where a plane cuts a ring of a
torus). On TopMod's cube (offset 0.25, both placements): one vertex 10/15/7,
one edge 10/15/7, one face 8/12/6 (a shorter box), truncate 24/36/14.

Everything outside the regions keeps its id; each split edge keeps its id on
the part that stays (see :meth:`Mesh.subdivide_edge`); caps are new faces, and
ordinary faces even where a region touched a hole face (the hole loses that
corner, as with ``subdivide("vertex-cut")``).

How this differs from TopMod:

* TopMod joined the crossing points of a face in any order; livemod cuts each
  run of removed corners off its face on its own, so a face crossed four times
  loses two pieces. A vertex on the plane stays (TopMod split its edges there,
  making edges of length 0).
* A cut whose element lies on the near side of its plane (a concave or saddle
  vertex: TopMod only split its edges) is refused: use the offset placement.
* TopMod's face panel set the edge offset while face cuts read the vertex
  offset, so its offset box did nothing; here each call takes its ``offset``.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from ._checks import finite_number, finite_vector, flag, id_list, shown
from ._cut_planes import Plane, beyond, edge_plane, face_plane, sides, vertex_plane
from ._truncation import check_truncatable, truncation
from .arrays import mesh_arrays
from .budget import check_growth, check_size
from .build import from_corner_arrays
from .errors import GeometryError, InvalidArgumentError
from .mesh import Mesh

__all__ = ["DEFAULT_OFFSET", "PLACEMENTS", "cut_vertices", "cut_edges", "cut_faces",
           "cut_plane", "plane_of_face", "truncate"]

DEFAULT_OFFSET = 0.25
"""TopMod's GUI default for every cut (its spin boxes started at 0.25)."""

PLACEMENTS = ("plane", "offset")
"""Where a cut puts its new points: where the element's plane crosses the edges
(TopMod's), or ``offset`` along each edge leaving the element."""


@dataclass(frozen=True)
class _Region:
    """What one cut removes: ``vertices`` (ids) and the ``inner`` edges between
    them that go with them (every other edge at them is crossed)."""

    vertices: frozenset[int]
    inner: frozenset[int]
    name: str = ""


def cut_vertices(mesh: Mesh, vertices: Iterable[int], offset: float = DEFAULT_OFFSET, *,
                 placement: str = "plane", peel: bool = False,
                 max_faces: object = None) -> list[int]:
    """Cut off each vertex: TopMod's ``cutSelectedVertices`` (Conical > Cut by Vertex).

    Plane placement: the plane through the mean of the points ``offset`` along
    the vertex's edges, square to its normal. Offset placement: a valence-``k``
    vertex becomes a ``k``-gon whose corners lie ``offset`` along its edges.
    Cube corner, offset 0.25, either way: 10/15/7 (a triangle, three pentagons,
    three squares).

    Args:
        mesh: modified in place.
        vertices: ``(n,)`` vertex ids; repeats count once, none is a no-op.
        offset: plane: a number > 0 (past 1 the plane passes the neighbours);
            offset: in (0, 1), and below 0.5 where two cut vertices share an edge.
        placement: ``"plane"`` (TopMod's) or ``"offset"`` (see the module).
        peel: plane only: cut the whole mesh by each plane (TopMod's Global Cut).

    Returns:
        The cap face ids, in the order of the vertices given.

    Raises:
        DLFLError: an id that is not a live vertex, a point-sphere, a vertex with
            a self-loop or only one edge, an offset out of range, a bad
            ``placement`` or ``peel``; plane placement: a vertex with no normal
            or on the near side of its own plane (concave or saddle). The mesh
            is unchanged.
        BudgetExceededError: the result would pass the face budget.
    """
    place, t, peel = _options(offset, placement, peel)
    ids = list(dict.fromkeys(id_list(vertices, "vertices")))
    for v in ids:
        _check_cuttable(mesh, v)
    if place == "offset":
        regions = [_Region(frozenset((v,)), frozenset(), f"vertex {v}") for v in ids]
        return _cut_at_offset(mesh, regions, t, max_faces)
    _check_plane_range(mesh, t)
    planes = [(vertex_plane(mesh, v, t), [v]) for v in ids]
    return _cut_by_planes(mesh, planes, peel, max_faces)


def cut_edges(mesh: Mesh, edges: Iterable[int], offset: float = DEFAULT_OFFSET, *,
              placement: str = "plane", peel: bool = False,
              max_faces: object = None) -> list[int]:
    """Cut off each edge with its end vertices: TopMod's ``cutSelectedEdges``.

    Plane placement: per edge, the plane through the mean of the points
    ``offset`` along the other edges at its two ends, square to the sum of its
    two faces' normals. Offset placement: edges that share a vertex form one
    region (they must not close a cycle: cut the face inside it instead), whose
    cap's corners lie ``offset`` along every other edge at its vertices. Cube
    edge, offset 0.25, either way: 10/15/7 (the cap and four squares, two
    pentagons).

    Args:
        mesh: modified in place.
        edges: ``(n,)`` edge ids; repeats count once, none is a no-op.
        offset, placement, peel: as :func:`cut_vertices` (offset placement:
            below 0.5 on an edge cut from both ends).

    Returns:
        The cap face ids, in the order of their first edge.

    Raises:
        DLFLError: an id that is not a live edge, a self-loop, an offset out of
            range, a bad ``placement`` or ``peel``; offset placement: edges
            closing a cycle, a region with fewer than two edges leaving it;
            plane placement: an edge with no plane or on its near side. The
            mesh is unchanged.
        BudgetExceededError: the result would pass the face budget.
    """
    place, t, peel = _options(offset, placement, peel)
    ids = list(dict.fromkeys(id_list(edges, "edges")))
    if place == "offset":
        return _cut_at_offset(mesh, _edge_regions(mesh, ids), t, max_faces)
    for e in ids:
        a, b = mesh.edge_vertices(e)
        if a == b:
            raise InvalidArgumentError(f"edge {e} is a self-loop (both ends at vertex {a}); "
                                       "it cannot be cut")
    _check_plane_range(mesh, t)
    planes = [(edge_plane(mesh, e, t), list(mesh.edge_vertices(e))) for e in ids]
    return _cut_by_planes(mesh, planes, peel, max_faces)


def cut_faces(mesh: Mesh, faces: Iterable[int], offset: float = DEFAULT_OFFSET, *,
              placement: str = "plane", peel: bool = False,
              max_faces: object = None) -> list[int]:
    """Cut off each face with its vertices and edges: TopMod's ``cutSelectedFaces``.

    Plane placement: the plane through the mean of the points ``offset`` along
    every edge that leaves the face's vertices, square to the face's normal.
    Offset placement: the cap replaces the face ``offset`` along every edge that
    leaves it. On a convex solid the face moves inwards and its neighbours get
    shorter. Cube face, offset 0.25, either way: 8/12/6, the box a quarter lower.

    Args:
        mesh: modified in place.
        faces: ``(n,)`` face ids; repeats count once. Offset placement: no two
            sharing a vertex.
        offset, placement, peel: as :func:`cut_vertices`.

    Returns:
        The cap face ids, in the order given.

    Raises:
        DLFLError: an id that is not a live face, a hole face, a point-sphere's
            face, a face that visits a vertex twice, an offset out of range, a
            bad ``placement`` or ``peel``; offset placement: two faces sharing a
            vertex, a face with fewer than two edges leaving it; plane
            placement: a face with no normal or no edge leaving it. The mesh is
            unchanged.
        BudgetExceededError: the result would pass the face budget.
    """
    place, t, peel = _options(offset, placement, peel)
    ids = list(dict.fromkeys(id_list(faces, "faces")))
    regions = [_face_region(mesh, f) for f in ids]
    if place == "offset":
        _check_disjoint(regions)
        return _cut_at_offset(mesh, regions, t, max_faces)
    _check_plane_range(mesh, t)
    planes = [(face_plane(mesh, f, t), mesh.face_vertices(f)) for f in ids]
    return _cut_by_planes(mesh, planes, peel, max_faces)


def plane_of_face(mesh: Mesh, face: int) -> tuple[np.ndarray, np.ndarray]:
    """``(point, normal)``, each ``(3,)``: the plane through ``face`` (its centroid
    and its unit normal, TopMod's), for :func:`cut_plane`.

    Raises:
        DLFLError: ``face`` is not a live face, or has no normal.
    """
    plane = face_plane(mesh, face)
    return plane.point, plane.normal


def cut_plane(mesh: Mesh, point: object, normal: object, *, seed: int | None = None,
              max_faces: object = None) -> list[int]:
    """Cut off everything beyond a plane: TopMod's ``peelByPlane`` (Global Cut).

    The vertices on the side ``normal`` points to go, with their edges and the
    faces wholly among them; every edge from one of them to a vertex before the
    plane gets a new vertex where the plane crosses it, and each opening is
    closed by a cap in the plane. With ``seed``, only the vertices beyond the
    plane joined to ``seed`` through vertices beyond it go (TopMod's local cut).
    Cube, plane z = 0.5: 8/12/6 (the box, its top at 0.5).

    Args:
        mesh: modified in place.
        point: three numbers, a point of the plane.
        normal: three numbers, not all 0; its length does not matter.
        seed: a vertex id, or None for the whole mesh.

    Returns:
        The cap face ids (none when nothing lies beyond the plane; a component
        wholly beyond it goes without a cap).

    Raises:
        DLFLError: ``point`` or ``normal`` not three finite numbers, a zero
            normal, a ``seed`` that is not a live vertex or does not lie beyond
            the plane. The mesh is unchanged.
        BudgetExceededError: the result would pass the face budget.
    """
    p = finite_vector(point, "point")
    n = finite_vector(normal, "normal")
    length = float(np.linalg.norm(n))
    if not length > 0:
        raise InvalidArgumentError(f"normal must not be zero, got {shown(normal)}")
    if seed is not None:
        mesh.position(int(id_list([seed], "seed")[0]))  # an unknown id is refused here
    _check_plane_range(mesh, offset_too=False)
    plane = Plane(p, n / length, "the plane" if seed is None else f"seed vertex {seed}")
    return _cut_by_planes(mesh, [(plane, None if seed is None else [int(seed)])],
                          seed is None, max_faces)


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
        raise InvalidArgumentError(
            f"truncate cuts every edge from both ends: offset must be below 0.5, "
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
    # a face keeps its id and colour; a cap has none
    kept = np.where(cut.face_ids >= 0, np.searchsorted(a.face_ids, cut.face_ids), -1)
    mesh.replace_with(from_corner_arrays(cut.positions, cut.offsets, cut.corner_vertex,
                                         cut.corner_mate, cut.face_hole, first_ids=first,
                                         ids=ids, face_colors=a.colors_at(kept)))
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

def _options(offset: object, placement: object, peel: object) -> tuple[str, float, bool]:
    """``(placement, offset, peel)`` checked.

    Raises:
        DLFLError: ``placement`` not one of :data:`PLACEMENTS`, ``peel`` not a flag
            or set with the offset placement, ``offset`` not a finite number, not
            > 0, or (offset placement) not below 1.
    """
    if placement not in PLACEMENTS:
        raise InvalidArgumentError(f"placement must be one of {', '.join(map(repr, PLACEMENTS))},"
                                   f" got {shown(placement)}")
    peeled = flag(peel, "peel")
    if peeled and placement == "offset":
        raise InvalidArgumentError("peel cuts the whole mesh by each element's plane: it needs "
                                   "placement='plane'")
    if placement == "offset":
        return "offset", _offset(offset), False
    t = finite_number(offset, "offset")
    if not t > 0:
        raise InvalidArgumentError(f"offset must be a number > 0 (how far along the edges the "
                                   f"plane passes), got {shown(offset)}")
    return "plane", t, peeled


# plane cuts take differences of positions and products of those (normals,
# distances to a plane): coordinates past the square root of the float range
# would overflow them
_PLANE_RANGE = 1e150


def _check_plane_range(mesh: Mesh, offset: float = 1.0, offset_too: bool = True) -> None:
    """Refuse a plane cut whose arithmetic would overflow: the mesh's coordinates,
    or the points ``offset`` along its edges, beyond :data:`_PLANE_RANGE`
    (``offset_too``: the message points to the offset placement as well).

    Raises:
        GeometryError: a coordinate beyond the range.
        InvalidArgumentError: an ``offset`` that takes the points beyond it.
    """
    positions = mesh.positions_view()
    largest = float(np.abs(positions).max(initial=0.0))
    if not largest <= _PLANE_RANGE:
        hint = ", or use placement='offset'" if offset_too else ""
        raise GeometryError(f"a plane cut needs coordinates within {_PLANE_RANGE:.0e}; this "
                            f"mesh has one of {largest:.3g} (scale it down{hint})")
    if not largest * offset <= _PLANE_RANGE:
        raise InvalidArgumentError(f"offset {offset:g} puts the plane's points beyond "
                                   f"{_PLANE_RANGE:.0e} from the origin; use a smaller offset")


def _offset(offset: object) -> float:
    """``offset`` as a float in (0, 1).

    Raises:
        DLFLError: not a finite number, or not strictly between 0 and 1.
    """
    t = finite_number(offset, "offset")
    if not 0.0 < t < 1.0:
        raise InvalidArgumentError(f"offset must lie strictly between 0 and 1 (a fraction of "
                                   f"each edge), got {offset!r}")
    return t


def _check_cuttable(mesh: Mesh, vertex: int) -> None:
    """Refuse a point-sphere or a vertex with a self-loop (its points would
    coincide with it).

    Raises:
        DLFLError: naming the vertex (or its missing id).
    """
    if mesh.is_point_sphere(vertex):
        raise InvalidArgumentError(
            f"vertex {vertex} is a point-sphere (no edges): there is nothing to cut")
    for c in mesh.vertex_corners(vertex):
        if mesh.corner_vertex(mesh.corner_next(c)) == vertex:
            raise InvalidArgumentError(
                f"vertex {vertex} has a self-loop (edge {mesh.corner_edge(c)}); "
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
            raise InvalidArgumentError(
                f"edge {e} is a self-loop (both ends at vertex {a}); it cannot be cut")
        _join(group, members, a, b, e)
    regions = []
    for verts, inner in (m for m in members if m[1]):
        if len(inner) != len(verts) - 1:
            raise InvalidArgumentError(
                f"edges {', '.join(map(str, inner))} close a cycle: a cut of edges "
                "needs them to form paths or trees (cut the face inside instead)")
        for v in verts:
            _check_cuttable(mesh, v)
        name = f"edge {inner[0]}" if len(inner) == 1 else f"edges {', '.join(map(str, inner))}"
        regions.append(_Region(frozenset(verts), frozenset(inner), name=name))
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
    """The region of a face cut: the face's vertices and its sides.

    Raises:
        DLFLError: a missing or hole face, a point-sphere's face, a face that
            visits a vertex twice.
    """
    verts = mesh.face_vertices(face)
    if mesh.is_hole(face):
        raise InvalidArgumentError(f"face {face} is a hole (a boundary of an open mesh): there "
                                   "is no surface to cut")
    if len(verts) == 1:
        raise InvalidArgumentError(f"face {face} is the face of point-sphere {verts[0]}: there "
                                   "is nothing to cut")
    twice = [v for v, n in Counter(verts).items() if n > 1]
    if twice:
        raise InvalidArgumentError(f"face {face} visits vertex {twice[0]} more than once; a "
                                   "face cut needs a face that visits each vertex once")
    for v in verts:
        _check_cuttable(mesh, v)
    return _Region(frozenset(verts), frozenset(mesh.face_edges(face)), f"face {face}")


def _check_disjoint(regions: list[_Region]) -> None:
    """Raises DLFLError naming two regions that share a vertex."""
    owner: dict[int, _Region] = {}
    for r in regions:
        for v in r.vertices:
            if v in owner:
                raise InvalidArgumentError(
                    f"{owner[v].name} and {r.name} share vertex {v}: cut them in "
                    "separate calls")
            owner[v] = r


# -- offset placement ----------------------------------------------------------------

def _cut_at_offset(mesh: Mesh, regions: list[_Region], t: float, max_faces: object
                   ) -> list[int]:
    """Cut every region (vertex-disjoint) at offset ``t``; return their caps.

    Everything that can fail is checked before the first change; the face
    budget too: a cap per region, and per leaving edge end at most a cap corner
    and the two corners of its split.
    """
    ends = [_leaving_ends(mesh, r) for r in regions]
    for r, region_ends in zip(regions, ends, strict=True):
        if len(region_ends) < 2:
            raise InvalidArgumentError(f"{r.name}: only {len(region_ends)} edge(s) leave it, and "
                                       "a cut needs at least two (the sides of its new face)")
    flat = [c for region_ends in ends for c in region_ends]
    check_growth(mesh, "cut", faces=len(regions), corners=3 * len(flat), max_faces=max_faces)
    _check_two_sided(mesh, flat, t)
    points = _end_points(mesh, flat, t)
    # from here on nothing can fail: all checks are done
    _split(mesh, flat, points)
    runs = [_run_starts(mesh, r.vertices) for r in regions]
    return [cap for r, starts in zip(regions, runs, strict=True)
            for cap in _close(mesh, r.vertices, starts)]


def _leaving_ends(mesh: Mesh, region: _Region) -> list[int]:
    """Corner ids at the region's vertices whose edges leave the region.

    A corner is one end of its edge (the edge runs from its vertex to the next
    corner's), so these are the edge ends the cap's corners go on.
    """
    return [c for v in sorted(region.vertices) for c in mesh.vertex_corners(v)
            if mesh.corner_edge(c) not in region.inner]


def _check_two_sided(mesh: Mesh, ends: list[int], t: float) -> None:
    """Raises DLFLError when an edge cut from both ends would get crossing points."""
    if t < 0.5:
        return
    both = [e for e, n in Counter(mesh.corner_edge(c) for c in ends).items() if n == 2]
    if both:
        raise InvalidArgumentError(f"edge {both[0]} is cut from both ends: offset must be "
                                   f"below 0.5 (the two new points would cross), got {t!r}")


def _end_points(mesh: Mesh, ends: list[int], t: float) -> np.ndarray:
    """``(k, 3)`` new points, ``t`` of the way along each end's edge from its vertex.

    Weighted ends clamped to their box, so no coordinate overflows.
    """
    near, far = _end_positions(mesh, ends)
    with np.errstate(over="ignore"):
        points = (1.0 - t) * near + t * far
    return np.clip(points, np.minimum(near, far), np.maximum(near, far))


def _end_positions(mesh: Mesh, ends: list[int]) -> tuple[np.ndarray, np.ndarray]:
    """``(near, far)``, ``(k, 3)`` each: the positions of each end's vertex and of
    the other end of its edge."""
    near = np.array([mesh.position(mesh.corner_vertex(c)) for c in ends]).reshape(-1, 3)
    far = np.array([mesh.position(mesh.corner_vertex(mesh.corner_next(c)))
                    for c in ends]).reshape(-1, 3)
    return near, far


# -- plane placement -----------------------------------------------------------------

def _cut_by_planes(mesh: Mesh, planes: Sequence[tuple[Plane, list[int] | None]], peel: bool,
                   max_faces: object) -> list[int]:
    """Cut by each plane in turn (its vertices beyond it joined to its seeds, or
    with ``peel`` all of them) on a copy, kept when every cut has succeeded;
    return the caps that are left."""
    work = mesh.copy()
    caps: list[int] = []
    for plane, seeds in planes:
        if seeds is not None and not any(work.has_vertex(v) for v in seeds):
            continue  # an earlier cut took the element away
        side = sides(work, plane)
        region = beyond(work, side, None if peel else [v for v in seeds or []
                                                      if work.has_vertex(v)])
        if not region and not peel:
            raise GeometryError(f"{plane.name} lies on the near side of its cutting plane (a "
                                "concave or saddle vertex): a plane cut removes nothing; use "
                                "placement='offset'")
        caps.extend(_cut_region(work, region, plane, side, max_faces))
    mesh.replace_with(work)
    return [f for f in dict.fromkeys(caps) if mesh.has_face(f)]


def _cut_region(mesh: Mesh, region: set[int], plane: Plane, side: dict[int, int],
                max_faces: object) -> list[int]:
    """Remove ``region`` (vertices beyond ``plane``), splitting each edge to a vertex
    before it where the plane crosses; return the caps."""
    if not region:
        return []
    ends = [c for v in sorted(region) for c in mesh.vertex_corners(v)
            if side[mesh.corner_vertex(mesh.corner_next(c))] < 0]
    pairs_bound = sum(mesh.face_size(f) for f in {mesh.corner_face(c) for v in region
                                                  for c in mesh.vertex_corners(v)})
    check_growth(mesh, "plane cut", faces=pairs_bound, corners=2 * len(ends) + 2 * pairs_bound,
                 max_faces=max_faces)
    near, far = _end_positions(mesh, ends)
    d_near, d_far = (near - plane.point) @ plane.normal, (far - plane.point) @ plane.normal
    t = (d_near / (d_near - d_far))[:, None]
    points = np.clip(near + t * (far - near), np.minimum(near, far), np.maximum(near, far))
    _split(mesh, ends, points)
    return _close(mesh, frozenset(region), _run_starts(mesh, frozenset(region)))


# -- closing a region ----------------------------------------------------------------

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


def _run_starts(mesh: Mesh, inside: frozenset[int]) -> list[int]:
    """The first corner of each run of ``inside`` corners in a face ring that also
    has other corners: where the cap's sides go."""
    starts = []
    for v in sorted(inside):
        for c in mesh.vertex_corners(v):
            if mesh.corner_vertex(mesh.corner_prev(c)) not in inside and _run_end(mesh, c, inside):
                starts.append(c)
    return starts


def _run_end(mesh: Mesh, start: int, inside: frozenset[int]) -> int | None:
    """The corner just after the run of ``inside`` corners from ``start``; None when
    the whole ring is inside."""
    after = mesh.corner_next(start)
    while mesh.corner_vertex(after) in inside:
        if after == start:
            return None
        after = mesh.corner_next(after)
    return after


def _close(mesh: Mesh, inside: frozenset[int], starts: list[int]) -> list[int]:
    """Cut each run (from its first corner in ``starts``) off its face, delete the
    region's vertices; return the caps.

    The corners around a run are found when it is cut: cutting an earlier run
    of the same face moves the corner two runs share to the piece cut off. A run
    whose face has no corner besides it and the one or two around it needs no
    new side: the whole face goes, its edge between those two is a cap side.
    """
    touched = {mesh.corner_face(c) for v in inside for c in mesh.vertex_corners(v)}
    first_new = mesh.next_ids()[2]
    kept: set[int] = set()
    rim: set[int] = set()
    for start in starts:
        before, after = mesh.corner_prev(start), _run_end(mesh, start, inside)
        assert after is not None  # the face keeps corners outside: a run start says so
        rim.update((mesh.corner_vertex(before), mesh.corner_vertex(after)))
        if mesh.corner_next(after) == before or after == before:
            continue
        mesh.insert_edge(before, after)
        kept.add(mesh.corner_face(before))  # the piece outside keeps the face's id
    _remove(mesh, inside)
    caps = [f for v in sorted(rim) if mesh.has_vertex(v) for f in mesh.vertex_faces(v)
            if (f in touched or f >= first_new) and f not in kept]
    caps = list(dict.fromkeys(caps))
    for cap in caps:
        mesh.set_hole(cap, False)
        mesh.set_face_color(cap, None)  # a cap lies across faces: it has no one source
    return caps


def _remove(mesh: Mesh, vertices: frozenset[int]) -> None:
    """Delete every edge at ``vertices`` and so the vertices: first each edge
    between two faces (merging them, one pass: merging never parts two faces),
    then what is left, which hangs in the merged faces as trees, leaves first."""
    doomed = sorted({e for v in vertices for e in mesh.vertex_edges(v)})
    left = []
    for e in doomed:
        f0, f1 = mesh.edge_faces(e)
        if f0 != f1:
            mesh.delete_edge(e)
        else:
            left.append(e)
    _delete_trees(mesh, left)


def _delete_trees(mesh: Mesh, edges: list[int]) -> None:
    """Delete ``edges`` (each with one face on both sides), each once one of its
    ends has no other edge (cleanup then takes that end away); an edge between
    two loops of its face, which no leaf reaches, splits the face in two."""
    todo = set(edges)
    leaves = [e for e in edges if _is_leaf(mesh, e)]
    while todo:
        e = leaves.pop() if leaves else min(todo)
        if e not in todo:
            continue
        ends = mesh.edge_vertices(e)
        mesh.delete_edge(e)
        todo.discard(e)
        for v in ends:
            if mesh.has_vertex(v):
                leaves.extend(x for x in mesh.vertex_edges(v) if x in todo and _is_leaf(mesh, x))


def _is_leaf(mesh: Mesh, edge: int) -> bool:
    """True when an end of ``edge`` has no other edge."""
    return any(mesh.valence(v) == 1 for v in mesh.edge_vertices(edge))
