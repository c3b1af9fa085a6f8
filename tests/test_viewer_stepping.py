"""Stepping: the controller on its own (GL-free, against a recording fake session),
then every step key and the timeline from every playback state through the window's
own key handling (headless, the real session): the window never sticks (issue 24,
section 2).

The controller waits only for the results the session says are coming, and says
when none is. The window's script makes six vertices, one step each; before its
fourth step it waits while a gate file exists, so that a run can be held at work
("running to the end") for as long as a test needs. The states: finished (the run
ended, its last step shown), paused at a step in the middle, paused at the first
step, playing, and running to the end.
"""

from __future__ import annotations

import io
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from types import SimpleNamespace

import pytest

from livemod.runner.playback import PlaybackState, PlaybackView
from livemod.viewer.runs import RunTracker
from livemod.viewer.stepping import REPEAT_DELAY, REPEAT_INTERVAL, Stepping
from livemod.viewer.window import LiveViewer, ViewOptions, close_viewer, create_viewer

from .viewer_support import FakePlayback, frames_until, press_key

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
    session.state = PlaybackState.PLAYING
    assert control.playing and control.view == PlaybackView(PlaybackState.PLAYING, None, 2.0)


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
    session.state = PlaybackState.RUNNING
    control.run_to_end()  # a run at work goes on to its end anyway
    assert said[-1] == "running to the end"


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

    assert mode_line(ViewState()) == "pick face  persp  mesh  finished, rate 2 steps/s"
    assert mode_line(ViewState(playback=PlaybackState.PLAYING, rate=0.5)) == \
        "pick face  persp  mesh  playing 0.5 steps/s"
    assert mode_line(ViewState(playback=PlaybackState.PAUSED, rate=4.0)) == \
        "pick face  persp  mesh  paused, rate 4 steps/s"


# -- through the window, from every playback state -----------------------------

STEPS = 6
GATED_AFTER = 3  # steps done when a run waits at the gate

SCRIPT = """
import os, time
from livemod.dlfl import createVertex
for i in range({steps}):
    if i == {gated}:
        open({mark!r}, "w").close()
        while os.path.exists({gate!r}):
            time.sleep(0.005)
    createVertex((i, 0, 0))
"""


@dataclass
class Window:
    """A headless window on the gated script, its terminal, and the gate's files."""

    viewer: LiveViewer
    echo: io.StringIO
    gate: Path
    mark: Path

    def press(self, key: str, shift: bool = False) -> None:
        press_key(self.viewer, key, shift=shift)

    def settle(self, done: Callable[[LiveViewer], bool] | None = None) -> None:
        """Draw frames until the window waits for nothing, no run works, nothing
        plays (and ``done`` holds)."""
        frames_until(self.viewer, lambda v: _settled(v) and (done is None or done(v)),
                     timeout=20.0)

    def shown(self) -> tuple[str, int | None]:
        """``(status, step index)`` of the result shown."""
        result = self.viewer.result
        return result.status, result.step_index

    def hud(self) -> str:
        from livemod.viewer.hud import hud_lines

        return "\n".join(text for text, _ in hud_lines(self.viewer.view_state()))


def _settled(viewer: LiveViewer) -> bool:
    return (viewer.result is not None and not viewer.waiting and viewer.runs.activity is None
            and not viewer.stepping.playing)


@pytest.fixture
def window(tmp_path: Path) -> Iterator[Window]:
    control = tmp_path / "control"
    control.mkdir()
    gate, mark = control / "gate", control / "at_gate"
    script = tmp_path / "six.py"
    script.write_text(SCRIPT.format(steps=STEPS, gated=GATED_AFTER, gate=str(gate),
                                    mark=str(mark)))
    echo = io.StringIO()
    viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(400, 300),
                                       samples=0, vsync=False, echo=echo))
    try:
        state = Window(viewer, echo, gate, mark)
        state.settle(lambda v: v.result.status == "ok")
        yield state
    finally:
        gate.unlink(missing_ok=True)
        close_viewer(viewer)


