"""Pictures of models in memory (livemod.viewer.pictures): notebooks' PNGs and
turntables, drawn as ``livemod render`` draws them."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from livemod.cli import main as livemod_main
from livemod.dlfl import Mesh, Scene, mesh_arrays
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.io import save_mesh
from livemod.dlfl.shapes import cube, tetrahedron
from livemod.runner import run_script
from livemod.viewer import pictures
from livemod.viewer.headless import NoOffscreenGL, Offscreen
from livemod.viewer.pictures import Animation, model_parts, picture, png_of, turntable
from tests.images import read_image


def _covered(image: np.ndarray) -> np.ndarray:
    """``(H, W)`` bool: pixels unlike the background (the top left one)."""
    return np.any(np.abs(image[..., :3].astype(int) - image[0, 0, :3]) > 12, axis=2)


def _blobs(image: np.ndarray) -> int:
    """How many runs of columns with something drawn the picture has."""
    columns = np.concatenate([[False], _covered(image).any(axis=0), [False]])
    return int(np.count_nonzero(np.diff(columns.astype(int)) == 1))


def _two_objects() -> Scene:
    scene = Scene()
    scene.add(cube(), "left")
    right = tetrahedron()
    for vid in right.vertex_ids():
        right.set_position(vid, right.position(vid) + (4.0, 0.0, 0.0))
    scene.add(right, "right")
    return scene


def test_a_picture_is_what_livemod_render_writes(tmp_path: Path):
    mesh = cube()
    save_mesh(mesh, str(tmp_path / "cube.obj"))
    assert livemod_main(["render", str(tmp_path / "cube.obj"), "--size", "480x360",
                         "-o", str(tmp_path / "cube.png")]) == 0
    shown = picture(mesh)
    assert shown.image.shape == (360, 480, 3)
    assert np.array_equal(shown.image, read_image(tmp_path / "cube.png"))
    assert np.array_equal(np.asarray(Image.open(io.BytesIO(shown._repr_png_()))), shown.image)
    assert shown.save(tmp_path / "again.png") == tmp_path / "again.png"
    assert np.array_equal(read_image(tmp_path / "again.png"), shown.image)


def test_a_scene_draws_its_current_object_and_the_others():
    scene = _two_objects()
    parts = model_parts(scene)
    assert parts.arrays is not None and parts.arrays.counts == (4, 6, 4)  # the current
    assert parts.others is not None and parts.others.counts == (8, 12, 6)
    assert parts.joined().counts == (12, 18, 10)
    assert _blobs(picture(scene).image) == 2 and _blobs(picture(scene.mesh).image) == 1


def test_a_run_s_result_shows_its_mesh_or_the_mesh_a_failed_run_left(tmp_path: Path):
    script = tmp_path / "model.py"
    script.write_text("from livemod.dlfl import *\nload('cube')\nsubdivide('catmull-clark')\n")
    result = run_script(script)
    assert model_parts(result).arrays.counts == (26, 48, 24)
    assert _covered(picture(result).image).mean() > 0.05
    script.write_text("from livemod.dlfl import *\nload('cube')\nraise ValueError('no')\n")
    failed = run_script(script)
    assert failed.arrays is None and model_parts(failed).arrays.counts == (8, 12, 6)
    assert np.array_equal(picture(failed).image, picture(cube()).image)


def test_nothing_to_draw_gives_no_picture_and_other_things_are_refused():
    assert png_of(Mesh()) is None and png_of(Scene()) is None
    assert Mesh()._repr_png_() is None
    with pytest.raises(InvalidArgumentError, match="a picture is of a Mesh, MeshArrays, "
                                                   "Scene or RunResult, not str"):
        picture("cube.obj")


def test_a_turntable_turns_the_model_and_shows_as_an_animated_png(tmp_path: Path):
    spin = turntable(mesh_arrays(tetrahedron()), frames=12, size=(96, 80), fps=20)
    assert isinstance(spin, Animation) and len(spin.frames) == 12
    assert all(frame.shape == (80, 96, 3) for frame in spin.frames)
    assert not np.array_equal(spin.frames[0], spin.frames[3])  # a quarter turn on
    shown = Image.open(io.BytesIO(spin._repr_png_()))
    assert shown.format == "PNG" and shown.is_animated and shown.n_frames == 12
    assert shown.info["duration"] == 50 and shown.info["loop"] == 0
    for index in (0, 7):
        shown.seek(index)
        assert np.array_equal(np.asarray(shown.convert("RGB")), spin.frames[index])
    assert spin.save(tmp_path / "spin.gif") == [tmp_path / "spin.gif"]
    with Image.open(tmp_path / "spin.gif") as gif:
        assert gif.n_frames == 12 and gif.size == (96, 80)


def test_a_turntable_needs_a_frame():
    with pytest.raises(InvalidArgumentError, match="at least one frame, not 0"):
        turntable(cube(), frames=0)


def test_without_offscreen_gl_the_hook_gives_none_and_says_why_once(
        monkeypatch: pytest.MonkeyPatch):
    def no_gl(*args: object, **kwargs: object) -> None:
        raise NoOffscreenGL("no EGL here")

    monkeypatch.setattr(pictures, "picture", no_gl)
    monkeypatch.setattr(pictures, "_NO_GL_SAID", [])
    with pytest.warns(RuntimeWarning, match="livemod draws no pictures here: no EGL here"):
        assert png_of(cube()) is None
    assert png_of(cube()) is None  # said once: a second warning would fail here


def test_pictures_of_each_size_are_drawn_in_a_kept_target_of_their_own():
    picture(cube(), size=(64, 48))
    picture(cube(), size=(48, 64))
    kept = [target for (size, _), target in pictures._TARGETS.items()
            if size in ((64, 48), (48, 64))]
    assert len(kept) == 2 and kept[0].ctx is not kept[1].ctx
    assert picture(cube(), size=(64, 48)).image.shape == (48, 64, 3)
    assert pictures.kept_target((64, 48), 4) is kept[0]  # made once


def test_a_picture_is_the_same_whichever_was_drawn_before(tmp_path: Path):
    first = picture(cube(), size=(50, 30))
    picture(tetrahedron(), size=(40, 30))  # another target and its context current
    other = Offscreen((16, 16), samples=0)  # and another context (a render command's)
    other.release()
    again = picture(cube(), size=(50, 30))
    assert np.array_equal(first.image, again.image) and _covered(first.image).any()
