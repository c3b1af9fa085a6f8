"""LiveSession.activity (the run at work now) and the working time of paused runs."""

from __future__ import annotations

import contextlib
import time

import pytest

from livemod.runner import LiveSession, ManualNotifier, RunResult

from .runner_scripts.support import closing_session, next_result, wait_until

SLOW = """
import time
start = time.perf_counter()
while time.perf_counter() - start < {seconds}:
    time.sleep(0.01)
createVertex((0, 0, 0))
"""

STEPS = "createVertex((0, 0, 0))\ncreateVertex((1, 0, 0))\ncreateVertex((2, 0, 0))\n"


def is_ok(r: RunResult) -> bool:
    return r.status == "ok"



@pytest.mark.timeout(60)
def test_a_run_a_save_starts_is_reported_at_work_until_its_result(tmp_path) -> None:
    script = tmp_path / "model.py"
    script.write_text(SLOW.format(seconds=0.0))
    notifier = ManualNotifier()
    with closing_session(LiveSession(str(script), notifier=notifier, preview=False,
                                     debounce=0.01)) as live:
        assert live.activity is None  # nothing started yet
        live.start()
        next_result(live, is_ok)
        wait_until(lambda: live.activity is None)
        script.write_text(SLOW.format(seconds=0.6))
        notifier.fire(str(script))  # saved in an editor: no call on the session
        busy = wait_until(lambda: live.activity)
        assert busy.run_id == 2 and busy.script == str(script)
        time.sleep(0.2)
        later = live.activity
        assert later is not None and later.run_id == 2 and later.working > busy.working
        done = next_result(live, is_ok)
        assert done.run_id == 2
        wait_until(lambda: live.activity is None)


@pytest.mark.timeout(60)
def test_only_the_newest_run_is_reported(tmp_path) -> None:
    script = tmp_path / "model.py"
    script.write_text(SLOW.format(seconds=5.0))
    with closing_session(LiveSession(str(script), notifier=ManualNotifier(),
                                     preview=False)) as live:
        live.start()
        assert wait_until(lambda: live.activity).run_id == 1
        script.write_text(SLOW.format(seconds=0.3))
        live.reload()  # supersedes run 1, which is cancelled
        assert wait_until(lambda: (a := live.activity) is not None and a.run_id == 2 and a)
        seen = []
        while (activity := live.activity) is not None:
            seen.append(activity.run_id)
            time.sleep(0.01)
        assert set(seen) <= {2}  # once run 2 started, run 1 never shows again
        assert next_result(live, is_ok).run_id == 2


@contextlib.contextmanager
def _paused_at_the_first_step(folder):
    """``(session, its first paused result)``: the STEPS script in ``folder``
    started paused."""
    script = folder / "steps.py"
    script.write_text(STEPS)
    with closing_session(LiveSession(str(script), notifier=ManualNotifier(),
                                     preview=False)) as live:
        live.pause()
        live.start()
        yield live, next_result(live, lambda r: r.status == "paused")


@pytest.mark.timeout(60)
def test_a_paused_run_is_not_at_work(tmp_path) -> None:
    with _paused_at_the_first_step(tmp_path) as (live, _):
        wait_until(lambda: live.activity is None)  # waiting on the viewer, not working
        time.sleep(0.1)
        assert live.activity is None
        live.run_to_end()
        next_result(live, is_ok)
        assert live.activity is None


@pytest.mark.timeout(60)
def test_the_time_a_run_spends_paused_is_not_its_elapsed_time(tmp_path) -> None:
    # bounded by the time since the run started less the pauses, whatever the speed
    started = time.perf_counter()
    with _paused_at_the_first_step(tmp_path) as (live, held):
        assert held.step_index == 0
        time.sleep(0.5)
        live.step_forward()
        second = next_result(live, lambda r: r.status == "paused" and r.step_index == 1)
        unpaused = time.perf_counter() - started - 0.5  # not the half second held at step 0
        assert second.elapsed <= unpaused and second.steps[1].elapsed <= unpaused
        assert second.steps[0].elapsed == held.steps[0].elapsed
        time.sleep(0.5)
        live.run_to_end()
        ended = next_result(live, is_ok)
        assert ended.run_id == held.run_id
        unpaused = time.perf_counter() - started - 1.0  # a second of pauses, left out
        assert ended.elapsed <= unpaused
        assert all(step.elapsed <= unpaused for step in ended.steps)
        assert [s.elapsed for s in ended.steps[:2]] == [s.elapsed for s in second.steps]
