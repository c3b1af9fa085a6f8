"""The multi-face handle family (livemod.dlfl.multihandle): maximum offsets, the
fitted hub, the closest-edge joins; counts on cubes worked out by hand, the same
counts at every scale, bad input that leaves the mesh unchanged."""

from __future__ import annotations

import importlib
import warnings

import numpy as np
import pytest

from livemod.dlfl import Mesh, face_size_histogram, from_polygons, genus, validate
from livemod.dlfl.analysis import num_components
from livemod.dlfl.errors import GeometryError, InvalidArgumentError, UnknownIdError
from livemod.dlfl.multihandle import (
    face_max_offsets,
    fitted_factor,
    multi_face_handle,
    multi_face_handle_closest_edges,
    multi_face_handle_fitted,
)
from livemod.dlfl.shapes import cube as cube_obj  # TopMod's cube.obj: edge length 2
from livemod.dlfl.shapes import octahedron
from tests.meshes import (
    CUBE_FACES,
    CUBE_POSITIONS,
    assert_refused,
    assert_scales,
    colour_counts,
    cube,
    euler_ok,
    rainbow_cube,
    two_cubes,
)

# the module, not a same-named function a star import might bring
multihandle = importlib.import_module("livemod.dlfl.multihandle")

# tests.meshes.cube: the unit cube [0, 1]^3; face 0 bottom (-z), 1 top (+z), 2 -y,
# 3 +x, 4 +y, 5 -x. A second cube's faces are 6..11 in the same order.
TOP, PLUS_X, MINUS_X = 1, 3, 5


def checked(mesh: Mesh) -> tuple[int, int, int]:
    validate(mesh)
    assert euler_ok(mesh)
    return mesh.counts()


def cubes_apart(shift: tuple[float, float, float]) -> Mesh:
    """The unit cube and a copy moved by ``shift``: 16/24/12."""
    pos = np.concatenate([CUBE_POSITIONS, CUBE_POSITIONS + np.asarray(shift)])
    return from_polygons(pos, CUBE_FACES + [[v + 8 for v in f] for f in CUBE_FACES])


def corner_cubes() -> Mesh:
    """A second cube up and to the side, [2, 3] x [0, 1] x [2, 3]: the first cube's
    top (face 1) and the second's -x side (face 11) meet at the point of a corner."""
    return cubes_apart((2.0, 0.0, 2.0))


def new_points(mesh: Mesh, first_vertex: int) -> list[tuple[float, ...]]:
    return sorted({tuple(mesh.position(v).tolist()) for v in mesh.vertex_ids()
                   if v >= first_vertex})


def edge_ends(mesh: Mesh, edges: list[int]) -> list[tuple[tuple[float, ...], ...]]:
    """Each edge's two end positions, sorted."""
    return [tuple(sorted(tuple(mesh.position(v).tolist()) for v in mesh.edge_vertices(e)))
            for e in edges]


def test_connect_keeps_the_family_importable():
    from livemod.dlfl import connect, multihandle

    for name in multihandle.__all__:
        assert getattr(connect, name) is getattr(multihandle, name)
    with pytest.raises(AttributeError, match="has no attribute 'multi_face_handel'"):
        connect.multi_face_handel  # noqa: B018 (a typo is still an AttributeError)


# -- maximum offsets -----------------------------------------------------------------------

def test_max_offsets_are_where_the_faces_side_walls_meet():
    # the top's rays (+z) meet the far cube's -x walls z = 2 and z = 3 at t = 1, 2;
    # that side's rays (-x from x = 2) meet the top's walls x = 1 and x = 0 at 1, 2
    np.testing.assert_array_equal(face_max_offsets(corner_cubes(), [TOP, 6 + MINUS_X]), [1.0, 1.0])


def test_a_wall_behind_the_face_does_not_limit_it():
    # the walls z = 0.8 and 1.8: TopMod took the nearer, t = -0.2, which pushes the
    # top face into its cube; livemod takes the nearest ahead, 0.8
    m = cubes_apart((2.0, 0.0, 0.8))
    np.testing.assert_allclose(face_max_offsets(m, [TOP, 6 + MINUS_X]), [0.8, 1.0])


