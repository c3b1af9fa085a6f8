"""Headless EGL renders (Mesa llvmpipe on CI) with pixel assertions, and ``livemod render``."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import moderngl
import numpy as np
import pytest
from PIL import Image

from livemod.dlfl import from_polygons, mesh_arrays
from livemod.dlfl.arrays import concatenate_arrays
from livemod.dlfl.rind import crust
from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import cube, tetrahedron
from livemod.dlfl.subdivision.smooth import catmull_clark
from livemod.viewer.camera import Camera
from livemod.viewer.cli import main
from livemod.viewer.headless import Offscreen, camera_framing, framed_camera, render_turntable
from livemod.viewer.id_pass import nearest_corner
from livemod.viewer.renderer import (
    BASE_COLOR,
    OTHER_COLOR,
    Renderer,
    Style,
)
from tests.images import read_image

from .conftest import OFFSCREEN_SIZE
from .viewer_support import cube_with, gl_objects

SIZE = OFFSCREEN_SIZE
BACKGROUND = np.array([round(0.16 * 255), round(0.17 * 255), round(0.19 * 255)])

CUBE_POSITIONS = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
                  (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
CUBE_FACES = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3), (7, 6, 5, 4)]

CUBE_SCRIPT = """
from livemod.dlfl import from_polygons, current_scene
P = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
     (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
F = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3), (7, 6, 5, 4)]
current_scene().add(from_polygons(P, F))
"""




def _mask(image: np.ndarray) -> np.ndarray:
    """``(H, W)`` bool: pixels that are not background."""
    return np.abs(image.astype(int) - BACKGROUND).sum(axis=2) > 6


def test_cube_covers_the_middle_of_the_frame(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    image = offscreen.render(framed_camera(arrays), Style())
    mask = _mask(image)
    assert image.shape == (SIZE[1], SIZE[0], 3)
    assert 0.2 < mask.mean() < 0.8
    assert mask[SIZE[1] // 2, SIZE[0] // 2]
    assert not mask[0, 0] and not mask[-1, -1]
    rows, cols = np.nonzero(mask)
    assert rows.min() > 0 and rows.max() < SIZE[1] - 1  # framed, not clipped


def test_front_view_ortho_cube_is_a_centred_square(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    mask = _mask(offscreen.render(camera, Style(edges=False)))
    rows, cols = np.nonzero(mask)
    height, width = np.ptp(rows) + 1, np.ptp(cols) + 1
    assert abs(height - width) <= 2
    assert abs((rows.min() + rows.max()) / 2 - SIZE[1] / 2) <= 2
    assert mask[rows.min():rows.max() + 1, cols.min():cols.max() + 1].mean() > 0.98


def test_hole_faces_are_not_drawn(offscreen: Offscreen) -> None:
    """An open box seen from above shows the inside of its bottom through the hole."""
    box = from_polygons(CUBE_POSITIONS, CUBE_FACES[1:])  # no top face: it becomes a hole
    arrays = mesh_arrays(box)
    assert arrays.face_hole.sum() == 1
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=89.0, yaw=0.0)
    hit = offscreen.renderer.pick(camera, SIZE, SIZE[0] // 2, SIZE[1] // 2, "face")
    assert hit is not None and not arrays.face_hole[hit.dense_index]
    bottom = arrays.positions[arrays.corner_vertex[
        arrays.face_offsets[hit.dense_index]:arrays.face_offsets[hit.dense_index + 1]]]
    np.testing.assert_allclose(bottom[:, 1], -1.0)
    inside = offscreen.render(camera, Style(edges=False))[SIZE[1] // 2, SIZE[0] // 2]
    assert inside[2] > inside[0]  # the bluish back side, not the orange front


def test_pick_reads_back_the_face_under_the_pixel(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0)
    hit = offscreen.renderer.pick(camera, SIZE, SIZE[0] // 2, SIZE[1] // 2, "face")
    assert hit is not None and hit.kind == "face"
    normal_z = [arrays.positions[arrays.corner_vertex[arrays.face_offsets[f]:
                                                     arrays.face_offsets[f + 1]], 2]
                for f in range(len(arrays.face_ids))]
    front = [f for f, z in enumerate(normal_z) if np.allclose(z, 1.0)]
    assert hit.dense_index == front[0]
    assert hit.element_id == int(arrays.face_ids[front[0]])
    assert offscreen.renderer.pick(camera, SIZE, 1, 1, "face") is None


def test_pick_edges_vertices_and_corners(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    mask = _mask(offscreen.render(camera, Style(edges=False)))
    rows, cols = np.nonzero(mask)
    top, left = int(rows.min()), int(cols.min())
    vertex = offscreen.renderer.pick(camera, SIZE, left + 2, top + 2, "vertex")
    assert vertex is not None
    np.testing.assert_allclose(arrays.positions[vertex.dense_index][:2], [-1, 1])
    edge = offscreen.renderer.pick(camera, SIZE, SIZE[0] // 2, top + 1, "edge")
    assert edge is not None
    ends = arrays.positions[arrays.edge_vertices[edge.dense_index]]
    np.testing.assert_allclose(ends[:, 1], [1, 1])
    corner = offscreen.renderer.pick(camera, SIZE, left + 5, top + 5, "corner")
    assert corner is not None
    np.testing.assert_allclose(
        arrays.positions[arrays.corner_vertex[corner.dense_index]], [-1, 1, 1])


def test_selection_and_labels_change_the_image(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays)
    plain = offscreen.render(camera, Style())
    front = offscreen.renderer.pick(camera, SIZE, SIZE[0] // 2, SIZE[1] // 2, "face")
    assert front is not None
    offscreen.renderer.set_selection(Selection(faces=(front.element_id,)))
    selected = offscreen.render(camera, Style())
    assert (selected != plain).any(axis=2).mean() > 0.05
    green = selected[SIZE[1] // 2, SIZE[0] // 2]
    assert green[1] > green[0] and green[1] > green[2]
    labelled = offscreen.render(camera, Style(labels=frozenset({"faces"})))
    assert (labelled != selected).any()
    only_selected = offscreen.render(camera, Style(labels=frozenset({"faces"}),
                                                   labels_selected_only=True))
    assert (only_selected != labelled).any() and (only_selected != selected).any()
    offscreen.renderer.set_selection(Selection())


def test_patch_preview_replaces_the_faces(offscreen: Offscreen) -> None:
    from livemod.runner.preview import preview_arrays

    mesh = cube()
    arrays, preview = mesh_arrays(mesh), preview_arrays(mesh)
    assert preview is not None
    offscreen.renderer.set_mesh(arrays, preview)
    camera = framed_camera(arrays)
    plain = offscreen.render(camera, Style())
    smooth = offscreen.render(camera, Style(preview=True))
    centre = smooth[SIZE[1] // 2, SIZE[0] // 2].astype(int)
    assert centre[2] > centre[0]                       # the preview's blue, not orange
    assert _mask(smooth).mean() < _mask(plain).mean()  # smoothed inside the cage


def _kinks(image: np.ndarray, inside: np.ndarray) -> float:
    """The share of pixels well inside ``inside`` where the brightness bends
    sharply (a second difference, across or down, above 6 levels): the seams of
    facets; smooth shading bends gently."""
    light = image.astype(int).sum(axis=2)
    core = inside.copy()
    for axis in (0, 1):
        for shift in (-2, -1, 1, 2):
            core &= np.roll(inside, shift, axis=axis)
    bend = np.maximum(np.abs(np.roll(light, 1, 0) - 2 * light + np.roll(light, -1, 0)),
                      np.abs(np.roll(light, 1, 1) - 2 * light + np.roll(light, -1, 1)))
    return float((bend[core] > 18).mean())


def test_the_patch_preview_is_drawn_smooth_with_its_own_normals(offscreen: Offscreen) -> None:
    from livemod.runner.preview import PreviewRequest, make_preview

    arrays = mesh_arrays(cube())
    made = make_preview(PreviewRequest((arrays,)))
    camera = framed_camera(arrays)
    offscreen.renderer.set_mesh(arrays, made)
    smooth = offscreen.render(camera, Style(preview=True, edges=False))
    flat_normals = dataclasses.replace(made, surface=dataclasses.replace(
        made.surface, normals=np.zeros_like(made.surface.normals)))
    offscreen.renderer.set_preview(flat_normals)
    faceted = offscreen.render(camera, Style(preview=True, edges=False))
    inside = _mask(smooth)
    assert np.array_equal(inside, _mask(faceted))         # the same surface
    assert _kinks(faceted, inside) > 0.1                   # its facets' seams
    assert _kinks(smooth, inside) < 0.01
    centre = smooth[SIZE[1] // 2, SIZE[0] // 2].astype(int)
    assert centre[2] > centre[0]                           # the preview's blue


def test_the_preview_draws_the_other_objects_parts_in_their_colour(
        offscreen: Offscreen) -> None:
    from livemod.runner.preview import PreviewRequest, make_preview

    current = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES))
    other = mesh_arrays(from_polygons(np.array(CUBE_POSITIONS) + [3.0, 0.0, 0.0], CUBE_FACES))
    made = make_preview(PreviewRequest((current, other)))
    assert len(made.parts) == 2 and made.closed
    offscreen.renderer.set_mesh(current, made, other)
    camera = framed_camera(concatenate_arrays([current, other]), elevation=0.0, yaw=0.0)
    picture = offscreen.render(camera, Style(preview=True, edges=False))
    plain = offscreen.render(camera, Style(edges=False))
    right = slice(SIZE[0] // 2 + 8, SIZE[0])
    # the other cube is smoothed too (rounder: fewer pixels), in the muted colour
    assert _mask(picture)[:, right].sum() < 0.95 * _mask(plain)[:, right].sum()
    shown = picture[:, right][_mask(picture)[:, right]].astype(int)
    assert (shown[:, 0] > shown[:, 2]).mean() > 0.9       # warm (others), not the blue


def test_turntable_frames_differ_and_frame_zero_is_stable(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=20.0)
    frames = render_turntable(offscreen, camera, Style(), 3)  # 120 degrees apart
    assert all((frames[i] != frames[i + 1]).any() for i in range(2))
    first = []
    for _ in range(2):   # two separate contexts, as two runs of ``livemod render``
        fresh = Offscreen(SIZE, samples=4)
        try:
            fresh.renderer.set_mesh(arrays)
            first.append(render_turntable(fresh, camera, Style(), 3)[0])
        finally:
            fresh.release()
    assert np.array_equal(first[0], first[1])


def test_render_command_writes_png_gif_and_sequence(tmp_path: Path, capsys) -> None:
    script = tmp_path / "cube.py"
    script.write_text(CUBE_SCRIPT)
    png = tmp_path / "one.png"
    assert main(["render", str(script), "-o", str(png), "--size", "96x64", "--labels"]) == 0
    with Image.open(png) as picture:
        assert picture.size == (96, 64)
    gif = tmp_path / "turn.gif"
    assert main(["render", str(script), "-o", str(gif), "--size", "64x64",
                 "--turntable", "3", "--elevation", "30"]) == 0
    with Image.open(gif) as animation:
        assert animation.n_frames == 3
    again = tmp_path / "again.gif"
    assert main(["render", str(script), "-o", str(again), "--size", "64x64",
                 "--turntable", "3", "--elevation", "30"]) == 0
    assert again.read_bytes() == gif.read_bytes()   # deterministic output
    assert "3/3" in capsys.readouterr().err
    assert main(["render", str(script), "-o", str(tmp_path / "seq"), "--size", "32x32",
                 "--turntable", "2"]) == 0
    assert sorted(p.name for p in (tmp_path / "seq").iterdir()) == [
        "frame_000.png", "frame_001.png"]


def test_render_command_writes_mp4_and_webp_turntables(tmp_path: Path, capsys) -> None:
    import av

    movie, webp = tmp_path / "turn.mp4", tmp_path / "turn.webp"
    for out in (movie, webp):
        assert main(["render", "cube", "-o", str(out), "--size", "64x48", "--turntable", "4",
                     "--fps", "12.5"]) == 0
    with av.open(str(movie)) as container:
        stream = container.streams.video[0]
        frames = [f.to_ndarray(format="rgb24") for f in container.decode(stream)]
        assert stream.average_rate == 12.5
    with Image.open(webp) as animation:
        assert animation.n_frames == 4
        pictures = []
        for k in range(4):
            animation.seek(k)
            pictures.append(np.asarray(animation.convert("RGB")))
        assert animation.info["duration"] == 80
    assert len(frames) == 4 and frames[0].shape == (48, 64, 3)
    for lossy, exact in zip(frames, pictures, strict=True):  # the same turntable
        assert np.abs(lossy.astype(int) - exact).mean() < 6.0
    assert not np.array_equal(pictures[0], pictures[1])  # and it turns
    assert capsys.readouterr().out.startswith("wrote ")


def test_render_writes_a_gif_asked_above_50_fps_at_50_with_a_note(tmp_path: Path,
                                                                   capsys) -> None:
    gif = tmp_path / "fast.gif"
    assert main(["render", "cube", "-o", str(gif), "--size", "32x32", "--turntable", "3",
                 "--fps", "60"]) == 0
    assert capsys.readouterr().err.startswith(
        "livemod: note: a GIF plays at most 50 frames per second (its delays are whole "
        "hundredths of a second, and viewers slow shorter ones to a tenth); writing "
        f"{gif} at 50 fps, not 60 (.webp or .mp4 play at 60)\n")
    with Image.open(gif) as animation:
        durations = []
        for k in range(animation.n_frames):
            animation.seek(k)
            durations.append(animation.info["duration"])
    assert durations == [20, 20, 20]


def test_render_of_a_script_that_leaves_no_mesh_warns(tmp_path: Path, capsys) -> None:
    script = tmp_path / "nothing.py"
    script.write_text("x = 1\n")
    out = tmp_path / "empty.png"
    assert main(["render", str(script), "-o", str(out), "--size", "32x24"]) == 0
    assert "nothing.py left no mesh; the picture shows an empty scene" in capsys.readouterr().err
    image = read_image(out)
    assert (image == image[0, 0]).all()  # the background only


def test_render_command_reports_script_errors(tmp_path: Path, capsys) -> None:
    script = tmp_path / "bad.py"
    script.write_text("x = 1\nraise ValueError('no mesh today')\n")
    assert main(["render", str(script), "-o", str(tmp_path / "x.png")]) == 1
    err = capsys.readouterr().err
    assert "bad.py:2" in err and "no mesh today" in err


def test_render_command_runs_the_script_with_the_selection(tmp_path: Path, capsys) -> None:
    script = tmp_path / "longer.py"
    # a picked face is pulled out three sizes of the cube: another shape in the frame
    script.write_text("load('cube')\nfor f in faces(True):\n    extrude('cubical', f, 3.0)\n")
    plain, moved = tmp_path / "plain.png", tmp_path / "moved.png"
    assert main(["render", str(script), "-o", str(plain), "--size", "48x48"]) == 0
    assert ("livemod: note: faces(True) found nothing selected, so the script got none; "
            "give --select faces=ID,...") in capsys.readouterr().err
    assert main(["render", str(script), "-o", str(moved), "--size", "48x48",
                 "--select", "faces=0,77"]) == 0
    assert plain.read_bytes() != moved.read_bytes()
    err = capsys.readouterr().err
    assert "the mesh had no faces 77 when" in err and "nothing selected" not in err
    assert main(["render", "cube", "-o", str(plain), "--select", "faces=0"]) == 2
    assert "--select needs a script, not 'cube'" in capsys.readouterr().err


def test_render_refuses_a_bad_output_before_the_script_runs(tmp_path: Path, capsys) -> None:
    marker = tmp_path / "ran"
    script = tmp_path / "slow.py"
    script.write_text(f"open({str(marker)!r}, 'w').close()\n" + CUBE_SCRIPT)
    assert main(["render", str(script), "-o", str(tmp_path / "x.foo")]) == 2
    assert main(["render", str(script), "-o", str(tmp_path / "t.png"), "--turntable", "3"]) == 2
    err = capsys.readouterr().err
    assert "give a .png, .gif, .webp or .mp4 name" in err
    assert "3 frames cannot go to one PNG" in err
    assert main(["render", str(script), "-o", str(tmp_path / "t.mp4"), "--size", "65x48",
                 "--turntable", "2"]) == 2
    assert main(["render", str(script), "-o", str(tmp_path / "t.gif"), "--fps", "0",
                 "--turntable", "2"]) == 2
    err = capsys.readouterr().err
    assert "MP4 needs an even width and height, got 65x48; try 66x48" in err
    assert "frames per second must be a positive number, got 0.0" in err
    assert main(["render", str(script), "-o", str(tmp_path / "y.png"), "--samples", "3"]) == 2
    assert main(["render", str(script), "-o", str(tmp_path / "y.png"), "--size", "99999x9"]) == 2
    err = capsys.readouterr().err
    assert "--samples 3: this GL takes 0, 2" in err and "is larger than this GL's largest" in err
    assert not marker.exists()  # the GL checks too came before the script
    assert sorted(p.name for p in tmp_path.iterdir()) == ["slow.py"]  # no image


def test_no_egl_is_one_line_naming_what_to_install(monkeypatch, tmp_path: Path, capsys) -> None:
    import moderngl

    def no_egl(**options: object) -> None:
        raise Exception("libEGL.so: cannot open shared object file")

    monkeypatch.setattr(moderngl, "create_standalone_context", no_egl)
    # the machine's fault, not the command line's: 1, as `view` without a display
    assert main(["render", "cube", "-o", str(tmp_path / "c.png")]) == 1
    err = capsys.readouterr().err
    assert err.startswith("livemod: error: no offscreen GL 3.3 context over EGL (libEGL.so: ")
    assert "apt-get install libegl1 libegl-mesa0" in err


def test_view_command_refuses_a_missing_script(tmp_path: Path, capsys) -> None:
    assert main(["view", str(tmp_path / "missing.py")]) == 1
    assert "missing.py" in capsys.readouterr().err


def _moved(arrays, dx: float):  # type: ignore[no-untyped-def]
    """``arrays`` with every position shifted by ``dx`` along x."""
    import dataclasses

    return dataclasses.replace(arrays, positions=arrays.positions + [dx, 0.0, 0.0])


def test_other_objects_are_drawn_framed_and_hide_but_are_never_picked(
        offscreen: Offscreen) -> None:
    current, other = mesh_arrays(cube()), _moved(mesh_arrays(cube()), -4.0)
    offscreen.renderer.set_mesh(current, None, other)
    both = framed_camera(concatenate_arrays([current, other]), elevation=0.0, yaw=0.0,
                         ortho=True)
    image = offscreen.render(both, Style(edges=False))
    y = SIZE[1] // 2
    (a, b), (c, d) = _runs(_mask(image)[y])  # the two cubes, the other on the left (-x)
    assert not np.array_equal(image[y, (a + b) // 2], image[y, (c + d) // 2])  # muted colour
    assert offscreen.renderer.pick(both, SIZE, (a + b) // 2, y, "face") is None
    hit = offscreen.renderer.pick(both, SIZE, (c + d) // 2, y, "face")
    assert hit is not None and hit.kind == "face"
    # seen from -x, the other cube stands in front of the current one: no pick
    behind = framed_camera(concatenate_arrays([current, other]), elevation=0.0, yaw=-90.0,
                           ortho=True)
    assert offscreen.renderer.pick(behind, SIZE, SIZE[0] // 2, SIZE[1] // 2, "face") is None
    offscreen.renderer.set_mesh(current)
    assert offscreen.renderer.pick(behind, SIZE, SIZE[0] // 2, SIZE[1] // 2, "face") is not None


def test_render_draws_every_object_of_the_scene(tmp_path: Path) -> None:
    script = tmp_path / "two.py"
    script.write_text("load('cube')\nload('cube')\ntranslate(5, 0, 0)\n")
    one = tmp_path / "one.py"
    one.write_text("load('cube')\ntranslate(5, 0, 0)\n")
    for path in (script, one):
        assert main(["render", str(path), "-o", str(tmp_path / f"{path.stem}.png"),
                     "--size", "160x120", "--elevation", "0"]) == 0
    two_mask = _mask(read_image(tmp_path / "two.png", "RGB"))
    one_mask = _mask(read_image(tmp_path / "one.png", "RGB"))
    # two cubes side by side, framed together, against the one cube alone
    assert len(_runs(two_mask[60])) == 2 and len(_runs(one_mask[60])) == 1


def _runs(row: np.ndarray) -> list[tuple[int, int]]:
    """The ``(start, stop)`` runs of True in a ``(W,)`` bool row."""
    edges = np.flatnonzero(np.diff(np.concatenate([[0], row.astype(int), [0]])))
    return list(zip(edges[::2].tolist(), edges[1::2].tolist(), strict=True))


def test_a_target_renders_the_same_after_other_contexts_come_and_go(
        offscreen: Offscreen) -> None:
    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays)
    before = offscreen.render(camera, Style())
    with pytest.raises(ValueError, match="--samples 3"):
        Offscreen(SIZE, samples=3)
    other = Offscreen(SIZE, samples=0)
    other.release()
    assert np.array_equal(offscreen.render(camera, Style()), before)


def test_grid_and_axes_show_when_asked_and_are_never_picked(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=30.0)
    camera.distance *= 2.5  # room around the cube for the grid
    plain = _mask(offscreen.render(camera, Style()))
    guided = _mask(offscreen.render(camera, Style(grid=True)))
    extra = guided & ~plain
    assert extra.sum() > 200 and not (plain & ~guided).any()
    rows, cols = np.nonzero(extra)
    assert offscreen.renderer.pick(camera, SIZE, int(cols[0]), int(rows[0]), "face") is None


def test_hidden_other_objects_are_not_drawn_nor_in_the_way(offscreen: Offscreen) -> None:
    current, other = mesh_arrays(cube()), _moved(mesh_arrays(cube()), -4.0)
    offscreen.renderer.set_mesh(current, None, other)
    behind = framed_camera(concatenate_arrays([current, other]), elevation=0.0, yaw=-90.0,
                           ortho=True)
    shown = offscreen.render(behind, Style())
    assert offscreen.renderer.pick(behind, SIZE, SIZE[0] // 2, SIZE[1] // 2, "face") is None
    hidden = offscreen.render(behind, Style(others=False))
    assert not np.array_equal(shown, hidden)
    assert offscreen.renderer.pick(behind, SIZE, SIZE[0] // 2, SIZE[1] // 2, "face") is not None


def test_render_on_a_light_background(tmp_path: Path) -> None:
    out = tmp_path / "light.png"
    assert main(["render", "cube", "-o", str(out), "--size", "64x48", "--background",
                 "light"]) == 0
    image = read_image(out, "RGB")
    assert image[0, 0].tolist() == [round(0.93 * 255)] * 2 + [round(0.92 * 255)]
    assert np.abs(image[24, 32].astype(int) - image[0, 0]).sum() > 60  # the cube is there


def test_smooth_shading_changes_the_faces_not_the_picks(offscreen: Offscreen) -> None:
    from livemod.dlfl.shapes import torus

    arrays = mesh_arrays(torus(16, 12))
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=40.0)
    flat = offscreen.render(camera, Style(edges=False))
    smooth = offscreen.render(camera, Style(edges=False, smooth=True))
    assert np.array_equal(_mask(flat), _mask(smooth))  # the same silhouette
    assert (np.abs(flat.astype(int) - smooth.astype(int)).sum(axis=2) > 6).mean() > 0.05
    hit = offscreen.renderer.pick(camera, SIZE, SIZE[0] // 2, SIZE[1] // 4, "face")
    offscreen.render(camera, Style(smooth=True))
    again = offscreen.renderer.pick(camera, SIZE, SIZE[0] // 2, SIZE[1] // 4, "face")
    assert hit is not None and again == hit


def test_smooth_shading_keeps_the_edges_sharper_than_the_crease_angle(
        offscreen: Offscreen) -> None:
    from livemod.dlfl.shapes import soccer_ball
    from livemod.dlfl.subdivision import subdivide

    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays)
    flat = offscreen.render(camera, Style(edges=False))
    creased = offscreen.render(camera, Style(edges=False, smooth=True))
    assert np.abs(flat.astype(int) - creased.astype(int)).max() <= 2   # 90 > 45 degrees
    rounded = offscreen.render(camera, Style(edges=False, smooth=True, crease_angle=91.0))
    assert np.abs(flat.astype(int) - rounded.astype(int)).max() > 40
    ball = soccer_ball()
    subdivide(ball, "catmull-clark")
    arrays = mesh_arrays(ball)
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays)
    faceted = offscreen.render(camera, Style(edges=False))
    smooth = offscreen.render(camera, Style(edges=False, smooth=True))
    inside = _mask(smooth)
    assert _kinks(smooth, inside) < 0.3 * _kinks(faceted, inside)


def test_render_on_a_transparent_background_writes_alpha(tmp_path: Path, capsys) -> None:
    out = tmp_path / "clear.png"
    assert main(["render", "cube", "-o", str(out), "--size", "64x48", "--background",
                 "transparent"]) == 0
    image = read_image(out)
    assert image.shape == (48, 64, 4)
    assert image[0, 0, 3] == 0 and image[24, 32, 3] == 255
    webp = tmp_path / "clear.webp"
    assert main(["render", "cube", "-o", str(webp), "--size", "64x48", "--background",
                 "transparent"]) == 0
    assert np.array_equal(read_image(webp, "RGBA"), image)  # lossless
    assert main(["render", "cube", "-o", str(tmp_path / "t.gif"), "--turntable", "2",
                 "--background", "transparent"]) == 2
    assert ("a transparent background needs PNG or WebP output, not "
            f"'{tmp_path / 't.gif'}' (a GIF cannot hold soft edges)") in capsys.readouterr().err
    assert not (tmp_path / "t.gif").exists()


def _face_at_z(arrays, z: float) -> int:
    """Dense index of the cube face whose corners all lie at ``z``."""
    for f in range(len(arrays.face_ids)):
        ring = arrays.positions[arrays.corner_vertex[arrays.face_offsets[f]:
                                                     arrays.face_offsets[f + 1]]]
        if np.allclose(ring[:, 2], z):
            return f
    raise AssertionError(f"no face at z={z}")


def _tones(pixels: np.ndarray, color) -> np.ndarray:
    """``(n,)`` brightness of each ``(n, 3)`` pixel as a multiple of ``color``, NaN
    where the pixel is not a shade of that colour (the cap is drawn flat)."""
    rgb = np.asarray(color) * 255
    k = pixels.astype(float) @ rgb / (rgb @ rgb)
    off = np.abs(pixels - k[:, None] * rgb).max(axis=1)
    return np.where(off <= 3.0, k, np.nan)


def _assert_hatched_cap(pixels: np.ndarray, color) -> None:
    """``pixels`` are the section cap of a mesh drawn in ``color``: flat 0.72 of it,
    with hatch lines at 0.55 of that."""
    tones = _tones(pixels.reshape(-1, 3), color)
    assert not np.isnan(tones).any()
    assert np.nanmax(tones) == pytest.approx(0.72, abs=0.01)
    assert np.nanmin(tones) < 0.66  # a hatch line (0.55 of the tone) crosses the region


def test_a_section_caps_a_closed_mesh_and_the_cap_is_not_picked(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES))
    offscreen.renderer.set_mesh(arrays)
    # from +z, looking down -z; orthographic, so the cut cube has the same outline
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    middle = (SIZE[1] // 2, SIZE[0] // 2)
    whole = offscreen.render(camera, Style(edges=False))
    cut = offscreen.render(camera, Style(edges=False, section=(2, 0.0)))
    assert np.array_equal(_mask(cut), _mask(whole))  # the same outline, now the cap
    rows, cols = np.nonzero(_mask(cut))
    inner = cut[rows.min() + 2:rows.max() - 1, cols.min() + 2:cols.max() - 1]
    _assert_hatched_cap(inner, BASE_COLOR)
    assert np.isnan(_tones(whole[middle][None], BASE_COLOR)).all()  # the lit top is no cap
    assert offscreen.renderer.pick(camera, SIZE, middle[1], middle[0], "face") is None
    offscreen.render(camera, Style(edges=False))  # no section: the front face again
    hit = offscreen.renderer.pick(camera, SIZE, middle[1], middle[0], "face")
    assert hit is not None and hit.dense_index == _face_at_z(arrays, 1.0)
    gone = offscreen.render(camera, Style(edges=False, section=(2, -1.5)))
    assert not _mask(gone).any()  # the plane behind the whole cube: nothing is left


def test_a_cut_crust_shows_its_wall_as_cap_and_its_cavity_as_faces(offscreen: Offscreen) -> None:
    mesh = from_polygons(CUBE_POSITIONS, CUBE_FACES)
    crust(mesh, 0.5)  # a cube of side 2 around a cavity of side 1
    arrays = mesh_arrays(mesh)
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    cut = offscreen.render(camera, Style(edges=False, section=(2, 0.0)))
    rows, cols = np.nonzero(_mask(cut))
    top, left = rows.min(), cols.min()
    side = rows.max() - top + 1  # the outer square; the cavity is its middle half
    wall = cut[top + 2:top + side // 4 - 2, left + 2:left + side - 2]
    _assert_hatched_cap(wall, BASE_COLOR)
    middle = (top + side // 2, left + side // 2)
    assert np.isnan(_tones(cut[middle][None], BASE_COLOR)).all()  # a lit face, no cap
    hit = offscreen.renderer.pick(camera, SIZE, middle[1], middle[0], "face")
    assert hit is not None  # the cavity's floor, a face of the inner shell at z = -0.5
    assert hit.dense_index == _face_at_z(arrays, -0.5)


def test_the_cap_hides_what_lies_behind_it(offscreen: Offscreen) -> None:
    """The cap is drawn at the plane's depth: a small cube inside the cut one (another
    object, so not part of its parity) and a vertex on the far face both lie behind it."""
    outer = from_polygons(CUBE_POSITIONS, CUBE_FACES)
    catmull_clark(outer)  # a vertex at the middle of the bottom face, (0, 0, -1)
    inner = from_polygons(np.asarray(CUBE_POSITIONS) * 0.25 + (0.0, 0.0, -0.5), CUBE_FACES)
    arrays, others = mesh_arrays(outer), mesh_arrays(inner)
    offscreen.renderer.set_mesh(arrays, others=others)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    middle = (slice(SIZE[1] // 2 - 5, SIZE[1] // 2 + 5), slice(SIZE[0] // 2 - 5, SIZE[0] // 2 + 5))
    whole = offscreen.render(camera, Style(edges=False, vertices=True))
    assert np.isnan(_tones(whole[middle].reshape(-1, 3), BASE_COLOR)).all()  # lit, a point
    cut = offscreen.render(camera, Style(edges=False, vertices=True, section=(2, 0.0)))
    _assert_hatched_cap(cut[middle], BASE_COLOR)  # no yellow point, no small cube


def test_overlapping_parts_of_one_mesh_are_capped_as_their_union(offscreen: Offscreen) -> None:
    """Two cubes of one mesh that overlap (x in [-1, 1] and [0, 2]): the cap counts the
    winding, so where both enclose the plane (x in [0, 1]) it is capped too, and so is
    an inside-out mesh (winding -1)."""
    positions = np.concatenate([CUBE_POSITIONS, np.asarray(CUBE_POSITIONS) + (1.0, 0.0, 0.0)])
    faces = CUBE_FACES + [tuple(v + 8 for v in face) for face in CUBE_FACES]
    flipped = [face[::-1] for face in CUBE_FACES]
    for mesh in (from_polygons(positions, faces), from_polygons(CUBE_POSITIONS, flipped)):
        arrays = mesh_arrays(mesh)
        offscreen.renderer.set_mesh(arrays)
        camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
        cut = offscreen.render(camera, Style(edges=False, section=(2, 0.0)))
        rows, cols = np.nonzero(_mask(cut))
        _assert_hatched_cap(cut[rows.min() + 2:rows.max() - 1, cols.min() + 2:cols.max() - 1],
                            BASE_COLOR)


def test_an_open_mesh_is_cut_but_not_capped(offscreen: Offscreen) -> None:
    """A mesh with a hole has no inside to cap: its back faces show through the cut."""
    arrays = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES[1:]))  # no top face
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    middle = (SIZE[1] // 2, SIZE[0] // 2)
    cut = offscreen.render(camera, Style(edges=False, section=(2, 0.0)))
    assert cut[middle][2] > cut[middle][0]  # the back of the far face, bluish
    hit = offscreen.renderer.pick(camera, SIZE, middle[1], middle[0], "face")
    assert hit is not None and hit.dense_index == _face_at_z(arrays, -1.0)


def test_the_other_objects_are_capped_in_their_own_colour(offscreen: Offscreen) -> None:
    current = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES))
    other = mesh_arrays(from_polygons(np.asarray(CUBE_POSITIONS) + (3.0, 0.0, 0.0),
                                      CUBE_FACES))
    offscreen.renderer.set_mesh(current, others=other)
    camera = framed_camera(concatenate_arrays([current, other]), elevation=0.0, yaw=0.0,
                           ortho=True)
    image = offscreen.render(camera, Style(edges=False, section=(2, 0.0)))
    mask = _mask(image)
    rows, cols = np.nonzero(mask)
    gap = np.flatnonzero(~mask[(rows.min() + rows.max()) // 2, cols.min():cols.max()])
    left, right = cols.min() + gap.min(), cols.min() + gap.max()  # the gap between them
    band = slice(rows.min() + 2, rows.max() - 1)
    _assert_hatched_cap(image[band, cols.min() + 2:left - 2], BASE_COLOR)
    _assert_hatched_cap(image[band, right + 3:cols.max() - 1], OTHER_COLOR)


def test_a_section_leaves_out_the_labels_of_what_it_cut_away(offscreen: Offscreen) -> None:
    arrays = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES))
    offscreen.renderer.set_mesh(arrays)
    renderer = offscreen.renderer

    def labelled(section) -> int:
        quads = renderer._label_quads(Style(labels=frozenset({"faces"}), section=section))
        return len({tuple(anchor) for anchor in quads[:, :3].tolist()})

    # face centroids: one at x=-1, four at x=0, one at x=+1
    assert (labelled(None), labelled((0, 0.0)), labelled((0, -0.5))) == (6, 5, 1)


def test_labels_of_anchors_prepared_off_the_thread_are_those_made_on_it(
        offscreen: Offscreen) -> None:
    from livemod.dlfl.shapes import grid
    from livemod.viewer.geometry import prepare_meshes

    arrays = mesh_arrays(grid(30, 20))                 # 600 faces and a hole
    renderer = offscreen.renderer
    selection = Selection(faces=(3, 40, 200), edges=(7, 300), vertices=(5,))
    kinds = frozenset({"faces", "edges", "vertices"})
    view = framed_camera(arrays, elevation=60.0).view_projection(SIZE[0] / SIZE[1])
    styles = [Style(labels=kinds, labels_selected_only=only, section=section)
              for only in (False, True) for section in (None, (0, 0.1))]

    def laid_out() -> list[np.ndarray]:
        renderer.set_selection(selection)
        return [renderer._label_quads(style, at) for style in styles for at in (None, view)]

    renderer.set_mesh(arrays)                          # anchors made on the thread
    made_here = laid_out()
    renderer.stage(arrays, None, None, prepare_meshes(arrays, labels=kinds))
    renderer.advance(math.inf)
    prepared = laid_out()
    assert [len(quads) for quads in made_here] == [len(quads) for quads in prepared]
    assert all(np.array_equal(a, b) for a, b in zip(made_here, prepared, strict=True))
    assert 0 < len(made_here[6]) < len(made_here[0])   # selected only, cut: fewer


def test_only_labels_on_screen_are_laid_out_the_nearest_first(offscreen: Offscreen) -> None:
    from livemod.dlfl.shapes import grid
    from livemod.viewer.renderer import MAX_LABELS

    arrays = mesh_arrays(grid(80, 80))                 # 6,400 faces
    renderer = offscreen.renderer
    renderer.set_mesh(arrays)
    style = Style(labels=frozenset({"faces"}))
    camera = framed_camera(arrays, elevation=60.0)
    view = camera.view_projection(SIZE[0] / SIZE[1])

    def labelled(quads: np.ndarray) -> np.ndarray:
        """The anchors of the label boxes (kind 9: a face label's box)."""
        return quads[quads[:, 11] == 9][:, :3]

    whole = labelled(renderer._label_quads(style, view))
    assert len(whole) == MAX_LABELS
    camera.distance *= 0.2                             # closer: fewer faces in view
    near = labelled(renderer._label_quads(style, camera.view_projection(SIZE[0] / SIZE[1])))
    assert 0 < len(near) < MAX_LABELS
    clip = np.c_[near, np.ones(len(near))] @ camera.view_projection(SIZE[0] / SIZE[1]).T
    assert (np.abs(clip[:, :2]) <= clip[:, 3:]).all() and (clip[:, 3] > 0).all()
    picture = offscreen.render(camera, style)
    assert (picture != offscreen.render(camera, Style())).any()


def test_render_section_option(tmp_path: Path, capsys) -> None:
    script = tmp_path / "cube.py"
    script.write_text(CUBE_SCRIPT)
    pictures = {}
    for name, extra in (("whole", []), ("middle", ["--section", "z"]),
                        ("at", ["--section", "z=0"]), ("beyond", ["--section", "z=-5"])):
        out = tmp_path / f"{name}.png"
        assert main(["render", str(script), "-o", str(out), "--size", "160x120",
                     "--samples", "0", "--elevation", "0", *extra]) == 0
        pictures[name] = read_image(out)
    assert np.array_equal(pictures["middle"], pictures["at"])  # a bare axis: the middle
    assert not np.array_equal(pictures["middle"], pictures["whole"])
    assert not _mask(pictures["beyond"]).any()
    for bad in ("w", "x=one", "x=inf", "xy=1"):
        with pytest.raises(SystemExit):
            main(["render", str(script), "-o", str(tmp_path / "bad.png"), "--section", bad])
        assert "--section takes x, y or z" in capsys.readouterr().err
    assert not (tmp_path / "bad.png").exists()


def _render(script: Path, out: Path, *extra: str) -> int:
    return main(["render", str(script), "-o", str(out), "--size", "160x120", "--samples", "0",
                 *extra])


def test_render_compares_with_a_reference_picture(tmp_path: Path, capsys) -> None:
    script = tmp_path / "cube.py"
    script.write_text(CUBE_SCRIPT)
    golden = tmp_path / "golden.png"
    assert _render(script, golden) == 0
    assert _render(script, tmp_path / "same.png", "--reference", str(golden)) == 0
    assert f"matches: 0.00% of the pixels differ from {golden}" in capsys.readouterr().out
    assert not (tmp_path / "same.diff.png").exists()
    turned = tmp_path / "turned.png"
    assert _render(script, turned, "--reference", str(golden), "--yaw", "60") == 1
    err = capsys.readouterr().err
    assert err.startswith(f"livemod: error: {turned} differs: ") and err.count("\n") == 1
    assert err.endswith(f"; see {tmp_path / 'turned.diff.png'}\n")
    marked = read_image(tmp_path / "turned.diff.png")
    moved = np.abs(read_image(turned).astype(int) - read_image(golden)).max(axis=2) > 25
    assert np.array_equal(np.all(marked == (255, 40, 40), axis=2), moved)
    assert _render(script, turned, "--reference", str(golden), "--yaw", "60",
                   "--threshold", " 100% ") == 0


def test_render_refuses_a_reference_it_cannot_compare_before_it_runs(tmp_path: Path,
                                                                      capsys) -> None:
    script = tmp_path / "cube.py"
    script.write_text(CUBE_SCRIPT)
    golden = tmp_path / "golden.png"
    Image.new("RGB", (80, 60)).save(golden)
    out = tmp_path / "out.png"
    refusals = {
        ("--reference", str(tmp_path / "gone.png")): (
            f"livemod: error: the reference picture: cannot read {tmp_path / 'gone.png'}: "
            "No such file or directory\n"),
        ("--reference", str(golden)): "is 80x60 pixels and the render 160x120 (give --size)",
        ("--threshold", "0.5"): "--threshold needs --reference",
    }
    for extra, message in refusals.items():
        assert _render(script, out, *extra) == 2
        assert message in capsys.readouterr().err
    assert _render(script, tmp_path / "t.gif", "--reference", str(golden), "--turntable", "3") == 2
    assert "--reference compares one picture: leave out --turntable" in capsys.readouterr().err
    assert _render(script, golden, "--size", "80x60", "--reference", str(golden)) == 2
    assert "-o would write over the reference" in capsys.readouterr().err
    assert not out.exists() and not (tmp_path / "t.gif").exists()
    assert read_image(golden).max() == 0  # nothing written over it
    for bad in ("-1", "101%", "half"):
        with pytest.raises(SystemExit):
            _render(script, out, "--reference", str(golden), "--threshold", bad)
        assert "the threshold is a share of the pixels" in capsys.readouterr().err


def test_render_yaw_turns_the_camera(tmp_path: Path, capsys) -> None:
    script = tmp_path / "two.py"
    script.write_text(CUBE_SCRIPT + "load('cube')\ntranslate(3, 0, 0)\n")
    pictures = {}
    for yaw in ("30", "0", "180", "-180"):
        assert _render(script, tmp_path / f"{yaw}.png", "--yaw", yaw) == 0
        pictures[yaw] = read_image(tmp_path / f"{yaw}.png")
    assert _render(script, tmp_path / "default.png") == 0
    assert np.array_equal(read_image(tmp_path / "default.png"), pictures["30"])
    assert not np.array_equal(pictures["0"], pictures["180"])
    assert np.array_equal(pictures["180"], pictures["-180"])
    with pytest.raises(SystemExit):
        _render(script, tmp_path / "bad.png", "--yaw", "inf")
    assert "the yaw must be a number of degrees, not 'inf'" in capsys.readouterr().err


def _segment():
    """Two point-spheres joined by insertEdge: one edge, one 2-gon, no triangle."""
    from livemod.dlfl import Mesh

    mesh = Mesh()
    a, b = mesh.create_vertex((-1.0, 0.0, 0.0)), mesh.create_vertex((1.0, 0.0, 0.0))
    mesh.insert_edge(mesh.vertex_corner(a), mesh.vertex_corner(b))
    return mesh


def test_meshes_without_triangles_draw_their_points_and_edges(offscreen: Offscreen) -> None:
    from livemod.dlfl import Mesh

    empty, points = Mesh(), Mesh()
    points.create_vertex((-1.0, 0.0, 0.0))
    points.create_vertex((1.0, 0.5, 0.0))
    drawn = {}
    for name, mesh in (("empty", empty), ("points", points), ("segment", _segment())):
        arrays = mesh_arrays(mesh)
        offscreen.renderer.set_mesh(arrays)  # GL buffers cannot be empty: no error here
        camera = framed_camera(arrays, elevation=0.0, yaw=0.0)
        image = offscreen.render(camera, Style())
        drawn[name] = int(_mask(image).sum())
        if name == "segment":  # one line across most of the frame
            labels, count = _blobs(_mask(image))
            assert count == 1 and np.ptp(np.nonzero(labels)[1]) > SIZE[0] / 2
        if name == "points":  # each point-sphere is a point although V is off
            labels, count = _blobs(_mask(image))
            assert count == 2
            hit = offscreen.renderer.pick(camera, SIZE, *_centre_of(labels == 1), "vertex")
            assert hit is not None and hit.kind == "vertex"
    assert drawn["empty"] == 0 and drawn["points"] > 0 and drawn["segment"] > 0


def _blobs(mask: np.ndarray) -> tuple[np.ndarray, int]:
    """Connected groups of True pixels (4-neighbours): ``(labels, count)``."""
    labels = np.zeros(mask.shape, dtype=int)
    count = 0
    for start in zip(*np.nonzero(mask), strict=True):
        if labels[start]:
            continue
        count += 1
        todo = [start]
        while todo:
            y, x = todo.pop()
            if 0 <= y < mask.shape[0] and 0 <= x < mask.shape[1] and mask[y, x] \
                    and not labels[y, x]:
                labels[y, x] = count
                todo += [(y + 1, x), (y - 1, x), (y, x + 1), (y, x - 1)]
    return labels, count


def _centre_of(mask: np.ndarray) -> tuple[int, int]:
    """``(x, y)`` pixel at the middle of a mask's True pixels."""
    rows, cols = np.nonzero(mask)
    return int(cols.mean()), int(rows.mean())


def test_render_command_draws_a_script_of_point_spheres(tmp_path: Path) -> None:
    script = tmp_path / "points.py"
    script.write_text("from livemod.dlfl import *\na = createVertex((0, 0, 0))[0]\n"
                      "b = createVertex((1, 0, 0))[0]\n")
    out = tmp_path / "points.png"
    assert main(["render", str(script), "-o", str(out), "--size", "160x120"]) == 0
    assert _blobs(_mask(read_image(out)))[1] == 2


def test_render_takes_the_seed_a_run_takes(tmp_path: Path) -> None:
    script = tmp_path / "random_box.py"
    script.write_text("import random\nload('cube')\n"
                      "scale((random.uniform(0.2, 1), random.uniform(0.2, 1), 1))\n")
    pictures = {}
    for name, seed in (("a", "1"), ("b", "1"), ("c", "2")):
        out = tmp_path / f"{name}.png"
        assert main(["render", str(script), "-o", str(out), "--size", "64x48",
                     "--seed", seed]) == 0
        pictures[name] = read_image(out)
    assert np.array_equal(pictures["a"], pictures["b"])
    assert not np.array_equal(pictures["a"], pictures["c"])


# inside the box [-1, 1]^3, 0.064 in front of its z = -1 side, looking up and away
INSIDE = dict(target=np.array([-0.6, 0.6, -0.4]), distance=1.05, yaw=128.0, pitch=-34.0,
              fov=60.0)



CLICK = (136, 8)  # a pixel of the z = -1 side, near the top right



def _z_side(arrays) -> int:
    """Dense index of the box's z = -1 side."""
    for face in range(len(arrays.face_ids)):
        ring = arrays.positions[arrays.corner_vertex[
            arrays.face_offsets[face]:arrays.face_offsets[face + 1]]]
        if len(ring) == 4 and np.all(ring[:, 2] == -1.0):
            return face
    raise AssertionError("no z = -1 side")



def test_a_corner_behind_the_eye_is_not_picked() -> None:
    """Two corners of the side lie behind the eye (clip w < 0); divided by their w
    they land mirrored, one of them nearest the click. The corner picked must be
    the one whose vertex the click is nearest on the screen among those seen."""
    arrays = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES))
    camera = Camera(**INSIDE)
    assert np.all(np.abs(camera.eye()) < 1.0)
    face = _z_side(arrays)
    start, stop = arrays.face_offsets[face], arrays.face_offsets[face + 1]
    at = arrays.positions[arrays.corner_vertex[start:stop]]
    clip = np.c_[at, np.ones(4)] @ camera.view_projection(SIZE[0] / SIZE[1]).T
    assert (clip[:, 3] < 0).sum() == 2  # two corners behind the eye
    front = np.flatnonzero(clip[:, 3] > 0)
    ndc = clip[front, :2] / clip[front, 3:4]
    pixels = np.c_[(ndc[:, 0] + 1) * SIZE[0] / 2, (1 - ndc[:, 1]) * SIZE[1] / 2]
    expected = start + front[np.argmin(((pixels - CLICK) ** 2).sum(axis=1))]
    picked = nearest_corner(arrays, face, camera, SIZE, CLICK)
    assert picked == expected
    assert arrays.positions[arrays.corner_vertex[picked]].tolist() == [-1.0, 1.0, -1.0]



