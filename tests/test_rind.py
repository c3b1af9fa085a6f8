"""Rind modeling: crust by thickness or scaling, punched faces, cleanup, bad input."""

from __future__ import annotations

import re

import numpy as np
import pytest

from livemod.dlfl import Mesh, face_size_histogram, from_polygons, genus, num_components, validate
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.errors import (
    BudgetExceededError,
    GeometryError,
    InvalidArgumentError,
    UnknownIdError,
)
from livemod.dlfl.rind import crust, crust_offsets, punch, rind
from livemod.dlfl.selection import faces_by_size
from livemod.dlfl.shapes import cube, icosahedron, soccer_ball, torus
from livemod.dlfl.sponge import sponge
from tests.meshes import (
    assert_refused,
    assert_refused_quietly,
    assert_scales,
    colour_counts,
    point_sphere,
    rainbow_cube,
    scaled_cube,
    snapshot,
    split_edge_cube,
)

# TopMod's cube.obj faces: 0 top (+y), 1 +x, 2 -z, 3 -x, 4 +z, 5 bottom (-y)
TOP, BOTTOM, PLUS_X = 0, 5, 1


def summary(mesh):
    validate(mesh)
    return mesh.counts(), face_size_histogram(mesh), genus(mesh), num_components(mesh)


def test_crust_of_the_cube_is_two_shells():
    m = cube()
    crust(m, 0.5)
    assert summary(m) == ((16, 24, 12), {4: 12}, 0, 2)


def test_crust_inner_copy_is_offset_exactly_by_the_thickness():
    m = cube()
    rind(m, (), 0.3)
    pos = m.positions_view()
    np.testing.assert_allclose(pos[:8], cube().positions_view(), atol=1e-12)
    np.testing.assert_allclose(pos[8:], cube().positions_view() * 0.7, atol=1e-12)


def test_one_hole_matches_topmod():
    m = cube()
    rind(m, [TOP], 0.5)
    assert summary(m) == ((16, 28, 14), {4: 14}, 0, 1)


def test_two_opposite_holes_make_a_torus():
    m = cube()
    rind(m, [TOP, BOTTOM], 0.5)
    assert summary(m) == ((16, 32, 16), {4: 16}, 1, 1)


def test_tube_quads_join_each_side_to_its_inner_twin():
    m = cube()
    rind(m, [TOP], 0.5)
    a = mesh_arrays(m)
    pos = a.positions
    tubes = [a.corner_vertex[a.face_offsets[f]:a.face_offsets[f + 1]] for f in range(10, 14)]
    for quad in tubes:
        outer, inner = pos[quad[:2]], pos[quad[2:]]
        assert np.allclose(outer[:, 1], 1.0) and np.allclose(inner[:, 1], 0.5)
        np.testing.assert_allclose(inner[::-1] / 0.5, outer, atol=1e-12)


@pytest.mark.parametrize("k", [1, 2, 3, 6, 12])
def test_genus_after_punching_k_faces_is_k_minus_1(k):
    m = soccer_ball()
    pentagons = faces_by_size(m, 5)  # no two pentagons share an edge
    rind(m, pentagons[:k], 0.2)
    assert genus(m) == k - 1 and num_components(m) == 1
    validate(m)


def test_adjacent_holes_merge_with_cleanup():
    m = cube()
    rind(m, [TOP, PLUS_X], 0.5)
    assert summary(m) == ((16, 28, 14), {4: 14}, 0, 1)


def test_adjacent_holes_keep_the_double_wall_without_cleanup():
    m = cube()
    rind(m, [TOP, PLUS_X], 0.5, cleanup=False)
    assert summary(m) == ((16, 32, 16), {4: 16}, 1, 1)


def test_scaling_crust_scales_the_copy_about_the_centroid():
    m = cube()
    rind(m, [TOP], use_scaling=True, scale=0.6)
    pos = m.positions_view()
    np.testing.assert_allclose(pos[8:], cube().positions_view() * 0.6, atol=1e-12)
    assert m.counts() == (16, 28, 14)


def test_negative_scale_grows_the_outer_shell():
    m = cube()
    rind(m, [], use_scaling=True, scale=-0.5)
    pos = m.positions_view()
    np.testing.assert_allclose(pos[:8], cube().positions_view() * 2, atol=1e-12)
    np.testing.assert_allclose(pos[8:], cube().positions_view(), atol=1e-12)


@pytest.mark.parametrize("scale", [1.0, -1.0])
def test_a_scale_of_magnitude_one_is_refused(scale):
    # TopMod clamped it to [-1, 1] and built an inner shell on the outer one
    m = cube()
    with pytest.raises(InvalidArgumentError, match=f"scale {scale} leaves no thickness between the shells"):
        rind(m, [0], use_scaling=True, scale=scale)
    assert snapshot(m) == snapshot(cube())


