"""The per-frame draws keep their GL buffers (HUD text, id labels, selected vertices
and corners), and measures of positions that are not finite say so instead of nan."""

from __future__ import annotations

import dataclasses
import io
import time
from pathlib import Path

import moderngl
import numpy as np
import pytest

from livemod.dlfl import face_normals, from_polygons, mesh_arrays
from livemod.dlfl.scene import Selection
from livemod.viewer.geometry import build_geometry, crease_shading
from livemod.viewer.headless import Offscreen, framed_camera
from livemod.viewer.hud import hud_lines
from livemod.viewer.measure import WholeMesh, measure_lines, measure_whole
from livemod.viewer.renderer import CORNER_COLOR, PALETTE, SELECTED_COLOR, Style
from livemod.viewer.text import PANEL, QUAD_FLOATS, TEXT, box_quad, glyph_atlas, layout_text
from livemod.viewer.window import ViewOptions, close_viewer, create_viewer, run_frames

from .conftest import OFFSCREEN_SIZE

SIZE = OFFSCREEN_SIZE
FRAMES = 6
BOX_POSITIONS = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
                 (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
BOX_FACES = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3),
             (7, 6, 5, 4)]
MAKERS = ("buffer", "vertex_array", "texture", "framebuffer", "renderbuffer",
          "depth_renderbuffer", "program", "simple_vertex_array")




