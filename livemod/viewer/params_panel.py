"""The parameters panel: the script's ``param()`` declarations as on-screen controls.

GL-free: :class:`ParameterPanel` holds what the panel shows, lays it out as text
and box quads (drawn with the HUD), and says which control a pointer position
hits. Numbers get sliders, bools a checkbox, choices a cycling button
(``<`` / ``>`` halves), strings a read-only text; every row has a reset button
and the header a "reset all". The window turns hits into values and sends them
to the session (debounced while a slider is dragged).

Coordinates are framebuffer pixels from the top left, as the HUD's.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from livemod.dlfl.params import ParamSpec

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
    GlyphAtlas,
    box_quad,
    glyph_atlas,
    layout_text,
    text_width,
)

PANEL_WIDTH, NAME_WIDTH, RESET_WIDTH = 340, 110, 16
SLIDER_STEPS = 1000  # an unstepped float slider moves in 1/1000 of its range


@dataclass(frozen=True)
class Hit:
    """What a pointer position is over: ``row`` (-1 = the header) and ``part``:
    "slider", "toggle", "prev", "next", "text", "reset", "reset_all" or "name"."""

    row: int
    part: str


def slider_range(spec: ParamSpec) -> tuple[float, float]:
    """``(lo, hi)`` a number's slider spans: its min and max, or around the default
    (as far again as the default is from zero, at least 1) where they are open."""
    span = max(abs(float(spec.default)), 1.0)
    lo = float(spec.min) if spec.min is not None else float(spec.default) - span
    hi = float(spec.max) if spec.max is not None else max(float(spec.default), lo) + span
    return lo, max(hi, lo)


def snap(spec: ParamSpec, fraction: float) -> Any:
    """The value at ``fraction`` (clamped to 0..1) along a number's slider.

    Values lie on the step grid ``lo + k * step`` (``lo`` the slider's left end;
    the step is whole numbers for an int without one, 1/1000 of the range for a
    float without one), from ``lo`` to the last grid value not above the right
    end. A declared ``max`` the grid misses (a step that does not divide the
    range) is a value of its own at the right end, so it can be reached; an open
    end's right end is only where the slider stops drawing, not a value.
    """
    lo, hi = slider_range(spec)
    raw = lo + min(max(fraction, 0.0), 1.0) * (hi - lo)
    step = abs(spec.step or 0.0) or (1.0 if spec.kind == "int" else (hi - lo) / SLIDER_STEPS)
    step = step or 1.0  # (an empty range)
    last = math.floor((hi - lo) / step * (1.0 + 1e-12) + 1e-9)  # the grid's last k
    value = lo + min(max(round((raw - lo) / step), 0), last) * step
    if spec.max is not None and abs(hi - raw) < abs(raw - value):
        value = hi
    value = min(max(value, lo), hi)
    return int(round(value)) if spec.kind == "int" else round(value, 12)


def _shown(value: Any) -> str:
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


class ParameterPanel:
    """The controls of one script's parameters and the values they show.

    Attributes:
        specs: the declarations, in the order of the script.
        values: ``name -> value`` shown now (the default when none was set).
        hover: the row under the pointer (its doc is shown), or None.
    """

    def __init__(self) -> None:
        self.specs: tuple[ParamSpec, ...] = ()
        self.values: dict[str, Any] = {}
        self.hover: int | None = None

    def sync(self, specs: tuple[ParamSpec, ...], values: dict[str, Any]) -> None:
        """Show ``specs`` with ``values`` (defaults for the names it lacks)."""
        self.specs = tuple(specs)
        self.values = {s.name: values.get(s.name, s.default) for s in self.specs}
        if self.hover is not None and self.hover >= len(self.specs):
            self.hover = None

    def state(self) -> tuple:
        """A hashable summary of everything drawn (the overlay is cached on it)."""
        return (self.specs, tuple(self.values.items()), self.hover)

    def python_lines(self) -> list[str]:
        """The shown values as ``name = param(...)`` lines to paste into the script."""
        return [f"{s.name} = {s.as_python(self.values.get(s.name, s.default))}"
                for s in self.specs]

    # -- layout --------------------------------------------------------------

    def frame(self, size: tuple[int, int]) -> tuple[float, float, float, float]:
        """``(x, y, width, row height)`` of the panel in a ``size`` framebuffer."""
        atlas = glyph_atlas()
        width = float(min(PANEL_WIDTH, max(size[0] - 2 * MARGIN, 120)))
        x = max(size[0] - MARGIN - width, float(MARGIN))
        return x, float(MARGIN), width, float(atlas.line_height + 4)

    def bottom(self, size: tuple[int, int]) -> float:
        """Framebuffer y just below the panel (its top when there are no parameters)."""
        _, y, _, row_height = self.frame(size)
        return y + (len(self.specs) + 1) * row_height + 2 * PADDING if self.specs else y

    def _control_x(self, size: tuple[int, int]) -> tuple[float, float, float]:
        """``(control left, control width, reset button left)``."""
        x, _, width, _ = self.frame(size)
        reset = x + width - PADDING - RESET_WIDTH
        left = x + PADDING + min(NAME_WIDTH, width / 3)
        return left, max(reset - 4 - left, 10.0), reset

    def hit(self, px: float, py: float, size: tuple[int, int]) -> Hit | None:
        """The control at framebuffer point ``(px, py)``, or None when it is off the panel."""
        if not self.specs:
            return None
        x, y, width, row_height = self.frame(size)
        row = int((py - y - PADDING) // row_height) - 1
        if not (x <= px <= x + width) or py < y or row >= len(self.specs):
            return None
        left, control_width, reset = self._control_x(size)
        if row < 0:
            return Hit(-1, "reset_all" if px >= x + width / 2 else "name")
        if px >= reset:
            return Hit(row, "reset")
        if px < left:
            return Hit(row, "name")
        kind = self.specs[row].kind
        if kind == "choice":
            return Hit(row, "prev" if px < left + control_width / 2 else "next")
        return Hit(row, {"bool": "toggle", "str": "text"}.get(kind, "slider"))

    def slider_fraction(self, px: float, size: tuple[int, int]) -> float:
        """Where ``px`` lies along the slider track, 0..1 (clamped)."""
        left, control_width, _ = self._control_x(size)
        return min(max((px - left) / control_width, 0.0), 1.0)

    def value_after(self, hit: Hit, px: float, size: tuple[int, int]) -> Any:
        """The value a click or drag on ``hit`` (a row's control) gives."""
        spec = self.specs[hit.row]
        current = self.values.get(spec.name, spec.default)
        if hit.part == "slider":
            return snap(spec, self.slider_fraction(px, size))
        if hit.part == "toggle":
            return not current
        if hit.part in ("prev", "next"):
            choices = list(spec.choices or ())
            index = choices.index(current) if current in choices else 0
            return choices[(index + (1 if hit.part == "next" else -1)) % len(choices)]
        return current

    # -- drawing -------------------------------------------------------------

    def quads(self, size: tuple[int, int]) -> np.ndarray:
        """Text and box quads of the whole panel (empty when there are no parameters)."""
        if not self.specs:
            return np.zeros((0, QUAD_FLOATS), dtype=np.float32)
        atlas = glyph_atlas()
        x, y, width, row_height = self.frame(size)
        height = (len(self.specs) + 1) * row_height + 2 * PADDING
        parts = [box_quad(atlas, x, y, width, height, PANEL),
                 layout_text(atlas, ["Parameters"], (x + PADDING, y + PADDING), TEXT)]
        label = "reset all"
        parts.append(layout_text(atlas, [label], (x + width - PADDING - text_width(atlas, label),
                                                  y + PADDING), LABEL_DIM))
        for row, spec in enumerate(self.specs):
            top = y + PADDING + (row + 1) * row_height
            parts.append(self._row_quads(atlas, spec, top, size))
        if self.hover is not None and self.specs[self.hover].doc:
            parts.append(_tooltip(atlas, self.specs[self.hover].doc, x + width, y + height + 4))
        return np.concatenate(parts)

    def _row_quads(self, atlas: GlyphAtlas, spec: ParamSpec, top: float,
                   size: tuple[int, int]) -> np.ndarray:
        x, _, _, row_height = self.frame(size)
        left, control_width, reset = self._control_x(size)
        value = self.values.get(spec.name, spec.default)
        name_kind = TEXT if value == spec.default else WARN_TEXT  # changed values stand out
        parts = [layout_text(atlas, [spec.name], (x + PADDING, top + 1), name_kind),
                 box_quad(atlas, reset, top + 2, RESET_WIDTH, row_height - 4, BUTTON),
                 layout_text(atlas, ["x"], (reset + 4, top + 1), LABEL_DIM)]
        box_height = row_height - 4
        if spec.kind in ("int", "float"):
            lo, hi = slider_range(spec)
            fraction = (float(value) - lo) / (hi - lo) if hi > lo else 0.0
            parts.append(box_quad(atlas, left, top + 2, control_width, box_height, TRACK))
            parts.append(box_quad(atlas, left, top + 2, control_width * min(max(fraction, 0.0), 1.0),
                                  box_height, FILL))
        elif spec.kind == "bool":
            parts.append(box_quad(atlas, left, top + 2, box_height, box_height,
                                  FILL if value else TRACK))
        elif spec.kind == "choice":
            parts.append(box_quad(atlas, left, top + 2, control_width, box_height, TRACK))
        text = {"bool": f"     {_shown(value)}", "choice": f"<  {_shown(value)}  >"}.get(
            spec.kind, _shown(value))
        parts.append(layout_text(atlas, [text], (left + 4, top + 1), TEXT))
        return np.concatenate(parts)


def _tooltip(atlas: GlyphAtlas, doc: str, right: float, top: float) -> np.ndarray:
    """A boxed line of ``doc`` whose top right is at ``(right, top)`` (kept on screen)."""
    width = text_width(atlas, doc) + 2 * PADDING
    left = max(right - width, float(MARGIN))
    return np.concatenate([
        box_quad(atlas, left, top, width, atlas.line_height + 2 * PADDING, PANEL),
        layout_text(atlas, [doc], (left + PADDING, top + PADDING), TEXT)])
