"""The live window over the real runner: headless (EGL) and a real glfw window under Xvfb."""

from __future__ import annotations

import contextlib
import io
import os
import select
import shutil
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Any

import moderngl
import numpy as np
import pytest
from PIL import Image

from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import cube, tetrahedron
from livemod.viewer.hud import hud_lines
from livemod.viewer.window import (
    LiveViewer,
    ViewOptions,
    close_viewer,
    create_viewer,
    run_frames,
)

from .viewer_support import cube_with, frames_until, gl_objects, run_probe

CUBE = """
from livemod.dlfl import from_polygons, current_scene, faces, translate
P = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
     (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
F = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3), (7, 6, 5, 4)]
current_scene().add(from_polygons([(x * {scale}, y * {scale}, z) for x, y, z in P], F))
if faces(True):   # a picked face moves the cube: the selection reached the run
    translate(2.0, 0.0, 0.0)
"""

SPINNING = """
while True:   # pure Python on the GIL until the run is cancelled
    total = sum(i * i for i in range(2000))
"""


def _wait(viewer: LiveViewer, done: Callable[[LiveViewer], bool], timeout: float = 20.0,
          nap: float = 0.005) -> None:
    """Draw frames until ``done`` (napping between frames so the worker gets a core)."""
    deadline = time.monotonic() + timeout

    def until(v: LiveViewer) -> bool:
        time.sleep(nap)
        return done(v) or time.monotonic() > deadline

    run_frames(viewer, until=until)
    assert done(viewer), "timed out waiting for the viewer"


def _measured(viewer: LiveViewer) -> bool:
    """The mesh shown has its genus and volume (a large one is measured off the main
    thread)."""
    return viewer.whole.facts() is not None


def _has_run(run_id: int) -> Callable[[LiveViewer], bool]:
    return lambda v: v.result is not None and v.result.run_id >= run_id and not v.waiting


@contextlib.contextmanager
def _opened(script: Path, size: tuple[int, int], **options: Any) -> Iterator[LiveViewer]:
    """A headless window on ``script`` (no MSAA, no vsync, ``echo`` a StringIO unless
    given) that has shown its first run; closed on the way out."""
    options.setdefault("echo", io.StringIO())
    viewer = create_viewer(ViewOptions(str(script), backend="headless", size=size, samples=0,
                                       vsync=False, **options))
    try:
        _wait(viewer, _has_run(1))
        yield viewer
    finally:
        close_viewer(viewer)


def _background_differs(image: np.ndarray) -> np.ndarray:
    """``(H, W)`` bool: the pixels that are not the dark background."""
    background = np.array([round(0.16 * 255), round(0.17 * 255), round(0.19 * 255)])
    return np.abs(image.astype(int) - background).sum(axis=2) > 6


def _hud_text(viewer: LiveViewer) -> str:
    return "\n".join(line for line, _ in hud_lines(viewer.view_state()))


@pytest.fixture
def headless(tmp_path: Path) -> Iterator[tuple[LiveViewer, Path, io.StringIO]]:
    script = tmp_path / "model.py"
    script.write_text(CUBE.format(scale=1.0))
    echo = io.StringIO()
    viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(320, 240),
                                       samples=0, vsync=False, echo=echo))
    yield viewer, script, echo
    close_viewer(viewer)


def test_pick_select_rerun_and_error_keeps_the_stale_mesh(headless) -> None:
    viewer, script, echo = headless
    _wait(viewer, _has_run(1))
    assert viewer.result.status == "ok"
    _wait(viewer, _measured)
    assert "V 8  E 12  F 6  genus 0  volume 8" in _hud_text(viewer)
    fitted = viewer.camera.distance
    viewer.click(160, 120)
    face = viewer.selection.faces
    assert len(face) == 1
    assert f"faces(True) == ({face[0]},)" in echo.getvalue()
    measured = f"face {face[0]}: 4 sides, area 4, normal "
    assert measured in echo.getvalue() and measured in _hud_text(viewer)
    viewer.handle_key("R")
    _wait(viewer, _has_run(2))
    assert viewer.result.arrays.positions[:, 0].max() == pytest.approx(3.0)  # saw faces(True)
    assert measured in _hud_text(viewer)  # measured again on the new mesh
    assert viewer.camera.distance == fitted               # kept across the reload
    before = viewer.capture()
    script.write_text("x = (\n")                          # a syntax error
    viewer.handle_key("R")
    _wait(viewer, _has_run(3))
    assert viewer.result.status == "error" and viewer.result.stale
    assert "error, stale" in _hud_text(viewer)
    assert "model.py:1" in echo.getvalue()
    assert np.array_equal(viewer.capture(), before)        # the last good mesh stays


def test_e_shows_the_mesh_a_failed_run_left(tmp_path: Path) -> None:
    script = tmp_path / "fails.py"
    script.write_text("load('cube')\n")
    echo = io.StringIO()
    with _opened(script, (200, 150), echo=echo) as viewer:
        good = viewer.renderer.arrays
        viewer.handle_key("E")
        assert "no failed run to show" in echo.getvalue()
        script.write_text("load('cube')\nsubdivide('catmull-clark')\nraise ValueError('no')\n")
        viewer.session.reload()
        _wait(viewer, lambda v: v.result.status == "error" and not v.waiting)
        assert viewer.renderer.arrays is good and "(E: the failed run's mesh)" in _hud_text(viewer)
        assert viewer.handle_key("E") == "toggle_partial"
        assert viewer.renderer.arrays is viewer.result.partial
        assert "V 26  E 48  F 24" in _hud_text(viewer)  # the subdivided cube of the failed run
        assert "the failed run's mesh (E: last good)" in _hud_text(viewer)
        viewer.handle_key("E")
        assert viewer.renderer.arrays is good and "V 8  E 12  F 6" in _hud_text(viewer)
        assert [step.label for step in viewer.result.steps] == ["load cube", "subdivide"]
        viewer.handle_key("LEFT")  # back through the steps the failed run finished
        _wait(viewer, lambda v: v.result.status == "paused" and v.result.step_index == 0)
        assert viewer.renderer.arrays.counts == (8, 12, 6)


def test_a_result_the_window_cannot_show_is_reported_and_the_old_mesh_stays(
        tmp_path: Path, monkeypatch, capsys) -> None:
    import livemod.viewer.content as content_module

    script = tmp_path / "model.py"
    script.write_text("load('cube')\n")
    echo = io.StringIO()
    with _opened(script, (160, 120), echo=echo) as viewer:
        before, shown = viewer.capture(), viewer.renderer.arrays

        def broken(*args, **kwargs):
            raise RuntimeError("GL said no")
        monkeypatch.setattr(content_module, "build_geometry", broken)
        script.write_text("load('tetrahedron')\n")
        viewer.session.reload()
        _wait(viewer, lambda v: v.runs.viewer_error is not None)
        run_frames(viewer, 3)  # the window goes on drawing
        assert "the viewer could not show run 2: RuntimeError: GL said no" in echo.getvalue()
        assert "RuntimeError: GL said no" in _hud_text(viewer)
        assert "Traceback" in capsys.readouterr().err
        assert viewer.renderer.arrays is shown and np.array_equal(viewer.capture(), before)
        monkeypatch.undo()
        viewer.session.reload()  # the next result that can be shown clears it
        _wait(viewer, _has_run(3))
        assert viewer.runs.viewer_error is None and viewer.renderer.arrays.counts == (4, 6, 4)

