"""LiveSession's playback, every action from every state: what is posted, in order.

Each case brings a fresh session into a state, takes one action and checks the
results posted (status, step, and whether they come from the run already
there or from a new one), what the action returned, and the playback's state
afterwards. The script has four steps and, after its second step, waits for a
gate file: the "running" state is a run waiting there (the gate opens right
after the action); in every other state the gate is open from the start.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Callable, Iterator
from dataclasses import dataclass

import pytest

from livemod.dlfl.arrays import mesh_arrays
from livemod.runner import LiveSession, RunResult
from livemod.runner.playback import MAX_RATE, MIN_RATE, PlaybackState

from .runner_scripts.support import drain, manual_session, next_result, wait_until

R, PL, PA, FI = (PlaybackState.RUNNING, PlaybackState.PLAYING, PlaybackState.PAUSED,
                 PlaybackState.FINISHED)
SLOW = 0.01  # steps a second: a play holds each step for 100 s (faster(): 4 s), longer than any case
QUIET = 0.3  # seconds without a result after the expected ones: nothing more comes

GATED = """import os, time
for i in range(4):
    createVertex((i, 0, 0))
    if i == {gate_at}:
        open({reached!r}, "a").close()
        while not os.path.exists({gate!r}):
            time.sleep(0.002)
