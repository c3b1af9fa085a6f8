"""Films of a script's build (livemod.viewer.film): a frame per step, one framing."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest
from PIL import Image

from livemod.cli import main as livemod_main
from livemod.dlfl import InvalidArgumentError
from livemod.dlfl.io import save_mesh
from livemod.dlfl.shapes import cube
from livemod.runner import ScriptFailedError
from livemod.runner.stepshots import shoot_steps
from livemod.view import Animation, film
from livemod.viewer.film import film_cameras, render_film, shot_captions
from livemod.viewer.headless import Framing
from livemod.viewer.pictures import View
from tests.images import read_image

from .conftest import OFFSCREEN_SIZE

SCRIPTS = Path(__file__).resolve().parents[1] / "scripts"


def _covered(image: np.ndarray) -> np.ndarray:
    return np.any(np.abs(image.astype(int) - image[0, 0]) > 12, axis=2)


def test_the_captions_word_each_step_as_the_hud_does():
    shots = shoot_steps(SCRIPTS / "steps_demo.py", which={0, 2, 11})
    assert shot_captions(shots) == ["step 1/12: load cube (line 9)",
                                    "step 3/12: extrude (line 13)",
                                    "step 12/12: smoothed (line 16)"]


def test_one_framing_holds_the_whole_build_and_the_camera_turns_per_frame():
    shots = shoot_steps(SCRIPTS / "steps_demo.py")
    cameras = film_cameras(shots, View((160, 120), elevation=20.0, yaw=350.0), turn=5.0)
    assert [camera.yaw for camera in cameras] == [(350.0 + 5.0 * k) % 360 for k in range(12)]
    assert len({camera.distance for camera in cameras}) == 1
    assert all(np.array_equal(camera.target, cameras[0].target) for camera in cameras)
    assert {camera.pitch for camera in cameras} == {20.0}


def test_the_film_s_framing_takes_the_view_s_zoom_margin_and_projection():
    shots = shoot_steps(SCRIPTS / "steps_demo.py", which={0, 11})
    plain = film_cameras(shots, View((160, 120)))[0]
    zoomed = film_cameras(shots, View((160, 120), framing=Framing(zoom=2.0)))[0]
    tight = film_cameras(shots, View((160, 120), framing=Framing(margin=0.0)))[0]
    assert zoomed.distance == pytest.approx(plain.distance / 2)
    assert tight.distance == pytest.approx(plain.distance / 1.06)  # the default border
    assert film_cameras(shots, View((160, 120), ortho=True))[0].ortho and not plain.ortho


def test_every_frame_shows_its_step_inside_the_frame(offscreen: Any):
    shots = shoot_steps(SCRIPTS / "steps_demo.py")
    done: list[tuple[int, int]] = []
    frames = render_film(offscreen, shots, View(), turn=10.0, captions=False,
                         progress=lambda k, n: done.append((k, n)))
    assert len(frames) == 12 and done[-1] == (12, 12)
    assert all(frame.shape == (*OFFSCREEN_SIZE[::-1], 3) for frame in frames)
    drawn = [_covered(frame) for frame in frames]
    for mask in drawn:  # framed for the tallest step: nothing touches the border
        assert mask.any() and not (mask[0].any() or mask[-1].any()
                                   or mask[:, 0].any() or mask[:, -1].any())
    # the build grows in place: the last step's tower is taller than the first cube
    heights = [np.ptp(np.nonzero(mask.any(axis=1))[0]) for mask in drawn]
    assert heights[-1] > 1.5 * heights[0]


def test_a_caption_is_drawn_at_the_bottom_left(offscreen: Any):
    shots = shoot_steps(SCRIPTS / "steps_demo.py", which={3})
    plain = render_film(offscreen, shots, View(), captions=False)[0]
    captioned = render_film(offscreen, shots, View(), captions=True)[0]
    changed = np.any(plain != captioned, axis=2)
    rows, columns = np.nonzero(changed)
    assert changed.any() and rows.min() > OFFSCREEN_SIZE[1] // 2
    assert columns.min() < 16


def test_film_runs_a_script_with_its_parameters(tmp_path: Path):
    made = film(SCRIPTS / "tower.py", parameters={"storeys": 2}, size=(64, 64), fps=5.0)
    assert isinstance(made, Animation) and made.fps == 5.0
    # load, an extrusion and a step() per storey, two duals, a subdivision
    assert len(made.frames) == 1 + 2 * 2 + 3
    assert made.frames[0].shape == (64, 64, 3)
    assert made.save(tmp_path / "build.webp") == [tmp_path / "build.webp"]


def test_film_refuses_a_failing_script_and_one_without_steps(tmp_path: Path):
    broken = tmp_path / "broken.py"
    broken.write_text("from livemod.dlfl import *\nload('cube')\nextrude('nosuch', 0)\n")
    with pytest.raises(ScriptFailedError, match=rf"^{broken}:3: ") as failed:
        film(broken)
    assert (failed.value.error.file, failed.value.error.line) == (str(broken), 3)
    idle = tmp_path / "idle.py"
    idle.write_text("x = 1\n")
    with pytest.raises(InvalidArgumentError, match=r"idle\.py has no steps; nothing to film$"):
        film(idle)
    with pytest.raises(InvalidArgumentError, match=r"^the run declared no parameter 'floors' \(it "
                                        r"declared: storeys, height, twist, swell\)"):
        film(SCRIPTS / "tower.py", parameters={"floors": 2})


# -- livemod render --steps / --step ---------------------------------------------------


def _render(script: Path, out: Path, *extra: str) -> int:
    return livemod_main(["render", str(script), "-o", str(out), "--size", "160x120", *extra])


def test_render_steps_films_a_frame_per_step(tmp_path: Path, offscreen: Any,
                                             capsys: pytest.CaptureFixture[str]):
    steps = len(shoot_steps(SCRIPTS / "steps_demo.py").outcome.steps)
    assert _render(SCRIPTS / "steps_demo.py", tmp_path / "build.gif", "--steps", "--turn", "5",
                   "--captions", "--fps", "4") == 0
    assert capsys.readouterr().out == f"wrote {tmp_path / 'build.gif'}\n"
    with Image.open(tmp_path / "build.gif") as gif:
        assert gif.n_frames == steps and gif.size == (160, 120)
        assert gif.info["duration"] == 250
    assert _render(SCRIPTS / "steps_demo.py", tmp_path / "frames", "--steps") == 0
    written = sorted((tmp_path / "frames").iterdir())
    assert [path.name for path in written] == [f"frame_{k:03d}.png" for k in range(steps)]
    # the frames render_film draws, without MSAA (the film default) as the shared target
    films = render_film(offscreen, shoot_steps(SCRIPTS / "steps_demo.py"), View(),
                        captions=False)
    for path, frame in zip(written, films, strict=True):
        assert np.array_equal(read_image(path), frame)


def test_render_step_draws_the_scene_a_step_left_and_compares_it(tmp_path: Path):
    golden, again = tmp_path / "golden.png", tmp_path / "again.png"
    assert _render(SCRIPTS / "tower.py", golden, "--set", "storeys=2", "--step", "1") == 0
    assert _render(SCRIPTS / "tower.py", again, "--set", "storeys=2", "--step", "1",
                   "--reference", str(golden)) == 0
    assert _render(SCRIPTS / "tower.py", again, "--set", "storeys=2", "--step", "7",
                   "--reference", str(golden)) == 1  # the subdivided tower is not the cube
    captioned = tmp_path / "captioned.png"
    assert _render(SCRIPTS / "tower.py", captioned, "--set", "storeys=2", "--step", "1",
                   "--captions") == 0
    changed = np.any(read_image(captioned) != read_image(golden), axis=2)
    assert changed.any() and np.nonzero(changed)[0].min() > 60  # in the bottom half


def test_render_steps_says_which_steps_a_script_has(tmp_path: Path,
                                                    capsys: pytest.CaptureFixture[str]):
    assert _render(SCRIPTS / "steps_demo.py", tmp_path / "x.png", "--step", "12") == 1
    assert capsys.readouterr().err == (f"livemod: error: {SCRIPTS / 'steps_demo.py'} has steps "
                                       f"0 to 11; no step 12\n")
    broken = tmp_path / "broken.py"
    broken.write_text("from livemod.dlfl import *\nload('cube')\nextrude('nosuch', 0)\n")
    assert _render(broken, tmp_path / "b.gif", "--steps") == 1
    assert capsys.readouterr().err.startswith(f"livemod: error: {broken}:3: ")
    assert not (tmp_path / "x.png").exists() and not (tmp_path / "b.gif").exists()


@pytest.mark.parametrize(("extra", "message"), [
    (("--steps", "--step", "2"), "--steps films every step and --step K draws one"),
    (("--steps", "--turntable", "4"), "leave out --turntable and --preview"),
    (("--step", "1", "--preview"), "leave out --turntable and --preview"),
    (("--steps", "--reference", "ref.png"), "--reference compares one picture: give "
                                            "--step K, not --steps"),
    (("--turn", "4"), "--turn turns the camera from frame to frame of --steps"),
    (("--step", "1", "--turn", "4"), "--turn turns the camera from frame to frame"),
    (("--captions",), "--captions needs --steps or --step"),
])
def test_render_refuses_film_options_that_do_not_go_together(
        tmp_path: Path, capsys: pytest.CaptureFixture[str], extra: tuple[str, ...],
        message: str):
    out = tmp_path / "out.gif"
    assert _render(SCRIPTS / "steps_demo.py", out, *extra) == 2
    assert message in capsys.readouterr().err and not out.exists()


def test_render_steps_needs_a_script_and_a_file_of_several_frames(
        tmp_path: Path, capsys: pytest.CaptureFixture[str]):
    mesh = tmp_path / "cube.obj"
    save_mesh(cube(), str(mesh))
    assert _render(mesh, tmp_path / "c.gif", "--steps") == 2
    assert f"--steps and --step need a script, not {str(mesh)!r}" in capsys.readouterr().err
    assert _render(SCRIPTS / "steps_demo.py", tmp_path / "one.png", "--steps") == 2
    assert "not one PNG" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        _render(SCRIPTS / "steps_demo.py", tmp_path / "x.gif", "--steps", "--turn", "spin")
    assert "the turn must be a number of degrees, not 'spin'" in capsys.readouterr().err