def test_the_select_option_reaches_the_first_run(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text(CUBE.format(scale=1.0))
    with _opened(script, (160, 120), selection=Selection(faces=(2,))) as viewer:
        assert viewer.result.arrays.positions[:, 0].max() == pytest.approx(3.0)
        assert viewer.selection == Selection(faces=(2,))


def test_the_window_shows_every_object_and_fits_them_all(tmp_path: Path) -> None:
    script = tmp_path / "two.py"
    script.write_text("load('cube')\nload('cube')\ntranslate(6, 0, 0)\n")
    with _opened(script, (200, 100)) as viewer:
        assert viewer.renderer.others is not None and viewer.renderer.others.counts == (8, 12, 6)
        image = viewer.capture().astype(int)
        covered = np.abs(image - image[0, 0]).sum(axis=2) > 12
        columns = np.flatnonzero(covered.any(axis=0))
        assert columns.min() < 60 and columns.max() > 140  # both cubes fitted in the frame
        assert viewer.renderer.bounds[:, 0].tolist() == pytest.approx([-1.0, 7.0])
        _wait(viewer, _measured)
        assert "V 8  E 12  F 6  genus 0  volume 8\nother objects: V 8  F 6" in _hud_text(viewer)


def _three_objects(folder: Path) -> Path:
    """A script whose scene is object 0 a tetrahedron, object 1 an octahedron (at
    x = 4) and object 2, current, a cube (at x = -4)."""
    script = folder / "three.py"
    script.write_text("load('tetrahedron')\nload('octahedron')\ntranslate(4, 0, 0)\n"
                      "load('cube')\ntranslate(-4, 0, 0)\n")
    return script


def test_tab_shows_the_other_objects_one_at_a_time(tmp_path: Path) -> None:
    script, echo = _three_objects(tmp_path), io.StringIO()
    with _opened(script, (200, 100), echo=echo) as viewer:
        assert [oid for oid, _, _ in viewer.result.other_objects] == [0, 1]
        assert viewer.renderer.others.counts == (4 + 6, 6 + 12, 4 + 8)
        everything = viewer.capture()
        seen = []
        for _ in range(3):
            assert viewer.handle_key("TAB") == "cycle_others"
            run_frames(viewer, 1)
            seen.append((viewer.objects.hidden, viewer.renderer.others.counts))
        assert seen == [({1}, (4, 6, 4)), ({0}, (6, 12, 8)), (set(), (10, 18, 12))]
        assert np.array_equal(viewer.capture(), everything)  # all of them again
        viewer.handle_key("TAB")
        assert ("other objects: object 0 'tetrahedron' alone (of 2; Tab: next): V 4  F 4"
                in _hud_text(viewer))
        assert not np.array_equal(viewer.capture(), everything)
        viewer.handle_key("A")  # hidden, then Tab shows the next one
        viewer.handle_key("TAB")
        assert viewer.style.others and viewer.objects.hidden == {0}
        script.write_text(script.read_text() + "kill(1)\n")  # the one shown goes away
        viewer.session.reload()
        _wait(viewer, _has_run(2))
        assert not viewer.objects.hidden and viewer.renderer.others.counts == (4, 6, 4)
        assert "other objects: object 1 'octahedron' alone (of 2; Tab: next)" in echo.getvalue()


def _click_object_row(viewer: LiveViewer, line: int, part: str = "row") -> None:
    """Click the object list's ``line``-th drawn row (0: the header); ``part`` "row",
    or the header's "all" / "none" button."""
    run_frames(viewer, 1)  # lays the list out below the parameters panel
    size = viewer.wnd.fbo.size
    x, y, width, row_height = viewer.objects.panel.frame(size)
    py = int(y + 6 + (line + 0.5) * row_height)
    px = x + 30 if part == "row" else next(  # the button's first pixel, as the panel lays it out
        px for px in range(int(x), int(x + width)) if viewer.objects.panel.hit(px, py, size).part == part)
    viewer.on_mouse_press_event(int(px), py, viewer.wnd.mouse.left)
    viewer.on_mouse_release_event(int(px), py, viewer.wnd.mouse.left)
    run_frames(viewer, 1)


def test_the_object_list_shows_and_hides_each_other_object(tmp_path: Path) -> None:
    script, echo = _three_objects(tmp_path), io.StringIO()
    with _opened(script, (400, 300), echo=echo) as viewer:
        everything = viewer.capture()
        assert viewer.handle_key("L") == "toggle_object_list"
        assert [row.text() for row in viewer.objects.panel.rows] == [
            "0 tetrahedron   V 4  F 4", "1 octahedron   V 6  F 8",
            "2 cube   V 8  F 6  (current)"]
        _click_object_row(viewer, 1)  # untick the tetrahedron
        assert viewer.objects.hidden == {0} and viewer.renderer.others.counts == (6, 12, 8)
        assert "other objects: object 1 'octahedron' alone (of 2; Tab: next)" in _hud_text(viewer)
        assert not np.array_equal(viewer.capture(), everything)
        _click_object_row(viewer, 0, "none")
        assert viewer.objects.hidden == {0, 1} and viewer.renderer.others is None
        assert "other objects: 0 of 2 shown (L: list)" in _hud_text(viewer)
        _click_object_row(viewer, 0, "all")
        assert not viewer.objects.hidden and np.array_equal(viewer.capture(), everything)
        _click_object_row(viewer, 3)  # the current object's row: hides it, then shows it
        _click_object_row(viewer, 3)
        assert "current object: hidden\ncurrent object: shown" in echo.getvalue()
        assert viewer.style.current and np.array_equal(viewer.capture(), everything)
        _click_object_row(viewer, 2)  # untick the octahedron, then the script adds one
        script.write_text(script.read_text() + "load('icosahedron')\n")
        viewer.session.reload()
        _wait(viewer, _has_run(2))
        assert viewer.objects.hidden == {1}  # still hidden; the new object is shown
        assert viewer.renderer.others.counts == (4 + 8, 6 + 12, 4 + 6)  # tetrahedron, cube
        assert "other objects: 2 of 3 shown (L: list)" in _hud_text(viewer)


def test_the_wheel_scrolls_the_object_list_and_zooms_elsewhere(tmp_path: Path) -> None:
    script = tmp_path / "many.py"
    script.write_text("for i in range(40):\n    load('tetrahedron')\n    translate(2 * i, 0, 0)\n")
    with _opened(script, (400, 300)) as viewer:
        viewer.handle_key("L")
        run_frames(viewer, 1)
        x, y, _, _ = viewer.objects.panel.frame(viewer.wnd.fbo.size)
        distance = viewer.camera.distance
        viewer.on_mouse_position_event(int(x + 30), int(y + 40), 0, 0)
        assert viewer.objects.panel.hover == 0  # the first object's row: highlighted
        viewer.on_mouse_scroll_event(0.0, -3.0)  # wheel down over the list: it scrolls
        assert viewer.objects.panel.shown_rows(viewer.wnd.fbo.size).start == 3
        assert viewer.camera.distance == distance
        viewer.on_mouse_scroll_event(0.0, 1.0)
        assert viewer.objects.panel.shown_rows(viewer.wnd.fbo.size).start == 2
        viewer.on_mouse_position_event(10, 290, 0, 0)  # off the list: the wheel zooms
        assert viewer.objects.panel.hover is None
        viewer.on_mouse_scroll_event(0.0, 1.0)
        assert viewer.camera.distance != distance
        viewer.handle_key("L")  # the list closed: the wheel zooms over its place too
        distance = viewer.camera.distance
        viewer.on_mouse_position_event(int(x + 30), int(y + 40), 0, 0)
        viewer.on_mouse_scroll_event(0.0, 1.0)
        assert viewer.camera.distance != distance


def test_c_cuts_the_mesh_and_brackets_move_the_plane(headless) -> None:
    viewer, _, echo = headless
    _wait(viewer, _has_run(1))
    whole = viewer.capture()
    assert viewer.handle_key("C") == "cycle_section"
    assert viewer.style.section == (0, 0.0)  # through the middle of the 2 x 2 x 2 cube
    assert "section x <= 0" in _hud_text(viewer) and "section: x <= 0" in echo.getvalue()
    assert not np.array_equal(viewer.capture(), whole)
    assert viewer.handle_key("RIGHT_BRACKET") == "section_forward"
    assert viewer.style.section == (0, pytest.approx(0.1))  # 1/20 of the size
    for _ in range(40):  # never further than a step beyond the mesh
        viewer.handle_key("LEFT_BRACKET")
    assert viewer.style.section == (0, pytest.approx(-1.1))
    assert [viewer.handle_key("C") and viewer.style.section for _ in range(3)] == [
        (1, 0.0), (2, 0.0), None]
    assert echo.getvalue().rstrip().endswith("section: off")
    assert np.array_equal(viewer.capture(), whole)
    viewer.handle_key("RIGHT_BRACKET")
    assert "no section to move" in echo.getvalue()


def test_keys_change_style_camera_and_pick_mode(headless) -> None:
    viewer, _, _ = headless
    _wait(viewer, _has_run(1))
    first = viewer.capture()
    viewer.handle_key("W")
    assert not viewer.style.edges
    viewer.handle_key("F", ctrl=True)
    assert viewer.style.labels == {"faces"}
    viewer.handle_key("O")
    assert viewer.camera.ortho
    viewer.handle_key("NUMBER_2")
    assert viewer.camera.pitch > 89
    assert not np.array_equal(viewer.capture(), first)
    viewer.handle_key("M")
    assert viewer.picking.mode == "edge"
    viewer.handle_key("C", shift=True)
    assert viewer.picking.mode == "corner"
    viewer.handle_key("H")
    run_frames(viewer, 2)
    assert viewer.look.show_help
    before = viewer.capture()
    assert viewer.handle_key("X") == "toggle_grid" and viewer.style.grid
    assert not np.array_equal(viewer.capture(), before)
    assert viewer.handle_key("A") == "toggle_others" and not viewer.style.others
    dark = viewer.capture()
    viewer.handle_key("B")
    light = viewer.capture()
    assert light[0, 0].min() > 200 > dark[0, 0].max()
    viewer.handle_key("B")
    assert np.array_equal(viewer.capture(), dark)
    assert viewer.handle_key("N") == "toggle_smooth" and viewer.style.smooth
    run_frames(viewer, 1)  # draws the normals' first use


def test_screenshots_opaque_and_transparent(headless, tmp_path: Path, monkeypatch) -> None:
    from tests.images import read_image

    viewer, _, echo = headless
    _wait(viewer, _has_run(1))
    monkeypatch.chdir(tmp_path)
    (tmp_path / "model_000.png").write_bytes(b"an earlier screenshot")
    assert viewer.handle_key("F12") == "screenshot"
    assert viewer.handle_key("F12", shift=True) == "screenshot_transparent"
    assert viewer.screenshots == [Path("model_001.png"), Path("model_002.png")]
    assert (tmp_path / "model_000.png").read_bytes() == b"an earlier screenshot"
    opaque = read_image("model_001.png")
    clear = read_image("model_002.png")
    assert opaque.shape == (240, 320, 3) and clear.shape == (240, 320, 4)
    assert np.array_equal(opaque, viewer.capture())
    drawn = clear[..., 3] == 255
    assert clear[0, 0, 3] == 0 and drawn[120, 160]
    assert np.array_equal(clear[drawn][:, :3], opaque[drawn])  # the same picture where drawn
    assert "screenshot: model_002.png" in echo.getvalue()


def test_shift_click_adds_and_escape_clears(headless) -> None:
    viewer, _, echo = headless
    _wait(viewer, _has_run(1))
    viewer.click(160, 120)
    first = viewer.selection.faces
    y, other = _row_with_another_face(viewer, first)
    viewer.click(160, y, add=True)
    assert viewer.selection.faces == (*first, other)
    assert f"faces(True) == {(*first, other)!r}" in echo.getvalue()
    assert "2 faces: area 8" in _hud_text(viewer)
    viewer.handle_key("ESCAPE")
    assert viewer.selection.is_empty() and "area" not in _hud_text(viewer)
    assert echo.getvalue().rstrip().endswith("faces(True) == ()")


def _row_with_another_face(viewer: LiveViewer, taken: tuple[int, ...]) -> tuple[int, int]:
    """``(window row, face id)`` of a face at x=160, other than ``taken``, scanning down."""
    size = viewer.wnd.fbo.size
    for y in range(5, 120, 4):
        hit = viewer.renderer.pick(viewer.camera, size, 160, y, "face")
        if hit is not None and hit.element_id not in taken:
            return y, hit.element_id
    raise AssertionError("no second face found")


STEPS = """
from livemod.dlfl import from_polygons, current_scene, edges, subdivideEdge, step
P = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
     (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
F = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3), (7, 6, 5, 4)]
current_scene().add(from_polygons(P, F))
step("cube")
subdivideEdge(edges()[0])
step("split")
"""


def test_step_keys_show_earlier_steps_in_the_hud(headless) -> None:
    viewer, script, _ = headless
    _wait(viewer, _has_run(1))
    script.write_text(STEPS)
    viewer.handle_key("R")
    _wait(viewer, lambda v: v.result.run_id >= 2 and v.result.status == "ok")
    total = len(viewer.result.steps)
    assert viewer.result.arrays.counts[0] == 9
    assert f"step {total}/{total}: split" in _hud_text(viewer)
    viewer.handle_key("LEFT")
    _wait(viewer, lambda v: v.result.status == "paused" and v.result.step_index == total - 2)
    viewer.handle_key("COMMA")
    _wait(viewer, lambda v: v.result.status == "paused" and v.result.step_index == total - 3)
    assert viewer.result.arrays.counts[0] == 8          # before the split
    assert f"step {total - 2}/{total}: cube" in _hud_text(viewer)
    assert "paused" in _hud_text(viewer)
    viewer.handle_key("RIGHT")
    _wait(viewer, lambda v: v.result.status == "paused" and v.result.step_index == total - 2)
    assert viewer.result.arrays.counts[0] == 9


THREE_STEPS = "load('cube')\nsubdivide('catmull-clark')\nsubdivide('catmull-clark')\n"


def _pressed(viewer: LiveViewer, key: str, frames: int = 30) -> None:
    """Press ``key`` and draw ``frames`` frames (time for a result to arrive)."""
    viewer.handle_key(key)
    for _ in range(frames):
        run_frames(viewer, 1)
        time.sleep(0.01)


def test_a_step_key_with_no_step_to_go_to_says_so_and_is_not_running(tmp_path: Path) -> None:
    script = tmp_path / "three.py"
    script.write_text(THREE_STEPS)
    echo = io.StringIO()
    with _opened(script, (200, 150), echo=echo) as viewer:
        for key, said in (("RIGHT", "at the last step"), ("END", "already at the end")):
            _pressed(viewer, key)  # the session posts nothing: the HUD must not wait for it
            assert not viewer.waiting and "ok  " in _hud_text(viewer) and said in echo.getvalue()
        viewer.handle_key("HOME")
        _wait(viewer, _at_step(0))
        _pressed(viewer, "LEFT")
        assert not viewer.waiting and "paused" in _hud_text(viewer)
        assert "at the first step" in echo.getvalue()
        viewer.handle_key("RIGHT")  # and the keys still step
        _wait(viewer, _at_step(1))
        assert "step 2/3: subdivide (line 2)" in _hud_text(viewer)


def test_playing_to_the_end_stops_playing(tmp_path: Path) -> None:
    script = tmp_path / "three.py"
    script.write_text(THREE_STEPS)
    with _opened(script, (200, 150)) as viewer:
        assert viewer.handle_key("SPACE") == "play_pause" and viewer.stepping.playing
        _wait(viewer, lambda v: v.result.run_id >= 2 and v.result.status == "ok")
        assert not viewer.stepping.playing and "playing" not in _hud_text(viewer)
        viewer.handle_key("SPACE")  # plays again, from the first step
        assert viewer.stepping.playing
        _wait(viewer, lambda v: v.result.run_id >= 3 and v.result.status == "paused")


def test_a_syntax_error_has_no_steps_to_scrub(tmp_path: Path) -> None:
    script = tmp_path / "three.py"
    script.write_text(THREE_STEPS)
    echo = io.StringIO()
    with _opened(script, (300, 200), echo=echo) as viewer:
        assert viewer.overlay.timeline_shown()
        script.write_text(THREE_STEPS + "x = (\n")
        viewer.handle_key("R")
        _wait(viewer, lambda v: v.result.status == "error" and not v.waiting)
        assert "no steps" in _hud_text(viewer) and not viewer.overlay.timeline_shown()
        for key in ("LEFT", "RIGHT", "HOME"):
            _pressed(viewer, key)
            assert not viewer.waiting and "error, stale" in _hud_text(viewer), key
        assert echo.getvalue().count("no steps") == 3
        script.write_text(THREE_STEPS + "raise ValueError('no')\n")  # fails after 3 steps
        viewer.handle_key("R")
        _wait(viewer, lambda v: v.result.status == "error" and v.result.steps and not v.waiting)
        assert viewer.runs.steps() == 3 and viewer.overlay.timeline_shown()


def _press_timeline(viewer: LiveViewer, step: int, drag_to: int | None = None) -> None:
    """Click the timeline at ``step`` (or press there and drag to ``drag_to``)."""
    size = viewer.wnd.fbo.size
    _, y, width, height = viewer.overlay.timeline.frame(size)
    total = viewer.runs.steps()

    def x_of(k: int) -> int:  # the first pixel whose step is k
        return next(px for px in range(size[0]) if viewer.overlay.timeline.step_at(px, size, total) == k)

    py = int(y + height - 8)
    viewer.on_mouse_press_event(x_of(step), py, viewer.wnd.mouse.left)
    end = step if drag_to is None else drag_to
    if drag_to is not None:
        viewer.on_mouse_drag_event(x_of(drag_to), py, x_of(drag_to) - x_of(step), 0)
    viewer.on_mouse_release_event(x_of(end), py, viewer.wnd.mouse.left)


def _at_step(k: int) -> Callable[[LiveViewer], bool]:
    return lambda v: (not v.waiting and v.result.status in ("paused", "ok")
                      and v.result.step_index == k)


def test_the_timeline_scrubs_through_the_steps(tmp_path: Path) -> None:
    script = tmp_path / "ten.py"
    script.write_text("for i in range(10):\n    createVertex((i, 0, 0))\n")
    with _opened(script, (400, 300)) as viewer:
        assert viewer.runs.steps() == 10 and viewer.overlay.timeline_shown()
        _press_timeline(viewer, 3)
        _wait(viewer, _at_step(3))
        assert viewer.result.arrays.counts[0] == 4  # the mesh after the fourth step
        assert "step 4/10: createVertex (line 2)" in _hud_text(viewer)
        _press_timeline(viewer, 1, drag_to=7)  # a drag goes where it is let go
        _wait(viewer, _at_step(7))
        assert viewer.result.arrays.counts[0] == 8
        assert viewer.handle_key("HOME") == "first_step"
        _wait(viewer, _at_step(0))
        assert viewer.result.arrays.counts[0] == 1
        viewer.handle_key("END")
        _wait(viewer, lambda v: not v.waiting and v.result.status == "ok"
              and v.result.step_index is None)
        assert viewer.result.arrays.counts[0] == 10
        distance = viewer.camera.distance
        _press_timeline(viewer, 5)  # a click on the bar is no pick and no orbit
        assert viewer.selection.is_empty() and viewer.camera.distance == distance

def test_dropping_a_script_or_a_mesh_opens_it(headless, tmp_path: Path) -> None:
    from livemod.dlfl.io import save_mesh
    from livemod.dlfl.shapes import tetrahedron

    viewer, _, echo = headless
    _wait(viewer, _has_run(1))
    other = tmp_path / "empty.py"
    other.write_text("x = 1\n")
    viewer.on_files_dropped_event(0, 0, [str(other)])
    assert "empty.py" in viewer.wnd.title
    _wait(viewer, lambda v: v.result is not None and v.result.script == str(other))
    mesh_file = tmp_path / "tet.obj"
    save_mesh(tetrahedron(), str(mesh_file))
    viewer.on_files_dropped_event(0, 0, [str(mesh_file)])
    _wait(viewer, lambda v: v.result is not None and v.result.arrays is not None)
    assert viewer.result.arrays.counts == (4, 6, 4)   # the script ran on the dropped mesh
    assert "opened" in echo.getvalue()


def test_frames_are_drawn_while_a_script_spins_on_the_gil(headless) -> None:
    # how long those frames take is measured by bench/bench_viewer.py, not asserted here
    viewer, script, _ = headless
    _wait(viewer, _has_run(1))
    script.write_text(SPINNING)
    viewer.handle_key("R")
    _wait(viewer, lambda v: v.runs.activity is not None and v.runs.activity.run_id == 2)
    run_frames(viewer, 30)
    # thirty frames later the run is still at work and run 1's cube still shown
    assert viewer.runs.activity is not None and viewer.runs.activity.run_id == 2
    assert viewer.result.run_id == 1 and viewer.result.arrays.counts == (8, 12, 6)


# -- a real glfw window under Xvfb --------------------------------------------------


@pytest.fixture
def xvfb_display(monkeypatch: pytest.MonkeyPatch) -> Iterator[str]:
    """Start Xvfb on a display it picks itself (-displayfd) and point DISPLAY at it."""
    assert shutil.which("Xvfb"), "Xvfb is needed (apt-get install xvfb)"
    read_end, write_end = os.pipe()
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-screen", "0",
                               "1024x768x24", "-nolisten", "tcp"], pass_fds=(write_end,),
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_end)
    try:
        ready, _, _ = select.select([read_end], [], [], 20.0)
        assert ready, "Xvfb did not start"
        display = ":" + os.read(read_end, 64).decode().strip()
        monkeypatch.setenv("DISPLAY", display)
        monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
        yield display
    finally:
        os.close(read_end)
        server.terminate()
        server.wait(timeout=10)


