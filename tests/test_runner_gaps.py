"""Runner gaps closed in session 22: a watched folder deleted and made again, helper
modules the host imported first, a forced interrupt landing in a run's cleanup, and
an emptied script the session keeps saying it ignores."""

from __future__ import annotations

import contextlib
import ctypes
import importlib
import os
import shutil
import sys
import threading
import time

import pytest
from watchdog.events import DirDeletedEvent

from livemod.dlfl.scene import current_scene
from livemod.runner import (
    LiveSession,
    RunControl,
    WatchdogNotifier,
    execute,
)
from livemod.runner.errors import Cancelled
from livemod.runner.execute import interrupt_user_code
from livemod.runner.process import ProcessState

from .runner_scripts.support import (
    closing_session,
    drain,
    manual_session,
    next_result,
    settle,
    vertex_count,
    vertices_script,
    wait_until,
    write_by_rename,
    write_in_place,
)

execute_module = importlib.import_module("livemod.runner.execute")


# -- 1. a watched folder deleted and made again ----------------------------------------


@pytest.mark.timeout(60)
@pytest.mark.parametrize("poll", [False, True], ids=["events", "polling"])
def test_a_watched_folder_deleted_and_made_again_is_watched_again(tmp_path, poll):
    folder = tmp_path / "project"
    folder.mkdir()
    script = str(folder / "model.py")
    write_in_place(script, vertices_script(2))
    live = LiveSession(script, debounce=0.05, preview=False, poll=poll)
    with closing_session(live):
        live.start()
        assert vertex_count(next_result(live)) == 2
        shutil.rmtree(folder)
        assert drain(live, quiet=0.8) == []  # nothing to run while it is gone
        folder.mkdir()
        write_in_place(script, vertices_script(5))  # written before the new watch, maybe
        assert [vertex_count(r) for r in settle(live)] == [5]
        write_by_rename(script, vertices_script(6))  # and the new watch sees saves
        assert [vertex_count(r) for r in settle(live)] == [6]


class _FakeObserver:
    """Records the watches a WatchdogNotifier schedules (no threads, no events)."""

    def __init__(self) -> None:
        self.watches: dict[object, tuple[str, object]] = {}
        self.unscheduled: list[str] = []

    def start(self) -> None:
        pass

    def stop(self) -> None:
        pass

    def join(self, timeout: float | None = None) -> None:
        pass

    def schedule(self, handler, path, *, recursive, event_filter):  # noqa: ANN001, ANN201
        token = object()
        self.watches[token] = (path, handler)
        return token

    def unschedule(self, token) -> None:  # noqa: ANN001
        path, _ = self.watches.pop(token)
        self.unscheduled.append(path)

    def paths(self) -> list[str]:
        return sorted(path for path, _ in self.watches.values())

    def handler(self, path: str):  # noqa: ANN201
        return next(h for p, h in self.watches.values() if p == path)


def _fake_notifier() -> tuple[WatchdogNotifier, _FakeObserver, list[str]]:
    observer, reported = _FakeObserver(), []
    notifier = WatchdogNotifier(observer_factory=lambda: observer, recheck_interval=3600)
    notifier.start(reported.append)
    return notifier, observer, reported


def test_a_missing_folder_is_watched_through_its_ancestor_until_it_exists(tmp_path):
    notifier, observer, reported = _fake_notifier()
    try:
        wanted = str(tmp_path / "a" / "b")
        notifier.watch({wanted})
        assert observer.paths() == [str(tmp_path)]
        assert notifier.watched == {wanted: str(tmp_path)}
        os.makedirs(wanted)
        write_in_place(os.path.join(wanted, "model.py"), "x = 1\n")
        notifier.recheck()
        assert observer.paths() == [wanted] and observer.unscheduled == [str(tmp_path)]
        assert reported == [os.path.join(wanted, "model.py")]  # written before its watch
        notifier.recheck()
        assert reported == [os.path.join(wanted, "model.py")]  # once only
        assert notifier.watched == {wanted: wanted}
    finally:
        notifier.stop()


def test_a_folder_whose_watch_saw_it_deleted_is_watched_anew_even_with_its_old_inode(
        tmp_path):
    notifier, observer, reported = _fake_notifier()
    try:
        wanted = str(tmp_path)
        notifier.watch({wanted})
        # the folder is still there (made again, say, with the same inode): only
        # its watch's "deleted" event tells that this watch is dead
        observer.handler(wanted).dispatch(DirDeletedEvent(wanted))
        notifier.recheck()
        assert observer.unscheduled == [wanted] and observer.paths() == [wanted]
        assert reported == []  # the folder is empty
    finally:
        notifier.stop()


