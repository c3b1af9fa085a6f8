"""The patch preview: computed off the caller's thread, posted as a second result."""

from __future__ import annotations

import dataclasses
import threading

import numpy as np
import pytest

from livemod.dlfl import MeshArrays, from_polygons, mesh_arrays, shapes
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.mesh import Mesh
from livemod.runner import LiveSession, ManualNotifier, preview
from livemod.runner.results import RunResult, snapshot_mesh
from livemod.viewer.camera import Camera

from .meshes import point_sphere
from .runner_scripts.support import closing_session, next_result, script_path, started_session

QUAD = ([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 1, 2, 3)])


def test_preview_is_the_mesh_subdivided_level_times_on_a_copy():
    mesh = from_polygons(*QUAD)
    before = mesh.counts()
    catmull_clark = preview.preview_arrays(mesh, levels=2)
    doo_sabin = preview.preview_arrays(mesh, scheme="doo-sabin", levels=1)
    assert mesh.counts() == before
    # a quad and its hole face (V 4, E 4, F 2): each Catmull-Clark level adds a point per
    # edge and face and quarters the faces: (4+4+2, 16, 8), then (10+16+8, 64, 32)
    assert catmull_clark is not None and catmull_clark.counts == (34, 64, 32)
    # Doo-Sabin: a vertex per corner, a quad per edge; the valence-2 vertices' 2-gons go
    assert doo_sabin is not None and doo_sabin.counts == (8, 12, 2 + 4)
    assert not catmull_clark.positions.flags.writeable


def test_no_preview_for_an_empty_mesh_or_over_the_face_budget():
    mesh = from_polygons(*QUAD)
    assert preview.preview_arrays(mesh, face_budget=31) is None  # 32 faces at two levels
    assert preview.preview_arrays(mesh, face_budget=32) is not None
    assert preview.preview_arrays(Mesh()) is None


def test_a_failing_preview_is_logged_and_the_worker_goes_on(caplog):
    posted: list[int] = []
    failed, done = threading.Event(), threading.Event()

    def compute(mesh: Mesh):
        if not failed.is_set():
            failed.set()
            raise RuntimeError("boom")
        done.set()
        return snapshot_mesh(mesh)

    worker: preview.PreviewWorker[RunResult, Mesh, MeshArrays] = preview.PreviewWorker(
        lambda result, arrays: posted.append(result.run_id), lambda result: True, compute)
    with caplog.at_level("ERROR", logger="livemod.preview"):
        worker.request(_result(1), from_polygons(*QUAD))
        assert failed.wait(10)
        worker.request(_result(2), from_polygons(*QUAD))
        assert done.wait(10)
        worker.close()
        worker._thread.join(10)
    assert posted == [2]
    assert "the preview of run 1 failed" in caplog.text and "boom" in caplog.text


def _result(run_id: int) -> RunResult:
    return RunResult.finished(run_id, "s.py", (), None, 0.0)


@pytest.mark.timeout(60)
def test_session_posts_the_preview_in_a_second_result_off_the_caller_thread():
    threads = []

    def compute(mesh: Mesh):
        threads.append(threading.current_thread())
        return snapshot_mesh(mesh)

    live = LiveSession(script_path("cube_steps.py"), notifier=ManualNotifier(), preview=compute)
    with closing_session(live):
        live.start()
        first = next_result(live)
        assert first.status == "ok" and first.preview is None
        second = next_result(live)
        assert second.run_id == first.run_id and second.preview is not None
        assert second.preview.counts == first.arrays.counts  # type: ignore[union-attr]
        assert threads and threading.main_thread() not in threads


def test_session_results_carry_the_other_objects(tmp_path):
    script = tmp_path / "two.py"
    script.write_text("load('cube')\nload('tetrahedron')\n")
    with started_session(script, preview=None) as live:
        result = next_result(live)
        assert result.status == "ok"
        assert result.arrays is not None and result.arrays.counts == (4, 6, 4)
        assert result.others is not None and result.others.counts == (8, 12, 6)


# -- the patch preview of a scene ------------------------------------------------------


def _objects(*meshes: Mesh) -> tuple:
    return tuple(mesh_arrays(m) for m in meshes)


