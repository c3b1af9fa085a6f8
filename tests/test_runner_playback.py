"""LiveSession playback: pause, step forward and back, goto, play, run to end."""

from __future__ import annotations

import dataclasses
import itertools
import time
from pathlib import Path

import pytest

from livemod.runner import LiveSession, ManualNotifier, RunResult
from livemod.runner.playback import (
    NEVER,
    NO_RUN,
    Action,
    Mode,
    PlaybackState,
    RunPosition,
    Show,
    transition,
)

from .runner_scripts.support import (
    closing_session,
    drain,
    next_result,
    same_mesh,
    script_path,
    started_session,
    straight_snapshots,
)

CUBE = script_path("cube_steps.py")


@pytest.fixture
def session():
    with closing_session(LiveSession(CUBE, notifier=ManualNotifier(), preview=False)) as live:
        yield live


def paused_at(k: int):
    return lambda r: r.status == "paused" and r.step_index == k


def is_ok(r: RunResult) -> bool:
    return r.status == "ok"


@pytest.mark.timeout(60)
def test_stepping_forward_and_back_matches_a_straight_run(session):
    snaps, final = straight_snapshots(CUBE)
    session.start()
    first = next_result(session, is_ok)
    assert same_mesh(first.arrays, final)
    session.goto_step(2)
    shown = next_result(session, paused_at(2))
    assert same_mesh(shown.arrays, snaps[2]) and len(shown.steps) == 3
    for k in (3, 4, 5):
        session.step_forward()
        assert same_mesh(next_result(session, paused_at(k)).arrays, snaps[k])
    for k in (4, 3):
        session.step_back()
        assert same_mesh(next_result(session, paused_at(k)).arrays, snaps[k])
    session.goto_step(9)
    assert same_mesh(next_result(session, paused_at(9)).arrays, snaps[9])
    session.goto_step(1)
    assert same_mesh(next_result(session, paused_at(1)).arrays, snaps[1])
    session.run_to_end()
    end = next_result(session, is_ok)
    assert same_mesh(end.arrays, final) and len(end.steps) == len(snaps)


@pytest.mark.timeout(60)
def test_step_back_from_the_end_shows_the_step_before_last(session):
    snaps, _ = straight_snapshots(CUBE)
    session.start()
    ended = next_result(session, is_ok)
    session.step_back()
    shown = next_result(session, paused_at(len(ended.steps) - 2))
    assert same_mesh(shown.arrays, snaps[len(ended.steps) - 2])


@pytest.mark.timeout(60)
def test_play_advances_through_every_step_then_ends(session):
    session.start()
    ended = next_result(session, is_ok)
    session.play(200.0)
    shown = []
    result = next_result(session)
    while result.status == "paused":
        shown.append(result.step_index)
        result = next_result(session)
    assert result.status == "ok"
    assert shown == list(range(len(ended.steps)))


@pytest.mark.timeout(60)
def test_pause_holds_a_run_and_resume_finishes_it(session):
    session.pause()
    session.start()
    held = next_result(session, lambda r: r.status == "paused")
    time.sleep(0.3)
    assert drain(session, quiet=0.2) == []  # nothing moves while paused
    session.resume()
    assert next_result(session, is_ok).run_id == held.run_id


@pytest.mark.timeout(60)
def test_a_reload_while_paused_keeps_the_place(session):
    session.start()
    next_result(session, is_ok)
    session.goto_step(4)
    next_result(session, paused_at(4))
    session.reload()
    again = next_result(session)
    assert again.status == "paused" and again.step_index == 4


@pytest.mark.timeout(60)
def test_goto_after_an_error_shows_the_steps_that_finished(tmp_path):
    path = tmp_path / "fails.py"
    path.write_text("createVertex((0, 0, 0))\ncreateVertex((1, 0, 0))\nraise ValueError('late')\n")
    with started_session(path, preview=False) as live:
        failed = next_result(live, lambda r: r.status == "error")
        assert len(failed.steps) == 2 and failed.arrays is None and not failed.stale
        assert failed.error is not None and failed.error.line == 3
        live.goto_step(0)
        shown = next_result(live, paused_at(0))
        assert shown.arrays is not None and shown.arrays.counts == (1, 0, 1)