def test_watch_after_stop_does_nothing(tmp_path):
    notifier, observer, _ = _fake_notifier()
    notifier.watch({str(tmp_path)})
    notifier.stop()
    notifier.watch({str(tmp_path / "other")})
    notifier.recheck()
    assert observer.paths() == [str(tmp_path)] and observer.unscheduled == []


@pytest.mark.timeout(60)
def test_watch_racing_stop_on_the_real_observer_raises_nothing(tmp_path):
    folders = [str(tmp_path / f"d{k}") for k in range(4)]
    for folder in folders:
        os.mkdir(folder)
    errors: list[BaseException] = []
    before = threading.active_count()
    for round_ in range(20):
        notifier = WatchdogNotifier()
        notifier.start(lambda path: None)

        def keep_watching(notifier=notifier, round_=round_) -> None:  # noqa: ANN001
            try:
                for k in range(30):
                    notifier.watch({folders[(k + round_) % 4]})
            except BaseException as exc:  # noqa: BLE001  (any error fails the test)
                errors.append(exc)

        thread = threading.Thread(target=keep_watching)
        thread.start()
        notifier.stop()
        thread.join()
    assert errors == []
    deadline = time.monotonic() + 10
    while threading.active_count() > before and time.monotonic() < deadline:
        time.sleep(0.05)
    assert threading.active_count() <= before


# -- 2. a helper module the host imported before the first run ---------------------


def _host_imports(tmp_path, monkeypatch, name: str, text: str):  # noqa: ANN001, ANN202
    """Write ``name``.py in ``tmp_path`` and import it as the host would."""
    (tmp_path / f"{name}.py").write_text(text)
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.delitem(sys.modules, name, raising=False)
    return importlib.import_module(name)


def test_a_helper_the_host_imported_first_is_fresh_in_each_run_and_given_back(
        tmp_path, monkeypatch):
    host_copy = _host_imports(tmp_path, monkeypatch, "helper_host", "VALUE = 2\n")
    script = tmp_path / "main_host.py"
    script.write_text("import helper_host\nfor i in range(helper_host.VALUE):\n"
                      "    createVertex((i, 0, 0))\n")
    path = list(sys.path)
    first = execute(str(script))
    assert first.status == "ok" and first.scene.mesh.counts()[0] == 2
    assert first.modules == (str(tmp_path / "helper_host.py"),)  # so it is watched
    (tmp_path / "helper_host.py").write_text("VALUE = 5  # edited\n")
    assert execute(str(script)).scene.mesh.counts()[0] == 5
    assert sys.modules["helper_host"] is host_copy and host_copy.VALUE == 2
    assert _local_names(tmp_path) == {"helper_host"} and sys.path == path


@pytest.mark.timeout(60)
def test_a_helper_the_host_imported_first_is_watched_by_the_session(tmp_path, monkeypatch):
    host_copy = _host_imports(tmp_path, monkeypatch, "helper_seen", "COUNT = 2\n")
    script = tmp_path / "model.py"
    script.write_text("import helper_seen\nfor i in range(helper_seen.COUNT):\n"
                      "    createVertex((i, 0, 0))\n")
    with manual_session(script) as (live, notifier):
        assert vertex_count(next_result(live)) == 2
        (tmp_path / "helper_seen.py").write_text("COUNT = 7  # edited\n")
        notifier.fire(str(tmp_path / "helper_seen.py"))
        assert [vertex_count(r) for r in settle(live)] == [7]
    assert sys.modules["helper_seen"] is host_copy


# -- 3. a forced interrupt landing in a run's cleanup ----------------------------------


def _local_names(folder) -> set[str]:  # noqa: ANN001
    """Names in ``sys.modules`` of modules whose file lies in ``folder``."""
    return {name for name, module in list(sys.modules.items())
            if str(getattr(module, "__file__", None) or "").startswith(str(folder) + os.sep)}


def _cancelled_once(real):  # noqa: ANN001, ANN202
    """``real``, raising Cancelled (as PyThreadState_SetAsyncExc would) on its first call."""
    calls = []

    def step(*args):  # noqa: ANN002, ANN202
        calls.append(args)
        if len(calls) == 1:
            raise Cancelled
        return real(*args)

    return step


