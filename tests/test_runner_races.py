"""Races between the caller, the supervisor, the worker and the watcher, each pinned
down deterministically (or with generous timing) so that it cannot come back."""

from __future__ import annotations

import time

import pytest

from livemod.dlfl.scene import Scene
from livemod.runner import LiveSession, ManualNotifier, Playback, RunControl, RunResult, execute
from livemod.runner import session as session_module
from livemod.runner.batch import SerialExecutor, make_variants, run_batch
from livemod.runner.execute import script_namespace
from livemod.runner.instrument import CANCEL_FLAG
from livemod.runner.playback import Action, RunPosition
from livemod.runner.recording import StepRecorder

from .runner_scripts.support import (
    closing_session,
    next_result,
    settle,
    vertex_count,
    vertices_script,
    wait_until,
)


def is_ok(r: RunResult) -> bool:
    return r.status == "ok"


# -- RunControl.attach against a cancel from another thread ---------------------------


class _CancelsOnFirstClear(dict):
    """A run namespace whose first write of ``False`` to the cancel flag lets a
    cancel from another thread run in full between the read of the control's flag
    and the write of what was read: the interleaving that lost the cancel."""

    def __init__(self, base: dict, control: RunControl) -> None:
        super().__init__(base)
        self.control = control
        self.armed = True

    def __setitem__(self, key: str, value: object) -> None:
        if key == CANCEL_FLAG and value is False and self.armed:
            self.armed = False
            self.control.cancel()  # sets the flag to True in here, first
        super().__setitem__(key, value)


def test_a_cancel_while_the_run_attaches_leaves_the_scripts_flag_set(tmp_path):
    script = str(tmp_path / "s.py")
    control = RunControl()
    namespace = _CancelsOnFirstClear(script_namespace(script, None), control)
    control.attach(namespace, StepRecorder(script, Scene(), control))
    assert control.cancelled
    assert namespace[CANCEL_FLAG] is True  # else `while True: pass` would spin on


# -- Playback's lock-free read ------------------------------------------------------


class _WatchedPlayback(Playback):
    """Asks ``should_pause(index)`` after every attribute write, as a step hook in
    another thread may at any moment (it reads without the lock)."""

    probe = 2
    seen: list[bool]

    def __setattr__(self, name: str, value: object) -> None:
        super().__setattr__(name, value)
        if hasattr(self, "seen"):
            self.seen.append(self.should_pause(self.probe))


def test_no_write_shows_a_step_hook_a_pause_nobody_asked_for():
    playback = _WatchedPlayback()
    playback.seen = []
    live = RunPosition(live=True, done=1)  # a run working on its second step
    for action, k in ((Action.GOTO, 5), (Action.END, 0), (Action.GOTO, 9), (Action.PLAY, 0),
                      (Action.GOTO, 3), (Action.RUN_ENDED, 4)):
        playback.apply(action, live, k)  # step 2 is before every step asked for
    assert len(playback.seen) >= 12 and not any(playback.seen)


# -- a script's own BaseException ---------------------------------------------------


def test_a_base_exception_the_script_raises_is_its_error(tmp_path):
    path = tmp_path / "stops.py"
    path.write_text("createVertex((0, 0, 0))\nclass Stop(BaseException):\n    pass\n"
                    "raise Stop('halt')\n")
    scene_before = Scene()
    outcome = execute(str(path), base=scene_before)
    assert outcome.status == "error" and outcome.error is not None
    assert outcome.error.line == 4 and outcome.error.message == "Stop: halt"
    assert outcome.run.step_hook is None  # the recording was released


def test_a_keyboard_interrupt_in_the_main_thread_still_propagates(tmp_path):
    path = tmp_path / "interrupts.py"
    path.write_text("createVertex((0, 0, 0))\nraise KeyboardInterrupt\n")
    with pytest.raises(KeyboardInterrupt):  # Ctrl-C of `livemod run` must stop it
        execute(str(path))


