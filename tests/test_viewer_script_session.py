"""The script shown and its session: starting, closing, retargeting, taking results."""

from __future__ import annotations

import queue
from pathlib import Path
from typing import Any

import pytest

from livemod.dlfl.scene import Selection
from livemod.runner.cli import run_summary
from livemod.runner.results import RunResult, RunStatus
from livemod.viewer.runs import RunTracker
from livemod.viewer.script_session import ScriptSession

from .viewer_support import FakePlayback


class FakeSession(FakePlayback):
    """A session that records its life and what it is given, in order."""

    def __init__(self, script: str, mesh_path: str | None) -> None:
        super().__init__()
        self.made_with = (script, mesh_path)
        self.results: queue.Queue[RunResult] = queue.Queue()
        self.parameters: dict[str, Any] = {}
        self.activity = None
        self.empty_script = None
        self.background_runs = ()

    def set_parameters(self, values: dict[str, Any]) -> None:
        self.calls.append(("set_parameters", values))

    def reset_parameters(self, names: list[str] | None = None) -> None:
        self.calls.append(("reset_parameters", names))

    def set_selection(self, selection: Selection | None) -> None:
        self.calls.append(("set_selection", selection))

    def start(self) -> None:
        self.calls.append(("start",))

    def close(self) -> None:
        self.calls.append(("close",))


def _scripts(tmp_path: Path, output: str | None = None,
             ) -> tuple[ScriptSession, list[FakeSession], list[str], RunTracker]:
    made: list[FakeSession] = []
    echoed: list[str] = []

    def factory(script: str, mesh_path: str | None) -> FakeSession:
        made.append(FakeSession(script, mesh_path))
        return made[-1]

    runs = RunTracker()
    scripts = ScriptSession(str(tmp_path / "a.py"), None, factory, runs, echoed.append, output)
    return scripts, made, echoed, runs


def test_start_gives_the_new_session_its_selection_and_parameters_first(tmp_path) -> None:
    scripts, made, _, runs = _scripts(tmp_path)
    assert scripts.session is None and not runs.waiting
    picks = Selection(faces=(2, 5))
    scripts.start(picks, {"n": 3})
    assert made[0].made_with == (str((tmp_path / "a.py").resolve()), None)
    assert made[0].calls == [("set_selection", picks), ("set_parameters", {"n": 3}), ("start",)]
    assert scripts.live() is made[0] and runs.waiting
    scripts.close()
    scripts.start(Selection())  # nothing to give: no selection, no parameters
    assert made[1].calls == [("start",)] and scripts.live() is made[1]


def test_close_closes_the_session_once(tmp_path) -> None:
    scripts, made, _, _ = _scripts(tmp_path)
    scripts.start(Selection())
    scripts.close()
    scripts.close()
    assert made[0].calls == [("start",), ("close",)] and scripts.session is None
    with pytest.raises(AssertionError, match="the session is closed"):
        scripts.live()


def test_retarget_replaces_the_script_or_the_mesh_by_the_suffix(tmp_path, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    scripts, made, _, _ = _scripts(tmp_path)
    scripts.start(Selection())
    assert scripts.retarget("box.OBJ") is False
    assert (scripts.script, scripts.mesh_path) == (str(tmp_path / "a.py"),
                                                   str(tmp_path / "box.OBJ"))
    assert scripts.retarget("b.PY") is True
    assert (scripts.script, scripts.mesh_path) == (str(tmp_path / "b.PY"),
                                                   str(tmp_path / "box.OBJ"))
    assert made[0].calls == [("start",)]  # the session is the caller's to restart
    scripts.close()
    scripts.start(Selection())
    assert made[1].made_with == (str(tmp_path / "b.PY"), str(tmp_path / "box.OBJ"))


def test_take_results_says_each_end_once_and_shows_the_newest(tmp_path) -> None:
    scripts, made, echoed, runs = _scripts(tmp_path, output="out.obj")
    scripts.start(Selection())
    shown: list[RunResult] = []
    scripts.take_results(shown.append)
    assert shown == [] and echoed == []  # nothing posted: nothing shown
    one = RunResult.finished(1, "a.py", (), None, 0.5)
    held = RunResult.paused(2, "a.py", (), 0, None, 0.1)
    two = RunResult.finished(2, "a.py", (), None, 0.25)
    for result in (one, held, two):
        made[0].results.put(result)
    scripts.take_results(shown.append)
    assert shown == [two]  # the newest posted only
    assert echoed == [run_summary(one), "run 1: wrote out.obj",
                      run_summary(two), "run 2: wrote out.obj"]
    again = RunResult.finished(2, "a.py", (), None, 0.25)  # (run 2 with its preview)
    made[0].results.put(again)
    scripts.take_results(shown.append)
    assert shown == [two, again] and len(echoed) == 4  # no second summary


def test_a_failed_run_names_no_output_file(tmp_path) -> None:
    scripts, made, echoed, _ = _scripts(tmp_path, output="out.obj")
    scripts.start(Selection())
    failed = RunResult.failed(1, "a.py", RunStatus.CANCELLED, (), None, 0.1, last_good=None)
    made[0].results.put(failed)
    scripts.take_results(lambda result: None)
    assert echoed == [run_summary(failed)]


def test_a_result_the_window_cannot_show_is_told_and_the_window_goes_on(
        tmp_path, capsys) -> None:
    scripts, made, echoed, runs = _scripts(tmp_path)
    scripts.start(Selection())
    made[0].results.put(RunResult.finished(4, "a.py", (), None, 0.5))

    def broken(result: RunResult) -> None:
        raise KeyError("no such table")

    scripts.take_results(broken)
    told = "the viewer could not show run 4: KeyError: 'no such table'"
    assert echoed[1:] == [told] and runs.viewer_error == told and not runs.waiting
    assert "KeyError: 'no such table'" in capsys.readouterr().err
