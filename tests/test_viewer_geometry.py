"""GL-free parts of the viewer: buffers, camera, text layout, keys, selection echo, HUD."""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from livemod.dlfl import enclosed_volume, from_polygons, mesh_arrays
from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import cube, grid, torus
from livemod.viewer.camera import Camera, bounds_changed_a_lot
from livemod.viewer.controls import (
    KEY_BINDINGS,
    action_for,
    help_lines,
    missing_lines,
    selection_python,
    split_picks,
    toggle_pick,
)
from livemod.viewer.geometry import build_geometry, decode_pick, fan_triangles
from livemod.viewer.hud import hud_lines, run_state, step_line
from livemod.viewer.measure import WholeMesh, WholeMeshMeasurer
from livemod.viewer.text import QUAD_FLOATS, WARN_TEXT, glyph_atlas, layout_labels
from livemod.viewer.view_state import ViewState


def test_fans_cover_every_face_and_skip_holes() -> None:
    arrays = mesh_arrays(grid(3, 2))
    triangles, tri_face, _ = fan_triangles(arrays)
    solid = ~arrays.face_hole
    assert arrays.face_hole.any()
    assert len(triangles) == int((arrays.face_sizes[solid] - 2).sum())
    assert set(tri_face.tolist()) == set(np.flatnonzero(solid).tolist())
    # every triangle's vertices belong to its face
    for (a, b, c), face in zip(triangles.tolist(), tri_face.tolist(), strict=True):
        ring = arrays.corner_vertex[arrays.face_offsets[face]:arrays.face_offsets[face + 1]]
        assert {a, b, c} <= set(ring.tolist())


def test_geometry_of_a_pentagon_and_a_triangle() -> None:
    mesh = from_polygons([(0, 0, 0), (1, 0, 0), (1.5, 1, 0), (0.5, 1.6, 0), (-0.5, 1, 0)],
                         [(0, 1, 2, 3, 4)])
    geometry = build_geometry(mesh_arrays(mesh))
    assert geometry.positions.dtype == np.float32
    assert geometry.triangles.tolist() == [[0, 1, 2], [0, 2, 3], [0, 3, 4]]
    assert geometry.lines.shape == (5, 2)
    np.testing.assert_allclose(geometry.bounds, [[-0.5, 0, 0], [1.5, 1.6, 0]])


def test_pick_ids_decode() -> None:
    assert decode_pick(0) is None
    assert decode_pick((2 << 28) | 13) == (2, 12)


def test_camera_fit_holds_the_bounding_sphere_in_view() -> None:
    camera = Camera(yaw=10, pitch=20)
    bounds = np.array([[-1.0, -2.0, -3.0], [3.0, 2.0, 1.0]])
    camera.fit(bounds)
    corners = np.array([[x, y, z] for x in bounds[:, 0] for y in bounds[:, 1]
                        for z in bounds[:, 2]])
    for yaw in range(0, 360, 30):
        camera.yaw = yaw
        clip = np.c_[corners, np.ones(8)] @ camera.view_projection(1.0).T
        ndc = clip[:, :3] / clip[:, 3:]
        assert np.all(np.abs(ndc) <= 1.0)


def test_camera_orbit_pan_zoom_ortho_presets() -> None:
    camera = Camera()
    camera.fit(np.array([[-1.0, -1, -1], [1, 1, 1]]))
    distance = camera.distance
    camera.zoom(1)
    assert camera.distance == pytest.approx(0.9 * distance)
    camera.orbit(0, 500)
    assert camera.pitch < 90
    camera.preset("top")
    assert camera.eye()[1] > 0.99 * camera.distance
    before = camera.target.copy()
    camera.pan(10, 0, 100)
    assert not np.allclose(before, camera.target)
    camera.ortho = True
    assert camera.projection_matrix(1.5)[3, 3] == 1.0


