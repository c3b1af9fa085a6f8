"""Connections and handles: TopMod's counts (TOPMOD.md §5), ring positions against
the rules, and bad input that leaves the mesh unchanged."""

from __future__ import annotations

import re

import numpy as np
import pytest

from livemod.dlfl import Mesh, face_size_histogram, genus, validate
from livemod.dlfl.analysis import face_points
from livemod.dlfl.connect import (
    bezier_handle,
    closest_corners,
    connect_corners,
    connect_edges,
    connect_faces,
    connect_faces_closest,
    dual_connect_faces,
    hermite_handle,
    hermite_point,
    multi_face_handle,
    rotation_between,
)
from livemod.dlfl.errors import (
    BudgetExceededError,
    GeometryError,
    InvalidArgumentError,
    UnknownIdError,
)
from livemod.dlfl.extrusion import extrude
from livemod.dlfl.shapes import cube
from livemod.dlfl.subdivision import subdivide
from tests.meshes import assert_refused, assert_refused_quietly, assert_scales, euler_ok, snapshot
from tests.meshes import cube as unit_cube
from tests.meshes import torus as unit_torus

TOP, RIGHT, BOTTOM = 0, 1, 5  # cube faces: 0 = (v0..v3) at y = 1, 1 at x = 1, 5 at y = -1


def checked(mesh: Mesh) -> tuple[int, int, int]:
    validate(mesh)
    assert euler_ok(mesh)
    return mesh.counts()


def head(m: Mesh, face: int) -> int:
    return m.face_corner(face)


def above(m: Mesh) -> tuple[int, int]:
    """Corner of the top face at v0 = (1, 1, 1) and of the bottom at v4 = (1, -1, 1)."""
    return m.corner_at(TOP, 0), m.corner_at(BOTTOM, 4)


def new_positions(m: Mesh, first_vertex: int = 8) -> np.ndarray:
    return np.array([m.position(v) for v in m.vertex_ids() if v >= first_vertex])


def as_set(points: np.ndarray) -> list[tuple[float, ...]]:
    return sorted(map(tuple, np.round(np.asarray(points).reshape(-1, 3), 9).tolist()))


# -- connect_faces -----------------------------------------------------------------

def test_top_to_bottom_gives_a_genus_one_ring_of_quads():
    m = cube()
    edges = connect_faces(m, *above(m))
    assert checked(m) == (8, 16, 8)
    assert genus(m) == 1 and face_size_histogram(m) == {4: 8}
    assert len(edges) == 4
    assert all(np.isclose(np.linalg.norm(np.subtract(*map(m.position, m.edge_vertices(e)))), 2.0)
               for e in edges)


def test_three_segments_interpolate_linearly():
    m = cube()
    c1, c2 = above(m)
    top, bottom = face_points(m, TOP), face_points(m, BOTTOM)
    connect_faces(m, c1, c2, 3)
    assert checked(m) == (16, 32, 16)
    assert genus(m) == 1 and face_size_histogram(m) == {4: 16}
    expected = [top + (bottom[[3, 2, 1, 0]] - top) * t for t in (1 / 3, 2 / 3)]
    assert as_set(new_positions(m)) == as_set(expected)


def test_pinch_scales_the_rings_about_their_centroids():
    m = cube()
    top = face_points(m, TOP)
    connect_faces(m, *above(m), 2, pinch=0.5)
    mid = top - [0.0, 1.0, 0.0]
    c = mid.mean(axis=0)
    assert as_set(new_positions(m)) == as_set(c + 0.5 * (mid - c))
    m = cube()
    connect_faces(m, *above(m), 4, pinch=0.5, pinch_center=0.5, bubble=2.0)
    checked(m)
    t2 = 0.5 ** 0.5  # ring 1: t = 1/4, t2 = (t / center) ** (1 / bubble)
    scale = (1 - t2) ** 2 + 2 * (1 - t2) * t2 * 0.5 + t2 * t2 * 0.5
    ring1 = [p for p in new_positions(m) if np.isclose(p[1], 0.5)]
    assert np.allclose(np.abs(np.array(ring1)[:, [0, 2]]), scale, atol=1e-12)


