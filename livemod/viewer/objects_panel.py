"""The object list: every object of the scene, each with a checkbox that shows or
hides it (GL-free).

A scene of several objects (each ``load()`` adds one) draws the current object
and, muted, the others. :class:`ObjectPanel` lists them all and says what a
pointer position hits; the window keeps the set of hidden object ids, and the
free functions here say what that set becomes when ``Tab`` is pressed or a new
result arrives. The current object's checkbox hides it whatever its id (the
script may make another object current), until it is ticked again.

Coordinates are framebuffer pixels from the top left, as the HUD's.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .params_panel import PANEL_WIDTH, Hit

if TYPE_CHECKING:
    from livemod.runner.results import RunResult
from .text import (
    BUTTON,
    FILL,
    LABEL_DIM,
    MARGIN,
    PADDING,
    PANEL,
    QUAD_FLOATS,
    TEXT,
    TRACK,
    WARN_TEXT,
    box_quad,
    glyph_atlas,
    layout_text,
    text_width,
)

CHECK_WIDTH = 18  # the checkbox column
BUTTONS = ("all", "none")  # header buttons, left to right


@dataclass(frozen=True)
class ObjectRow:
    """One listed object: its id, name, vertex and face counts, and whether it is
    the current object."""

    oid: int
    name: str
    vertices: int
    faces: int
    current: bool = False

    def text(self) -> str:
        """The row's words: ``3 name   V 12  F 10``."""
        named = f" {self.name}" if self.name else ""
        tail = "  (current)" if self.current else ""
        return f"{self.oid}{named}   V {self.vertices}  F {self.faces}{tail}"


def result_rows(result: RunResult) -> tuple[ObjectRow, ...]:
    """The rows of a runner ``RunResult``: its objects in object order (the current
    one where its id falls), with render counts (holes not counted as faces)."""
    rows = [ObjectRow(oid, name, arrays.counts[0],
                      arrays.counts[2] - int(arrays.face_hole.sum()))
            for oid, name, arrays in result.other_objects]
    current, arrays = result.current_object, result.arrays
    if current is not None and arrays is not None:
        holes = int(arrays.face_hole.sum())
        rows.append(ObjectRow(current[0], current[1], arrays.counts[0],
                              arrays.counts[2] - holes, current=True))
    return tuple(sorted(rows, key=lambda row: row.oid))


def visible_objects(objects: Sequence[tuple[int, str, Any]], hidden: frozenset[int],
                    ) -> list[tuple[int, str, Any]]:
    """The ``(object id, name, arrays)`` of ``objects`` whose ids are not ``hidden``."""
    return [item for item in objects if item[0] not in hidden]


def next_alone(ids: Sequence[int], hidden: frozenset[int]) -> frozenset[int]:
    """The hidden set after ``Tab``: each of ``ids`` alone in turn, then all again.

    When exactly one of two or more objects is shown, the next one is shown alone
    (all of them after the last); from any other set, the first one alone.
    """
    shown = [oid for oid in ids if oid not in hidden]
    if len(ids) > 1 and len(shown) == 1:
        at = list(ids).index(shown[0]) + 1
        return frozenset() if at == len(ids) else frozenset(ids) - {ids[at]}
    return frozenset(ids) - {ids[0]} if ids else frozenset()


def kept_hidden(hidden: frozenset[int], shown_before: frozenset[int],
                ids: Sequence[int]) -> frozenset[int]:
    """What stays hidden when a result with objects ``ids`` replaces one in which
    ``shown_before`` were shown: the same ids, also those the result lacks (an
    earlier step of a playback may not have made them yet), so objects the script
    adds later are shown; but none at all once every object that was shown is gone,
    so that a re-run never leaves the others all hidden by accident."""
    if shown_before and not shown_before & frozenset(ids):
        return frozenset()
    return hidden