def test_refit_only_on_big_bounds_changes() -> None:
    unit = np.array([[-1.0, -1, -1], [1, 1, 1]])
    assert bounds_changed_a_lot(None, unit)
    assert not bounds_changed_a_lot(unit, unit * 1.5)
    assert bounds_changed_a_lot(unit, unit * 2.5)
    assert bounds_changed_a_lot(unit, unit * 0.3)
    assert bounds_changed_a_lot(unit, unit + 10)


def test_label_layout_has_one_box_and_one_glyph_per_digit() -> None:
    atlas = glyph_atlas()
    quads = layout_labels(atlas, np.zeros((3, 3)), np.array([0, 7, 1234]), 1,
                          np.array([False, True, False]))
    assert quads.shape == (3 + 1 + 1 + 4, QUAD_FLOATS)
    digits_of_1234 = quads[5:, 7]
    expected = atlas.uv[[ord(c) for c in "1234"], 0]
    np.testing.assert_allclose(digits_of_1234, expected)
    assert quads[1, 12] == 1.0 and quads[0, 12] == 0.0


def test_keys_cover_the_issue_and_are_unique() -> None:
    actions = {b.action for b in KEY_BINDINGS}
    needed = {"toggle_edges", "toggle_vertices", "labels_faces", "labels_edges",
              "labels_vertices", "labels_selected", "toggle_preview", "toggle_ortho",
              "play_pause", "step_forward", "step_back", "run_to_end", "reload",
              "screenshot", "help", "fit", "view_front", "view_top", "view_side", "view_iso",
              "next_pick_mode"}
    assert needed <= actions
    keys = [(b.key, b.modifiers) for b in KEY_BINDINGS]
    assert len(keys) == len(set(keys))
    assert action_for("F", shift=False, ctrl=True) == "labels_faces"
    assert action_for("F", shift=True, ctrl=False) == "pick_face"
    assert action_for("F", shift=False, ctrl=False) == "fit"
    assert len(help_lines()) > len(KEY_BINDINGS)


def test_click_and_shift_click_edit_the_selection() -> None:
    sel = toggle_pick(Selection(edges=(4,)), "face", 12, add=False)
    assert sel == Selection(faces=(12,))
    sel = toggle_pick(sel, "face", 31, add=True)
    assert sel.faces == (12, 31)
    assert toggle_pick(sel, "face", 12, add=True).faces == (31,)


def test_selection_echo_is_python() -> None:
    arrays = mesh_arrays(cube())
    corner = int(arrays.corner_ids[5])
    lines = selection_python(Selection(faces=(12, 31), vertices=(2,), corners=(corner,)),
                             arrays)
    assert lines[0] == "faces(True) == (12, 31)"
    assert lines[1] == "verts(True) == (2,)"
    face = int(arrays.face_ids[arrays.corner_face[5]])
    vertex = int(arrays.vertex_ids[arrays.corner_vertex[5]])
    assert lines[2] == f"corners(True) == (({face}, {vertex}),)"
    assert lines[3] == (f"(headless: livemod run|render|batch SCRIPT --select faces=12,31 "
                        f"--select verts=2 --select corners={corner})")
    assert selection_python(Selection(), arrays) == ["faces(True) == ()"]


def test_picks_the_mesh_lacks_are_told_apart() -> None:
    arrays = mesh_arrays(cube())  # faces 0-5, vertices 0-7
    picked = Selection(faces=(5, 12, 2), edges=(40,), vertices=(7,))
    present, missing = split_picks(picked, arrays)
    assert present == Selection(faces=(5, 2), vertices=(7,))  # in pick order
    assert missing == Selection(faces=(12,), edges=(40,))
    assert missing_lines(missing) == ["picked, not in this mesh: face 12; edge 40"]
    assert missing_lines(Selection(faces=(8, 9), vertices=(20,))) == [
        "picked, not in this mesh: faces 8, 9; vertex 20"]
    assert missing_lines(Selection()) == []
    assert split_picks(picked, None) == (picked, Selection())  # no mesh: nothing to tell