def test_max_connections_leaves_loose_rings():
    m = cube()
    connect_faces(m, *above(m), 3, max_connections=1)
    assert checked(m) == (16, 24, 12)  # 2 two-sided rings, only the first joined
    assert genus(m) == 0


def test_quad_to_pentagon_ends_in_a_triangle():
    m = cube()
    m.subdivide_edge(m.face_edges(BOTTOM)[0])
    assert m.face_size(BOTTOM) == 5
    connect_faces(m, *above(m))
    assert checked(m) == (9, 18, 9)
    assert face_size_histogram(m) == {3: 1, 4: 7, 5: 1}
    assert genus(m) == 1


def test_closest_corners_pair_the_vertically_aligned_vertices():
    m = cube()
    c1, c2 = closest_corners(m, TOP, BOTTOM)
    assert np.linalg.norm(m.position(m.corner_vertex(c1)) - m.position(m.corner_vertex(c2))) == 2.0
    connect_faces_closest(m, TOP, BOTTOM, 3)
    assert checked(m) == (16, 32, 16)


# -- dual connections, corners, edges ---------------------------------------------

def test_dual_connect_faces_makes_a_triangle_band():
    m = cube()
    edges = dual_connect_faces(m, *above(m))
    assert checked(m) == (8, 20, 12)
    assert face_size_histogram(m) == {3: 8, 4: 4} and genus(m) == 1
    assert len(edges) == 8


def test_connect_corners_dual_with_segments():
    m = cube()
    connect_corners(m, *above(m), 3, dual=True)
    assert checked(m) == (16, 44, 28)
    assert face_size_histogram(m) == {3: 24, 4: 4} and genus(m) == 1
    m = cube()
    connect_corners(m, *above(m), 2)
    assert checked(m) == (12, 24, 12)


def test_connect_edges_joins_two_half_edges_with_a_quad():
    m = cube()
    e1, e2 = m.face_edges(TOP)[0], m.face_edges(BOTTOM)[0]
    made = connect_edges(m, e1, TOP, e2, BOTTOM)
    assert len(made) == 2
    assert checked(m) == (8, 14, 6) and genus(m) == 1
    quad = [f for f in m.face_ids() if set(m.face_edges(f)) >= {e1, e2} or
            (set(made) <= set(m.face_edges(f)) and m.face_size(f) == 4)]
    assert quad


def test_connect_edge_sides_picks_the_side_of_an_edge_whose_sides_share_a_face():
    from livemod.dlfl.connect import connect_edge_sides

    # a dangling edge inside the top face: both of its sides are in that face, so
    # (edge, face) names neither; its corners do
    m = cube()
    v = m.create_vertex((0.0, 0.5, 0.5))
    inner = m.insert_edge(m.face_corner(TOP), m.vertex_corner(v))
    assert m.edge_faces(inner) == (TOP, TOP)
    out_side = next(c for c in m.edge_corners(inner) if m.corner_vertex(c) == v)
    other = m.face_corners(BOTTOM)[0]
    u = m.corner_vertex(m.corner_next(out_side))
    b0, b1 = m.corner_vertex(other), m.corner_vertex(m.corner_next(other))
    made = connect_edge_sides(m, out_side, other)
    # 9/13/6 with the dangling edge; one merging and one splitting edge: 9/15/6
    assert len(made) == 2 and checked(m) == (9, 15, 6) and genus(m) == 1
    # (side, next(other)) and (next(side), other): from v, not from the top's corner
    assert [set(m.edge_vertices(e)) for e in made] == [{v, b1}, {u, b0}]
    assert_refused(cube(), lambda m: connect_edge_sides(m, 0, 0),
                   "connect_edge_sides needs two different corners, got corner 0 twice",
                   error=InvalidArgumentError)
    assert_refused(cube(), lambda m: connect_edge_sides(m, 0, 999), "side2: corner 999 does not exist",
                   error=UnknownIdError)