def test_patches_cover_every_object_at_the_density_asked():
    objects = _objects(shapes.cube(), shapes.torus(6, 4))       # 24 + 96 corners
    made = preview.make_preview(preview.PreviewRequest(objects, preview.PreviewSettings(
        density=3)))
    assert (made.density, made.shown, made.total, made.by_view) == (3, 120, 120, False)
    assert made.surface.triangles.shape == (120 * 2 * 9, 3)
    assert made.surface.positions.shape == (120 * 16, 3)
    assert made.description == "patches, density 3"
    assert not made.surface.positions.flags.writeable
    # the torus's patches come after the cube's, its indices shifted past them
    assert made.surface.triangles[24 * 18:].min() == 24 * 16
    cube_part = made.surface.positions[:24 * 16]
    assert np.abs(cube_part).max() <= 1.0 + 1e-6                 # inside the cube (size 2)


def test_the_preview_carries_the_faces_colours_of_the_objects_that_have_some():
    colored = shapes.cube()
    colored.set_face_color(int(colored.face_ids()[1]), (1.0, 0.0, 0.0))
    objects = _objects(colored, shapes.torus(6, 4))              # 24 + 96 corners
    made = preview.make_preview(preview.PreviewRequest(objects, preview.PreviewSettings(
        density=2)))
    colors = made.surface.colors
    assert colors is not None and colors.shape == (120 * 9, 4) and not colors.flags.writeable
    red = (colors == (255, 0, 0, 255)).all(axis=1)
    assert red.sum() == 4 * 9 and not colors[~red].any()   # face 1's four patches; none else
    assert red[:24 * 9].sum() == 4 * 9                      # in the cube's part
    plain = preview.make_preview(preview.PreviewRequest(_objects(shapes.cube(), shapes.torus(
        6, 4)), preview.PreviewSettings(density=2)))
    assert plain.surface.colors is None


def test_the_catmull_clark_preview_keeps_the_faces_colours():
    colored = shapes.cube()
    colored.set_face_color(int(colored.face_ids()[1]), (0.0, 0.0, 1.0))
    made = preview.make_preview(preview.PreviewRequest(
        _objects(colored), preview.PreviewSettings(mode=preview.CATMULL_CLARK, levels=2)))
    assert made.description == "Catmull-Clark, 2 levels"
    colors = made.surface.colors
    # a point per vertex of the 96 quads, and a blue one more on each of the 16 around
    # face 1's 4 x 4 quads (beside faces without colour)
    assert colors is not None and len(colors) == 98 + 16
    blue = (colors[made.surface.triangles] == (0, 0, 255, 255)).all(axis=(1, 2))
    assert blue.sum() == 16 * 2                             # face 1's 16 quads, 2 triangles each


def test_over_the_budget_the_density_drops_first():
    objects = _objects(shapes.cube())
    made = preview.make_preview(preview.PreviewRequest(objects, preview.PreviewSettings(
        density=4, budget=24 * 2 * 9)))
    assert made.density == 3 and made.shown == 24
    assert made.description == "patches, density 3 (of 4: budget)"


def test_then_only_the_nearest_faces_in_view_get_patches():
    near, far = shapes.cube(), shapes.cube()
    far.set_positions(far.vertex_ids(), mesh_arrays(far).positions + [0.0, 0.0, -20.0])
    behind = shapes.cube()
    behind.set_positions(behind.vertex_ids(), mesh_arrays(behind).positions + [0.0, 0.0, 20.0])
    objects = _objects(far, behind, near)
    camera = Camera()
    camera.fit_points(mesh_arrays(near).positions, 1.0)
    view = preview.View(camera.eye(), camera.view_projection(1.0))
    assert np.linalg.norm(camera.eye() - [0, 0, 20]) > 5            # not inside "behind"
    everything = preview.make_preview(preview.PreviewRequest(
        objects, preview.PreviewSettings(budget=2 * 18), view))
    assert (everything.density, everything.by_view) == (0, False)   # 18 quads, 2 each
    assert everything.description == "patches at their vertex points (of 4: budget)"
    made = preview.make_preview(preview.PreviewRequest(
        objects, preview.PreviewSettings(budget=2 * 7 + 1), view))
    assert made.by_view and made.density == 0
    assert made.shown == 28 and made.total == 72                  # 7 whole quads of 4
    assert made.description == ("patches at their vertex points (of 4: budget), 28 of 72 "
                                "(the nearest in view: budget)")
    triangles = made.surface.positions[made.surface.triangles]
    clip = np.c_[triangles.reshape(-1, 3), np.ones(len(triangles) * 3)] @ \
        camera.view_projection(1.0).T
    assert (clip[:, 3] > 0).all()
    # the near cube's six faces all, and one more: the far cube's nearest
    assert (np.abs(triangles.mean(axis=1)[:, 2]) <= 1.0).sum() == 12