def _result(status: str = "ok", stale: bool = False, step_index: int | None = None):
    steps = tuple(SimpleNamespace(index=i, label=f"op{i}", line=10 + i, counts=(1, 1, 1),
                                  elapsed=0.0) for i in range(3))
    return SimpleNamespace(status=status, stale=stale, steps=steps, step_index=step_index,
                           arrays=mesh_arrays(cube()), elapsed=0.25, error=None, others=None)


def test_hud_shows_state_counts_genus_and_step() -> None:
    assert run_state(None, True) == "running"
    assert run_state(_result(), False, 1.5) == run_state(None, True, 1.5) == "running... 1.5 s"
    assert run_state(_result("error", stale=True), False) == "error, stale"
    assert step_line(_result(step_index=1)) == "step 2/3: op1 (line 11)"
    assert step_line(_result()) == "step 3/3: op2 (line 12)"
    result = _result()
    state = ViewState(script="/x/tower.py", result=result, arrays=result.arrays,
                      whole=WholeMesh(0, 8.0), fps=59.6, selection=("faces(True) == (1,)",))
    text = "\n".join(line for line, _ in hud_lines(state))
    for part in ("tower.py", "ok", "0.250 s", "V 8  E 12  F 6  genus 0  volume 8\n",
                 "step 3/3", "60 fps", "faces(True) == (1,)"):
        assert part in text
    running = "\n".join(line for line, _ in hud_lines(replace(state, working=2.0)))
    assert "running... 2.0 s\n" in running and "0.250 s" not in running  # not the last run's
    missing = hud_lines(replace(state, missing=("picked, not in this mesh: face 12",)))
    assert ("picked, not in this mesh: face 12", WARN_TEXT) in missing
    emptied = hud_lines(replace(state, empty_script="/x/tower.py"))
    assert ("tower.py is empty: showing the last result", WARN_TEXT) in emptied
    hidden = "\n".join(line for line, _ in hud_lines(replace(state, current_hidden=True)))
    assert "volume 8  (hidden: L lists it)" in hidden
    for whole, said in ((None, "genus ...\n"), (WholeMesh(1, None), "genus 1\n"),
                        (WholeMesh(0, -1.5), "genus 0  volume -1.5 (inside out)\n")):
        assert said in "\n".join(line for line, _ in hud_lines(replace(state, whole=whole)))


def test_the_whole_mesh_is_measured_at_once_or_when_large_off_the_main_thread(
        monkeypatch) -> None:
    import livemod.viewer.measure as measure

    measurer = WholeMeshMeasurer()
    try:
        assert measurer.facts() is None  # nothing shown yet
        measurer.measure(mesh_arrays(cube()))
        assert measurer.facts() == WholeMesh(0, pytest.approx(8.0))  # small: at once
        monkeypatch.setattr(measure, "MEASURE_AT_ONCE", 10)  # every mesh is large now
        measurer.measure(mesh_arrays(cube()))
        measurer.measure(mesh_arrays(torus(40, 30)))  # the cube's answer is dropped
        assert measurer.wait(30) == WholeMesh(1, pytest.approx(
            enclosed_volume(mesh_arrays(torus(40, 30)))))
        measurer.measure(mesh_arrays(from_polygons(np.eye(3), [(0, 1, 2)])))  # open
        assert measurer.wait(30) == WholeMesh(0, None)
        measurer.measure(None)
        assert measurer.facts() is None and measurer.wait() is None
    finally:
        measurer.close()


def test_a_background_measurement_that_fails_is_logged_and_says_nothing(
        monkeypatch, caplog) -> None:
    import livemod.viewer.measure as measure

    def broken(arrays):
        raise FloatingPointError("no volume")

    monkeypatch.setattr(measure, "MEASURE_AT_ONCE", 10)
    monkeypatch.setattr(measure, "measure_whole", broken)
    measurer = WholeMeshMeasurer()
    try:
        with caplog.at_level("ERROR", logger="livemod.measure"):
            measurer.measure(mesh_arrays(cube()))
            assert measurer.wait(30) is None
            measurer.close(wait=True)  # the log is written by the done callback
    finally:
        measurer.close()
    assert "measuring the mesh shown failed" in caplog.text and "no volume" in caplog.text