@pytest.mark.timeout(60)
def test_user_cancel_posts_a_cancelled_result_with_last_good_mesh(tmp_path):
    path = tmp_path / "slow.py"
    path.write_text("createVertex((0, 0, 0))\n")
    live = LiveSession(str(path), notifier=ManualNotifier(), preview=False)
    with closing_session(live):
        live.start()
        good = next_result(live, is_ok)
        path.write_text("createVertex((0, 0, 0))\nwhile True:\n    pass\n")
        live.reload()
        time.sleep(0.3)
        live.cancel()
        cancelled = next_result(live, lambda r: r.status == "cancelled")
        assert cancelled.stale and same_mesh(cancelled.arrays, good.arrays)
        assert cancelled.error is not None and cancelled.error.kind == "cancelled"


@pytest.mark.timeout(60)
def test_controls_return_at_once_even_mid_run(tmp_path):
    path = tmp_path / "busy.py"
    path.write_text("while True:\n    createVertex((0, 0, 0))\n")
    live = LiveSession(str(path), notifier=ManualNotifier(), preview=False)
    with closing_session(live):
        live.start()
        time.sleep(0.2)
        controls = [live.pause, live.step_forward, live.step_back, lambda: live.goto_step(3),
                    lambda: live.play(5.0), live.resume, live.run_to_end, live.reload,
                    lambda: live.set_parameters({"a": 1}), lambda: live.set_selection(None)]
        # the run never ends: a call that waited for it would hang here (how long each
        # takes is bench/bench_responsiveness.py's to time)
        for control in controls:
            control()


def test_play_rejects_a_non_positive_rate(session):
    with pytest.raises(ValueError):
        session.play(0)


@pytest.mark.timeout(60)
def test_stepping_back_uses_the_snapshot_cache_without_a_replay(session):
    snaps, final = straight_snapshots(CUBE)
    session.pause()
    session.start()
    first = next_result(session, paused_at(0))
    for k in (1, 2, 3):
        session.step_forward()
        assert next_result(session, paused_at(k)).run_id == first.run_id
    for k in (2, 1, 0):
        session.step_back()
        back = next_result(session, paused_at(k))
        assert back.run_id == first.run_id and same_mesh(back.arrays, snaps[k])
    for k in (1, 2, 3, 4):  # through the cache, then the live run goes on
        session.step_forward()
        shown = next_result(session, paused_at(k))
        assert shown.run_id == first.run_id and same_mesh(shown.arrays, snaps[k])
    session.run_to_end()
    assert same_mesh(next_result(session, is_ok).arrays, final)


@pytest.mark.timeout(60)
def test_without_a_snapshot_budget_stepping_back_replays():
    snaps, _ = straight_snapshots(CUBE)
    live = LiveSession(CUBE, notifier=ManualNotifier(), preview=False, snapshot_budget=0)
    with closing_session(live):
        live.pause()
        live.start()
        first = next_result(live, paused_at(0))
        live.step_forward()
        next_result(live, paused_at(1))
        live.step_back()
        back = next_result(live, paused_at(0))
        assert back.run_id > first.run_id and same_mesh(back.arrays, snaps[0])


@pytest.mark.timeout(60)
def test_resume_after_pausing_a_play_plays_on(session):
    session.start()
    ended = next_result(session, is_ok)
    session.play(5.0)
    held = next_result(session, paused_at(1))
    session.pause()
    late = drain(session, quiet=0.6)  # at most the step that was already due
    assert len(late) <= 1
    held = late[-1] if late else held
    assert drain(session, quiet=0.5) == []  # paused: the play does not go on
    session.resume()
    result = next_result(session, lambda r: r.status == "paused" and r.step_index > held.step_index)
    assert result.run_id == held.run_id
    session.run_to_end()
    finished = next_result(session, is_ok)
    assert [(s.label, s.counts) for s in finished.steps] == [
        (s.label, s.counts) for s in ended.steps]


@pytest.mark.timeout(60)
def test_a_storm_of_controls_ends_in_the_straight_result(session):
    import random as rnd

    _, final = straight_snapshots(CUBE)
    session.start()
    chooser = rnd.Random(5)
    controls = [session.pause, session.resume, session.step_forward, session.step_back,
                session.reload, lambda: session.goto_step(chooser.randrange(14)),
                lambda: session.play(50.0), session.cancel]
    for _ in range(200):
        chooser.choice(controls)()
        time.sleep(0.005)
    session.run_to_end()
    session.reload()
    assert same_mesh(next_result(session, lambda r: r.status == "ok").arrays, final)


# -- the state machine alone (livemod/runner/playback.py's table) -------------------

R, PL, PA, FI = (PlaybackState.RUNNING, PlaybackState.PLAYING, PlaybackState.PAUSED,
                 PlaybackState.FINISHED)
