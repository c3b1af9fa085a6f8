"""Putting frames on the screen (over EGL): the kept frame is copied, not drawn again,
and the frame rate counts the frames drawn."""

from __future__ import annotations

import io
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from livemod.viewer.window import LiveViewer, ViewOptions, close_viewer, create_viewer, run_frames

from .viewer_support import frames_until


@pytest.fixture
def viewer(tmp_path: Path) -> Iterator[LiveViewer]:
    """A headless window (320 x 240) that has shown a cube."""
    script = tmp_path / "model.py"
    script.write_text("load('cube')\n")
    window = create_viewer(ViewOptions(str(script), backend="headless", size=(320, 240),
                                       samples=0, vsync=False, echo=io.StringIO()))
    frames_until(window, lambda v: v.result is not None and not v.waiting)
    yield window
    close_viewer(window)


def _count_draws(viewer: LiveViewer) -> list[int]:
    """Count the renderer's draws from now on (the list's one item)."""
    drawn, draw = [0], viewer.renderer.draw

    def counted(*args: Any, **kwargs: Any) -> None:
        drawn[0] += 1
        draw(*args, **kwargs)

    viewer.renderer.draw = counted  # type: ignore[method-assign]
    return drawn



def _screen(viewer: LiveViewer) -> np.ndarray:
    raw = viewer.wnd.fbo.read(components=3, alignment=1)
    width, height = viewer.wnd.fbo.size
    return np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3)



def test_an_unchanged_frame_is_copied_not_drawn_again(viewer: LiveViewer) -> None:
    viewer.handle_key("U")  # no HUD: its frame rate would change the picture
    run_frames(viewer, 2)
    drawn = _count_draws(viewer)
    kept = _screen(viewer).copy()
    run_frames(viewer, 5)
    assert drawn[0] == 0 and np.array_equal(_screen(viewer), kept)
    assert not viewer.painter.frames.presented  # nothing new: the loop need not swap
    viewer.painter.frames.presented_at -= 1.0  # half a second later it is put up again
    run_frames(viewer, 1)
    assert viewer.painter.frames.presented and drawn[0] == 0  # copied, not drawn
    viewer.painter.frames.keep_frames = False  # drawn directly, the same picture
    run_frames(viewer, 1)
    assert drawn[0] == 1 and np.array_equal(_screen(viewer), kept)
    viewer.painter.frames.keep_frames = True
    for change in (lambda: viewer.camera.orbit(10.0, 0.0), lambda: viewer.handle_key("W"),
                   lambda: viewer.click(160, 120)):
        before = drawn[0]
        change()
        run_frames(viewer, 3)
        assert drawn[0] == before + 1  # drawn once for the change, then copied
    assert not np.array_equal(_screen(viewer), kept)



def test_a_screen_that_refuses_the_copy_is_drawn_every_frame(viewer: LiveViewer) -> None:

    class RefusingContext:
        """The window's context, but every copy to the screen fails."""

        def __init__(self, ctx: Any) -> None:
            self._ctx, self.copies = ctx, 0

        def copy_framebuffer(self, dst: Any, src: Any) -> None:
            self.copies += 1

        @property
        def error(self) -> str:
            return "GL_INVALID_OPERATION" if self.copies else "GL_NO_ERROR"

        def __getattr__(self, name: str) -> Any:
            return getattr(self._ctx, name)

    viewer.painter.frames.kept = None  # the next frame makes a new target, and checks the copy
    viewer.painter.frames.ctx = RefusingContext(viewer.painter.frames.ctx)
    drawn = _count_draws(viewer)
    run_frames(viewer, 3)
    assert not viewer.painter.frames.keep_frames
    assert drawn[0] == 1 + 3  # into the kept frame once, then straight to the screen


def test_the_frame_rate_counts_only_frames_drawn(viewer: LiveViewer) -> None:
    run_frames(viewer, 3)
    counted = len(viewer.painter.frames.frame_times)
    run_frames(viewer, 20)  # nothing changes: no frame is drawn
    assert not viewer.painter.frames.presented
    assert len(viewer.painter.frames.frame_times) == counted
    for _ in range(5):  # each turn of the view draws a frame
        viewer.camera.orbit(5.0, 0.0)
        run_frames(viewer, 1)
    run_frames(viewer, 1)  # (a drawn frame's time ends where the next turn starts)
    assert len(viewer.painter.frames.frame_times) == counted + 5