def test_a_corner_pick_from_inside_an_open_box(offscreen: Offscreen) -> None:
    """The same through the pick pass: the box has no bottom, so it is not closed
    and its inner sides are drawn (and picked) from inside."""
    arrays = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES[:5]))
    offscreen.renderer.set_mesh(arrays)
    hit = offscreen.renderer.pick(Camera(**INSIDE), SIZE, *CLICK, "corner")
    assert hit is not None and hit.kind == "corner"
    assert arrays.corner_face[hit.dense_index] == _z_side(arrays)
    assert arrays.positions[arrays.corner_vertex[hit.dense_index]].tolist() == [-1.0, 1.0, -1.0]



def test_framing_leaves_out_positions_that_are_not_finite() -> None:
    arrays = cube_with({3: (np.nan, np.nan, np.nan), 5: (1e308 * 10, 0.0, 0.0)})
    clean = np.delete(np.array(arrays.positions), [3, 5], axis=0)
    framed = camera_framing(arrays.positions, aspect=4 / 3)
    expected = camera_framing(clean, aspect=4 / 3)
    assert np.isfinite(framed.target).all() and np.isfinite(framed.distance)
    assert framed.target.tolist() == expected.target.tolist()
    assert framed.distance == expected.distance
    untouched = Camera()
    untouched.fit_points(np.full((4, 3), np.nan), 1.0)  # nothing finite: left as it was
    assert untouched.target.tolist() == [0.0, 0.0, 0.0] and untouched.distance == 5.0
    with pytest.raises(ValueError, match="cannot frame bounds that are not finite"):
        Camera().fit(np.array([[0.0, 0, 0], [np.nan, 1, 1]]))



