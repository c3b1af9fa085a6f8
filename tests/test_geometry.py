"""Geometry-only operations and TopMod's cleanup helpers."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from livemod.dlfl import DLFLError, Mesh, face_size_histogram, validate
from livemod.dlfl.analysis import face_normals
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.geometry import (
    cleanup_2gons,
    cleanup_winged_vertices,
    edge_cleanup,
    mesh_smooth,
    planarize,
    spheralize,
    split_valence2_vertices,
)
from livemod.dlfl.shapes import cube, spherical_cube, torus
from tests.meshes import assert_refused, assert_refused_quietly, assert_scales, snapshot
from tests.meshes import cube as unit_cube


def bumped_cube():
    m = cube()
    m.set_position(0, (1.3, 1.2, 1.1))
    return m


def non_planarity(mesh):
    """Largest distance of a corner from its face's centroid plane."""
    a = mesh_arrays(mesh)
    normals = face_normals(a)[a.corner_face]
    sums = np.zeros((len(a.face_ids), 3))
    np.add.at(sums, a.corner_face, a.positions[a.corner_vertex])
    centres = (sums / a.face_sizes[:, None])[a.corner_face]
    return np.abs(np.einsum("ij,ij->i", a.positions[a.corner_vertex] - centres, normals)).max()


def test_smoothing_keeps_the_cube_and_its_topology():
    m = cube()
    mesh_smooth(m, 3)
    validate(m)
    assert m.counts() == (8, 12, 6)
    np.testing.assert_allclose(m.positions_view(), cube().positions_view(), atol=1e-12)


def test_smoothing_moves_only_tangentially():
    m = spherical_cube(4)
    before = m.positions_view()
    mesh_smooth(m)
    after = m.positions_view()
    assert not np.allclose(before, after)
    # a round mesh stays nearly round: tangential moves barely change the radius
    assert np.abs(np.linalg.norm(after, axis=1) - 1).max() < 0.1


def test_smoothing_rejects_negative_iterations():
    with pytest.raises(DLFLError):
        mesh_smooth(cube(), -1)


def test_planarize_flattens_faces():
    m = bumped_cube()
    before = non_planarity(m)
    planarize(m)
    validate(m)
    assert m.counts() == (8, 12, 6)
    assert non_planarity(m) < before / 5


def test_planarize_rejects_negative_steps():
    with pytest.raises(DLFLError):
        planarize(cube(), -3)


def test_spheralize_puts_vertices_on_the_unit_sphere_about_the_centroid():
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * 3 + 5)
    spheralize(m)
    np.testing.assert_allclose(np.linalg.norm(m.positions_view(), axis=1), 1.0)
    np.testing.assert_allclose(m.positions_view(), cube().positions_view() / np.sqrt(3))


def test_edge_cleanup_removes_a_face_diagonal():
    m = cube()
    c = m.face_corners(0)
    m.insert_edge(c[0], c[2])
    assert m.counts() == (8, 13, 7)
    assert edge_cleanup(m) == 1
    validate(m)
    assert m.counts() == (8, 12, 6)
    assert edge_cleanup(cube()) == 0


def test_cleanup_2gons():
    m = cube()
    c = m.face_corners(0)
    m.insert_edge(c[0], c[1])  # adjacent corners: a 2-gon
    assert face_size_histogram(m)[2] == 1
    assert cleanup_2gons(m) == 1
    validate(m)
    assert m.counts() == (8, 12, 6)


def test_cleanup_winged_vertices_undoes_an_edge_split():
    m = cube()
    m.subdivide_edge(0)
    assert cleanup_winged_vertices(m) == 1
    validate(m)
    assert m.counts() == (8, 12, 6)


def test_split_valence2_vertices_pushes_the_pair_apart():
    m = cube()
    (v,) = m.subdivide_edge(0)
    origin = m.position(v)
    new = split_valence2_vertices(m, 0.2)
    validate(m)
    assert len(new) == 1 and m.counts() == (10, 14, 6)
    d = m.position(v) - m.position(new[0])
    assert np.isclose(np.linalg.norm(d), 0.4)
    np.testing.assert_allclose((m.position(v) + m.position(new[0])) / 2, origin)


def test_geometry_ops_keep_torus_topology():
    m = torus()
    before = snapshot(m)
    for op in (mesh_smooth, planarize, spheralize):
        op(m)
        validate(m)
    after = snapshot(m)
    assert after[2:] != () and m.counts() == (48, 96, 48)
    assert before[0] != after[0]