def _glfw_probe(script_path: str) -> None:
    """Run in a fresh process (GLX and EGL contexts do not mix in one process, and an
    X error ends the process): open, reload on save, close. Raises on failure."""
    script = Path(script_path)
    viewer = create_viewer(ViewOptions(str(script), backend="glfw", size=(320, 240),
                                       samples=0, vsync=False, echo=io.StringIO()))
    session = viewer.session
    try:
        assert viewer.wnd.name == "glfw"
        _wait(viewer, _has_run(1))
        first = viewer.capture()
        assert first.shape == (240, 320, 3) and first.std() > 5
        time.sleep(0.05)
        script.write_text(CUBE.format(scale=1.6))   # saved in the editor: no key pressed
        _wait(viewer, _has_run(2))
        assert viewer.result.arrays.positions[:, 0].max() == pytest.approx(1.6)
        second = viewer.capture()
        assert not np.array_equal(second, first)
        for key in ("C", "H", "L"):  # the section and the overlays on a real GLX context
            viewer.handle_key(key)
        assert run_frames(viewer, 3) == 3
        assert not np.array_equal(viewer.capture(), second)  # cut open
        viewer.handle_key("Q")
        assert run_frames(viewer, 5) == 0
    finally:
        close_viewer(viewer)
    assert session.join(10.0)
    print("glfw window ok")