def test_a_mesh_with_a_nan_vertex_is_framed_and_drawn(offscreen: Offscreen) -> None:
    arrays = cube_with({0: (np.nan, 0.0, 0.0)})
    offscreen.renderer.set_mesh(arrays)
    assert offscreen.renderer.nonfinite == 1
    assert offscreen.renderer.bounds.tolist() == [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
    camera = framed_camera(arrays)
    assert np.isfinite(camera.eye()).all()
    image = offscreen.render(camera, Style(grid=True))  # the grid is sized on the bounds
    assert _mask(image)[SIZE[1] // 2, SIZE[0] // 2]
    offscreen.renderer.set_mesh(cube_with({v: (np.nan,) * 3 for v in range(8)}))
    assert offscreen.renderer.bounds is None  # nothing finite: nothing to size on
    offscreen.render(Camera(), Style(grid=True))



def test_the_guide_lines_are_made_once_per_bounds(offscreen: Offscreen) -> None:
    renderer = offscreen.renderer
    renderer.set_mesh(mesh_arrays(cube()))
    camera = framed_camera(renderer.arrays)
    first = offscreen.render(camera, Style(grid=True))
    made = renderer._guides
    turned = camera.copy()
    turned.orbit(20.0, 0.0)
    offscreen.render(turned, Style(grid=True))
    again = offscreen.render(camera, Style(grid=True))
    assert renderer._guides is made  # the same GL objects, not made again
    assert np.array_equal(first, again)
    old = [vao for vao, _, _ in made[1]]
    renderer.set_mesh(mesh_arrays(tetrahedron()))  # other bounds: made again
    offscreen.render(camera, Style(grid=True))
    assert renderer._guides is not made
    assert all(isinstance(vao.mglo, moderngl.InvalidObject) for vao in old)



def test_release_frees_every_gl_object_of_the_renderer() -> None:
    offscreen = Offscreen(SIZE, samples=0)
    try:
        renderer = Renderer(offscreen.ctx)
        arrays = mesh_arrays(cube())
        renderer.set_mesh(arrays, preview=arrays, others=mesh_arrays(tetrahedron()))
        renderer.set_selection(Selection(edges=(int(arrays.edge_ids[0]),)))
        camera = framed_camera(arrays)
        style = Style(grid=True, smooth=True, section=(0, 0.0))  # the winding target too
        renderer.draw(offscreen.target, camera, style)
        renderer.pick(camera, SIZE, SIZE[0] // 2, SIZE[1] // 2, "face")
        assert renderer._pick_fbo is not None and renderer._winding is not None
        objects = gl_objects(renderer)
        kinds = {type(obj).__name__ for obj in objects}
        assert {"Buffer", "VertexArray", "Texture", "Program", "Framebuffer"} <= kinds
        renderer.release()
        alive = [obj for obj in objects if not isinstance(obj.mglo, moderngl.InvalidObject)]
        assert alive == []
        renderer.release()  # again: nothing happens
        assert offscreen.ctx.error == "GL_NO_ERROR"
    finally:
        offscreen.release()


def test_an_ortho_camera_zoomed_in_does_not_clip_what_is_in_front(offscreen) -> None:
    """Zooming an orthographic view brings the eye closer, not the picture: the
    eye may go inside the mesh, and what lies behind the eye still shows."""
    arrays = mesh_arrays(cube())
    offscreen.activate()
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    camera.zoom(25)  # distance 0.07 of the fit: the eye is inside the cube
    image = offscreen.render(camera, Style(edges=False))
    assert _mask(image)[SIZE[1] // 2, SIZE[0] // 2]  # the front face fills the view



def test_a_mesh_moved_off_the_target_is_not_cut_by_the_far_plane(offscreen) -> None:
    """A re-run that moves the mesh by less than its size keeps the camera; the
    clip planes must still enclose all of it."""
    arrays = mesh_arrays(cube())
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0)
    depth = -0.9 * float(np.linalg.norm(np.ptp(arrays.positions, axis=0)))
    offscreen.activate()
    offscreen.renderer.set_mesh(_translated(arrays, (0.0, 0.0, depth)))
    style = Style(faces=False)  # the wireframe: the far side's edges show
    seen = offscreen.render(camera.copy(), style)
    # the same eye and view, its target at the moved cube's centre
    centred = camera.copy()
    centred.target, centred.distance = np.array([0.0, 0.0, depth]), camera.distance - depth
    assert np.allclose(centred.eye(), camera.eye())
    assert np.array_equal(_mask(seen), _mask(offscreen.render(centred, style)))



def _translated(arrays, offset: tuple[float, float, float]):
    """``arrays`` of a cube moved by ``offset`` (built again from its polygons)."""
    positions = [tuple(map(float, p + np.asarray(offset))) for p in arrays.positions]
    faces = [tuple(int(v) for v in arrays.corner_vertex[arrays.face_offsets[f]:
                                                        arrays.face_offsets[f + 1]])
             for f in range(len(arrays.face_ids))]
    return mesh_arrays(from_polygons(positions, faces))



def test_render_refuses_a_reference_for_an_mp4_before_it_renders(tmp_path: Path,
                                                                 capsys) -> None:
    """An MP4 cannot be read back as a picture (and H.264 is lossy): said at once,
    not as a traceback after the render."""
    from PIL import Image

    from livemod.viewer.cli import main

    golden = tmp_path / "golden.png"
    Image.new("RGB", (64, 48)).save(golden)
    out = tmp_path / "out.mp4"
    code = main(["render", "cube", "-o", str(out), "--size", "64x48",
                 "--reference", str(golden)])
    assert code == 2 and not out.exists()
    assert "--reference compares a PNG, GIF or WebP picture, not out.mp4" in \
        capsys.readouterr().err



def test_render_refuses_mesh_for_a_mesh_input(tmp_path: Path, capsys) -> None:
    """``--mesh`` is the mesh a script starts from: for a mesh input it did nothing."""
    from livemod.viewer.cli import main

    out = tmp_path / "out.png"
    assert main(["render", "cube", "-o", str(out), "--mesh", "tetrahedron"]) == 2
    assert "--mesh needs a script" in capsys.readouterr().err and not out.exists()


def test_new_content_is_drawn_in_slices_to_the_same_picture(offscreen: Offscreen) -> None:
    from livemod.dlfl.shapes import torus

    renderer = offscreen.renderer
    first, second = mesh_arrays(torus(12, 8)), mesh_arrays(torus(20, 14))
    renderer.set_mesh(first)
    camera = framed_camera(second)
    style = Style(smooth=True)
    renderer.set_selection(Selection(faces=(3, 40, 200), edges=(7, 300)))
    assert renderer.draw(offscreen.target, camera, style, budget=100)   # first content
    renderer.set_mesh(second)
    renderer.set_selection(Selection(faces=(3, 40, 200), edges=(7, 300)))
    calls = 1
    while not renderer.draw(offscreen.target, camera, style, budget=100):
        calls += 1
    # 560 triangles (the wireframe drawn in them) and the marks, 100 a call
    assert calls == 6
    sliced = np.frombuffer(offscreen.target.read(components=3), np.uint8)
    assert renderer.draw(offscreen.target, camera, style, budget=100)  # whole: nothing new
    whole = np.frombuffer(offscreen.target.read(components=3), np.uint8)
    assert np.array_equal(sliced, whole)
    renderer.set_mesh(first)
    assert not renderer.draw(offscreen.target, camera, style, budget=50)
    camera.yaw += 10.0                               # the view turns: all at once
    assert renderer.draw(offscreen.target, camera, style, budget=50)
    renderer.set_selection(Selection())


def test_a_preview_and_its_cage_drawn_in_slices_match_the_whole(offscreen: Offscreen) -> None:
    from livemod.dlfl.shapes import torus
    from livemod.runner.preview import PreviewRequest, PreviewSettings, make_preview

    renderer = offscreen.renderer
    current, other = mesh_arrays(torus(10, 6)), mesh_arrays(cube())
    made = make_preview(PreviewRequest((current, other), PreviewSettings(density=2)))
    camera = framed_camera(concatenate_arrays([current, other]))
    style = Style(preview=True)
    renderer.set_mesh(other)
    assert renderer.draw(offscreen.target, camera, style, budget=64)
    renderer.set_mesh(current, made, other)
    calls = 1
    while not renderer.draw(offscreen.target, camera, style, budget=64):
        calls += 1
    # the others' part (24 corners * 8) and the torus's (240 * 8), 120 cage edges, marks
    assert calls == -(-(24 * 8 + 240 * 8 + 120 + 1) // 64)
    sliced = np.frombuffer(offscreen.target.read(components=3), np.uint8)
    renderer.draw(offscreen.target, camera, style)
    assert np.array_equal(sliced, np.frombuffer(offscreen.target.read(components=3), np.uint8))


def test_a_big_scene_drawn_again_unchanged_is_copied(offscreen: Offscreen,
                                                     monkeypatch: pytest.MonkeyPatch) -> None:
    import livemod.viewer.renderer as renderer_module
    from livemod.dlfl.shapes import torus

    monkeypatch.setattr(renderer_module, "CACHED_PRIMITIVES", 100)
    renderer = offscreen.renderer
    renderer.set_mesh(mesh_arrays(torus(20, 14)))
    camera, style = framed_camera(renderer.arrays), Style()
    assert renderer.draw(offscreen.target, camera, style, budget=10_000)  # a new view:
    assert renderer.draw(offscreen.target, camera, style, budget=10_000)  # it rests: kept
    drawn = np.frombuffer(offscreen.target.read(components=3), np.uint8)
    offscreen.target.clear(0.0, 0.0, 0.0, 1.0)

    def never(*args, **kwargs):
        raise AssertionError("drawn again")

    monkeypatch.setattr(renderer, "_draw_whole", never)
    assert renderer.draw(offscreen.target, camera, style, budget=10_000)   # copied
    assert np.array_equal(np.frombuffer(offscreen.target.read(components=3), np.uint8), drawn)
    camera.yaw += 5.0
    with pytest.raises(AssertionError, match="drawn again"):
        renderer.draw(offscreen.target, camera, style, budget=10_000)


def test_render_preview_draws_the_patches_of_every_object(tmp_path: Path) -> None:
    script = tmp_path / "two.py"
    script.write_text(CUBE_SCRIPT + "P = [(x + 4, y, z) for x, y, z in P]\n"
                      "current_scene().add(from_polygons(P, F))\n")
    pictures = {}
    for name, extra in (("plain", []), ("preview", ["--preview"])):
        out = tmp_path / f"{name}.png"
        assert main(["render", str(script), "-o", str(out), "--size", "160x120",
                     "--samples", "0", "--elevation", "0", "--yaw", "0", "--no-edges",
                     *extra]) == 0
        pictures[name] = read_image(out)
    for half in (slice(0, SIZE[0] // 2), slice(SIZE[0] // 2, SIZE[0])):  # both objects
        assert _mask(pictures["preview"][:, half]).sum() < \
            0.95 * _mask(pictures["plain"][:, half]).sum()


def _grid(columns: int, rows: int):  # noqa: ANN202
    """A flat ``columns`` x ``rows`` grid of unit quads in the plane z = 0, its
    faces numbered row by row."""
    points = [(x, y, 0.0) for y in range(rows + 1) for x in range(columns + 1)]
    faces = [(y * (columns + 1) + x, y * (columns + 1) + x + 1,
              (y + 1) * (columns + 1) + x + 1, (y + 1) * (columns + 1) + x)
             for y in range(rows) for x in range(columns)]
    return from_polygons(points, faces)


def test_faces_past_the_first_row_of_the_tables_are_picked_and_selected(
        offscreen: Offscreen) -> None:
    # the face tables are 4096 texels wide: a face numbered above that is read
    # from a later row, in the pick pass and in the selection's flags alike
    arrays = mesh_arrays(_grid(100, 50))
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    x, y = SIZE[0] * 8 // 10, SIZE[1] * 3 // 10  # near the top right: the last faces
    hit = offscreen.renderer.pick(camera, SIZE, x, y, "face")
    assert hit is not None and hit.dense_index > 4096
    corners = arrays.corner_vertex[arrays.face_offsets[hit.dense_index]:
                                   arrays.face_offsets[hit.dense_index + 1]]
    clip = np.c_[arrays.positions[corners], np.ones(4)] @ camera.view_projection(
        SIZE[0] / SIZE[1]).T
    pixels = (clip[:, :2] / clip[:, 3:] + 1) * 0.5 * np.array(SIZE)
    assert pixels[:, 0].min() - 1 <= x + 0.5 <= pixels[:, 0].max() + 1
    assert pixels[:, 1].min() - 1 <= SIZE[1] - y - 0.5 <= pixels[:, 1].max() + 1
    offscreen.renderer.set_selection(Selection(faces=(hit.element_id,)))
    red, green, blue = offscreen.render(camera, Style(edges=False))[y, x].astype(int)
    assert green > red and green > blue


@pytest.mark.parametrize("style", [Style(faces=False), Style(preview=True)],
                         ids=["edges alone", "the preview's cage"])
def test_a_selected_edge_changes_no_other_pixel_of_the_edges(offscreen: Offscreen,
                                                             style: Style) -> None:
    # edges with none selected are drawn by a program without flags or ids
    from livemod.runner.preview import PreviewRequest, make_preview

    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays, make_preview(PreviewRequest((arrays,))))
    camera = framed_camera(arrays)
    plain = offscreen.render(camera, style).astype(int)
    offscreen.renderer.set_selection(Selection(edges=(int(arrays.edge_ids[0]),)))
    selected = offscreen.render(camera, style).astype(int)
    changed = (plain != selected).any(axis=2)
    assert changed.sum() > 10
    red, green, blue = selected[changed].T
    assert ((green > red) & (green > blue)).all()


def test_a_section_cuts_the_preview_and_caps_it(offscreen: Offscreen) -> None:
    from livemod.runner.preview import PreviewRequest, make_preview
    from livemod.viewer.renderer import PREVIEW_COLOR

    arrays = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES))
    offscreen.renderer.set_mesh(arrays, make_preview(PreviewRequest((arrays,))))
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    cut = offscreen.render(camera, Style(preview=True, edges=False, section=(2, 0.0)))
    middle = (SIZE[1] // 2, SIZE[0] // 2)
    _assert_hatched_cap(cut[middle[0] - 8:middle[0] + 8, middle[1] - 8:middle[1] + 8],
                        PREVIEW_COLOR)


def test_the_quick_picture_of_a_big_scene_leaves_its_edges_out(
        offscreen: Offscreen, monkeypatch: pytest.MonkeyPatch) -> None:
    import livemod.viewer.renderer as renderer

    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays)
    whole = offscreen.render(camera, Style())
    assert offscreen.renderer.quick_style(Style()) is None  # 12 triangles: drawn whole
    monkeypatch.setattr(renderer, "QUICK_PRIMITIVES", 10)
    assert offscreen.renderer.quick_style(Style()) == Style(edges=False)
    assert offscreen.renderer.quick_style(Style(edges=False)) is None  # nothing to leave
    assert offscreen.renderer.quick_style(Style(faces=False)) is None  # out, or no faces
    offscreen.activate()
    offscreen.renderer.draw(offscreen.target, camera, Style(), quick=True)
    quick = read_image_of(offscreen)
    assert np.array_equal(quick, offscreen.render(camera, Style(edges=False)))
    assert not np.array_equal(quick, whole)


def read_image_of(offscreen: Offscreen) -> np.ndarray:
    """The picture in ``offscreen``'s target (no MSAA here: it is the resolved one)."""
    from livemod.viewer.renderer import read_image

    return read_image(offscreen.target, Style())


def test_the_quick_picture_of_a_preview_is_its_surface_alone(
        offscreen: Offscreen, monkeypatch: pytest.MonkeyPatch) -> None:
    import livemod.viewer.renderer as renderer
    from livemod.runner.preview import PreviewRequest, make_preview

    arrays = mesh_arrays(cube())
    offscreen.renderer.set_mesh(arrays, make_preview(PreviewRequest((arrays,))))
    camera = framed_camera(arrays)
    surface = offscreen.render(camera, Style(preview=True, edges=False)).astype(int)
    monkeypatch.setattr(renderer, "QUICK_PRIMITIVES", 10)
    offscreen.activate()
    offscreen.renderer.draw(offscreen.target, camera, Style(preview=True), quick=True)
    quick = read_image_of(offscreen).astype(int)
    # no cage; the surface lit alike but at its outline, where the normal is
    # turned by the side seen instead of by the flat normal
    differ = np.abs(quick - surface).max(axis=2) > 2
    assert differ.mean() < 0.01 and _mask(quick).sum() == _mask(surface).sum()


def _cube_colored(faces: dict[int, tuple[float, float, float]]):  # type: ignore[no-untyped-def]
    mesh = from_polygons(CUBE_POSITIONS, CUBE_FACES)
    for face, color in faces.items():
        mesh.set_face_color(face, color)
    return mesh_arrays(mesh)


FRONT, BACK = 4, 2  # the cube's faces at z = +1 (toward a camera on +z) and z = -1


@pytest.mark.parametrize("settings", [
    {}, {"budget": 30}, {"mode": "catmull-clark"}],
    ids=["patches", "vertex points", "catmull-clark"])
def test_the_preview_draws_each_face_s_patches_in_its_colour(offscreen: Offscreen,
                                                             settings: dict) -> None:
    from livemod.runner.preview import PreviewRequest, PreviewSettings, make_preview

    def picture(arrays, **style: object) -> np.ndarray:  # type: ignore[no-untyped-def]
        made = make_preview(PreviewRequest((arrays,), PreviewSettings(**settings)))
        offscreen.renderer.set_mesh(arrays, made)
        return offscreen.render(camera, Style(preview=True, edges=False, **style))

    plain_arrays = _cube_colored({})
    # from +z a little up and right: the front face in the middle, two sides beside it
    camera = framed_camera(plain_arrays, elevation=15.0, yaw=15.0, ortho=True)
    plain = picture(plain_arrays)
    red = picture(_cube_colored({FRONT: (1.0, 0.0, 0.0)}))
    changed = (red != plain).any(axis=2)
    middle = (slice(SIZE[1] // 2 - 8, SIZE[1] // 2 + 8), slice(SIZE[0] // 2 - 8, SIZE[0] // 2 + 8))
    assert changed[middle].all()                          # the front face's patches...
    assert (red[changed][:, 1:] == 0).all() and (red[changed][:, 0] > 60).all()  # ...lit red
    assert changed.sum() < 0.9 * _mask(plain).sum()       # the side faces' stay as they were
    centre = plain[SIZE[1] // 2, SIZE[0] // 2].astype(int)
    assert centre[2] > centre[0]                          # (the preview's blue)
    # a coloured face out of sight changes nothing: the others keep the preview's colour
    assert np.array_equal(picture(_cube_colored({BACK: (1.0, 0.0, 0.0)})), plain)
    flat = picture(_cube_colored({FRONT: (1.0, 0.0, 0.0)}), colors=False)   # K
    assert np.array_equal(flat, plain)


@pytest.mark.parametrize("preview", [False, True], ids=["faces", "preview"])
def test_the_other_objects_show_their_own_colours_muted(offscreen: Offscreen,
                                                        preview: bool) -> None:
    from livemod.runner.preview import PreviewRequest, make_preview

    current = _cube_colored({})
    green = {face: (0.0, 1.0, 0.0) for face in range(6)}
    other = dataclasses.replace(_cube_colored(green), positions=np.asarray(CUBE_POSITIONS)
                                + [3.0, 0.0, 0.0])
    made = make_preview(PreviewRequest((current, other)))
    offscreen.renderer.set_mesh(current, made, other)
    camera = framed_camera(concatenate_arrays([current, other]), elevation=0.0, yaw=0.0)
    right = slice(SIZE[0] // 2 + 8, SIZE[0])

    def shown(colors: bool) -> np.ndarray:
        picture = offscreen.render(camera, Style(preview=preview, edges=False, colors=colors))
        return picture[:, right][_mask(picture)[:, right]].astype(int)

    tinted, flat = shown(True), shown(False)
    assert len(tinted) > 100
    # green mixed 60 % toward light grey (0.46, 0.86, 0.46): green, red and blue alike
    assert (tinted[:, 1] > 1.5 * tinted[:, 0]).all() and (tinted[:, 2] <= tinted[:, 0]).all()
    assert (tinted[:, 0] > 0.6 * tinted[:, 1] * 0.46 / 0.86).all()  # muted, not pure green
    assert (flat[:, 0] > flat[:, 2]).all() and (flat[:, 0] > flat[:, 1]).all()  # K: warm


def test_a_label_beyond_the_section_is_not_drawn_while_one_in_front_is(
        offscreen: Offscreen) -> None:
    arrays = mesh_arrays(from_polygons(CUBE_POSITIONS, CUBE_FACES))
    offscreen.renderer.set_mesh(arrays)
    # from +z: the vertices at x = -1 on the left of the square, those at x = +1 on its right
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    view = camera.view_projection(SIZE[0] / SIZE[1])
    left, right = (((view @ [x, 0.0, 0.0, 1.0])[0] * 0.5 + 0.5) * SIZE[0] for x in (-1.0, 1.0))

    def labelled_columns(section) -> np.ndarray:  # type: ignore[no-untyped-def]
        """Columns where the vertex labels changed the picture cut at ``section``."""
        bare = offscreen.render(camera, Style(edges=False, section=section))
        labelled = offscreen.render(camera, Style(edges=False, section=section,
                                                  labels=frozenset({"vertices"})))
        return np.flatnonzero((bare != labelled).any(axis=2).any(axis=0))

    def near(columns: np.ndarray, at: float) -> bool:
        return bool((np.abs(columns - at) < 12).any())

    whole = labelled_columns(None)
    assert near(whole, left) and near(whole, right)
    cut = labelled_columns((0, 0.0))                        # x <= 0 is kept
    assert near(cut, left) and not near(cut, right)
    assert cut.max() < SIZE[0] / 2                          # nothing right of the plane