@pytest.mark.parametrize(("given", "message"), [
    ({"thickness": float("nan")}, "thickness must be finite, got nan"),
    ({"use_scaling": True, "scale": float("inf")}, "scale must be finite, got inf"),
])
def test_non_finite_thickness_or_scale_is_refused(given, message):
    m = cube()
    with pytest.raises(InvalidArgumentError, match=message):
        rind(m, [0], **given)
    assert snapshot(m) == snapshot(cube())


def test_negative_thickness_moves_the_original_outward():
    m = cube()
    rind(m, [], -0.25)
    pos = m.positions_view()
    np.testing.assert_allclose(pos[:8], cube().positions_view() * 1.25, atol=1e-12)
    np.testing.assert_allclose(pos[8:], cube().positions_view(), atol=1e-12)


def test_uniform_and_plain_offsets():
    a = mesh_arrays(cube())
    np.testing.assert_allclose(crust_offsets(a, 0.5), a.positions * 0.5, atol=1e-12)
    plain = crust_offsets(a, 0.5, uniform=False)
    np.testing.assert_allclose(np.linalg.norm(plain, axis=1), 0.5)


def test_rind_of_a_torus_and_an_icosahedron():
    for shape, g in ((torus(), 1), (icosahedron(), 0)):
        f = int(shape.face_ids()[0])
        rind(shape, [f], 0.05)
        validate(shape)
        assert genus(shape) == 2 * g


def test_ids_are_fresh_after_the_rebuild():
    m = cube()
    before = m.next_ids()
    rind(m, [TOP], 0.5)
    assert int(m.face_ids().min()) >= before[2]


@pytest.mark.parametrize(
    ("faces", "thickness", "error"),
    [([99], 0.5, UnknownIdError), ([TOP, 42], 0.5, UnknownIdError),
     ([TOP], 0.0, InvalidArgumentError),
     ([TOP], 1.0, GeometryError), ([TOP], 1.5, GeometryError), ([TOP], 7.0, GeometryError)],
)
def test_bad_input_leaves_the_mesh_unchanged(faces, thickness, error):
    m = cube()
    before = snapshot(m)
    with pytest.raises(error):
        rind(m, faces, thickness)
    assert snapshot(m) == before


def test_zero_scale_is_refused():
    m = cube()
    with pytest.raises(InvalidArgumentError, match="scale 0"):
        rind(m, [TOP], use_scaling=True, scale=0.0)


def test_a_vertex_whose_faces_are_all_punched_goes_with_cleanup():
    m = cube()
    rind(m, [0, 1, 2], 0.5)
    assert summary(m) == ((14, 24, 12), {4: 12}, 0, 1)
    m = cube()
    rind(m, [0, 1, 2], 0.5, cleanup=False)
    assert summary(m) == ((16, 36, 18), {4: 18}, 2, 1)


def test_punching_every_face_with_cleanup_is_refused():
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="leaves nothing"):
        rind(m, range(6), 0.5)
    assert snapshot(m) == before


def test_point_spheres_are_refused():
    with pytest.raises(InvalidArgumentError, match="point-sphere"):
        rind(point_sphere(), [], 0.5)


def test_rind_of_an_open_grid_is_a_closed_slab():
    from livemod.dlfl.shapes import grid

    m = grid(3, 3)
    rind(m, [], 0.1)
    assert summary(m) == ((32, 60, 30), {4: 30}, 0, 1)
    assert face_size_histogram(m, holes=True) == {4: 30}
    np.testing.assert_allclose(sorted(set(np.round(m.positions_view()[:, 1], 12))), [-0.1, 0.0])
    g = grid(3, 3)
    rind(g, [int(g.face_ids()[4])], 0.1)
    assert summary(g)[2] == 1


def enclosed_volume(mesh):
    """Signed volume by the divergence theorem (faces fanned from their centroids)."""
    a = mesh_arrays(mesh)
    p = a.positions
    centres = np.zeros((len(a.face_ids), 3))
    np.add.at(centres, a.corner_face, p[a.corner_vertex])
    centres /= a.face_sizes[:, None]
    cross = np.cross(p[a.corner_vertex], p[a.corner_vertex[a.corner_next]])
    return np.einsum("ij,ij->i", centres[a.corner_face], cross).sum() / 6


