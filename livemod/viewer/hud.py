"""HUD, error overlay and help overlay as screen-text quads (GL-free).

:func:`hud_lines` says what the HUD shows of a
:class:`~livemod.viewer.view_state.ViewState`; :func:`hud_quads` lays out the
HUD panel (top left), the error panel (bottom) and the help panel (top right).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Protocol

import numpy as np

from livemod.runner.results import RunStatus

from .controls import help_lines, section_text
from .text import (
    ERROR_PANEL,
    ERROR_TEXT,
    LABEL_DIM,
    MARGIN,
    OK_TEXT,
    PADDING,
    PANEL,
    QUAD_FLOATS,
    TEXT,
    WARN_TEXT,
    GlyphAtlas,
    box_quad,
    glyph_atlas,
    layout_text,
    text_width,
    wrap_line,
)
from .view_state import ViewState

if TYPE_CHECKING:
    from livemod.runner.recording import StepRecord
    from livemod.runner.results import RunResult, ScriptError

# while a big scene's view moves (ViewState.quick)
QUICK_LINE = "view moving: edges and MSAA off until it rests"


def run_state(result: RunResult | None, waiting: bool, working: float | None = None) -> str:
    """``running... 1.5 s`` while a run works (``working`` its seconds so far),
    ``running`` while the window waits for one, or the result's status, with
    ``stale`` appended when it is stale."""
    if working is not None:
        return f"running... {working:.1f} s"
    if waiting or result is None:
        return "running"
    return f"{result.status}, stale" if result.stale else str(result.status)


class ShownSteps(Protocol):
    """What :func:`step_line` reads of a result (a ``RunResult``, or a film's shot)."""

    @property
    def steps(self) -> Sequence[StepRecord]:
        """The steps of the run."""

    @property
    def step_index(self) -> int | None:
        """The 0-based step shown, or None for the last."""


def step_line(result: ShownSteps | None, total: int = 0) -> str:
    """``step k/N: label (line L)`` of the shown step, or ``no steps``.

    A paused run has only finished the steps up to the shown one, so N is the
    larger of that and ``total``, the step count of the last complete run.
    """
    if result is None or not result.steps:
        return "no steps"
    steps = result.steps
    shown = len(steps) - 1 if result.step_index is None else min(result.step_index,
                                                                 len(steps) - 1)
    step = steps[shown]
    where = f" (line {step.line})" if step.line is not None else ""
    return f"step {shown + 1}/{max(len(steps), total)}: {step.label}{where}"


def hud_lines(state: ViewState) -> list[tuple[str, int]]:
    """The HUD's ``(text, colour kind)`` lines of ``state``."""
    lines = [(Path(state.script).name, TEXT), _state_line(state)]
    if state.background:  # a run that would not stop: it may still hold a core
        lines.append((background_line(state.background), WARN_TEXT))
    if state.viewer_error:
        lines.append((state.viewer_error, ERROR_TEXT))
    if state.empty_script:  # a save emptied it: nothing ran, the last mesh stays
        lines.append((f"{Path(state.empty_script).name} is empty: showing the last result",
                      WARN_TEXT))
    lines += _count_lines(state)
    lines.append((_run_of_steps(state) + step_line(state.result, state.total_steps), TEXT))
    lines.append((_mode_line(state), LABEL_DIM))
    if state.preview:
        lines.append((state.preview, LABEL_DIM))
    if state.quick:
        lines.append((QUICK_LINE, LABEL_DIM))
    lines += [(line, LABEL_DIM) for line in state.selection[:4]]
    lines += [(line, WARN_TEXT) for line in state.missing]
    lines += [(line, TEXT) for line in state.measures[:4]]
    lines.append((f"{state.fps:.0f} fps   H: help", LABEL_DIM))
    return lines


def background_line(run_ids: tuple[int, ...]) -> str:
    """``run 3 is still finishing in the background`` for the ids of abandoned runs
    that still work (``runs 3 and 5 are ...`` for several)."""
    if len(run_ids) == 1:
        return f"run {run_ids[0]} is still finishing in the background"
    named = ", ".join(map(str, run_ids[:-1])) + f" and {run_ids[-1]}"
    return f"runs {named} are still finishing in the background"


def _mode_line(state: ViewState) -> str:
    """Pick mode, projection, mesh or preview, the section, the playback's state
    (docs/playback.md) and the play rate."""
    style = state.style
    view = "ortho" if state.ortho else "persp"
    mode = "preview" if style.preview else "mesh"
    cut = f"  section {section_text(style.section)}" if style.section is not None else ""
    rate = f"{state.rate:g} steps/s"
    playback = f"playing {rate}" if state.playback == "playing" else f"{state.playback}, rate {rate}"
    return f"pick {state.pick_mode}  {view}  {mode}{cut}  {playback}"


def _state_line(state: ViewState) -> tuple[str, int]:
    """The run state and time, and after an error which mesh is shown (``E``)."""
    result, working = state.result, state.working
    text = run_state(result, state.waiting, working)
    colour = ERROR_TEXT if "error" in text else (WARN_TEXT if text != "ok" else OK_TEXT)
    # a run at work says its own time; the result's is of the run before
    elapsed = f"  {result.elapsed:.3f} s" if result is not None and working is None else ""
    shown = ""
    if result is not None and result.error is not None and result.partial is not None:
        shown = ("  - the failed run's mesh (E: last good)" if state.partial
                 else "  (E: the failed run's mesh)")
    return f"{text}{elapsed}{shown}", colour


def _failed_run(result: RunResult | None) -> str:
    """``failed run 3`` (``cancelled run 3``) for a result of a run that did not
    end well; "" otherwise."""
    if result is None or result.error is None:
        return ""
    failed = "cancelled" if result.status == RunStatus.CANCELLED else "failed"
    return f"{failed} run {result.run_id}"


def _run_of_steps(state: ViewState) -> str:
    """Whose steps the step line counts, when it is not plain: a failed run's."""
    result = state.result
    failed = _failed_run(result)
    return f"{failed}: " if failed and result is not None and result.steps else ""


def _run_of_mesh(state: ViewState) -> str:
    """Whose mesh the counts are of, when it is not plain: after a failed run the
    last good run's (``last good mesh (run 2): ``) or, with ``E``, the failed run's."""
    result = state.result
    failed = _failed_run(result)
    if not failed or result is None:
        return ""
    if state.arrays is result.partial:
        return f"{failed}: "
    if state.arrays is not result.arrays:
        return ""  # (not on screen: the window failed to show the result)
    return f"last good mesh (run {state.good_run}): " if state.good_run is not None \
        else "last good mesh: "


def _count_lines(state: ViewState) -> list[tuple[str, int]]:
    """V/E/F, genus and volume of the mesh on screen (which run's, when that is not
    the result's own), then the counts of the other objects drawn."""
    result, arrays, lines = state.result, state.arrays, []
    if result is not None and arrays is not None:
        v, e, f = arrays.counts
        holes = int(arrays.face_hole.sum())  # counted apart, as TopMod does
        extra = f"  holes {holes}" if holes else ""
        said = "genus ..." if state.whole is None else state.whole.text()
        hidden = "  (hidden: L lists it)" if state.current_hidden else ""
        lines.append((f"{_run_of_mesh(state)}V {v}  E {e}  F {f - holes}{extra}  {said}"
                      f"{hidden}", TEXT))
    lines += nonfinite_lines(state.nonfinite)
    # drawn beside the current object (A hides them, Tab shows one at a time, L lists them)
    others, note = state.others, state.others_note
    if others is not None or note:
        counts = "" if others is None else (
            f": V {others.counts[0]}  F {others.counts[2] - int(others.face_hole.sum())}")
        lines.append((f"other objects{': ' + note if note else ''}{counts}", LABEL_DIM))
    return lines


def nonfinite_lines(count: int) -> list[tuple[str, int]]:
    """The HUD's warning that ``count`` vertices drawn have a position that is not
    finite (NaN or inf), which the framing leaves out; none when ``count`` is 0."""
    if count <= 0:
        return []
    vertices = "vertex" if count == 1 else "vertices"
    return [(f"{count} {vertices} not finite (NaN or inf): left out of the framing",
             WARN_TEXT)]


def _panel(atlas: GlyphAtlas, lines: list[tuple[str, int]], x: float, y: float,
           panel_kind: int) -> np.ndarray:
    """A boxed block of coloured lines with its top left at ``(x, y)``."""
    width = max((text_width(atlas, text) for text, _ in lines), default=0.0)
    height = len(lines) * atlas.line_height
    parts = [box_quad(atlas, x, y, width + 2 * PADDING, height + 2 * PADDING, panel_kind)]
    for row, (text, kind) in enumerate(lines):
        parts.append(layout_text(atlas, [text], (x + PADDING, y + PADDING
                                                 + row * atlas.line_height), kind))
    return np.concatenate(parts)


def _wrapped(atlas: GlyphAtlas, lines: list[tuple[str, int]],
             width: float) -> list[tuple[str, int]]:
    """``lines`` broken to fit ``width`` pixels (each piece keeps its colour)."""
    return [(piece, kind) for text, kind in lines for piece in wrap_line(atlas, text, width)]


def error_lines(error: ScriptError, max_lines: int = 8, run_id: int | None = None,
                running: int | None = None) -> list[tuple[str, int]]:
    """The error panel: which run failed, ``file:line``, the message and the
    traceback's last lines, but those that repeat the message (a SyntaxError's
    traceback ends in it, as an exception's ends in its text).

    With ``run_id`` the head names the run; while a newer run ``running`` is at
    work, the error is the previous run's, and the head says so.
    """
    where = f"{Path(error.file).name}:{error.line}" if error.line is not None else error.file
    head = f"{error.kind} error in {where}"
    if run_id is not None and running is not None and running > run_id:
        head = f"previous run {run_id}: {head} (run {running} is running)"
    elif run_id is not None:
        head = f"run {run_id}: {head}"
    lines = [(head, ERROR_TEXT), (error.message, TEXT)]
    lines += [(line, LABEL_DIM) for line in error.trace_lines()[-max_lines:]]
    return lines


def error_panel(state: ViewState) -> list[tuple[str, int]]:
    """The error panel's lines for ``state`` (none when the result shown has no
    error), wrapped to the window's width."""
    result = state.result
    if result is None or result.error is None:
        return []
    lines = error_lines(result.error, run_id=result.run_id, running=state.running_run)
    return _wrapped(glyph_atlas(), lines, _room(state.size))


def _room(size: tuple[int, int]) -> float:
    """Pixels of text a panel as wide as a ``size`` window holds."""
    return max(size[0] - 2 * MARGIN - 2 * PADDING, 1)


def hud_quads(state: ViewState) -> np.ndarray:
    """All overlay quads of ``state`` (HUD, error panel, help) for its framebuffer
    size; long lines wrap inside the window."""
    atlas, size = glyph_atlas(), state.size
    parts = [np.zeros((0, QUAD_FLOATS), dtype=np.float32)]
    if state.hud:
        parts.append(_panel(atlas, _wrapped(atlas, hud_lines(state), _room(size)), MARGIN,
                            MARGIN, PANEL))
        lines = error_panel(state)
        if lines:
            bottom = size[1] - state.bottom  # above the step timeline
            top = bottom - MARGIN - 2 * PADDING - len(lines) * atlas.line_height
            parts.append(_panel(atlas, lines, MARGIN, top, ERROR_PANEL))
    if state.help:
        parts += _help_panels(atlas, [(line, TEXT) for line in help_lines()], size)
    return np.concatenate(parts)


def _help_panels(atlas: GlyphAtlas, lines: list[tuple[str, int]],
                 size: tuple[int, int]) -> list[np.ndarray]:
    """The help overlay at the top right, in as many columns (right to left) as the
    window's height needs."""
    rows = max(int((size[1] - 2 * MARGIN - 2 * PADDING) // atlas.line_height), 1)
    columns = [lines[start:start + rows] for start in range(0, len(lines), rows)]
    panels, right = [], float(size[0] - MARGIN)
    for column in reversed(columns):  # the first column ends up leftmost
        width = max(text_width(atlas, text) for text, _ in column) + 2 * PADDING
        right = max(right - width, float(MARGIN))
        panels.append(_panel(atlas, column, right, MARGIN, PANEL))
        right -= MARGIN
    return panels
