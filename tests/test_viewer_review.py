"""Regression tests of the viewer review: timeline hits, camera clipping, far-off
faces' measures, and what a dropped script resets."""

from __future__ import annotations

import io
from collections.abc import Iterator
from pathlib import Path

import numpy as np
import pytest

from livemod.dlfl import from_polygons, mesh_arrays
from livemod.dlfl.shapes import cube
from livemod.viewer import measure
from livemod.viewer.camera import Camera
from livemod.viewer.headless import Offscreen, framed_camera
from livemod.viewer.measure import WholeMeshMeasurer, face_area_normal
from livemod.viewer.renderer import Style
from livemod.viewer.timeline import Timeline
from livemod.viewer.window import ViewOptions, close_viewer, create_viewer

from .viewer_support import frames_until

SIZE = (160, 120)
BACKGROUND = np.array([round(0.16 * 255), round(0.17 * 255), round(0.19 * 255)])


@pytest.fixture(scope="module")
def offscreen() -> Iterator[Offscreen]:
    target = Offscreen(SIZE, samples=0)
    yield target
    target.release()


def _drawn(image: np.ndarray) -> np.ndarray:
    """``(H, W)`` bool: the pixels that are not background."""
    return np.abs(image.astype(int) - BACKGROUND).sum(axis=2) > 6


# -- the timeline ----------------------------------------------------------------


def test_a_press_on_the_timeline_handle_stays_on_its_step() -> None:
    """The handle of step k is drawn at the end of the fill, (k + 1) / total of the
    bar: pressing it (to drag it) must not jump to step k + 1."""
    timeline, size, total = Timeline(), (800, 600), 10
    for shown in range(total):
        quads = timeline.quads(size, shown, total)
        handle = quads[-1]  # the handle is the last quad
        centre = float(handle[0] + handle[5] / 2)  # x + width / 2
        assert timeline.step_at(centre, size, total) == shown


# -- camera clipping ---------------------------------------------------------------


def test_an_ortho_camera_zoomed_in_does_not_clip_what_is_in_front(offscreen) -> None:
    """Zooming an orthographic view brings the eye closer, not the picture: the
    eye may go inside the mesh, and what lies behind the eye still shows."""
    arrays = mesh_arrays(cube())
    offscreen.activate()
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=0.0, yaw=0.0, ortho=True)
    camera.zoom(25)  # distance 0.07 of the fit: the eye is inside the cube
    image = offscreen.render(camera, Style(edges=False))
    assert _drawn(image)[SIZE[1] // 2, SIZE[0] // 2]  # the front face fills the view


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
    assert np.array_equal(_drawn(seen), _drawn(offscreen.render(centred, style)))


def _translated(arrays, offset: tuple[float, float, float]):
    """``arrays`` of a cube moved by ``offset`` (built again from its polygons)."""
    positions = [tuple(map(float, p + np.asarray(offset))) for p in arrays.positions]
    faces = [tuple(int(v) for v in arrays.corner_vertex[arrays.face_offsets[f]:
                                                        arrays.face_offsets[f + 1]])
             for f in range(len(arrays.face_ids))]
    return mesh_arrays(from_polygons(positions, faces))


def test_an_ortho_near_plane_may_lie_behind_the_eye() -> None:
    near, far = Camera(distance=0.5, scene_radius=1.0, ortho=True).clip_range()
    assert near < -1.0 and far > 1.5
    near, _ = Camera(distance=0.5, scene_radius=1.0).clip_range()
    assert near > 0.0  # a perspective one never


# -- measures ------------------------------------------------------------------------


def test_a_face_far_from_the_origin_keeps_its_area_and_normal() -> None:
    far = 1e8
    square = [(far, far, 0.0), (far + 1, far, 0.0), (far + 1, far + 1, 0.0), (far, far + 1, 0.0)]
    arrays = mesh_arrays(from_polygons(square, [(0, 1, 2, 3)]))
    area, normal = face_area_normal(arrays, 0)
    assert area == pytest.approx(1.0, rel=1e-6)
    assert np.allclose(np.abs(normal), (0, 0, 1))


def test_a_measurer_closed_for_another_script_measures_again(monkeypatch) -> None:
    """The window closes its measurer with the session when a script is dropped on
    it; measuring the next script's large mesh must still work."""
    monkeypatch.setattr(measure, "MEASURE_AT_ONCE", 0)  # every mesh in the background
    measurer = WholeMeshMeasurer()
    measurer.close()
    measurer.measure(mesh_arrays(cube()))
    facts = measurer.wait(10.0)
    assert facts is not None and facts.genus == 0
    measurer.close()


# -- a dropped script ---------------------------------------------------------------



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


# -- livemod render's options ---------------------------------------------------------


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