"""


@dataclass
class Setup:
    """A session brought into a state, and the run its results came from."""

    live: LiveSession
    run_id: int
    gate: str


def _open_gate(gate: str) -> None:
    with open(gate, "a"):
        pass


@contextlib.contextmanager
def _session(tmp_path, gate_open: bool, gate_at: int = 1,  # noqa: ANN001
             **options: object) -> Iterator[tuple[LiveSession, str, str]]:
    """A started session on the gated script, waiting after step ``gate_at``;
    yields ``(session, gate file, file the script makes on reaching the gate)``."""
    gate, reached = str(tmp_path / "gate"), str(tmp_path / "reached")
    if gate_open:
        _open_gate(gate)
    path = tmp_path / "model.py"
    path.write_text(GATED.format(gate=gate, reached=reached, gate_at=gate_at))
    with manual_session(path, **options) as (live, _):
        yield live, gate, reached


def _ended(live: LiveSession) -> RunResult:
    return next_result(live, lambda r: r.status == "ok")


def _running(live: LiveSession, gate: str, reached: str) -> int:
    wait_until(lambda: os.path.exists(reached))  # the run waits after its second step
    return wait_until(lambda: live.activity).run_id


def _finished(live: LiveSession, gate: str, reached: str) -> int:
    return _ended(live).run_id


def _paused(live: LiveSession, gate: str, reached: str) -> int:
    _ended(live)
    live.play_rate = SLOW
    live.goto_step(1)  # nothing cached of a straight run: a replay holds at step 1
    return next_result(live, lambda r: r.status == "paused" and r.step_index == 1).run_id


def _playing(live: LiveSession, gate: str, reached: str) -> int:
    run_id = _paused(live, gate, reached)
    live.play()  # held at step 1 for 1 / SLOW seconds
    return run_id


def _behind(live: LiveSession, gate: str, reached: str) -> int:
    """Played to the end (every step cached), then one step back: a cached step
    of a run that has ended."""
    _ended(live)
    live.play(1000.0)
    run_id = _ended(live).run_id
    live.play_rate = SLOW
    live.step_back()
    assert next_result(live).step_index == 2
    return run_id


SETUPS: dict[str, Callable[[LiveSession, str, str], int]] = {
    "running": _running, "finished": _finished, "paused": _paused, "playing": _playing,
    "paused-behind": _behind,
}


@contextlib.contextmanager
def in_state(tmp_path, name: str) -> Iterator[Setup]:  # noqa: ANN001
    with _session(tmp_path, gate_open=name != "running") as (live, gate, reached):
        run_id = SETUPS[name](live, gate, reached)
        assert drain(live, quiet=0.05) == []  # the setup left nothing unread
        yield Setup(live, run_id, gate)


ACTIONS: dict[str, Callable[[LiveSession], object]] = {
    "play": lambda s: s.play(), "pause": lambda s: s.pause(),
    "toggle": lambda s: s.toggle_play(), "resume": lambda s: s.resume(),
    "forward": lambda s: s.step_forward(), "back": lambda s: s.step_back(),
    "goto1": lambda s: s.goto_step(1), "goto3": lambda s: s.goto_step(3),
    "goto9": lambda s: s.goto_step(9), "end": lambda s: s.run_to_end(),
    "cancel": lambda s: s.cancel(), "new run": lambda s: s.reload(),
    "faster": lambda s: s.faster(),
}

# (state, action) -> (what the action returns, [(status, step, from a new run?)],
#                     (playback state, step) afterwards)
OK, PAUSED, CANCELLED = "ok", "paused", "cancelled"
CASES: dict[tuple[str, str], tuple[object, list, tuple]] = {
    ("running", "play"): (True, [(PAUSED, 2, False)], (PL, 2)),
    ("running", "pause"): (True, [(PAUSED, 2, False)], (PA, 2)),
    ("running", "toggle"): (True, [(PAUSED, 2, False)], (PL, 2)),
    ("running", "resume"): (False, [(OK, None, False)], (FI, 3)),
    ("running", "forward"): (True, [(PAUSED, 2, False)], (PA, 2)),
    ("running", "back"): (True, [(PAUSED, 0, True)], (PA, 0)),
    ("running", "goto1"): (True, [(PAUSED, 1, True)], (PA, 1)),
    ("running", "goto3"): (True, [(PAUSED, 3, False)], (PA, 3)),
    ("running", "goto9"): (True, [(OK, None, False)], (FI, 3)),
    ("running", "end"): (False, [(OK, None, False)], (FI, 3)),
    ("running", "cancel"): (True, [(CANCELLED, None, False)], (FI, 1)),
    ("running", "new run"): (None, [(OK, None, True)], (FI, 3)),
    ("running", "faster"): (4.0, [(OK, None, False)], (FI, 3)),
    ("playing", "play"): (False, [], (PL, 1)),
    ("playing", "pause"): (False, [], (PA, 1)),
    ("playing", "toggle"): (False, [], (PA, 1)),
    ("playing", "resume"): (False, [], (PL, 1)),
    ("playing", "forward"): (True, [(PAUSED, 2, False)], (PA, 2)),
    ("playing", "back"): (True, [(PAUSED, 0, True)], (PA, 0)),
    ("playing", "goto1"): (True, [(PAUSED, 1, False)], (PA, 1)),
    ("playing", "goto3"): (True, [(PAUSED, 3, False)], (PA, 3)),
    ("playing", "goto9"): (True, [(OK, None, False)], (FI, 3)),
    ("playing", "end"): (True, [(OK, None, False)], (FI, 3)),
    ("playing", "cancel"): (True, [(CANCELLED, None, False)], (FI, 1)),
    ("playing", "new run"): (None, [(PAUSED, 1, True)], (PL, 1)),
    ("playing", "faster"): (MIN_RATE, [], (PL, 1)),
    ("paused", "play"): (True, [], (PL, 1)),
    ("paused", "pause"): (False, [], (PA, 1)),
    ("paused", "toggle"): (True, [], (PL, 1)),
    ("paused", "resume"): (True, [(OK, None, False)], (FI, 3)),
    ("paused", "forward"): (True, [(PAUSED, 2, False)], (PA, 2)),
    ("paused", "back"): (True, [(PAUSED, 0, True)], (PA, 0)),
    ("paused", "goto1"): (True, [(PAUSED, 1, False)], (PA, 1)),
    ("paused", "goto3"): (True, [(PAUSED, 3, False)], (PA, 3)),
    ("paused", "goto9"): (True, [(OK, None, False)], (FI, 3)),
    ("paused", "end"): (True, [(OK, None, False)], (FI, 3)),
    ("paused", "cancel"): (True, [(CANCELLED, None, False)], (FI, 1)),
    ("paused", "new run"): (None, [(PAUSED, 1, True)], (PA, 1)),
    ("paused", "faster"): (MIN_RATE, [], (PA, 1)),
    ("finished", "play"): (True, [(PAUSED, 0, True)], (PL, 0)),
    ("finished", "pause"): (False, [], (PA, 3)),
    ("finished", "toggle"): (True, [(PAUSED, 0, True)], (PL, 0)),
    ("finished", "resume"): (False, [], (FI, 3)),
    ("finished", "forward"): (False, [], (FI, 3)),
    ("finished", "back"): (True, [(PAUSED, 2, True)], (PA, 2)),
    ("finished", "goto1"): (True, [(PAUSED, 1, True)], (PA, 1)),
    ("finished", "goto3"): (True, [(PAUSED, 3, True)], (PA, 3)),
    ("finished", "goto9"): (False, [], (FI, 3)),
    ("finished", "end"): (False, [], (FI, 3)),
    ("finished", "cancel"): (False, [], (FI, 3)),
    ("finished", "new run"): (None, [(OK, None, True)], (FI, 3)),
    ("finished", "faster"): (4.0, [], (FI, 3)),
    ("paused-behind", "play"): (True, [(PAUSED, 2, True)], (PL, 2)),
    ("paused-behind", "pause"): (False, [], (PA, 2)),
    ("paused-behind", "toggle"): (True, [(PAUSED, 2, True)], (PL, 2)),
    ("paused-behind", "resume"): (True, [(OK, None, False)], (FI, 3)),
    ("paused-behind", "forward"): (True, [(PAUSED, 3, False)], (PA, 3)),
    ("paused-behind", "back"): (True, [(PAUSED, 1, False)], (PA, 1)),
    ("paused-behind", "goto1"): (True, [(PAUSED, 1, False)], (PA, 1)),
    ("paused-behind", "goto3"): (True, [(PAUSED, 3, False)], (PA, 3)),
    ("paused-behind", "goto9"): (True, [(OK, None, False)], (FI, 3)),
    ("paused-behind", "end"): (True, [(OK, None, False)], (FI, 3)),
    ("paused-behind", "cancel"): (False, [], (PA, 2)),
    ("paused-behind", "new run"): (None, [(PAUSED, 2, True)], (PA, 2)),
    ("paused-behind", "faster"): (MIN_RATE, [], (PA, 2)),
}


def test_every_action_is_checked_in_every_state():
    assert set(CASES) == {(state, action) for state in SETUPS for action in ACTIONS}


def _posted(setup: Setup, count: int) -> list[tuple]:
    """The next ``count`` results, then none for QUIET seconds, as ``(status,
    step, from a new run?)``."""
    got = [next_result(setup.live) for _ in range(count)]
    got += drain(setup.live, quiet=QUIET)
    return [(r.status, r.step_index, r.run_id != setup.run_id) for r in got]


@pytest.mark.timeout(60)
@pytest.mark.parametrize(("state", "action"), sorted(CASES),
                         ids=[f"{state}-{action}" for state, action in sorted(CASES)])
def test_each_action_from_each_state(tmp_path, state, action):
    returned, posts, (after, step) = CASES[state, action]
    with in_state(tmp_path, state) as setup:
        assert ACTIONS[action](setup.live) == returned
        _open_gate(setup.gate)
        assert _posted(setup, len(posts)) == posts
        view = setup.live.playback
        assert (view.state, view.step) == (after, step)


@pytest.mark.timeout(60)
@pytest.mark.parametrize("back", [lambda s: s.step_back(), lambda s: s.goto_step(0)],
                         ids=["left", "home"])
def test_after_a_play_to_the_end_going_back_then_to_the_end_shows_the_end(tmp_path, back):
    """The first stuck playback of the issue: Left (or Home) then End after Space
    had played the run to its end posted nothing, for good."""
    with in_state(tmp_path, "finished") as setup:
        setup.live.play(1000.0)
        played = [(r.status, r.step_index) for r in _results_until_ok(setup.live)]
        assert played == [(PAUSED, 0), (PAUSED, 1), (PAUSED, 2), (PAUSED, 3), (OK, None)]
        assert back(setup.live)
        shown = next_result(setup.live)
        assert shown.status == PAUSED and shown.step_index in (0, 2)
        assert setup.live.run_to_end()
        end = next_result(setup.live)
        assert (end.status, end.run_id, len(end.steps)) == (OK, shown.run_id, 4)
        assert setup.live.playback.state is FI


@pytest.mark.timeout(60)
def test_after_a_play_to_the_end_later_runs_go_straight_to_their_end(tmp_path):
    """The second: after one play, every later run (a save with more steps, a
    parameter change) posted ``paused`` at each new step before ``ok``."""
    with in_state(tmp_path, "finished") as setup:
        setup.live.play(1000.0)
        _results_until_ok(setup.live)
        script = tmp_path / "model.py"
        script.write_text(script.read_text() + "for i in range(3):\n    createVertex((9, i, 0))\n")
        setup.live.reload()
        assert [(r.status, len(r.steps)) for r in _posted_all(setup.live)] == [(OK, 7)]
        setup.live.set_parameters({"extra": 1})
        assert [(r.status, len(r.steps)) for r in _posted_all(setup.live)] == [(OK, 7)]
        assert setup.live.playback.state is FI


@pytest.mark.timeout(60)
def test_a_run_ending_while_an_earlier_step_is_shown_is_kept_for_the_end(tmp_path):
    """Going back while the played run works on after its last step: the earlier
    step stays on screen when the run ends; End posts its end, and the preview
    made meanwhile."""
    with _session(tmp_path, gate_open=False, gate_at=3, preview=mesh_arrays) as (
            live, gate, reached):
        _running(live, gate, reached)  # the first run waits after its last step
        os.remove(reached)
        live.goto_step(0)  # a replay: the first run is superseded
        replay = next_result(live, lambda r: r.status == PAUSED and r.step_index == 0)
        live.play(1000.0)
        for k in (1, 2, 3):
            next_result(live, lambda r, k=k: r.status == PAUSED and r.step_index == k)
        wait_until(lambda: os.path.exists(reached))  # played past its last step
        drain(live, quiet=0.05)  # late previews
        assert live.goto_step(1)
        shown = next_result(live)  # from the cache (with its preview, if made by now)
        assert (shown.status, shown.step_index, shown.run_id) == (PAUSED, 1, replay.run_id)
        _open_gate(gate)
        wait_until(lambda: live.activity is None)  # the replay has ended ...
        assert [r.status for r in drain(live, quiet=QUIET)] == []  # ... unseen
        assert (live.playback.state, live.playback.step) == (PA, 1)
        assert live.run_to_end()
        end = next_result(live, lambda r: r.status == OK and r.preview is not None)
        assert (end.run_id, len(end.steps)) == (replay.run_id, 4)


def test_the_play_rate_is_the_users_choice_within_bounds(tmp_path):
    with _session(tmp_path, gate_open=True) as (live, _, _):
        assert live.play_rate == 2.0 and live.playback.rate == 2.0
        rates = [live.faster() for _ in range(7)]
        assert rates == [4.0, 8.0, 16.0, 32.0, 64.0, MAX_RATE, MAX_RATE]
        live.play_rate = 1.0
        assert [live.slower() for _ in range(4)] == [0.5, 0.25, MIN_RATE, MIN_RATE]
        for bad in (0, -1.0, float("inf"), float("nan")):
            with pytest.raises(ValueError, match="play rate must be a positive number"):
                live.play_rate = bad
        assert live.play_rate == MIN_RATE  # unchanged by the refusals
        live.play_rate = 200.0  # a rate set outside the bounds stays until moved back in
        assert (live.faster(), live.slower()) == (200.0, MAX_RATE)
        live.play_rate = 0.1
        assert (live.slower(), live.faster()) == (0.1, MIN_RATE)
        with pytest.raises(ValueError, match="play rate"):
            live.play(0)


def _results_until_ok(live: LiveSession) -> list[RunResult]:
    got = [next_result(live)]
    while got[-1].status != OK:
        got.append(next_result(live))
    return got


def _posted_all(live: LiveSession) -> list[RunResult]:
    """The next result and every other one until none comes for QUIET seconds."""
    return [next_result(live), *drain(live, quiet=QUIET)]