@pytest.mark.parametrize("faces", [[0, 2, 4], [0, 1]], ids=["adjacent", "opposite"])
def test_a_face_no_wall_limits_gets_the_fallback(faces):
    # adjacent faces: the wall through a shared edge meets the face at t = 0 (TopMod's
    # offset 0); opposite faces: every wall is parallel to the rays (TopMod's 1e3)
    np.testing.assert_array_equal(face_max_offsets(cube(), faces), [0.5] * len(faces))
    np.testing.assert_array_equal(face_max_offsets(cube(), faces, 0.25), [0.25] * len(faces))


def test_max_offsets_push_the_faces_until_they_meet():
    m = corner_cubes()
    multi_face_handle(m, [TOP, 6 + MINUS_X], max_offsets=True)
    # hub: a triangular prism 6/9/5 in the corner (the faces' shared points kept once),
    # two quad tubes of +4 edges and +2 faces each; one component: genus 0
    assert checked(m) == (22, 41, 21) and genus(m) == 0 and num_components(m) == 1
    assert face_size_histogram(m) == {3: 2, 4: 19}
    assert new_points(m, 16) == [(0.0, 0.0, 2.0), (0.0, 1.0, 2.0), (1.0, 0.0, 2.0),
                                 (1.0, 0.0, 3.0), (1.0, 1.0, 2.0), (1.0, 1.0, 3.0)]


def test_without_max_offsets_the_faces_are_pushed_by_extrude():
    m = corner_cubes()
    multi_face_handle(m, [TOP, 6 + MINUS_X])
    assert checked(m) == (24, 44, 22) and genus(m) == 0  # a hub of 8 points, a box
    assert {p[2] for p in new_points(m, 16)} == {1.5, 2.0, 3.0}


def test_max_offsets_on_three_cube_faces_is_the_plain_handle():
    m = cube()
    multi_face_handle(m, [0, 2, 4], max_offsets=True)
    assert checked(m) == (20, 42, 20) and genus(m) == 2


# -- closest edges ----------------------------------------------------------------------------

def test_closest_edges_join_the_top_and_bottom_of_a_cube():
    m = cube()
    new = multi_face_handle_closest_edges(m, [0, TOP])
    # four vertical quads: the faces merge (genus 1), as connect_faces does; TopMod
    # joined nothing for two faces (their centroid plane does not exist)
    assert checked(m) == (8, 16, 8) and genus(m) == 1 and face_size_histogram(m) == {4: 8}
    assert len(new) == 4
    assert all(a[:2] == b[:2] and {a[2], b[2]} == {0.0, 1.0} for a, b in edge_ends(m, new))


def test_closest_edges_of_three_cube_faces_join_the_opposite_two():
    m = cube()
    new = multi_face_handle_closest_edges(m, [0, 2, 4])
    # -y to +y at distance 1 (bottom and top planes); the bottom's pairs, at sqrt(2),
    # reuse those edges; pairs in the plane of the centroids (x = 0, 1) are dropped
    assert checked(m) == (8, 16, 8) and genus(m) == 1
    assert len(new) == 4
    assert all({a[1], b[1]} == {0.0, 1.0} and a[0] == b[0] and a[2] == b[2]
               for a, b in edge_ends(m, new))


def test_closest_edges_of_facing_cubes_make_a_tube():
    m = two_cubes()
    multi_face_handle_closest_edges(m, [PLUS_X, 6 + MINUS_X])
    assert checked(m) == (16, 28, 14) and genus(m) == 0 and num_components(m) == 1


def hex_prisms() -> Mesh:
    """Two prisms over a 2 x 1 rectangle with a corner at the middle of each long
    side (12/18/8 each), the second 3 above the first; faces 1 and 8 face each other."""
    ring = [(0, 0), (1, 0), (2, 0), (2, 1), (1, 1), (0, 1)]
    pos = np.array([(x, y, z) for z in (0, 1, 4, 5) for x, y in ring], float)
    polys = []
    for base in (0, 12):
        bottom, top = list(range(base, base + 6)), list(range(base + 6, base + 12))
        polys += [bottom[::-1], top]
        polys += [[bottom[i], bottom[(i + 1) % 6], top[(i + 1) % 6], top[i]] for i in range(6)]
    return from_polygons(pos, polys)


