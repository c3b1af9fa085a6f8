"""Playback: one state machine for where runs pause and what the screen shows.

A session owns one :class:`Playback`. The caller's actions (keys, the
timeline) and the runs' own events go through :func:`transition`, a pure
function of the mode, the action and where the newest run is
(:class:`RunPosition`); it returns the next :class:`Mode` and what the session
must do to show it (:class:`Show`). The worker threads read only
:attr:`Playback.hold_from`, a single integer, to know whether to pause after a
step. Going back to a step no longer cached is done by replaying the script to
it with the same seed (:attr:`Show.REPLAY`), so only one live mesh exists
whatever the number of steps.

States (``s`` is :attr:`Mode.step`, the step shown or to be shown, 0-based):

* ``RUNNING``: runs go on to their end without pausing.
* ``PLAYING``: the run pauses at ``s``, shows it ``1 / rate`` seconds, goes on.
* ``PAUSED``: runs hold at ``s``; later runs (a save, a parameter) hold there too.
* ``FINISHED``: the newest run ended and its result is shown (``s``: its last
  step, None without steps); runs go on to their end without pausing.

``behind`` (PAUSED and PLAYING) means the step shown is not the live run's own
pause: it came from the snapshot cache, or a replay is on its way. The live
run then holds without posting, and its end changes nothing; a new run clears
it. FINISHED is a state of its own so that nothing of a finished playback
(its rate, its target step) reaches a later run: a run started in FINISHED
runs to its end.

Actions, in each state (``d``: steps the newest run finished; ``h``: the step
it is held at; *goto k* is the row below, which turns into *end* past the
last step of an ended run; "—" leaves the mode and the screen as they are):

=============  ===================  ===================  ==================  ==================
action         RUNNING              PLAYING s            PAUSED s            FINISHED s
=============  ===================  ===================  ==================  ==================
play           PLAYING d (no live   —  (rate only)       PLAYING s; replay   PLAYING 0, replay
               run: 0, replay)                           if behind or no
                                                         live run
pause          PAUSED d             PAUSED s, resume     —                   PAUSED s (or 0)
                                    plays
toggle         play                 pause                play                play
resume         —                    —                    play if it was a    —
                                                         paused play, else
                                                         end
step forward   PAUSED d (no live    goto s + 1 if held   goto s + 1          —
               run: —)              at s, else goto s
step back      goto d - 2 (if       goto the shown       goto s - 1 (s = 0:  goto s - 1 (s < 1:
               d >= 2)              step - 1             —)                  —)
goto k         PAUSED k             PAUSED k, resume     PAUSED k            PAUSED k
                                    plays
end            —                    RUNNING (no live     as PLAYING          —
                                    run: FINISHED,
                                    post the end again)
cancel         FINISHED (live run)  FINISHED (live run)  FINISHED (live      —
                                                         run)
new run        RUNNING              PLAYING s, not       PAUSED s, not       RUNNING
                                    behind               behind
run ends       FINISHED d - 1       FINISHED d - 1 (if   FINISHED d - 1 (if  FINISHED d - 1
                                    behind: —)           behind: —)
open script    RUNNING              RUNNING              RUNNING             RUNNING
=============  ===================  ===================  ==================  ==================

*goto k* shows step ``k``: a live run that has not reached it goes on to it
(:attr:`Show.LIVE`); a cached step is posted from the cache; an ended run's
step ``k >= d`` is its end (FINISHED, its final result posted again); anything
else is replayed. The worker's events: a run that pauses at step ``i``
(``i >= s``) is shown unless ``behind``, and ``s`` becomes ``i``; in PLAYING,
``1 / rate`` seconds after the pause ``s`` becomes ``i + 1`` and the run goes on.
Changing the play rate changes no state. Every action thus either posts a
result now, or leaves a live run or a requested replay that will post one, or
changes nothing on screen (and says so: :attr:`Show.NOTHING`).
"""

from __future__ import annotations

import dataclasses
import enum
import math
import sys
import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

_POLL = 0.05  # seconds between checks of the cancel flag while paused
NEVER = sys.maxsize  # hold_from when runs never pause

