"""What the window knows of the session's runs (GL-free).

:class:`RunTracker` holds the result shown, whether the window waits for one it
asked for, the run at work, and the step count of the last run that ended; the
controllers ask it where the steps stand, and tell it when they asked the
session for something (:meth:`RunTracker.expect`).
"""

from __future__ import annotations

import queue
from typing import TYPE_CHECKING

from livemod.runner.results import RunStatus

from .timeline import shown_step

if TYPE_CHECKING:
    from livemod.dlfl.arrays import MeshArrays
    from livemod.runner.results import RunResult
    from livemod.runner.session import RunActivity

    from .session import Session

# the HUD's time of a run at work goes up in these steps (each one draws the frame
# again: a million faces take half a second a frame on software GL)
RUNNING_TICK = 0.5


class RunTracker:
    """The runs as the window sees them.

    Attributes:
        result: the result shown (None before the first).
        waiting: the window asked the session for a result that has not come.
        activity: the session's run at work, newer than the result shown, or None.
        total_steps: the step count of the last run that ended.
        viewer_error: why the window could not show the last result, or None.
        empty_script: the session's: a save left the script empty, or None.
        background: the session's: ids of abandoned runs still working (they
            did not stop when a newer run began), oldest first.
    """

    def __init__(self) -> None:
        self.forget()

    def forget(self) -> None:
        """Start afresh (another script: its runs are numbered anew)."""
        self.result: RunResult | None = None
        self.waiting = False
        self.activity: RunActivity | None = None
        self.total_steps = 0
        self.viewer_error: str | None = None
        self.empty_script: str | None = None
        self.background: tuple[int, ...] = ()
        # (run id, arrays) of the last ok run
        self._good: tuple[int, MeshArrays | None] | None = None
        self._summarized = 0  # the newest run whose end was summarized

    def expect(self) -> None:
        """The window asked the session for a result: it is waiting for one."""
        self.waiting = True

    # -- results arriving --------------------------------------------------------

    def arrived(self, results: queue.Queue[RunResult]) -> list[RunResult]:
        """Every result posted since the last call, oldest first (never blocks)."""
        taken = []
        while True:
            try:
                taken.append(results.get_nowait())
            except queue.Empty:
                return taken

    def newly_ended(self, result: RunResult) -> bool:
        """``result`` ends a run (ok, error, cancelled) not said ended before: a
        preview posted after it, or a step, is no new end."""
        if result.status == RunStatus.PAUSED or result.run_id <= self._summarized:
            return False
        self._summarized = result.run_id
        return True

    def take(self, result: RunResult) -> None:
        """Show ``result``: the window waits no more, and a run that ended gives
        its step count (a failed run's steps are what the step keys and the
        timeline go through; a syntax error has none, so the timeline goes too)."""
        self.result, self.waiting, self.viewer_error = result, False, None
        if result.status in (RunStatus.OK, RunStatus.ERROR):
            self.total_steps = len(result.steps)
        if result.status == RunStatus.OK:
            self._good = (result.run_id, result.arrays)

    def failed_to_show(self, result: RunResult, exc: Exception) -> str:
        """Note (and return) that ``result`` could not be shown."""
        self.viewer_error = (f"the viewer could not show run {result.run_id}: "
                             f"{type(exc).__name__}: {exc}")
        self.waiting = False
        return self.viewer_error

    # -- polled each frame -----------------------------------------------------------

    def poll(self, session: Session) -> None:
        """Read the session's run at work, its empty-script note and its runs left
        in the background. A run whose end is already shown, or one older than the
        result shown, is at work no more: its result arrived before the session
        marked it ended."""
        activity, shown = session.activity, self.result
        self.activity = activity if activity is None or shown is None or _newer(
            activity.run_id, shown) else None
        self.empty_script = session.empty_script
        self.background = session.background_runs

    def working(self) -> float | None:
        """Seconds the run at work has worked, in :data:`RUNNING_TICK` steps (None
        when no run works)."""
        if self.activity is None:
            return None
        return RUNNING_TICK * int(self.activity.working / RUNNING_TICK)

    # -- where the steps stand ----------------------------------------------------------

    @property
    def good_run(self) -> int | None:
        """The id of the run whose mesh the result shown shows, when it is an earlier
        run's (a failed run shows the last good mesh) and the window saw that run."""
        result, good = self.result, self._good
        if result is None or good is None or result.arrays is not good[1]:
            return None
        return good[0]

    def steps(self) -> int:
        """Steps the timeline spans: the last complete run's, or more while one runs."""
        shown = len(self.result.steps) if self.result is not None else 0
        return max(self.total_steps, shown)

    def shown_step(self) -> int | None:
        """The 0-based step shown, None when there are no steps."""
        return shown_step(self.result, self.steps())

    def ended(self) -> bool:
        """The result shown is of a run that ended (not a paused or cached step) and
        the window asked for nothing since: no step lies ahead of it."""
        result = self.result
        return (not self.waiting and result is not None and result.status != RunStatus.PAUSED
                and result.step_index is None)


def _newer(run_id: int, shown: RunResult) -> bool:
    """Run ``run_id`` is at work beyond ``shown``: a newer run, or the paused run
    shown going on."""
    return run_id > shown.run_id or (run_id == shown.run_id and shown.status == RunStatus.PAUSED)