@pytest.mark.parametrize("owner,step", [(execute_module._HostState, "_remove_run_modules"),
                                        (ProcessState, "restore")])
def test_an_interrupt_landing_in_the_cleanup_still_gives_back_path_and_modules(
        tmp_path, monkeypatch, owner, step):
    host_copy = _host_imports(tmp_path, monkeypatch, "helper_late", "VALUE = 1\n")
    (tmp_path / "other_late.py").write_text("OTHER = 1\n")
    script = tmp_path / "late.py"
    script.write_text("import helper_late, other_late\ncreateVertex((0, 0, 0))\n")
    path = list(sys.path)
    monkeypatch.setattr(owner, step, _cancelled_once(getattr(owner, step)))
    outcome = execute(str(script))
    assert outcome.status == "cancelled"  # it was being cancelled: that still shows
    assert outcome.error is not None and outcome.error.line == 2  # its last step
    assert sys.path == path and _local_names(tmp_path) == {"helper_late"}
    assert sys.modules["helper_late"] is host_copy


def test_an_interrupt_landing_while_the_runs_modules_are_looked_at_gives_them_back(
        tmp_path, monkeypatch):
    # the same point in the code before this session's change (local_modules' finally)
    (tmp_path / "first_late.py").write_text("FIRST = 1\n")
    (tmp_path / "other_late.py").write_text("OTHER = 1\n")
    script = tmp_path / "late.py"
    script.write_text("import first_late, other_late\ncreateVertex((0, 0, 0))\n")
    path = list(sys.path)
    real, raised = execute_module.is_user_file, []

    def interrupted_once(filename: str, script_path: str) -> bool:
        if not raised and filename.endswith("late.py") and filename != str(script):
            raised.append(filename)
            raise Cancelled
        return real(filename, script_path)

    monkeypatch.setattr(execute_module, "is_user_file", interrupted_once)
    assert execute(str(script)).status == "cancelled"
    assert len(raised) == 1
    assert sys.path == path and _local_names(tmp_path) == set()


def test_an_interrupt_landing_as_the_script_ends_cancels_the_run_cleanly(tmp_path, monkeypatch):
    script = tmp_path / "ends.py"
    script.write_text("createVertex((0, 0, 0))\n")
    path, scene = list(sys.path), current_scene()
    monkeypatch.setattr(execute_module, "_leave_user_code",
                        _cancelled_once(execute_module._leave_user_code))
    outcome = execute(str(script))
    assert outcome.status == "cancelled" and outcome.error is not None
    assert outcome.error.kind == "cancelled"
    assert sys.path == path and current_scene() is scene


def _innermost(thread: threading.Thread) -> str | None:
    """The name of the function ``thread`` runs now (its innermost Python frame)."""
    frame = sys._current_frames().get(thread.ident)  # type: ignore[arg-type]
    return None if frame is None else frame.f_code.co_name


@pytest.mark.timeout(60)
def test_an_interrupt_sent_as_the_run_leaves_user_code_is_raised_by_the_leaving():
    """The supervisor sends under the lock the worker leaves by: an exception it sent
    just before comes out of _leave_user_code (in _run_code's finally), never later."""
    where: list[str] = []
    for _ in range(20):
        ready, go = threading.Event(), threading.Event()

        def worker(ready: threading.Event = ready, go: threading.Event = go) -> None:
            execute_module._enter_user_code()
            ready.set()
            go.wait()
            try:
                execute_module._leave_user_code()  # waits for the lock the sender holds
            except Cancelled:
                where.append("leaving")
                execute_module._leave_user_code()  # as _exec does after it
                return
            try:
                for _ in range(1000):  # bytecodes enough for a pending exception
                    pass
            except Cancelled:
                where.append("after")

        thread = threading.Thread(target=worker)
        thread.start()
        ready.wait()
        with execute_module._INTERRUPT_LOCK:
            go.set()
            # the worker is in _leave_user_code now, waiting for the lock (or about to)
            wait_until(lambda thread=thread: _innermost(thread) == "_leave_user_code")
            ctypes.pythonapi.PyThreadState_SetAsyncExc(
                ctypes.c_ulong(thread.ident), ctypes.py_object(Cancelled))
        thread.join(10)
        assert thread.ident not in execute_module._IN_USER_CODE
    assert where == ["leaving"] * 20


