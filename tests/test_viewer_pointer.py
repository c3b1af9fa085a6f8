"""The mouse (GL-free): panels and the timeline first, the camera after."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from livemod.dlfl.params import make_spec
from livemod.viewer.camera import Camera
from livemod.viewer.look import Look
from livemod.viewer.objects import SceneObjects
from livemod.viewer.overlay import Overlay
from livemod.viewer.parameters import Parameters
from livemod.viewer.pointer import CLICK_SLOP, Buttons, Pointer
from livemod.viewer.runs import RunTracker
from livemod.viewer.stepping import Stepping

from .viewer_support import FakePlayback

SIZE = (800, 600)


@pytest.fixture
def parts() -> SimpleNamespace:
    look, runs, playback = Look(), RunTracker(), FakePlayback()
    session = SimpleNamespace(parameters={}, set_parameters=lambda values: None)
    parameters = Parameters(runs, lambda: session, print)
    parameters.sync(SimpleNamespace(parameters=(make_spec("n", 1, min=0, max=4),), error=None))
    objects = SceneObjects(runs, look, print, lambda others: None)
    stepping = Stepping(runs, lambda: playback, print)
    overlay = Overlay(look, runs, parameters, objects)
    camera = Camera()
    pointer = Pointer(overlay, parameters, objects, stepping, camera, lambda: (SIZE, 1.0))
    runs.take(SimpleNamespace(run_id=1, status="ok", steps=tuple(range(10)), step_index=None,
                              error=None, arrays=None, other_objects=()))
    return SimpleNamespace(pointer=pointer, camera=camera, parameters=parameters,
                           stepping=stepping, playback=playback, overlay=overlay)


def test_a_press_that_does_not_move_is_a_click(parts) -> None:
    pointer, camera = parts.pointer, parts.camera
    pointer.press(300, 300)
    pointer.drag(300 + CLICK_SLOP, 300, CLICK_SLOP, 0, Buttons(left=True))
    assert pointer.release()  # (moved no more than the slop)
    yaw = camera.yaw
    pointer.press(300, 300)
    pointer.drag(320, 300, 20, 0, Buttons(left=True))
    assert not pointer.release() and camera.yaw == pytest.approx((yaw - 8.0) % 360)


def test_shift_or_another_button_pans(parts) -> None:
    pointer, camera = parts.pointer, parts.camera
    target, yaw = camera.target.copy(), camera.yaw
    pointer.press(300, 300)
    pointer.drag(310, 300, 10, 0, Buttons(left=True, shift=True))
    pointer.drag(320, 300, 10, 0, Buttons(middle=True))
    assert camera.yaw == yaw and (camera.target != target).any()


def test_the_timeline_scrubs_and_goes_where_it_is_let_go(parts) -> None:
    pointer, overlay = parts.pointer, parts.overlay
    _, y, _, height = overlay.timeline.frame(SIZE)
    x_of = {overlay.timeline_step(px, SIZE): px for px in range(SIZE[0], 0, -1)}
    pointer.press(x_of[2], y + height - 4)
    pointer.drag(x_of[7], y + height - 4, 5, 0, Buttons(left=True))
    assert parts.stepping.scrubbing and parts.stepping.scrub_step == 7
    assert not pointer.release()  # not a click on the model
    assert parts.playback.calls == [("goto_step", 7)]


def test_a_press_on_the_parameters_panel_drags_its_slider(parts) -> None:
    pointer, parameters = parts.pointer, parts.parameters
    left, width, _ = parameters.panel._control_x(SIZE)
    _, top, _, row_height = parameters.panel.frame(SIZE)
    row = top + 6 + 1.5 * row_height
    pointer.press(left, row)
    pointer.drag(left + width, row, width, 0, Buttons(left=True))
    assert parameters.panel.values["n"] == 4
    assert not pointer.release() and parameters.dragged is None
    pointer.move(left, row)
    assert parameters.panel.hover == 0


def test_the_wheel_zooms_off_the_object_list(parts) -> None:
    pointer, camera = parts.pointer, parts.camera
    distance = camera.distance
    pointer.move(10, 590)
    pointer.scroll(1.0)
    assert camera.distance == pytest.approx(distance * 0.9)
