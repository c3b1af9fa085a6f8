"""The parameters panel of the live window, driven through its input handlers over EGL."""

from __future__ import annotations

import io
from collections.abc import Iterator
from pathlib import Path

import pytest

from livemod.dlfl.params import make_spec
from livemod.viewer.params_panel import ParameterPanel, slider_range, snap
from livemod.viewer.window import LiveViewer, ViewOptions, close_viewer, create_viewer

from .test_viewer_window import _has_run, _wait, xvfb_display  # noqa: F401  (a fixture)
from .viewer_support import run_probe

POLYGON = """
import math
from livemod.dlfl import param, createFace, createVertex
sides = param("sides", 4, min=3, max=12, doc="corners of the polygon")
radius = param("radius", 1.0, min=0.5, max=3.0)
apex = param("apex", False, doc="add a lone vertex above")
kind = param("kind", "flat", choices=["flat", "star"])
createFace([(radius * math.cos(2 * math.pi * i / sides),
             radius * math.sin(2 * math.pi * i / sides), 0.0) for i in range(sides)])
if apex:
    createVertex((0.0, 0.0, 1.0))
"""


@pytest.fixture
def window(tmp_path: Path) -> Iterator[tuple[LiveViewer, io.StringIO]]:
    script = tmp_path / "polygon.py"
    script.write_text(POLYGON)
    echo = io.StringIO()
    viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(400, 300),
                                       samples=0, vsync=False, echo=echo))
    yield viewer, echo
    close_viewer(viewer)


def _row_y(viewer: LiveViewer, row: int) -> float:
    _, top, _, row_height = viewer.parameters.panel.frame(viewer.wnd.fbo.size)
    return top + 6 + (row + 1.5) * row_height


def _slider_x(viewer: LiveViewer, fraction: float) -> float:
    left, width, _ = viewer.parameters.panel._control_x(viewer.wnd.fbo.size)
    return left + fraction * width


def _vertices(viewer: LiveViewer) -> int:
    return viewer.result.arrays.counts[0]


def test_a_dragged_slider_reruns_once_per_settled_value(window) -> None:
    viewer, _ = window
    _wait(viewer, _has_run(1))
    assert [s.name for s in viewer.parameters.panel.specs] == ["sides", "radius", "apex", "kind"]
    assert _vertices(viewer) == 4
    y = _row_y(viewer, 0)
    viewer.on_mouse_press_event(_slider_x(viewer, 0.0), y, 1)
    for fraction in (0.2, 0.4, 0.6, 1.0):          # a quick drag: nothing re-runs yet
        viewer.on_mouse_drag_event(_slider_x(viewer, fraction), y, 5, 0)
    assert viewer.parameters.panel.values["sides"] == 12
    assert viewer.parameters.runs_asked == 0
    _wait(viewer, lambda v: v.parameters.runs_asked == 1)   # still held: the value settled
    _wait(viewer, lambda v: not v.waiting and v.result.values == (("sides", 12),))
    assert _vertices(viewer) == 12
    viewer.on_mouse_drag_event(_slider_x(viewer, 0.56), y, -5, 0)
    viewer.on_mouse_release_event(_slider_x(viewer, 0.56), y, 1)  # release: sent at once
    assert viewer.parameters.runs_asked == 2
    _wait(viewer, lambda v: not v.waiting and v.result.values == (("sides", 8),))
    assert _vertices(viewer) == 8 and viewer.result.run_id <= 3
    assert viewer.selection.is_empty()                  # the drag never picked or orbited


def test_checkbox_choice_reset_hover_and_copy(window) -> None:
    viewer, echo = window
    _wait(viewer, _has_run(1))
    size = viewer.wnd.fbo.size
    viewer.on_mouse_press_event(_slider_x(viewer, 0.1), _row_y(viewer, 2), 1)   # apex on
    viewer.on_mouse_release_event(_slider_x(viewer, 0.1), _row_y(viewer, 2), 1)
    viewer.on_mouse_press_event(_slider_x(viewer, 0.9), _row_y(viewer, 3), 1)   # kind >
    _wait(viewer, lambda v: not v.waiting and dict(v.result.values).get("kind") == "star")
    assert dict(viewer.result.values) == {"apex": True, "kind": "star"}
    assert _vertices(viewer) == 5
    viewer.handle_key("C", ctrl=True)
    assert "apex = param('apex', True, doc='add a lone vertex above')" in echo.getvalue()
    assert "kind = param('kind', 'star', choices=['flat', 'star'])" in echo.getvalue()
    plain = len(viewer.parameters.panel.quads(size))
    viewer.on_mouse_position_event(_slider_x(viewer, 0.5), _row_y(viewer, 0), 0, 0)
    assert viewer.parameters.panel.hover == 0 and len(viewer.parameters.panel.quads(size)) > plain   # the doc
    _, reset_x = viewer.parameters.panel._control_x(size)[1:]
    viewer.on_mouse_press_event(reset_x + 4, _row_y(viewer, 2), 1)              # reset apex
    _wait(viewer, lambda v: not v.waiting and v.result.values == (("kind", "star"),))
    x, top, width, _ = viewer.parameters.panel.frame(size)
    viewer.on_mouse_press_event(x + width - 10, top + 8, 1)                     # reset all
    _wait(viewer, lambda v: not v.waiting and v.result.values == ())
    assert _vertices(viewer) == 4 and viewer.parameters.panel.values["kind"] == "flat"


