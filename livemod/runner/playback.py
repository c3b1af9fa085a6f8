"""Playback: where a run pauses, and how it is told to go on.

One :class:`Playback` belongs to a session and is consulted by each run's step
hook (in the worker thread) after every step. Going back is done by the session
replaying the script to the wanted step with the same seed, so only one live
mesh ever exists whatever the number of steps.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

_POLL = 0.05  # seconds between checks of the cancel flag while paused


class Playback:
    """Thread-safe playback state.

    In ``"run"`` mode runs never pause. In ``"step"`` mode a run pauses after
    the first step whose index is at least :attr:`target`; with a :attr:`rate`
    it moves on by itself after ``1 / rate`` seconds.
    """

    def __init__(self) -> None:
        self._cond = threading.Condition()
        self.mode = "run"
        self.target = 0
        self.rate: float | None = None

    def run_to_end(self) -> None:
        """Let runs go on to the end without pausing."""
        with self._cond:
            self.mode, self.rate = "run", None
            self._cond.notify_all()

    def pause_at(self, index: int, rate: float | None = None) -> None:
        """Pause runs after step ``index`` (and advance at ``rate`` steps/s if given)."""
        with self._cond:
            # the mode last: a step hook reads without the lock, and "step" with the
            # old target would pause it at a step nobody asked for
            self.target, self.rate = max(0, index), rate
            self.mode = "step"
            self._cond.notify_all()

    def wake(self) -> None:
        """Wake paused runs so they re-check their cancel flag."""
        with self._cond:
            self._cond.notify_all()

    def should_pause(self, index: int) -> bool:
        """True when a run that just finished step ``index`` must pause (lock-free read)."""
        return self.mode == "step" and index >= self.target

    def wait(self, index: int, cancelled: Callable[[], bool]) -> None:
        """Block the calling run at step ``index`` until told to go on or cancelled."""
        paused_at = time.monotonic()
        with self._cond:
            while not cancelled() and self.should_pause(index):
                if self.rate is None:
                    self._cond.wait(_POLL)
                    continue
                left = paused_at + 1.0 / self.rate - time.monotonic()
                if left <= 0:
                    self.target = index + 1  # playing: the next step is due
                    return
                self._cond.wait(min(_POLL, left))
