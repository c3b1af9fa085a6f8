"""The selection as the window edits it: the pick mode, clicks, and what the HUD
and the terminal say of the picks (GL-free).

The window's renderer finds the element under a click; :class:`Picking` turns
that into the new selection, gives it to the session's next runs
(:class:`~livemod.viewer.session.SelectionInput`), measures it, and echoes it as
the Python a script would see.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

from livemod.dlfl.scene import Selection

from .controls import (
    PickMode,
    missing_lines,
    selection_python,
    split_picks,
    toggle_pick,
    unpicked_lines,
)
from .measure import measure_lines
from .session import SelectionInput

if TYPE_CHECKING:
    from livemod.dlfl.arrays import MeshArrays


class Picking:
    """The pick mode, the selection and its measures.

    Args:
        session: gives the session the selection goes to (the window's current one).
        echo: prints a line in the terminal.
        selection: the selection to start with (``--select``).

    Attributes:
        mode: what a click picks.
        selection: the picks, kept while a mesh shown lacks them (stepping back to
            before they were made must not lose them).
        measures: the HUD's measurements of the picks, on the mesh shown.
    """

    def __init__(self, session: Callable[[], SelectionInput], echo: Callable[[str], None],
                 selection: Selection | None = None) -> None:
        self._session = session
        self._echo = echo
        self.mode = PickMode.FACE
        self.selection = selection or Selection()
        self.measures: list[str] = []
        # (selection, arrays, (selection lines, missing lines)) of the last lines asked
        self._lines: tuple[Selection, object, tuple[list[str], list[str]]] | None = None

    def forget(self) -> None:
        """Another script or mesh: the picks' ids were the old mesh's."""
        self.selection = Selection()
        self.measures = []

    def next_mode(self) -> None:
        """``M``: the next pick mode."""
        self.mode = self.mode.following()

    def set_mode(self, mode: PickMode) -> None:
        self.mode = PickMode(mode)

    def clicked(self, element_id: int | None, add: bool) -> Selection | None:
        """The selection after a click on ``element_id`` (None: the background, which
        clears it unless ``add``); None when it does not change."""
        if element_id is None:
            return None if add else Selection()
        return toggle_pick(self.selection, self.mode, element_id, add)

    def select(self, selection: Selection, arrays: MeshArrays | None) -> None:
        """Take ``selection``, give it to the session, and echo it as Python with
        its measures on ``arrays`` (the mesh shown)."""
        self.selection = selection
        self._session().set_selection(selection)
        self.measures = measure_lines(selection, arrays)
        for line in (*selection_python(selection, arrays), *self.measures):
            self._echo(line)

    def remeasure(self, arrays: MeshArrays | None) -> None:
        """Measure the picks again, on a new mesh shown."""
        self.measures = measure_lines(self.selection, arrays)

    def hud_lines(self, arrays: MeshArrays | None,
                  unselected: Sequence[str]) -> tuple[list[str], list[str]]:
        """The HUD's selection lines (the picks ``arrays`` holds, as the next run's
        ``faces(True)`` and the like see them) and its notes: picks it lacks, and
        selections the run asked for (``unselected``) with nothing picked."""
        selection = self.selection
        unpicked = unpicked_lines(unselected, selection)
        if selection.is_empty():
            return [], unpicked
        cached = self._lines  # (the arrays held, not their id: ids are reused)
        if cached is None or cached[0] != selection or cached[1] is not arrays:
            present, absent = split_picks(selection, arrays)
            # all missing: no `faces(True) == ()` line (that says a pick was cleared)
            held = selection_python(present, arrays) if not present.is_empty() else []
            cached = (selection, arrays, (held, missing_lines(absent)))
            self._lines = cached
        held, missing = cached[2]
        return held, missing + unpicked