def test_the_help_overlay_fits_the_window_in_columns() -> None:
    from livemod.viewer.hud import hud_quads

    state = ViewState(script="/x/tower.py", waiting=True, hud=False, help=True)
    boxes = {}
    for height in (2000, 800, 400):
        quads = hud_quads(replace(state, size=(1200, height)))
        assert quads[:, 0].min() >= 0 and (quads[:, 1] + quads[:, 6]).max() <= height
        boxes[height] = int((quads[:, 11] == 8).sum())  # one panel box per column
    assert boxes[2000] == 1 and boxes[800] == 2 and boxes[400] >= 3

def test_docs_list_every_key() -> None:
    from pathlib import Path

    doc = (Path(__file__).resolve().parent.parent / "docs" / "viewer.md").read_text()
    for binding in KEY_BINDINGS:
        assert f"`{binding.label()}`" in doc, binding


def test_fit_points_frames_a_whole_turntable_tightly() -> None:
    rng = np.random.default_rng(3)
    points = rng.normal(size=(500, 3)) * [0.3, 3.0, 0.3]   # tall and thin
    yaws = np.arange(0, 360, 30.0)
    for ortho in (False, True):
        camera = Camera(pitch=20, ortho=ortho)
        camera.fit_points(points, 1.5, yaws)
        widest = 0.0
        for yaw in yaws:
            camera.yaw = yaw
            clip = np.c_[points, np.ones(len(points))] @ camera.view_projection(1.5).T
            ndc = np.abs(clip[:, :2] / clip[:, 3:])
            assert ndc.max() <= 1.0
            widest = max(widest, float(ndc.max()))
        assert widest > 0.9   # tight: no loose bounding-sphere margin


def test_guide_lines_grid_spacing_and_axes() -> None:
    from livemod.viewer.renderer import AXIS_COLORS, GRID_COLOR, guide_lines

    bounds = np.array([[-1.0, -2.0, -1.0], [1.0, 3.0, 1.0]])
    (grid, grid_color), *axes = guide_lines(bounds)
    assert grid_color == GRID_COLOR and [color for _, color in axes] == list(AXIS_COLORS)
    assert np.all(grid[:, 1] == -2.0)  # on the ground under the scene
    xs = np.unique(grid[:, 0].round(9))
    step = float(np.diff(xs).min())
    assert step == pytest.approx(0.1)  # size 2 -> 20 cells of 0.1 across it
    assert xs.min() <= -1.0 and xs.max() >= 1.0  # it reaches past the scene
    for k, (ends, _) in enumerate(axes):
        assert ends[0].tolist() == [0.0, 0.0, 0.0]
        assert ends[1][k] == pytest.approx(5.0) and np.count_nonzero(ends[1]) == 1
    big = guide_lines(np.array([[0.0, 0.0, 0.0], [300.0, 1.0, 40.0]]))[0][0]
    assert float(np.diff(np.unique(big[:, 0].round(6))).min()) == pytest.approx(20.0)


def test_vertex_normals_are_unit_sums_of_the_triangles_around() -> None:
    from livemod.dlfl import mesh_arrays
    from livemod.dlfl.shapes import cube
    from livemod.viewer.geometry import build_geometry, vertex_normals

    geometry = build_geometry(mesh_arrays(cube()))
    normals = vertex_normals(geometry.positions, geometry.triangles)
    assert normals.dtype == np.float32 and normals.shape == (8, 3)
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, rtol=1e-6)
    # each corner of the cube points out along its diagonal, up to the fan's
    # uneven split of each square into two triangles
    outward = np.sign(geometry.positions)
    assert np.all(np.sign(normals) == outward)
    lonely = vertex_normals(np.zeros((2, 3)), np.zeros((0, 3), dtype=np.uint32))
    assert np.array_equal(lonely, np.zeros((2, 3), dtype=np.float32))
