"""The window's frames: quick or whole pictures, their keys, scene and overlay (GL-free)."""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

from livemod.viewer.frames import REST_SECONDS, ViewMotion
from livemod.viewer.painter import FRAME_PRIMITIVES, FramePainter
from livemod.viewer.renderer import Style
from livemod.viewer.view_state import ViewState

SIZE = (64, 48)
SCREEN = SimpleNamespace(samples=0)
STYLE = Style()


class FakeRenderer:
    """A renderer that records its draws; ``big`` pictures have a quick style."""

    def __init__(self) -> None:
        self.calls: list[tuple] = []
        self.version, self.big = 1, True
        self.unfinished, self.sliced, self.hidden = False, 0, False

    def quick_style(self, style: Style) -> Style | None:
        return dataclasses.replace(style, edges=False) if self.big else None

    def draw(self, fbo: object, camera: object, style: Style, size: tuple[int, int],
             budget: int, quick: bool, behind: bool) -> None:
        self.calls.append(("draw", quick, behind, budget))

    def draw_overlay(self, fbo: object, quads: object, size: tuple[int, int]) -> None:
        self.calls.append(("overlay", quads, size))


class Overlay:
    def quads(self, state: ViewState) -> str:
        return f"quads at {state.fps} fps"


def _painter() -> tuple[FramePainter, FakeRenderer, SimpleNamespace, list[float]]:
    """A painter whose view turns when ``camera.at`` changes, on a clock that
    moves when the test says."""
    renderer, camera, now = FakeRenderer(), SimpleNamespace(at=0.0), [0.0]
    camera.pose = lambda: camera.at
    painter = FramePainter(None, renderer, camera, Overlay())  # type: ignore[arg-type]
    painter.motion = ViewMotion(lambda: now[0])
    return painter, renderer, camera, now


def _frame(painter: FramePainter, style: Style = STYLE, **state: object) -> None:
    painter.follow_view(style)
    painter.paint(SCREEN, ViewState(style=style, size=SIZE, quick=painter.quick, **state),
                  idle_ok=True)


def test_a_big_picture_is_quick_while_the_view_turns_then_whole_behind_it() -> None:
    painter, renderer, camera, now = _painter()
    painter.frames.keep_frames = False  # (no GL: whole frames are drawn on the screen)
    _frame(painter)  # the view the window opened on is at rest
    for at in (1.0, 2.0):  # turning
        camera.at, now[0] = at, now[0] + 0.01
        _frame(painter)
    now[0] += REST_SECONDS  # at rest: the whole picture, behind the quick one, then whole
    _frame(painter)
    _frame(painter)
    draws = [call[1:3] for call in renderer.calls if call[0] == "draw"]
    assert draws == [(False, False), (True, False), (True, False), (False, True),
                     (False, False)]


def test_a_small_picture_is_never_quick() -> None:
    painter, renderer, camera, now = _painter()
    painter.frames.keep_frames = False
    renderer.big = False
    for at in (0.0, 1.0, 2.0):
        camera.at, now[0] = at, now[0] + 0.01
        _frame(painter)
        assert not painter.quick
    assert {call[1:3] for call in renderer.calls if call[0] == "draw"} == {(False, False)}


def test_the_overlay_is_drawn_over_the_scene_when_the_hud_or_help_shows() -> None:
    painter, renderer, _, _ = _painter()
    painter.frames.keep_frames = False
    _frame(painter, fps=30.0)
    _frame(painter, hud=False, help=True)
    _frame(painter, hud=False)
    assert [call[0] for call in renderer.calls] == ["draw", "overlay", "draw", "overlay", "draw"]
    assert renderer.calls[1][1:] == ("quads at 30.0 fps", SIZE)
    assert renderer.calls[0][3] == FRAME_PRIMITIVES  # the first frame's slice budget


def test_a_slice_drawn_behind_the_screen_gets_no_overlay_and_is_not_shown() -> None:
    painter, renderer, _, _ = _painter()  # (a quick picture: drawn straight on the screen)
    renderer.hidden = True
    painter.paint(SCREEN, ViewState(style=STYLE, size=SIZE, quick=True), idle_ok=True)
    assert [call[0] for call in renderer.calls] == ["draw"]
    assert not painter.frames.presented  # the loop does not swap


def test_a_frame_that_differs_only_in_its_frame_rate_is_not_drawn_again() -> None:
    painter, renderer, _, _ = _painter()  # (quick pictures: drawn straight, by key)

    def paint(style: Style = STYLE, **state: object) -> None:
        painter.paint(SCREEN, ViewState(style=style, size=SIZE, quick=True, **state),
                      idle_ok=True)

    paint(fps=30.0)
    paint(fps=60.0)
    assert len(renderer.calls) == 2  # one frame: the scene and the overlay
    paint(Style(edges=False), fps=60.0)
    renderer.version += 1  # new content
    paint(fps=60.0)
    assert [call[0] for call in renderer.calls].count("draw") == 3


def test_a_picture_drawn_in_slices_draws_every_frame() -> None:
    painter, renderer, _, _ = _painter()
    renderer.unfinished = True
    for _ in range(3):
        painter.paint(SCREEN, ViewState(style=Style(), size=SIZE, quick=True), idle_ok=True)
    assert [call[0] for call in renderer.calls].count("draw") == 3