DEFAULT_RATE = 2.0  # steps per second
MIN_RATE = 0.25  # faster() and slower() stay within these
MAX_RATE = 64.0


class PlaybackState(enum.StrEnum):
    """Where playback is (see the module's table)."""

    RUNNING = "running"
    PLAYING = "playing"
    PAUSED = "paused"
    FINISHED = "finished"


class Action(enum.Enum):
    """What the caller or a run does to the playback (see the module's table)."""

    PLAY = "play"
    PAUSE = "pause"
    TOGGLE = "toggle"
    RESUME = "resume"
    STEP_FORWARD = "step forward"
    STEP_BACK = "step back"
    GOTO = "goto"
    END = "end"
    CANCEL = "cancel"
    NEW_RUN = "new run"
    RUN_ENDED = "run ends"
    OPEN = "open script"


class Show(enum.Enum):
    """What the session must do after an action to show :attr:`Mode.step`."""

    NOTHING = "nothing"  # the screen stays as it is
    # the live run goes on (or is stopped) and posts what comes, or the replay
    # asked for before does
    LIVE = "live"
    CACHED = "cached"  # post the cached snapshot of the step
    REPLAY = "replay"  # run the script again (same text and seed); it pauses at the step
    FINAL = "final"  # post the ended run's final result again


@dataclass(frozen=True)
class Mode:
    """The playback's whole state.

    Attributes:
        state: see :class:`PlaybackState`.
        step: the step shown or to be shown (PAUSED, PLAYING), the last step of
            the ended run (FINISHED), None (RUNNING, or no step).
        behind: the step shown is not the live run's own pause (see the module).
        resume_plays: PAUSED by pausing a play: :attr:`Action.RESUME` plays on.
    """

    state: PlaybackState = PlaybackState.RUNNING
    step: int | None = None
    behind: bool = False
    resume_plays: bool = False

    @property
    def hold_from(self) -> int:
        """Runs pause after any step ``index >= hold_from`` (:data:`NEVER`: no pauses)."""
        if self.state in _HOLDING and self.step is not None:
            return self.step
        return NEVER


_HOLDING = (PlaybackState.PAUSED, PlaybackState.PLAYING)


@dataclass(frozen=True)
class RunPosition:
    """Where the session's newest run is when an action comes.

    Attributes:
        live: the run has not ended yet (its end will be posted, or a newer run
            will replace it).
        held: the step the live run is held at now, or None.
        done: steps the run finished (all of them once it ended).
        final: the ended run's final result can be posted again.
        cached: the steps whose snapshot the cache holds.
    """

    live: bool = False
    held: int | None = None
    done: int = 0
    final: bool = False
    cached: frozenset[int] = frozenset()


NO_RUN = RunPosition()


@dataclass(frozen=True)
class PlaybackView:
    """What a window shows of the playback: the state, the step, the play rate."""

    state: PlaybackState
    step: int | None
    rate: float


_Handler = Callable[[Mode, RunPosition, int], tuple[Mode, Show]]


def transition(mode: Mode, action: Action, where: RunPosition = NO_RUN,
               k: int = 0) -> tuple[Mode, Show]:
    """The mode after ``action`` and what to do to show it (the module's table).

    Args:
        mode: the mode now.
        action: what happened.
        where: the newest run's position.
        k: the step of :attr:`Action.GOTO`; the steps the run finished for
            :attr:`Action.RUN_ENDED`; unused otherwise.
    """
    return _HANDLERS[action](mode, where, max(0, k))


