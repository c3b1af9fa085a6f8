"""What the window needs of a live session, as typed protocols.

The window drives the runner's :class:`~livemod.runner.session.LiveSession`
through these, as the watcher takes its file events through
:class:`~livemod.runner.watch.Notifier`. Each controller is given the narrow part
it uses (stepping the playback, the parameters, the selection), so a test drives
it with a small fake, and nothing is looked up by name.
"""

from __future__ import annotations

import queue
from typing import TYPE_CHECKING, Any, Protocol

from livemod.dlfl.scene import Selection

if TYPE_CHECKING:
    from livemod.runner.playback import PlaybackView
    from livemod.runner.results import RunResult
    from livemod.runner.session import RunActivity


class PlaybackControls(Protocol):
    """Stepping through the runs (docs/playback.md has the state machine). Every
    call only changes state and returns at once; what it shows arrives later as a
    result, and the calls that step say whether one will (False: nothing is to
    come, as at the last step already)."""

    @property
    def playback(self) -> PlaybackView:
        """The playback's state, the step it shows (or goes to) and the play rate."""

    @property
    def play_rate(self) -> float:
        """Steps a second while playing."""

    def faster(self) -> float:
        """Double the play rate (within the session's bounds); the new rate."""

    def slower(self) -> float:
        """Halve the play rate (within the session's bounds); the new rate."""

    def toggle_play(self) -> bool:
        """Pause while playing, else play."""

    def play(self, rate: float | None = None) -> bool:
        """Play at :attr:`play_rate` (``rate``, when given, becomes it)."""

    def pause(self) -> bool:
        """Hold the run at the step shown (a running run at its next step)."""

    def resume(self) -> bool:
        """Go on from a pause: play again if a play was paused, else to the end."""

    def run_to_end(self) -> bool:
        """Show the end: the run goes on without pausing."""

    def step_forward(self) -> bool:
        """Show the next step."""

    def step_back(self) -> bool:
        """Show the previous step."""

    def goto_step(self, k: int) -> bool:
        """Show the mesh right after step ``k`` (0-based)."""

    def cancel(self) -> bool:
        """Stop the running run."""

    def reload(self) -> None:
        """Re-run the script now."""


class ParameterInputs(Protocol):
    """The script parameters the next run gets."""

    @property
    def parameters(self) -> dict[str, Any]:
        """The values the next run gets, by name."""

    def set_parameters(self, values: dict[str, Any]) -> None:
        """Change ``values`` and re-run; raises when a value does not fit its
        declaration (nothing is changed then)."""

    def reset_parameters(self, names: list[str] | None = None) -> None:
        """Back to the defaults (all when ``names`` is None) and re-run."""


class SelectionInput(Protocol):
    """What ``faces(True)`` and the like return from the next run on."""

    def set_selection(self, selection: Selection | None) -> None:
        """Give ``selection`` to the next runs (no re-run)."""


class Session(PlaybackControls, ParameterInputs, SelectionInput, Protocol):
    """A live session the window shows: the runs it posts, and its life cycle."""

    results: queue.Queue[RunResult]
    """Results as the runs post them; the window drains it without blocking."""

    @property
    def activity(self) -> RunActivity | None:
        """The newest run while it works (neither paused nor ended), else None."""

    @property
    def empty_script(self) -> str | None:
        """The script's path while a save left it empty (and ran nothing), else None."""

    @property
    def background_runs(self) -> tuple[int, ...]:
        """Ids of abandoned runs still working in the background, oldest first."""

    def start(self) -> None:
        """Start watching and run the script once."""

    def close(self) -> None:
        """Stop watching and cancel the run; threads wind down in the background."""