@pytest.mark.timeout(60)
def test_code_of_a_script_s_file_outside_a_run_is_never_interrupted(tmp_path):
    script = str(tmp_path / "model.py")
    code = compile("def spin(stop):\n    while not stop.is_set():\n        pass\n", script, "exec")
    namespace: dict = {}
    exec(code, namespace)  # noqa: S102
    stop = threading.Event()
    thread = threading.Thread(target=namespace["spin"], args=(stop,))
    thread.start()
    try:
        time.sleep(0.05)  # spinning in the script's file, but not inside a run
        assert interrupt_user_code(thread, script) is False
    finally:
        stop.set()
        thread.join()


@pytest.mark.timeout(60)
def test_code_of_a_script_s_file_inside_a_run_is_interrupted(tmp_path):
    (tmp_path / "spin_in_run.py").write_text("def spin():\n    while True:\n        pass\n")
    script = tmp_path / "model.py"
    script.write_text("import spin_in_run\nspin_in_run.spin()\n")
    control, outcomes = RunControl(), []
    thread = threading.Thread(target=lambda: outcomes.append(
        execute(str(script), control=control)))
    thread.start()
    deadline = time.monotonic() + 10
    while not interrupt_user_code(thread, str(script)):
        assert time.monotonic() < deadline
        time.sleep(0.01)
    thread.join(10)
    assert [o.status for o in outcomes] == ["cancelled"]


@pytest.mark.timeout(60)
def test_an_interrupt_asked_for_another_run_is_not_sent(tmp_path):
    # an abandoned run's thread id may be a newer run's once it has ended: the
    # interrupt names its run, and a thread running any other is left alone
    (tmp_path / "spin_in_run.py").write_text("def spin():\n    while True:\n        pass\n")
    script = tmp_path / "model.py"
    script.write_text("import spin_in_run\nspin_in_run.spin()\n")
    running, other, outcomes = RunControl(), RunControl(), []
    thread = threading.Thread(target=lambda: outcomes.append(
        execute(str(script), control=running)))
    thread.start()
    wait_until(lambda: _innermost(thread) == "spin")  # in the run's own code, interruptible
    assert interrupt_user_code(thread, str(script), other) is False
    assert interrupt_user_code(thread, str(script), running) is True
    thread.join(10)
    assert [o.status for o in outcomes] == ["cancelled"]


# -- 4. an emptied script --------------------------------------------------------------


@contextlib.contextmanager
def _three_vertex_session(tmp_path):  # noqa: ANN001, ANN202
    """``(session, script, notifier)``: a started session on ``model.py``, which
    makes 3 vertices, its first result taken; closed afterwards."""
    script = tmp_path / "model.py"
    script.write_text(vertices_script(3))
    with manual_session(script) as (live, notifier):
        assert vertex_count(next_result(live)) == 3
        yield live, script, notifier


@pytest.mark.timeout(60)
@pytest.mark.parametrize("empty", ["", "  \n\n\t\n"], ids=["no bytes", "whitespace"])
def test_an_emptied_script_keeps_the_last_result_and_says_so(tmp_path, empty):
    with _three_vertex_session(tmp_path) as (live, script, notifier):
        assert live.empty_script is None
        write_in_place(str(script), empty)
        notifier.fire(str(script))
        assert drain(live, quiet=0.5) == []  # nothing runs: the last mesh stays shown
        assert live.empty_script == str(script)
        write_in_place(str(script), vertices_script(4))
        notifier.fire(str(script))
        assert [vertex_count(r) for r in settle(live)] == [4]
        assert live.empty_script is None


@pytest.mark.timeout(60)
def test_an_emptied_script_given_its_old_text_back_is_not_empty_any_more(tmp_path):
    with _three_vertex_session(tmp_path) as (live, script, notifier):
        write_in_place(str(script), "")
        notifier.fire(str(script))
        wait_until(lambda: live.empty_script == str(script))
        write_in_place(str(script), vertices_script(3))  # undone: the same text again
        notifier.fire(str(script))
        wait_until(lambda: live.empty_script is None)
        assert drain(live, quiet=0.5) == []  # the text that shows ran already


@pytest.mark.timeout(60)
def test_a_reload_of_an_emptied_script_runs_it_and_clears_the_state(tmp_path):
    with _three_vertex_session(tmp_path) as (live, script, notifier):
        write_in_place(str(script), "\n")
        notifier.fire(str(script))
        wait_until(lambda: live.empty_script == str(script))
        live.reload()  # asked for: the empty script runs
        result = next_result(live)
        assert result.status == "ok" and result.arrays is None
        assert live.empty_script is None

