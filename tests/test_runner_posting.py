"""ResultPosting alone: only the newest run's results reach the caller, and a
playback action shows its step from the snapshot cache, the end, or a replay."""

from __future__ import annotations

import queue
import threading
from types import SimpleNamespace

from livemod.dlfl import from_polygons
from livemod.runner.playback import Action, Playback
from livemod.runner.posting import ResultPosting
from livemod.runner.recording import StepRecord
from livemod.runner.results import RunResult, RunStatus, snapshot_mesh
from livemod.runner.snapshots import SnapshotCache

SCRIPT = "/scripts/model.py"


class _Runs:
    """The supervisor as the posting sees it: run ``newest`` of SCRIPT is the newest."""

    current = None
    closed = False

    def __init__(self) -> None:
        self.newest = 1
        self.requests: list[str | None] = []

    def is_newest(self, run_id: int, script: str) -> bool:
        return run_id == self.newest and script == SCRIPT

    def request(self, source: str | None) -> None:
        self.requests.append(source)


def _arrays(z: float):
    return snapshot_mesh(from_polygons([(0, 0, 0), (1, 0, 0), (0, 1, z)], [(0, 1, 2)]))


def _steps(count: int) -> tuple[StepRecord, ...]:
    return tuple(StepRecord(k, "createVertex", k + 1, (k + 1, 0, 0), 0.0) for k in range(count))


def _finished(run_id: int, count: int = 3) -> RunResult:
    return RunResult.finished(run_id, SCRIPT, _steps(count), _arrays(-1.0), 0.0)


def _paused(run_id: int, index: int) -> RunResult:
    return RunResult.paused(run_id, SCRIPT, _steps(index + 1), index, _arrays(index), 0.0)


def _posting() -> tuple[ResultPosting, _Runs, SnapshotCache]:
    runs, snapshots = _Runs(), SnapshotCache()
    snapshots.reset(1)
    posting = ResultPosting(threading.RLock(), runs, SimpleNamespace(source="pass\n"),
                            Playback(), snapshots)
    return posting, runs, snapshots


def _drain(results: queue.Queue[RunResult]) -> list[RunResult]:
    drained = []
    while not results.empty():
        drained.append(results.get_nowait())
    return drained


def test_only_the_newest_runs_results_are_posted():
    posting, runs, _ = _posting()
    older, newest = _finished(0), _finished(1)
    posting.post(older)
    posting.post(newest)
    assert _drain(posting.results) == [newest]
    assert posting.final is newest
    runs.newest = 2  # a newer run started: run 1's end is not shown any more
    posting.post(_finished(1))
    assert _drain(posting.results) == []


def test_a_finished_run_is_the_last_good_one_only_while_it_is_the_newest():
    posting, _, _ = _posting()
    posting.post_good(_finished(0))
    assert posting.last_good is None
    good = _finished(1)
    posting.post_good(good)
    assert posting.last_good is good
    cancelled = posting.cancelled_result(SimpleNamespace(
        run_id=1, script=SCRIPT, working=lambda: 0.5))
    assert cancelled.status is RunStatus.CANCELLED and cancelled.elapsed == 0.5
    assert cancelled.stale


def test_a_step_not_waited_for_is_cached_and_shown_from_the_cache_later():
    posting, runs, snapshots = _posting()
    step = _paused(1, 0)
    assert not posting.post_step(step, 0)  # the playback follows the run: no pause
    assert snapshots.get(0) is step and _drain(posting.results) == []
    end = _finished(1)
    posting.post(end)
    assert posting.act(Action.GOTO, 0)
    assert _drain(posting.results) == [end, step]
    assert runs.requests == []
    assert posting.act(Action.GOTO, 1)  # not cached: the script is replayed to it
    assert runs.requests == ["pass\n"]


def test_a_preview_reposts_only_the_result_shown():
    posting, runs, _ = _posting()
    end = _finished(1)
    posting.post(end)
    _drain(posting.results)
    assert posting.is_latest(end) and not posting.is_latest(_finished(1))
    preview = _arrays(5.0)
    posting.post_preview(end, preview)
    again = _drain(posting.results)
    assert [r.preview for r in again] == [preview] and posting.final is again[0]
    runs.newest = 2
    assert not posting.is_latest(again[0])
    posting.post_preview(again[0], preview)
    assert _drain(posting.results) == []