def test_the_view_moves_until_its_pose_rests_for_rest_seconds() -> None:
    from livemod.viewer.frames import REST_SECONDS, ViewMotion

    now = [10.0]
    motion = ViewMotion(lambda: now[0])
    assert not motion.moving("a")  # the view a window opens on is at rest
    assert not motion.moving("a")
    now[0] += 0.01
    assert motion.moving("b")
    now[0] += REST_SECONDS * 0.9  # unchanged, but not for long enough yet
    assert motion.moving("b")
    now[0] += REST_SECONDS * 0.2
    assert not motion.moving("b")
    assert motion.moving("c")


def test_a_moving_view_of_a_big_scene_is_drawn_quick_then_whole(
        viewer: LiveViewer, monkeypatch: pytest.MonkeyPatch) -> None:
    import livemod.viewer.renderer as renderer
    from livemod.viewer.frames import REST_SECONDS, ViewMotion
    from livemod.viewer.hud import QUICK_LINE, hud_lines

    monkeypatch.setattr(renderer, "QUICK_PRIMITIVES", 0)  # the cube counts as big
    now = [0.0]
    viewer.painter.motion = ViewMotion(lambda: now[0])
    run_frames(viewer, 2)
    assert not viewer.view_state().quick
    drawn = _count_draws(viewer)
    viewer.camera.orbit(20.0, 0.0)
    run_frames(viewer, 1)
    state = viewer.view_state()
    assert state.quick and QUICK_LINE in [line for line, _ in hud_lines(state)]
    assert drawn[0] == 1 and viewer.painter.frames.direct is not None  # on the screen, no copy
    quick = _screen(viewer).copy()
    run_frames(viewer, 3)  # the view rests, not yet for long: not drawn again
    assert drawn[0] == 1 and np.array_equal(_screen(viewer), quick)
    now[0] += REST_SECONDS
    run_frames(viewer, 1)  # at rest: the whole picture, edges and all
    assert drawn[0] == 2 and not viewer.view_state().quick
    whole = _screen(viewer).copy()
    edges = np.all(whole < 40, axis=2) & ~np.all(quick < 40, axis=2)  # the wire's dark
    assert edges.sum() > 20
    run_frames(viewer, 1)  # then kept (copied from the renderer's kept picture)
    assert viewer.painter.frames.direct is None and viewer.painter.frames.kept is not None
    assert np.array_equal(_screen(viewer), whole)


def test_the_whole_picture_of_a_view_at_rest_is_drawn_behind_the_quick_one(
        viewer: LiveViewer, monkeypatch: pytest.MonkeyPatch) -> None:
    import livemod.viewer.renderer as renderer
    from livemod.viewer.frames import REST_SECONDS, ViewMotion
    from livemod.viewer.slices import SliceBudget

    monkeypatch.setattr(renderer, "QUICK_PRIMITIVES", 0)
    viewer.painter.slice_budget = SliceBudget(4, seconds=0.0, least=4)  # 4 primitives a frame
    now = [0.0]
    viewer.painter.motion = ViewMotion(lambda: now[0])
    run_frames(viewer, 2)
    while viewer.renderer.unfinished:
        run_frames(viewer, 1)
    viewer.camera.orbit(20.0, 0.0)
    run_frames(viewer, 1)
    quick = _screen(viewer).copy()
    now[0] += REST_SECONDS
    behind = 0
    run_frames(viewer, 1)
    while viewer.renderer.unfinished:  # slices drawn behind: the quick one stays up
        assert viewer.renderer.hidden and not viewer.painter.frames.presented
        assert np.array_equal(_screen(viewer), quick)
        behind += 1
        run_frames(viewer, 1)
    assert behind >= 2 and viewer.painter.frames.presented
    whole = _screen(viewer)
    assert (np.all(whole < 40, axis=2) & ~np.all(quick < 40, axis=2)).sum() > 20


def test_a_small_scene_is_drawn_whole_while_the_view_moves(viewer: LiveViewer) -> None:
    run_frames(viewer, 2)
    viewer.camera.orbit(20.0, 0.0)
    run_frames(viewer, 1)
    assert not viewer.view_state().quick and viewer.painter.frames.direct is None