WORKING = RunPosition(live=True, done=2)  # a run working on its third step
HELD_1 = RunPosition(live=True, held=1, done=2, cached=frozenset({0, 1}))  # held at step 1
ENDED = RunPosition(final=True, done=4, cached=frozenset({0, 1, 2, 3}))  # 4 steps, all cached
ENDED_BARE = RunPosition(final=True, done=4)  # 4 steps, none cached (it never paused)

TABLE = [
    # (mode now, where the run is, action, k) -> (mode after, what to show)
    ((Mode(R), WORKING, Action.PLAY, 0), (Mode(PL, 2), Show.LIVE)),
    ((Mode(R), NO_RUN, Action.PLAY, 0), (Mode(PL, 0, behind=True), Show.REPLAY)),
    ((Mode(PL, 1), HELD_1, Action.PLAY, 0), (Mode(PL, 1), Show.NOTHING)),
    ((Mode(PA, 1), HELD_1, Action.PLAY, 0), (Mode(PL, 1), Show.LIVE)),
    ((Mode(PA, 0, behind=True), HELD_1, Action.PLAY, 0), (Mode(PL, 0, behind=True), Show.REPLAY)),
    ((Mode(PA, 2, behind=True), ENDED, Action.PLAY, 0), (Mode(PL, 2, behind=True), Show.REPLAY)),
    ((Mode(FI, 3), ENDED, Action.PLAY, 0), (Mode(PL, 0, behind=True), Show.REPLAY)),
    ((Mode(R), WORKING, Action.PAUSE, 0), (Mode(PA, 2), Show.LIVE)),
    ((Mode(R), NO_RUN, Action.PAUSE, 0), (Mode(PA, 0, behind=True), Show.NOTHING)),
    ((Mode(PL, 1), HELD_1, Action.PAUSE, 0), (Mode(PA, 1, resume_plays=True), Show.NOTHING)),
    ((Mode(PL, 2), HELD_1, Action.PAUSE, 0), (Mode(PA, 2, resume_plays=True), Show.LIVE)),
    ((Mode(PA, 1), HELD_1, Action.PAUSE, 0), (Mode(PA, 1), Show.NOTHING)),
    ((Mode(FI, 3), ENDED, Action.PAUSE, 0), (Mode(PA, 3, behind=True), Show.NOTHING)),
    ((Mode(FI), ENDED, Action.PAUSE, 0), (Mode(PA, 0, behind=True), Show.NOTHING)),
    ((Mode(PL, 1), HELD_1, Action.TOGGLE, 0), (Mode(PA, 1, resume_plays=True), Show.NOTHING)),
    ((Mode(PA, 1), HELD_1, Action.TOGGLE, 0), (Mode(PL, 1), Show.LIVE)),
    ((Mode(FI, 3), ENDED, Action.TOGGLE, 0), (Mode(PL, 0, behind=True), Show.REPLAY)),
    ((Mode(R), WORKING, Action.TOGGLE, 0), (Mode(PL, 2), Show.LIVE)),
    ((Mode(PA, 1, resume_plays=True), HELD_1, Action.RESUME, 0), (Mode(PL, 1), Show.LIVE)),
    ((Mode(PA, 1), HELD_1, Action.RESUME, 0), (Mode(R), Show.LIVE)),
    ((Mode(PA, 1, behind=True), ENDED, Action.RESUME, 0), (Mode(FI, 3), Show.FINAL)),
    ((Mode(R), WORKING, Action.RESUME, 0), (Mode(R), Show.NOTHING)),
    ((Mode(PL, 1), HELD_1, Action.RESUME, 0), (Mode(PL, 1), Show.NOTHING)),
    ((Mode(FI, 3), ENDED, Action.RESUME, 0), (Mode(FI, 3), Show.NOTHING)),
    ((Mode(R), WORKING, Action.STEP_FORWARD, 0), (Mode(PA, 2), Show.LIVE)),
    ((Mode(R), NO_RUN, Action.STEP_FORWARD, 0), (Mode(R), Show.NOTHING)),
    ((Mode(PL, 1), HELD_1, Action.STEP_FORWARD, 0), (Mode(PA, 2, resume_plays=True), Show.LIVE)),
    ((Mode(PL, 2), HELD_1, Action.STEP_FORWARD, 0), (Mode(PA, 2, resume_plays=True), Show.LIVE)),
    ((Mode(PA, 1), HELD_1, Action.STEP_FORWARD, 0), (Mode(PA, 2), Show.LIVE)),
    ((Mode(PA, 0, behind=True), HELD_1, Action.STEP_FORWARD, 0), (Mode(PA, 1), Show.CACHED)),
    ((Mode(PA, 2, behind=True), ENDED, Action.STEP_FORWARD, 0), (Mode(PA, 3, behind=True), Show.CACHED)),
    ((Mode(PA, 3, behind=True), ENDED, Action.STEP_FORWARD, 0), (Mode(FI, 3), Show.FINAL)),
    ((Mode(FI, 3), ENDED, Action.STEP_FORWARD, 0), (Mode(FI, 3), Show.NOTHING)),
    ((Mode(R), WORKING, Action.STEP_BACK, 0), (Mode(PA, 0, behind=True), Show.REPLAY)),
    ((Mode(R), RunPosition(live=True, done=1), Action.STEP_BACK, 0), (Mode(R), Show.NOTHING)),
    ((Mode(PL, 1), HELD_1, Action.STEP_BACK, 0), (Mode(PA, 0, True, True), Show.CACHED)),
    ((Mode(PL, 2), HELD_1, Action.STEP_BACK, 0), (Mode(PA, 0, True, True), Show.CACHED)),
    ((Mode(PA, 1), HELD_1, Action.STEP_BACK, 0), (Mode(PA, 0, behind=True), Show.CACHED)),
    ((Mode(PA, 0), HELD_1, Action.STEP_BACK, 0), (Mode(PA, 0), Show.NOTHING)),
    ((Mode(FI, 3), ENDED, Action.STEP_BACK, 0), (Mode(PA, 2, behind=True), Show.CACHED)),
    ((Mode(FI, 3), ENDED_BARE, Action.STEP_BACK, 0), (Mode(PA, 2, behind=True), Show.REPLAY)),
    ((Mode(FI, 0), RunPosition(final=True, done=1), Action.STEP_BACK, 0), (Mode(FI, 0), Show.NOTHING)),
    ((Mode(R), WORKING, Action.GOTO, 3), (Mode(PA, 3), Show.LIVE)),
    ((Mode(R), WORKING, Action.GOTO, 1), (Mode(PA, 1, behind=True), Show.REPLAY)),
    ((Mode(PL, 1), HELD_1, Action.GOTO, 1), (Mode(PA, 1, resume_plays=True), Show.CACHED)),
    ((Mode(PA, 0, behind=True), RunPosition(live=True, held=1, done=2), Action.GOTO, 1),
     (Mode(PA, 1, behind=True), Show.REPLAY)),  # its own step, not cached (no budget)
    ((Mode(PA, 1), HELD_1, Action.GOTO, 5), (Mode(PA, 5), Show.LIVE)),
    ((Mode(FI, 3), ENDED, Action.GOTO, 0), (Mode(PA, 0, behind=True), Show.CACHED)),
    ((Mode(FI, 3), ENDED, Action.GOTO, 9), (Mode(FI, 3), Show.NOTHING)),
    ((Mode(PA, 1, behind=True), ENDED, Action.GOTO, 9), (Mode(FI, 3), Show.FINAL)),
    ((Mode(R), WORKING, Action.END, 0), (Mode(R), Show.NOTHING)),
    ((Mode(PL, 1), HELD_1, Action.END, 0), (Mode(R), Show.LIVE)),
    ((Mode(PA, 0, behind=True), HELD_1, Action.END, 0), (Mode(R), Show.LIVE)),
    ((Mode(PA, 2, behind=True), ENDED, Action.END, 0), (Mode(FI, 3), Show.FINAL)),
    ((Mode(PA, 0, behind=True), NO_RUN, Action.END, 0), (Mode(R), Show.NOTHING)),
    ((Mode(FI, 3), ENDED, Action.END, 0), (Mode(FI, 3), Show.NOTHING)),
    ((Mode(R), WORKING, Action.CANCEL, 0), (Mode(FI), Show.LIVE)),
    ((Mode(PL, 1), HELD_1, Action.CANCEL, 0), (Mode(FI), Show.LIVE)),
    ((Mode(PA, 1), HELD_1, Action.CANCEL, 0), (Mode(FI), Show.LIVE)),
    ((Mode(PA, 1, behind=True), ENDED, Action.CANCEL, 0), (Mode(PA, 1, behind=True), Show.NOTHING)),
    ((Mode(FI, 3), ENDED, Action.CANCEL, 0), (Mode(FI, 3), Show.NOTHING)),
    ((Mode(R), ENDED, Action.NEW_RUN, 0), (Mode(R), Show.LIVE)),
    ((Mode(FI, 3), ENDED, Action.NEW_RUN, 0), (Mode(R), Show.LIVE)),
    ((Mode(PL, 2, behind=True), ENDED, Action.NEW_RUN, 0), (Mode(PL, 2), Show.LIVE)),
    ((Mode(PA, 2, True, True), ENDED, Action.NEW_RUN, 0), (Mode(PA, 2, False, True), Show.LIVE)),
    ((Mode(R), WORKING, Action.RUN_ENDED, 4), (Mode(FI, 3), Show.LIVE)),
    ((Mode(PL, 4), HELD_1, Action.RUN_ENDED, 4), (Mode(FI, 3), Show.LIVE)),
    ((Mode(PA, 9), HELD_1, Action.RUN_ENDED, 4), (Mode(FI, 3), Show.LIVE)),
    ((Mode(PA, 1, behind=True), HELD_1, Action.RUN_ENDED, 4), (Mode(PA, 1, behind=True), Show.NOTHING)),
    ((Mode(PL, 0, behind=True), HELD_1, Action.RUN_ENDED, 4), (Mode(PL, 0, behind=True), Show.NOTHING)),
    ((Mode(FI), ENDED, Action.RUN_ENDED, 0), (Mode(FI), Show.LIVE)),
    ((Mode(PA, 2, True, True), ENDED, Action.OPEN, 0), (Mode(R), Show.NOTHING)),
]