def test_slider_values_snap_to_the_declaration() -> None:
    from livemod.dlfl.params import make_spec

    steps = make_spec("t", 0.5, min=0.0, max=1.0, step=0.25)
    assert [snap(steps, f) for f in (0.0, 0.3, 0.9, 2.0)] == [0.0, 0.25, 1.0, 1.0]
    count = make_spec("n", 3, min=1)
    assert slider_range(count) == (1.0, 6.0) and snap(count, 0.6) == 4
    open_float = make_spec("x", -2.0)
    assert slider_range(open_float) == (-4.0, 0.0)
    panel = ParameterPanel()
    panel.sync((steps, count), {"n": 5})
    assert panel.values == {"t": 0.5, "n": 5}
    assert panel.python_lines()[1] == "n = param('n', 5, min=1)"
    assert panel.hit(0, 0, (400, 300)) is None


def test_frames_keep_coming_while_the_panel_reruns(window) -> None:
    viewer, _ = window
    _wait(viewer, _has_run(1))
    y = _row_y(viewer, 1)
    viewer.on_mouse_press_event(_slider_x(viewer, 0.0), y, 1)
    for step in range(20):                         # a long drag, a frame between moves
        viewer.on_mouse_drag_event(_slider_x(viewer, step / 19), y, 2, 0)
        _wait(viewer, lambda v: True)
    viewer.on_mouse_release_event(_slider_x(viewer, 1.0), y, 1)
    _wait(viewer, lambda v: not v.waiting and v.result.values == (("radius", 3.0),))
    assert viewer.parameters.runs_asked <= 20


def _glfw_clipboard_probe(script_path: str) -> None:
    """In a fresh process with a real glfw window: Ctrl+C puts the param() lines on
    the clipboard. Raises on failure."""
    import glfw

    viewer = create_viewer(ViewOptions(script_path, backend="glfw", size=(320, 240),
                                       samples=0, vsync=False, echo=io.StringIO()))
    try:
        _wait(viewer, _has_run(1))
        viewer.parameters.set("sides", 6)
        viewer.handle_key("C", ctrl=True)
        copied = glfw.get_clipboard_string(viewer.wnd._window)
        text = copied.decode() if isinstance(copied, bytes) else str(copied)
        assert "sides = param('sides', 6, min=3, max=12, doc='corners of the polygon')" in text
    finally:
        close_viewer(viewer)
    print("clipboard ok")


@pytest.mark.usefixtures("xvfb_display")
def test_copy_key_fills_the_glfw_clipboard(tmp_path: Path) -> None:
    script = tmp_path / "polygon.py"
    script.write_text(POLYGON)
    said = run_probe("test_viewer_params_panel", "_glfw_clipboard_probe", script)
    assert "clipboard ok" in said


def _values(spec) -> list:
    return sorted({snap(spec, k / 2000) for k in range(2001)})



def test_a_stepped_slider_reaches_its_max_and_stays_on_the_grid() -> None:
    spec = make_spec("t", 0.0, min=0.0, max=1.0, step=0.3)
    assert _values(spec) == [0.0, 0.3, 0.6, 0.9, 1.0]
    assert snap(spec, 1.0) == 1.0 and snap(spec, 0.93) == 0.9 and snap(spec, 0.97) == 1.0
    spec = make_spec("t", 0.0, min=0.0, max=1.0, step=0.4)
    assert _values(spec) == [0.0, 0.4, 0.8, 1.0] and snap(spec, 1.0) == 1.0
    spec = make_spec("n", 1, min=1, max=10, step=4)
    assert _values(spec) == [1, 5, 9, 10]
    spec = make_spec("t", 0.0, min=0.0, max=1.0, step=0.1)  # a step that divides it
    assert _values(spec) == [round(0.1 * k, 12) for k in range(11)]



def test_an_open_ended_stepped_slider_ends_on_its_grid() -> None:
    """With no max the slider's right end is where drawing stops, not a value."""
    spec = make_spec("t", 0.5, min=0.0, step=0.2)  # the slider spans 0 .. 1.5
    assert _values(spec) == [round(0.2 * k, 12) for k in range(8)]
