"""The stepping controller (GL-free), driven against a recording fake session."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from livemod.viewer.runs import RunTracker
from livemod.viewer.stepping import HIGHEST_RATE, LOWEST_RATE, Stepping

from .viewer_support import FakePlayback


@pytest.fixture
def stepping() -> tuple[Stepping, FakePlayback, list[str]]:
    session, said = FakePlayback(), []
    return Stepping(RunTracker(), lambda: session, said.append), session, said


def test_the_rate_halves_and_doubles_within_its_bounds(stepping) -> None:
    control, session, said = stepping
    assert control.rate == 2.0
    control.faster()
    control.slower()
    control.slower()
    assert control.rate == 1.0 and said == ["play rate: 4 steps/s", "play rate: 2 steps/s",
                                            "play rate: 1 steps/s"]
    assert session.calls == []  # not playing: the rate waits for Space
    for _ in range(12):
        control.faster()
    assert control.rate == HIGHEST_RATE and said[-1] == "play rate: 64 steps/s"
    for _ in range(12):
        control.slower()
    assert control.rate == LOWEST_RATE and said[-1] == "play rate: 0.125 steps/s"


def test_a_rate_changed_while_playing_plays_at_once(stepping) -> None:
    control, session, _ = stepping
    control.faster()
    control.play_pause()
    assert control.playing and control.runs.waiting
    control.faster()
    control.slower()
    assert session.calls == [("play", 4.0), ("play", 8.0), ("play", 4.0)]
    control.play_pause()
    assert session.calls[-1] == ("pause",) and not control.playing
    assert not control.runs.waiting


def test_the_hud_shows_the_rate() -> None:
    from livemod.viewer.hud import hud_lines
    from livemod.viewer.view_state import ViewState

    def mode_line(state: ViewState) -> str:
        return next(text for text, _ in hud_lines(state) if text.startswith("pick "))

    assert mode_line(ViewState()) == "pick face  persp  mesh  rate 2 steps/s"
    assert mode_line(ViewState(playing=True, rate=0.5)) == \
        "pick face  persp  mesh  playing 0.5 steps/s"




def _result(status: str = "ok", steps: int = 3, step_index: int | None = None,
            run_id: int = 1) -> SimpleNamespace:
    return SimpleNamespace(run_id=run_id, status=status, steps=tuple(range(steps)),
                           step_index=step_index, arrays=None, error=None)


def test_a_step_key_with_nowhere_to_go_says_so_and_waits_for_nothing(stepping) -> None:
    control, session, said = stepping
    control.runs.take(_result())  # at the end of a run of 3 steps
    control.step_forward()
    control.run_to_end()
    assert said == ["at the last step (Left, Home or the timeline go back)",
                    "already at the end"]
    assert session.calls == [("step_forward",), ("run_to_end",)] and not control.runs.waiting
    control.runs.take(_result("paused", step_index=0))
    control.step_back()
    assert said[-1] == "at the first step" and not control.runs.waiting
    control.runs.take(_result("error", steps=0))  # a syntax error
    for key in (control.step_forward, control.step_back, control.first_step):
        key()
    assert said[-3:] == ["no steps"] * 3
    assert ("goto_step", 0) not in session.calls  # (a replay would fail again)


def test_a_step_key_with_a_step_to_go_to_waits_for_it(stepping) -> None:
    control, session, said = stepping
    control.runs.take(_result("paused", step_index=1))
    control.step_forward()
    assert control.runs.waiting and session.calls == [("step_forward",)]
    control.runs.take(_result("paused", step_index=2))
    control.step_back()
    control.runs.take(_result("paused", step_index=1))
    control.first_step()
    control.runs.take(_result("paused", step_index=0))
    control.reload()
    assert session.calls[1:] == [("step_back",), ("goto_step", 0), ("reload",)]
    assert control.runs.waiting and said == []


def test_playing_stops_at_a_runs_end_not_at_a_step_or_a_preview(stepping) -> None:
    control, _, _ = stepping
    shown = _result("paused", step_index=0)
    control.runs.take(shown)
    control.play_pause()
    control.result_arrived(shown, _result("paused", step_index=1))
    assert control.playing
    ended = _result()
    control.result_arrived(shown, ended)
    assert not control.playing
    control.playing = True
    control.result_arrived(ended, _result())  # the same end, posted with its preview
    assert control.playing


def test_a_held_step_key_repeats_once_each_step_arrived(stepping) -> None:
    from livemod.viewer.stepping import REPEAT_DELAY, REPEAT_INTERVAL

    control, session, _ = stepping
    clock = [10.0]
    control.clock = lambda: clock[0]
    control.runs.take(_result("paused", step_index=0, steps=1))
    control.step_forward()
    control.hold("right", "step_forward")  # it went somewhere: held
    assert control.held is not None and control.held.due == 10.0 + REPEAT_DELAY
    clock[0] += REPEAT_DELAY
    control.repeat_held()
    assert session.calls == [("step_forward",)]  # the step before has not arrived
    control.runs.take(_result("paused", step_index=1, steps=2))
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
    control, _, said = stepping
    clock = [0.0]
    control.clock = lambda: clock[0]
    control.runs.take(_result("paused", step_index=1))
    control.step_forward()
    control.hold("right", "step_forward")
    control.runs.take(_result())  # the last step
    clock[0] = 5.0
    control.repeat_held()
    assert control.held is None and said == ["at the last step (Left, Home or the "
                                             "timeline go back)"]


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
