"""Stepping through the script's steps: the step keys, playing, a held key's
repeat and the timeline's scrub (GL-free).

:class:`Stepping` turns the keys and the timeline into the session's playback
calls (:class:`~livemod.viewer.session.PlaybackControls`), whose state machine
(docs/playback.md) decides what is shown. Each call says whether a result is on
its way: then the :class:`~livemod.viewer.runs.RunTracker` waits for it; else
nothing is to come (at the last step already, say) and the terminal says so, so
the window never waits for a result that will not come.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from livemod.runner.playback import PlaybackState, PlaybackView

from .runs import RunTracker
from .session import PlaybackControls

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
        self.clock: Callable[[], float] = time.perf_counter
        self.forget()

    def forget(self) -> None:
        """Drop a held key and a scrub (another script opened)."""
        self.held: HeldKey | None = None
        self.scrubbing = False
        self.scrub_step: int | None = None
        self._scrub_time = 0.0

    @property
    def view(self) -> PlaybackView:
        """The session's playback: its state (docs/playback.md), step and rate."""
        return self._session().playback

    @property
    def state(self) -> PlaybackState:
        """Where the session's playback is."""
        return self.view.state

    @property
    def playing(self) -> bool:
        """The session plays the steps (until a key stops it or the run ends)."""
        return self.state is PlaybackState.PLAYING

    @property
    def rate(self) -> float:
        """Steps a second while playing."""
        return self.view.rate

    # -- keys ---------------------------------------------------------------------

    def play_pause(self) -> None:
        """Play the steps (from the first after the end), or pause."""
        self._asked(self._session().toggle_play())

    def faster(self) -> None:
        """Double the play rate (at once when playing)."""
        self._echo(f"play rate: {self._session().faster():g} steps/s")

    def slower(self) -> None:
        """Halve the play rate (at once when playing)."""
        self._echo(f"play rate: {self._session().slower():g} steps/s")

    def step_forward(self) -> None:
        """Show the next step; at the last one say so."""
        if not self._asked(self._session().step_forward()):
            self._echo("no steps" if self.runs.shown_step() is None
                       else "at the last step (Left, Home or the timeline go back)")

    def step_back(self) -> None:
        """Show the previous step; at the first one say so."""
        if not self._asked(self._session().step_back()):
            self._echo("no steps" if self.runs.shown_step() is None else "at the first step")

    def first_step(self) -> None:
        """Go to the first step (a syntax error has none)."""
        if not self._asked(self._session().goto_step(0)):
            self._echo("no steps" if self.runs.shown_step() is None else "at the first step")

    def run_to_end(self) -> None:
        """Run to the end; at the end already, or running there, say so."""
        if not self._asked(self._session().run_to_end()):
            running = self.state is PlaybackState.RUNNING
            self._echo("running to the end" if running else "already at the end")

    def reload(self) -> None:
        """Re-run the script now."""
        self._session().reload()
        self.runs.expect()

    def goto(self, k: int) -> None:
        """Show the mesh right after step ``k`` (0-based)."""
        self._asked(self._session().goto_step(k))

    def step(self, action: str) -> None:
        """Run a step action by name (one of :data:`REPEATING`)."""
        (self.step_forward if action == "step_forward" else self.step_back)()

    def _asked(self, coming: bool) -> bool:
        """Wait for a result when the session said one is ``coming``; returns it."""
        if coming:
            self.runs.expect()
        return coming

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