@pytest.mark.parametrize(("before", "after"), TABLE,
                         ids=[f"{m.state}{m.step}-{a.name}{k}" for (m, _, a, k), _ in TABLE])
def test_the_transition_table(before, after):
    mode, where, action, k = before
    assert transition(mode, action, where, k) == after


def test_the_table_covers_every_action_in_every_state():
    covered = {(mode.state, action) for (mode, _, action, _), _ in TABLE}
    assert covered >= {(state, action) for state in PlaybackState for action in Action
                       if not (action is Action.OPEN and state is not PA)}


def _positions() -> list[RunPosition]:
    runs = [NO_RUN, WORKING, HELD_1, ENDED, ENDED_BARE, RunPosition(final=True),
            RunPosition(live=True), RunPosition(live=True, held=0, done=1)]
    return [*runs, *(dataclasses.replace(r, cached=frozenset(range(4))) for r in runs)]


def _modes() -> list[Mode]:
    modes = [Mode(R), Mode(FI), Mode(FI, 3)]
    for state in (PA, PL):
        modes += [Mode(state, s, b, p) for s in (0, 1, 2, 5) for b in (False, True)
                  for p in (False, True)]
    return modes


def _consistent(mode: Mode, where: RunPosition) -> bool:
    """The invariant: a mode that holds runs and shows the live run's own pause
    has a live run."""
    return mode.state not in (PA, PL) or mode.behind or where.live


