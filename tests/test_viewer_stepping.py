"""The stepping controller (GL-free), driven against a recording fake session: the
session's state machine decides what is shown; the controller waits only for the
results the session says are coming, and says when none is."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from livemod.runner.playback import PlaybackState, PlaybackView
from livemod.viewer.runs import RunTracker
from livemod.viewer.stepping import REPEAT_DELAY, REPEAT_INTERVAL, Stepping

from .viewer_support import FakePlayback

AT_THE_LAST = "at the last step (Left, Home or the timeline go back)"


@pytest.fixture
def stepping() -> tuple[Stepping, FakePlayback, list[str]]:
    session, said = FakePlayback(), []
    return Stepping(RunTracker(), lambda: session, said.append), session, said


def _result(status: str = "ok", steps: int = 3, step_index: int | None = None,
            run_id: int = 1) -> SimpleNamespace:
    return SimpleNamespace(run_id=run_id, status=status, steps=tuple(range(steps)),
                           step_index=step_index, arrays=None, error=None)


def test_the_rate_keys_ask_the_session_and_say_its_rate(stepping) -> None:
    control, session, said = stepping
    assert control.rate == 2.0
    control.faster()
    control.faster()
    control.slower()
    assert control.rate == session.play_rate == 4.0
    assert said == ["play rate: 4 steps/s", "play rate: 8 steps/s", "play rate: 4 steps/s"]
    for _ in range(6):
        control.slower()
    assert said[-1] == "play rate: 0.25 steps/s"  # where the session stops halving
    assert session.calls == [] and not control.runs.waiting  # no result comes of it


def test_playing_is_the_sessions_state(stepping) -> None:
    control, session, _ = stepping
    assert not control.playing
    session.playback = PlaybackView(PlaybackState.PLAYING, 2, 4.0)
    assert control.playing


def test_space_waits_for_a_result_only_when_one_comes(stepping) -> None:
    control, session, said = stepping
    control.play_pause()
    assert session.calls == [("toggle_play",)] and control.runs.waiting
    control.runs.take(_result("paused", step_index=1))
    session.coming["toggle_play"] = False  # a pause where the run is held: nothing comes
    control.play_pause()
    assert not control.runs.waiting and said == []


def test_a_step_key_with_nowhere_to_go_says_so_and_waits_for_nothing(stepping) -> None:
    control, session, said = stepping
    session.coming.update(step_forward=False, step_back=False, goto_step=False,
                          run_to_end=False)
    control.runs.take(_result())  # the end of a run of 3 steps
    control.step_forward()
    control.run_to_end()
    control.runs.take(_result("paused", step_index=0))
    control.step_back()
    control.first_step()
    assert said == [AT_THE_LAST, "already at the end", "at the first step", "at the first step"]
    control.runs.take(_result("error", steps=0))  # a syntax error: no steps
    for key in (control.step_forward, control.step_back, control.first_step):
        key()
    assert said[-3:] == ["no steps"] * 3 and not control.runs.waiting


def test_a_step_key_with_a_step_to_go_to_waits_for_it(stepping) -> None:
    control, session, said = stepping
    control.runs.take(_result("paused", step_index=1))
    for key in (control.step_forward, control.step_back, control.first_step,
                control.run_to_end, control.reload):
        control.runs.waiting = False
        key()
        assert control.runs.waiting
    control.goto(2)
    assert session.calls == [("step_forward",), ("step_back",), ("goto_step", 0),
                             ("run_to_end",), ("reload",), ("goto_step", 2)]
    assert said == []


def test_a_held_step_key_repeats_once_each_step_arrived(stepping) -> None:
    control, session, _ = stepping
    clock = [10.0]
    control.clock = lambda: clock[0]
    control.runs.take(_result("paused", step_index=0))
    control.step_forward()
    control.hold("right", "step_forward")  # it went somewhere: held
    assert control.held is not None and control.held.due == 10.0 + REPEAT_DELAY
    clock[0] += REPEAT_DELAY
    control.repeat_held()
    assert session.calls == [("step_forward",)]  # the step before has not arrived
    control.runs.take(_result("paused", step_index=1))
    control.repeat_held()
    assert session.calls == [("step_forward",)] * 2
    assert control.held.due == clock[0] + REPEAT_INTERVAL
    control.release("left")  # another key's release
    assert control.held is not None
    control.release("right")
    assert control.held is None
    control.hold("w", "toggle_edges")  # not a step key
    control.hold("right", None)  # an unbound key
    assert control.held is None


def test_a_held_key_at_the_last_step_stops_repeating(stepping) -> None:
    control, session, said = stepping
    clock = [0.0]
    control.clock = lambda: clock[0]
    control.runs.take(_result("paused", step_index=1))
    control.step_forward()
    control.hold("right", "step_forward")
    control.runs.take(_result())  # the last step
    session.coming["step_forward"] = False
    clock[0] = 5.0
    control.repeat_held()
    assert control.held is None and said == [AT_THE_LAST]


def test_the_timeline_goes_to_a_step_once_the_pointer_rests_or_lets_go(stepping) -> None:
    control, session, _ = stepping
    control.runs.take(_result(steps=10))
    control.scrub_to(3)
    control.flush_scrub()  # still moving: not yet
    assert control.scrubbing and session.calls == []
    control.scrub_to(6)
    control.end_scrub()
    assert not control.scrubbing and session.calls == [("goto_step", 6)]
    assert control.scrub_step is None and control.runs.waiting
    control.runs.take(_result("paused", steps=7, step_index=6))
    control.scrub_to(6)  # the step shown: nothing to do
    control.end_scrub()
    assert session.calls == [("goto_step", 6)]


def test_the_hud_shows_the_rate() -> None:
    from livemod.viewer.hud import hud_lines
    from livemod.viewer.view_state import ViewState

    def mode_line(state: ViewState) -> str:
        return next(text for text, _ in hud_lines(state) if text.startswith("pick "))

    assert mode_line(ViewState()) == "pick face  persp  mesh  rate 2 steps/s"
    assert mode_line(ViewState(playing=True, rate=0.5)) == \
        "pick face  persp  mesh  playing 0.5 steps/s"
