"""The step timeline: a bar along the bottom of the window to scrub through the
steps of the script (GL-free).

The bar spans the window's width; its fill reaches the step shown, and a click
or a drag on it goes to the step under the pointer. The window sends that step
to the session (``goto_step``), which shows it from its snapshot cache or
replays the script to it.

Coordinates are framebuffer pixels from the top left, as the HUD's.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .text import (
    FILL,
    LABEL_DIM,
    MARGIN,
    PADDING,
    PANEL,
    QUAD_FLOATS,
    TEXT,
    TRACK,
    box_quad,
    glyph_atlas,
    layout_text,
    text_width,
)

if TYPE_CHECKING:
    from livemod.runner.results import RunResult

HANDLE = TEXT  # the bright handle on the track
BAR_HEIGHT = 10
HANDLE_WIDTH = 4


def shown_step(result: RunResult | None, total: int) -> int | None:
    """The 0-based step a result shows: its paused or cached step, else its last
    one; None when it has no steps."""
    steps = () if result is None else result.steps
    if not steps and not total:
        return None
    index = None if result is None else result.step_index
    return len(steps) - 1 if index is None else min(index, max(len(steps), total) - 1)


class Timeline:
    """Layout and hit testing of the step bar (see the module docstring)."""

    def frame(self, size: tuple[int, int]) -> tuple[float, float, float, float]:
        """``(x, y, width, height)`` of the whole panel (bar and its labels)."""
        height = BAR_HEIGHT + glyph_atlas().line_height + 2 * PADDING
        width = max(size[0] - 2 * MARGIN, 40)
        return float(MARGIN), float(size[1] - MARGIN - height), float(width), float(height)

    def _bar(self, size: tuple[int, int]) -> tuple[float, float, float]:
        """``(left, top, width)`` of the track."""
        x, y, width, _ = self.frame(size)
        return x + PADDING, y + PADDING + glyph_atlas().line_height, width - 2 * PADDING

    def hit(self, px: float, py: float, size: tuple[int, int]) -> bool:
        """True when framebuffer point ``(px, py)`` is on the panel."""
        x, y, width, height = self.frame(size)
        return x <= px <= x + width and y <= py <= y + height

    def step_at(self, px: float, size: tuple[int, int], total: int) -> int:
        """The 0-based step of ``total`` whose handle is nearest ``px`` (clamped to
        the bar's ends).

        Step k's handle stands at the end of its fill, ``(k + 1) / total`` of the
        bar (see :meth:`quads`), so a press on the handle to drag it keeps its step.
        """
        left, _, width = self._bar(size)
        fraction = min(max((px - left) / max(width, 1.0), 0.0), 1.0)
        return min(max(round(fraction * total) - 1, 0), total - 1)

    def quads(self, size: tuple[int, int], shown: int | None, total: int) -> np.ndarray:
        """The panel's quads: the track, its fill to step ``shown`` of ``total``, a
        handle there and the labels ``1`` and ``total`` at its ends."""
        if total < 2 or shown is None:
            return np.zeros((0, QUAD_FLOATS), dtype=np.float32)
        atlas = glyph_atlas()
        x, y, width, height = self.frame(size)
        left, top, bar_width = self._bar(size)
        reach = bar_width * (shown + 1) / total
        end = str(total)
        return np.concatenate([
            box_quad(atlas, x, y, width, height, PANEL),
            layout_text(atlas, ["steps   click or drag to go to one"], (left, y + PADDING - 1),
                        LABEL_DIM),
            layout_text(atlas, [end], (left + bar_width - text_width(atlas, end),
                                       y + PADDING - 1), LABEL_DIM),
            box_quad(atlas, left, top, bar_width, BAR_HEIGHT, TRACK),
            box_quad(atlas, left, top, reach, BAR_HEIGHT, FILL),
            box_quad(atlas, left + reach - HANDLE_WIDTH / 2, top - 2, HANDLE_WIDTH,
                     BAR_HEIGHT + 4, HANDLE)])