def test_sculpted_solids_face_outward():
    from livemod.dlfl.sponge import sponge
    from livemod.dlfl.wireframe import columns, wireframe

    m = cube()
    rind(m, [], 0.5)
    assert np.isclose(enclosed_volume(m), 8 - 1)  # the cube minus its unit hollow
    ops = [lambda m: rind(m, [TOP], 0.3), lambda m: wireframe(m, 0.1),
           lambda m: columns(m, 0.1, 6), lambda m: sponge(m, 2 / 3, keep_2gons=False)]
    for op in ops:
        m = cube()
        op(m)
        assert 0 < enclosed_volume(m) < 8
    m = cube()
    sponge(m, 2 / 3, keep_2gons=False)
    assert np.isclose(enclosed_volume(m), 8 * 20 / 27)  # 20 of the 27 sub-cubes


@pytest.mark.parametrize("faces", [[TOP, None], [1.0], ["0"]])
def test_rind_refuses_face_lists_holding_no_ids(faces):
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="faces must hold ids"):
        rind(m, faces, 0.2)
    assert snapshot(m) == before


def test_a_thickness_that_overflows_is_refused():
    m = cube()
    before = snapshot(m)
    with pytest.raises(GeometryError, match=r"would move vertex 0 to \[-?inf.*its numbers overflow"):
        crust(m, -1e308)  # the outer copy moves outward past the float range
    assert snapshot(m) == before


@pytest.mark.parametrize(("call", "message"), [
    (lambda m: crust(m, 1e308), r"thickness 1e\+308 would move vertex 0 to \[-?inf"),
    (lambda m: rind(m, [0], 1e308), r"thickness 1e\+308 would move vertex 0 to \[-?inf"),
    (lambda m: rind(m, [0], 1e308, uniform=False), "too large to check for faces turning over"),
    # a unit cube's copy pushed 1e300 inward comes out inside out, and says so
    (lambda m: crust(m, 1e300), "thickness 1e\\+300 would invert the crust"),
])
def test_a_thickness_that_overflows_prints_no_numpy_warning(call, message):
    assert_refused_quietly(cube(), call, message)


def test_a_crust_too_large_to_check_says_so_not_that_it_turns_over():
    # the edge products that tell a copy pushed through overflow past ~1e154
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * 1e160)
    with pytest.raises(GeometryError, match="too large to check for faces turning over"):
        crust(m, 1e159)


def test_a_crust_of_a_huge_mesh_is_the_scaled_crust_of_the_unit_one():
    # the face-area check once squared raw Newell sums, which overflowed past 1e77
    assert_scales(cube, lambda m, s: crust(m, 0.1 * s), rtol=1e-12)


# -- punching a crust made earlier (TopMod's cmMakeHole) ------------------------------

def _polygons(mesh) -> list[tuple[tuple[float, ...], ...]]:
    """The faces as sorted tuples of their rounded points: the geometry, not the ids."""
    return sorted(tuple(sorted(tuple(np.round(mesh.position(v), 12))
                               for v in mesh.face_vertices(f)))
                  for f in mesh.face_ids().tolist())


@pytest.mark.parametrize("punched", [[0], [0, 5], [0, 1], [0, 1, 2], [0, 1, 2, 3, 4]])
@pytest.mark.parametrize("cleanup", [True, False])
def test_punching_later_is_punching_at_once(punched, cleanup):
    at_once = cube()
    rind(at_once, punched, 0.5, cleanup=cleanup)
    one_by_one, together = cube(), cube()
    twins_1, twins_2 = crust(one_by_one, 0.5), crust(together, 0.5)
    outer = list(twins_1.faces)
    for i in punched:
        punch(one_by_one, twins_1, [outer[i]], cleanup=cleanup)
    punch(together, twins_2, [list(twins_2.faces)[i] for i in punched], cleanup=cleanup)
    for mesh in (one_by_one, together):
        validate(mesh)
        assert mesh.counts() == at_once.counts() and genus(mesh) == genus(at_once)
        assert _polygons(mesh) == _polygons(at_once)
    assert len(twins_1.faces) == len(twins_2.faces) == 6 - len(punched)


def test_a_punch_keeps_every_other_id_and_either_copy_names_the_pair():
    m = cube()
    twins = crust(m, 0.5)
    outer, inner = next(iter(twins.faces.items()))
    others = [f for f in m.face_ids().tolist() if f not in (outer, inner)]
    tube = punch(m, twins, [inner])
    assert m.counts() == (16, 28, 14) and len(tube) == 4
    assert all(m.has_face(f) for f in others) and outer not in twins.faces
    assert all(m.face_size(f) == 4 for f in tube)


