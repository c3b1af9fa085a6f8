"""Stepping through the script's steps: the step keys, playing, a held key's
repeat and the timeline's scrub (GL-free).

:class:`Stepping` turns the keys and the timeline into the session's playback
calls (:class:`~livemod.viewer.session.PlaybackControls`) and tells the
:class:`~livemod.viewer.runs.RunTracker` when a result is to come. When no result
will come (at the last step, or the first), it says so instead of waiting.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from .runs import RunTracker
from .session import PlaybackControls

if TYPE_CHECKING:
    from livemod.runner.results import RunResult

DEFAULT_RATE = 2.0  # steps a second while playing
LOWEST_RATE, HIGHEST_RATE = 0.125, 64.0  # where halving and doubling the rate stop

# a held step key steps again after REPEAT_DELAY s, then every REPEAT_INTERVAL s
REPEAT_DELAY = 0.4
REPEAT_INTERVAL = 0.1
REPEATING = frozenset({"step_forward", "step_back"})

SCRUB_REST = 0.05  # seconds the timeline's pointer rests before its step is gone to


@dataclass
class HeldKey:
    """A step key held down: its key code, the action it repeats, and when."""

    key: Any
    action: str
    due: float


class Stepping:
    """The step keys, playing, a held key's repeat and the timeline's scrub.

    Args:
        runs: what the window knows of the runs (it is told when a result is due).
        session: gives the session to drive (the window's current one).
        echo: prints a line in the terminal.

    Attributes:
        playing: the steps play at :attr:`rate` (until the run ends or a key stops it).
        rate: steps a second while playing.
        held: the step key held down, repeating, or None.
        clock: the clock of the key repeat (tests step it by hand).
        scrubbing: the timeline is being dragged.
        scrub_step: the step to go to once the pointer rests, or None.
    """

    def __init__(self, runs: RunTracker, session: Callable[[], PlaybackControls],
                 echo: Callable[[str], None]) -> None:
        self.runs = runs
        self._session = session
        self._echo = echo
        self.rate = DEFAULT_RATE
        self.clock: Callable[[], float] = time.perf_counter
        self.forget()

    def forget(self) -> None:
        """Drop what belongs to the runs of another script (the rate stays)."""
        self.playing = False
        self.held: HeldKey | None = None
        self.scrubbing = False
        self.scrub_step: int | None = None
        self._scrub_time = 0.0

    def result_arrived(self, shown: RunResult | None, result: RunResult) -> None:
        """Playing stops once a run played to its end (or failed): Space plays again."""
        if self.playing and run_ended(shown, result):
            self.playing = False

    # -- keys ---------------------------------------------------------------------

    def play_pause(self) -> None:
        """Play the steps at :attr:`rate`, or pause."""
        self.playing = not self.playing
        if self.playing:
            self._session().play(self.rate)
        else:
            self._session().pause()
        self.runs.waiting = self.playing

    def faster(self) -> None:
        """Double the play rate (up to :data:`HIGHEST_RATE`)."""
        self._set_rate(min(self.rate * 2, HIGHEST_RATE))

    def slower(self) -> None:
        """Halve the play rate (down to :data:`LOWEST_RATE`)."""
        self._set_rate(max(self.rate / 2, LOWEST_RATE))

    def _set_rate(self, rate: float) -> None:
        """Play at ``rate`` from now on (at once when playing)."""
        self.rate = rate
        if self.playing:
            self._session().play(rate)
        self._echo(f"play rate: {rate:g} steps/s")

    def step_forward(self) -> None:
        """Show the next step; at the last one say so (the session posts nothing)."""
        self.playing = False
        self._session().step_forward()  # (a run a save started pauses at its next step)
        if self.runs.ended():
            self._echo("no steps" if self.runs.shown_step() is None
                       else "at the last step (Left, Home or the timeline go back)")
        else:
            self.runs.expect()

    def step_back(self) -> None:
        """Show the previous step; at the first one say so (the session posts nothing)."""
        self.playing = False
        shown = self.runs.shown_step()
        self._session().step_back()
        if self.runs.waiting or (shown is not None and shown > 0):
            self.runs.expect()
        else:
            self._echo("no steps" if shown is None else "at the first step")

    def first_step(self) -> None:
        """Go to the first step (a syntax error has none: replaying it would fail again)."""
        if not self.runs.waiting and self.runs.shown_step() is None:
            self._echo("no steps")
            return
        self.goto(0)

    def run_to_end(self) -> None:
        """Run to the end; at the end already, say so."""
        self.playing = False
        self._session().run_to_end()
        if self.runs.ended():
            self._echo("already at the end")
        else:
            self.runs.expect()

    def reload(self) -> None:
        """Re-run the script now."""
        self._session().reload()
        self.runs.expect()

    def goto(self, k: int) -> None:
        """Stop playing and show the mesh right after step ``k`` (0-based)."""
        self.playing = False
        self._session().goto_step(k)
        self.runs.expect()

    def step(self, action: str) -> None:
        """Run a step action by name (one of :data:`REPEATING`)."""
        (self.step_forward if action == "step_forward" else self.step_back)()

    # -- a held key ------------------------------------------------------------------

    def hold(self, key: Any, action: str | None) -> None:
        """``key`` went down and ran ``action``: a step key that went somewhere
        repeats while held (one that said why not, once, does not)."""
        self.held = None  # another key ends a repeat, as a keyboard's does
        if action in REPEATING and self.runs.waiting:
            self.held = HeldKey(key, action, self.clock() + REPEAT_DELAY)

    def release(self, key: Any) -> None:
        """``key`` went up: its repeat ends."""
        if self.held is not None and self.held.key == key:
            self.held = None

    def repeat_held(self) -> None:
        """Step again while a step key is held, once the step before has arrived (a
        step that replays the script must not pile up behind the key); at the
        first or last step the repeat ends."""
        held = self.held
        if held is None or self.runs.waiting:
            return
        now = self.clock()
        if now < held.due:
            return
        self.step(held.action)
        if self.runs.waiting:
            held.due = now + REPEAT_INTERVAL
        else:
            self.held = None  # nowhere to go: it said so once

    # -- the timeline ------------------------------------------------------------------

    def scrub_to(self, step: int) -> None:
        """The timeline was dragged to ``step``: it is gone to once the pointer rests
        or is let go (a drag over steps not in the snapshot cache would replay the
        script for each)."""
        self.scrubbing = True
        self.scrub_step = step
        self._scrub_time = time.perf_counter()

    def end_scrub(self) -> None:
        """The timeline was let go: go to its step now."""
        self.scrubbing = False
        self.flush_scrub(force=True)

    def flush_scrub(self, force: bool = False) -> None:
        """Go to the scrubbed step once the pointer rested :data:`SCRUB_REST` s."""
        step = self.scrub_step
        resting = time.perf_counter() - self._scrub_time >= SCRUB_REST
        if step is None or not (force or resting):
            return
        self.scrub_step = None
        if step != self.runs.shown_step() or self.runs.waiting:
            self.goto(step)


def run_ended(shown: RunResult | None, result: RunResult) -> bool:
    """``result`` is a run's end (ok, error, cancelled) newly arrived, not the
    re-post of ``shown`` with its preview."""
    if result.status == "paused":
        return False
    return shown is None or (shown.run_id, shown.status) != (result.run_id, result.status)