# -- reaching each state ------------------------------------------------------------


def _finished(w: Window) -> None:
    assert w.shown() == ("ok", None) and w.viewer.runs.steps() == STEPS


def _paused_at(k: int) -> Callable[[Window], None]:
    def reach(w: Window) -> None:
        w.press("HOME")
        w.settle(lambda v: v.result.status == "paused" and v.result.step_index == 0)
        for step in range(1, k + 1):
            w.press("RIGHT")
            w.settle(lambda v, s=step: v.result.step_index == s)
        assert w.shown() == ("paused", k)
    return reach


def _playing(w: Window) -> None:
    w.press("EQUAL")  # 4 steps a second: long enough to act while it plays
    w.press("SPACE")
    frames_until(w.viewer, lambda v: v.stepping.playing and v.result.status == "paused"
                 and v.result.step_index >= 1)


def _running(w: Window) -> None:
    w.gate.touch()
    w.press("R")
    frames_until(w.viewer, lambda v: w.mark.exists() and v.runs.activity is not None)


STATES = {"finished": _finished, "paused": _paused_at(2), "first": _paused_at(0),
          "playing": _playing, "running": _running}


def _act(w: Window, action: str) -> None:
    """Press ``action``'s key (or click the timeline at step 4), then let a held
    run go on."""
    if action.startswith("timeline"):
        _click_timeline(w.viewer, int(action.split()[1]))
    else:
        key, _, modifier = action.partition("+")
        w.press(key, shift=modifier == "shift")
    w.gate.unlink(missing_ok=True)


def _click_timeline(viewer: LiveViewer, step: int) -> None:
    overlay, size = viewer.overlay, viewer.screen_size
    _, y, _, height = overlay.timeline.frame(size)
    x = next(px for px in range(size[0]) if overlay.timeline_step(px, size) == step)
    viewer.on_mouse_press_event(x, int(y + height - 8), viewer.wnd.mouse.left)
    viewer.on_mouse_release_event(x, int(y + height - 8), viewer.wnd.mouse.left)


# -- what each action leads to, from each state -------------------------------------

END = ("ok", None)
ANY_PAUSE = "paused somewhere"

EXPECTED: dict[tuple[str, str], object] = {
    ("finished", "SPACE"): END,  # played from the first step to the end again
    ("finished", "RIGHT"): END,  # nowhere to go: it says so
    ("finished", "LEFT"): ("paused", STEPS - 2),
    ("finished", "HOME"): ("paused", 0),
    ("finished", "END"): END,  # already there: it says so
    ("finished", "R"): END,
    ("finished", "timeline 4"): ("paused", 4),
    ("paused", "SPACE"): END,  # plays on from step 2
    ("paused", "RIGHT"): ("paused", 3),
    ("paused", "LEFT"): ("paused", 1),
    ("paused", "HOME"): ("paused", 0),
    ("paused", "END"): END,
    ("paused", "R"): ("paused", 2),  # a new run holds where the last one was held
    ("paused", "timeline 4"): ("paused", 4),
    ("first", "SPACE"): END,
    ("first", "RIGHT"): ("paused", 1),
    ("first", "LEFT"): ("paused", 0),  # nowhere to go: it says so
    ("first", "HOME"): ("paused", 0),
    ("first", "END"): END,
    ("first", "R"): ("paused", 0),
    ("first", "timeline 4"): ("paused", 4),
    ("playing", "SPACE"): ANY_PAUSE,
    ("playing", "RIGHT"): ANY_PAUSE,
    ("playing", "LEFT"): ANY_PAUSE,
    ("playing", "HOME"): ("paused", 0),
    ("playing", "END"): END,
    ("playing", "R"): END,  # the new run plays on to its end
    ("playing", "timeline 4"): ("paused", 4),
    ("running", "SPACE"): END,  # plays from where the run is to its end
    ("running", "RIGHT"): ("paused", GATED_AFTER),  # the run stops at its next step
    ("running", "LEFT"): ("paused", GATED_AFTER - 2),
    ("running", "HOME"): ("paused", 0),
    ("running", "END"): END,
    ("running", "R"): END,
    ("running", "timeline 4"): ("paused", 4),
}
# where each state comes to rest by itself: the rate keys change how fast it plays,
# nothing else
AT_REST = {"finished": END, "paused": ("paused", 2), "first": ("paused", 0),
           "playing": END, "running": END}
