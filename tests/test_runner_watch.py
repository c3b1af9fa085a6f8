"""Watching: debounce with an injected notifier, then editor saves on the real file system."""

from __future__ import annotations

import os
import shutil
import threading
import time

import pytest
from watchdog.events import DirDeletedEvent

from livemod.runner import FileWatcher, LiveSession, ManualNotifier, WatchdogNotifier

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
    write_vim_style,
)

# -- FileWatcher with an injected notifier (no timing on the file system) ----------


@pytest.mark.timeout(60)
def test_events_in_a_burst_give_one_callback(tmp_path):
    notifier, calls = ManualNotifier(), []
    watched = str(tmp_path / "a.py")
    watcher = FileWatcher(lambda: calls.append(time.monotonic()), debounce=0.3,
                          notifier=notifier)
    watcher.start()
    watcher.set_files([watched])
    try:
        assert notifier.folders == {str(tmp_path)}
        for _ in range(5):
            notifier.fire(watched)
        notifier.fire(str(tmp_path / "unrelated.py"))
        deadline = time.monotonic() + 10
        while not calls and time.monotonic() < deadline:
            time.sleep(0.01)
        time.sleep(0.6)
        assert len(calls) == 1
    finally:
        watcher.close()


@pytest.mark.timeout(60)
def test_unchanged_content_is_skipped_and_changes_run(tmp_path):
    script = tmp_path / "m.py"
    script.write_text(vertices_script(2))
    with manual_session(script) as (live, notifier):
        assert vertex_count(next_result(live)) == 2
        notifier.fire(str(script))  # touched, not changed
        assert drain(live, quiet=0.5) == []
        script.write_text(vertices_script(3))
        notifier.fire(str(script))
        assert vertex_count(next_result(live)) == 3


@pytest.mark.timeout(60)
def test_vanished_script_waits_for_its_return(tmp_path):
    script = tmp_path / "gone.py"
    script.write_text(vertices_script(2))
    with manual_session(script) as (live, notifier):
        next_result(live)
        script.unlink()
        notifier.fire(str(script))
        assert drain(live, quiet=0.4) == []
        script.write_text(vertices_script(4))
        notifier.fire(str(script))
        assert vertex_count(next_result(live)) == 4


@pytest.mark.timeout(60)
def test_a_script_created_after_the_session_started_runs_on_its_first_save(tmp_path):
    script = tmp_path / "later.py"
    with manual_session(script) as (live, notifier):
        assert next_result(live).status == "error"  # not there yet
        script.write_text(vertices_script(2))
        notifier.fire(str(script))
        assert vertex_count(next_result(live)) == 2
        script.write_text(vertices_script(3))
        notifier.fire(str(script))
        assert vertex_count(next_result(live)) == 3


# -- real file system (watchdog) ----------------------------------------------------


def start_session(tmp_path, text: str, **options) -> tuple[LiveSession, str]:
    script = tmp_path / "model.py"
    script.write_text(text)
    live = LiveSession(str(script), preview=False, **options)
    live.start()
    first = next_result(live)
    assert first.status == "ok", first.error
    time.sleep(0.2)  # let the observer settle before the saves under test
    return live, str(script)


@pytest.mark.timeout(60)
@pytest.mark.parametrize("save", [write_by_rename, write_in_place, write_vim_style])
def test_each_editor_save_style_triggers_exactly_one_run(tmp_path, save):
    live, script = start_session(tmp_path, vertices_script(2))
    with closing_session(live):
        save(script, vertices_script(5))
        results = settle(live)
        assert [vertex_count(r) for r in results] == [5]
        save(script, vertices_script(6))
        assert [vertex_count(r) for r in settle(live)] == [6]


@pytest.mark.timeout(60)
def test_a_burst_of_saves_ends_with_the_last_content(tmp_path):
    live, script = start_session(tmp_path, vertices_script(1))
    with closing_session(live):
        for n in range(2, 22):
            write_by_rename(script, vertices_script(n))
            time.sleep(0.05)
        results = settle(live)
        assert results and vertex_count(results[-1]) == 21
        assert len(results) < 20  # debounced
        run_ids = [r.run_id for r in results]
        assert run_ids == sorted(run_ids)


@pytest.mark.timeout(60)
def test_an_infinite_loop_is_cancelled_by_the_next_save(tmp_path):
    live, script = start_session(tmp_path, vertices_script(1))
    with closing_session(live):
        write_in_place(script, "createVertex((0, 0, 0))\nwhile True:\n    pass\n")
        time.sleep(0.6)  # the looping run is under way
        write_by_rename(script, vertices_script(3))
        result = next_result(live)  # how soon: bench/bench_runner.py's cancel latency
        assert vertex_count(result) == 3


@pytest.mark.timeout(60)
def test_imported_helper_modules_are_watched_and_reloaded(tmp_path):
    (tmp_path / "helper.py").write_text("COUNT = 2\n")
    live, script = start_session(
        tmp_path, "import helper\nfor i in range(helper.COUNT):\n    createVertex((i, 0, 0))\n")
    with closing_session(live):
        write_by_rename(str(tmp_path / "helper.py"), "COUNT = 7\n")
        assert [vertex_count(r) for r in settle(live)] == [7]
        write_in_place(script, "import helper\ncreateVertex((0, 0, helper.COUNT))\n")
        assert [vertex_count(r) for r in settle(live)] == [1]


def _quads_obj(count: int) -> str:
    """An OBJ of ``count`` separate unit squares (``4 * count`` vertices)."""
    lines = []
    for k in range(count):
        lines += [f"v {x + 2 * k} {y} 0" for x, y in ((0, 0), (1, 0), (1, 1), (0, 1))]
        lines.append(f"f {4 * k + 1} {4 * k + 2} {4 * k + 3} {4 * k + 4}")
    return "\n".join(lines) + "\n"