def test_glfw_window_reloads_on_save_and_closes(xvfb_display: str, tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text(CUBE.format(scale=1.0))
    assert "glfw window ok" in run_probe("test_viewer_window", "_glfw_probe", script)


def _glfw_resize_probe(script_path: str) -> None:
    """Run in a fresh process: resize the window (larger, then smaller) and check that
    the screen shows the whole scene at the new size, as :meth:`capture` draws it, and
    that a click in the middle picks. Raises on failure."""
    import glfw

    viewer = create_viewer(ViewOptions(script_path, backend="glfw", size=(320, 240),
                                       samples=0, vsync=False, echo=io.StringIO()))
    try:
        _wait(viewer, _has_run(1))
        viewer.handle_key("U")  # no HUD: the screen is the scene alone
        for width, height in ((480, 360), (200, 150)):
            glfw.set_window_size(viewer.wnd._window, width, height)
            deadline = time.monotonic() + 5.0
            while tuple(viewer.wnd.buffer_size) != (width, height) and time.monotonic() < deadline:
                glfw.poll_events()
                time.sleep(0.01)
            run_frames(viewer, 2)
            viewer.painter.frames.presented_at = 0.0  # put the frame up again: read it before a swap
            viewer.on_render(0.0, 0.0)
            raw = viewer.ctx.screen.read(viewport=(0, 0, width, height), components=3,
                                         alignment=1)
            screen = np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3)[::-1]
            assert np.array_equal(screen, viewer.capture()), (width, height)
            viewer.click(width / 2, height / 2)
            assert len(viewer.selection.faces) == 1, (width, height)
            viewer.click(2, 2)  # the background clears it
            assert viewer.selection.is_empty()
    finally:
        close_viewer(viewer)
    print("glfw resize ok")


