"""RunResult's named constructors, RunStatus, and what a run's output writes."""

from __future__ import annotations

import json
import pickle

from livemod.dlfl.io import save_mesh
from livemod.dlfl.scene import Scene
from livemod.dlfl.shapes import cube
from livemod.runner import RunResult, RunStatus
from livemod.runner.errors import cancelled_error
from livemod.runner.results import (
    object_fields,
    save_problem,
    save_result,
    snapshot_mesh,
)


def _scene_of_two() -> Scene:
    scene = Scene()
    scene.add(cube(), "other")
    scene.add(cube(), "current")
    return scene


def test_run_status_reads_and_writes_as_its_old_strings():
    assert [str(s) for s in RunStatus] == ["ok", "error", "cancelled", "paused"]
    assert RunStatus.OK == "ok" and f"{RunStatus.PAUSED}" == "paused"
    assert json.dumps({"status": RunStatus.ERROR}) == '{"status": "error"}'
    assert pickle.loads(pickle.dumps(RunStatus.CANCELLED)) is RunStatus.CANCELLED


def test_finished_and_paused_results():
    scene = _scene_of_two()
    arrays = snapshot_mesh(cube())
    done = RunResult.finished(3, "s.py", (), arrays, 0.5, values=(("a", 1),),
                              **object_fields(scene))
    assert (done.status, done.step_index, done.stale, done.error) == (RunStatus.OK, None,
                                                                      False, None)
    assert done.arrays is arrays and done.values == (("a", 1),)
    assert done.current_object == (scene.current, "current") and len(done.other_objects) == 1
    held = RunResult.paused(3, "s.py", (), 4, arrays, 0.25)
    assert (held.status, held.step_index, held.elapsed, held.others) == (RunStatus.PAUSED, 4,
                                                                        0.25, None)


def test_a_failed_result_shows_the_last_good_one_stale():
    good = RunResult.finished(1, "s.py", (), snapshot_mesh(cube()), 0.1,
                              **object_fields(_scene_of_two()))
    partial = snapshot_mesh(cube())
    error = cancelled_error("s.py", 7)
    failed = RunResult.failed(2, "s.py", RunStatus.CANCELLED, (), error, 0.2, last_good=good,
                              partial=partial)
    assert (failed.status, failed.error, failed.stale, failed.partial) == (
        RunStatus.CANCELLED, error, True, partial)
    assert failed.arrays is good.arrays and failed.others is good.others
    assert (failed.other_objects, failed.current_object) == (good.other_objects,
                                                             good.current_object)
    first = RunResult.failed(1, "s.py", RunStatus.ERROR, (), error, 0.2, last_good=None)
    assert (first.arrays, first.preview, first.stale, first.current_object) == (
        None, None, False, None)


def test_a_run_s_output_makes_its_folder_and_is_not_written_without_an_object(tmp_path):
    mesh = cube()
    save_result([("cube", mesh)], str(tmp_path / "run" / "m.obj"))
    save_mesh(mesh, tmp_path / "m.obj")
    assert (tmp_path / "run" / "m.obj").read_bytes() == (tmp_path / "m.obj").read_bytes()
    assert save_problem([], str(tmp_path / "none.obj")) == \
        f"the script left no mesh; {tmp_path / 'none.obj'} was not written"
    assert not (tmp_path / "none.obj").exists()


def test_a_snapshot_carries_the_face_colours_read_only_and_pickles():
    mesh = cube()
    mesh.set_face_color(int(mesh.face_ids()[3]), (0.25, 0.5, 1.0))
    arrays = snapshot_mesh(mesh)
    assert arrays.face_colors is not None and not arrays.face_colors.flags.writeable
    assert arrays.face_colors[3].tolist() == [0.25, 0.5, 1.0]
    back = pickle.loads(pickle.dumps(arrays))
    assert back.face_colors[3].tolist() == [0.25, 0.5, 1.0]
    assert snapshot_mesh(cube()).face_colors is None
