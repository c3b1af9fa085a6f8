"""Regression tests for the sculpting gaps the review left (session 22): crusts of
meshes with no face normals, straight (edge-split) vertices, rind's scale check
order, and connect_faces_closest's id check."""

from __future__ import annotations

import re

import numpy as np
import pytest

from livemod.dlfl import from_polygons, validate
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.connect import closest_corners, connect_faces_closest
from livemod.dlfl.errors import GeometryError, InvalidArgumentError, UnknownIdError
from livemod.dlfl.rind import crust_offsets, rind
from livemod.dlfl.shapes import cube
from livemod.dlfl.sponge import sponge
from tests.meshes import assert_refused

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


def _split_edge_cube():
    """The edge-2 cube with edge 0 ((1,1,1)-(1,1,-1)) split at (1,1,0): vertex 8,
    both of whose corners are straight."""
    m = cube()
    assert m.subdivide_edge(0) == [8]
    return m


# ------------------------------------------------------------ no face normal


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


# ------------------------------------------------------------ straight vertices


@pytest.mark.parametrize("uniform", [True, False])
def test_the_inner_copy_of_a_vertex_on_a_split_edge_moves_with_its_edge(uniform):
    # its corners are straight (no corner normal): it stayed on the outer shell
    m = _split_edge_cube()
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


def test_the_sponge_of_a_cube_with_a_split_edge_takes_the_default_thickness():
    m = _split_edge_cube()
    assert sponge(m) == 0.67
    validate(m)
    p = m.positions_view()
    # the split vertex's inner copy is on the inner shell's edge, not the outer one
    assert any(np.allclose(q, [0.33, 0.33, 0], atol=1e-12) for q in p)
    assert not any(np.allclose(q, [1, 1, 0], atol=1e-12) for q in p[9:])


# ------------------------------------------------------------ scale check order


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


# ------------------------------------------------------------ connect_faces_closest ids


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