class ObjectPanel:
    """The list of the scene's objects and the checkboxes of the other objects.

    Attributes:
        rows: the listed objects, in object order.
        hidden: ids of the other objects that are not drawn.
        top: framebuffer y of the panel's top (the window puts it below the
            parameters panel).
        first: the first row shown (the list scrolls when it does not fit).
        hover: the index into :attr:`rows` of the row under the pointer (drawn
            highlighted when a click there toggles it), or None.
        current_hidden: the current object is not drawn (its row unticked).
    """

    def __init__(self) -> None:
        self.rows: tuple[ObjectRow, ...] = ()
        self.hidden: frozenset[int] = frozenset()
        self.top = float(MARGIN)
        self.first = 0
        self.hover: int | None = None
        self.current_hidden = False

    def sync(self, rows: Sequence[ObjectRow], hidden: frozenset[int]) -> None:
        """Show ``rows`` with the ``hidden`` ones unticked."""
        self.rows, self.hidden = tuple(rows), hidden
        self.first = min(self.first, max(len(self.rows) - 1, 0))
        if self.hover is not None and self.hover >= len(self.rows):
            self.hover = None

    def point_at(self, hit: Hit | None) -> None:
        """Follow the pointer: ``hit`` is what :meth:`hit` says it is over."""
        self.hover = hit.row if hit is not None and hit.part in ("toggle", "current") else None

    def state(self) -> tuple:
        """A hashable summary of everything drawn (the overlay is cached on it)."""
        return (self.rows, self.hidden, self.top, self.first, self.hover, self.current_hidden)

    # -- layout --------------------------------------------------------------

    def frame(self, size: tuple[int, int]) -> tuple[float, float, float, float]:
        """``(x, y, width, row height)`` of the panel in a ``size`` framebuffer."""
        width = float(min(PANEL_WIDTH, max(size[0] - 2 * MARGIN, 120)))
        x = max(size[0] - MARGIN - width, float(MARGIN))
        return x, self.top, width, float(glyph_atlas().line_height + 4)

    def fitting_rows(self, size: tuple[int, int]) -> int:
        """How many rows fit between the panel's top and the bottom of the window
        (at least one)."""
        _, y, _, row_height = self.frame(size)
        return max(int((size[1] - MARGIN - y - 2 * PADDING) // row_height) - 1, 1)

    def shown_rows(self, size: tuple[int, int]) -> range:
        """The indices of :attr:`rows` drawn now."""
        count = self.fitting_rows(size)
        first = min(self.first, max(len(self.rows) - count, 0))
        return range(first, min(first + count, len(self.rows)))

    def scroll(self, rows: int, size: tuple[int, int]) -> None:
        """Scroll the list by ``rows`` (positive: down), within its length."""
        last_first = max(len(self.rows) - self.fitting_rows(size), 0)
        self.first = min(max(self.shown_rows(size).start + rows, 0), last_first)

    def _button_x(self, size: tuple[int, int]) -> list[tuple[str, float, float]]:
        """``(button, left, right)`` of the header buttons."""
        x, _, width, _ = self.frame(size)
        atlas, right = glyph_atlas(), x + width - PADDING
        placed: list[tuple[str, float, float]] = []
        for label in reversed(BUTTONS):
            left = right - text_width(atlas, label)
            # the last button reaches the panel's edge: easier to hit
            placed.append((label, left - 3, x + width if not placed else right + 3))
            right = left - 12
        return placed[::-1]

    def hit(self, px: float, py: float, size: tuple[int, int]) -> Hit | None:
        """What framebuffer point ``(px, py)`` is over, or None when it is off the panel.

        Rows hit as ``Hit(index into rows, "toggle")`` (``"current"`` for the
        current object's), the header as ``Hit(-1, "all" | "none" | "name")``.
        """
        if not self.rows:
            return None
        x, y, width, row_height = self.frame(size)
        shown = self.shown_rows(size)
        line = int((py - y - PADDING) // row_height) - 1
        if not (x <= px <= x + width) or py < y or line >= len(shown):
            return None
        if line < 0:
            for label, left, right in self._button_x(size):
                if left <= px <= right:
                    return Hit(-1, label)
            return Hit(-1, "name")
        index = shown[line]
        return Hit(index, "current" if self.rows[index].current else "toggle")

    # -- drawing -------------------------------------------------------------

    def quads(self, size: tuple[int, int]) -> np.ndarray:
        """Text and box quads of the whole panel (empty when it lists no objects)."""
        if not self.rows:
            return np.zeros((0, QUAD_FLOATS), dtype=np.float32)
        atlas = glyph_atlas()
        x, y, width, row_height = self.frame(size)
        shown = self.shown_rows(size)
        height = (len(shown) + 1) * row_height + 2 * PADDING
        parts = [box_quad(atlas, x, y, width, height, PANEL),
                 layout_text(atlas, [self._title(shown)], (x + PADDING, y + PADDING), TEXT)]
        for label, left, _ in self._button_x(size):
            parts.append(layout_text(atlas, [label], (left + 3, y + PADDING), LABEL_DIM))
        for line, index in enumerate(shown):
            top = y + PADDING + (line + 1) * row_height
            if index == self.hover:
                parts.append(box_quad(atlas, x + 2, top, width - 4, row_height, BUTTON))
            parts.append(self._row_quads(self.rows[index], x + PADDING, top, row_height))
        return np.concatenate(parts)

    def _title(self, shown: range) -> str:
        total = len(self.rows)
        if len(shown) == total:
            return f"Objects ({total})"
        return f"Objects {shown.start + 1}-{shown.stop} of {total} (wheel)"

    def _row_quads(self, row: ObjectRow, left: float, top: float,
                   row_height: float) -> np.ndarray:
        atlas, box = glyph_atlas(), row_height - 6
        ticked = not self.current_hidden if row.current else row.oid not in self.hidden
        colour = (WARN_TEXT if row.current else TEXT) if ticked else LABEL_DIM
        return np.concatenate([
            box_quad(atlas, left, top + 3, box, box, FILL if ticked else TRACK),
            layout_text(atlas, [row.text()], (left + CHECK_WIDTH, top + 1), colour)])