def test_closest_edges_delete_new_edges_between_coplanar_quads():
    m = hex_prisms()
    new = multi_face_handle_closest_edges(m, [1, 8])
    # six vertical quads (+6 edges, +4 faces); the two new edges at the long sides'
    # middles lie between coplanar quads and go (-2 edges, -2 faces): 24/40/18
    assert checked(m) == (24, 40, 18) and genus(m) == 0
    assert face_size_histogram(m) == {4: 14, 6: 4}
    assert sorted(p[0] for a, b in edge_ends(m, new) for p in (a, b)) == [0, 0, 0, 0, 2, 2, 2, 2]


def test_closest_edges_refuse_faces_with_no_qualifying_pair():
    # opposite octahedron faces: their parallel edges run the same way (crossed quads)
    assert_refused(octahedron(), lambda m: multi_face_handle_closest_edges(m, [0, 6]),
                   r"no two edges of faces \[0, 6\] make a nearly planar quad", error=GeometryError)


# -- fitted hub ---------------------------------------------------------------------------------

def test_fitted_factor_follows_topmods_search():
    tried: list[float] = []

    def fits(factor: float) -> bool:
        tried.append(factor)
        return factor <= 0.7

    # up, down, up, up, down, down; the next step (1/128) is below 0.01, so a failing
    # factor moves down by 0.01 and the fitting one ends the search
    assert fitted_factor(fits) == pytest.approx(0.693125)
    assert tried == pytest.approx([0.5, 0.75, 0.625, 0.6875, 0.71875, 0.703125, 0.693125])
    assert fitted_factor(lambda f: f < 1.0) == 0.984375
    assert fitted_factor(lambda f: True, min_factor=0.3) == 0.5


def test_fitted_factor_gives_up_after_ten_tries():
    tried: list[float] = []
    with pytest.raises(GeometryError, match="no hub that keeps every point found in 10 steps"):
        fitted_factor(lambda f: tried.append(f) is not None)
    assert len(tried) == 10


def test_fitted_hub_between_facing_cubes():
    m = two_cubes()
    multi_face_handle_fitted(m, [PLUS_X, 6 + MINUS_X])
    # the faces at x = 1 and 3 move toward x = 2 by 0.984375 of the way: a box hub
    # 8/12/6 and two tubes; one component, genus 0
    assert checked(m) == (24, 44, 22) and genus(m) == 0 and num_components(m) == 1
    assert {p[0] for p in new_points(m, 16)} == {1.984375, 2.015625}


def test_fitted_hub_alone_without_connections():
    m = two_cubes()
    multi_face_handle_fitted(m, [PLUS_X, 6 + MINUS_X], connect=False)
    assert checked(m) == (24, 36, 18) and num_components(m) == 3


def test_fitted_hub_inside_a_cube_joins_top_and_bottom():
    m = cube()
    multi_face_handle_fitted(m, [0, TOP])
    # a thin slab at the middle, turned inside out, joined to both: 16/32/16, genus 1
    assert checked(m) == (16, 32, 16) and genus(m) == 1
    assert {p[2] for p in new_points(m, 8)} == {0.4921875, 0.5078125}


def test_fitted_hub_refuses_faces_it_cannot_face():
    assert_refused(cube(), lambda m: multi_face_handle_fitted(m, [0, 2, 4]),
                   "face 2 has no hull face facing it; the fitted hub suits faces that face",
                   error=GeometryError)


def test_fitted_hub_refuses_points_inside_the_faces_hull():
    inner = CUBE_POSITIONS * 0.2 + 0.4
    m = from_polygons(np.concatenate([CUBE_POSITIONS, inner]),
                      CUBE_FACES + [[v + 8 for v in f] for f in CUBE_FACES])
    assert_refused(m, lambda m: multi_face_handle_fitted(m, [0, TOP, 6 + TOP]),
                   r"the faces' point \[0.4, 0.4, 0.6.*\] lies inside the convex hull",
                   error=GeometryError)


