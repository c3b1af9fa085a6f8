"""LiveSession: a run that does not answer its cancel is abandoned, and the next
save's result arrives all the same (issue 30, section 2).

Each hostile script first makes one vertex and writes a marker file, so the test
knows it is under way, then blocks or spins where no check of the runner can
stop it; the test saves again once the run's thread is seen there. The
deadlines are generous waits, never measurements.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading
from types import FrameType

import pytest

import livemod.runner.session as session_module
from livemod.dlfl.io import load_mesh
from livemod.dlfl.scene import Scene
from livemod.runner import RunResult

from .runner_scripts.support import (
    WAIT,
    drain,
    manual_session,
    next_result,
    vertex_count,
    vertices_script,
    wait_until,
    write_in_place,
)

STUCK = """\
import os, threading, time
import numpy as np
createVertex((0, 0, 0))
event = threading.Event()
open({marker!r}, "w").close()
{block}
"""
BLOCK_LINE = 6  # the line of STUCK that {block} starts on


class Blocked:
    """Where a stuck run's thread is once it is stuck for sure: its innermost
    frame's file (base name), and its line or function when they tell.

    Only then may the test save again: an interrupt sent a moment earlier,
    while the run is still on its way, would stop it as any other run."""

    def __init__(self, file: str, line: int | None = None, function: str | None = None):
        self.file, self.line, self.function = file, line, function

    def holds(self, frame: FrameType) -> bool:
        return (os.path.basename(frame.f_code.co_filename) == self.file
                and self.line in (None, frame.f_lineno)
                and self.function in (None, frame.f_code.co_name))


# blocks that never end by themselves (their threads stay behind, asleep, daemon):
# time.sleep is a C call (no frame of its own); Event.wait waits in threading.py
FOREVER = {
    "sleep": ("time.sleep(10**6)", Blocked("model.py", BLOCK_LINE)),
    "event": ("event.wait()", Blocked("threading.py", function="wait")),
}

# a helper module's loop (compiled without the runner's checks) that swallows
# the forced interrupt, until the test lets it end
SWALLOWER = """\
import os, time

def swallow(stop):
    while not os.path.exists(stop):
        try:
            time.sleep(0.01)
        except BaseException:
            pass
"""


@contextlib.contextmanager
def _superseding(tmp_path, **options):  # noqa: ANN001, ANN003, ANN202
    """``(session, save)``: a session on ``model.py`` (three vertices) whose first
    result was taken; ``save(text)`` writes the script and fires its event."""
    script = tmp_path / "model.py"
    script.write_text(vertices_script(3))
    with manual_session(script, **options) as (live, notifier):
        assert vertex_count(next_result(live)) == 3

        def save(text: str) -> None:
            write_in_place(str(script), text)
            notifier.fire(str(script))

        yield live, save


def _innermost(run_id: int) -> FrameType | None:
    """The innermost frame of run ``run_id``'s thread, None if it has none (the
    newest thread of that name: runs abandoned by earlier tests' sessions live on)."""
    named = [t for t in threading.enumerate() if t.name == f"livemod-run-{run_id}"]
    return sys._current_frames().get(named[-1].ident) if named else None  # type: ignore[arg-type]


def _save_stuck(live, save, marker, block: str, blocked: Blocked) -> int:  # noqa: ANN001
    """Save a script stuck in ``block`` and wait until it is (``blocked``); its run id."""
    save(STUCK.format(marker=str(marker), block=block))
    wait_until(marker.exists)
    stuck = wait_until(lambda: live.activity).run_id
    wait_until(lambda: (frame := _innermost(stuck)) is not None and blocked.holds(frame))
    return stuck


def _stuck_then_saved(live, save, marker, block: str,  # noqa: ANN001
                      blocked: Blocked) -> tuple[int, RunResult]:
    """Save a script stuck in ``block``, then, once it is stuck, one making five
    vertices; ``(the stuck run's id, the later save's result)``."""
    stuck = _save_stuck(live, save, marker, block, blocked)
    save(vertices_script(5))
    result = next_result(live, lambda r: r.status != "paused")
    return stuck, result