def test_without_a_view_the_first_faces_get_patches():
    objects = _objects(shapes.cube(), shapes.cube())
    made = preview.make_preview(preview.PreviewRequest(objects, preview.PreviewSettings(
        budget=13)))
    assert made.shown == 24 and made.parts == (12, 0)


def test_catmull_clark_keeps_its_levels_and_gives_way_to_patches_over_the_budget():
    objects = _objects(shapes.cube())
    settings = preview.PreviewSettings(mode="catmull-clark")
    made = preview.make_preview(preview.PreviewRequest(objects, settings))
    assert made.description == "Catmull-Clark, 2 levels" and made.density == 2
    assert len(made.surface.triangles) == 6 * 16 * 2
    np.testing.assert_allclose(np.linalg.norm(made.surface.normals, axis=1), 1.0, atol=1e-6)
    fewer = preview.make_preview(preview.PreviewRequest(
        objects, dataclasses.replace(settings, budget=2 * 24)))
    assert fewer.description == "Catmull-Clark, 1 level (of 2: budget)"
    patches = preview.make_preview(preview.PreviewRequest(
        objects, dataclasses.replace(settings, budget=2 * 23)))
    assert patches.description == ("Catmull-Clark over the budget: patches at their vertex "
                                   "points (of 4: budget)")


def test_a_scene_with_nothing_to_smooth_gets_an_empty_preview():
    for objects in ((), _objects(Mesh()), _objects(point_sphere())):
        made = preview.make_preview(preview.PreviewRequest(objects))
        assert made.surface.triangles.shape == (0, 3)
        assert made.description == "patches: nothing to smooth"


@pytest.mark.parametrize("field, value, message", [
    ("mode", "loop", "preview mode must be one of ('patches', 'catmull-clark'), got 'loop'"),
    ("density", 0, "preview density must be an int from 1 to 32, got 0"),
    ("levels", 2.0, "preview levels must be an int from 1 to 4, got 2.0"),
    ("budget", 1, "preview budget must be an int from 2 to 2147483648, got 1"),
])
def test_settings_out_of_range_are_refused(field, value, message):
    with pytest.raises(InvalidArgumentError) as caught:
        preview.PreviewSettings(**{field: value})
    assert str(caught.value) == message


@pytest.mark.timeout(60)
def test_scene_previews_hand_back_the_newest_request_made_off_the_caller_thread():
    threads, release = [], threading.Event()

    def compute(request: preview.PreviewRequest) -> preview.Preview:
        threads.append(threading.current_thread())
        release.wait(10)
        return preview.make_preview(request)

    previews = preview.ScenePreviews(compute)
    try:
        first = previews.ask(preview.PreviewRequest(_objects(shapes.cube())))
        second = previews.ask(preview.PreviewRequest(_objects(shapes.tetrahedron())))
        third = previews.ask(preview.PreviewRequest(_objects(shapes.torus(4, 3))))
        assert previews.take() is None
        release.set()
        assert previews.ready.wait(20)
        number, made = previews.take()  # type: ignore[misc]
        assert (first, second, number) == (1, 2, third)
        assert made.total == 48
        assert previews.take() is None
        assert threads and threading.main_thread() not in threads
    finally:
        previews.close()


@pytest.mark.timeout(60)
def test_a_failing_scene_preview_is_logged_and_the_next_one_comes(caplog):
    failed = threading.Event()

    def compute(request: preview.PreviewRequest) -> preview.Preview:
        if len(request.objects) == 2:
            failed.set()
            raise RuntimeError("boom")
        return preview.make_preview(request)

    previews = preview.ScenePreviews(compute)
    try:
        with caplog.at_level("ERROR", logger="livemod.preview"):
            previews.ask(preview.PreviewRequest(_objects(shapes.cube(), shapes.cube())))
            assert failed.wait(20)
            number = previews.ask(preview.PreviewRequest(_objects(shapes.cube())))
            assert previews.ready.wait(20)
        taken = previews.take()
        assert taken is not None and taken[0] == number == 2
        assert "the preview of 1 failed" in caplog.text and "boom" in caplog.text
    finally:
        previews.close()
