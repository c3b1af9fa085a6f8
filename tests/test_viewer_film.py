"""Films of a script's build (livemod.viewer.film): a frame per step, one framing."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from livemod.dlfl import DLFLError
from livemod.runner.stepshots import shoot_steps
from livemod.view import Animation, film
from livemod.viewer.film import film_cameras, render_film, shot_captions
from livemod.viewer.pictures import View

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
    with pytest.raises(DLFLError, match=rf"^{broken}:3: "):
        film(broken)
    idle = tmp_path / "idle.py"
    idle.write_text("x = 1\n")
    with pytest.raises(DLFLError, match=r"idle\.py has no steps; nothing to film$"):
        film(idle)