def _play(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    if mode.state is PlaybackState.PLAYING:
        return mode, Show.NOTHING
    if mode.state is PlaybackState.PAUSED and mode.step is not None:
        if where.live and not mode.behind:
            return Mode(PlaybackState.PLAYING, mode.step), Show.LIVE
        return Mode(PlaybackState.PLAYING, mode.step, behind=True), Show.REPLAY
    if mode.state is PlaybackState.RUNNING and where.live:
        return Mode(PlaybackState.PLAYING, where.done), Show.LIVE
    return Mode(PlaybackState.PLAYING, 0, behind=True), Show.REPLAY


def _pause(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    if mode.state is PlaybackState.PLAYING:
        held = not mode.behind and where.held == mode.step
        paused = dataclasses.replace(mode, state=PlaybackState.PAUSED, resume_plays=True)
        return paused, Show.NOTHING if held else Show.LIVE
    if mode.state is PlaybackState.RUNNING:
        if where.live:
            return Mode(PlaybackState.PAUSED, where.done), Show.LIVE
        return Mode(PlaybackState.PAUSED, 0, behind=True), Show.NOTHING
    if mode.state is PlaybackState.FINISHED:
        return Mode(PlaybackState.PAUSED, mode.step or 0, behind=True), Show.NOTHING
    return mode, Show.NOTHING


def _toggle(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    if mode.state is PlaybackState.PLAYING:
        return _pause(mode, where, k)
    return _play(mode, where, k)


def _resume(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    if mode.state is not PlaybackState.PAUSED:
        return mode, Show.NOTHING
    return (_play if mode.resume_plays else _end)(mode, where, k)


def _step_forward(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    step = mode.step if mode.step is not None else 0
    if mode.state is PlaybackState.PAUSED:
        return _goto(mode, where, step + 1)
    if mode.state is PlaybackState.PLAYING:
        held = not mode.behind and where.held == step
        return _goto(mode, where, step + 1 if held else step)
    if mode.state is PlaybackState.RUNNING and where.live:
        return Mode(PlaybackState.PAUSED, where.done), Show.LIVE
    return mode, Show.NOTHING


def _shown(mode: Mode, where: RunPosition) -> int | None:
    """The step on screen now, as far as stepping back is concerned."""
    if mode.state is PlaybackState.RUNNING:
        return where.done - 1 if where.live and where.done else None
    if mode.state is PlaybackState.PLAYING and mode.step is not None:
        held = not mode.behind and where.held == mode.step
        return mode.step if held else mode.step - 1
    return mode.step


def _step_back(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    shown = _shown(mode, where)
    if shown is None or shown < 1:
        return mode, Show.NOTHING
    return _goto(mode, where, shown - 1)


def _goto(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    if not where.live and where.final and k >= where.done:
        return _end(mode, where, k)
    plays = mode.state is PlaybackState.PLAYING or mode.resume_plays
    if where.live and where.held == k:
        behind, show = (False, Show.CACHED) if k in where.cached else (True, Show.REPLAY)
    elif where.live and k >= (where.done if where.held is None else where.held + 1):
        behind, show = False, Show.LIVE  # the run goes on to it
    else:
        behind, show = True, Show.CACHED if k in where.cached else Show.REPLAY
    return Mode(PlaybackState.PAUSED, k, behind, plays), show


def _end(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    if mode.state in (PlaybackState.RUNNING, PlaybackState.FINISHED):
        return mode, Show.NOTHING
    if where.live:
        return Mode(PlaybackState.RUNNING), Show.LIVE
    if where.final:
        return _finished(where.done), Show.FINAL
    return Mode(PlaybackState.RUNNING), Show.NOTHING


def _cancel(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    if not where.live:
        return mode, Show.NOTHING
    return Mode(PlaybackState.FINISHED), Show.LIVE  # its "cancelled" result comes


def _new_run(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    if mode.state in _HOLDING:
        return dataclasses.replace(mode, behind=False), Show.LIVE
    return Mode(PlaybackState.RUNNING), Show.LIVE


def _run_ended(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    """``k`` is the number of steps the run finished. Show.NOTHING: do not post
    its end (the caller looks at an earlier step)."""
    if mode.state in _HOLDING and mode.behind:
        return mode, Show.NOTHING
    return _finished(k), Show.LIVE


def _open(mode: Mode, where: RunPosition, k: int) -> tuple[Mode, Show]:
    return Mode(PlaybackState.RUNNING), Show.NOTHING


def _finished(steps: int) -> Mode:
    return Mode(PlaybackState.FINISHED, steps - 1 if steps else None)


_HANDLERS: dict[Action, _Handler] = {
    Action.PLAY: _play, Action.PAUSE: _pause, Action.TOGGLE: _toggle,
    Action.RESUME: _resume, Action.STEP_FORWARD: _step_forward,
    Action.STEP_BACK: _step_back, Action.GOTO: _goto, Action.END: _end,
    Action.CANCEL: _cancel, Action.NEW_RUN: _new_run, Action.RUN_ENDED: _run_ended,
    Action.OPEN: _open,
}


def check_rate(rate: float) -> float:
    """``rate`` as a float.

    Raises:
        ValueError: ``rate`` is not a positive finite number.
    """
    value = float(rate)
    if not (value > 0 and math.isfinite(value)):
        raise ValueError(f"play rate must be a positive number of steps a second, got {rate!r}")
    return value


class Playback:
    """The thread-safe holder of a :class:`Mode` and the play rate.

    The caller's thread applies actions (:meth:`apply`); each run's step hook,
    in the worker thread, reads :attr:`hold_from` without the lock after every
    step and, when it must pause, calls :meth:`arrived` and :meth:`wait`.

    Args:
        rate: steps per second while playing.
    """

    def __init__(self, rate: float = DEFAULT_RATE) -> None:
        self._cond = threading.Condition()
        self._mode = Mode()
        self._rate = check_rate(rate)
        self.hold_from = NEVER  # the mode's, as one int a step hook reads lock-free

    @property
    def mode(self) -> Mode:
        """The mode now."""
        return self._mode

    @property
    def view(self) -> PlaybackView:
        """The state, step and rate now (for a HUD)."""
        mode = self._mode
        return PlaybackView(mode.state, mode.step, self._rate)

    @property
    def rate(self) -> float:
        """Steps per second while playing."""
        return self._rate

    @rate.setter
    def rate(self, rate: float) -> None:
        with self._cond:
            self._rate = check_rate(rate)
            self._cond.notify_all()  # a run waiting for its next step goes by the new rate

    def scale_rate(self, factor: float) -> float:
        """Multiply the rate by ``factor`` without leaving [MIN_RATE, MAX_RATE] (a
        rate set outside them stays where it is rather than jump); the new rate."""
        with self._cond:
            scaled = min(max(self._rate * factor, MIN_RATE), MAX_RATE)
            if (scaled - self._rate) * (factor - 1.0) > 0:  # moved the way asked
                self.rate = scaled
            return self._rate

    def apply(self, action: Action, where: RunPosition = NO_RUN, k: int = 0) -> Show:
        """Take ``action`` (see :func:`transition`); what to do to show the new step."""
        with self._cond:
            mode, show = transition(self._mode, action, where, k)
            self._set(mode)
            return show

    def arrived(self, index: int) -> bool:
        """A run paused after step ``index``: True when that is to be shown (the
        mode's step becomes ``index``); False while the caller looks at another
        step, or when the run should not have paused (it then goes on)."""
        with self._cond:
            mode = self._mode
            if mode.state not in _HOLDING or mode.behind or index < self.hold_from:
                return False
            self._set(dataclasses.replace(mode, step=index))
            return True

    def wake(self) -> None:
        """Wake paused runs so they re-check their cancel flag."""
        with self._cond:
            self._cond.notify_all()

    def should_pause(self, index: int) -> bool:
        """True when a run that just finished step ``index`` must pause (lock-free)."""
        return index >= self.hold_from

    def wait(self, index: int, cancelled: Callable[[], bool]) -> None:
        """Block the calling run at step ``index`` until it may go on or is cancelled.

        While playing, ``1 / rate`` seconds after this call the next step is due:
        the mode's step becomes ``index + 1`` and the run goes on.
        """
        paused_at = time.monotonic()
        with self._cond:
            while not cancelled() and self.should_pause(index):
                mode = self._mode
                if mode.state is not PlaybackState.PLAYING or mode.behind:
                    self._cond.wait(_POLL)
                    continue
                left = paused_at + 1.0 / self._rate - time.monotonic()
                if left <= 0:
                    self._set(dataclasses.replace(mode, step=index + 1))
                    return
                self._cond.wait(min(_POLL, left))

    def _set(self, mode: Mode) -> None:
        """Caller holds the lock."""
        self._mode = mode
        self.hold_from = mode.hold_from
        self._cond.notify_all()
