"""The stepping controller (GL-free), driven against a recording fake session."""

from __future__ import annotations

import pytest

from livemod.viewer.runs import RunTracker
from livemod.viewer.stepping import HIGHEST_RATE, LOWEST_RATE, Stepping


class FakePlayback:
    """Records the playback calls it gets, in order."""

    def __init__(self) -> None:
        self.calls: list[tuple] = []

    def __getattr__(self, name: str):
        if name.startswith("_"):
            raise AttributeError(name)
        return lambda *args: self.calls.append((name, *args))


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


