"""The view state: everything the HUD and the panels show, in one value (GL-free).

The window gathers it once a frame from its controllers (see
``LiveViewer.view_state``). Everything drawn over the scene derives from it: the
HUD's lines (:func:`livemod.viewer.hud.hud_lines`), the overlay's quads, and the
cache keys, since two equal states draw the same overlay. The results and mesh
snapshots it holds compare by identity (a new result is a new picture even when
its arrays are equal); every other field by value.
"""

from __future__ import annotations

import dataclasses
import operator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from livemod.runner.playback import PlaybackState

from .controls import PickMode
from .measure import WholeMesh
from .renderer import Style

if TYPE_CHECKING:
    from livemod.dlfl.arrays import MeshArrays
    from livemod.runner.results import RunResult


def _same() -> Any:
    """A field compared by identity (see :meth:`ViewState.__eq__`)."""
    return field(default=None, metadata={"identity": True})


@dataclass(frozen=True, eq=False)
class ViewState:
    """What the overlay shows.

    Attributes:
        script: the path of the script shown.
        result: the runner's ``RunResult`` shown (None before the first one).
        waiting: the window asked the session for a result that has not come.
        working: seconds the run at work has worked (None when none works).
        running_run: the id of the run at work (newer than ``result``), or None.
        background: ids of abandoned runs still working in the background.
        good_run: the id of the run whose mesh a failed result shows (the last
            good one), when the window saw it; else None.
        total_steps: the step count of the last run that ended.
        arrays: the mesh on screen (the last good one, or a failed run's own).
        partial: the mesh on screen is the failed run's own (``E``).
        nonfinite: vertices drawn whose position is not finite.
        viewer_error: why the window could not show the last result, or None.
        empty_script: the script's path while a save left it empty, or None.
        whole: genus and volume of the mesh on screen (None until measured).
        fps: the frame rate shown.
        pick_mode: what a click picks.
        selection: the HUD's Python lines of the picks the mesh holds.
        missing: the HUD's notes of picks it lacks and selections found empty.
        measures: the measurements of the picks.
        others: the other objects drawn, joined (None when none is).
        others_note: which other objects are drawn ("" for all).
        current_hidden: the current object is not drawn.
        style: what the renderer draws.
        preview: the HUD's line about the smoothed preview ("" when it is not drawn).
        quick: the view moves and the picture is big: it is drawn quick, without
            its edges and multisampling, until the view rests (see
            :meth:`~.renderer.Renderer.quick_style`).
        ortho: the camera is orthographic.
        playback: the session's playback state: running, playing, paused, finished.
        rate: the play rate in steps a second.
        hud, help: the HUD and the help overlay are shown.
        panels: a hashable summary of the parameters panel, the object list and
            the timeline as drawn.
        size: the framebuffer's size.
        bottom: pixels the error panel keeps free at the bottom (the timeline).
    """

    script: str = ""
    result: RunResult | None = _same()
    waiting: bool = False
    working: float | None = None
    running_run: int | None = None
    background: tuple[int, ...] = ()
    good_run: int | None = None
    total_steps: int = 0
    arrays: MeshArrays | None = _same()
    partial: bool = False
    nonfinite: int = 0
    viewer_error: str | None = None
    empty_script: str | None = None
    whole: WholeMesh | None = None
    fps: float = 0.0
    pick_mode: PickMode = PickMode.FACE
    selection: tuple[str, ...] = ()
    missing: tuple[str, ...] = ()
    measures: tuple[str, ...] = ()
    others: MeshArrays | None = _same()
    others_note: str = ""
    current_hidden: bool = False
    style: Style = field(default_factory=Style)
    preview: str = ""
    quick: bool = False
    ortho: bool = False
    playback: PlaybackState = PlaybackState.FINISHED
    rate: float = 2.0
    hud: bool = True
    help: bool = False
    panels: tuple = ()
    size: tuple[int, int] = (0, 0)
    bottom: float = 0.0

    def __eq__(self, other: object) -> bool:
        # (compared every frame, as part of the frame's key: kept to a few
        # microseconds by comparing the value fields as one tuple)
        if not isinstance(other, ViewState):
            return NotImplemented
        return all(mine is theirs for mine, theirs in zip(
            _BY_IDENTITY(self), _BY_IDENTITY(other), strict=True)) and \
            _BY_VALUE(self) == _BY_VALUE(other)

    __hash__ = None  # type: ignore[assignment]  # compared, never a dict key

    def without_fps(self) -> ViewState:
        """The state with no frame rate: the frame rate alone does not draw a frame
        again (a million faces take half a second a frame on software GL)."""
        clone = object.__new__(ViewState)  # (dataclasses.replace costs 30 us a frame)
        clone.__dict__.update(self.__dict__, fps=0.0)
        return clone


_BY_IDENTITY = operator.attrgetter(*(spec.name for spec in dataclasses.fields(ViewState)
                                     if spec.metadata.get("identity")))
_BY_VALUE = operator.attrgetter(*(spec.name for spec in dataclasses.fields(ViewState)
                                  if not spec.metadata.get("identity")))
