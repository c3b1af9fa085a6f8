"""Putting frames on the screen: the kept frame and the frame rate.

A frame that would look like the last one is not drawn again: :class:`Frames`
keeps the last frame in a framebuffer of its own with the key it was drawn at,
and copies it to the screen; an unchanged picture is not even copied but every
:data:`REPRESENT` seconds, so that an idle window costs almost nothing. The frame
rate counts the frames drawn only. :class:`ViewMotion` tells a moving view from
one at rest, for the quick pictures of a big scene while it moves.
"""

from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable
from typing import Any

from .renderer import release_framebuffer

# an unchanged picture is put on the screen again this often (repaints a window that
# was covered)
REPRESENT = 0.5
FPS_EVERY = 0.5  # seconds between updates of the frame rate shown
# the view counts as moving this long after its pose last changed (mouse events
# do not come every frame: a drag must not flicker between quick and whole pictures)
REST_SECONDS = 0.25


class ViewMotion:
    """Whether the view moves: its pose changed less than :data:`REST_SECONDS` ago.

    Args:
        clock: seconds, monotonic (for tests).
    """

    def __init__(self, clock: Callable[[], float] = time.perf_counter) -> None:
        self._clock = clock
        self._pose: object = None
        self._changed_at = -float("inf")

    def moving(self, pose: object) -> bool:
        """Give the view's ``pose`` this frame; True while it moves. The first pose
        given is the view at rest (a window opens on a still view)."""
        now = self._clock()
        if self._pose is not None and pose != self._pose:
            self._changed_at = now
        self._pose = pose
        return now - self._changed_at < REST_SECONDS


class Frames:
    """The kept frame and the frame rate of one window.

    Args:
        ctx: the window's GL context.

    Attributes:
        ctx: the GL context the frames are copied in.
        kept: ``(key, framebuffer)`` of the last frame drawn, or None.
        keep_frames: copy the kept frame (False: draw every frame, for a screen
            that refuses the copy).
        presented: the last turn put a picture on the screen (else the loop need
            not swap).
        presented_at: when a picture was last put on the screen.
        direct: the key of the picture drawn straight on the screen last (see
            :meth:`present`'s ``keep``), or None.
        frame_times: seconds of the last turns that drew a frame.
        fps: the frame rate shown.
    """

    def __init__(self, ctx: Any) -> None:
        self.ctx = ctx
        self.kept: tuple[object, Any] | None = None
        self.keep_frames = True
        self.presented = True
        self.presented_at = 0.0
        self.direct: object = None
        self.frame_times: deque[float] = deque(maxlen=120)
        self.fps = 0.0
        self._fps_at = 0.0
        self._drew = False  # this loop turn drew a frame
        self._turn_started = time.perf_counter()

    def begin_turn(self) -> None:
        """A turn of the loop starts: a turn that drew a frame counts from its start
        to this one's (results taken, the draw, the swap); the rate shown is
        updated every :data:`FPS_EVERY` s. Turns that drew nothing (a copy, or a
        wait for input) do not count, so an idle window keeps its last rate."""
        now = time.perf_counter()
        if self._drew:
            self.frame_times.append(now - self._turn_started)
        self._drew, self._turn_started = False, now
        if now - self._fps_at > FPS_EVERY and self.frame_times:
            self.fps = round(len(self.frame_times) / max(sum(self.frame_times), 1e-9))
            self._fps_at = now

    def present(self, screen: Any, size: tuple[int, int], key: object,
                draw: Callable[[Any], object], idle_ok: bool, keep: bool = True) -> None:
        """Put the frame of ``key`` on ``screen`` (of ``size`` pixels: not
        ``screen.size``, which moderngl keeps at the size the window opened
        with): copied from the kept frame, drawn
        into it first (``draw(framebuffer)``) when the key changed, or drawn
        straight on the screen when copies fail. With ``idle_ok`` an unchanged
        picture is not copied at all but every :data:`REPRESENT` s (other backends
        take their input events while swapping: they swap every frame). Without
        ``keep`` (a quick picture of a moving view, which the next frame replaces)
        the frame is drawn straight on the screen: the copy is saved; a ``draw``
        that returns False drew nothing there, and the screen is not put up."""
        if not keep and self.keep_frames:
            self._present_direct(screen, key, draw, idle_ok)
            return
        self.direct = None
        if not self.keep_frames:
            self._draw(draw, screen)
            self.presented = True
            return
        now, kept = time.perf_counter(), self.kept
        changed = kept is None or kept[0] != key
        self.presented = changed or not idle_ok or now - self.presented_at > REPRESENT
        if not self.presented:
            return
        self.presented_at = now
        target, fresh = (kept[1], False) if not changed and kept is not None \
            else self._redraw(screen, size, key, draw)
        self._copy(screen, target, fresh, draw)

    def _present_direct(self, screen: Any, key: object, draw: Callable[[Any], object],
                        idle_ok: bool) -> None:
        """Draw the frame of ``key`` straight on ``screen``, unless it is the one
        drawn there last and the screen need not be shown again yet."""
        now = time.perf_counter()
        self.presented = self.direct != key or not idle_ok or now - self.presented_at > REPRESENT
        if not self.presented:
            return
        self.presented_at, self.direct = now, key
        if self.kept is not None:
            self.kept = (None, self.kept[1])  # (drawn over: the kept frame is not on screen)
        self.presented = self._draw(draw, screen) is not False

    def _redraw(self, screen: Any, size: tuple[int, int], key: object,
                draw: Callable[[Any], object]) -> tuple[Any, bool]:
        """Draw the frame of ``key`` into the kept framebuffer; ``(it, made anew)``."""
        target = self._target(screen, size)
        fresh = self.kept is None or target is not self.kept[1]
        self.kept = (key, target)
        self._draw(draw, target)
        return target, fresh

    def _copy(self, screen: Any, target: Any, fresh: bool, draw: Callable[[Any], object]) -> None:
        """Copy ``target`` to ``screen``; the first copy from a new framebuffer is
        checked: a screen whose MSAA moderngl misreports refuses it, and is drawn
        every frame from then on."""
        if fresh:
            self.ctx.error  # noqa: B018  (reading it clears an older error)
        self.ctx.copy_framebuffer(screen, target)
        screen.use()
        if fresh and self.ctx.error != "GL_NO_ERROR":
            self.keep_frames = False
            self._draw(draw, screen)

    def _draw(self, draw: Callable[[Any], object], fbo: Any) -> object:
        self._drew = True
        return draw(fbo)

    def _target(self, screen: Any, size: tuple[int, int]) -> Any:
        """A framebuffer of ``size`` with ``screen``'s MSAA to keep the last frame in;
        the old one is released when the size changed."""
        old = None if self.kept is None else self.kept[1]
        if old is not None and old.size == size and old.samples == screen.samples:
            return old
        if old is not None:
            release_framebuffer(old)
        return self.ctx.framebuffer(
            [self.ctx.renderbuffer(size, 4, samples=screen.samples)],
            self.ctx.depth_renderbuffer(size, samples=screen.samples))

    def release(self) -> None:
        """Free the kept framebuffer (calling it again does nothing)."""
        if self.kept is not None:
            release_framebuffer(self.kept[1])
            self.kept = None
