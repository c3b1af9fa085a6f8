"""Stopping a live session's runs: cancel, wait a short grace, abandon.

A cancelled run stops at its next check (a step, a loop of the script): at
once, almost always. Code without checks (a comprehension, a loop in a helper
module) is interrupted every ``_FORCE_AFTER`` seconds by an exception sent into
the run's thread. A run that does neither within :data:`GRACE` seconds is
blocked in a call no interrupt reaches (``time.sleep``, a wait, a read, one long
library or numpy operation) or swallows the interrupt: it is abandoned. Its
results are never posted, the process state it holds is given back on its
behalf (:meth:`~livemod.runner.execute.RunLease.revoke`), and its thread, a
daemon, is left to end in the background while the next run starts at once.
"""

from __future__ import annotations

import enum
import logging
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

from .execute import RunControl, RunLease, interrupt_user_code

_LOG = logging.getLogger("livemod.session")
_JOIN_POLL = 0.02  # seconds between checks while waiting for a cancelled run
# seconds a cancelled run may ignore its checks before it is interrupted: short
# enough that code without checks (a comprehension) still stops within 200 ms
_FORCE_AFTER = 0.1
# seconds a cancelled run has to stop before it is abandoned: a few interrupts'
# worth, so that the next save's result comes well within a second
GRACE = 0.3
# seconds between interrupts sent to abandoned runs still in the script's code
_POKE_EVERY = 0.5


class CancelReason(enum.StrEnum):
    """Why a run was cancelled."""

    USER = "user"  # LiveSession.cancel(): its "cancelled" result shows
    SUPERSEDED = "superseded"  # a newer run (or closing) replaced it: nothing of it shows


@dataclass
class Run:
    """One run of the script, as the supervisor and the worker share it."""

    run_id: int
    script: str
    control: RunControl
    lease: RunLease
    thread: threading.Thread | None = None
    cancel_reason: CancelReason | None = None
    cancelled_at: float = 0.0  # perf_counter() of the user's cancel
    started: float = 0.0  # perf_counter() when the supervisor started it
    ended: bool = False  # its end was published (or dropped): it works no more
    abandoned: bool = False  # it did not stop when asked: nothing of it is posted

    def working(self) -> float:
        """Seconds it has worked since it started, its pauses left out."""
        return max(time.perf_counter() - self.started - self.control.waited, 0.0)

    @property
    def superseded(self) -> bool:
        """True when its results must not show: a newer run replaced it, or it was
        abandoned."""
        return self.cancel_reason is CancelReason.SUPERSEDED or self.abandoned

    @property
    def stopped(self) -> bool:
        """True once it has ended or been abandoned (nothing to wait for)."""
        return self.ended or self.abandoned

    @property
    def user_cancelled(self) -> bool:
        """True while the user's cancel of it is under way (see :meth:`RunStopper.mind`)."""
        return self.cancel_reason is CancelReason.USER and not self.stopped


class RunStopper:
    """Stops a session's runs, and keeps the ones it abandoned until they end.

    Args:
        lock: the session's lock; the runs' flags and :attr:`background` change
            under it.
        on_abandon: called (under ``lock``) just before a run is marked
            abandoned: the last moment its result can still be posted.
    """

    def __init__(self, lock: threading.RLock, on_abandon: Callable[[Run], None]) -> None:
        self._lock = lock
        self._on_abandon = on_abandon
        self._background: dict[int, Run] = {}

    @property
    def background(self) -> tuple[int, ...]:
        """Ids of the abandoned runs still working, oldest first."""
        with self._lock:
            return tuple(sorted(self._background))

    def stop(self, run: Run, reason: CancelReason) -> None:
        """Cancel ``run`` (its results stale from now, for ``reason``) and wait until
        its thread is done, or abandon it when not within :data:`GRACE` seconds."""
        if run.stopped:
            return
        if not run.control.finished:
            with self._lock:  # the session's posting reads it
                run.cancel_reason = run.cancel_reason or reason
            run.control.cancel()
        if not self._wait_for(run):
            self.abandon(run)

    def mind_interval(self, current: Run | None) -> float | None:
        """How long the supervisor may wait before calling :meth:`mind`; None when
        there is nothing to mind."""
        with self._lock:
            if current is not None and current.user_cancelled:
                return _FORCE_AFTER
            return _POKE_EVERY if self._background else None

    def mind(self, current: Run | None) -> None:
        """Interrupt the run the user cancelled (abandoning it past the grace) and
        the abandoned runs still in the script's code (one may have swallowed an
        interrupt and be looping again)."""
        with self._lock:
            background = list(self._background.values())
        if current is not None and current.user_cancelled:
            if time.perf_counter() - current.cancelled_at >= GRACE:
                self.abandon(current)
            else:
                _interrupt(current)
        for run in background:
            _interrupt(run)

    def abandon(self, run: Run) -> None:
        """Leave ``run`` to end in the background: its results are never posted and
        the process state it holds is given back at once."""
        with self._lock:
            if run.stopped:
                return
            self._on_abandon(run)
            run.abandoned = True
            self._background[run.run_id] = run
        run.lease.revoke()
        _LOG.info("run %d of %s did not stop within %.1f s of its cancel; it goes on in "
                  "the background, its result discarded", run.run_id, run.script, GRACE)

    def ended(self, run: Run) -> None:
        """The worker is done with ``run`` (called at its very end)."""
        with self._lock:
            run.ended = True
            self._background.pop(run.run_id, None)

    def _wait_for(self, run: Run) -> bool:
        """Wait up to :data:`GRACE` s for the cancelled ``run``'s thread to end,
        interrupting it every ``_FORCE_AFTER`` s; True when it ended."""
        assert run.thread is not None
        waited = since_interrupt = 0.0
        while run.thread.is_alive():
            if waited >= GRACE:
                return False
            run.thread.join(_JOIN_POLL)
            waited += _JOIN_POLL
            since_interrupt += _JOIN_POLL
            if since_interrupt >= _FORCE_AFTER:
                _interrupt(run)
                since_interrupt = 0.0
        return True


def _interrupt(run: Run) -> None:
    """The forced interrupt, for a cancelled run's own code only (not once its
    script has ended: the worker is only publishing then)."""
    if run.thread is not None and run.control.cancelled and not run.control.finished:
        # e.g. a loop in a helper module, or a comprehension (no checks there)
        interrupt_user_code(run.thread, run.script, run.control)
