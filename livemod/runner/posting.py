"""Which results of a live session's runs reach the caller, and when.

Only the newest run's results are posted (a superseded run's are dropped); a
run's end goes to the playback first, which keeps it unposted while the caller
looks at an earlier step; a playback action shows its step from the snapshot
cache, from the end kept, or by replaying the script to it (see
livemod/runner/playback.py for the states and the transition table).
"""

from __future__ import annotations

import dataclasses
import queue
import threading

from livemod.dlfl.arrays import MeshArrays

from .errors import cancelled_error
from .inputs import RunInputs
from .playback import Action, Playback, RunPosition, Show
from .results import RunResult, RunStatus
from .snapshots import SnapshotCache
from .stopping import Run
from .supervisor import RunSupervisor


class ResultPosting:
    """Posts the newest run's results to :attr:`results`, as the playback shows them.

    Args:
        lock: the session's lock; it guards the results kept here.
        runs: the session's supervisor (which run is the newest).
        inputs: the session's run inputs (the source a replay runs).
        playback: the session's playback.
        snapshots: the newest run's paused results, by step.

    Attributes:
        results: :class:`RunResult` snapshots as they are posted; drain with
            ``get_nowait()``.
        last_good: the newest ``"ok"`` result, shown under later failures.
        final: the newest run's end (ok, error, cancelled), posted or not (see
            :meth:`post_locked`).
    """

    def __init__(self, lock: threading.RLock, runs: RunSupervisor, inputs: RunInputs,
                 playback: Playback, snapshots: SnapshotCache) -> None:
        self._lock = lock
        self._runs = runs
        self._inputs = inputs
        self._playback = playback
        self._snapshots = snapshots
        self.results: queue.Queue[RunResult] = queue.Queue()
        self.last_good: RunResult | None = None
        self.final: RunResult | None = None
        self._last_posted: RunResult | None = None

    def forget(self) -> None:
        """Another script is open: its runs have no last good nor final result
        yet (caller holds the lock)."""
        self.last_good, self.final = None, None

    # -- posting ------------------------------------------------------------------------

    def is_newest(self, result: RunResult) -> bool:
        """True while ``result`` belongs to the newest run of the open script and
        that run was not superseded, nor the session closed (caller holds the lock)."""
        return self._runs.is_newest(result.run_id, result.script)

    def post(self, result: RunResult) -> None:
        """Publish ``result`` if it is still the newest (see :meth:`is_newest`)."""
        with self._lock:
            self.post_locked(result)

    def post_locked(self, result: RunResult) -> None:
        """Publish ``result`` (e.g. again, from the snapshot cache) if it is still
        the newest (caller holds the lock). A run's end goes to the playback
        first, which keeps it unposted while the caller looks at an earlier step."""
        if not self.is_newest(result):
            return
        if result.status is not RunStatus.PAUSED:
            self.final = result
            if self._playback.apply(Action.RUN_ENDED, k=len(result.steps)) is Show.NOTHING:
                return
        self._last_posted = result
        self.results.put(result)

    def post_good(self, result: RunResult) -> None:
        """Publish a finished run's result; it becomes the last good one if it is
        still the newest."""
        with self._lock:
            if self.is_newest(result):
                self.last_good = result
            self.post_locked(result)

    def post_step(self, result: RunResult, index: int) -> bool:
        """Keep the paused ``result`` (after step ``index``) in the snapshot cache,
        and publish it if the playback waits for that step; whether it did."""
        with self._lock:
            self._snapshots.put(result)
            if not self.is_newest(result) or not self._playback.arrived(index):
                return False  # e.g. the caller is looking at an earlier, cached step
            self.post_locked(result)
            return True

    def cancelled_result(self, run: Run) -> RunResult:
        """The ``"cancelled"`` result of a run the user stopped, over the last good
        mesh (caller holds the lock)."""
        return RunResult.failed(run.run_id, run.script, RunStatus.CANCELLED, (),
                                cancelled_error(run.script), run.working(),
                                last_good=self.last_good)

    # -- previews -------------------------------------------------------------------------

    def is_latest(self, result: RunResult) -> bool:
        """Whether ``result`` is still worth a preview: the last one posted, or the
        newest run's end kept unposted (it is posted on :attr:`Action.END`)."""
        with self._lock:
            return ((self._last_posted is result or self.final is result)
                    and self.is_newest(result))

    def post_preview(self, result: RunResult, preview: MeshArrays) -> None:
        """Preview thread: post ``result`` again with its preview, if still shown
        (and keep it with its preview, if it is the end kept unposted)."""
        with self._lock:
            if not self.is_newest(result):
                return
            with_preview = dataclasses.replace(result, preview=preview)
            if self.final is result:
                self.final = with_preview
            if self._last_posted is result:
                self._snapshots.put(with_preview)
                self._last_posted = with_preview
                self.results.put(with_preview)

    # -- playback -------------------------------------------------------------------------

    def act(self, action: Action, k: int = 0) -> bool:
        """Apply ``action`` to the playback and do what showing its step takes;
        True when a result is on its way (or was posted)."""
        with self._lock:
            show = self._playback.apply(action, self._run_position(), k)
            if show is Show.CACHED:
                cached = self._snapshots.get(self._playback.mode.step or 0)
                assert cached is not None  # the position said it was there
                self.post_locked(cached)
            elif show is Show.FINAL:
                assert self.final is not None  # the position said it was there
                self.post_locked(self.final)
            elif show is Show.REPLAY:
                self._runs.request(self._inputs.source)
            return show is not Show.NOTHING

    def _run_position(self) -> RunPosition:
        """Where the newest run is, for the playback (caller holds the lock)."""
        run, final = self._runs.current, self.final
        if final is not None and not self.is_newest(final):
            final = None
        if run is None or final is not None or run.stopped or self._runs.closed:
            return RunPosition(final=final is not None,
                               done=len(final.steps) if final is not None else 0,
                               cached=self._snapshots.indexes())
        return RunPosition(live=True, held=run.control.paused_at,
                           done=run.control.step_count, cached=self._snapshots.indexes())