@pytest.mark.parametrize(("call", "message"), [
    (lambda m: mesh_smooth(m, 1.5), "iterations must be an integer >= 0"),
    (lambda m: mesh_smooth(m, "2"), "iterations must be an integer >= 0"),
    (lambda m: planarize(m, None), "steps must be an integer >= 0"),
    (lambda m: planarize(m, 2.5), "steps must be an integer >= 0"),
    (lambda m: split_valence2_vertices(m, "2"), "offset must be a number"),
])
def test_arguments_of_the_wrong_type_are_refused(call, message):
    assert_refused(cube(), call, message)


def _far_cube_with_valence2_vertices() -> Mesh:
    """A unit cube with a valence-2 vertex on edge 0-1, then one on edge 2-6 moved
    to (1.79e308, 1.79e308, 0): its new neighbour's push overflows."""
    m = unit_cube()
    for ends in ((0, 1), (2, 6)):
        edge = next(e for e in m.edge_ids().tolist() if set(m.edge_vertices(e)) == set(ends))
        new = m.subdivide_edge(edge)[0]
    m.set_position(new, (1.79e308, 1.79e308, 0.0))
    return m


def test_split_valence2_vertices_that_overflow_change_nothing():
    # the first split succeeds, the second overflows
    assert_refused_quietly(_far_cube_with_valence2_vertices(),
                           lambda m: split_valence2_vertices(m, -1.0),
                           r"splitting valence-2 vertex \d+ by .* would put .* not finite")


def _cube_with_valence2_vertices() -> Mesh:
    m = unit_cube()
    for edge in m.edge_ids()[:2].tolist():
        m.subdivide_edge(edge)
    return m


@pytest.mark.parametrize("scale", [1e160, 1e300])
def test_a_huge_mesh_splits_valence2_vertices_like_the_unit_one(scale):
    # the edge lengths and directions were measured raw: inf, then a NaN position
    # ("expected a position ... of three finite numbers") for a result that exists
    assert_scales(_cube_with_valence2_vertices, lambda m, s: split_valence2_vertices(m, -1.0),
                  scale)


@pytest.mark.parametrize("scale", [1e160, 1.5e308])
def test_a_huge_mesh_spheralizes_like_the_unit_one(scale):
    # raw norms overflowed to inf (every vertex went to the origin); the centroid's
    # sum overflowed near the float maximum
    small, big = unit_cube(), unit_cube()
    big.set_positions(big.vertex_ids(), big.positions_view() * scale)
    spheralize(small)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        spheralize(big)
    np.testing.assert_allclose(big.positions_view(), small.positions_view(), atol=1e-15)


def test_a_mesh_near_the_float_maximum_smooths_like_the_unit_one():
    # the face centroids' sums overflowed: "positions must be finite numbers"
    assert_scales(_diagonal_bumped_cube, lambda m, s: mesh_smooth(m, 2), 1e308)


def _spread_cube() -> Mesh:
    """A unit cube moved 1 along x but for vertex 0, moved to x = -1."""
    m = unit_cube()
    m.set_positions(m.vertex_ids(), m.positions_view() + [1.0, 0.0, 0.0])
    m.set_position(0, (-1.0, 0.0, 0.0))
    return m


def test_a_mesh_spread_over_the_float_range_smooths_like_the_unit_one():
    # vertex 0's move (about 2.1e308) overflowed: refused, though it ends in range
    assert_scales(_spread_cube, lambda m, s: mesh_smooth(m, 2), 8e307)


def test_cleanup_winged_vertices_keeps_a_vertex_whose_faces_are_2gons():
    m = Mesh()
    m.create_face([(0, 0, 0), (1, 0, 0), (0, 1, 0)])  # two-sided: every vertex has valence 2
    assert cleanup_winged_vertices(m) == 1  # then the other two sit on two 2-gons
    validate(m)
    assert m.counts() == (2, 2, 2)


def _diagonal_bumped_cube():
    m = bumped_cube()
    c = m.face_corners(2)  # a flat face (vertex 0 is the bumped one): a removable diagonal
    m.insert_edge(c[0], c[2])
    return m


@pytest.mark.parametrize("op", [lambda m, s: mesh_smooth(m, 3),
                                lambda m, s: planarize(m, 20), lambda m, s: edge_cleanup(m)])
def test_a_huge_mesh_smooths_and_flattens_like_the_unit_one(op):
    # the face normals of raw products overflowed past ~1e77 and came out zero
    assert_scales(_diagonal_bumped_cube, op)
