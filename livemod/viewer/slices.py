"""Frames drawn a slice at a time, and a big scene's picture kept whole.

:class:`SlicedFrames` owns a target of its own (colour and depth renderbuffers of
the frame's size and samples), the picture in progress in it and the key of the
last whole picture. New content seen from an unchanged view is drawn into the
target over several calls when it holds more primitives than a call's budget; a
big scene (by the renderer's measure) seen again from the view of the last
picture is copied from the target instead of drawn. The renderer gives each frame
as a :class:`Frame`. Every method must be called on the thread that owns the GL
context.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import moderngl

from .framebuffers import release_framebuffer

# a pass of a frame: (primitives, draw(first, count))
Pass = tuple[int, Callable[[int, int], None]]

SLICE_SECONDS = 0.05  # what a window's slice of a picture drawn in slices should take


class SliceBudget:
    """Primitives a window's frame may draw of a picture drawn in slices: ``first``
    until a slice was measured, then as many as take about ``seconds`` at the
    rate the last slices were drawn: more where frames are cheap, fewer on a
    busy machine, so that no frame holds the window much longer than that.

    Attributes:
        primitives: the budget of the next frame (at least ``least``).
    """

    def __init__(self, first: int, seconds: float = SLICE_SECONDS,
                 least: int = 50_000) -> None:
        self.primitives = first
        self._seconds, self._least = seconds, least

    def measured(self, primitives: int, seconds: float) -> None:
        """A frame drew ``primitives`` of a picture in slices in ``seconds``
        (wall-clock, its drawing finished): the next budget is half the old one
        and half what this rate draws in the time wanted."""
        if primitives <= 0:
            return
        wanted = self._seconds * primitives / max(seconds, 1e-6)
        self.primitives = max(int(0.5 * self.primitives + 0.5 * wanted), self._least)


@dataclass(frozen=True)
class Frame:
    """One picture to draw.

    Attributes:
        key: ``(content version, view key)``: two frames of one key are the same
            picture.
        size: ``(width, height)`` pixels drawn.
        passes: the passes in order; each draws any range of its primitives.
        background: RGBA clear colour.
        sliceable: it may be drawn a slice at a time (a section's cap needs the
            whole mesh at once).
        begin: sets the scene's GL state (and draws what goes under it).
        finish: draws what goes over the passes, for a target of the size given.
        whole: draws the whole picture into the framebuffer given.
        finish_apart: drawn in slices, what goes over the passes is drawn in a
            call of its own after the last slice (the id labels, which lay out
            their quads the first time a mesh is drawn).
    """

    key: tuple
    size: tuple[int, int]
    passes: list[Pass]
    background: tuple[float, float, float, float]
    sliceable: bool
    begin: Callable[[], None]
    finish: Callable[[tuple[int, int]], None]
    whole: Callable[[moderngl.Framebuffer], None]
    finish_apart: bool = False

    @property
    def primitives(self) -> int:
        return sum(count for count, _ in self.passes)


@dataclass
class _Progress:
    """A picture drawn a slice at a time: for ``key`` (content version and view),
    into ``target``, ``done`` primitives so far; ``hidden``: shown only once whole."""

    key: tuple
    target: moderngl.Framebuffer
    done: int = 0
    hidden: bool = False


class SlicedFrames:
    """Draws frames whole, a slice at a time, or from the picture kept whole.

    Args:
        ctx: the GL context.
    """

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        # the picture drawn in slices, its target, and the key of the last whole one
        self.progress: _Progress | None = None
        self.target: moderngl.Framebuffer | None = None
        self.drawn: tuple[int, object] = (-1, None)
        self.cached: tuple | None = None  # the key of the whole picture kept in target
        self.sliced = 0  # primitives the last call drew of a picture in slices (0: none)

    @property
    def unfinished(self) -> bool:
        """A picture drawn in slices is not whole yet: draw again."""
        return self.progress is not None

    @property
    def hidden(self) -> bool:
        """The last call drew a slice of a picture drawn behind: nothing on its
        framebuffer (see :meth:`draw`'s ``behind``)."""
        return self.progress is not None and self.progress.hidden

    def draw(self, fbo: moderngl.Framebuffer, frame: Frame, budget: int | None,
             keep_over: int, behind: bool = False) -> bool:
        """Draw ``frame`` into ``fbo``: whole, or with a ``budget`` (primitives a call
        may draw) the next slice of new content seen from the last picture's view;
        False while that picture is unfinished (call again with the same frame).
        With a budget too, a frame of more than ``keep_over`` primitives seen from
        the last picture's view is drawn into the target and kept whole, and
        copied from it the next time it is drawn unchanged. With ``behind`` (and a
        budget), a frame of more than the budget is drawn in slices whatever it
        shows, and nothing is drawn on ``fbo`` until it is whole: what ``fbo``
        showed stays (the window's quick picture of a view that came to rest)."""
        view_key = frame.key[1]
        self.sliced = 0
        if behind and self._behind(fbo, frame, budget):
            assert self.progress is not None
            self.cached = None
            finished = self._draw_slice(fbo, frame, self.progress, budget or 0)
            self.cached = frame.key if finished else None
            return finished
        # kept whole for the next frames once the view rests (a turning view would
        # only pay for the copy)
        kept = (budget is not None and tuple(fbo.size) == frame.size
                and self.drawn[1] == view_key and frame.primitives > keep_over)
        if kept and self.cached == frame.key and self.target is not None \
                and self.target.samples == fbo.samples:
            self._show(fbo, self.target)
            return True
        progress = self._progress_of(fbo, frame, budget)
        if progress is not None:
            self.cached = None  # (the target is drawn over)
            finished = self._draw_slice(fbo, frame, progress, budget or 0)
            self.cached = frame.key if finished else None
            return finished
        target = self._target(frame.size, fbo.samples) if kept else fbo
        frame.whole(target)
        self.drawn, self.cached = frame.key, frame.key if kept else self.cached
        if kept:
            self._show(fbo, target)
        return True

    def _show(self, fbo: moderngl.Framebuffer, target: moderngl.Framebuffer) -> None:
        self.ctx.copy_framebuffer(fbo, target)
        fbo.use()

    def _behind(self, fbo: moderngl.Framebuffer, frame: Frame, budget: int | None) -> bool:
        """Start (or go on with) drawing ``frame`` in slices behind what ``fbo``
        shows; False when it is drawn as :meth:`draw` draws it otherwise."""
        if self.progress is not None and self.progress.key == frame.key:
            return self.progress.hidden
        if (budget is None or not frame.sliceable or tuple(fbo.size) != frame.size
                or frame.primitives <= budget):
            return False
        self.progress = _Progress(frame.key, self._target(frame.size, fbo.samples),
                                  hidden=True)
        return True

    def _progress_of(self, fbo: moderngl.Framebuffer, frame: Frame,
                     budget: int | None) -> _Progress | None:
        """The picture to go on drawing a slice at a time, or None to draw it whole:
        new content, the view of the last picture, more than ``budget`` to draw, a
        sliceable frame and a ``fbo`` of its size."""
        if self.progress is not None and self.progress.key == frame.key:
            return self.progress
        self.progress = None
        version, view_key = frame.key
        if (budget is None or not frame.sliceable or tuple(fbo.size) != frame.size
                or self.drawn[0] == version or self.drawn[1] != view_key
                or frame.primitives <= budget):
            return None
        self.progress = _Progress(frame.key, self._target(frame.size, fbo.samples))
        return self.progress

    def _draw_slice(self, fbo: moderngl.Framebuffer, frame: Frame, progress: _Progress,
                    budget: int) -> bool:
        """The next ``budget`` primitives of the frame's passes into the progress's
        target, copied to ``fbo``; True once they are all drawn (with what goes
        over them)."""
        target = progress.target
        target.use()
        if progress.done == 0:
            target.clear(*frame.background)
        total = frame.primitives
        if progress.done < total:
            frame.begin()
        start, stop, offset = progress.done, progress.done + budget, 0
        for count, draw in frame.passes:
            first, last = max(start - offset, 0), min(stop - offset, count)
            if first < last:
                draw(first, last - first)
            offset += count
        self.sliced = min(stop, offset) - progress.done
        progress.done = min(stop, offset)
        finished = progress.done >= offset and not (frame.finish_apart and self.sliced)
        if finished:
            frame.finish(target.size)
            self.drawn, self.progress = progress.key, None
        if finished or not progress.hidden:
            self._show(fbo, target)
        return finished

    def _target(self, size: tuple[int, int], samples: int) -> moderngl.Framebuffer:
        """A framebuffer of ``size`` and ``samples`` to draw a picture in slices or
        keep it whole (kept for the next picture of that size)."""
        if self.target is not None and self.target.size == size \
                and self.target.samples == samples:
            return self.target
        if self.target is not None:
            release_framebuffer(self.target)
        self.cached = None
        self.target = self.ctx.framebuffer(
            [self.ctx.renderbuffer(size, 4, samples=samples)],
            self.ctx.depth_renderbuffer(size, samples=samples))
        return self.target

    def release(self) -> None:
        """Free the target (the next picture that needs it makes it again)."""
        if self.target is not None:
            release_framebuffer(self.target)
        self.target = self.progress = None
        self.cached = None