def test_a_resized_window_draws_and_picks_at_its_new_size(xvfb_display: str,
                                                          tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text(CUBE.format(scale=1.0).replace("if faces(True)", "if False"))
    assert "glfw resize ok" in run_probe("test_viewer_window", "_glfw_resize_probe", script)


def test_view_without_a_display_says_so_in_one_line(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text(CUBE.format(scale=1.0))
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    done = subprocess.run([sys.executable, "-m", "livemod", "view", str(script)],
                          capture_output=True, text=True, timeout=60, env=env)
    assert done.returncode == 1
    assert "Traceback" not in done.stderr
    assert done.stderr.startswith("livemod: error: cannot open a window (")
    assert "no display" in done.stderr and "livemod render" in done.stderr


def test_view_output_writes_every_good_result_and_shows_a_failed_write(tmp_path: Path) -> None:
    from livemod.dlfl import mesh_arrays
    from livemod.dlfl.io import open_mesh

    script = tmp_path / "model.py"
    script.write_text(CUBE.format(scale=1.0))
    out = tmp_path / "out" / "model.obj"
    echo = io.StringIO()
    with _opened(script, (320, 240), echo=echo, output=str(out)) as viewer:
        assert open_mesh(str(out)).counts() == (8, 12, 6)
        assert f"run {viewer.result.run_id}: wrote {out}" in echo.getvalue()
        time.sleep(0.05)
        script.write_text(CUBE.format(scale=2.0))
        _wait(viewer, _has_run(2))
        assert mesh_arrays(open_mesh(str(out))).positions[:, 0].max() == pytest.approx(2.0)
        out.unlink()
        out.mkdir()  # a folder where the file should go: the write fails
        time.sleep(0.05)
        script.write_text(CUBE.format(scale=3.0))
        _wait(viewer, _has_run(3))
        assert viewer.result.status == "error" and viewer.result.error.file == str(out)
        assert viewer.result.stale  # the last good cube, as after a script error
        assert viewer.renderer.arrays.positions[:, 0].max() == pytest.approx(2.0)


def test_view_refuses_an_output_no_writer_takes(tmp_path: Path, capsys) -> None:
    from livemod.viewer.cli import main

    script = tmp_path / "model.py"
    script.write_text(CUBE.format(scale=1.0))
    assert main(["view", str(script), "-o", str(tmp_path / "model.txt")]) == 2
    assert "livemod: error: output" in capsys.readouterr().err


def test_view_output_of_all_objects_joins_them(tmp_path: Path) -> None:
    from livemod.dlfl.io import open_mesh

    out = tmp_path / "all.obj"
    with _opened(_three_objects(tmp_path), (320, 240), output=str(out), all_objects=True):
        assert open_mesh(str(out)).counts() == (4 + 6 + 8, 6 + 12 + 12, 4 + 8 + 6)
    alone = tmp_path / "alone.obj"
    with _opened(_three_objects(tmp_path), (320, 240), output=str(alone)):
        assert open_mesh(str(alone)).counts() == (8, 12, 6)  # the current cube


SLOW_SAVE = """
import time
start = time.perf_counter()
while time.perf_counter() - start < 1.5:
    time.sleep(0.01)
load('tetrahedron')
"""


def test_a_run_a_save_starts_shows_running_over_the_last_result(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text("load('cube')\n")
    with _opened(script, (240, 160)) as viewer:
        shown = viewer.renderer.arrays
        assert "running" not in _hud_text(viewer)
        time.sleep(0.05)
        script.write_text(SLOW_SAVE)  # saved in an editor: no key, the window waits for nothing
        _wait(viewer, lambda v: v.runs.activity is not None)
        assert not viewer.waiting and viewer.runs.activity.run_id == 2
        assert "running... " in _hud_text(viewer)
        assert viewer.renderer.arrays is shown  # over the last good mesh
        _wait(viewer, lambda v: "running... 0.5 s" in _hud_text(v))  # the time goes on
        _wait(viewer, _has_run(2))
        assert viewer.runs.activity is None and "running" not in _hud_text(viewer)
        assert viewer.renderer.arrays.counts == (4, 6, 4)


def test_a_finished_run_the_session_still_reports_is_not_running(headless) -> None:
    from types import SimpleNamespace

    viewer, _, _ = headless
    _wait(viewer, _has_run(1))
    session = viewer.session

    class Reporting:
        """The session, still saying that a run works."""

        activity = SimpleNamespace(run_id=1, script=viewer.script, working=0.7)

        def __getattr__(self, name: str) -> Any:
            return getattr(session, name)

    viewer.scripts.session = Reporting()
    try:
        run_frames(viewer, 1)
        assert viewer.runs.activity is None  # run 1's end is shown: it works no more
        Reporting.activity = SimpleNamespace(run_id=2, script=viewer.script, working=0.7)
        run_frames(viewer, 1)
        assert viewer.runs.activity.run_id == 2 and "running... 0.5 s" in _hud_text(viewer)
    finally:
        viewer.scripts.session = session


def test_the_hud_names_the_runs_the_session_left_in_the_background(headless) -> None:
    viewer, _, _ = headless
    _wait(viewer, _has_run(1))
    session = viewer.session

    class Reporting:
        """The session, saying that run 1 still works in the background."""

        background_runs: tuple[int, ...] = (1,)

        def __getattr__(self, name: str) -> Any:
            return getattr(session, name)

    viewer.scripts.session = Reporting()
    try:
        run_frames(viewer, 1)
        assert "run 1 is still finishing in the background" in _hud_text(viewer)
        Reporting.background_runs = ()
        run_frames(viewer, 1)
        assert "background" not in _hud_text(viewer)
    finally:
        viewer.scripts.session = session


TEN_STEPS = "for i in range(10):\n    createVertex((i, 0, 0))\n"


def _key(viewer: LiveViewer, action: str) -> None:
    """Press or release the Right arrow (the headless backend has no key codes)."""
    from moderngl_window.context.base.keys import KeyModifiers

    viewer._key_names = {"right": "RIGHT"}
    viewer.on_key_event("right", getattr(viewer.wnd.keys, action), KeyModifiers())


def test_holding_a_step_key_keeps_stepping(tmp_path: Path) -> None:
    script = tmp_path / "ten.py"
    script.write_text(TEN_STEPS)
    echo = io.StringIO()
    with _opened(script, (300, 200), echo=echo) as viewer:
        viewer.handle_key("HOME")
        _wait(viewer, _at_step(0))
        clock = [100.0]
        viewer.stepping.clock = lambda: clock[0]
        _key(viewer, "ACTION_PRESS")
        _wait(viewer, _at_step(1))
        clock[0] += 0.3  # not yet held long enough to repeat
        run_frames(viewer, 5)
        assert _at_step(1)(viewer) and viewer.stepping.held is not None
        for step in (2, 3, 4):  # then ten steps a second
            clock[0] += 0.11
            _wait(viewer, _at_step(step))
        _key(viewer, "ACTION_RELEASE")
        clock[0] += 1.0
        run_frames(viewer, 5)
        assert _at_step(4)(viewer) and viewer.stepping.held is None
        viewer.on_key_event("right", 2, None)  # glfw's own repeat: the timer repeats instead
        run_frames(viewer, 3)
        assert _at_step(4)(viewer)
        viewer.handle_key("END")
        _wait(viewer, lambda v: not v.waiting and v.result.status == "ok")
        _key(viewer, "ACTION_PRESS")  # at the end: says so once, and does not repeat
        for _ in range(3):
            clock[0] += 0.5
            run_frames(viewer, 2)
        assert viewer.stepping.held is None and echo.getvalue().count("at the last step") == 1


def test_picks_a_later_run_removed_are_marked_missing(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text("load('cube')\n")
    picked = Selection(faces=(5,), vertices=(1,))
    with _opened(script, (240, 160), selection=picked) as viewer:
        assert "faces(True) == (5,)" in _hud_text(viewer)
        assert "not in this mesh" not in _hud_text(viewer)
        script.write_text("load('tetrahedron')\n")  # faces 0 to 3 only
        viewer.session.reload()
        _wait(viewer, _has_run(2))
        text = _hud_text(viewer)
        assert "faces(True)" not in text and "verts(True) == (1,)" in text
        assert "picked, not in this mesh: face 5" in text
        assert viewer.selection == picked  # kept: an earlier step or a later run may have it
        script.write_text("load('cube')\n")
        viewer.session.reload()
        _wait(viewer, _has_run(3))
        assert "faces(True) == (5,)" in _hud_text(viewer)
        assert "not in this mesh" not in _hud_text(viewer)


def test_a_selection_the_run_found_empty_says_how_to_pick(tmp_path: Path) -> None:
    script = tmp_path / "crust.py"
    script.write_text("load('cube')\nrind(faces(True), False, 0.1)\n")
    hint = "faces(True) found nothing picked: M to face mode, click a face"
    with _opened(script, (320, 200)) as viewer:
        assert viewer.result.unselected == ("faces",)
        assert hint in _hud_text(viewer)
        viewer.set_selection(Selection(faces=(0,)))  # picked: the next save uses it
        assert hint not in _hud_text(viewer)
    with _opened(script, (320, 200), selection=Selection(faces=(0,))) as viewer:
        assert viewer.result.unselected == ()
        assert "found nothing picked" not in _hud_text(viewer)


def test_the_object_list_hides_the_current_object_too(tmp_path: Path) -> None:
    script, echo = _three_objects(tmp_path), io.StringIO()
    with _opened(script, (400, 300), echo=echo) as viewer:
        viewer.handle_key("U")  # no HUD: the picture is the scene alone
        everything = viewer.capture()
        viewer.handle_key("U")
        viewer.handle_key("L")
        size = viewer.screen_size
        on_cube = next((x, y) for x in range(0, 400, 4) for y in range(0, 300, 4)
                       if viewer.renderer.pick(viewer.camera, size, x, y, "face") is not None)
        _click_object_row(viewer, 3)  # the cube's row: the current object
        assert not viewer.style.current and "current object: hidden" in echo.getvalue()
        assert "(hidden: L lists it)" in _hud_text(viewer)
        viewer.handle_key("U")
        assert not np.array_equal(viewer.capture(), everything)
        assert viewer.renderer.pick(viewer.camera, size, *on_cube, "face") is None
        viewer.session.reload()  # hidden across runs
        _wait(viewer, _has_run(2))
        assert not viewer.style.current
        viewer.handle_key("U")
        _click_object_row(viewer, 0, "all")  # all: the current object as well
        viewer.handle_key("U")
        assert viewer.style.current and np.array_equal(viewer.capture(), everything)


def test_the_object_list_of_one_object_hides_it(tmp_path: Path) -> None:
    script, echo = tmp_path / "one.py", io.StringIO()
    script.write_text("load('cube')\n")
    with _opened(script, (400, 300), echo=echo) as viewer:
        viewer.handle_key("L")  # one object is listed too: its checkbox hides it
        run_frames(viewer, 1)
        assert "no objects to list" not in echo.getvalue()
        assert [row.text() for row in viewer.objects.panel.rows] == ["0 cube   V 8  F 6  (current)"]
        _click_object_row(viewer, 1)
        assert not viewer.style.current and "current object: hidden" in echo.getvalue()
        assert "(hidden: L lists it)" in _hud_text(viewer)
        _click_object_row(viewer, 1)
        assert viewer.style.current and "current object: shown" in echo.getvalue()


def test_a_script_truncated_before_its_write_keeps_the_mesh_shown(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text("load('cube')\n")
    with _opened(script, (240, 160)) as viewer:
        with open(script, "w"):  # an editor's truncate, its write still to come
            pass
        deadline = time.monotonic() + 1.0  # well past the watcher's debounce
        run_frames(viewer, until=lambda v: time.sleep(0.01) or time.monotonic() > deadline)
        assert viewer.result.run_id == 1 and viewer.renderer.arrays.counts[2] == 6
        assert viewer.runs.total_steps == 1  # not the empty run's none
        script.write_text("load('tetrahedron')\n")
        _wait(viewer, _has_run(2))
        assert viewer.renderer.arrays.counts[2] == 4


def test_a_pick_all_missing_lists_no_empty_faces_line(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text("load('tetrahedron')\n")  # faces 0 to 3 only
    with _opened(script, (240, 160), selection=Selection(faces=(5,))) as viewer:
        text = _hud_text(viewer)
        assert "picked, not in this mesh: face 5" in text
        assert "faces(True)" not in text and "--select" not in text  # not `== ()`: kept


def _error_panel_text(viewer: LiveViewer) -> list[str]:
    from livemod.viewer.hud import error_panel

    return [line for line, _ in error_panel(viewer.view_state())]


def test_the_error_panel_says_whose_error_it_is(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text("load('cube')\nx = (\n")
    with _opened(script, (400, 300)) as viewer:
        panel = _error_panel_text(viewer)
        assert panel[:2] == ["run 1: syntax error in model.py:2",
                             "SyntaxError: '(' was never closed"]
        assert panel.count("SyntaxError: '(' was never closed") == 1
        time.sleep(0.05)
        script.write_text(SLOW_SAVE)  # a newer save, at work for a while
        _wait(viewer, lambda v: v.runs.activity is not None)
        assert _error_panel_text(viewer)[0] == \
            "previous run 1: syntax error in model.py:2 (run 2 is running)"
        _wait(viewer, _has_run(2))
        assert viewer.result.status == "ok" and _error_panel_text(viewer) == []


def test_after_a_name_error_the_counts_and_the_step_say_whose_they_are(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text("load('cube')\n")
    with _opened(script, (400, 300)) as viewer:
        script.write_text("load('cube')\nsubdivide('catmull-clark')\ncub()\n")
        viewer.session.reload()
        _wait(viewer, lambda v: v.result.status == "error" and not v.waiting)
        _wait(viewer, _measured)
        text = _hud_text(viewer)
        assert "last good mesh (run 1): V 8  E 12  F 6  genus 0  volume 8" in text
        assert "failed run 2: step 2/2: subdivide (line 2)" in text
        viewer.handle_key("E")  # the failed run's own mesh: both are of run 2
        _wait(viewer, _measured)
        assert "failed run 2: V 26  E 48  F 24  genus 0" in _hud_text(viewer)


def _summaries(echo: io.StringIO) -> list[str]:
    """The echo's run summary lines, with their times (which vary) cut off."""
    return [line.rsplit(", ", 1)[0] if " steps, " in line else line
            for line in echo.getvalue().splitlines() if line.startswith("run ")]


def test_view_prints_one_summary_line_per_run(tmp_path: Path) -> None:
    script = tmp_path / "model.py"
    script.write_text("load('cube')\nsubdivide('catmull-clark')\n")
    echo = io.StringIO()
    with _opened(script, (240, 160), echo=echo) as viewer:
        viewer.handle_key("P")  # the window's own preview: no result is posted again
        _wait(viewer, lambda v: v.renderer.preview is not None)
        assert _summaries(echo) == ["run 1: ok, 2 steps, V=26 E=48 F=24"]
        assert echo.getvalue().splitlines()[0].endswith(
            f", {viewer.result.elapsed:.3f} s")  # as run --watch prints it
        script.write_text("load('cube')\nsubdivide('catmull-clark')\ncub()\n")
        viewer.session.reload()
        _wait(viewer, _has_run(2))
        viewer.handle_key("LEFT")  # a step of the failed run: a replay, no run's end
        _wait(viewer, lambda v: v.result.status == "paused" and not v.waiting)
        viewer.handle_key("END")  # the replay goes on to the error: that run ends
        _wait(viewer, lambda v: v.result.status == "error" and not v.waiting)
        said = f"{script}:3: NameError: name 'cub' is not defined"
        assert _summaries(echo) == ["run 1: ok, 2 steps, V=26 E=48 F=24", f"run 2: {said}",
                                    f"run {viewer.result.run_id}: {said}"]


def test_the_rate_keys_change_how_fast_the_steps_play(tmp_path: Path) -> None:
    from .viewer_support import press_key

    script = tmp_path / "ten.py"
    script.write_text(TEN_STEPS)
    echo = io.StringIO()
    with _opened(script, (300, 200), echo=echo) as viewer:
        assert "rate 2 steps/s" in _hud_text(viewer)
        for _ in range(4):
            press_key(viewer, "EQUAL")
        press_key(viewer, "MINUS")
        assert viewer.stepping.rate == 16.0 and "rate 16 steps/s" in _hud_text(viewer)
        press_key(viewer, "SPACE")
        assert "playing 16 steps/s" in _hud_text(viewer)
        press_key(viewer, "EQUAL")  # while playing: at once
        assert "playing 32 steps/s" in _hud_text(viewer)
        _wait(viewer, lambda v: v.result.run_id >= 2 and v.result.status == "ok")
        assert not viewer.stepping.playing and "rate 32 steps/s" in _hud_text(viewer)
        assert "play rate: 16 steps/s\nplay rate: 32 steps/s" in echo.getvalue()


def _settled(viewer) -> bool:
    return viewer.result is not None and not viewer.waiting and viewer.result.status == "ok"



@pytest.fixture
def cube_script(tmp_path: Path) -> Path:
    script = tmp_path / "box.py"
    script.write_text("load('cube')\n")
    return script



def _viewer(script: Path, **options):
    options.setdefault("echo", io.StringIO())
    return create_viewer(ViewOptions(str(script), backend="headless", size=(200, 150),
                                     samples=0, vsync=False, **options))



def test_the_window_frames_and_warns_about_a_mesh_with_nan(cube_script: Path) -> None:
    """A NaN vertex reaches the window's upload (as from a script's own arrays): the
    view is fitted on the rest, and the HUD counts it."""
    from livemod.viewer.hud import hud_lines

    viewer = _viewer(cube_script)
    try:
        frames_until(viewer, _settled)
        viewer.display.fit_bounds = None  # (fit on this upload)
        viewer.display.upload(cube_with({2: (np.nan, 0.0, 0.0)}), None, None)
        assert np.isfinite(viewer.camera.eye()).all() and viewer.camera.distance > 1.0
        text = [line for line, _ in hud_lines(viewer.view_state())]
        assert "1 vertex not finite (NaN or inf): left out of the framing" in text
        run_frames(viewer, 1)
        assert _background_differs(viewer.capture())[75, 100]
    finally:
        close_viewer(viewer)



def test_closing_the_window_releases_the_renderer(cube_script: Path) -> None:
    viewer = _viewer(cube_script)
    try:
        frames_until(viewer, _settled)
        run_frames(viewer, 2)
        objects = gl_objects(viewer.renderer) + [viewer.painter.frames.kept[1]]
    finally:
        close_viewer(viewer)
    assert all(isinstance(obj.mglo, moderngl.InvalidObject) for obj in objects)
    assert viewer.renderer._released and viewer.painter.frames.kept is None



def test_a_screenshot_name_taken_meanwhile_is_not_written_over(
        cube_script: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """Another process writes ``box_000.png`` while the window renders its picture."""
    monkeypatch.chdir(tmp_path)
    viewer = _viewer(cube_script)
    try:
        frames_until(viewer, _settled)
        capture = viewer.capture

        def racing(transparent: bool = False) -> np.ndarray:
            Path("box_000.png").write_bytes(b"the other process's")
            return capture(transparent)

        monkeypatch.setattr(viewer, "capture", racing)
        path = viewer.save_screenshot()
    finally:
        close_viewer(viewer)
    assert path == Path("box_001.png")
    assert Path("box_000.png").read_bytes() == b"the other process's"
    assert np.asarray(Image.open(path)).shape == (150, 200, 3)



SUBDIVIDED = """
from livemod.dlfl import param
n = param("n", 0, min=0, max=2)
for _ in range(n):
    subdivide("catmull-clark")
"""



def test_a_dropped_mesh_keeps_the_scripts_parameters(tmp_path: Path) -> None:
    from livemod.dlfl.io import save_mesh

    script = tmp_path / "smooth.py"
    script.write_text(SUBDIVIDED)
    box, tet = tmp_path / "box.obj", tmp_path / "tet.obj"
    save_mesh(cube(), str(box))
    save_mesh(tetrahedron(), str(tet))
    echo = io.StringIO()
    viewer = _viewer(script, mesh_path=str(box), echo=echo)
    try:
        frames_until(viewer, _settled)
        viewer.parameters.set("n", 1)
        viewer.parameters.flush(force=True)
        frames_until(viewer, lambda v: _settled(v) and v.result.arrays.counts == (26, 48, 24))
        viewer.set_selection(Selection(faces=(int(viewer.result.arrays.face_ids[0]),)))
        viewer.open_path(str(tet))
        assert viewer.selection.is_empty()
        frames_until(viewer, lambda v: _settled(v) and v.result.arrays.counts[0] != 26)
        # the tetrahedron subdivided once: the script ran with n = 1 on it
        assert viewer.result.arrays.counts == (14, 24, 12)
        assert viewer.session.parameters == {"n": 1} and viewer.parameters.panel.values == {"n": 1}
        assert viewer.selection.is_empty()
        said = echo.getvalue()
        assert f"opened {tet.resolve()}" in said
        assert ("the script runs on the new mesh with its parameter values kept; the "
                "selection was cleared (its ids were the old mesh's)") in said
    finally:
        close_viewer(viewer)



def test_an_emptied_script_is_named_over_the_last_mesh(cube_script: Path) -> None:
    """Saved empty (or blank), the script runs nothing: the window keeps the cube and
    the HUD says why, until the script has content again."""
    from livemod.viewer.hud import hud_lines

    viewer = _viewer(cube_script)
    try:
        frames_until(viewer, _settled)
        cube_run = viewer.result.run_id
        cube_script.write_text("\n  \n")
        frames_until(viewer, lambda v: v.runs.empty_script is not None)
        text = [line for line, _ in hud_lines(viewer.view_state())]
        assert "box.py is empty: showing the last result" in text
        assert viewer.result.run_id == cube_run and viewer.result.arrays.counts == (8, 12, 6)
        cube_script.write_text("load('tetrahedron')\n")
        frames_until(viewer, lambda v: _settled(v) and v.result.arrays.counts == (4, 6, 4))
        assert viewer.runs.empty_script is None
        assert not any("is empty" in line for line, _ in hud_lines(viewer.view_state()))
    finally:
        close_viewer(viewer)


def test_a_dropped_script_starts_without_the_old_scripts_view_state(tmp_path: Path) -> None:
    first = tmp_path / "fails.py"
    first.write_text("load('cube')\nsubdivide('catmull-clark')\nraise ValueError('no')\n")
    viewer = create_viewer(ViewOptions(str(first), backend="headless", size=(200, 150),
                                       samples=0, vsync=False, echo=io.StringIO()))
    try:
        frames_until(viewer, lambda v: v.result is not None and not v.waiting)
        viewer.handle_key("E")  # the failed run's mesh
        assert viewer.display.show_partial
        viewer.runs.viewer_error = "an old failure"
        second = tmp_path / "ok.py"
        second.write_text("load('cube')\n")
        viewer.open_path(str(second))
        assert not viewer.display.show_partial and viewer.runs.viewer_error is None
        assert viewer.stepping.held is None and viewer.stepping.scrub_step is None and not viewer.stepping.playing
    finally:
        close_viewer(viewer)