@pytest.mark.parametrize("action", list(Action))
def test_no_transition_promises_what_cannot_come(action):
    """The stuck playbacks of the first hour, for every mode, run and step: what
    an action says to show can be shown, and the invariant holds after it."""
    for mode, where, k in itertools.product(_modes(), _positions(), (0, 1, 3, 4, 9)):
        if not _consistent(mode, where):
            continue
        after, show = transition(mode, action, where, k)
        assert (after.state in (PA, PL)) == (after.hold_from != NEVER)
        if show is Show.LIVE and action not in (Action.NEW_RUN, Action.RUN_ENDED):
            replaying = mode.state is PL and mode.behind  # a replay was asked for
            assert where.live or replaying, (mode, where, action, k)
        if show is Show.CACHED:
            assert after.step in where.cached
        if show is Show.FINAL:
            assert where.final and not where.live and after.state is FI
        if show is Show.REPLAY:
            assert after.behind  # the live run's pauses are not the ones shown
        if action is Action.NEW_RUN:  # the new run is live from now on
            where = RunPosition(live=True)
        elif action is Action.RUN_ENDED:  # the run is gone
            where = RunPosition(final=True, done=k)
        assert _consistent(after, where), (mode, where, action, k)


def test_a_finished_playback_leaves_later_runs_unpaused():
    mode, _ = transition(Mode(PL, 3), Action.RUN_ENDED, HELD_1, 4)  # played to the end
    assert transition(mode, Action.NEW_RUN)[0].hold_from == NEVER


def test_the_docs_table_has_every_action_and_every_state():
    text = (Path(__file__).resolve().parents[1] / "docs" / "playback.md").read_text("utf-8")
    rows = [line.split("|")[1].strip() for line in text.splitlines() if line.startswith("| ")]
    header = next(line for line in text.splitlines() if line.startswith("| action |"))
    assert [cell.split()[0] for cell in header.strip("| \n").split(" | ")[1:]] == [
        str(state) for state in PlaybackState]
    for action in Action:
        assert any(row.startswith(action.value) for row in rows), action
