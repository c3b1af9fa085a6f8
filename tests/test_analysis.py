"""Tests of livemod.dlfl.analysis: normals, centroids, bounds, components, genus."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from livemod.dlfl import (
    Mesh,
    bounds,
    component_genera,
    euler_characteristic,
    face_centroids,
    face_normals,
    face_size_histogram,
    from_polygons,
    genus,
    mesh_arrays,
    num_components,
    summarize,
    vertex_normals,
)
from livemod.dlfl.analysis import (
    component_of_vertices,
    corner_normals,
    enclosed_volume,
    face_areas,
    face_centroid,
    face_normal,
    polygon_normal,
    surface_area,
)
from tests.meshes import (
    CUBE_FACES,
    CUBE_OUTWARD,
    CUBE_POSITIONS,
    cube,
    path_face,
    tetrahedron,
    torus,
    torus_polygons,
    triangle,
    two_cubes,
)


def test_two_cubes_are_genus_zero_each():
    m = two_cubes()
    assert num_components(m) == 2
    assert component_genera(m) == [0, 0]
    assert genus(m) == 0  # not TopMod's 1 - (V - E + F) / 2 = -1
    assert euler_characteristic(m) == 4


def test_torus_and_handles():
    assert component_genera(torus(6, 4)) == [1]
    m = cube()
    m.insert_edge(0, 4)
    assert genus(m) == 1
    m2 = two_cubes()
    m2.insert_edge(0, 4)  # a handle on the first cube only
    assert component_genera(m2) == [1, 0]


def test_point_spheres_are_components():
    m = cube()
    m.create_vertex((9.0, 9.0, 9.0))
    vlab, flab = component_of_vertices(m)
    assert vlab.tolist() == [0] * 8 + [1]
    assert flab.tolist() == [0] * 6 + [1]
    assert component_genera(m) == [0, 0]
    assert num_components(Mesh()) == 0 and component_genera(Mesh()) == []


def test_cube_normals_point_outward():
    normals = face_normals(cube())
    np.testing.assert_allclose(normals, CUBE_OUTWARD, atol=1e-12)
    vn = vertex_normals(cube())
    np.testing.assert_allclose(vn[6], np.ones(3) / np.sqrt(3))
    cn = corner_normals(cube())
    np.testing.assert_allclose(cn[:4], [CUBE_OUTWARD[0]] * 4, atol=1e-12)


def test_concave_corner_normal_is_flipped_to_the_face_side():
    l_shape = np.array([[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]], float)
    np.testing.assert_allclose(polygon_normal(l_shape), [0, 0, 1], atol=1e-12)


def test_degenerate_faces_have_zero_normals():
    normals = face_normals(path_face())
    np.testing.assert_allclose(normals, np.zeros((1, 3)))
    assert polygon_normal(np.zeros((2, 3))).tolist() == [0, 0, 0]


def test_centroids_areas_and_bounds():
    m = cube()
    np.testing.assert_allclose(face_centroids(m)[1], [0.5, 0.5, 1.0])
    np.testing.assert_allclose(face_centroid(m, 3), [1.0, 0.5, 0.5])
    np.testing.assert_allclose(face_areas(m), np.ones(6))
    np.testing.assert_allclose(face_normal(m, 4), [0, 1, 0])
    np.testing.assert_allclose(bounds(m), [[0, 0, 0], [1, 1, 1]])
    np.testing.assert_allclose(bounds(two_cubes()), [[0, 0, 0], [4, 1, 1]])
    assert bounds(Mesh()).tolist() == [[0, 0, 0], [0, 0, 0]]


def test_histogram_and_summary():
    m = triangle()
    assert face_size_histogram(m) == {3: 1}
    assert face_size_histogram(m, holes=True) == {3: 2}
    s = summarize(tetrahedron())
    assert (s.vertices, s.edges, s.faces, s.holes, s.genus) == (4, 6, 4, 0, 0)
    assert s.components == 1 and s.face_sizes == {3: 4}
    m = cube()
    m.create_vertex()
    assert summarize(m).point_spheres == 1 and summarize(m).component_genera == [0, 0]


def _scaled_cube(scale: float) -> Mesh:
    mesh = cube()
    mesh.set_positions(mesh.vertex_ids(), mesh.positions_view() * scale)
    return mesh


@pytest.mark.parametrize("scale", [1e150, 1e-150, 1e300, 1e-300, 3.0 ** 200])
def test_normals_do_not_depend_on_the_scale_of_the_mesh(scale):
    # cross products of raw coordinates overflowed (or underflowed) past ~1e77
    # and the normals came out zero
    unit = mesh_arrays(cube())
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        big = mesh_arrays(_scaled_cube(scale))
        got = (face_normals(big), corner_normals(big), vertex_normals(big))
        polygon = polygon_normal(big.positions[big.corner_vertex[:4]])
    for g, want in zip(got, (face_normals(unit), corner_normals(unit), vertex_normals(unit)),
                       strict=True):
        np.testing.assert_allclose(g, want, rtol=0, atol=1e-12)
    np.testing.assert_allclose(polygon, face_normals(unit)[0], rtol=0, atol=1e-12)


@pytest.mark.parametrize("scale", [1e150, 1e-150])
def test_face_areas_scale_with_the_square_of_the_mesh(scale):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        areas = face_areas(_scaled_cube(scale))
    np.testing.assert_allclose(areas / scale / scale, np.ones(6), rtol=1e-12)


def test_face_areas_beyond_the_float_range_are_inf_without_a_warning():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        areas = face_areas(_scaled_cube(1e200))
    assert np.isinf(areas).all()


@pytest.mark.parametrize("offset", [1e12, 1e15])
def test_a_small_face_far_from_the_origin_keeps_its_normal_and_area(offset):
    # Newell's sum of p_i x p_{i+1} cancelled there: a wrong area, a flipped normal
    square = np.array([[0.0, 0.0, 0.0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]) + offset
    mesh = from_polygons(square, [[0, 1, 2, 3]])
    np.testing.assert_allclose(face_areas(mesh), [1.0, 1.0], rtol=1e-12)
    np.testing.assert_array_equal(face_normals(mesh)[0], [0.0, 0.0, 1.0])
    np.testing.assert_array_equal(corner_normals(mesh)[:4], [[0.0, 0.0, 1.0]] * 4)
    np.testing.assert_array_equal(polygon_normal(square), [0.0, 0.0, 1.0])


def test_volume_and_area_of_closed_meshes():
    assert enclosed_volume(cube()) == pytest.approx(1.0) and surface_area(cube()) == 6.0
    assert enclosed_volume(tetrahedron()) == pytest.approx(1 / 6)
    assert enclosed_volume(two_cubes()) == pytest.approx(2.0)
    pos, quads = torus_polygons(64, 48)
    # a polygonal torus: between its inscribed and its smooth volume
    smooth = 2 * np.pi**2 * 3.0 * 1.0**2
    assert 0.99 * smooth < enclosed_volume(from_polygons(pos, quads)) < smooth
    m = cube()
    m.create_vertex()  # a point-sphere encloses nothing and changes nothing
    assert enclosed_volume(m) == pytest.approx(1.0)
    assert enclosed_volume(Mesh()) == 0.0


def test_volume_is_signed_and_counts_a_crust_as_its_material():
    from livemod.dlfl.rind import crust

    inside_out = from_polygons(CUBE_POSITIONS, [face[::-1] for face in CUBE_FACES])
    assert enclosed_volume(inside_out) == pytest.approx(-1.0)
    shell = cube()
    crust(shell, 0.25)  # the inner cube, of side 0.5, faces inward
    assert enclosed_volume(shell) == pytest.approx(1.0 - 0.5**3)


def test_an_open_mesh_encloses_no_volume():
    assert enclosed_volume(triangle()) is None
    assert enclosed_volume(from_polygons(CUBE_POSITIONS, CUBE_FACES[1:])) is None
    assert surface_area(from_polygons(CUBE_POSITIONS, CUBE_FACES[1:])) == 5.0


@pytest.mark.parametrize("scale, offset", [(1e-100, 0.0), (1e100, 0.0), (1.0, 1e12),
                                           (1e-3, -1e6)])
def test_volume_keeps_its_precision_at_any_scale_and_offset(scale, offset):
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * scale + offset)
    assert enclosed_volume(m) == pytest.approx(scale**3, rel=1e-9)


def test_volume_beyond_the_float_range_is_inf_without_a_warning():
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * 1e200)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert enclosed_volume(m) == np.inf

