"""The runs of a live session: a queue of requests, one supervisor thread.

:class:`RunSupervisor` takes run requests, cancels the running run, waits a
short grace for it to stop and starts the next one (latest wins: queued
requests coalesce). A run that does not stop in the grace is abandoned (see
:class:`~livemod.runner.stopping.RunStopper`). Each run gets a thread of its
own, in which a :class:`RunWork` runs the script and publishes what came out;
the supervisor knows which run is the newest, whose results alone are shown.
"""

from __future__ import annotations

import functools
import queue
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Protocol

from livemod.dlfl.run_context import RunContext
from livemod.dlfl.scene import Scene

from .execute import RunControl, RunLease
from .inputs import RunInputs
from .playback import Action, Playback
from .process import ProcessState
from .recording import StepRecord
from .snapshots import SnapshotCache
from .stopping import GRACE, CancelReason, Run, RunStopper

_WAKE = object()  # queued by cancel(): the supervisor minds the cancelled run


@dataclass
class _Request:
    """A run to start: the script and the text to run (None: read it)."""

    script: str
    source: str | None


@dataclass(frozen=True)
class RunActivity:
    """The newest run while it works on the script (see :attr:`LiveSession.activity`).

    Attributes:
        run_id: the run's id, as its results will carry.
        script: the script it runs.
        working: seconds it has worked so far (its pauses left out, as in the
            ``elapsed`` of its results).
    """

    run_id: int
    script: str
    working: float


class RunWork(Protocol):
    """What a run does in its thread, and what the supervisor has it publish."""

    def run(self, run: Run, source: str | None) -> None:
        """Worker thread: run the script once (``source`` None: read it) and
        publish what came out."""

    def paused(self, run: Run, index: int, steps: Sequence[StepRecord], scene: Scene,
               context: RunContext) -> None:
        """Worker, at a pause: publish the mesh as it is after step ``index``."""

    def publish_cancelled(self, run: Run) -> None:
        """Publish the ``"cancelled"`` result of ``run`` if the user cancelled it
        (takes the lock; also called under it, as the run is abandoned)."""

    def close(self) -> None:
        """The last run has stopped: end what publishing keeps running."""


