"""Tests of livemod.dlfl.colors: setting many face colours, selecting by colour."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import DLFLError, InvalidArgumentError
from livemod.dlfl.colors import (
    MODELLING_COLOR,
    faces_by_color,
    filled_colors,
    rgba_bytes,
    set_face_colors,
)
from tests.meshes import assert_refused, cube

RED, BLUE = (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)


def test_set_face_colors_takes_one_id_or_many_and_none_clears():
    m = cube()
    assert set_face_colors(m, 2, RED) == [2]
    assert set_face_colors(m, np.array([3, 4]), BLUE) == [3, 4]
    assert [m.face_color(f) for f in range(6)] == [None, None, RED, BLUE, BLUE, None]
    set_face_colors(m, [3], None)
    assert m.face_color(3) is None


@pytest.mark.parametrize(("faces", "color", "error", "message"), [
    ([1, 99], RED, DLFLError, "face 99 does not exist"),
    ([1, 2.0], RED, InvalidArgumentError, "faces must hold ids"),
    ("12", RED, InvalidArgumentError, "faces must be a list of ids"),
    ([1], (255, 0, 0), InvalidArgumentError, r"divide 0-255 values by 255"),
    ([1], "red", InvalidArgumentError, r"colour must be three numbers"),
])
def test_a_refused_call_colours_no_face(faces, color, error, message):
    m = cube()
    m.set_face_color(1, BLUE)
    assert_refused(m, lambda mesh: set_face_colors(mesh, faces, color), message, error)


def test_faces_by_color_finds_the_faces_within_the_tolerance():
    m = cube()
    set_face_colors(m, [0, 2], RED)
    m.set_face_color(4, (0.999, 0.0, 0.0))
    m.set_face_color(5, (0.9, 0.0, 0.0))
    assert faces_by_color(m, RED) == [0, 2, 4]  # 0.999 is 255 in 8 bits too
    assert faces_by_color(m, RED, 0.0) == [0, 2]
    assert faces_by_color(m, RED, 0.11) == [0, 2, 4, 5]
    assert faces_by_color(m, RED, 0.09) == [0, 2, 4]
    assert faces_by_color(m, 5) == [5]  # a face id: that face's colour
    assert faces_by_color(m, None) == [1, 3] == faces_by_color(m, 1)
    assert faces_by_color(cube(), None) == list(range(6))
    assert faces_by_color(cube(), RED) == []


def test_faces_by_color_leaves_holes_out():
    m = cube()
    set_face_colors(m, [0, 1], RED)
    m.set_hole(1)
    assert faces_by_color(m, RED) == [0]


@pytest.mark.parametrize(("color", "tolerance", "message"), [
    (RED, -0.1, "tolerance must be >= 0"), (RED, float("nan"), "tolerance must be finite"),
    ((1, 2), 0.0, "colour must be three numbers"), (99, 0.0, "face 99 does not exist")])
def test_faces_by_color_refuses_bad_arguments(color, tolerance, message):
    with pytest.raises(DLFLError, match=message):
        faces_by_color(cube(), color, tolerance)


def test_filled_colors_puts_the_modelling_colour_where_there_is_none():
    colors = np.array([[0.5, 0.5, 0.5], [np.nan] * 3], dtype=np.float32)
    filled = filled_colors(colors)
    assert filled[0].tolist() == [0.5, 0.5, 0.5]
    assert filled[1].tolist() == np.float32(MODELLING_COLOR).tolist()
    assert np.isnan(colors[1]).all()  # the argument is not changed


def test_rgba_bytes_rounds_each_channel_and_zeroes_faces_without_colour():
    colors = np.array([[1.0, 0.5, 0.0], [np.nan] * 3, [0.2, 1 / 255, 0.998]], np.float32)
    assert rgba_bytes(colors).tolist() == [[255, 128, 0, 255], [0, 0, 0, 0], [51, 1, 254, 255]]
    assert rgba_bytes(colors).dtype == np.uint8
    assert rgba_bytes(None) is None