def test_connect_edges_check_skips_adjacent_corners():
    m = cube()
    c = m.face_corner(TOP)
    e1, e2 = m.corner_edge(c), m.corner_edge(m.corner_next(m.corner_next(c)))
    assert connect_edges(m, e1, TOP, e2, TOP, check=True) == []  # (a, d) and (b, c) adjacent
    assert len(connect_edges(m, e1, TOP, e2, TOP, check=False)) == 2
    assert checked(m) == (8, 14, 8)
    assert face_size_histogram(m) == {2: 2, 4: 6}
    m = cube()
    c = m.face_corner(TOP)
    e1, e2 = m.corner_edge(c), m.corner_edge(m.corner_next(c))
    made = connect_edges(m, e1, TOP, e2, TOP, check=True)  # (a, c): a diagonal; (b, b): none
    assert len(made) == 1 and checked(m) == (8, 13, 7)


# -- handles -----------------------------------------------------------------------

def test_hermite_handle_ten_segments_matches_topmod():
    m = cube()
    hermite_handle(m, m.corner_at(TOP, 0), m.corner_at(RIGHT, 0), 10)
    assert checked(m) == (44, 88, 44)
    assert genus(m) == 1 and face_size_histogram(m) == {4: 44}


def test_hermite_ring_centroids_follow_the_curve():
    m = cube()
    c1, c2 = m.corner_at(TOP, 0), m.corner_at(RIGHT, 0)
    hermite_handle(m, c1, c2, 5, 3.0, 2.0)
    cen1, cen2 = np.array([0.0, 1.0, 0.0]), np.array([1.0, 0.0, 0.0])
    n1, n2 = np.array([0.0, 1.0, 0.0]), np.array([-1.0, 0.0, 0.0])
    rings = new_positions(m).reshape(4, 4, 3)
    m1, m2 = 3.0 * n1, 2.0 * n2
    for i, ring in enumerate(rings, start=1):
        t = i / 5
        # the Hermite basis written out, independent of the library's helper
        point = ((2 * t**3 - 3 * t**2 + 1) * cen1 + (t**3 - 2 * t**2 + t) * m1
                 + (-2 * t**3 + 3 * t**2) * cen2 + (t**3 - t**2) * m2)
        tangent = ((6 * t**2 - 6 * t) * cen1 + (3 * t**2 - 4 * t + 1) * m1
                   + (-6 * t**2 + 6 * t) * cen2 + (3 * t**2 - 2 * t) * m2)
        assert np.allclose(hermite_point(cen1, m1, cen2, m2, t)[0], point, atol=1e-12)
        assert np.allclose(ring.mean(axis=0), point, atol=1e-9)
        sides = np.linalg.norm(ring - np.roll(ring, 1, axis=0), axis=1)
        assert np.allclose(sides, 2.0, atol=1e-9)  # congruent ends: every ring a 2x2 square
        normal = np.cross(ring[1] - ring[0], ring[2] - ring[1])
        assert np.allclose(normal / np.linalg.norm(normal), tangent / np.linalg.norm(tangent),
                           atol=1e-9)  # each ring faces along the curve


def test_hermite_twists_keep_counts():
    m = cube()
    hermite_handle(m, m.corner_at(TOP, 0), m.corner_at(RIGHT, 0), 6, twists=1)
    assert checked(m) == (28, 56, 28) and genus(m) == 1


def test_bezier_handle_vertices_follow_their_own_curves():
    m = cube()
    c1, c2 = m.corner_at(TOP, 0), m.corner_at(RIGHT, 0)
    start = face_points(m, TOP)
    end_face = m.face_vertices(RIGHT)
    k = end_face.index(0)
    end = np.array([m.position(end_face[(k - j) % 4]) for j in range(4)])
    bezier_handle(m, c1, c2, 10, 4.0, 4.0)
    assert checked(m) == (44, 88, 44) and genus(m) == 1
    n1, n2 = np.array([0.0, 1.0, 0.0]), np.array([-1.0, 0.0, 0.0])
    expected = [hermite_point(start, 4.0 * n1, end, 4.0 * n2, i / 10)[0] for i in range(1, 10)]
    assert np.allclose(new_positions(m), np.concatenate(expected), atol=1e-9)


def test_rotation_between_is_the_identity_for_opposite_vectors_as_in_topmod():
    a = np.array([0.0, 1.0, 0.0])
    assert np.array_equal(rotation_between(a, -a), np.eye(3))
    b = np.array([0.6, 0.0, 0.8])
    assert np.allclose(rotation_between(a, b) @ a, b)