@pytest.fixture
def made(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """The names of the GL objects made while the test runs (every context)."""
    log: list[str] = []
    for name in MAKERS:
        original = getattr(moderngl.Context, name)

        def counted(self, *args, _original=original, _name=name, **kwargs):
            log.append(_name)
            return _original(self, *args, **kwargs)

        monkeypatch.setattr(moderngl.Context, name, counted)
    return log


def _hud(text: str) -> np.ndarray:
    """A HUD-like panel: a box and one line of ``text`` at its top left."""
    atlas = glyph_atlas()
    return np.concatenate([box_quad(atlas, 4, 4, 150, 22, PANEL),
                           layout_text(atlas, [text], (10, 8), TEXT)])


def _text_pixels(image: np.ndarray) -> np.ndarray:
    """``(H, W)`` bool: pixels of the HUD text colour (drawn over the panel)."""
    colour = np.round(PALETTE[TEXT, :3] * 255)
    return np.abs(image.astype(int) - colour).sum(axis=2) <= 12


def _cube(bad: dict[int, tuple[float, float, float]] | None = None, faces=BOX_FACES):
    arrays = mesh_arrays(from_polygons(BOX_POSITIONS, faces))
    positions = np.array(arrays.positions)
    for vertex, position in (bad or {}).items():
        positions[vertex] = position
    return dataclasses.replace(arrays, positions=positions)


# -- 1. buffers kept between frames ---------------------------------------------------


def test_an_unchanged_hud_makes_no_gl_objects_after_the_first_frame(
        offscreen: Offscreen, made: list[str]) -> None:
    renderer = offscreen.renderer
    renderer.set_mesh(_cube())
    camera, style = framed_camera(renderer.arrays), Style()
    hud = _hud("livemod 12 fps")
    first = offscreen.render(camera, style, hud)
    after_first = len(made)
    frames = [offscreen.render(camera, style, hud) for _ in range(FRAMES)]
    # a HUD laid out again with the same text (a fresh array each frame) is written
    # into the same buffer
    frames += [offscreen.render(camera, style, hud.copy()) for _ in range(FRAMES)]
    assert made[after_first:] == []
    assert _text_pixels(first)[8:24, 10:100].sum() > 40  # the text is drawn
    assert not _text_pixels(first)[40:, :].any()  # and nowhere else
    assert all(np.array_equal(first, frame) for frame in frames)


def test_labels_and_selected_points_make_no_gl_objects_after_the_first_frame(
        offscreen: Offscreen, made: list[str]) -> None:
    renderer = offscreen.renderer
    arrays = _cube()
    renderer.set_mesh(arrays)
    renderer.set_selection(Selection(vertices=(int(arrays.vertex_ids[0]),),
                                     corners=(int(arrays.corner_ids[0]),)))
    camera = framed_camera(arrays)
    # (no vertex labels: the selected vertex's label would be drawn over its point)
    style = Style(labels=frozenset({"faces", "edges"}), point_size=8.0)
    first = offscreen.render(camera, style, _hud("hud"))
    after_first = len(made)
    frames = [offscreen.render(camera, style, _hud("hud")) for _ in range(FRAMES)]
    assert made[after_first:] == []
    assert all(np.array_equal(first, frame) for frame in frames)
    for colour in (SELECTED_COLOR, CORNER_COLOR):  # the vertex's point, the corner's
        rgb = np.round(np.asarray(colour) * 255)
        assert (np.abs(first.astype(int) - rgb).sum(axis=2) <= 12).sum() >= 4


def test_a_longer_hud_grows_its_buffer_in_place_and_a_shorter_one_draws_alone(
        offscreen: Offscreen, made: list[str]) -> None:
    renderer = offscreen.renderer
    renderer.set_mesh(_cube())
    camera, style = framed_camera(renderer.arrays), Style()
    short, long = _hud("short"), _hud("a much longer line of HUD text " * 4)
    assert len(short) < 64 < len(long) <= 128
    alone = offscreen.render(camera, style, short)
    stream = renderer._text_streams[True]
    buffer, vao = stream.buffer, stream.vao
    assert buffer is not None and buffer.size == 64 * QUAD_FLOATS * 4
    before = len(made)
    wide = offscreen.render(camera, style, long)
    assert buffer.size == 128 * QUAD_FLOATS * 4  # grown in place: the same buffer name
    assert stream.buffer is buffer and stream.vao is vao and made[before:] == []
    assert _text_pixels(wide)[:, 100:].any()
    again = offscreen.render(camera, style, short)  # the longer text's rows are not drawn
    assert np.array_equal(alone, again)
    assert offscreen.ctx.error == "GL_NO_ERROR"



def test_release_frees_the_kept_buffers() -> None:
    target = Offscreen(SIZE, samples=0)
    try:
        renderer = target.renderer
        arrays = _cube()
        renderer.set_mesh(arrays)
        renderer.set_selection(Selection(vertices=(int(arrays.vertex_ids[0]),),
                                         corners=(int(arrays.corner_ids[0]),)))
        target.render(framed_camera(arrays), Style(labels=frozenset({"faces"})), _hud("hud"))
        streams = [*renderer._text_streams.values(), *renderer._point_streams.values()]
        objects = [obj for stream in streams for obj in (stream.buffer, stream.vao)]
        assert len(objects) == 8 and None not in objects  # all four were drawn
        renderer.release()
        assert all(isinstance(obj.mglo, moderngl.InvalidObject) for obj in objects)
        assert all(stream.buffer is None and stream.vao is None for stream in streams)
        assert target.ctx.error == "GL_NO_ERROR"
    finally:
        target.release()

# -- 2. positions that are not finite -------------------------------------------------


def test_the_volume_of_a_mesh_with_a_nan_vertex_is_not_measured() -> None:
    whole = measure_whole(_cube({0: (np.nan, 1.0, 1.0)}))
    assert whole == WholeMesh(0, None, 1)
    assert whole.text() == "genus 0  volume n/a, 1 vertex not finite"
    two = measure_whole(_cube({0: (np.nan, 1.0, 1.0), 6: (-np.inf, -1.0, -1.0)}))
    assert two.text() == "genus 0  volume n/a, 2 vertices not finite"
    open_box = measure_whole(_cube({0: (np.nan, 1.0, 1.0)}, faces=BOX_FACES[:5]))
    assert open_box == WholeMesh(0, None) and open_box.text() == "genus 0"  # no volume
    assert measure_whole(_cube()) == WholeMesh(0, pytest.approx(8.0))


def test_measures_of_elements_with_a_nan_vertex_say_they_cannot_be_measured() -> None:
    arrays = _cube({0: (np.nan, 1.0, 1.0), 6: (np.inf, -1.0, -1.0)})
    vid = [int(v) for v in arrays.vertex_ids]
    fid = [int(f) for f in arrays.face_ids]
    assert measure_lines(Selection(faces=(fid[0],)), arrays) == [
        f"face {fid[0]}: 4 sides, area and normal n/a, vertex {vid[0]} not finite"]
    assert measure_lines(Selection(faces=tuple(fid[:3])), arrays) == [
        "3 faces: area n/a, 2 vertices not finite"]
    edge = next(int(arrays.edge_ids[e]) for e in range(len(arrays.edge_ids))
                if 0 in arrays.corner_vertex[arrays.edge_corners[e]])
    line = measure_lines(Selection(edges=(edge,)), arrays)[0]
    assert line.startswith(f"edge {edge}: vertices ")
    assert line.endswith(f", length n/a, vertex {vid[0]} not finite")
    assert measure_lines(Selection(edges=tuple(int(e) for e in arrays.edge_ids)), arrays) == [
        "12 edges: length n/a, 2 vertices not finite"]
    assert measure_lines(Selection(vertices=(vid[0],)), arrays) == [
        f"vertex {vid[0]}: valence 3, position not finite (nan, 1, 1)"]
    assert measure_lines(Selection(vertices=(vid[1], vid[6])), arrays) == [
        f"vertices {vid[1]}-{vid[6]}: distance and delta n/a, vertex {vid[6]} not finite"]
    assert measure_lines(Selection(vertices=tuple(vid[:3])), arrays) == [
        f"3 vertices: extent n/a, vertex {vid[0]} not finite"]
    corner = int(arrays.corner_ids[0])  # at vertex 0
    face = int(arrays.face_ids[arrays.corner_face[0]])
    assert measure_lines(Selection(corners=(corner,)), arrays) == [
        f"corner {corner}: face {face} at vertex {vid[0]}, angle n/a, "
        f"vertex {vid[0]} not finite"]


def test_measures_of_finite_elements_of_that_mesh_are_unchanged() -> None:
    arrays = _cube({0: (np.nan, 1.0, 1.0)})
    bottom = next(f for f in range(len(arrays.face_ids))
                  if 0 not in arrays.corner_vertex[arrays.face_offsets[f]:
                                                  arrays.face_offsets[f + 1]]
                  and np.all(arrays.positions[arrays.corner_vertex[
                      arrays.face_offsets[f]:arrays.face_offsets[f + 1]], 1] == -1))
    fid, v1 = int(arrays.face_ids[bottom]), int(arrays.vertex_ids[1])
    assert measure_lines(Selection(faces=(fid,)), arrays) == [
        f"face {fid}: 4 sides, area 4, normal (0, -1, 0)"]
    assert measure_lines(Selection(vertices=(v1,)), arrays) == [
        f"vertex {v1} at (1, 1, -1), valence 3"]


def test_the_window_hud_says_the_volume_and_the_pick_cannot_be_measured(
        tmp_path: Path) -> None:
    script = tmp_path / "box.py"
    script.write_text("load('cube')\n")
    viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(200, 150),
                                       samples=0, vsync=False, echo=io.StringIO()))
    try:
        deadline = time.monotonic() + 30
        run_frames(viewer, until=lambda v: time.sleep(0.005) or time.monotonic() > deadline
                   or (v.result is not None and not v.waiting and v.result.status == "ok"))
        arrays = _cube({2: (np.nan, 0.0, 0.0)})
        viewer.display.upload(arrays, None, None)
        vertex = int(arrays.vertex_ids[2])
        viewer.set_selection(Selection(vertices=(vertex,)))
        assert viewer.whole.wait(30) == WholeMesh(0, None, 1)
        text = [line for line, _ in hud_lines(viewer.view_state())]
        assert "V 8  E 12  F 6  genus 0  volume n/a, 1 vertex not finite" in text
        assert f"vertex {vertex}: valence 3, position not finite (nan, 0, 0)" in text
        assert not any("nan" in line and "not finite" not in line for line in text)
    finally:
        close_viewer(viewer)


