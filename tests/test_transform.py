"""Vectorized transforms: translate, scale, rotate, move_vertices, bad input."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import validate
from livemod.dlfl.errors import InvalidArgumentError, UnknownIdError
from livemod.dlfl.shapes import cube
from livemod.dlfl.transform import (
    move_vertices,
    rotate,
    rotation_matrix,
    scale,
    transform,
    translate,
)
from tests.meshes import assert_refused, assert_refused_quietly, snapshot
from tests.meshes import cube as unit_cube

BASE = cube().positions_view()


def test_translate_all_and_some():
    m = cube()
    translate(m, (1, 2, 3))
    np.testing.assert_allclose(m.positions_view(), BASE + [1, 2, 3])
    translate(m, (-1, -2, -3), vertices=[0])
    np.testing.assert_allclose(m.position(0), BASE[0])
    np.testing.assert_allclose(m.positions_view()[1:], BASE[1:] + [1, 2, 3])


def test_scale_per_axis_and_uniform_about_a_centre():
    m = cube()
    scale(m, (2, 1, 0.5))
    np.testing.assert_allclose(m.positions_view(), BASE * [2, 1, 0.5])
    m = cube()
    scale(m, 3, center=(1, 1, 1))
    np.testing.assert_allclose(m.positions_view(), (BASE - 1) * 3 + 1)


def test_rotate_a_quarter_turn_about_z():
    m = cube()
    rotate(m, (0, 0, 1), 90)
    expected = np.stack([-BASE[:, 1], BASE[:, 0], BASE[:, 2]], 1)
    np.testing.assert_allclose(m.positions_view(), expected, atol=1e-12)
    validate(m)


def test_rotation_matrix_is_orthonormal_and_right_handed():
    r = rotation_matrix((1, 2, 3), 37)
    np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert np.isclose(np.linalg.det(r), 1.0)
    np.testing.assert_allclose(rotation_matrix((0, 0, 5), 90) @ [1, 0, 0], [0, 1, 0], atol=1e-12)


def test_rotate_about_a_centre_keeps_it_fixed():
    m = cube()
    rotate(m, (1, 0, 0), 180, center=(1, 1, 1))
    np.testing.assert_allclose(m.position(0), (1, 1, 1))


def test_move_vertices_relative_and_absolute():
    m = cube()
    move_vertices(m, [0, 1], (0, 1, 0))
    np.testing.assert_allclose(m.positions_view()[:2], BASE[:2] + [0, 1, 0])
    move_vertices(m, [2, 3], (5, 5, 5), relative=False)
    np.testing.assert_allclose(m.positions_view()[2:4], [[5, 5, 5]] * 2)


def test_transform_with_a_matrix():
    m = cube()
    transform(m, np.diag([1, -1, 1]))
    np.testing.assert_allclose(m.positions_view(), BASE * [1, -1, 1])


@pytest.mark.parametrize(("call", "error"), [
    (lambda m: translate(m, (1, 2)), InvalidArgumentError),
    (lambda m: translate(m, (1, 2, float("nan"))), InvalidArgumentError),
    (lambda m: scale(m, "big"), InvalidArgumentError),
    (lambda m: rotate(m, (0, 0, 0), 30), InvalidArgumentError),
    (lambda m: transform(m, np.eye(2)), InvalidArgumentError),
    (lambda m: move_vertices(m, [0, 99], (1, 1, 1)), UnknownIdError),
    (lambda m: translate(m, (1, 1, 1), vertices=[99]), UnknownIdError),
])
def test_bad_input_raises_and_leaves_the_mesh_unchanged(call, error):
    m = cube()
    before = snapshot(m)
    with pytest.raises(error):
        call(m)
    assert snapshot(m) == before


@pytest.mark.parametrize(("call", "message"), [
    (lambda m: rotate(m, (0, 0, 1), None), "degrees must be a number"),
    (lambda m: rotate(m, (0, 0, 1), float("nan")), "degrees must be finite"),
    (lambda m: translate(m, (1, 0, 0), vertices=[None]), "vertices must hold ids"),
    (lambda m: translate(m, (1, 0, 0), vertices=[0.5]), "vertices must hold ids"),
    (lambda m: move_vertices(m, [True], (1, 0, 0)), "vertices must hold ids"),
])
def test_bad_arguments_are_refused_and_move_nothing(call, message):
    assert_refused(cube(), call, message, error=InvalidArgumentError)


@pytest.mark.parametrize("call", [
    lambda m: translate(m, (1.7e308, 0, 0)),
    lambda m: move_vertices(m, [0, 1], (1.7e308, 0, 0)),
    lambda m: scale(m, 1e308, center=(1e308, 0, 0)),
    lambda m: transform(m, np.full((3, 3), 1e308)),
    lambda m: rotate(m, (0, 0, 1), 45, center=(1.7e308, 1.7e308, 0)),
])
def test_moves_that_overflow_are_refused_without_numpy_warnings(call):
    big = cube()
    translate(big, (1.7e308, 0, 0))  # every x at 1.7e308 plus or minus 1
    assert_refused_quietly(big, call, r"the transform would move vertex \d+ to \[.*inf")


def test_a_huge_or_tiny_axis_rotates_like_the_unit_one():
    # the norm of (1e308, 1e308, 0) overflowed and the axis became zero: no rotation
    for axis in [(1e308, 1e308, 0), (1e-200, 1e-200, 0)]:
        np.testing.assert_allclose(rotation_matrix(axis, 45), rotation_matrix((1, 1, 0), 45))


# -- a matrix or flag of the wrong type and deleted vertices are refused by name


@pytest.mark.parametrize("matrix", ["abc", [[1, 2], [3]]])
def test_transform_refuses_a_matrix_that_is_not_numbers(matrix):
    assert_refused(unit_cube(), lambda m: transform(m, matrix),
                   "matrix must be a finite 3x3 array", error=InvalidArgumentError)


def test_move_vertices_refuses_a_string_flag():
    assert_refused(unit_cube(), lambda m: move_vertices(m, [0], (1, 1, 1), relative="False"),
                   "relative must be True or False", error=InvalidArgumentError)


def test_transform_of_a_deleted_vertex_says_it_was_deleted():
    m = unit_cube()
    m.collapse_edge(0)
    gone = next(v for v in range(8) if not m.has_vertex(v))
    assert_refused(m, lambda m: translate(m, (1, 0, 0), vertices=[gone]),
                   f"vertex {gone} was deleted", error=UnknownIdError)
    assert_refused(m, lambda m: translate(m, (1, 0, 0), vertices=[99]), "vertex 99 does not exist",
                   error=UnknownIdError)