# -- bad input ----------------------------------------------------------------------

def pentagon_cube() -> Mesh:
    m = cube()
    m.subdivide_edge(m.face_edges(BOTTOM)[0])
    return m


BAD = [
    (lambda m: connect_faces(m, head(m, TOP), m.corner_next(head(m, TOP))),
     InvalidArgumentError, "two different faces"),
    (lambda m: connect_faces(m, 999, head(m, BOTTOM)), UnknownIdError, "corner 999 does not exist"),
    (lambda m: connect_faces(m, *above(m), 0), InvalidArgumentError, "segments"),
    (lambda m: connect_faces(m, *above(m), 2, pinch_center=1.0), InvalidArgumentError,
     "pinch_center"),
    (lambda m: dual_connect_faces(m, head(m, TOP), head(m, TOP)), InvalidArgumentError,
     "two different faces"),
    (lambda m: connect_faces_closest(m, TOP, 77), UnknownIdError, "face 77 does not exist"),
    (lambda m: connect_edges(m, m.face_edges(TOP)[0], BOTTOM, 0, TOP), InvalidArgumentError,
     "is not on face"),
    (lambda m: connect_edges(m, 500, TOP, 0, TOP), UnknownIdError, "edge 500 does not exist"),
    (lambda m: hermite_handle(m, head(m, TOP), head(m, BOTTOM), 4), GeometryError,
     "against the handle's axis"),
    (lambda m: bezier_handle(m, head(m, TOP), head(m, BOTTOM), 0), InvalidArgumentError,
     "segments"),
]


@pytest.mark.parametrize("case", range(len(BAD)))
def test_bad_input_raises_and_leaves_the_mesh_unchanged(case):
    m = cube()
    call, error, message = BAD[case]
    before = snapshot(m)
    with pytest.raises(error, match=message):
        call(m)
    assert snapshot(m) == before


@pytest.mark.parametrize("op", [
    lambda m: connect_faces(m, *above(m), 3),
    lambda m: connect_corners(m, *above(m), 2, dual=True),
    lambda m: hermite_handle(m, m.corner_at(TOP, 0), m.corner_at(BOTTOM, 4), 5),
    lambda m: bezier_handle(m, m.corner_at(TOP, 0), m.corner_at(BOTTOM, 4), 5),
])
def test_faces_of_different_sizes_are_refused_with_segments(op):
    m = pentagon_cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="equal size; face 0 has 4 corners and face 5 has 5"):
        op(m)
    assert snapshot(m) == before


# -- multi-face handle ----------------------------------------------------------------

def test_multi_face_handle_on_three_cube_faces_matches_topmod():
    from livemod.dlfl.connect import multi_face_handle

    m = cube()
    multi_face_handle(m, [0, 2, 4])
    assert checked(m) == (20, 42, 20)
    assert genus(m) == 2 and face_size_histogram(m) == {4: 18, 6: 2}


def test_multi_face_handle_on_all_six_faces():
    from livemod.dlfl.connect import multi_face_handle

    m = cube()
    multi_face_handle(m, [0, 1, 2, 3, 4, 5], scale=1.0, extrude=1.0)
    assert checked(m) == (32, 84, 44) and genus(m) == 5


def test_add_polyhedron_builds_a_hull_with_a_point_on_an_edge():
    from livemod.dlfl.connect import add_polyhedron
    from livemod.dlfl.hull import hull_polygons

    corners = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)
    extra = np.array([[0, 0, 0], [1, 0, 0], [0.5, 1, 1]], float)  # inside, face centre, edge
    pts = np.concatenate([corners, extra])
    polygons = hull_polygons(pts)
    # the edge point is a corner of both faces beside its edge; the others are left out
    assert sorted(len(p) for p in polygons) == [4] * 4 + [5] * 2
    m = Mesh()
    faces = add_polyhedron(m, pts, polygons)
    assert checked(m) == (9, 13, 6) and len(set(faces)) == 6
    for face in faces:
        centre = face_points(m, face).mean(axis=0)
        normal = np.cross(*(face_points(m, face)[1:3] - face_points(m, face)[0]))
        assert centre @ normal > 0  # outward