@pytest.mark.timeout(60)
def test_a_keyboard_interrupt_the_script_raises_in_a_session_is_an_error(tmp_path):
    script = tmp_path / "model.py"
    script.write_text("createVertex((0, 0, 0))\nraise KeyboardInterrupt\n")
    live = LiveSession(str(script), notifier=ManualNotifier(), preview=False, debounce=0.02)
    with closing_session(live):
        live.start()
        result = next_result(live)
        assert result.status == "error" and result.error is not None
        assert result.error.line == 2 and "KeyboardInterrupt" in result.error.message
        assert live.activity is None
        script.write_text(vertices_script(3))
        live.reload()
        assert vertex_count(next_result(live)) == 3


# -- stale runs -----------------------------------------------------------------------


@pytest.mark.timeout(60)
def test_a_run_superseded_after_its_last_check_posts_nothing(tmp_path):
    """The first run passes its last check, then sleeps through the save: it ends
    "ok", but it ran old text, so only the newer run's result may show."""
    script = tmp_path / "model.py"
    script.write_text("createVertex((0, 0, 0))\nimport time\ntime.sleep(0.45)\n")
    live = LiveSession(str(script), notifier=ManualNotifier(), preview=False, debounce=0.01)
    with closing_session(live):
        live.start()
        deadline = time.monotonic() + 10
        while live.activity is None and time.monotonic() < deadline:
            time.sleep(0.005)
        time.sleep(0.15)  # inside the sleep: the cancel finds no check before the end
        script.write_text(vertices_script(4))
        live.reload()
        results = settle(live)
        assert [vertex_count(r) for r in results] == [4]


@pytest.mark.timeout(60)
def test_open_runs_the_new_scripts_own_text_when_a_replay_is_asked_at_once(tmp_path):
    first, second = tmp_path / "first.py", tmp_path / "second.py"
    first.write_text(vertices_script(2))
    second.write_text(vertices_script(7))
    live = LiveSession(str(first), notifier=ManualNotifier(), preview=False)
    with closing_session(live):
        live.start()
        assert vertex_count(next_result(live, is_ok)) == 2
        live.open(str(second))
        live.set_parameters({})  # a replay with "the text that ran last"
        results = [r for r in settle(live) if r.status == "ok"]
        assert results and all(r.script == str(second) for r in results)
        assert [vertex_count(r) for r in results][-1] == 7


# -- the --mesh base, reloaded while a run loads it -----------------------------------


def _quads_obj(count: int) -> str:
    lines = []
    for q in range(count):
        x = 3 * q
        lines += [f"v {x} 0 0", f"v {x + 1} 0 0", f"v {x + 1} 1 0", f"v {x} 1 0"]
    lines += [f"f {4 * q + 1} {4 * q + 2} {4 * q + 3} {4 * q + 4}" for q in range(count)]
    return "\n".join(lines) + "\n"


@pytest.mark.timeout(60)
def test_a_mesh_file_changed_while_a_run_loads_it_is_loaded_again(tmp_path, monkeypatch):
    shape = tmp_path / "start.obj"
    shape.write_text(_quads_obj(1))
    script = tmp_path / "model.py"
    script.write_text("pass\n")
    live = LiveSession(str(script), mesh_path=str(shape), notifier=ManualNotifier(),
                       preview=False, debounce=0.01)
    loads = []
    real = session_module.base_scene

    def load_then_see_the_file_change(path: str) -> Scene:
        scene = real(path)  # the old content, read...
        if not loads:  # ...while the file is rewritten and the watcher reacts
            shape.write_text(_quads_obj(3))
            live._files_changed()
        loads.append(path)
        return scene

    monkeypatch.setattr(session_module, "base_scene", load_then_see_the_file_change)
    with closing_session(live):
        live.start()
        counts = [vertex_count(r) for r in settle(live)]
        assert counts[-1] == 12, counts


@pytest.mark.timeout(60)
def test_a_mesh_file_that_does_not_load_is_the_error_s_file(tmp_path):
    shape = tmp_path / "start.obj"
    shape.write_text("v 0 0 0\nf 1 2 3\n")
    script = tmp_path / "model.py"
    script.write_text("pass\n")
    live = LiveSession(str(script), mesh_path=str(shape), notifier=ManualNotifier(),
                       preview=False)
    with closing_session(live):
        live.start()
        result = next_result(live)
        assert result.status == "error" and result.error is not None
        assert result.error.file == str(shape), result.error


# -- batch --------------------------------------------------------------------------


