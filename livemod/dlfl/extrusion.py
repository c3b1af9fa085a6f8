"""Extrusions: grow a face into a tube, a cone or a polyhedral cap (TOPMOD.md §4).

One registry, :data:`KINDS`, names every kind. Most kinds end in a new *end
face*, which :func:`extrude` returns, so repeated extrusion on the returned face
builds the thesis's towers::

    face = extrude(mesh, face, "doo-sabin", distance=0.5, scale=0.9)

The kinds that end in a fan of triangles around an apex (stellate,
double-stellate, dome) have no end face; :func:`extrude_fan` runs them and
returns the triangles' ids. Every extrusion reads only the face it extrudes
and touches only the elements next to it, so a chain of extrusions costs the
same per step however large the mesh is.

The direction of every extrusion is TopMod's face normal (the normalised sum of
the corner normals, :mod:`livemod.dlfl.normals`). Rotations are
in degrees, right-handed about that normal, about the new polygon's centroid;
scales are about the new polygon's centroid, by ``|scale|``, skipped for 0 and 1
as TopMod does.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Any

import numpy as np

from ._checks import (
    MAX_ELEMENTS,
    finite_number,
    first_not_finite,
    flag,
    id_list,
    shown,
    whole_count,
)
from ._vectors import unit as unit_rows
from .bands import quad_band, triangle_band
from .budget import check_growth
from .errors import DLFLError, GeometryError, InvalidArgumentError, UnknownIdError, unknown_name
from .mesh import Mesh
from .normals import inset_offsets, small_polygon_normal

__all__ = [
    "DODECA_SHAPE", "ICOSA_SHAPE", "KINDS", "TOPMOD_KEYWORDS", "Kind", "Options", "Shape",
    "dodeca_shape_rings", "extrude", "extrude_faces", "extrude_fan", "icosa_shape_rings",
    "kind_names", "resolve_kind",
    "cubical_step", "doo_sabin_step", "dual_step", "planar_offset_step", "dodeca_step",
    "hex_tile_step", "icosa_step", "cuboctahedral_step", "stellate_fan",
    "double_stellate_fan", "dome_fan", "doo_sabin_weights", "small_polygon_normal",
]

TINY = 1e-12


@dataclass(frozen=True)
class Options:
    """The parameters of one extrusion step (see :func:`extrude` for their meaning)."""

    distance: float = 2.0
    rotation: float = 0.0
    scale: float = 1.0
    twist: float = 0.0
    dual_mesh: bool = False
    hexagonalize: bool = False
    thickness: float = 0.25
    fractional: bool = True
    shape: Shape | None = None


@dataclass(frozen=True)
class Shape:
    """The shape options of TopMod's GUI dodecahedral and icosahedral extrusions.

    With a shape, a dodeca or icosa step places its new rings by TopMod's GUI
    rules (:func:`dodeca_shape_rings`, :func:`icosa_shape_rings`) instead of
    moving along the normal: ``angle`` in degrees tilts the side faces, and
    ``l1``, ``l2``, ``l3`` scale the three rings' offsets by the base face's mean
    edge length. :data:`DODECA_SHAPE` and :data:`ICOSA_SHAPE` are the GUI's defaults.
    """

    angle: float
    l1: float
    l2: float
    l3: float


#: TopMod's GUI defaults of the dodecahedral extrusion (angle 40, l1-l3 .5, 1, 1)
DODECA_SHAPE = Shape(40.0, 0.5, 1.0, 1.0)
#: TopMod's GUI defaults of the icosahedral extrusion (angle 50, l1-l3 .5, .7, .8)
ICOSA_SHAPE = Shape(50.0, 0.5, 0.7, 0.8)


# -- local geometry ------------------------------------------------------------------

def _step_failure(message: str, reason: str) -> GeometryError:
    """The error of a step that cannot be built: the face it extrudes has no
    normal, or a point it makes is not finite. ``message`` names the face or
    point; the error's ``reason`` says the same without ids, for a rehearsal
    (:func:`_rehearse`), whose ids are those of a scratch mesh."""
    return GeometryError(message, reason=reason)


def _face_geometry(mesh: Mesh, face: int) -> tuple[np.ndarray, np.ndarray]:
    """``(k, 3)`` points of ``face`` from its head and its ``(3,)`` unit normal.

    Every step reads its face through here before it changes anything, so this
    is where a degenerate face is refused (checking it earlier would compute the
    geometry twice per extrusion, a sixth of a chained step's time).

    Raises:
        GeometryError: the face has no normal (collinear or coincident points).
    """
    points = mesh.face_points(face)
    normal = small_polygon_normal(points.tolist())
    if normal == (0.0, 0.0, 0.0):
        raise _step_failure(f"face {face} is degenerate (no normal); it cannot be extruded",
                            "a face it makes on the way is degenerate (no normal)")
    return points, np.array(normal)


def _finite(points: np.ndarray) -> np.ndarray:
    """``points`` (``(k, 3)`` or ``(3,)``), checked before they reach the mesh.

    Raises:
        GeometryError: a coordinate overflowed to infinity (or is NaN).
    """
    rows = np.atleast_2d(points)
    row = first_not_finite(rows)
    if row is not None:
        raise _step_failure(
            f"the extrusion would put a point at {rows[row].tolist()}: its numbers overflow; "
            "use a smaller distance or scale",
            "a point it makes on the way overflows (use a smaller distance or scale)")
    return points


@lru_cache(maxsize=64)
def _after(k: int) -> np.ndarray:
    """``(k,)`` index of the next point around a ``k``-gon (``np.roll(-1)`` as a gather)."""
    return np.r_[1:k, 0]


@lru_cache(maxsize=64)
def _before(k: int) -> np.ndarray:
    """``(k,)`` index of the previous point around a ``k``-gon."""
    return np.r_[k - 1, 0:k - 1]


def _transformed(points: np.ndarray, axis: np.ndarray, scale: float,
                 degrees: float) -> np.ndarray:
    """Scale by ``|scale|`` (skipped for 0 and 1, TopMod's rule) and rotate
    right-handed by ``degrees`` about ``axis`` (unit), both about the centroid.

    Uniform scaling and rotation about one point commute, so TopMod's order
    (scale, then rotate) is one matrix: Rodrigues' times the factor, built in
    plain floats since numpy's per-call cost dominates on a handful of points.
    """
    factor = abs(scale)
    if factor < TINY or abs(factor - 1.0) < TINY:
        factor = 1.0
    if abs(degrees) < TINY and factor == 1.0:
        return points
    theta = math.radians(degrees)
    x, y, z = axis.tolist()
    c, s = math.cos(theta), math.sin(theta)
    k = 1.0 - c
    matrix = np.array([
        [c + k * x * x, k * x * y - s * z, k * x * z + s * y],
        [k * y * x + s * z, c + k * y * y, k * y * z - s * x],
        [k * z * x - s * y, k * z * y + s * x, c + k * z * z],
    ]) * factor
    centre = points.sum(axis=0) / len(points)
    return centre + (points - centre) @ matrix.T


@lru_cache(maxsize=64)
def doo_sabin_weights(n: int) -> np.ndarray:
    """``(n, n)`` Doo-Sabin weights: ``1/4 + 5/(4n)`` on the diagonal, else
    ``(3 + 2 cos(2π(i - j)/n)) / (4n)``; quads get (9, 3, 1, 3)/16."""
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    weights = (3.0 + 2.0 * np.cos(2.0 * np.pi * (i - j) / n)) / (4.0 * n)
    np.fill_diagonal(weights, 0.25 + 5.0 / (4.0 * n))
    weights.flags.writeable = False
    return weights


# -- building blocks: one new polygon joined to the face --------------------------------

def _bridge(mesh: Mesh, face: int, points: np.ndarray, dual: bool = False) -> int:
    """Create ``points`` as a two-sided polygon and join its back to ``face``, head to
    head (quads, or with ``dual`` a band of triangles). Returns the front, the end
    face, which takes ``face``'s colour (the sides, cut from ``face`` merged with
    the back, take it too)."""
    front, back = mesh.create_face(_finite(points).tolist())
    color = mesh.face_color(face)
    if color is not None:  # a new face has none
        mesh.set_face_color(front, color)
    join = triangle_band if dual else quad_band
    join(mesh, mesh.face_corner(face), mesh.face_corner(back))
    return front


def cubical_step(mesh: Mesh, face: int, opts: Options) -> int:
    """TopMod's ``extrudeFace``: the face's points scaled, rotated, then moved
    ``distance`` along the normal; ``n`` side quads. Returns the end face."""
    points, normal = _face_geometry(mesh, face)
    with np.errstate(over="ignore", invalid="ignore"):  # _bridge refuses what overflows
        points = _transformed(points, normal, opts.scale, opts.rotation) + opts.distance * normal
    return _bridge(mesh, face, points)


def doo_sabin_step(mesh: Mesh, face: int, opts: Options) -> int:
    """TopMod's ``extrudeFaceDS``: ``q_i = d n + (1 - twist) p_i + twist p_{i+1}``,
    then the Doo-Sabin weights, then the scale (and livemod's rotation)."""
    points, normal = _face_geometry(mesh, face)
    with np.errstate(over="ignore", invalid="ignore"):  # _bridge refuses what overflows
        twisted = (1.0 - opts.twist) * points + opts.twist * points[_after(len(points))]
        # each row of the weights sums to 1, so moving before or after them is the same
        inner = doo_sabin_weights(len(points)) @ twisted + opts.distance * normal
        inner = _transformed(inner, normal, opts.scale, opts.rotation)
    return _bridge(mesh, face, inner)


def dual_step(mesh: Mesh, face: int, opts: Options) -> int:
    """TopMod's ``extrudeDualFace``: edge midpoints moved ``distance`` along the normal,
    scaled, rotated, joined by ``2n`` triangles; ``dual_mesh`` then deletes the
    face's old edges (cube: 12/24/14, with ``dual_mesh`` 12/20/10)."""
    points, normal = _face_geometry(mesh, face)
    old_edges = mesh.face_edges(face) if opts.dual_mesh else []
    with np.errstate(over="ignore", invalid="ignore"):  # _bridge refuses what overflows
        mids = (points + points[_after(len(points))]) * 0.5 + opts.distance * normal
        mids = _transformed(mids, normal, opts.scale, opts.rotation)
    end = _bridge(mesh, face, mids, dual=True)
    _delete_edges(mesh, old_edges)
    return end


def _delete_edges(mesh: Mesh, edges: list[int]) -> None:
    for edge in edges:
        if mesh.has_edge(edge):
            mesh.delete_edge(edge, cleanup=True)


def planar_offset_step(mesh: Mesh, face: int, opts: Options) -> int:
    """TopMod's ``extrudeFacePlanarOffset`` (an inset): corner ``p`` moves by
    ``thickness (pvec + nvec)`` in the face plane (``pvec``, ``nvec``: the edge
    vectors to its neighbours, unit unless ``fractional``), flipped at concave
    corners; straight corners move ``thickness`` along ``n x nvec``. Then rotation
    and ``distance`` along the normal."""
    points, normal = _face_geometry(mesh, face)
    with np.errstate(over="ignore", invalid="ignore"):  # _bridge refuses what overflows
        inset = points + _inset_offsets(points, opts)
        inset = _transformed(inset, normal, 1.0, opts.rotation) + opts.distance * normal
    return _bridge(mesh, face, inset)


def _inset_offsets(points: np.ndarray, opts: Options) -> np.ndarray:
    """``(k, 3)`` in-plane move of each corner of a planar-offset step."""
    k = len(points)
    return inset_offsets(points, np.arange(k), np.array([0, k]), opts.thickness,
                         opts.fractional)


# -- compound kinds ----------------------------------------------------------------

def dodeca_step(mesh: Mesh, face: int, opts: Options) -> int:
    """One dodecahedral step (TopMod's Python overload of ``extrudeFaceDodeca``):
    cubical, dual with ``dual_mesh``, cubical, each ``distance / 3`` with scale
    ``scale^(1/6)``, the dual one rotated; then the dual face's edges are deleted,
    leaving pentagons (cube: 20/32/14). (TopMod takes the square root of the
    scale per step, then the cube root per sub-step, so a step scales by
    ``sqrt(scale)``.)"""
    if opts.shape is not None:
        return _dodeca_shaped(mesh, face, opts.shape)
    third = replace(opts, distance=opts.distance / 3.0, scale=abs(opts.scale) ** (1.0 / 6.0))
    face = cubical_step(mesh, face, replace(third, rotation=0.0))
    return _dual_then_cubical(mesh, face, third)


def _dodeca_shaped(mesh: Mesh, face: int, shape: Shape) -> int:
    """TopMod's GUI ``extrudeFaceDodeca(angle, l1, l2, l3)``: the dodeca step's
    topology (cubical, dual with ``dual_mesh``, cubical, the dual face's edges
    deleted), then its three rings placed by :func:`dodeca_shape_rings`."""
    base, normal = _face_geometry(mesh, face)
    unit_step = Options(distance=1.0)
    first = cubical_step(mesh, face, unit_step)
    ring1 = mesh.face_vertices(first)
    end, ring2 = _dual_then_cubical_rings(mesh, first, unit_step)
    rings = dodeca_shape_rings(base, normal, shape)
    _place(mesh, [*ring1, *ring2, *mesh.face_vertices(end)], rings)
    return end


def _place(mesh: Mesh, vertices: list[int], points: np.ndarray) -> None:
    """Move ``vertices`` to ``points`` (``(k, 3)``), checked finite first."""
    mesh.set_positions(vertices, _finite(points))


def hex_tile_step(mesh: Mesh, face: int, opts: Options) -> int:
    """TopMod's ``extrudeHexTileFace``: dual with ``dual_mesh`` then cubical, each
    ``distance / 3`` with scale ``sqrt(scale)``, then the dual face's edges deleted.
    An ``n``-gon step adds ``2n`` vertices, ``3n`` edges and ``n`` faces and ends
    in an ``n``-gon (cube: 16/24/10, 2 segments 24/36/14)."""
    third = replace(opts, distance=opts.distance / 3.0, scale=math.sqrt(abs(opts.scale)))
    return _dual_then_cubical(mesh, face, third)


def _dual_then_cubical(mesh: Mesh, face: int, step: Options) -> int:
    """A dual step with ``dual_mesh``, a cubical step, then the dual face's edges
    deleted (the shared tail of dodeca and hex-tile); returns the end face."""
    return _dual_then_cubical_rings(mesh, face, step)[0]


def _dual_then_cubical_rings(mesh: Mesh, face: int, step: Options) -> tuple[int, list[int]]:
    """:func:`_dual_then_cubical`, also returning the dual face's vertices from its
    head (vertex ``i`` on the side from ``face``'s corner ``i``)."""
    face = dual_step(mesh, face, replace(step, dual_mesh=True))
    dual_vertices = mesh.face_vertices(face)
    dual_edges = mesh.face_edges(face)
    face = cubical_step(mesh, face, replace(step, rotation=0.0))
    _delete_edges(mesh, dual_edges)
    return face, dual_vertices


def icosa_step(mesh: Mesh, face: int, opts: Options) -> int:
    """TopMod's ``extrudeFaceIcosa`` topology: dual ``distance / 3`` (rotated, scaled),
    cubical ``2 distance / 3``, the dual face's edges deleted, then each side face
    next to the end face stellated at 0 (cube: 20/48/30).

    Differs from TopMod: the positions are those of these steps; TopMod then
    re-placed three rings by angle rules, which its Python binding fed with
    misbound parameters (angle = distance, ...)."""
    if opts.shape is not None:
        base, normal = _face_geometry(mesh, face)
        end, rings = _icosa_build(mesh, face, replace(opts, distance=3.0))
        _place(mesh, rings, icosa_shape_rings(base, normal, opts.shape))
        return end
    return _icosa_build(mesh, face, opts)[0]


def _icosa_build(mesh: Mesh, face: int, opts: Options) -> tuple[int, list[int]]:
    """The icosa step of :func:`icosa_step`; returns the end face and its new
    vertices as :func:`icosa_shape_rings` orders them: the dual step's points
    (``i`` on the side from corner ``i``), the cubical copies of those, then the
    apex of the side face at each corner of ``face``."""
    base = mesh.face_vertices(face)
    face = dual_step(mesh, face, replace(opts, distance=opts.distance / 3.0, dual_mesh=False))
    mids = mesh.face_vertices(face)
    dual_edges = mesh.face_edges(face)
    face = cubical_step(mesh, face, Options(distance=2.0 * opts.distance / 3.0))
    copies = mesh.face_vertices(face)
    _delete_edges(mesh, dual_edges)
    sides = []
    for edge in mesh.face_edges(face):
        f0, f1 = mesh.edge_faces(edge)
        sides.append(f1 if f0 == face else f0)
    apex_at = {}
    for side in sides:
        corner = (set(mesh.face_vertices(side)) & set(base)).pop()
        fan = stellate_fan(mesh, side, 0.0)
        apex_at[corner] = mesh.corner_vertex(_shared_corner(mesh, fan))
    return face, [*mids, *copies, *(apex_at[v] for v in base)]


def cuboctahedral_step(mesh: Mesh, face: int, opts: Options) -> int:
    """TopMod's ``extrudeFaceCubOcta`` topology: two dual extrusions of ``distance / 3``
    (rotated, scaled), then the first dual face's edges deleted (cube: 16/32/18).

    Differs from TopMod: the positions are those of the two dual steps; TopMod
    re-placed both rings by angle rules (the kind is not in its GUI or Python)."""
    third = replace(opts, distance=opts.distance / 3.0, dual_mesh=False)
    face = dual_step(mesh, face, third)
    first_edges = mesh.face_edges(face)
    face = dual_step(mesh, face, third)
    _delete_edges(mesh, first_edges)
    return face


# -- the GUI's dodecahedral and icosahedral shapes ------------------------------------

def _tilted(axis: np.ndarray, toward: np.ndarray, alpha: float) -> np.ndarray:
    """``(k, 3)`` ``normalize(cos(alpha) normalize(axis) + sin(alpha) toward)``: a
    side-face normal tilted from ``axis`` (``(k, 3)``) toward ``toward``
    (``(3,)`` or ``(k, 3)``, unit) by ``alpha`` radians, TopMod's construction."""
    return unit_rows(math.cos(alpha) * unit_rows(axis) + math.sin(alpha) * toward)


def _ring_frame(base: np.ndarray) -> tuple[np.ndarray, np.ndarray, float]:
    """``(after, before, mean edge length)`` of the ``(k, 3)`` base ring: the next
    and previous points of each and the mean length of its sides."""
    after, before = base[_after(len(base))], base[_before(len(base))]
    return after, before, float(np.linalg.norm(after - base, axis=1).mean())


def dodeca_shape_rings(base: np.ndarray, normal: np.ndarray, shape: Shape) -> np.ndarray:
    """``(3k, 3)`` TopMod's GUI placement of a dodecahedral step's three rings.

    ``base`` is the extruded face's ``(k, 3)`` points, ``normal`` its ``(3,)`` unit
    normal; with ``a = -angle``, ``L`` the mean base side and ``e_i`` the unit
    side from point ``i`` to ``i + 1``, ``fn_i`` tilts ``e_i x n`` toward ``n`` by
    ``a`` (the side face over ``e_i``) and ``fp_i`` tilts ``n x e_{i-1}`` back:

    * ring 1, point ``i`` (the first cubical copy): ``b_i + L l1 normalize(fp_i x fn_i)``;
    * ring 2 (the dual points): the midpoint of ring 1's points ``i, i + 1``
      plus ``L cos 54° l2 normalize(fn_i x e_i)``;
    * ring 3 (the second cubical copy): ring 2's point ``i`` plus
      ``l3^2 (|b_{i-1} - b_i| + |b_{i+1} - b_i|) / 2`` along the cross product of
      the normals of the planes (ring 2 ``i - 1``, ring 1 ``i``, ring 2 ``i``) and
      (ring 2 ``i``, ring 1 ``i + 1``, ring 2 ``i + 1``).
    """
    alpha = -math.radians(shape.angle)
    after, before, mean_side = _ring_frame(base)
    e_next = unit_rows(after - base)
    fn = _tilted(np.cross(e_next, normal), normal, alpha)
    fp = _tilted(np.cross(normal, unit_rows(before - base)), normal, alpha)
    ring1 = base + mean_side * shape.l1 * unit_rows(np.cross(fp, fn))
    k = len(base)
    ring2 = (ring1 + ring1[_after(k)]) * 0.5 + (
        mean_side * math.cos(math.radians(54.0)) * shape.l2) * unit_rows(np.cross(fn, e_next))
    reach = (np.linalg.norm(before - base, axis=1) + np.linalg.norm(after - base, axis=1)) * 0.5
    prev_plane = _plane_normal(ring2[_before(k)], ring1, ring2)
    next_plane = _plane_normal(ring2, ring1[_after(k)], ring2[_after(k)])
    ring3 = ring2 + (reach * shape.l3 * shape.l3)[:, None] * unit_rows(
        np.cross(prev_plane, next_plane))
    return np.concatenate([ring1, ring2, ring3])


def _plane_normal(first: np.ndarray, middle: np.ndarray, last: np.ndarray) -> np.ndarray:
    """``(k, 3)`` unit normal of each plane through ``first, middle, last`` (each
    ``(k, 3)``): ``normalize(normalize(last - middle) x normalize(first - middle))``."""
    return unit_rows(np.cross(unit_rows(last - middle), unit_rows(first - middle)))


def icosa_shape_rings(base: np.ndarray, normal: np.ndarray, shape: Shape) -> np.ndarray:
    """``(3k, 3)`` TopMod's GUI placement of an icosahedral step's three rings.

    With ``base``, ``normal``, ``a``, ``L``, ``e_i`` and ``fn_i`` as in
    :func:`dodeca_shape_rings`:

    * the dual points ``m_i``: the midpoint of side ``i`` plus
      ``L l1 sqrt(3)/2 normalize(fn_i x e_i)``;
    * the cubical copies ``c_i`` (the end face): ``m_i + L l3 d_i``;
    * the apex ``p_i`` of the side face at base point ``i``: ``b_i + L l2 d'_i``;

    where ``d'_i`` and ``d_i`` are TopMod's cross products of two side-face
    normals each tilted by ``a`` about the edges from ``b_i`` to ``m_i``,
    ``m_{i-1}`` (for the apex) and from ``m_i`` to ``b_i``, ``b_{i+1}`` against
    the triangles toward the apexes (for the copies). The result lists ``m``,
    then ``c``, then ``p``.
    """
    alpha = -math.radians(shape.angle)
    after, before, mean_side = _ring_frame(base)
    k = len(base)
    e_next = unit_rows(after - base)
    fn = _tilted(np.cross(e_next, normal), normal, alpha)
    fp = _tilted(np.cross(normal, unit_rows(before - base)), normal, alpha)
    mids = (base + (after - base) * 0.5
            + (mean_side * shape.l1 * math.sqrt(3.0) * 0.5) * unit_rows(np.cross(fn, e_next)))
    apexes = base + mean_side * shape.l2 * _cross_tilted(
        mids[_before(k)] - base, -fp, mids - base, -fn, alpha)
    to_prev_apex, to_next_apex = unit_rows(apexes - mids), unit_rows(apexes[_after(k)] - mids)
    to_base, to_next_base = unit_rows(base - mids), unit_rows(after - mids)
    copies = mids + mean_side * shape.l3 * _cross_tilted(
        to_base, -unit_rows(np.cross(to_prev_apex, to_base)),
        to_next_base, -unit_rows(np.cross(to_next_base, to_next_apex)), alpha)
    return np.concatenate([mids, copies, apexes])


def _cross_tilted(prev_edge: np.ndarray, prev_face: np.ndarray, next_edge: np.ndarray,
                  next_face: np.ndarray, alpha: float) -> np.ndarray:
    """``(k, 3)`` TopMod's direction between two tilted faces:
    ``normalize(tilt(prev_face x prev_edge, prev_face) x tilt(next_edge x next_face,
    next_face))``, each tilt by ``alpha`` (all ``(k, 3)``)."""
    before = _tilted(np.cross(prev_face, prev_edge), prev_face, alpha)
    after = _tilted(np.cross(next_edge, next_face), next_face, alpha)
    return unit_rows(np.cross(before, after))


def stellate_fan(mesh: Mesh, face: int, distance: float) -> list[int]:
    """TopMod's ``stellateFace``: a point at centroid + ``distance`` n joined to every
    corner (a cone of triangles). Returns the triangles' ids around the apex, the
    one over the face's first side (from its head corner) first."""
    points, normal = _face_geometry(mesh, face)
    first_side = mesh.face_edges(face)[0]
    with np.errstate(over="ignore", invalid="ignore"):  # refused by _finite
        apex_point = points.mean(axis=0) + distance * normal
    apex = mesh.create_vertex(_finite(apex_point))
    tip = mesh.vertex_corner(apex)
    mesh.insert_edge(tip, mesh.face_corner(face))
    while mesh.face_size(mesh.corner_face(tip)) > 3:
        mesh.insert_edge(tip, mesh.corner_next(mesh.corner_next(tip)))
    return _starting_over(mesh, mesh.vertex_faces(apex), first_side)


def _starting_over(mesh: Mesh, triangles: list[int], side: int) -> list[int]:
    """``triangles`` rotated to start with the one ``side`` (an edge) borders."""
    first = next(i for i, t in enumerate(triangles) if side in mesh.face_edges(t))
    return triangles[first:] + triangles[:first]


def double_stellate_fan(mesh: Mesh, face: int, distance: float) -> list[int]:
    """TopMod's ``doubleStellateFace``: stellate at 0, stellate each new triangle at 0,
    then move the first apex ``distance`` along the face's normal (cube: 13/28/17).
    Returns the ``3n`` triangles that replace the face, the one over its first
    side first."""
    _, normal = _face_geometry(mesh, face)
    first_side = mesh.face_edges(face)[0]
    first = stellate_fan(mesh, face, 0.0)
    apex = mesh.corner_vertex(_shared_corner(mesh, first))
    triangles = []
    for triangle in first:
        triangles.extend(stellate_fan(mesh, triangle, 0.0))
    with np.errstate(over="ignore", invalid="ignore"):  # refused by _finite
        moved = mesh.position(apex) + distance * normal
    mesh.set_position(apex, _finite(moved))
    return _starting_over(mesh, triangles, first_side)


def _shared_corner(mesh: Mesh, faces: list[int]) -> int:
    """A corner of ``faces[0]`` at the vertex all of ``faces`` share (a fan's apex)."""
    common = set(mesh.face_vertices(faces[0]))
    for f in faces[1:]:
        common &= set(mesh.face_vertices(f))
    vertex = common.pop()
    return mesh.corner_at(faces[0], vertex)


DOME_DISTANCES = (0.3, 0.18, 0.1, 0.05, 0.025)
DOME_SCALES = (1.7, 1.6, 1.4, 1.2, 1.1)


def dome_fan(mesh: Mesh, face: int, opts: Options) -> list[int]:
    """TopMod's ``extrudeFaceDome``: five Doo-Sabin steps with distances
    (.3, .18, .1, .05, .025) x ``distance``, twist ``rotation / 5`` and scales
    (1.7, 1.6, 1.4, 1.2, 1.1) x ``scale``, then a stellation at .01 x ``distance``
    (cube: 29/56/29). Returns the apex triangles, the one over the last
    Doo-Sabin face's first side first."""
    for d, s in zip(DOME_DISTANCES, DOME_SCALES, strict=True):
        step = Options(distance=d * opts.distance, twist=opts.rotation / 5.0, scale=s * opts.scale)
        face = doo_sabin_step(mesh, face, step)
    return stellate_fan(mesh, face, 0.01 * opts.distance)


# -- the registry -------------------------------------------------------------------

#: an extrusion's options in a script, positionally, where the thesis lists none
TOWER_OPTIONS = ("distance", "segments", "rotation", "scale")


@dataclass(frozen=True)
class Kind:
    """One extrusion kind: how it is built and how a script names its options.

    Building: ``step`` (one segment, returns the end face) or ``fan`` (ends in a
    fan of triangles around an apex, returns them, the one over the face's first
    side first); ``topmod``, TopMod's function; ``growth``, at most how many
    faces and corners one step adds per corner of the face (for the face
    budget); ``simple_face``, whether it needs a face that visits each of its
    vertices once (kinds whose later sub-steps work on faces the first one
    made, which come out degenerate from a face with a dangling edge or a loop
    inside it); ``single_build``, whether one step is a single build (one
    polygon or apex, every point checked before the mesh changes), which needs
    no rehearsal on a scratch copy to fail cleanly.

    Script options (``extrude(type, faceid, *options, **keywords)``):
    ``options``, the positional options in the thesis appendix's order;
    ``keyword_options``, options only a keyword sets (those TopMod's module
    or GUI had and the thesis leaves out); ``library_names``, the argument of
    :func:`extrude` a script option sets where the names differ; ``topmod_names``,
    TopMod's argument names this kind reads differently from
    :data:`TOPMOD_KEYWORDS`; ``aliases``, other exact names of the kind;
    ``shape``, the GUI's shape defaults where the kind has them (the keywords
    ``angle``, ``l1``, ``l2``, ``l3``). :data:`KINDS` lists TopMod's seven Python
    types first, in the order its module matched a type by prefix.
    """

    step: Callable[[Mesh, int, Options], int] | None
    fan: Callable[[Mesh, int, Options], list[int]] | None
    topmod: str
    growth: tuple[int, int]
    simple_face: bool = False
    single_build: bool = False
    options: tuple[str, ...] = TOWER_OPTIONS
    keyword_options: tuple[str, ...] = ()
    library_names: dict[str, str] = field(default_factory=dict)
    topmod_names: dict[str, str] = field(default_factory=dict)
    aliases: tuple[str, ...] = ()
    shape: Shape | None = None


#: TopMod's Python argument names (``extrude(type, fid, dist, num, rot, sf, flag)``),
#: accepted as keywords by every kind that has the option they name
TOPMOD_KEYWORDS = {"dist": "distance", "num": "segments", "numsegs": "segments",
                   "rot": "rotation", "sf": "scale"}


def _stellate(m: Mesh, f: int, opts: Options) -> list[int]:
    return stellate_fan(m, f, opts.distance)


def _double_stellate(m: Mesh, f: int, opts: Options) -> list[int]:
    return double_stellate_fan(m, f, opts.distance)


KINDS: dict[str, Kind] = {
    "doo-sabin": Kind(doo_sabin_step, None, "extrudeFaceDS", (1, 4), single_build=True,
                      library_names={"rotation": "twist"}, aliases=("ds",)),
    "dodeca": Kind(dodeca_step, None, "extrudeFaceDodeca", (2, 10),
                   options=("distance", "segments", "twist", "scale", "hexagonalize"),
                   library_names={"twist": "rotation"},
                   topmod_names={"rot": "twist", "flag": "hexagonalize"}, shape=DODECA_SHAPE),
    "icosa": Kind(icosa_step, None, "extrudeFaceIcosa", (6, 18), simple_face=True,
                  shape=ICOSA_SHAPE),
    "octa": Kind(dual_step, None, "extrudeDualFace", (2, 6), single_build=True,
                 options=("distance", "rotation", "scale"), keyword_options=("segments", "mesh"),
                 library_names={"mesh": "dual_mesh"}, topmod_names={"flag": "mesh"},
                 aliases=("dual",)),
    "stellate": Kind(None, _stellate, "stellateFace", (1, 2), single_build=True,
                     options=("distance",)),
    "double-stellate": Kind(None, _double_stellate, "doubleStellateFace", (3, 8),
                            simple_face=True, options=("distance",)),
    "cubical": Kind(cubical_step, None, "extrudeFace", (1, 4), single_build=True),
    "dome": Kind(None, dome_fan, "extrudeFaceDome", (6, 22),
                 options=("distance", "rotation", "scale")),
    "cuboctahedral": Kind(cuboctahedral_step, None, "extrudeFaceCubOcta", (3, 10),
                          aliases=("cubocta",)),
    "hex-tile": Kind(hex_tile_step, None, "extrudeHexTileFace", (1, 6), aliases=("hextile",)),
    "planar-offset": Kind(planar_offset_step, None, "extrudeFacePlanarOffset", (1, 4),
                          single_build=True,
                          options=("distance", "rotation", "thickness", "fractional"),
                          aliases=("inset",)),
}
ALIASES = {alias: name for name, kind in KINDS.items() for alias in kind.aliases}
# each kind's name in a face-budget refusal, made once (every extrusion passes one)
_OPERATIONS = {name: f"{name} extrusion" for name in KINDS}


def kind_names() -> list[str]:
    """The extrusion kinds, in registry order."""
    return list(KINDS)


def resolve_kind(name: str) -> str:
    """The registry name for ``name``: exact names and aliases first, then a unique
    prefix (``"doo"``, ``"double"``, ``"cub"`` is ambiguous).

    Raises:
        DLFLError: unknown or ambiguous, listing the valid kinds.
    """
    if not isinstance(name, str):
        raise InvalidArgumentError(
            f"extrusion kind must be a string, got {name!r}; kinds: {', '.join(KINDS)}")
    if name in KINDS:  # a registry name as it is: every extrusion of a chain
        return name
    key = name.strip().lower().replace("_", "-")
    if key in KINDS:
        return key
    if key in ALIASES:
        return ALIASES[key]
    matches = [k for k in KINDS if key and k.startswith(key)]
    if len(matches) == 1:
        return matches[0]
    if matches:
        raise InvalidArgumentError(f"ambiguous extrusion kind {name!r}: it starts "
                                   f"{', '.join(map(repr, matches))}; valid kinds: "
                                   f"{', '.join(KINDS)}")
    raise InvalidArgumentError(unknown_name("unknown extrusion kind", name, KINDS,
                                            "valid kinds"))


def _check_face(mesh: Mesh, face: int) -> int:
    """Refuse a ``face`` no extrusion can start from (every kind, via :func:`_prepare`);
    return its number of corners.

    Raises:
        DLFLError: ``face`` is not an int id, does not exist, is a hole (a
            boundary loop of an open mesh: a cap on it would be detached, with
            hole walls), or has fewer than 3 corners.
    """
    # a plain int first: the union isinstance costs more than the rest of the test
    if type(face) is not int and (isinstance(face, bool)
                                  or not isinstance(face, int | np.integer)):
        raise InvalidArgumentError(f"face must be a face id (int), got {face!r}")
    if not mesh.has_face(int(face)):
        raise UnknownIdError(f"face {shown(int(face))} does not exist (deleted or never made)")
    if mesh.is_hole(int(face)):
        raise InvalidArgumentError(
            f"face {face} is a hole (a boundary loop of an open mesh, not part of "
            "the surface); it cannot be extruded")
    size = mesh.face_size(int(face))
    if size < 3:
        raise InvalidArgumentError(f"face {face} has {size} corner(s); "
                                   "only faces of 3 or more corners can be extruded")
    return size


def _checked_numbers(opts: Options) -> Options:
    """``opts`` with its numbers as floats.

    Raises:
        DLFLError: an option is not a finite number.
    """
    # a new Options, not dataclasses.replace: this runs on every extrusion
    return Options(finite_number(opts.distance, "distance"),
                   finite_number(opts.rotation, "rotation"), finite_number(opts.scale, "scale"),
                   finite_number(opts.twist, "twist"), opts.dual_mesh, opts.hexagonalize,
                   finite_number(opts.thickness, "thickness"), opts.fractional,
                   None if opts.shape is None else _checked_shape(opts.shape))


def _checked_shape(shape: Shape) -> Shape:
    """``shape`` with its numbers as floats.

    Raises:
        InvalidArgumentError: not a :class:`Shape`, or a number that is not finite.
    """
    if not isinstance(shape, Shape):
        raise InvalidArgumentError(f"shape must be an extrusion.Shape, got {shape!r}")
    return Shape(*(finite_number(getattr(shape, name), name)
                   for name in ("angle", "l1", "l2", "l3")))


def _prepare(mesh: Mesh, faces: Sequence[int], kind: str, segments: int, opts: Options,
             max_faces: object) -> tuple[str, Kind, Options]:
    """The kind's name and spec and the checked options for extruding ``faces``, or
    a DLFLError (see :func:`extrude`); the face budget is checked for all of them.

    This runs before every extrusion of a chain, so each check is cheap when it
    passes: every face's ring is walked once, and ``segments`` is read once.
    """
    name = resolve_kind(kind)
    spec = KINDS[name]
    sides = 0
    for face in faces:
        sides += _check_face(mesh, face)
        if spec.simple_face:
            _check_simple(mesh, int(face), name)
    count = whole_count(segments, "segments", each=0)
    if spec.fan is not None and count != 1:
        raise InvalidArgumentError(f"a {name} extrusion ends in a fan of triangles: it has "
                                   f"no segments, got segments={count}")
    grown, corners = spec.growth
    check_growth(mesh, _OPERATIONS[name], faces=count * grown * sides,
                 corners=count * corners * sides, max_faces=max_faces)
    # every segment makes at least a new polygon of the face's size (a budget
    # raised past what a mesh can hold); whole_count says so
    if count * sides > MAX_ELEMENTS:
        whole_count(segments, "segments", each=sides)
    if opts.shape is not None and spec.shape is None:
        raise InvalidArgumentError(f"a {name} extrusion has no shape options (angle, l1, l2, "
                                   "l3); only dodeca and icosa have them")
    return name, spec, _checked_numbers(opts)


def _runner(spec: Kind, opts: Options, count: int) -> Callable[[Mesh, int], list[int]]:
    """What extrudes one face: returns ``[end face]``, or a fan's triangles."""
    fan, step = spec.fan, spec.step
    if fan is not None:
        return lambda m, f: fan(m, f, opts)
    assert step is not None

    def run(m: Mesh, f: int) -> list[int]:
        for i in range(count):
            previous = m.face_edges(f) if (opts.hexagonalize and i > 0) else []
            f = step(m, f, opts)
            _delete_edges(m, previous)
        return [f]

    return run


def _check_simple(mesh: Mesh, face: int, kind: str) -> None:
    """Raises DLFLError when ``face`` visits a vertex more than once."""
    vertices = mesh.face_vertices(face)
    if len(set(vertices)) < len(vertices):
        twice = next(v for v in vertices if vertices.count(v) > 1)
        raise InvalidArgumentError(
            f"face {face} visits vertex {twice} more than once (an edge dangles "
            f"into it, or a loop): {kind} extrusion needs a face whose corners "
            "are distinct vertices")


def extrude(
    mesh: Mesh, face: int, kind: str = "cubical", distance: float = 2.0, segments: int = 1,
    rotation: float = 0.0, scale: float = 1.0, *, twist: float = 0.0,
    dual_mesh: bool = False, hexagonalize: bool = False, thickness: float = 0.25,
    fractional: bool = True, shape: Shape | None = None, max_faces: object = None,
) -> int:
    """Extrude ``face`` and return the new end face (TopMod's extrusions, TOPMOD.md §4).

    ``segments`` repeats the step on the returned face, each moving the full
    ``distance`` again (3 cubical segments of 2 from cube face 0 end at y = 3, 5, 7).
    Counts on cube face 0: cubical 12/20/10, doo-sabin 12/20/10, octa 12/24/14
    (``dual_mesh`` 12/20/10), dodeca 20/32/14 (2 segments with ``hexagonalize``
    32/48/18), icosa 20/48/30, cuboctahedral 16/32/18, hex-tile 16/24/10
    (2 segments 24/36/14), planar-offset 12/20/10. The kinds that end in a fan of
    triangles (stellate 9/16/9, double-stellate 13/28/17, dome 29/56/29) return
    the triangle over the face's first side, from its head corner (over the last
    Doo-Sabin face's for dome); :func:`extrude_fan` returns all of them.

    Args:
        kind: a name of :data:`KINDS` (or alias, or unique prefix).
        distance: along the face normal (TopMod default 2).
        rotation: degrees about the normal (dodeca: the dual step's twist angle).
        scale: factor about the new polygon's centroid (dodeca: over the whole step).
        twist: doo-sabin only, TopMod's fraction ``t`` of ``(1 - t) p_i + t p_{i+1}``.
        dual_mesh: octa only, delete the face's old edges (TopMod's ``mesh``).
        hexagonalize: delete the previous end face's edges between segments;
            meant for dodeca, where adjacent pentagons merge into octagons.
            This is TopMod's GUI rule, whose counts TOPMOD.md lists; its Python
            binding ran one dodeca step, then hex-tile steps (cube, 2 segments:
            28/44/18, the counts of a ``"hex-tile"`` extrusion of a ``"dodeca"``
            one's end face; ``kind="hex-tile"`` alone, 2 segments: 24/36/14).
        thickness, fractional: planar-offset only, the inset (fractional: of the
            edge vectors; else absolute along unit edge vectors).
        shape: dodeca and icosa only, TopMod's GUI shape (:class:`Shape`): the
            rings are placed by its angle and lengths, and ``distance``,
            ``rotation`` and ``scale`` are not used.
        max_faces: the face budget (None: the session's, see
            :mod:`livemod.dlfl.budget`).

    Raises:
        DLFLError: unknown kind (lists the valid ones), a face that is gone, is
            a hole, has < 3 corners or no normal, for icosa and double-stellate
            a face that visits a vertex twice, ``segments`` not an integer >= 1
            or more than a mesh can hold (a fan kind takes none), a shape for a
            kind without one, a non-finite number, or numbers that overflow or
            make a degenerate face in a later step or segment (checked on a
            scratch copy first). The mesh is unchanged.
        BudgetExceededError: the segments would pass the face budget.
    """
    name, spec, opts = _prepare(mesh, (face,), kind, segments, Options(
        distance, rotation, scale, twist, flag(dual_mesh, "dual_mesh"),
        flag(hexagonalize, "hexagonalize"), thickness, flag(fractional, "fractional"), shape),
        max_faces)
    # one face: the path of chained extrusions, kept lean (extrude_faces does the rest)
    count, start = int(segments), int(face)
    step = spec.step
    if count == 1 and spec.single_build and step is not None:
        return step(mesh, start, opts)  # what run() does, without the rehearsal
    run = _runner(spec, opts, count)
    if count > 1 or not spec.single_build:
        _rehearse(mesh, start, name, run)
    return run(mesh, start)[0]


def extrude_faces(
    mesh: Mesh, faces: list[int], kind: str = "cubical", distance: float = 2.0,
    segments: int = 1, rotation: float = 0.0, scale: float = 1.0, *, twist: float = 0.0,
    dual_mesh: bool = False, hexagonalize: bool = False, thickness: float = 0.25,
    fractional: bool = True, shape: Shape | None = None, fans: bool = False,
    max_faces: object = None,
) -> list[Any]:
    """Extrude several faces, one after another in the order given, as TopMod
    extrudes a selection (CTRL+X); return their end faces (see :func:`extrude`),
    or with ``fans`` (kinds that end in a fan) each face's list of triangles as
    :func:`extrude_fan` gives it.

    Each face gets its own extrusion, as if extruded alone: two faces that share
    an edge each get a side wall over it. The one kind whose rule reaches past
    its face is octa with ``dual_mesh``, which deletes the face's old edges:
    those are deleted once every face is extruded, so an edge between two
    extruded faces merges their two side triangles into a quad (TopMod deleted
    them face by face, merging a later selected face with the earlier one's
    triangle, or freeing it).

    Raises:
        DLFLError: as :func:`extrude`, for any of the faces, or a face given
            twice; every face is checked (on a scratch copy where its steps
            need it) before the mesh changes, so it is unchanged.
        BudgetExceededError: the extrusions together would pass the face budget.
    """
    results = _extrude_all(mesh, _distinct_faces(faces), kind, segments, Options(
        distance, rotation, scale, twist, flag(dual_mesh, "dual_mesh"),
        flag(hexagonalize, "hexagonalize"), thickness, flag(fractional, "fractional"), shape),
        max_faces, fans=flag(fans, "fans"))
    return results if fans else [made[0] for made in results]


def _extrude_all(mesh: Mesh, faces: list[int], kind: str, segments: int, options: Options,
                 max_faces: object, *, fans: bool = False) -> list[list[int]]:
    """:func:`extrude_faces` once its flags are read (and :func:`extrude`): for each
    face ``[end face]``, or a fan's triangles.

    Raises:
        InvalidArgumentError: ``fans`` for a kind that ends in a face; see
            :func:`extrude`.
    """
    name, spec, opts = _prepare(mesh, faces, kind, segments, options, max_faces)
    if fans and spec.fan is None:
        raise InvalidArgumentError(f"a {name} extrusion ends in a face, not a fan of triangles")
    ids = [int(f) for f in faces]
    count = int(segments)
    deferred: list[int] = []
    if opts.dual_mesh and len(ids) > 1 and spec.step is dual_step:
        deferred = [e for f in ids for e in mesh.face_edges(f)]
        run = _octa_keeping_first_edges(opts, count)
    else:
        run = _runner(spec, opts, count)
    if len(ids) > 1 or count > 1 or not spec.single_build:
        for face in ids:
            _rehearse(mesh, face, name, run)
    made = [run(mesh, face) for face in ids]
    _delete_edges(mesh, deferred)
    return made


def _distinct_faces(faces: object) -> list[int]:
    """``faces`` as a list of ints, each once.

    Raises:
        InvalidArgumentError: not a list of integer ids, or an id given twice.
    """
    ids = id_list(faces, "faces")
    twice = next((f for i, f in enumerate(ids) if f in ids[:i]), None)
    if twice is not None:
        raise InvalidArgumentError(f"face {twice} is given twice; each face is extruded once")
    return ids


def _octa_keeping_first_edges(opts: Options, count: int) -> Callable[[Mesh, int], list[int]]:
    """Octa with ``dual_mesh`` whose first segment keeps the face's old edges
    (:func:`extrude_faces` deletes them after every face)."""
    first, later = replace(opts, dual_mesh=False), opts

    def run(m: Mesh, f: int) -> list[int]:
        for i in range(count):
            f = dual_step(m, f, later if i else first)
        return [f]

    return run


def extrude_fan(
    mesh: Mesh, face: int, kind: str = "stellate", distance: float = 2.0,
    rotation: float = 0.0, scale: float = 1.0, *, max_faces: object = None,
) -> list[int]:
    """Run an extrusion that ends in a fan of triangles; return all the triangles' ids,
    the one over the face's first side first (:func:`extrude` returns that one).

    Kinds: stellate (apex at centroid + ``distance`` n; cube face: 9/16/9),
    double-stellate (13/28/17, returns all ``3n`` triangles), dome (``distance`` is
    TopMod's length, ``rotation`` its twist x 5; 29/56/29). TopMod returned -1.

    Raises:
        DLFLError: unknown kind, a kind with an end face (use :func:`extrude`), a
            face that is gone, is a hole, has < 3 corners or no normal, for
            double-stellate a face that visits a vertex twice, or numbers that
            overflow or make a degenerate face in a later step (dome,
            double-stellate; checked on a scratch copy first). The mesh is
            unchanged.
    """
    name, spec, opts = _prepare(mesh, (face,), kind, 1,
                                Options(distance=distance, rotation=rotation, scale=scale),
                                max_faces)
    if spec.fan is None:
        raise InvalidArgumentError(f"extrusion kind {name!r} ends in a face; use extrude()")
    run = _runner(spec, opts, 1)
    if not spec.single_build:
        _rehearse(mesh, int(face), name, run)
    return run(mesh, int(face))


def _rehearse(mesh: Mesh, face: int, kind: str, run: Callable[[Mesh, int], object]) -> None:
    """Run an extrusion of several steps on a scratch copy of ``face`` first.

    Later steps extrude faces the earlier ones made, whose shape is known only
    once those are built: a step can find its face degenerate or its points
    overflowing after others have changed the mesh. Each step reads nothing but
    the points of the face it extrudes and builds on faces the extrusion made,
    so the face's points as a two-sided polygon meet the same geometry. This
    costs as much again as the extrusion, independent of the mesh's size (a
    copy of the mesh to restore would not be); single builds skip it.

    Raises:
        DLFLError: the face itself is degenerate, or a step on the way would fail
            (the message says why); ``mesh`` is untouched.
    """
    points, _ = _face_geometry(mesh, face)  # a degenerate face is named as itself
    scratch = Mesh()
    front, _ = scratch.create_face(points.tolist())
    try:
        run(scratch, front)
    except DLFLError as exc:  # the same kind of failure, said of the face given
        # a step's reason names no scratch ids
        why = exc.reason if isinstance(exc, GeometryError) and exc.reason else exc
        raise type(exc)(f"{kind} extrusion of face {face} cannot be built: {why}; "
                        "the mesh is unchanged") from None
