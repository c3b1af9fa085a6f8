"""What is drawn over the scene: the HUD, the parameters panel, the object list and
the step timeline, where each one lies, and their quads (GL-free).

:class:`Overlay` says which panels are up, lays them out (the object list below
the parameters, the error panel above the timeline), tells which one a pointer
position is over, and makes the quads of a
:class:`~livemod.viewer.view_state.ViewState`, again only when the state changed.
"""

from __future__ import annotations

import numpy as np

from .hud import hud_quads
from .look import Look
from .objects import SceneObjects
from .parameters import Parameters
from .params_panel import Hit
from .runs import RunTracker
from .text import MARGIN
from .timeline import Timeline
from .view_state import ViewState


class Overlay:
    """The panels over the scene, in framebuffer pixels from the top left.

    Args:
        look: whether the HUD and the help are up.
        runs: the steps the timeline spans and the step shown.
        parameters: the parameters panel.
        objects: the object list.
    """

    def __init__(self, look: Look, runs: RunTracker, parameters: Parameters,
                 objects: SceneObjects) -> None:
        self._look = look
        self._runs = runs
        self._parameters = parameters
        self._objects = objects
        self.timeline = Timeline()
        self._quads: tuple[ViewState, np.ndarray] | None = None  # the last state's

    # -- what is up, and where -----------------------------------------------------

    def timeline_shown(self) -> bool:
        """The step timeline is drawn (with the panels, for two steps or more)."""
        return self._look.panels_shown and self._runs.steps() > 1

    def objects_shown(self) -> bool:
        return self._objects.list_shown(self._look.panels_shown)

    def lay_out(self, size: tuple[int, int]) -> None:
        """Put the object list below the parameters panel."""
        panel = self._parameters.panel
        self._objects.panel.top = panel.bottom(size) + (MARGIN if panel.specs else 0)

    def state(self) -> tuple:
        """A hashable summary of the panels as drawn (for :attr:`ViewState.panels`)."""
        return (self._parameters.panel.state(), self._objects.panel.state(),
                self.objects_shown(), self.timeline_shown())

    def error_room(self, size: tuple[int, int]) -> float:
        """Pixels the error panel leaves free at the bottom: the timeline's."""
        return self.timeline.frame(size)[3] + MARGIN if self.timeline_shown() else 0.0

    # -- what a point is over ---------------------------------------------------------

    def parameters_hit(self, px: float, py: float, size: tuple[int, int]) -> Hit | None:
        """The parameters panel's control at framebuffer point ``(px, py)``, or None."""
        if not self._look.panels_shown:
            return None
        return self._parameters.panel.hit(px, py, size)

    def objects_hit(self, px: float, py: float, size: tuple[int, int]) -> Hit | None:
        """The object list's row or button at ``(px, py)``, or None."""
        if not self.objects_shown():
            return None
        return self._objects.panel.hit(px, py, size)

    def timeline_hit(self, px: float, py: float, size: tuple[int, int]) -> bool:
        return self.timeline_shown() and self.timeline.hit(px, py, size)

    def timeline_step(self, px: float, size: tuple[int, int]) -> int:
        """The step whose handle on the timeline is nearest framebuffer x ``px``."""
        return self.timeline.step_at(px, size, self._runs.steps())

    # -- drawing ---------------------------------------------------------------------

    def quads(self, state: ViewState) -> np.ndarray:
        """The quads of the panels and the HUD of ``state``, laid out again only when
        the state changed (the frame rate changes twice a second), to keep frames
        cheap while a script runs."""
        if self._quads is None or self._quads[0] != state:
            size, parts = state.size, []
            if self.timeline_shown():
                parts.append(self.timeline.quads(size, self._runs.shown_step(),
                                                 self._runs.steps()))
            if self.objects_shown():
                parts.append(self._objects.panel.quads(size))
            if self._look.panels_shown:  # the parameters' tooltip is drawn over the list
                parts.append(self._parameters.panel.quads(size))
            parts.append(hud_quads(state))
            self._quads = (state, np.concatenate(parts))
        return self._quads[1]