# -- bad input ------------------------------------------------------------------------------------

@pytest.mark.parametrize(("call", "message", "error"), [
    (lambda m: multi_face_handle(m, [0, 1], max_offsets="yes"), "max_offsets must be True or False",
     InvalidArgumentError),
    (lambda m: face_max_offsets(m, [0, 1], float("nan")), "fallback must be finite",
     InvalidArgumentError),
    (lambda m: face_max_offsets(m, [0]), "face_max_offsets needs two or more different faces",
     InvalidArgumentError),
    (lambda m: multi_face_handle_closest_edges(m, [0, 0]), "needs two or more different faces",
     InvalidArgumentError),
    (lambda m: multi_face_handle_closest_edges(m, [0, 99]), "face 99 does not exist",
     UnknownIdError),
    (lambda m: multi_face_handle_closest_edges(m, [0, 1.0]), "faces must hold ids",
     InvalidArgumentError),
    (lambda m: multi_face_handle_fitted(m, [0, 1], 0.0), "min_factor must be a positive number",
     InvalidArgumentError),
    (lambda m: multi_face_handle_fitted(m, [0, 1], connect=2), "connect must be True or False",
     InvalidArgumentError),
    (lambda m: multi_face_handle_fitted(m, [3]), "multi_face_handle_fitted needs two or more",
     InvalidArgumentError),
])
def test_bad_input_is_refused_unchanged(call, message, error):
    assert_refused(cube(), call, message, error=error)


def test_faces_without_a_normal_are_refused():
    m = cube()
    v = m.create_vertex((5.0, 5.0, 5.0))  # a point-sphere: a one-corner face
    lone = m.corner_face(m.vertex_corner(v))
    assert_refused(m, lambda m: multi_face_handle_closest_edges(m, [0, lone]),
                   f"face {lone} has no normal", error=GeometryError)


# -- huge and tiny meshes ---------------------------------------------------------------------

@pytest.mark.parametrize(("make", "op"), [
    (corner_cubes, lambda m, s: multi_face_handle(m, [TOP, 11], 1.0, 0.5 * s, max_offsets=True)),
    (two_cubes, lambda m, s: multi_face_handle_closest_edges(m, [PLUS_X, 11])),
    (cube, lambda m, s: multi_face_handle_closest_edges(m, [0, 2, 4])),
    (two_cubes, lambda m, s: multi_face_handle_fitted(m, [PLUS_X, 11])),
], ids=["max-offsets", "closest-2", "closest-3", "fitted"])
@pytest.mark.parametrize("scale", [1e154, 1e300])
def test_handles_of_a_huge_mesh_are_the_scaled_unit_ones(make, op, scale):
    assert_scales(make, op, scale)


@pytest.mark.parametrize("op", [
    lambda m, s: multi_face_handle_closest_edges(m, [PLUS_X, 11]),
    lambda m, s: multi_face_handle_fitted(m, [PLUS_X, 11]),
], ids=["closest", "fitted"])
def test_handles_of_a_tiny_mesh_are_the_scaled_unit_ones(op):
    # (the convex-hull handle: test_every_handle_is_the_same_at_every_scale)
    assert_scales(two_cubes, op, 1e-300)


# -- the same handle at every scale ---------------------------------------------------------

# TopMod merged the hub's points within an absolute 1e-2, which swallowed the whole
# hub of a cube 1e-6 across ("a convex hull needs at least 4 points, got 1"); livemod
# merges within 5e-3 times the faces' extent, TopMod's 1e-2 on its cube (edge 2)
SCALES = [1e-150, 1e-6, 1.0, 1e6, 1e150]