class RunSupervisor:
    """Starts the runs a session asks for, one at a time, stopping the previous.

    Args:
        lock: the session's lock; it guards the current run, the run ids and
            the closed flag.
        inputs: the session's run inputs (the open script).
        playback: the session's playback (each run's pauses follow it).
        snapshots: the session's snapshot cache (a new run's replaces the old).
    """

    def __init__(self, lock: threading.RLock, inputs: RunInputs, playback: Playback,
                 snapshots: SnapshotCache) -> None:
        self._lock = lock
        self._inputs = inputs
        self._playback = playback
        self._snapshots = snapshots
        self._requests: queue.Queue[_Request | object | None] = queue.Queue()
        self._run_id = 0
        self._current: Run | None = None
        self._work: RunWork | None = None  # given at start
        self._stopper = RunStopper(lock, self._before_abandoning)
        self._process: ProcessState | None = None  # shared by the runs (see start)
        self._closed = False
        # set once closing has stopped (or abandoned) the last run: no run of the
        # session holds the process state any more (see close)
        self._let_go = threading.Event()
        self._thread = threading.Thread(target=self._supervise, name="livemod-session",
                                        daemon=True)

    @property
    def current(self) -> Run | None:
        """The newest run started, or None (caller holds the lock)."""
        return self._current

    @property
    def closed(self) -> bool:
        """True once :meth:`close` was called (caller holds the lock)."""
        return self._closed

    # -- life cycle --------------------------------------------------------------------

    def start(self, work: RunWork, process: ProcessState) -> None:
        """Start the supervisor thread: ``work`` does each run, every run starting
        from ``process`` (closed once the last run gave it back)."""
        self._work, self._process = work, process
        self._thread.start()

    def close(self) -> bool:
        """Take no more requests and stop the current run; False when the
        supervisor never started (nothing winds down then).

        Returns once the run has stopped or been abandoned (within
        :data:`~livemod.runner.stopping.GRACE` seconds and a little more), unless
        called on the supervisor's own thread."""
        with self._lock:
            self._closed = True
            started = self._thread.ident is not None
        self._requests.put(None)
        if started and threading.current_thread() is not self._thread:
            self._let_go.wait(GRACE + 1.0)
        return started

    def join(self, timeout: float) -> bool:
        """Wait (up to ``timeout`` s) for the supervisor thread after :meth:`close`."""
        if self._thread.ident is None:
            return True
        self._thread.join(timeout)
        return not self._thread.is_alive()

    # -- requests ----------------------------------------------------------------------

    def request(self, source: str | None) -> None:
        """Queue a run of the current script (``source`` None: read it from disk).

        The current run, unless it has finished, is superseded at once: what it
        posts from now on is dropped, also before the supervisor gets to stopping
        it (a run that ends in that moment would otherwise show, and then the
        new run's result)."""
        with self._lock:
            if self._closed:
                return
            self._requests.put(_Request(self._inputs.script, source))
            run = self._current
            if run is not None and not run.control.finished:
                run.cancel_reason = run.cancel_reason or CancelReason.SUPERSEDED

    def cancel(self, run: Run) -> None:
        """The user cancelled ``run`` (live, by the playback): interrupt it, and have
        the supervisor mind it from now on (caller holds the lock)."""
        run.cancel_reason = CancelReason.USER
        run.cancelled_at = time.perf_counter()
        run.control.cancel()
        self._requests.put(_WAKE)

    # -- what the caller polls ------------------------------------------------------------

    def is_newest(self, run_id: int, script: str) -> bool:
        """True while run ``run_id`` of ``script`` is the newest run of the open
        script and was not superseded, nor the session closed (caller holds the
        lock)."""
        run = self._current
        return (run is not None and run_id == run.run_id
                and script == self._inputs.script and not run.superseded
                and not self._closed)

    @property
    def activity(self) -> RunActivity | None:
        """The newest run while it works (neither paused nor ended), else None."""
        with self._lock:
            run = self._current
            if (run is None or run.stopped or self._closed
                    or run.control.paused_at is not None):
                return None
            return RunActivity(run.run_id, run.script, run.working())

    @property
    def background(self) -> tuple[int, ...]:
        """Ids of the abandoned runs still working, oldest first."""
        return self._stopper.background

    # -- the supervisor thread ---------------------------------------------------------------

    def _supervise(self) -> None:
        """Supervisor thread: start each requested run after stopping the previous one."""
        while True:
            request = self._next_request()
            self._stop_current(CancelReason.SUPERSEDED)
            if request is None:
                self._let_go.set()
                break
            self._start_run(request)
        self._inputs.stop_watching()
        if self._work is not None:
            self._work.close()
        if self._process is not None:
            self._process.close()  # no run holds it now: the last one gave it back

    def _next_request(self) -> _Request | None:
        """The newest queued request (older ones coalesce); None means close. While
        it waits it minds the runs asked to stop (see :meth:`RunStopper.mind`)."""
        while True:
            with self._lock:
                current = self._current
            request = self._take(self._stopper.mind_interval(current))
            if request is not _WAKE:
                return request  # type: ignore[return-value]
            self._stopper.mind(current)

    def _take(self, timeout: float | None) -> _Request | object | None:
        """The newest queued item (a close wins), or ``_WAKE`` when only wake-ups
        came, or nothing within ``timeout`` seconds."""
        try:
            newest = self._requests.get(timeout=timeout)
        except queue.Empty:
            return _WAKE
        while newest is not None:
            try:
                item = self._requests.get_nowait()
            except queue.Empty:
                break
            if item is not _WAKE:
                newest = item
        return newest

    def _stop_current(self, reason: CancelReason) -> None:
        """Cancel the running run; wait until its thread is done with the script,
        or abandon it (see :class:`RunStopper`)."""
        if self._current is not None:
            self._stopper.stop(self._current, reason)

    def _before_abandoning(self, run: Run) -> None:
        """A run the user cancelled says so now, as it is abandoned (under the lock)."""
        assert self._work is not None  # runs start only after start()
        self._work.publish_cancelled(run)

    def _start_run(self, request: _Request) -> None:
        work = self._work
        assert work is not None  # the thread runs only after start()
        with self._lock:
            if request.script != self._inputs.script:
                return  # queued before open() switched scripts
            self._run_id += 1
            run = Run(self._run_id, request.script, RunControl(self._playback),
                      RunLease(self._process), started=time.perf_counter())
            run.control.on_pause = functools.partial(work.paused, run)
            run.thread = threading.Thread(target=self._run_body, args=(run, request.source),
                                          name=f"livemod-run-{run.run_id}", daemon=True)
            self._current = run
            self._snapshots.reset(run.run_id)
            self._inputs.empty_script = None
            self._playback.apply(Action.NEW_RUN)
        run.thread.start()

    def _run_body(self, run: Run, source: str | None) -> None:
        """Worker thread: the run's work, then the run has ended."""
        assert self._work is not None  # the thread runs only after start()
        try:
            self._work.run(run, source)
        finally:
            run.control.detach()  # frees the run's scene now, not at the next collection
            self._stopper.ended(run)  # after the publishing: the caller sees no gap between