# -- 3. smooth shading next to a vertex that is not finite ------------------------------


@pytest.mark.parametrize("bad", [(np.nan, 1.0, 1.0), (np.inf, 1.0, 1.0)])
def test_smooth_normals_leave_out_the_faces_of_a_vertex_that_is_not_finite(bad) -> None:
    """Before, each finite vertex of a triangle at the bad vertex lost its normal
    (zero), and the faces beside it were shaded as if flat at those corners."""
    clean, arrays = _cube(), _cube({0: bad})
    shading = crease_shading(arrays, crease_angle=180.0)      # no crease: one per vertex
    assert len(shading.positions) == 8
    vertex_of_sector = np.empty(8, dtype=np.int64)
    vertex_of_sector[shading.triangles.ravel()] = build_geometry(arrays).triangles.ravel()
    normals = shading.normals[np.argsort(vertex_of_sector)]
    faces_at_bad = np.isin(np.arange(6), arrays.corner_face[arrays.corner_vertex == 0])
    clean_normals = face_normals(clean)
    for vertex in range(1, 8):
        around = np.unique(arrays.corner_face[arrays.corner_vertex == vertex])
        kept = clean_normals[around[~faces_at_bad[around]]]
        expected = kept.sum(axis=0) / np.linalg.norm(kept.sum(axis=0))
        np.testing.assert_allclose(normals[vertex], expected, atol=1e-6)  # each kept one
    assert normals[0].tolist() == [0.0, 0.0, 0.0]