@pytest.mark.timeout(60)
def test_loaded_mesh_files_are_watched_and_read_again(tmp_path):
    shape = tmp_path / "shape.obj"
    shape.write_text(_quads_obj(1))
    live, _ = start_session(tmp_path, 'load("shape.obj")\n')
    with closing_session(live):
        write_by_rename(str(shape), _quads_obj(3))
        assert [vertex_count(r) for r in settle(live)] == [12]
        write_by_rename(str(shape), "f 1 2 3\n")  # malformed: the run fails, still watched
        assert [r.status for r in settle(live)] == ["error"]
        write_in_place(str(shape), _quads_obj(2))
        assert [vertex_count(r) for r in settle(live)] == [8]


@pytest.mark.timeout(60)
def test_the_mesh_file_a_session_starts_from_is_watched(tmp_path):
    shape = tmp_path / "start.obj"
    shape.write_text(_quads_obj(1))
    live, _ = start_session(tmp_path, "createVertex((5, 5, 5))\n", mesh_path=str(shape))
    with closing_session(live):
        write_by_rename(str(shape), _quads_obj(2))
        # the new file's 8 vertices and the script's point-sphere
        assert [vertex_count(r) for r in settle(live)] == [9]


@pytest.mark.timeout(60)
def test_files_a_run_writes_are_not_watched(tmp_path):
    """A script that rewrites its input, or a session whose output is the script's
    input, would otherwise re-run itself for ever."""
    shape = tmp_path / "shape.obj"
    shape.write_text(_quads_obj(1))
    saves, output = tmp_path / "saves.py", tmp_path / "output.py"
    saves.write_text('load("shape.obj")\nsubdivide("catmull-clark")\nsave("shape.obj")\n')
    output.write_text('load("shape.obj")\nsubdivide("catmull-clark")\n')
    for script, options in ((saves, {}), (output, {"output": str(shape)})):
        live = LiveSession(str(script), preview=False, **options)
        with closing_session(live):
            live.start()
            assert next_result(live).status == "ok"
            assert drain(live, quiet=1.0) == []  # no run started by its own write
            live.reload()  # now the file is known: a second run rewrites it again
            assert [r.status for r in drain(live, quiet=1.0)] == ["ok"]


@pytest.mark.timeout(60)
def test_a_syntax_error_keeps_the_last_good_mesh_marked_stale(tmp_path):
    live, script = start_session(tmp_path, vertices_script(3))
    with closing_session(live):
        write_by_rename(script, "createVertex((0, 0, 0)\n")
        broken = next_result(live)
        assert broken.status == "error" and broken.stale and vertex_count(broken) == 3
        assert broken.error is not None and broken.error.kind == "syntax"
        write_by_rename(script, vertices_script(4))
        fixed = next_result(live)
        assert fixed.status == "ok" and not fixed.stale and vertex_count(fixed) == 4


@pytest.mark.timeout(60)
def test_polling_fallback_sees_saves(tmp_path):
    live, script = start_session(tmp_path, vertices_script(2), poll=True)
    with closing_session(live):
        write_vim_style(script, vertices_script(3))
        assert vertex_count(next_result(live)) == 3


@pytest.mark.timeout(60)
def test_open_switches_scripts(tmp_path):
    live, _ = start_session(tmp_path, vertices_script(2))
    other = tmp_path / "other.py"
    other.write_text(vertices_script(9))
    with closing_session(live):
        live.open(str(other))
        result = next_result(live)
        assert result.script == str(other) and vertex_count(result) == 9
        write_in_place(str(other), vertices_script(8))
        assert vertex_count(next_result(live)) == 8


@pytest.mark.timeout(60)
def test_close_stops_the_threads(tmp_path):
    before = threading.active_count()
    live, _ = start_session(tmp_path, vertices_script(1))
    live.close()
    assert live.join(10)
    deadline = time.monotonic() + 10
    while threading.active_count() > before and time.monotonic() < deadline:
        time.sleep(0.05)
    assert threading.active_count() <= before
    assert os.path.exists(tmp_path / "model.py")


@pytest.mark.timeout(60)
def test_an_endless_loop_in_a_helper_module_is_interrupted(tmp_path):
    (tmp_path / "spinner.py").write_text("def spin():\n    while True:\n        pass\n")
    script = tmp_path / "uses_spinner.py"
    script.write_text("import spinner\ncreateVertex((0, 0, 0))\nspinner.spin()\n")
    live = LiveSession(str(script), notifier=ManualNotifier(), preview=False)
    with closing_session(live):
        live.start()
        time.sleep(0.3)
        script.write_text("createVertex((0, 0, 0))\ncreateVertex((1, 0, 0))\n")
        live.reload()
        result = next_result(live)  # how soon is bench/bench_responsiveness.py's to time
        assert result.status == "ok" and vertex_count(result) == 2
        wait_until(lambda: not live.background_runs)  # the interrupt stopped it


@pytest.mark.timeout(60)
def test_a_deleted_script_runs_again_when_it_comes_back(tmp_path):
    live, script = start_session(tmp_path, vertices_script(2))
    with closing_session(live):
        os.remove(script)
        assert drain(live, quiet=0.6) == []  # nothing to run while it is gone
        write_in_place(script, vertices_script(5))
        assert [vertex_count(r) for r in settle(live)] == [5]


# -- a watched folder deleted and made again, or missing, is watched again


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


# -- watch and stop from two threads


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