SCALED_HANDLES = {
    "hub": (cube, lambda m, s: multi_face_handle(m, [0, 2, 4], 1.0, 0.5 * s),
            (20, 42, 20), 2, {4: 18, 6: 2}),
    "scaled-hub": (cube, lambda m, s: multi_face_handle(m, [0, 2, 4], 0.8, 0.5 * s),
                   (20, 42, 20), 2, {4: 18, 6: 2}),
    "six-faces": (cube, lambda m, s: multi_face_handle(m, [0, 1, 2, 3, 4, 5], 1.0, s),
                  (32, 84, 44), 5, {3: 8, 4: 36}),
    "max-offsets": (corner_cubes,
                    lambda m, s: multi_face_handle(m, [TOP, 11], 1.0, 0.5 * s, max_offsets=True),
                    (22, 41, 21), 0, {3: 2, 4: 19}),
    "fitted": (two_cubes, lambda m, s: multi_face_handle_fitted(m, [PLUS_X, 11]),
               (24, 44, 22), 0, {4: 22}),
    "closest": (cube, lambda m, s: multi_face_handle_closest_edges(m, [0, 2, 4]),
                (8, 16, 8), 1, {4: 8}),
}


def scaled_by(make, scale: float) -> Mesh:
    """``make()`` with every position times ``scale``."""
    mesh = make()
    mesh.set_positions(mesh.vertex_ids(), mesh.positions_view() * scale)
    return mesh


@pytest.mark.parametrize("name", sorted(SCALED_HANDLES))
@pytest.mark.parametrize("scale", SCALES)
def test_every_handle_is_the_same_at_every_scale(name, scale):
    make, op, counts, handles, sizes = SCALED_HANDLES[name]
    unit_mesh, mesh = make(), scaled_by(make, scale)
    op(unit_mesh, 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        op(mesh, scale)
    assert checked(mesh) == counts and genus(mesh) == handles
    assert face_size_histogram(mesh) == sizes
    np.testing.assert_allclose(mesh.positions_view() / scale, unit_mesh.positions_view(),
                               rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("scale", SCALES)
def test_the_faces_shared_points_are_kept_once_at_every_scale(scale):
    m = scaled_by(corner_cubes, scale)
    multi_face_handle(m, [TOP, 6 + MINUS_X], 1.0, 0.5 * scale, max_offsets=True)
    expected = [(0.0, 0.0, 2.0), (0.0, 1.0, 2.0), (1.0, 0.0, 2.0),
                (1.0, 0.0, 3.0), (1.0, 1.0, 2.0), (1.0, 1.0, 3.0)]
    np.testing.assert_allclose(np.array(new_points(m, 16)) / scale, expected, atol=1e-12)


@pytest.mark.parametrize("scale", SCALES)
def test_hub_points_merge_within_half_a_hundredth_of_the_faces_extent(scale):
    faces_points = CUBE_POSITIONS * scale  # extent 1 (times scale)
    points = np.array([[0, 0, 0], [0.004, 0, 0], [0.01, 0, 0],
                       [1, 1, 1], [1, 1, 1.0049], [1, 1, 0.98]]) * scale
    np.testing.assert_array_equal(multihandle._merged(points, faces_points), points[[0, 2, 3, 5]])


def test_on_topmods_cube_the_merge_distance_is_its_absolute_hundredth():
    topmod_cube = cube_obj().positions_view()  # extent 2
    points = np.array([[0.5, 0.5, 2.0], [0.5, 0.5, 2.0099], [0.5, 0.5, 1.9899]])
    np.testing.assert_array_equal(multihandle._merged(points, topmod_cube), points[[0, 2]])
    # faces 200 across: 0.5 apart (TopMod: two points) is one point
    big = np.array([[50.0, 50.0, 200.0], [50.0, 50.0, 200.5]])
    np.testing.assert_array_equal(multihandle._merged(big, topmod_cube * 100), big[[0]])


def test_each_leg_takes_its_faces_colour_and_the_hub_none():
    m = rainbow_cube()
    multi_face_handle(m, [0, 2, 4], max_offsets=True)
    validate(m)
    # a leg of four quads per face; the hub, joining three faces, has no one source
    assert colour_counts(m) == {0: 4, 2: 4, 4: 4, 1: 1, 3: 1, 5: 1, None: 5}