@pytest.mark.parametrize(("faces", "message", "error"), [
    ([0], "two or more different faces", InvalidArgumentError),
    ([0, 0], "two or more different faces", InvalidArgumentError),
    ([0, 99], "face 99 does not exist", UnknownIdError),
])
def test_multi_face_handle_bad_input(faces, message, error):
    from livemod.dlfl.connect import multi_face_handle

    assert_refused(cube(), lambda m: multi_face_handle(m, faces), message, error=error)


def test_multi_face_handle_refuses_coplanar_points():
    from livemod.dlfl.connect import multi_face_handle

    m = Mesh()
    front, back = m.create_face([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)])
    before = snapshot(m)
    with pytest.raises(GeometryError, match="not all in one plane"):
        multi_face_handle(m, [front, back], extrude=0.0)
    assert snapshot(m) == before


def test_resolve_polygon_angles_ascend_from_the_first():
    from livemod.dlfl.connect import resolve_polygon

    x, y = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    square = np.array([[1, 0, 0], [0, 1, 0], [-1, 0, 0], [0, -1, 0]], float) + 5.0
    angles, dist = resolve_polygon(square, x, y)
    assert np.allclose(angles, [0, np.pi / 2, np.pi, 3 * np.pi / 2]) and np.allclose(dist, 1)
    angles, _ = resolve_polygon(square[::-1], x, y)  # clockwise: steps of 3π/2
    assert np.allclose(np.diff(angles), 3 * np.pi / 2) and 0 <= angles[0] < 2 * np.pi


def test_one_segment_hermite_handle_is_connect_faces_even_for_unequal_faces():
    m = pentagon_cube()
    hermite_handle(m, *above(m), 1)
    assert checked(m) == (9, 18, 9) and genus(m) == 1


@pytest.mark.parametrize(("call", "message"), [
    (lambda m: multi_face_handle(m, [TOP, None]), "faces must hold ids"),
    (lambda m: multi_face_handle(m, [TOP, 1.5]), "faces must hold ids"),
    (lambda m: multi_face_handle(m, [TOP, BOTTOM], "abc"), "scale must be a number"),
    (lambda m: multi_face_handle(m, [TOP, BOTTOM], 1.0, [1, 2]), "extrude must be a number"),
    (lambda m: connect_faces(m, m.face_corner(TOP), m.face_corner(BOTTOM), 3, bubble=None),
     "bubble must be a number"),
    (lambda m: connect_faces(m, m.face_corner(TOP), m.face_corner(BOTTOM), 3, pinch=[1, 2]),
     "pinch must be a number"),
])
def test_arguments_of_the_wrong_type_are_refused(call, message):
    assert_refused(cube(), call, message, error=InvalidArgumentError)


def test_a_hub_whose_hull_does_not_close_is_refused_before_building():
    m = unit_cube()
    v = m.create_vertex((0.5, 0.5, 0.0))  # a dangling edge inside face 0
    m.insert_edge(m.face_corners(0)[0], m.vertex_corner(v))
    extrude(m, 3, "cubical", 0.999999999)
    subdivide(m, "pentagon-preserve", scale=-0.9999)
    before = snapshot(m)
    # pushed 720 out, these faces' points are nearly coplanar at the hull's scale
    with pytest.raises(GeometryError, match="convex hull does not close up"):
        multi_face_handle(m, [37, 40, 34], 1.0, 720.0)
    assert snapshot(m) == before


def test_segment_counts_a_mesh_cannot_hold_are_refused_at_once():
    # past the face budget first; past what a mesh can hold with the budget raised
    assert_refused(cube(), lambda m: connect_faces(m, *above(m), 10**30),
                   "connect_faces would produce more than 10\\^18 faces",
                   error=BudgetExceededError)
    assert_refused(cube(), lambda m: connect_faces(m, *above(m), 10**30, max_faces=10**40),
                   f"segments={10**30} would make at least {2 * 10**30:,} corners",
                   error=InvalidArgumentError)
    assert_refused(cube(), lambda m: connect_faces(m, *above(m), True),
                   "segments must be an integer >= 1, got True", error=InvalidArgumentError)