EXPECTED.update({(state, key): rest for state, rest in AT_REST.items()
                 for key in ("MINUS", "EQUAL")})


def _showing(expected: object) -> Callable[[LiveViewer], bool]:
    """The window shows ``expected``: a ``(status, step index)``, or any pause."""
    def shows(viewer: LiveViewer) -> bool:
        result = viewer.result
        if expected == ANY_PAUSE:
            return result.status == "paused"
        return (result.status, result.step_index) == expected
    return shows


def _state_line(w: Window) -> str:
    return w.hud().splitlines()[1]


@pytest.mark.parametrize(("state", "action"), list(EXPECTED))
def test_every_action_from_every_state_ends_where_it_should(window: Window, state: str,
                                                            action: str) -> None:
    """A result arriving late (a preview posted after its mesh) may show for a
    frame or two; what counts is where the window comes to rest, and that it does."""
    STATES[state](window)
    said_before = window.echo.getvalue()
    _act(window, action)
    window.settle(_showing(EXPECTED[(state, action)]))
    status = window.shown()[0]
    assert _state_line(window).startswith("paused" if status == "paused" else "ok")
    said = window.echo.getvalue()[len(said_before):]
    if (state, action) in NOWHERE_TO_GO:
        assert said.count(NOWHERE_TO_GO[(state, action)]) == 1
    assert not any(note in said for note in NOWHERE_TO_GO.values()) or \
        (state, action) in NOWHERE_TO_GO


# the actions that change nothing, and what the terminal says instead
NOWHERE_TO_GO = {
    ("finished", "RIGHT"): "at the last step (Left, Home or the timeline go back)",
    ("finished", "END"): "already at the end",
    ("first", "LEFT"): "at the first step",
    ("running", "END"): "running to the end",
}


def test_space_to_the_end_then_left_then_end_ends(window: Window) -> None:
    window.press("SPACE")
    window.settle(lambda v: v.result.run_id >= 2 and _showing(END)(v))
    window.press("LEFT")
    window.settle(_showing(("paused", STEPS - 2)))
    window.press("END")
    window.settle(_showing(END))
    assert _state_line(window).startswith("ok")


def test_home_then_end_ends(window: Window) -> None:
    window.press("HOME")
    window.settle(_showing(("paused", 0)))
    window.press("END")
    window.settle(_showing(END))
    assert _state_line(window).startswith("ok")


def test_a_run_after_a_playback_goes_straight_to_its_end(window: Window) -> None:
    """After Space played a run to its end, a save with more steps does not pause at
    each new step: its first result is its end."""
    taken: list[tuple[int, str]] = []
    take = window.viewer.runs.take
    window.viewer.runs.take = lambda result: (taken.append((result.run_id, result.status)),
                                              take(result))[1]
    window.press("EQUAL")
    window.press("EQUAL")
    window.press("SPACE")
    window.settle(lambda v: v.result.run_id >= 2)
    script = Path(window.viewer.script)
    script.write_text(script.read_text().replace(f"range({STEPS})", f"range({STEPS + 4})"))
    window.settle(lambda v: v.result.run_id >= 3)
    assert window.shown() == END and window.viewer.runs.steps() == STEPS + 4
    assert [status for run, status in taken if run >= 3] == ["ok"]
