"""The window's frames: which picture each one is, and painting it.

:class:`FramePainter` decides the picture of each frame of the live window: a big
scene is drawn quick (no edges, no multisampling: see
:meth:`~livemod.viewer.renderer.Renderer.quick_style`) while the view moves, and
whole once it rests, in slices drawn behind the last quick picture, which stays on
the screen meanwhile; new content is drawn in slices as many a frame as
:class:`~livemod.viewer.slices.SliceBudget` allows. It keys each frame by what it
shows (the content's version, the camera's pose, the
:class:`~livemod.viewer.view_state.ViewState` but for the frame rate, the size),
so :class:`~livemod.viewer.frames.Frames` copies or skips a frame that would look
like the last, and paints the scene and the overlay into the target ``Frames``
gives. Every method must be called on the thread that owns the GL context.
"""

from __future__ import annotations

import time
from functools import partial
from typing import Any

import moderngl

from .camera import Camera
from .frames import Frames, ViewMotion
from .overlay import Overlay
from .renderer import Renderer, Style
from .slices import SliceBudget
from .view_state import ViewState

# primitives the first frame draws of new content (software GL: some 50 ms at 4x MSAA);
# the rest follows in the next frames, as many a frame as take SLICE_SECONDS (see
# Renderer.draw and SliceBudget)
FRAME_PRIMITIVES = 150_000


class FramePainter:
    """Paints the frames of ``renderer``'s scene seen by ``camera``, with
    ``overlay`` over it, in ``ctx``.

    Attributes:
        frames: the kept frame and the frame rate.
        motion: whether the view moves.
        slice_budget: primitives a frame may draw of a picture drawn in slices.
        quick: this frame draws the quick picture (see :meth:`follow_view`).
    """

    def __init__(self, ctx: moderngl.Context, renderer: Renderer, camera: Camera,
                 overlay: Overlay) -> None:
        self.frames = Frames(ctx)
        self.motion = ViewMotion()
        self.slice_budget = SliceBudget(FRAME_PRIMITIVES)
        self.quick = False
        self._behind = False  # this frame draws the whole picture behind the quick one
        self._slices = 0  # counts the frames of pictures drawn in slices
        self._renderer, self._camera, self._overlay = renderer, camera, overlay

    def follow_view(self, style: Style) -> None:
        """Choose this frame's picture of ``style``: the quick one while the view
        moves and the picture is big, else the whole one (behind the quick one
        on screen, the first frame the view rests)."""
        was_quick = self.quick
        self.quick = self.motion.moving(self._camera.pose()) and \
            self._renderer.quick_style(style) is not None
        self._behind = was_quick and not self.quick

    def paint(self, screen: Any, state: ViewState, idle_ok: bool) -> None:
        """Put the frame of ``state`` (its ``quick`` from :meth:`follow_view`) on
        ``screen``: drawn, copied from the kept frame, or neither when nothing
        changed and ``idle_ok`` (see :meth:`Frames.present`)."""
        overlay = state.without_fps() if state.hud or state.help else None
        sliced = self._renderer.unfinished
        if sliced:  # a picture drawn in slices: draw its next one
            self._slices += 1
        key = (self._renderer.version, self._camera.pose(), state.style, overlay, state.size,
               screen.samples, self._slices)
        self.frames.present(screen, state.size, key, partial(self._draw, state=state),
                            idle_ok=idle_ok, keep=not (state.quick or sliced or self._behind))

    def _draw(self, fbo: Any, state: ViewState) -> bool:
        """Draw the scene and the overlay of ``state`` into ``fbo`` (the screen or
        the kept frame, both of the state's size); False when it drew nothing on
        it (a slice of a picture drawn behind the one on screen)."""
        started = time.perf_counter()
        self._renderer.draw(fbo, self._camera, state.style, state.size,
                            budget=self.slice_budget.primitives, quick=state.quick,
                            behind=self._behind)
        self.slice_budget.measured(self._renderer.sliced, time.perf_counter() - started)
        if self._renderer.hidden:
            return False
        if state.hud or state.help:
            self._renderer.draw_overlay(fbo, self._overlay.quads(state), state.size)
        return True
