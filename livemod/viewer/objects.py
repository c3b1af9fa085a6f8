"""The scene's other objects as the window shows them: which are drawn, ``Tab``
one at a time, and the object list's checkboxes (GL-free).

:class:`SceneObjects` keeps the :class:`~livemod.viewer.objects_panel.ObjectPanel`
and its set of hidden object ids across results, and hands the joined arrays of
the objects to draw to the renderer through the ``show_others`` callable it is
given.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from .look import Look
from .objects_panel import ObjectPanel, kept_hidden, next_alone, result_rows, visible_objects
from .params_panel import Hit
from .runs import RunTracker

if TYPE_CHECKING:
    from livemod.dlfl.arrays import MeshArrays
    from livemod.runner.results import RunResult


class SceneObjects:
    """Which of the scene's objects are drawn, and the object list (``L``).

    Args:
        runs: the result shown (its objects are the ones listed).
        look: its style says whether the others and the current object are drawn.
        echo: prints a line in the terminal.
        show_others: gives the renderer the other objects to draw (None: none).

    Attributes:
        panel: the object list's rows, hidden ids and layout.
        listed: the object list is open.
    """

    def __init__(self, runs: RunTracker, look: Look, echo: Callable[[str], None],
                 show_others: Callable[[MeshArrays | None], None]) -> None:
        self._runs = runs
        self._look = look
        self._echo = echo
        self._show_others = show_others
        self.panel = ObjectPanel()
        self.listed = False

    def forget(self) -> None:
        """Another script: its objects share no ids with these; its current one is drawn."""
        self.panel.sync((), frozenset())
        self.set_current_shown(True)

    @property
    def hidden(self) -> frozenset[int]:
        """Ids of the other objects not drawn (unticked in the list, or not the one
        ``Tab`` shows alone)."""
        return self.panel.hidden

    def other_ids(self, result: RunResult | None = None) -> list[int]:
        """The ids of ``result``'s other objects (the result shown's by default)."""
        result = self._runs.result if result is None else result
        return [oid for oid, _, _ in result.other_objects] if result is not None else []

    def sync(self, result: RunResult) -> None:
        """List ``result``'s objects (before it is shown), keeping hidden the ones
        still there."""
        before = frozenset(self.other_ids()) - self.panel.hidden
        hidden = kept_hidden(self.panel.hidden, before, self.other_ids(result))
        self.panel.sync(result_rows(result), hidden)

    def visible_others(self, result: RunResult) -> MeshArrays | None:
        """The other objects to draw, joined: all of them (the result's own join),
        or those not hidden; None when none is shown."""
        if not self.panel.hidden:
            return result.others
        from livemod.runner.results import join_others

        return join_others(visible_objects(result.other_objects, self.panel.hidden))

    def set_hidden(self, hidden: frozenset[int]) -> None:
        """Draw the other objects whose ids are not in ``hidden`` (and the others at
        all: choosing what to show means showing it)."""
        self.panel.hidden = frozenset(hidden)
        self._look.change(others=True)
        if self._runs.result is not None:
            self._show_others(self.visible_others(self._runs.result))

    def set_current_shown(self, shown: bool) -> None:
        """Draw the current object or not (not drawn, it is not picked or labelled);
        it stays so across runs, whichever object the script leaves current."""
        self.panel.current_hidden = not shown
        self._look.change(current=shown)

    def note(self) -> str:
        """Which other objects are drawn, for the HUD and the echo ("" for all)."""
        result = self._runs.result
        objects = result.other_objects if result is not None else ()
        shown = visible_objects(objects, self.panel.hidden)
        if len(shown) == len(objects):
            return ""
        if len(shown) == 1:
            oid, name, _ = shown[0]
            named = f" {name!r}" if name else ""
            return f"object {oid}{named} alone (of {len(objects)}; Tab: next)"
        return f"{len(shown)} of {len(objects)} shown (L: list)"

    def list_shown(self, panels_shown: bool) -> bool:
        """The list is drawn: open, the panels up, and an object to list (one
        object too: its checkbox hides it)."""
        return self.listed and panels_shown and bool(self.panel.rows)

    # -- keys and clicks ------------------------------------------------------------

    def cycle(self) -> None:
        """``Tab``: each other object alone in turn, then all again."""
        ids = self.other_ids()
        if not ids:
            self._echo("the scene has no other objects")
            return
        self.set_hidden(next_alone(ids, self.panel.hidden))
        self._echo_others()

    def toggle_list(self) -> None:
        """``L``: open or close the object list."""
        self.listed = not self.listed
        if self.listed and not self.panel.rows:
            self._echo("the scene has no objects to list")

    def press(self, hit: Hit) -> None:
        """A click on the object list: tick or untick an object, or all (the current
        one too) / none (of the others)."""
        if hit.part == "current":
            self.set_current_shown(self.panel.current_hidden)
            self._echo(f"current object: {'hidden' if self.panel.current_hidden else 'shown'}")
            return
        if hit.part in ("all", "none"):
            if hit.part == "all":
                self.set_current_shown(True)
            self.set_hidden(frozenset() if hit.part == "all" else frozenset(self.other_ids()))
        elif hit.part == "toggle":
            self.set_hidden(self.panel.hidden ^ {self.panel.rows[hit.row].oid})
        else:
            return
        self._echo_others()

    def _echo_others(self) -> None:
        """Say which other objects are drawn now."""
        self._echo(f"other objects: {self.note() or 'all ' + str(len(self.other_ids()))}")