def test_a_hub_that_overflows_is_refused_before_lapack_sees_it(capfd):
    from livemod.dlfl.connect import multi_face_handle

    assert_refused(cube(), lambda m: multi_face_handle(m, [TOP, BOTTOM, 2], 1e308, 1.0),
                   "a convex hull needs finite points whose differences are finite",
                   error=GeometryError)
    assert "DLASCL" not in capfd.readouterr().err  # LAPACK's own complaint about NaN


# -- huge meshes and overflowing parameters (tests.meshes.cube: face 1 is the top,
# face 3 the +x side, faces 0, 2 and 4 the bottom, -y and +y)

def huge_cube(scale: float = 1e300) -> Mesh:
    m = unit_cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * scale)
    return m


@pytest.mark.parametrize("op", [
    lambda m, s: connect_faces_closest(m, 0, 1, 2),
    lambda m, s: hermite_handle(m, m.face_corner(1), m.face_corner(3), 4, 2 * s, 2 * s,
                                pinch=0.5),
    lambda m, s: multi_face_handle(m, [0, 2, 4], 0.8, 0.5 * s),
    lambda m, s: multi_face_handle(m, [0, 2, 4], 1.0, 0.5 * s),
], ids=["closest", "hermite", "multi-scaled", "multi"])
@pytest.mark.parametrize("scale", [1e154, 1e300])
def test_handles_of_a_huge_mesh_are_the_scaled_unit_ones(op, scale):
    # squared distances, norms and hull cross products of raw coordinates overflowed:
    # warnings, then a refusal ("no hull face facing it") or NaN rings
    assert_scales(unit_cube, op, scale)


def test_a_hermite_handle_between_torus_faces_a_huge_mesh_apart():
    def op(m: Mesh, s: float) -> None:
        hermite_handle(m, m.face_corner(2), m.face_corner(9), 4, 2 * s, 2 * s)

    assert_scales(unit_torus, op, 1e200)


@pytest.mark.parametrize(("call", "message"), [
    (lambda m: connect_faces(m, m.corner_at(0, 0), m.corner_at(1, 4), 3, pinch=1e10),
     r"the handle would put a point at \[-inf.*overflow"),
    (lambda m: hermite_handle(m, m.face_corner(1), m.face_corner(3), 4, 2.0, 2.0, pinch=1e10),
     r"the handle would put a point at \[nan.*overflow"),
], ids=["connect_faces", "hermite_handle"])
def test_a_pinch_that_overflows_is_refused_quietly_by_name(call, message):
    # the mesh refused the ring itself ("expected a position ... of three finite
    # numbers"), after numpy's warnings
    assert_refused_quietly(huge_cube(), call, message)


@pytest.mark.parametrize(("scale", "extrude", "message"), [
    (1e307, 1.75e308, "a convex hull needs finite points"),
    (1.0, 1e300, "not all in one plane"),
])
def test_a_hub_that_overflows_is_refused_quietly(scale, extrude, message):
    # the pushed points' coincidence test and the hull's products overflowed
    assert_refused_quietly(huge_cube(scale),
                           lambda m: multi_face_handle(m, [0, 2, 4], 1.0, extrude), message)


# -- face colours --------------------------------------------------------------------

RED, BLUE = (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)


def _new_face_colours(m: Mesh, old: set[int]) -> list[tuple[float, float, float] | None]:
    return [m.face_color(f) for f in m.face_ids().tolist() if f not in old]


@pytest.mark.parametrize("segments", [1, 3])
def test_a_tube_takes_the_colour_of_the_face_it_starts_from(segments):
    m = cube()
    m.set_face_color(TOP, RED)
    m.set_face_color(BOTTOM, BLUE)
    old = set(m.face_ids().tolist())
    connect_faces(m, *above(m), segments)
    checked(m)
    tube = [m.face_color(f) for f in m.face_ids().tolist()
            if f not in old or f in (TOP, BOTTOM)]
    assert tube == [RED] * 4 * segments


def test_a_tube_from_a_face_without_colour_takes_the_other_faces():
    m = cube()
    m.set_face_color(BOTTOM, BLUE)
    old = set(m.face_ids().tolist()) - {TOP, BOTTOM}
    connect_faces(m, *above(m))
    assert _new_face_colours(m, old) == [BLUE] * 4


