"""The selection as the window edits it: the pick mode, clicks, and what the HUD
and the terminal say of the picks (GL-free).

The window's renderer finds the element under a click; :class:`Picking` turns
that into the new selection, gives it to the session's next runs
(:class:`~livemod.viewer.session.SelectionInput`), measures it, and echoes it as
the Python a script would see.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from livemod.dlfl import selection as rules
from livemod.dlfl.errors import DLFLError, InvalidArgumentError
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

    def tool(self, name: str, arrays: MeshArrays | None) -> Selection | None:
        """The selection after TopMod's selection tool ``name`` (a key of
        :data:`SELECTION_TOOLS`) on the picks ``arrays`` holds; None, with a line
        in the terminal saying why, when there is nothing to act on."""
        if arrays is None:
            self._echo(f"{name.replace('_', ' ')}: no mesh shown yet")
            return None
        present, _ = split_picks(self.selection, arrays)
        needs, make = SELECTION_TOOLS[name]
        seeds_of = needs or self.mode.selection_field
        try:
            made = make(arrays, present, seeds_of)
        except DLFLError as exc:
            self._echo(f"{name.replace('_', ' ')}: {exc}")
            return None
        if made is None:
            one, mode = _WHAT[seeds_of]
            self._echo(f"{name.replace('_', ' ')}: pick {one} first (M to {mode} mode, click "
                       f"{one})")
        return made


# what each kind of pick is called in the terminal's hints
_WHAT = {"faces": ("a face", "face"), "edges": ("an edge", "edge"),
         "vertices": ("a vertex", "vertex"), "corners": ("a corner", "corner")}


def _union(rule: Callable[[MeshArrays, int], list[int]], arrays: MeshArrays,
           seeds: Sequence[int]) -> tuple[int, ...] | None:
    """The ids ``rule`` gives from each seed, each once in the order found; None
    without seeds."""
    if not seeds:
        return None
    found: dict[int, None] = {}
    for seed in seeds:
        found.update(dict.fromkeys(rule(arrays, seed)))
    return tuple(found)


def _from_seeds(rule: Callable[[MeshArrays, int], list[int]], into: str, keep: bool = False,
                ) -> Callable[[MeshArrays, Selection, str], Selection | None]:
    """A tool that applies ``rule`` to each pick of the kind it reads and puts the
    union into the ``into`` field (after what it held, with ``keep``)."""
    def tool(arrays: MeshArrays, picks: Selection, seeds_of: str) -> Selection | None:
        found = _union(rule, arrays, getattr(picks, seeds_of))
        if found is None:
            return None
        held: tuple[int, ...] = getattr(picks, into) if keep else ()
        return replace(picks, **{into: tuple(dict.fromkeys((*held, *found)))})
    return tool


def _similar(arrays: MeshArrays, picks: Selection, kind: str) -> Selection | None:
    """SHIFT+S: faces of the picked faces' sizes, edges of their end valences,
    vertices of their valences (the pick mode's kind)."""
    rule = {"faces": rules.matching_faces, "edges": rules.matching_edges,
            "vertices": rules.matching_vertices}.get(kind)
    if rule is None:
        raise InvalidArgumentError("corners have no similar ones (pick faces, edges or vertices)")
    return _from_seeds(rule, kind)(arrays, picks, kind)


def _whole(rule: Callable[[MeshArrays, list[int], str], list[int]], needs_picks: bool,
           ) -> Callable[[MeshArrays, Selection, str], Selection | None]:
    """A tool that replaces the pick mode's kind of picks by ``rule`` of them."""
    def tool(arrays: MeshArrays, picks: Selection, kind: str) -> Selection | None:
        ids: tuple[int, ...] = getattr(picks, kind)
        if needs_picks and not ids:
            return None
        return replace(picks, **{kind: tuple(rule(arrays, list(ids), kind))})
    return tool


#: TopMod's selection tools in the window: name -> (the kind of picks it reads,
#: None for the pick mode's; what it makes of them, None without picks to act on)
SELECTION_TOOLS: dict[str, tuple[str | None,
                                 Callable[[MeshArrays, Selection, str], Selection | None]]] = {
    "edge_loop": ("edges", _from_seeds(rules.edge_loop, "edges")),
    "edge_ring": ("edges", _from_seeds(rules.edge_ring, "edges")),
    "face_loop": ("edges", _from_seeds(rules.face_loop, "faces", keep=True)),
    "checkerboard": ("faces", _from_seeds(rules.checkerboard, "faces")),
    "similar": (None, _similar),
    "similar_area": ("faces", _from_seeds(rules.faces_by_area, "faces")),
    "grow": (None, _whole(rules.grow, True)),
    "shrink": (None, _whole(rules.shrink, True)),
    "invert": (None, _whole(rules.invert, False)),
    "all": (None, _whole(lambda arrays, ids, kind: rules.select_all(arrays, kind), False)),
}
