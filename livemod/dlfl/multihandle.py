"""The multi-face handle family: several faces joined at once (TopMod's
``multiConnectFaces`` overloads, ``DLFLMultiConnect.cc``; TOPMOD.md §5).

* :func:`multi_face_handle`: a hub, the convex hull of the faces' points pushed
  along their normals (by ``extrude``, or with ``max_offsets`` by each face's
  :func:`face_max_offsets`), joined to every face by a tube;
* :func:`multi_face_handle_fitted`: the same kind of hub, fitted by a binary search
  that moves the faces toward their common centre (TopMod's iterative variant);
* :func:`multi_face_handle_closest_edges`: no hub, quads between the closest edges
  of the faces (TopMod's "ClosestEdge" variant).

The hubs are built with :func:`add_polyhedron` and :func:`.hull.hull_polygons`,
whose merged coplanar facets leave nothing for TopMod's ``edgeCleanup`` of the
hull to do; the tubes and quads are :func:`.connect.connect_faces` and
:func:`.connect.connect_edge_sides`. Every function checks its input and builds
its hull before touching the mesh, so a :class:`DLFLError` leaves the mesh
unchanged. :mod:`livemod.dlfl.connect` re-exports the family.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from ._checks import finite_number, flag, id_list, positive_number
from ._vectors import centroid, lengths, shifted_in_range, unit
from .analysis import face_points, polygon_normal
from .bands import edges_since
from .budget import check_growth
from .connect import closest_corners, connect_edge_sides, connect_faces
from .errors import (
    DLFLError,
    GeometryError,
    InvalidArgumentError,
    InvalidMeshError,
    UnknownIdError,
)
from .geometry import edge_cleanup
from .hull import hull_polygons
from .mesh import Mesh

__all__ = [
    "multi_face_handle", "multi_face_handle_fitted", "multi_face_handle_closest_edges",
    "face_max_offsets", "fitted_factor", "add_polyhedron",
]

# TopMod's 5 degrees: the planarity a pair of edges needs, and how near to the
# plane of the faces' centroids its quad may turn
_COS5 = math.cos(math.radians(5.0))

# hub points closer than this times the faces' largest extent are one: TopMod's
# absolute 1e-2 on its cube.obj (edge length 2, livemod's cube())
_MERGE = 5e-3


# -- checks and small helpers --------------------------------------------------------

def _check_handle_faces(mesh: Mesh, faces: list[int], op: str = "multi_face_handle") -> None:
    """Raises DLFLError unless ``faces`` holds two or more different live faces,
    each with a normal."""
    if len(faces) < 2 or len(set(faces)) != len(faces):
        raise InvalidArgumentError(f"{op} needs two or more different faces, got {faces}")
    for f in faces:
        if not mesh.has_face(f):
            raise UnknownIdError(f"face {f} does not exist (deleted or never made)")
        if mesh.face_size(f) < 3 or not np.any(polygon_normal(face_points(mesh, f))):
            raise GeometryError(f"face {f} has no normal (fewer than 3 corners or degenerate)")


def _check_budget(mesh: Mesh, faces: list[int], op: str, growth: tuple[int, int],
                  max_faces: object) -> None:
    """Refuse a handle of the (checked) ``faces`` that could pass the face budget:
    it adds at most ``growth`` ``(faces, corners)`` per corner of the faces.

    A hub of ``S`` points (at most the faces' ``S`` corners) has at most ``2S``
    faces and ``6S`` corners, and each tube to it at most as many faces as its
    two ends have corners, four corners each (see :mod:`.connect`): ``(9, 34)``.
    Quads between closest edges add a face and four corners per pair: ``(1, 4)``.

    Raises:
        BudgetExceededError: the handle could pass the budget.
    """
    corners = sum(mesh.face_size(f) for f in faces)
    check_growth(mesh, op, faces=growth[0] * corners, corners=growth[1] * corners,
                 max_faces=max_faces)


# a hub handle's most faces and corners per corner of its faces (_check_budget)
_HUB_GROWTH = (9, 34)


def _apart(p: np.ndarray, q: np.ndarray, merge: float) -> bool:
    """Whether the ``(3,)`` points are at least ``merge`` apart, squaring only
    differences too small to overflow. A difference that overflows counts as apart
    (inf - inf, NaN, does not: such points are refused anyway)."""
    with np.errstate(over="ignore", invalid="ignore"):  # inf - inf: NaN, not apart
        d = p - q
    top = float(np.abs(d).max())
    if not top < merge:  # apart, or NaN somewhere
        return top >= merge
    return float(d @ d) >= merge * merge


def _merged(points: np.ndarray, faces_points: np.ndarray) -> np.ndarray:
    """``(k, 3)`` the ``(n, 3)`` ``points`` with coincident ones kept once (the first
    of each, in order): those closer than :data:`_MERGE` times the largest extent
    along an axis of the ``(m, 3)`` ``faces_points``, the selected faces' own points.

    TopMod merged within an absolute 1e-2, which swallows the whole hub of a mesh
    1e-6 across; relative, the merge is the same at every scale, and on TopMod's
    cube (edge length 2) exactly its 1e-2. The faces' size, not the pushed
    points', is the measure: how far apart their corners are does not depend on
    ``extrude``. The test runs on both sets framed together
    (:func:`.shifted_in_range`: moved and scaled by one power of two, so no
    product of huge or tiny coordinates under- or overflows); inside the float
    band the frame is the points themselves. Faces too far apart for a finite
    extent fall back to TopMod's absolute 1e-2 on the raw points, and pushed
    points that overflow stay inf: :func:`.hull.hull_polygons` refuses both.
    """
    framed = shifted_in_range(np.concatenate([faces_points, points]))
    own, pushed = framed[:len(faces_points)], framed[len(faces_points):]
    with np.errstate(over="ignore", invalid="ignore"):  # inf / NaN: the fallback below
        extent = float(np.ptp(own, axis=0).max())
    if not math.isfinite(extent):  # faces spread beyond the float range: refused later
        pushed, extent = points, 1.0
    merge = _MERGE * extent
    kept: list[int] = []
    for i, p in enumerate(pushed):
        if all(_apart(p, pushed[j], merge) for j in kept):
            kept.append(i)
    return points[kept]


# -- the hub ------------------------------------------------------------------------------

def add_polyhedron(mesh: Mesh, points: np.ndarray, polygons: list[list[int]]) -> list[int]:
    """Add a closed genus-0 polyhedron to ``mesh`` with the minimal operators only.

    One point-sphere per point, then one :meth:`Mesh.insert_edge` per edge. Each
    edge goes into the corner whose angular sector, in the rotation the polygons
    give each vertex, holds the new neighbour, so the partial graph always stays
    planar and the last edges close exactly the given faces.

    Args:
        points: ``(k, 3)`` positions; every point must be used by a polygon.
        polygons: point indices per face, counter-clockwise seen from outside,
            forming a closed sphere-like surface (as :func:`.hull.hull_polygons`).

    Returns:
        The new face id of each polygon, in order.
    """
    rotation = _rotations(polygons)
    vertex = {p: mesh.create_vertex(points[p]) for p in sorted(rotation)}
    done: set[tuple[int, int]] = set()
    for poly in polygons:
        for a, b in zip(poly, poly[1:] + poly[:1], strict=True):
            if (b, a) in done:
                continue
            done.add((a, b))
            mesh.insert_edge(_sector_corner(mesh, vertex, rotation, a, b),
                             _sector_corner(mesh, vertex, rotation, b, a))
    return [mesh.corner_face(_corner_towards(mesh, vertex[poly[0]], vertex[poly[1]]))
            for poly in polygons]


def _rotations(polygons: list[list[int]]) -> dict[int, list[int]]:
    """Each point's neighbours counter-clockwise around it, seen from outside."""
    after: dict[int, dict[int, int]] = {}
    for poly in polygons:
        n = len(poly)
        for i, p in enumerate(poly):
            after.setdefault(p, {})[poly[(i + 1) % n]] = poly[i - 1]
    rotation = {}
    for p, step in after.items():
        first = next(iter(step))
        ring, q = [first], step[first]
        while q != first:
            ring.append(q)
            q = step[q]
        rotation[p] = ring
    return rotation


def _sector_corner(mesh: Mesh, vertex: dict[int, int], rotation: dict[int, list[int]],
                   a: int, b: int) -> int:
    """The corner at point ``a`` whose sector (from its next vertex counter-clockwise
    to its previous one) holds the new neighbour ``b``."""
    corners = mesh.vertex_corners(vertex[a])
    if len(corners) == 1:
        return corners[0]
    point_of = {v: p for p, v in vertex.items()}
    ring = rotation[a]
    place = {q: i for i, q in enumerate(ring)}
    for c in corners:
        start = place[point_of[mesh.corner_vertex(mesh.corner_next(c))]]
        end = place[point_of[mesh.corner_vertex(mesh.corner_prev(c))]]
        span = (end - start) % len(ring) or len(ring)
        if 0 < (place[b] - start) % len(ring) < span:
            return c
    raise InvalidMeshError(f"internal: no corner of point {a} can take an edge to point {b}")


def _corner_towards(mesh: Mesh, u: int, w: int) -> int:
    for c in mesh.vertex_corners(u):
        if mesh.corner_vertex(mesh.corner_next(c)) == w:
            return c
    raise InvalidMeshError(f"internal: vertex {u} has no edge to vertex {w}")


def _hub_polygons(mesh: Mesh, face: int, normal: np.ndarray,
                  points: np.ndarray) -> list[list[int]]:
    """The hull of the ``(k, 3)`` hub points, turned inside out when ``face``'s
    ``normal`` points away from the points' centroid (the hub then wraps the faces
    and must face them from outside).

    Raises:
        DLFLError: see :func:`.hull.hull_polygons` and :func:`_check_every_point_used`.
    """
    polygons = hull_polygons(points)
    # quarters: the difference of two huge centroids cannot overflow
    outward = centroid(face_points(mesh, face)) * 0.25 - centroid(points) * 0.25
    if float(normal @ outward) > 0:
        polygons = [poly[::-1] for poly in polygons]
    _check_every_point_used(polygons, len(points))
    return polygons


def _check_every_point_used(polygons: list[list[int]], count: int) -> None:
    """Refuse a hub hull that leaves out one of its ``count`` points (one inside the
    hull or inside a hull face): its face would lose a corner to the hub.

    Raises:
        DLFLError: naming the first point no polygon uses.
    """
    unused = sorted(set(range(count)) - {p for poly in polygons for p in poly})
    if unused:
        raise GeometryError(f"hub point {unused[0]} lies inside the hub's convex hull (or "
                            "inside one of its faces); try another extrude or scale")


def _facing_polygons(points: np.ndarray, polygons: list[list[int]], faces: list[int],
                     normals: list[np.ndarray], hint: str = "try another extrude or scale"
                     ) -> list[int]:
    """For each selected face, the hull polygon whose normal is opposite to its own
    (``hint``: what the error message suggests).

    Raises:
        DLFLError: a face has no such polygon left (TopMod skipped the face).
    """
    hull_normals = [polygon_normal(points[poly]) for poly in polygons]
    partner: list[int] = []
    for f, normal in zip(faces, normals, strict=True):
        match = [i for i, n in enumerate(hull_normals) if abs(1.0 + float(n @ normal)) < 1e-6]
        free = [i for i in match if i not in partner]
        if not free:
            raise GeometryError(f"face {f} has no hull face facing it; {hint}")
        partner.append(free[0])
    return partner


def _join_hub(mesh: Mesh, faces: list[int], points: np.ndarray, polygons: list[list[int]],
              partner: list[int] | None) -> list[int]:
    """Add the hub and join each face to its partner polygon (closest corners);
    ``partner`` None adds the hub alone. Returns the new edge ids."""
    first = mesh.next_ids()[1]
    hull_faces = add_polyhedron(mesh, points, polygons)
    for face, poly in zip(faces, partner or [], strict=False):
        connect_faces(mesh, *closest_corners(mesh, face, hull_faces[poly]))
    return edges_since(mesh, first)


# -- convex-hull handle ------------------------------------------------------------------

def multi_face_handle(mesh: Mesh, faces: list[int], scale: float = 1.0,
                      extrude: float = 0.5, *, max_offsets: bool = False,
                      max_faces: object = None) -> list[int]:
    """Join several faces through one hub, the convex hull of their vertices
    (TopMod's ``multiConnectFaces(faces, scale, extrude, maxOffsets)``).

    Each face's vertices are pushed along its normal, by ``extrude`` or, with
    ``max_offsets``, by the face's own :func:`face_max_offsets` (``extrude`` where
    nothing limits it); coincident points (within 5e-3 times the faces' largest
    extent along an axis: TopMod's absolute 1e-2 on its cube, edge length 2) are
    kept once, then scaled by ``|scale|`` about their centroid (unless 0 or 1).
    Their convex hull
    (:func:`.hull.hull_polygons`: coplanar facets merged, points on hull edges kept
    as corners) is added, reversed when the first face's normal points away from
    the hull's centroid. Each face is joined (closest corners,
    :func:`.connect.connect_faces`) to the hull face parallel to it and facing it.
    Cube faces 0, 2, 4: 20/42/20, genus 2 (with ``max_offsets`` too: no face's
    offset is limited there).

    Returns:
        The ids of the new edges (the hull's and the tubes').

    Raises:
        DLFLError: fewer than two faces, an entry that is not an id, a repeated
            or gone face, a face of fewer than 3 corners, ``scale`` or ``extrude``
            not a finite number, ``max_offsets`` not a flag, points all in one
            plane or too nearly coplanar for their hull to close up, a point inside
            the hull (or one of its faces), or a face with no hull face facing it
            (TopMod skipped it silently). The mesh is unchanged.
        BudgetExceededError: the handle could pass the face budget
            (``max_faces``, None for the session's: :mod:`livemod.dlfl.budget`).
    """
    faces = id_list(faces, "faces")
    scale = finite_number(scale, "scale")
    extrude = finite_number(extrude, "extrude")
    use_max = flag(max_offsets, "max_offsets")
    _check_handle_faces(mesh, faces)
    _check_budget(mesh, faces, "multi_face_handle", _HUB_GROWTH, max_faces)
    normals = [polygon_normal(face_points(mesh, f)) for f in faces]
    offsets = face_max_offsets(mesh, faces, extrude) if use_max else np.full(len(faces), extrude)
    points = _hub_points(mesh, faces, normals, offsets, scale)
    polygons = _hub_polygons(mesh, faces[0], normals[0], points)
    partner = _facing_polygons(points, polygons, faces, normals)
    return _join_hub(mesh, faces, points, polygons, partner)


def _hub_points(mesh: Mesh, faces: list[int], normals: list[np.ndarray], offsets: np.ndarray,
                scale: float) -> np.ndarray:
    """``(k, 3)`` the face points pushed by ``offsets`` ``(len(faces),)``, coincident
    ones kept once (:func:`_merged`), scaled by ``|scale|`` about their centroid;
    points beyond the float range come out inf, which :func:`.hull.hull_polygons`
    refuses."""
    rings = [face_points(mesh, f) for f in faces]
    with np.errstate(over="ignore", invalid="ignore"):  # refused by hull_polygons
        pushed = np.concatenate([ring + t * n
                                 for ring, n, t in zip(rings, normals, offsets, strict=True)])
    points = _merged(pushed, np.concatenate(rings))
    factor = abs(scale)
    if factor > 1e-12 and abs(factor - 1.0) > 1e-12:
        centre = centroid(points)
        with np.errstate(over="ignore", invalid="ignore"):  # refused by hull_polygons
            points = centre + (points - centre) * factor
    return points


def face_max_offsets(mesh: Mesh, faces: list[int], fallback: float = 0.5) -> np.ndarray:
    """How far each face can be pushed along its normal before one of its points
    crosses a side wall of another face (TopMod's ``findMaxOffsets``).

    A face's side walls are the planes through its edges along its normal (origin:
    the edge midpoint; normal: the unit edge direction x the face normal). For face
    ``i``, the ray from each of its points along its normal meets the walls of every
    other face (walls within 1e-6 of parallel to the ray are skipped); its offset is
    the nearest meeting ahead of the face. livemod differs from TopMod, which took
    the meeting of smallest ``|t|`` (from 1e3): meetings at or behind the face
    (``t`` <= 1e-9 times the face's size; a wall through a shared edge meets it at 0)
    do not limit it, and a face nothing limits gets ``fallback`` (TopMod: 1e3).
    Adjacent or opposite cube faces: ``fallback``.

    Args:
        faces: face ids, as for :func:`multi_face_handle`.
        fallback: the offset of a face no wall limits.

    Returns:
        ``(len(faces),)`` float offsets, each > 0 or ``fallback``.

    Raises:
        DLFLError: ``fallback`` not a finite number, or ``faces`` as
            :func:`multi_face_handle` refuses them.
    """
    faces = id_list(faces, "faces")
    fallback = finite_number(fallback, "fallback")
    _check_handle_faces(mesh, faces, "face_max_offsets")
    rings = [face_points(mesh, f) for f in faces]
    normals = [polygon_normal(ring) for ring in rings]
    walls = [_side_walls(ring, n) for ring, n in zip(rings, normals, strict=True)]
    offsets = np.full(len(faces), fallback)
    for i, (ring, normal) in enumerate(zip(rings, normals, strict=True)):
        others = [w for j, w in enumerate(walls) if j != i]
        origins, wall_normals = (np.concatenate(parts) for parts in zip(*others, strict=True))
        t = _ray_hits(ring, normal, origins, wall_normals)
        if t.size:
            offsets[i] = float(t.min())
    return offsets


def _side_walls(ring: np.ndarray, normal: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(m, 3)`` origins and unit normals of the walls of a face with ``(k, 3)``
    points ``ring`` and unit ``normal``; edges too short for a direction have none."""
    ahead = np.roll(ring, -1, axis=0)
    with np.errstate(over="ignore", invalid="ignore"):  # inf rows get no direction
        direction = ahead - ring
    wall_normals = unit(np.cross(unit(direction), normal))
    keep = np.any(wall_normals != 0.0, axis=1)
    return (ring * 0.5 + ahead * 0.5)[keep], wall_normals[keep]


def _ray_hits(ring: np.ndarray, normal: np.ndarray, origins: np.ndarray,
              wall_normals: np.ndarray) -> np.ndarray:
    """The parameters ``t`` > 1e-9 times the ring's size at which rays from the
    ``(k, 3)`` points along ``normal`` meet the walls (finite ones only)."""
    along = wall_normals @ normal  # (m,)
    crossing = np.abs(along) > 1e-6  # others are (nearly) parallel to the ray
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):  # dropped below
        gap = np.einsum("pmk,mk->pm", origins[None, :, :] - ring[:, None, :], wall_normals)
        t = gap[:, crossing] / along[crossing]
    size = float(lengths(ring * 0.5 - centroid(ring) * 0.5).max()) * 2.0
    return t[np.isfinite(t) & (t > 1e-9 * size)]


# -- fitted hull ------------------------------------------------------------------------

def fitted_factor(fits: Callable[[float], bool], min_factor: float = 0.01,
                  iterations: int = 10) -> float:
    """TopMod's binary search for the fitted hub: the largest factor it finds
    for which ``fits(factor)`` holds.

    From 0.5 (and 0 before it), each step is half the change of the last one:
    up when the factor fits, down when not. When a step would fall below
    ``min_factor``, a fitting factor ends the search and a failing one moves
    down by ``min_factor``. At most ``iterations`` calls of ``fits``.

    Returns:
        The last factor tried, which fits.

    Raises:
        DLFLError: no end within ``iterations`` (TopMod printed a message and
            stopped).
    """
    factor, previous = 0.5, 0.0
    for _ in range(iterations):
        ok = fits(factor)
        step, previous = 0.5 * abs(factor - previous), factor
        if step < min_factor:
            if ok:
                return factor
            step = min_factor
        factor = factor + step if ok else factor - step
    raise GeometryError(f"no hub that keeps every point found in {iterations} steps (last "
                        f"factor {previous:g}); try another min_factor")


def multi_face_handle_fitted(mesh: Mesh, faces: list[int], min_factor: float = 0.01, *,
                             connect: bool = True, max_faces: object = None) -> list[int]:
    """Join several faces through the smallest hub that keeps all of their points
    (TopMod's ``multiConnectFaces(faces, min_factor, make_connections)``).

    Every point of face ``i`` moves by ``factor * (g - c_i)``, ``c_i`` the face's
    centroid and ``g`` the mean of the ``c_i``; :func:`fitted_factor` searches for
    the largest factor whose convex hull still has every moved point as a corner
    (or on a hull edge), in at most 10 steps. The hull is added as in
    :func:`multi_face_handle` and, with ``connect``, each face joined to the hull
    face facing it. livemod orients the hull as :func:`multi_face_handle` does;
    TopMod's test here looked the other way (it reversed the hull when the first
    face's normal pointed toward the centre), which paired each face with the hull
    face on the far side of the hub, or with none. Meant for faces that face each
    other or a common centre (faces of separate objects, of a hollow): the facing
    faces of two unit cubes 2 apart: 24/44/22, genus 0, a hub 0.03125 thick (factor
    0.984375); a cube's top and bottom: 16/32/16, genus 1; faces of a convex object
    that are not opposite rarely get a hull face facing them (cube faces 0, 2, 4
    are refused).

    Returns:
        The ids of the new edges (the hull's and the tubes').

    Raises:
        DLFLError: faces as :func:`multi_face_handle` refuses them, ``min_factor``
            not a positive number, ``connect`` not a flag, the faces' own points
            not all corners of their convex hull (TopMod stopped too), no fitting
            factor within 10 steps, or a face no hull face faces (TopMod left it
            unjoined). The mesh is unchanged.
        BudgetExceededError: the handle could pass the face budget.
    """
    faces = id_list(faces, "faces")
    min_factor = positive_number(min_factor, "min_factor")
    join = flag(connect, "connect")
    _check_handle_faces(mesh, faces, "multi_face_handle_fitted")
    _check_budget(mesh, faces, "multi_face_handle_fitted", _HUB_GROWTH, max_faces)
    rings = [face_points(mesh, f) for f in faces]
    _check_convex_position(np.concatenate(rings))
    moved = _toward_centre(rings)
    factor = fitted_factor(lambda f: _keeps_every_point(moved(f)), min_factor)
    points = moved(factor)
    normals = [polygon_normal(ring) for ring in rings]
    polygons = _hub_polygons(mesh, faces[0], normals[0], points)
    hint = "the fitted hub suits faces that face each other or a common centre"
    partner = _facing_polygons(points, polygons, faces, normals, hint) if join else None
    return _join_hub(mesh, faces, points, polygons, partner)


def _toward_centre(rings: list[np.ndarray]) -> Callable[[float], np.ndarray]:
    """``moved(factor)``: the ``(sum k_i, 3)`` points of the ``(k_i, 3)`` rings, each
    ring moved by ``factor`` times the way from its centroid to their mean."""
    centres = [centroid(ring) for ring in rings]
    middle = centroid(np.array(centres))
    # quarters: differences of huge centroids cannot overflow
    ways = [(middle * 0.25 - c * 0.25) * 4.0 for c in centres]

    def moved(factor: float) -> np.ndarray:
        with np.errstate(over="ignore", invalid="ignore"):  # refused by hull_polygons
            return np.concatenate([ring + factor * way for ring, way in zip(rings, ways,
                                                                              strict=True)])
    return moved


def _keeps_every_point(points: np.ndarray) -> bool:
    """Whether every one of the ``(n, 3)`` points is a corner of their convex hull
    (or on a hull edge); a hull that cannot be built keeps none."""
    try:
        polygons = hull_polygons(points)
    except DLFLError:
        return False
    return len({p for poly in polygons for p in poly}) == len(points)


def _check_convex_position(points: np.ndarray) -> None:
    """Refuse faces whose own ``(n, 3)`` points (shared vertices kept once) are not
    all on their convex hull's corners and edges.

    Raises:
        DLFLError: naming a point inside, or as :func:`.hull.hull_polygons`.
    """
    distinct = np.unique(points, axis=0)
    used = {p for poly in hull_polygons(distinct) for p in poly}
    inside = sorted(set(range(len(distinct))) - used)
    if inside:
        raise GeometryError(f"the faces' point {distinct[inside[0]].tolist()} lies inside the "
                            "convex hull of their points: no hub can keep it")


# -- closest edges ------------------------------------------------------------------------

def multi_face_handle_closest_edges(mesh: Mesh, faces: list[int], *,
                                    max_faces: object = None) -> list[int]:
    """Join several faces by quads between their closest edges (TopMod's
    "ClosestEdge" ``multiConnectFaces(faces)``).

    Candidates are the half-edges of the faces (self-loops and edges with both
    sides in one face left out). Half-edges ``p0 -> p1`` and ``q0 -> q1`` of
    different faces and edges span the quad ``p0 p1 q0 q1`` that joining them
    makes; with its corners pulled a quarter along their edges (so edges sharing a
    vertex still span a quad), ``n1 = unit((q1 - p0) x (p1 - p0))`` and
    ``n2 = unit((p1 - q0) x (q1 - q0))``. The pair qualifies when its planarity
    ``n1 . n2`` exceeds cos 5 degrees and, with three or more faces, its plane
    (normal ``unit(n1 + n2)``) is more than 5 degrees from parallel to the plane
    through the two faces' centroids and the mean centroid, a plane that must
    exist. With two faces that plane never exists, and planarity alone decides
    (TopMod then joined nothing). Pairs are joined with
    :func:`.connect.connect_edge_sides`, closest first (distance of the edge
    midpoints, ties in candidate order), skipping a pair with an edge already
    joined. Then each new edge whose two sides are one face or coplanar faces
    (``|n1 . n2 - 1| < 1e-5``) is deleted (TopMod's ``edgeCleanup`` of the new
    edges). Cube top and bottom: 8/16/8, genus 1; cube faces 0, 2, 4: the two
    opposite ones joined, 8/16/8; the facing faces of two cubes: a tube, 16/28/14.

    Returns:
        The ids of the new edges that remain.

    Raises:
        DLFLError: faces as :func:`multi_face_handle` refuses them, or no pair of
            edges qualifies (TopMod did nothing). The mesh is unchanged.
        BudgetExceededError: the quads could pass the face budget.
    """
    faces = id_list(faces, "faces")
    _check_handle_faces(mesh, faces, "multi_face_handle_closest_edges")
    _check_budget(mesh, faces, "multi_face_handle_closest_edges", (1, 4), max_faces)
    halves = _half_edges(mesh, faces)
    pairs = _edge_pairs(mesh, faces, halves)
    if not pairs:
        raise GeometryError(f"no two edges of faces {faces} make a nearly planar quad across "
                            "the handle; use multi_face_handle")
    first = mesh.next_ids()[1]
    joined: set[int] = set()
    for a, b in pairs:
        (edge1, start1), (edge2, start2) = halves[a][1:], halves[b][1:]
        if edge1 in joined or edge2 in joined:
            continue
        joined |= {edge1, edge2}
        connect_edge_sides(mesh, _side_from(mesh, edge1, start1), _side_from(mesh, edge2, start2))
    edge_cleanup(mesh, edges_since(mesh, first))  # TopMod's cleanup, of the new edges only
    return edges_since(mesh, first)


def _half_edges(mesh: Mesh, faces: list[int]) -> list[tuple[int, int, int]]:
    """``(index of the face in faces, edge, start vertex)`` of each candidate
    half-edge, face by face in ring order. A half-edge is kept by its start: its
    corner changes as edges are inserted, its edge and direction do not."""
    halves = []
    for i, f in enumerate(faces):
        for c in mesh.face_corners(f):
            edge, start = mesh.corner_edge(c), mesh.corner_vertex(c)
            a, b = mesh.edge_faces(edge)
            if start != mesh.corner_vertex(mesh.corner_next(c)) and a != b:
                halves.append((i, edge, start))
    return halves


def _side_from(mesh: Mesh, edge: int, start: int) -> int:
    """The side (corner) of ``edge`` at vertex ``start`` (not a self-loop)."""
    c1, c2 = mesh.edge_corners(edge)
    return c1 if mesh.corner_vertex(c1) == start else c2


def _edge_pairs(mesh: Mesh, faces: list[int],
                halves: list[tuple[int, int, int]]) -> list[tuple[int, int]]:
    """Qualifying pairs ``(a, b)``, ``a < b`` indices into ``halves``, closest first;
    the rule is :func:`multi_face_handle_closest_edges`'s."""
    a, b = _pair_indices(halves)
    starts, ends, centres = _pair_points(mesh, faces, halves)
    ps, pe = _pulled(starts[a], ends[a])
    qs, qe = _pulled(starts[b], ends[b])
    n1 = unit(np.cross(qe - ps, pe - ps))
    n2 = unit(np.cross(pe - qs, qe - qs))
    keep = np.einsum("ij,ij->i", n1, n2) > _COS5
    if len(faces) > 2:
        owner = np.array([h[0] for h in halves])
        keep &= _off_centre_plane(centres[owner[a]], centres[owner[b]], centroid(centres),
                                  unit(n1 + n2))
    mid = (starts + ends) * 0.5
    order = np.argsort(lengths(mid[a] - mid[b])[keep], kind="stable")
    return list(zip(a[keep][order].tolist(), b[keep][order].tolist(), strict=True))


def _pair_indices(halves: list[tuple[int, int, int]]) -> tuple[np.ndarray, np.ndarray]:
    """``(p,)`` and ``(p,)`` indices ``a < b`` of the half-edges of different faces
    and different edges, in candidate order."""
    owner = np.array([h[0] for h in halves])
    edge = np.array([h[1] for h in halves])
    a, b = np.triu_indices(len(halves), 1)
    keep = (owner[a] != owner[b]) & (edge[a] != edge[b])
    return a[keep], b[keep]


def _pair_points(mesh: Mesh, faces: list[int], halves: list[tuple[int, int, int]]
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(n, 3)`` starts and ends of the half-edges and ``(k, 3)`` face centroids,
    moved and scaled together into range (:func:`._vectors.shifted_in_range`): the
    tests compare directions and orders of distance only."""
    starts = [mesh.position(v) for _, _, v in halves]
    ends = [mesh.position(mesh.corner_vertex(mesh.corner_next(_side_from(mesh, e, v))))
            for _, e, v in halves]
    centres = [centroid(face_points(mesh, f)) for f in faces]
    pts = shifted_in_range(np.array(starts + ends + centres))
    n = len(halves)
    return pts[:n], pts[n:2 * n], pts[2 * n:]


def _pulled(starts: np.ndarray, ends: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The ``(p, 3)`` ends of half-edges pulled a quarter of the way toward each other."""
    return starts * 0.75 + ends * 0.25, starts * 0.25 + ends * 0.75


def _off_centre_plane(c1: np.ndarray, c2: np.ndarray, middle: np.ndarray,
                      normals: np.ndarray) -> np.ndarray:
    """``(p,)`` whether the plane of each pair (unit ``normals`` ``(p, 3)``) is more
    than 5 degrees from parallel to the plane through its faces' centroids ``c1``,
    ``c2`` ``(p, 3)`` and the mean centroid ``middle`` ``(3,)``; False where the
    three are in line (the sine of their angle below 1e-9)."""
    u, v = c1 - middle, c2 - middle
    cross = np.cross(u, v)
    exists = lengths(cross) > 1e-9 * lengths(u) * lengths(v)
    return exists & (np.abs(np.einsum("ij,ij->i", unit(cross), normals)) < _COS5)
