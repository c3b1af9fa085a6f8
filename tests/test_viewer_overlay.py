"""The overlay (GL-free): which panels are up, where they lie, and their cached quads."""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

from livemod.dlfl.params import make_spec
from livemod.viewer.look import Look
from livemod.viewer.objects import SceneObjects
from livemod.viewer.overlay import Overlay
from livemod.viewer.parameters import Parameters
from livemod.viewer.runs import RunTracker
from livemod.viewer.text import MARGIN
from livemod.viewer.view_state import ViewState

SIZE = (800, 600)


def _overlay() -> tuple[Overlay, Look, RunTracker, Parameters, SceneObjects]:
    look, runs = Look(), RunTracker()
    session = SimpleNamespace(parameters={})
    parameters = Parameters(runs, lambda: session, print)
    objects = SceneObjects(runs, look, print, lambda others: None)
    return Overlay(look, runs, parameters, objects), look, runs, parameters, objects


def _steps(count: int) -> SimpleNamespace:
    return SimpleNamespace(run_id=1, status="ok", steps=tuple(range(count)), step_index=None,
                           error=None, arrays=None)


def test_the_timeline_is_up_with_the_panels_for_two_steps_or_more() -> None:
    overlay, look, runs, _, _ = _overlay()
    runs.take(_steps(1))
    assert not overlay.timeline_shown() and overlay.error_room(SIZE) == 0.0
    runs.take(_steps(2))
    assert overlay.timeline_shown()
    assert overlay.error_room(SIZE) == overlay.timeline.frame(SIZE)[3] + MARGIN
    _, y, _, height = overlay.timeline.frame(SIZE)
    assert overlay.timeline_hit(400, y + height / 2, SIZE)
    assert overlay.timeline_step(10_000, SIZE) == 1
    look.toggle_help()  # the help hides the panels
    assert not overlay.timeline_shown() and not overlay.timeline_hit(400, y + height / 2, SIZE)
    assert overlay.parameters_hit(790, 20, SIZE) is None


def test_the_object_list_lies_below_the_parameters() -> None:
    overlay, _, _, parameters, objects = _overlay()
    overlay.lay_out(SIZE)
    assert objects.panel.top == MARGIN  # no parameters: at the top
    parameters.sync(SimpleNamespace(parameters=(make_spec("n", 1),), error=None))
    overlay.lay_out(SIZE)
    assert objects.panel.top == parameters.panel.bottom(SIZE) + MARGIN
    x, top, _, _ = parameters.panel.frame(SIZE)
    assert overlay.parameters_hit(x + 5, top + 5, SIZE) is not None


def test_quads_are_laid_out_again_only_for_another_state() -> None:
    overlay = _overlay()[0]
    state = ViewState(script="/x/model.py", size=SIZE)
    first = overlay.quads(state)
    assert overlay.quads(replace(state)) is first  # equal: the cached quads
    assert overlay.quads(replace(state, fps=60.0)) is not first
