"""The step timeline (GL-free): where a click lands, what it draws, which step a
result shows."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from livemod.viewer.timeline import Timeline, shown_step

SIZE = (800, 600)


def _bar_x(timeline: Timeline, fraction: float) -> float:
    """Framebuffer x at ``fraction`` along the track (as the panel lays it out)."""
    x, _, width, _ = timeline.frame(SIZE)
    return x + 6 + fraction * (width - 12)


def test_clicks_map_to_steps_and_clamp_at_the_ends() -> None:
    timeline = Timeline()
    assert timeline.step_at(_bar_x(timeline, 0.0), SIZE, 10) == 0
    assert timeline.step_at(_bar_x(timeline, 0.35), SIZE, 10) == 3
    assert timeline.step_at(_bar_x(timeline, 0.999), SIZE, 10) == 9
    assert timeline.step_at(-50, SIZE, 10) == 0 and timeline.step_at(5000, SIZE, 10) == 9


def test_the_panel_lies_along_the_bottom() -> None:
    timeline = Timeline()
    x, y, width, height = timeline.frame(SIZE)
    assert y + height == SIZE[1] - 8 and x == 8 and width == SIZE[0] - 16
    assert timeline.hit(400, y + height / 2, SIZE) and not timeline.hit(400, y - 2, SIZE)


def test_the_fill_reaches_the_step_shown() -> None:
    timeline = Timeline()
    left = _bar_x(timeline, 0.0)
    track_width = _bar_x(timeline, 1.0) - left

    def fill_width(shown: int, total: int) -> float:
        quads = timeline.quads(SIZE, shown, total)
        fills = quads[quads[:, 11] == 14]  # the fill's palette slot
        assert len(fills) == 1
        return float(fills[0, 5])

    assert fill_width(0, 4) == pytest.approx(track_width / 4)
    assert fill_width(3, 4) == pytest.approx(track_width)
    assert len(timeline.quads(SIZE, 0, 1)) == 0  # one step: nothing to scrub
    assert len(timeline.quads(SIZE, None, 5)) == 0


def test_shown_step_of_results() -> None:
    steps = ("a", "b", "c")
    assert shown_step(SimpleNamespace(steps=steps, step_index=None), 3) == 2
    assert shown_step(SimpleNamespace(steps=steps, step_index=1), 3) == 1
    # a paused run has only the steps up to the shown one; the total is the last run's
    assert shown_step(SimpleNamespace(steps=steps[:2], step_index=1), 3) == 1
    assert shown_step(SimpleNamespace(steps=(), step_index=None), 0) is None
    assert shown_step(None, 0) is None


def test_a_press_on_the_timeline_handle_stays_on_its_step() -> None:
    """The handle of step k is drawn at the end of the fill, (k + 1) / total of the
    bar: pressing it (to drag it) must not jump to step k + 1."""
    timeline, size, total = Timeline(), (800, 600), 10
    for shown in range(total):
        quads = timeline.quads(size, shown, total)
        handle = quads[-1]  # the handle is the last quad
        centre = float(handle[0] + handle[5] / 2)  # x + width / 2
        assert timeline.step_at(centre, size, total) == shown
