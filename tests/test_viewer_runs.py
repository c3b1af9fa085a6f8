"""The run tracker (GL-free): what the window knows of the session's runs."""

from __future__ import annotations

import queue
from types import SimpleNamespace

from livemod.viewer.runs import RunTracker


def _result(run_id: int, status: str = "ok", steps: int = 3, step_index: int | None = None,
            arrays: object = None) -> SimpleNamespace:
    return SimpleNamespace(run_id=run_id, status=status, steps=tuple(range(steps)),
                           step_index=step_index, arrays=arrays, error=None)


def test_results_arrive_oldest_first_without_blocking() -> None:
    runs, posted = RunTracker(), queue.Queue()
    assert runs.arrived(posted) == []
    first, second = _result(1), _result(2)
    posted.put(first)
    posted.put(second)
    assert runs.arrived(posted) == [first, second] and posted.empty()


def test_a_run_ends_once_whatever_is_posted_after_it() -> None:
    runs = RunTracker()
    assert not runs.newly_ended(_result(1, "paused", step_index=0))  # a step is no end
    assert runs.newly_ended(_result(1))
    assert not runs.newly_ended(_result(1))  # posted again with its preview
    assert runs.newly_ended(_result(2, "error"))
    assert not runs.newly_ended(_result(1, "cancelled"))  # older than one said ended
    runs.forget()  # another script: its runs count from 1 again
    assert runs.newly_ended(_result(1))


def test_the_step_count_is_the_last_ended_runs() -> None:
    runs = RunTracker()
    runs.expect()
    runs.take(_result(1, steps=5))
    assert not runs.waiting and runs.total_steps == 5 and runs.steps() == 5
    assert runs.shown_step() == 4 and runs.ended()
    runs.take(_result(2, "paused", steps=2, step_index=1))  # a replay on its way
    assert runs.total_steps == 5 and runs.steps() == 5 and runs.shown_step() == 1
    assert not runs.ended()
    runs.take(_result(3, "error", steps=0))  # a syntax error: no steps
    assert runs.steps() == 0 and runs.shown_step() is None
    runs.expect()
    assert not runs.ended()  # asked for something: a result is to come


def test_a_run_at_work_is_the_newest_or_the_paused_one_going_on() -> None:
    runs = RunTracker()
    session = SimpleNamespace(activity=SimpleNamespace(run_id=1, working=0.7),
                              empty_script="/x/model.py", background_runs=(0,))
    runs.poll(session)
    assert runs.activity.run_id == 1 and runs.working() == 0.5  # in half seconds
    assert runs.empty_script == "/x/model.py" and runs.background == (0,)
    runs.take(_result(1))
    runs.poll(session)
    assert runs.activity is None  # its end is shown
    runs.take(_result(1, "paused", step_index=0))
    runs.poll(session)
    assert runs.activity.run_id == 1  # a paused run that goes on
    session.activity = SimpleNamespace(run_id=2, working=1.2)
    runs.take(_result(1))
    runs.poll(session)
    assert runs.activity.run_id == 2 and runs.working() == 1.0
    session.activity, session.background_runs = None, ()
    runs.poll(session)
    assert runs.activity is None and runs.working() is None and runs.background == ()


def test_the_last_good_run_is_named_while_its_mesh_is_shown() -> None:
    runs, good = RunTracker(), object()
    runs.take(_result(2, arrays=good))
    assert runs.good_run == 2  # (its own result shows its own mesh)
    runs.take(_result(3, "error", arrays=good))
    assert runs.good_run == 2
    runs.take(_result(4, "error", arrays=object()))  # a mesh of a run never shown
    assert runs.good_run is None


def test_a_result_the_window_cannot_show_is_said() -> None:
    runs = RunTracker()
    runs.expect()
    said = runs.failed_to_show(_result(7), RuntimeError("GL said no"))
    assert said == "the viewer could not show run 7: RuntimeError: GL said no"
    assert runs.viewer_error == said and not runs.waiting
    runs.take(_result(8))
    assert runs.viewer_error is None