def test_the_twins_pair_every_outer_vertex_with_its_offset_copy():
    m = cube()
    twins = crust(m, 0.5)
    for outer, inner in twins.vertices.items():
        np.testing.assert_allclose(m.position(inner), m.position(outer) * 0.5)
    assert len(twins.faces) == 6 and len(twins.vertices) == 8


def test_rind_returns_the_twins_of_the_faces_it_left_to_punch():
    m = cube()
    twins = rind(m, [0, 1, 2], 0.5)
    assert len(twins.faces) == 3
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="punching every face of a crust with "
                       "cleanup leaves nothing"):
        punch(m, twins, list(twins.faces))
    assert snapshot(m) == before
    punch(m, twins, list(twins.faces)[:2])
    five = cube()
    rind(five, [0, 1, 2, 3, 4], 0.5)
    assert m.counts() == five.counts() == (8, 12, 6)
    validate(m)


@pytest.mark.parametrize(("faces", "message"), [
    (["0"], "must hold ids"),
    ([99], "face 99 is not a face of the crust still to punch"),
])
def test_punching_what_is_no_unpunched_face_of_the_crust_is_refused(faces, message):
    m = cube()
    twins = crust(m, 0.5)
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match=message):
        punch(m, twins, [list(twins.faces)[0], *faces])
    assert snapshot(m) == before and len(twins.faces) == 6


def test_punching_faces_changed_since_the_crust_is_refused():
    m = cube()
    twins = crust(m, 0.5)
    outer, _ = next(iter(twins.faces.items()))
    m.subdivide_edge(m.face_edges(outer)[0])
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match=f"faces {outer} and .* are no longer twins"):
        punch(m, twins, [outer])
    assert snapshot(m) == before


def test_punch_checks_the_face_budget_before_any_tube():
    """Two cube faces: 8 tube quads on the crust's 12 faces; 19 faces refuse both."""
    m = cube()
    twins = crust(m, 0.5)
    two = list(twins.faces)[:2]
    before = snapshot(m)
    with pytest.raises(BudgetExceededError, match="punch would produce 20 faces"):
        punch(m, twins, two, max_faces=19)
    assert snapshot(m) == before and len(twins.faces) == 6
    punch(m, twins, two, max_faces=20)
    validate(m)

def test_both_copies_keep_their_face_colour_and_a_tube_takes_the_punched_one():
    m = rainbow_cube()
    crust(m, 0.2)
    validate(m)
    assert colour_counts(m) == {f: 2 for f in range(6)}
    m = rainbow_cube()
    rind(m, [0], 0.2)
    validate(m)
    # face 0 gone, its four tube quads in its colour; the rest outside and inside
    assert colour_counts(m) == {0: 4, 1: 2, 2: 2, 3: 2, 4: 2, 5: 2}


# -- a crust of a mesh with no face normal is refused by name

NO_NORMAL = re.escape(
    "vertex 0 has no face normal to offset it along: the faces at it have no area "
    "(their corners are collinear or coincident); the crust would have no thickness there")
NO_AREA = re.escape(
    "a crust needs a face with an area; every face of this mesh has collinear or "
    "coincident corners, so the shells would have no thickness")


def _collinear_sliver():
    """Two triangles back to back on three collinear points: 3/3/2, no normal anywhere."""
    return from_polygons(np.array([[0.0, 0, 0], [1, 0, 0], [2, 0, 0]]), [[0, 1, 2], [0, 2, 1]])


def _coincident_sliver():
    return from_polygons(np.zeros((3, 3)), [[0, 1, 2], [0, 2, 1]])


@pytest.mark.parametrize("make", [_collinear_sliver, _coincident_sliver])
@pytest.mark.parametrize("call", [
    lambda m: rind(m, [], 0.1),
    lambda m: rind(m, [0], 0.1),
    lambda m: rind(m, [], -0.1, uniform=False),
    lambda m: sponge(m, 0.1),
    lambda m: sponge(m),
], ids=["rind", "rind-punched", "rind-outward", "sponge", "sponge-default"])
def test_a_crust_of_a_mesh_with_no_face_normal_is_refused(make, call):
    mesh = make()
    validate(mesh)
    assert_refused(mesh, call, NO_NORMAL, error=GeometryError)


@pytest.mark.parametrize("make", [_collinear_sliver, _coincident_sliver])
def test_a_scaled_crust_of_a_mesh_with_no_face_area_is_refused(make):
    assert_refused(make(), lambda m: rind(m, [], use_scaling=True, scale=0.5), NO_AREA,
                   error=GeometryError)


def test_crust_offsets_of_a_mesh_with_no_face_normal_are_refused():
    with pytest.raises(GeometryError, match=NO_NORMAL):
        crust_offsets(mesh_arrays(_collinear_sliver()), 0.1)


