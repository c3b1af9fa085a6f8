"""Tests of livemod.dlfl.commands.colors: setFaceColor, selectFacesByColor, faceInfo."""

from __future__ import annotations

import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import DLFLError, RunContext, Scene, Selection, use_scene
from tests.meshes import cube


@pytest.fixture
def scene() -> Scene:
    sc = Scene()
    sc.add(cube())
    return sc


def test_set_read_and_select_colours_in_a_script(scene: Scene):
    with use_scene(scene):
        assert dlfl.setFaceColor([0, 1], (1, 0.5, 0)) == [0, 1]
        dlfl.setFaceColor(2, (0, 0, 1))
        assert dlfl.faceInfo(0)["color"] == (1.0, 0.5, 0.0)
        assert dlfl.faceInfo(3)["color"] is None
        assert dlfl.selectFacesByColor((1, 0.5, 0)) == [0, 1]
        assert dlfl.selectFacesByColor(2) == [2]
        assert dlfl.selectFacesByColor(None) == [3, 4, 5]


def test_set_face_color_colours_the_selection_when_given_none(scene: Scene):
    scene.selection = Selection(faces=(4, 5))
    with use_scene(scene):
        assert dlfl.setFaceColor(None, (0, 1, 0)) == [4, 5]
    assert scene.mesh.face_color(5) == (0.0, 1.0, 0.0)


def test_set_face_color_is_a_step_and_select_is_not(scene: Scene, run: RunContext):
    labels: list[str] = []
    run.step_hook = labels.append
    with use_scene(scene):
        dlfl.setFaceColor(0, (1, 0, 0))
        dlfl.selectFacesByColor((1, 0, 0))
    assert labels == ["setFaceColor"]


def test_a_bad_colour_is_refused_with_the_mesh_unchanged(scene: Scene):
    with use_scene(scene), pytest.raises(DLFLError, match=r"divide 0-255 values by 255"):
        dlfl.setFaceColor([0, 1], (255, 128, 0))
    assert scene.mesh.face_colors() is None
