"""The viewer gaps the review left: corner picks from inside a mesh, positions that
are not finite, stepped sliders, the guide lines' buffers, the renderer's release,
screenshot names, and what a dropped mesh keeps."""

from __future__ import annotations

import dataclasses
import io
from pathlib import Path

import moderngl
import numpy as np
import pytest
from PIL import Image

from livemod.dlfl import from_polygons, mesh_arrays
from livemod.dlfl.params import make_spec
from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import cube, tetrahedron
from livemod.viewer.camera import Camera
from livemod.viewer.geometry import build_geometry, finite_bounds
from livemod.viewer.headless import Offscreen, camera_framing, framed_camera
from livemod.viewer.imagefiles import save_new_png
from livemod.viewer.params_panel import snap
from livemod.viewer.renderer import Renderer, Style, nearest_corner
from livemod.viewer.window import ViewOptions, close_viewer, create_viewer, run_frames

from .conftest import OFFSCREEN_SIZE
from .viewer_support import frames_until

SIZE = OFFSCREEN_SIZE
BACKGROUND = np.array([round(0.16 * 255), round(0.17 * 255), round(0.19 * 255)])

BOX_POSITIONS = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
                 (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
BOX_FACES = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3),
             (7, 6, 5, 4)]


def _drawn(image: np.ndarray) -> np.ndarray:
    """``(H, W)`` bool: the pixels that are not background."""
    return np.abs(image.astype(int) - BACKGROUND).sum(axis=2) > 6


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


# -- 1. a corner pick with the eye inside the mesh ------------------------------------

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
    arrays = mesh_arrays(from_polygons(BOX_POSITIONS, BOX_FACES))
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
    arrays = mesh_arrays(from_polygons(BOX_POSITIONS, BOX_FACES[:5]))
    offscreen.renderer.set_mesh(arrays)
    hit = offscreen.renderer.pick(Camera(**INSIDE), SIZE, *CLICK, "corner")
    assert hit is not None and hit.kind == "corner"
    assert arrays.corner_face[hit.dense_index] == _z_side(arrays)
    assert arrays.positions[arrays.corner_vertex[hit.dense_index]].tolist() == [-1.0, 1.0, -1.0]


# -- 2. positions that are not finite -------------------------------------------------


def _cube_with(bad: dict[int, tuple[float, float, float]]):
    """The arrays of the 2-unit cube with the positions of vertices ``bad`` replaced."""
    arrays = mesh_arrays(from_polygons(BOX_POSITIONS, BOX_FACES))
    positions = np.array(arrays.positions)
    for vertex, position in bad.items():
        positions[vertex] = position
    return dataclasses.replace(arrays, positions=positions)