def test_a_crust_of_a_mesh_with_a_two_gon_still_works():
    # a 2-gon has no area, but its vertices have other faces' normals
    a = mesh_arrays(cube())
    polygons = [a.corner_vertex[a.face_offsets[k] : a.face_offsets[k + 1]].tolist()
                for k in range(6)]
    m = from_polygons(cube().positions_view(), [*polygons, [0, 1]])
    rind(m, [], 0.5)
    validate(m)
    assert (m.num_vertices, m.num_edges, m.num_faces) == (16, 26, 14)
    np.testing.assert_allclose(np.abs(m.positions_view()[8:]), 0.5, atol=1e-15)


# -- the inner copy of a straight vertex (on a split edge) moves with its edge


@pytest.mark.parametrize("uniform", [True, False])
def test_the_inner_copy_of_a_vertex_on_a_split_edge_moves_with_its_edge(uniform):
    # its corners are straight (no corner normal): it stayed on the outer shell
    m = split_edge_cube()
    rind(m, [], 0.5, uniform=uniform)
    validate(m)
    assert (m.num_vertices, m.num_edges, m.num_faces) == (18, 26, 12)
    p = m.positions_view()
    np.testing.assert_array_equal(p[8], [1, 1, 0])
    if uniform:  # on the inner copy of the split edge, half-way between its ends
        np.testing.assert_allclose(p[17], (p[9] + p[10]) / 2, atol=1e-15)
    # non-uniform: t along the mean of its two faces' normals, as at any edge
    expected = [0.5, 0.5, 0] if uniform else [1 - 0.5 / 2**0.5, 1 - 0.5 / 2**0.5, 0]
    np.testing.assert_allclose(p[17], expected, atol=1e-15)


# -- a scale beyond one is refused naming the value given, before a scale of one


@pytest.mark.parametrize("scale", [1.5, -5, 5.0, 1.0000001, -1e300])
def test_a_scale_beyond_one_is_refused_naming_the_value_given(scale):
    message = re.escape(f"scale {scale} is beyond +-1: a scaled crust needs 0 < |scale| < 1")
    assert_refused(cube(), lambda m: rind(m, [0], use_scaling=True, scale=scale), message,
                   error=InvalidArgumentError)


@pytest.mark.parametrize("scale", [1, -1.0])
def test_a_scale_of_one_still_says_there_is_no_thickness(scale):
    message = re.escape(f"scale {scale} leaves no thickness between the shells")
    assert_refused(cube(), lambda m: rind(m, [], use_scaling=True, scale=scale), message,
                   error=InvalidArgumentError)


# -- the inversion check at any scale, and outward into a concave slot


def _u_prism() -> Mesh:
    """A U-shaped prism (a slot 1 wide, 1 deep): concave, 16/24/10."""
    outline = [(0, 0), (3, 0), (3, 2), (2, 2), (2, 1), (1, 1), (1, 2), (0, 2)]
    n = len(outline)
    points = [(x, y, 0.0) for x, y in outline] + [(x, y, 1.0) for x, y in outline]
    faces = [list(range(n))[::-1], list(range(n, 2 * n))]
    faces += [[i, (i + 1) % n, (i + 1) % n + n, i + n] for i in range(n)]
    return from_polygons(np.array(points), faces)


@pytest.mark.parametrize("scale", [1e-13, 1e-150])
@pytest.mark.parametrize("thickness", [1.5, 3.0])
def test_a_rind_that_inverts_a_tiny_mesh_is_refused(scale, thickness):
    # absolute cut-offs (edges 1e-24 squared, areas 1e-12) left out every edge
    # and face of a tiny mesh, so a copy pushed through the middle passed
    m = scaled_cube(scale)
    assert_refused(m, lambda m: rind(m, [m.face_ids()[0]], thickness * scale), "invert",
                   error=GeometryError)


def test_the_rind_of_a_tiny_mesh_still_works():
    m = scaled_cube(1e-150)
    rind(m, [m.face_ids()[0]], 0.5e-150)
    validate(m)
    assert m.counts() == (16, 28, 14)


def test_a_negative_thickness_that_turns_a_slot_floor_over_is_refused():
    # outward, the U's slot walls (1 apart) meet at 0.5: its floor reversed unchecked
    assert_refused(_u_prism(), lambda m: rind(m, [], -0.6), "-0.6 would invert",
                   error=GeometryError)


def test_a_negative_thickness_that_fits_the_slot_works():
    m = _u_prism()
    rind(m, [], -0.3)
    validate(m)
    assert m.counts() == (32, 48, 20)