@pytest.mark.timeout(60)
@pytest.mark.parametrize(("block", "blocked"), FOREVER.values(), ids=FOREVER.keys())
def test_a_run_blocked_for_ever_is_superseded_by_the_next_save(tmp_path, block, blocked):
    with _superseding(tmp_path) as (live, save):
        stuck, result = _stuck_then_saved(live, save, tmp_path / "started", block, blocked)
        assert result.status == "ok" and vertex_count(result) == 5
        assert result.run_id == stuck + 1
        assert live.background_runs == (stuck,)  # still blocked, left in the background
        activity = live.activity
        assert activity is None or activity.run_id > stuck  # never the abandoned run
        save(vertices_script(6))  # and the session goes on serving saves
        assert vertex_count(next_result(live)) == 6


@pytest.mark.timeout(60)
def test_a_run_blocked_reading_a_pipe_is_abandoned_and_never_posts_nor_saves(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    out = tmp_path / "out.obj"
    with _superseding(tmp_path, output=str(out)) as (live, save):
        # (opened for reading and writing, so that the open itself does not block)
        block = (f"with open({str(fifo)!r}, 'r+b', buffering=0) as pipe:\n"
                 "    pipe.read(1)\ncreateVertex((1, 0, 0))")
        stuck, result = _stuck_then_saved(live, save, tmp_path / "started", block,
                                          Blocked("model.py", BLOCK_LINE + 1))
        assert result.status == "ok" and vertex_count(result) == 5
        assert live.background_runs == (stuck,)
        with open(fifo, "wb") as pipe:  # lets the abandoned run go on, and end
            pipe.write(b"x")
        wait_until(lambda: live.background_runs == ())
        assert [r.run_id for r in drain(live)] == []  # it posted nothing
        assert load_mesh(str(out)).counts()[0] == 5  # and did not write the output


@pytest.mark.timeout(60)
def test_a_loop_that_swallows_the_interrupt_is_abandoned(tmp_path):
    (tmp_path / "swallower.py").write_text(SWALLOWER)
    stop = tmp_path / "stop"
    out = tmp_path / "out.obj"
    with _superseding(tmp_path, output=str(out)) as (live, save):
        block = f"import swallower\nswallower.swallow({str(stop)!r})"
        stuck, result = _stuck_then_saved(live, save, tmp_path / "started", block,
                                          Blocked("swallower.py"))
        assert result.status == "ok" and vertex_count(result) == 5
        assert live.background_runs == (stuck,)
        stop.write_text("")  # the loop ends; its script then ends as if nothing happened
        wait_until(lambda: live.background_runs == ())
        assert drain(live) == []
        assert load_mesh(str(out)).counts()[0] == 5


@pytest.mark.timeout(120)
def test_a_long_numpy_call_is_left_to_finish_in_the_background(tmp_path):
    done = tmp_path / "done"
    block = (f"np.linalg.eigvals(np.random.default_rng(0).random((1600, 1600)))\n"
             f"open({str(done)!r}, 'w').close()")
    with _superseding(tmp_path) as (live, save):
        stuck, result = _stuck_then_saved(live, save, tmp_path / "started", block,
                                          Blocked("_linalg.py", function="eigvals"))
        assert vertex_count(result) == 5
        assert not done.exists()  # the result came while the call was still computing
        assert live.background_runs == (stuck,)
        wait_until(lambda: live.background_runs == (), timeout=100)
        assert drain(live) == []


@pytest.mark.timeout(60)
def test_a_user_cancel_of_a_blocked_run_says_cancelled_and_abandons_it(tmp_path):
    with _superseding(tmp_path) as (live, save):
        stuck = _save_stuck(live, save, tmp_path / "started", *FOREVER["event"])
        live.cancel()
        cancelled = next_result(live)
        assert cancelled.status == "cancelled" and cancelled.run_id == stuck
        assert cancelled.stale and vertex_count(cancelled) == 3  # the last good mesh
        assert live.background_runs == (stuck,)
        wait_until(lambda: live.activity is None)


@pytest.mark.timeout(60)
def test_closing_a_session_does_not_wait_for_a_blocked_run(tmp_path):
    script = tmp_path / "model.py"
    marker = tmp_path / "started"
    script.write_text(STUCK.format(marker=str(marker), block=FOREVER["sleep"][0]))
    with manual_session(script) as (live, _):
        wait_until(marker.exists)
        live.close()
        assert live.join(WAIT)  # the supervisor did not wait for the sleeping run


def test_closing_a_session_gives_the_process_state_back_before_it_returns(tmp_path):
    # a give-back after close() returned would undo what the host changed since
    script, marker, elsewhere = tmp_path / "model.py", tmp_path / "started", tmp_path / "away"
    elsewhere.mkdir()
    block = f"os.chdir({str(elsewhere)!r})\n" + FOREVER["sleep"][0]
    script.write_text(STUCK.format(marker=str(marker), block=block))
    cwd = os.getcwd()
    with manual_session(script) as (live, _):
        wait_until(lambda: os.getcwd() == str(elsewhere))
        live.close()
        assert os.getcwd() == cwd  # the stuck run was abandoned and its change undone
        assert live.background_runs != ()


@pytest.mark.timeout(60)
def test_the_interrupt_of_an_abandoned_run_never_reaches_the_next_one(tmp_path):
    # the abandoned run swallows interrupts in a helper; the next one spends its
    # time in a helper's loop too, where an interrupt meant for the first would stop it
    (tmp_path / "swallower.py").write_text(SWALLOWER)
    (tmp_path / "counter.py").write_text(
        "def count(n):\n    total = 0\n    for i in range(n):\n        total += i\n"
        "    return total\n")
    stop = tmp_path / "stop"
    with _superseding(tmp_path) as (live, save):
        block = f"import swallower\nswallower.swallow({str(stop)!r})"
        _save_stuck(live, save, tmp_path / "started", block, Blocked("swallower.py"))
        save("import counter\ncounter.count(3_000_000)\n" + vertices_script(4))
        result = next_result(live)
        stop.write_text("")
        assert result.status == "ok" and vertex_count(result) == 4
        wait_until(lambda: live.background_runs == ())


def test_background_runs_is_empty_before_anything_runs(tmp_path):
    script = tmp_path / "model.py"
    script.write_text(vertices_script(1))
    with manual_session(script) as (live, _):
        assert live.background_runs == ()
        assert vertex_count(next_result(live)) == 1
        assert live.background_runs == ()


QUAD = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n"


@pytest.mark.timeout(60)
def test_a_run_abandoned_before_its_script_began_never_runs_it(tmp_path, monkeypatch):
    shape, log = tmp_path / "start.obj", tmp_path / "runs.txt"
    shape.write_text(QUAD)
    script = tmp_path / "model.py"
    script.write_text(f"with open({str(log)!r}, 'a') as log:\n    log.write('ran\\n')\n")
    real, armed, release = session_module.base_scene, threading.Event(), threading.Event()

    def slow_once(path: str) -> Scene:  # the --mesh of run 2 takes its time to load
        if armed.is_set():
            armed.clear()
            release.wait()
        return real(path)

    monkeypatch.setattr(session_module, "base_scene", slow_once)
    with manual_session(script, mesh_path=str(shape)) as (live, notifier):
        assert next_result(live).status == "ok"
        armed.set()
        shape.write_text(QUAD.replace("v 1 1 0", "v 2 2 0"))
        notifier.fire(str(shape))  # run 2 loads the changed --mesh, slowly
        wait_until(lambda: not armed.is_set())
        live.reload()  # run 3 does not wait for it
        third = next_result(live)
        assert third.run_id == 3 and third.status == "ok"
        assert live.background_runs == (2,)
        release.set()
        wait_until(lambda: live.background_runs == ())
        assert drain(live) == []
    assert log.read_text() == "ran\n" * 2  # runs 1 and 3: run 2's script never ran


@pytest.mark.timeout(60)
def test_what_an_abandoned_run_changes_once_it_wakes_is_undone_for_the_next_run(tmp_path):
    fifo, elsewhere = tmp_path / "pipe", tmp_path / "elsewhere"
    os.mkfifo(fifo)
    elsewhere.mkdir()
    cwd = os.getcwd()
    with _superseding(tmp_path) as (live, save):
        # blocked in the library's frame (no interrupt is sent there), it runs on
        # after waking up, to the end of the script: no check of the runner is left
        block = (f"import pathlib, livemod.dlfl\npathlib.Path({str(fifo)!r}).read_bytes()\n"
                 f"os.chdir({str(elsewhere)!r})\nlivemod.dlfl.load = None")
        stuck, result = _stuck_then_saved(live, save, tmp_path / "started", block,
                                          Blocked("pathlib.py"))
        assert vertex_count(result) == 5 and live.background_runs == (stuck,)
        with open(fifo, "wb"):
            pass  # the abandoned run reads the end of the pipe and goes on
        wait_until(lambda: live.background_runs == ())
        save(f"import os\nassert os.getcwd() == {cwd!r}, os.getcwd()\nload('cube')\n")
        cube = next_result(live)
        assert cube.status == "ok", cube.error
        assert cube.arrays is not None and cube.arrays.counts == (8, 12, 6)
    assert os.getcwd() == cwd