def test_a_mesh_that_does_not_load_fails_each_serial_variant_alone(tmp_path):
    script = tmp_path / "s.py"
    script.write_text("createVertex((0, 0, 0))\n")
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nf 1 2 3\n")
    variants = make_variants(str(script), [{"n": 1}, {"n": 2}], None, mesh_path=str(bad))
    results = run_batch(variants, SerialExecutor(), quiet=True)
    assert [r.status for r in results] == ["error", "error"]
    assert all(r.error is not None and "bad.obj" in r.error for r in results)


# -- failures after the script ran must still reach the caller ------------------------


class _WatchLimitNotifier(ManualNotifier):
    """Refuses every watch after the first, as inotify does at its watch limit."""

    def __init__(self) -> None:
        super().__init__()
        self.calls = 0

    def watch(self, folders: set[str]) -> None:
        self.calls += 1
        if self.calls > 1:
            raise OSError(28, "inotify watch limit reached")
        super().watch(folders)


@pytest.mark.timeout(60)
def test_a_folder_that_cannot_be_watched_does_not_lose_the_runs_result(tmp_path):
    (tmp_path / "helpers").mkdir()
    (tmp_path / "helpers" / "shape.py").write_text("COUNT = 3\n")
    script = tmp_path / "model.py"
    script.write_text("from helpers import shape\n" + vertices_script(3))
    live = LiveSession(str(script), notifier=_WatchLimitNotifier(), preview=False)
    with closing_session(live):
        live.start()
        assert vertex_count(next_result(live)) == 3


@pytest.mark.timeout(60)
def test_a_failure_while_publishing_is_posted_as_the_runs_error(tmp_path, monkeypatch):
    script = tmp_path / "model.py"
    script.write_text(vertices_script(2))

    def broken(scene: Scene) -> None:
        raise RuntimeError("snapshot failed")

    monkeypatch.setattr(session_module, "snapshot_scene", broken)
    live = LiveSession(str(script), notifier=ManualNotifier(), preview=False)
    with closing_session(live):
        live.start()
        result = next_result(live)
        assert result.status == "error" and result.error is not None
        assert "snapshot failed" in result.error.message
        assert live.activity is None


def test_a_current_object_id_the_scene_does_not_hold_names_no_object(tmp_path):
    path = tmp_path / "model.py"
    path.write_text("from livemod.dlfl import current_scene\n"
                    "createVertex((0, 0, 0))\ncurrent_scene().current = 42\n")
    from livemod.runner import run_script

    result = run_script(str(path))
    assert result.status == "ok" and result.current_object is None


# -- a forced interrupt that lands after the script ended --------------------------------



def test_a_user_cancel_whose_interrupt_lands_after_the_script_still_says_cancelled(
        tmp_path, monkeypatch):
    script = tmp_path / "model.py"
    script.write_text(vertices_script(3))

    def ends_then_interrupted(*args, control, **kwargs):
        while not control.cancelled:  # the script is done; the interrupt is on its way
            time.sleep(0.005)
        raise session_module.Cancelled  # as PyThreadState_SetAsyncExc delivers it

    with closing_session(LiveSession(str(script), notifier=ManualNotifier(),
                                     preview=False)) as live:
        live.start()
        first = next_result(live, is_ok)
        monkeypatch.setattr(session_module, "execute", ends_then_interrupted)
        live.reload()
        wait_until(lambda: live.activity is not None)
        live.cancel()
        cancelled = next_result(live, lambda r: r.status == "cancelled")
        assert cancelled.run_id == first.run_id + 1 and cancelled.stale
        assert vertex_count(cancelled) == 3  # the last good mesh stays shown


@pytest.mark.timeout(60)
def test_an_endless_generator_expression_is_stopped_by_the_next_save(tmp_path):
    # no check can be compiled into a comprehension: the forced interrupt stops it (how
    # soon is bench/bench_responsiveness.py's to time)
    script = tmp_path / "model.py"
    script.write_text("any(False for _ in iter(int, 1))\n")
    with closing_session(LiveSession(str(script), notifier=ManualNotifier(),
                                     preview=False)) as live:
        live.start()
        wait_until(lambda: live.activity is not None)
        script.write_text(vertices_script(2))
        live.reload()
        assert vertex_count(next_result(live, is_ok)) == 2
        wait_until(lambda: not live.background_runs)  # stopped, not left looping