def test_bounds_leave_out_positions_that_are_not_finite() -> None:
    arrays = _cube_with({0: (np.nan, 1.0, 1.0), 6: (-np.inf, -1.0, -1.0)})
    geometry = build_geometry(arrays)
    assert geometry.nonfinite == 2
    # vertex 0 was the only one at max x = 1 with y = z = 1; 6 the only -x, -y, -z
    assert geometry.bounds.tolist() == [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
    assert np.isfinite(geometry.center).all() and geometry.radius == pytest.approx(3 ** 0.5)
    assert finite_bounds(np.full((3, 3), np.nan)).tolist() == [[0.0] * 3, [0.0] * 3]
    assert build_geometry(mesh_arrays(cube())).nonfinite == 0


def test_framing_leaves_out_positions_that_are_not_finite() -> None:
    arrays = _cube_with({3: (np.nan, np.nan, np.nan), 5: (1e308 * 10, 0.0, 0.0)})
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
    arrays = _cube_with({0: (np.nan, 0.0, 0.0)})
    offscreen.renderer.set_mesh(arrays)
    assert offscreen.renderer.nonfinite == 1
    assert offscreen.renderer.bounds.tolist() == [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
    camera = framed_camera(arrays)
    assert np.isfinite(camera.eye()).all()
    image = offscreen.render(camera, Style(grid=True))  # the grid is sized on the bounds
    assert _drawn(image)[SIZE[1] // 2, SIZE[0] // 2]
    offscreen.renderer.set_mesh(_cube_with({v: (np.nan,) * 3 for v in range(8)}))
    assert offscreen.renderer.bounds is None  # nothing finite: nothing to size on
    offscreen.render(Camera(), Style(grid=True))


def test_the_window_frames_and_warns_about_a_mesh_with_nan(cube_script: Path) -> None:
    """A NaN vertex reaches the window's upload (as from a script's own arrays): the
    view is fitted on the rest, and the HUD counts it."""
    from livemod.viewer.hud import hud_lines

    viewer = _viewer(cube_script)
    try:
        frames_until(viewer, _settled)
        viewer.display.fit_bounds = None  # (fit on this upload)
        viewer.display.upload(_cube_with({2: (np.nan, 0.0, 0.0)}), None, None)
        assert np.isfinite(viewer.camera.eye()).all() and viewer.camera.distance > 1.0
        text = [line for line, _ in hud_lines(viewer.view_state())]
        assert "1 vertex not finite (NaN or inf): left out of the framing" in text
        run_frames(viewer, 1)
        assert _drawn(viewer.capture())[75, 100]
    finally:
        close_viewer(viewer)


# -- 3. a slider whose step does not divide its range -----------------------------------


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


# -- 4. the guide lines, the frame rate, releasing the renderer ------------------------


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


def _gl_objects(value, seen: set[int] | None = None) -> list:
    """Every moderngl object reachable from ``value``'s attributes (recursively)."""
    seen = set() if seen is None else seen
    if id(value) in seen or isinstance(value, str | bytes | np.ndarray | int | float):
        return []
    seen.add(id(value))
    kinds = (moderngl.Buffer, moderngl.VertexArray, moderngl.Texture, moderngl.Program,
             moderngl.Framebuffer, moderngl.Renderbuffer)
    if isinstance(value, kinds):
        found = [value]
        if isinstance(value, moderngl.Framebuffer) and \
                not isinstance(value.mglo, moderngl.InvalidObject):
            found += [a for a in (*value.color_attachments, value.depth_attachment) if a]
        return found
    if isinstance(value, dict):
        items = list(value.values())
    elif isinstance(value, list | tuple):
        items = list(value)
    elif hasattr(value, "__dict__") and type(value).__module__.startswith("livemod.viewer"):
        items = [v for k, v in vars(value).items() if k != "ctx"]
    else:
        return []
    return [obj for item in items for obj in _gl_objects(item, seen)]


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
        objects = _gl_objects(renderer)
        kinds = {type(obj).__name__ for obj in objects}
        assert {"Buffer", "VertexArray", "Texture", "Program", "Framebuffer"} <= kinds
        renderer.release()
        alive = [obj for obj in objects if not isinstance(obj.mglo, moderngl.InvalidObject)]
        assert alive == []
        renderer.release()  # again: nothing happens
        assert offscreen.ctx.error == "GL_NO_ERROR"
    finally:
        offscreen.release()


def test_closing_the_window_releases_the_renderer(cube_script: Path) -> None:
    viewer = _viewer(cube_script)
    try:
        frames_until(viewer, _settled)
        run_frames(viewer, 2)
        objects = _gl_objects(viewer.renderer) + [viewer.frames.kept[1]]
    finally:
        close_viewer(viewer)
    assert all(isinstance(obj.mglo, moderngl.InvalidObject) for obj in objects)
    assert viewer.renderer._released and viewer.frames.kept is None


# -- 5. screenshot names ----------------------------------------------------------------


def test_a_new_png_never_replaces_a_file(tmp_path: Path) -> None:
    path = tmp_path / "shot.png"
    path.write_bytes(b"someone else's")
    image = np.zeros((4, 6, 3), np.uint8)
    with pytest.raises(FileExistsError):
        save_new_png(path, image)
    assert path.read_bytes() == b"someone else's"
    fresh = tmp_path / "sub" / "new.png"
    save_new_png(fresh, image)
    assert np.asarray(Image.open(fresh)).shape == (4, 6, 3)
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["new.png", "shot.png", "sub"]


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


# -- 6. a dropped mesh -----------------------------------------------------------------

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


# -- 7. a save that empties the script ------------------------------------------------

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