def test_a_hermite_handle_is_coloured_along_its_whole_length():
    m = cube()
    m.set_face_color(TOP, RED)
    old = set(m.face_ids().tolist()) - {TOP}
    hermite_handle(m, m.corner_at(TOP, 0), m.corner_at(RIGHT, 0), 6)
    checked(m)
    assert _new_face_colours(m, old - {RIGHT}) == [RED] * 24


# -- connect_faces_closest: face ids must be ints (numpy ones too)


@pytest.mark.parametrize(("face1", "face2", "message"), [
    (0.0, 5, "face1 must be a face id (int), got 0.0"),
    (0, 5.0, "face2 must be a face id (int), got 5.0"),
    (0, 0.0, "face2 must be a face id (int), got 0.0"),  # was "two different faces"
    (True, 5, "face1 must be a face id (int), got True"),
    ("0", 5, "face1 must be a face id (int), got '0'"),
])
def test_connect_faces_closest_says_face_ids_are_ints(face1, face2, message):
    assert_refused(cube(), lambda m: connect_faces_closest(m, face1, face2), re.escape(message),
                   error=InvalidArgumentError)
    with pytest.raises(InvalidArgumentError, match=re.escape(message)):
        closest_corners(cube(), face1, face2)


def test_connect_faces_closest_takes_numpy_ints():
    m = cube()
    assert connect_faces_closest(m, np.int64(0), np.int32(5)) == [12, 13, 14, 15]
    validate(m)
    assert (m.num_vertices, m.num_edges, m.num_faces) == (8, 16, 8)


def test_connect_faces_closest_on_a_missing_face_still_says_so():
    message = re.escape("face 99 does not exist (deleted or never made)")
    assert_refused(cube(), lambda m: connect_faces_closest(m, 0, 99), message, error=UnknownIdError)


# -- hermite_handle: twists must be whole turns; options checked; tiny meshes


def _first_and_second_face_corners(m: Mesh) -> tuple[int, int]:
    """A corner of the cube's first face and one of the opposite face."""
    f0, f1 = m.face_ids()[:2].tolist()
    return m.face_corners(f0)[0], m.face_corners(f1)[0]


@pytest.mark.parametrize("twists", [1.5, float("nan"), float("inf"), "2", True, 10**400])
def test_hermite_twists_that_are_not_a_whole_number_of_turns_are_refused(twists):
    # int(twists) truncated 1.5 to 1 unseen and raised ValueError/OverflowError on the rest
    m = cube()
    c1, c2 = _first_and_second_face_corners(m)
    assert_refused(m, lambda m: hermite_handle(m, c1, c2, 4, twists=twists), "twists",
                   error=InvalidArgumentError)


@pytest.mark.parametrize("twists", [2.0, np.int64(-1), -3])
def test_hermite_whole_twists_of_any_type_and_sign_work(twists):
    m = cube()
    c1, c2 = _first_and_second_face_corners(m)
    hermite_handle(m, c1, c2, 4, twists=twists)
    validate(m)
    assert m.counts() == (20, 40, 20) and genus(m) == 1


@pytest.mark.parametrize(("option", "message"), [
    ({"twists": "x"}, "twists"), ({"pinch": float("nan")}, "pinch"),
    ({"bubble": 0.0}, "bubble")])
def test_a_one_segment_hermite_handle_still_checks_its_options(option, message):
    # one segment is a plain connect_faces, which silently ignored bad options
    m = cube()
    c1, c2 = _first_and_second_face_corners(m)
    assert_refused(m, lambda m: hermite_handle(m, c1, c2, 1, **option), message,
                   error=InvalidArgumentError)


def test_the_hermite_handle_of_a_tiny_mesh_is_the_scaled_unit_one():
    # the centroids' distance was compared with an absolute 1e-12: "different centroids"
    def op(m: Mesh, s: float) -> None:
        c1, c2 = _first_and_second_face_corners(m)
        hermite_handle(m, c1, c2, 4, 25.0 * s, 25.0 * s)

    assert_scales(cube, op, scale=1e-150)
