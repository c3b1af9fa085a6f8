"""Modified corner cutting, wireframe and columns: counts, genus, TopMod's geometry."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from livemod.dlfl import face_size_histogram, genus, num_components, validate
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.cutting import truncate
from livemod.dlfl.errors import GeometryError, InvalidArgumentError, NonManifoldError
from livemod.dlfl.shapes import (
    cube,
    dodecahedron,
    genus_torus,
    icosahedron,
    octahedron,
    soccer_ball,
    tetrahedron,
    torus,
)
from livemod.dlfl.wireframe import (
    columns,
    modified_corner_cut,
    vertex_rings,
    wireframe,
)
from tests.meshes import (
    assert_refused,
    assert_refused_quietly,
    assert_scales,
    colour_counts,
    point_sphere,
    rainbow_cube,
    snapshot,
)
from tests.meshes import tetrahedron as unit_tetrahedron


def summary(mesh):
    validate(mesh)
    return mesh.counts(), face_size_histogram(mesh), genus(mesh)


def as_set(points):
    return sorted(map(tuple, np.round(points, 9).tolist()))


def test_modified_corner_cut_of_the_cube():
    m = cube()
    front = modified_corner_cut(m, 0.25)
    assert summary(m) == ((24, 48, 26), {3: 8, 4: 18}, 0)
    assert len(front) == 6 and all(m.face_size(f) == 4 for f in front)


def test_corner_cut_points_sit_half_the_thickness_from_both_edges():
    m = cube()
    modified_corner_cut(m, 0.25)
    expected = [(sx * 0.875, sy * 0.875, sz) for sz in (1, -1) for sx in (1, -1)
                for sy in (1, -1)]
    points = m.positions_view()
    on_z = points[np.isclose(np.abs(points[:, 2]), 1.0)]
    assert as_set(on_z) == as_set(np.array(expected)[:, [0, 1, 2]])


def test_corner_cut_counts_on_other_meshes():
    for shape in (tetrahedron(), icosahedron(), dodecahedron(), torus()):
        v, e, f = shape.counts()
        modified_corner_cut(shape, 0.1)
        validate(shape)
        assert shape.counts() == (2 * e, 4 * e, f + e + v)


def test_wireframe_of_the_cube_matches_topmod():
    m = cube()
    wireframe(m, 0.1)
    assert summary(m) == ((48, 120, 64), {3: 16, 4: 48}, 5)
    assert num_components(m) == 1


@pytest.mark.parametrize("t", [0.05, 0.25, 0.5])
def test_wireframe_counts_do_not_depend_on_thickness(t):
    m = cube()
    wireframe(m, t)
    assert summary(m) == ((48, 120, 64), {3: 16, 4: 48}, 5)


def test_wireframe_geometry_matches_topmods_rule():
    t = 0.1
    m = cube()
    wireframe(m, t)
    outer = np.array([(sx * (1 - t / 2), sy * (1 - t / 2), sz) for sx in (1, -1)
                      for sy in (1, -1) for sz in (1, -1)])
    outer = np.concatenate([np.roll(outer, k, axis=1) for k in range(3)])
    # each inner copy sits t along the inward cube diagonal from its outer point
    inner = outer - t * np.sign(outer) / np.sqrt(3)
    assert as_set(m.positions_view()) == as_set(np.concatenate([outer, inner]))


def test_wireframe_genus_is_the_cycle_rank_of_the_edge_graph():
    for shape in (icosahedron(), torus(6, 4), tetrahedron()):
        v, e, _ = shape.counts()
        wireframe(shape, 0.05)
        validate(shape)
        assert genus(shape) == e - v + 1


@pytest.mark.parametrize("t", [0.0, -0.1, float("nan")])
def test_wireframe_bad_thickness_leaves_the_mesh_unchanged(t):
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError):
        wireframe(m, t)
    assert snapshot(m) == before


def test_wireframe_refuses_point_spheres():
    with pytest.raises(InvalidArgumentError, match="point-sphere"):
        wireframe(point_sphere(), 0.1)


def test_columns_four_segments_match_topmod():
    m = cube()
    columns(m, 0.25, 4)
    assert summary(m) == ((96, 216, 112), {3: 16, 4: 96}, 5)


def test_columns_six_segments_match_topmod():
    m = cube()
    columns(m, 0.25, 6)
    assert summary(m) == ((144, 312, 160), {3: 16, 4: 144}, 5)


# A joint's faces by TopMod's rule (the hull of its rings cut into triangles, the
# parity rule, faces in one plane merged), counted by hand per kind of vertex:
# a valence-3 joint has 2 triangles (each touching the three rings) and, between
# each two rings, a band of 4 triangles the parity rule pairs into 2 quads. With
# its E tubes of 4 quads a mesh of valence-3 vertices gets
# V' = 8E, F' = 8V + 4E, {3: 2V, 4: 6V + 4E}, genus E - V + 1.
def valence3_columns(v: int, e: int) -> tuple[tuple[int, int, int], dict[int, int], int]:
    faces = {3: 2 * v, 4: 6 * v + 4 * e}
    corners = 3 * faces[3] + 4 * faces[4]
    return (8 * e, corners // 2, sum(faces.values())), faces, e - v + 1


def test_columns_on_a_soccer_ball_pair_each_joints_triangles_into_quads():
    m = soccer_ball()
    columns(m, 0.1, 4)
    assert summary(m) == valence3_columns(60, 90) == ((720, 1620, 840), {3: 120, 4: 720}, 31)


def test_columns_on_a_genus3_mesh_of_valence_3_vertices():
    m = genus_torus(3)  # 64/136/68: a slab with three holes
    truncate(m, 0.25)  # 272/408/132, every vertex of valence 3
    assert genus(m) == 3
    columns(m, 0.05, 4)
    assert summary(m) == valence3_columns(272, 408) == ((3264, 7344, 3808),
                                                         {3: 544, 4: 3264}, 137)


def test_columns_on_a_four_by_four_torus_give_topmods_faces():
    # TopMod's run on this torus: 256/560/272, {4: 248, 5: 16, 6: 8}. Per joint,
    # by the rule: the 4 joints on the outer equator 10 quads (their hull's planar
    # quads); the 4 on the inner equator 4 quads and 4 pentagons; the 8 off the
    # equator 8 quads and a hexagon
    m = torus(4, 4)
    columns(m, 0.25, 4)
    tubes = 32 * 4
    quads = 4 * 10 + 4 * 4 + 8 * 8 + tubes
    assert summary(m) == ((256, 560, 272), {4: quads, 5: 4 * 4, 6: 8 * 1}, 17)


@pytest.mark.parametrize("make, segments, expected", [
    # TopMod's counts, each run on TopMod's own sample solid
    (tetrahedron, 4, ((48, 108, 56), {3: 8, 4: 48})),
    (octahedron, 4, ((96, 216, 108), {4: 108})),
    (icosahedron, 4, ((240, 540, 264), {4: 240, 5: 24})),
    (dodecahedron, 6, ((360, 780, 400), {3: 40, 4: 360})),
])
def test_columns_on_the_platonic_solids_give_topmods_counts(make, segments, expected):
    m = make()
    v, e, _ = m.counts()
    columns(m, 0.1, segments)
    assert summary(m) == (*expected, e - v + 1)


def test_columns_of_an_odd_segment_count_keep_the_merged_hull():
    # the parity of a place in a ring does not go round an odd ring: TopMod's rule
    # merged whole bands into 9-gons (300/570/250, {4: 210, 6: 20, 9: 20});
    # livemod keeps the hull with its faces in one plane merged: each joint of
    # three 5-point rings a triangle, 6 quads and a hexagon, every face planar
    m = dodecahedron()
    columns(m, 0.1, 5)
    counts, sizes, g = summary(m)
    assert (counts, sizes, g) == ((300, 630, 310), {3: 20, 4: 20 * 6 + 30 * 5, 6: 20}, 11)
    for f in m.face_ids().tolist():
        points = np.array([m.position(v) for v in m.face_vertices(f)])
        centred = points - points.mean(axis=0)
        assert np.linalg.svd(centred, compute_uv=False)[-1] < 1e-9  # every face planar


def test_column_rings_have_the_thickness_as_radius():
    m = cube()
    columns(m, 0.2, 4)
    pos = m.positions_view()
    # every point is 0.2 from the cube edge it follows: two coordinates at 1 +- 0.2/sqrt(2)
    off = np.abs(np.abs(pos) - 1)
    close = np.isclose(off, 0.2 / np.sqrt(2))
    assert (close.sum(axis=1) == 2).all()
    radial = np.sqrt(np.sort(np.where(close, off, 0.0), axis=1)[:, 1:] ** 2 @ np.ones(2))
    np.testing.assert_allclose(radial, 0.2)


def test_columns_on_other_meshes():
    for shape in (tetrahedron(), icosahedron(), torus(6, 4)):
        v, e, _ = shape.counts()
        columns(shape, 0.05, 5)
        validate(shape)
        assert genus(shape) == e - v + 1


@pytest.mark.parametrize("segments", [-1, 0, 1, 2, 2.5])
def test_columns_refuse_too_few_segments(segments):
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="segments"):
        columns(m, 0.25, segments)
    assert snapshot(m) == before


def test_columns_refuse_an_empty_mesh():
    from livemod.dlfl import Mesh

    m = Mesh()
    with pytest.raises(InvalidArgumentError, match="^columns need a mesh with faces; this one "
                                                   "is empty$"):
        columns(m, 0.25, 4)
    assert m.counts() == (0, 0, 0)


def test_columns_refuse_a_bad_thickness():
    m = cube()
    with pytest.raises(InvalidArgumentError, match="thickness"):
        columns(m, 0.0, 4)


def test_vertex_rings_walk_against_vnext():
    a = mesh_arrays(cube())
    order, offsets = vertex_rings(a)
    assert np.diff(offsets).tolist() == [3] * 8
    vnext = a.corner_vnext
    for v in range(8):
        ring = order[offsets[v]:offsets[v + 1]]
        for i in range(3):
            assert vnext[ring[(i + 1) % 3]] == ring[i]


def test_vertex_rings_refuse_a_vertex_with_two_fans():
    from dataclasses import replace

    from tests.meshes import two_cubes

    a = mesh_arrays(two_cubes())
    bow_tie = replace(a, corner_vertex=np.where(a.corner_vertex == 8, 0, a.corner_vertex))
    with pytest.raises(NonManifoldError, match="^a vertex's corners form several fans; the "
                                               "mesh is not manifold there$"):
        vertex_rings(bow_tie)


def test_open_grids_become_wire_grids():
    from livemod.dlfl.shapes import grid

    for op in (lambda m: wireframe(m, 0.05), lambda m: columns(m, 0.05, 4)):
        m = grid(3, 3)
        op(m)
        validate(m)
        assert genus(m) == 24 - 16 + 1


def test_wireframe_with_a_separate_width():
    m = cube()
    wireframe(m, 0.1, width=0.3)
    assert summary(m) == ((48, 120, 64), {3: 16, 4: 48}, 5)
    outer = m.positions_view()[:24]
    assert np.isclose(np.abs(outer).min(), 0.85)
    with pytest.raises(InvalidArgumentError):
        wireframe(cube(), 0.1, width=0.0)


def test_corner_cut_points_are_half_the_thickness_from_both_edge_lines():
    from livemod.dlfl.wireframe import corner_cut_arrays

    for shape in (dodecahedron(), icosahedron(), torus(7, 5)):
        a = mesh_arrays(shape)
        points = corner_cut_arrays(a, 0.2).positions
        p = a.positions
        v0 = p[a.corner_vertex]
        for nb in (a.corner_next, a.corner_prev):
            d = p[a.corner_vertex[nb]] - v0
            d /= np.linalg.norm(d, axis=1, keepdims=True)
            rel = points - v0
            dist = np.linalg.norm(rel - np.einsum("ij,ij->i", rel, d)[:, None] * d, axis=1)
            np.testing.assert_allclose(dist, 0.1, atol=1e-12)


@pytest.mark.parametrize(("call", "message", "error"), [
    (lambda m: wireframe(m, 1.7e308), r"a crust 1.7e\+308 thick .*numbers overflow", GeometryError),
    (lambda m: wireframe(m, None), "thickness must be a number", InvalidArgumentError),
    (lambda m: wireframe(m, 0.1, width="1"), "width must be a number", InvalidArgumentError),
    (lambda m: modified_corner_cut(m, (1.0,)), "thickness must be a number", InvalidArgumentError),
    (lambda m: columns(m, None, 4), "thickness must be a number", InvalidArgumentError),
    (lambda m: columns(m, 0.25, "4"), "segments must be a whole number", InvalidArgumentError),
    (lambda m: columns(m, 0.25, 3.5), "segments must be a whole number", InvalidArgumentError),
])
def test_bad_input_is_refused_and_changes_nothing(call, message, error):
    assert_refused(cube(), call, message, error=error)


# a unit cube's cut points stay below the thickness (no thickness overflows them):
# the unit tetrahedron's 45-degree corners put them farther
@pytest.mark.parametrize("call", [
    lambda m: wireframe(m, 1.7e308), lambda m: wireframe(m, 1.7e308, False),
    lambda m: wireframe(m, 0.1, width=1.7e308), lambda m: modified_corner_cut(m, 1.7e308),
])
def test_a_cut_that_overflows_prints_no_numpy_warning(call):
    assert_refused_quietly(unit_tetrahedron(), call, r"cutting corners by .* would put a point at "
                           r"vertex \d+ at \[.*(inf|nan).*numbers overflow")


def test_a_crust_that_overflows_is_refused_quietly():
    assert_refused_quietly(cube(), lambda m: wireframe(m, 1.7e308, False),
                           r"a crust 1.7e\+308 thick would put the inner copy of vertex \d+ "
                           r"at \[.*inf.*numbers overflow")


@pytest.mark.parametrize("scale", [1e160, 1e300])
def test_a_huge_mesh_cut_by_a_huge_thickness_is_the_scaled_unit_cut(scale):
    # t * t overflowed from t ~ 1e154: refused as "its numbers overflow", which they do not
    assert_scales(torus, lambda m, s: modified_corner_cut(m, 0.25 * s), scale)
    assert_scales(torus, lambda m, s: wireframe(m, 0.1 * s), scale)


def test_a_huge_mesh_cuts_corners_without_a_warning():
    # the 2-gon test measured |v1 - v2| raw: its square overflowed past ~1e154
    assert_scales(cube, lambda m, s: modified_corner_cut(m, 0.25 * s), 1e154)


def test_columns_take_a_whole_float_count():
    m = cube()
    columns(m, 0.25, 4.0)
    assert summary(m)[0] == (96, 216, 112)


@pytest.mark.parametrize("op", [lambda m, s: wireframe(m, 0.1 * s),
                                lambda m, s: wireframe(m, 0.1 * s, width=0.05 * s)])
def test_the_wireframe_of_a_huge_mesh_is_the_scaled_unit_one(op):
    # its inner copy took cubes of raw edge vectors, which overflowed past ~1e100
    assert_scales(icosahedron, op)


@pytest.mark.parametrize("make", [cube, tetrahedron])
def test_columns_of_a_thickness_that_overflows_are_refused_quietly(make):
    # the joints' hulls squared inf - inf, then said "the points are all coplanar"
    assert_refused_quietly(make(), lambda m: columns(m, 1e308, 4), "the thickness overflows")


@pytest.mark.parametrize("scale", [1e154, 1e300])
def test_the_columns_of_a_huge_mesh_are_the_scaled_unit_ones(scale):
    # the joints' hull took cross products of raw coordinates ("coplanar" past ~1e154);
    # rings once sat an absolute 1e-4 beyond their clearance (now 4e-4 t): atol kept
    small, big = torus(), torus()
    big.set_positions(big.vertex_ids(), big.positions_view() * scale)
    columns(small, 0.1, 4)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        columns(big, 0.1 * scale, 4)
    assert summary(big) == summary(small)
    np.testing.assert_allclose(big.positions_view() / scale, small.positions_view(), atol=2e-4)


def test_modified_corner_cut_variant_2_moves_each_corner_along_both_edges():
    m = cube()
    front = modified_corner_cut(m, 0.25, 2)
    validate(m)
    assert m.counts() == (24, 48, 26) and face_size_histogram(m) == {3: 8, 4: 18}
    # cube corner (1, 1, 1) on the top face: 0.25 along both edges, (0.75, 1, 0.75)
    points = np.abs(np.array([m.position(v) for f in front for v in m.face_vertices(f)]))
    assert sorted(set(points.ravel().round(12))) == [0.75, 1.0]
    assert ((points == 1.0).sum(axis=1) == 1).all()


def test_modified_corner_cut_variant_2_ignores_the_corners_angle():
    """Subdivide2's x = thickness: on the tetrahedron's 60-degree corners each
    point lies on the bisector, thickness * |n1 + n2| = thickness * sqrt(3) away."""
    m = tetrahedron()
    old = m.positions_view().copy()
    front = modified_corner_cut(m, 0.1, 2)
    validate(m)
    assert m.counts() == (12, 24, 14) and face_size_histogram(m) == {3: 8, 4: 6}
    points = np.array([m.position(v) for f in front for v in m.face_vertices(f)])
    nearest = np.linalg.norm(points[:, None] - old[None], axis=2).min(axis=1)
    np.testing.assert_allclose(nearest, 0.1 * np.sqrt(3.0))


@pytest.mark.parametrize("variant", [3, 0, True, 2.0, "2", None])
def test_a_bad_variant_is_refused_before_the_budget(variant):
    assert_refused(cube(), lambda m: modified_corner_cut(m, 0.25, variant, max_faces=1),
                   "variant must be 1", InvalidArgumentError)


def test_modified_corner_cut_variants_differ_and_others_are_refused():
    first, second = cube(), cube()
    modified_corner_cut(first, 0.25)
    modified_corner_cut(second, 0.25, 2)
    assert not np.allclose(first.positions_view(), second.positions_view())
    assert_refused(cube(), lambda m: modified_corner_cut(m, 0.25, 3),
                   r"variant must be 1 \(TopMod's modifiedCornerCuttingSubdivide\) or 2")
def test_a_corner_cut_keeps_each_face_colour_on_its_inner_polygon():
    m = rainbow_cube()
    modified_corner_cut(m)
    validate(m)
    # an inner polygon per face; 12 edge quads and 8 vertex triangles have no one source
    assert colour_counts(m) == {**{f: 1 for f in range(6)}, None: 20}


def test_a_wireframe_colours_the_tube_around_each_face_opening():
    m = rainbow_cube()
    wireframe(m, 0.1)
    validate(m)
    # 4 tube quads around each face's opening; the bars' outer and inner faces none
    counts = colour_counts(m)
    assert {f: counts[f] for f in range(6)} == {f: 4 for f in range(6)}
    assert counts[None] == m.num_faces - 24


# -- corner cuts and columns of tiny meshes are the scaled unit ones


@pytest.mark.parametrize("make", [cube, icosahedron])
def test_the_corner_cut_of_a_tiny_mesh_is_the_scaled_unit_one(make):
    # neighbours closer than an absolute 1e-3 were taken for a 2-gon's: every
    # corner of a mesh 1e-150 across was cut toward the wrong corner
    assert_scales(make, lambda m, s: modified_corner_cut(m, 0.1 * s), scale=1e-150)


def test_the_columns_of_a_tiny_mesh_are_the_scaled_unit_ones():
    # rings sat an absolute 1e-4 out, where rings 1e-151 wide round to points
    # ("a convex hull needs 4 points not all in one plane")
    assert_scales(cube, lambda m, s: columns(m, 0.1 * s, 4), scale=1e-150)
