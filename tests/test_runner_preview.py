"""The patch preview: computed off the caller's thread, posted as a second result."""

from __future__ import annotations

import threading

import pytest

from livemod.dlfl import from_polygons
from livemod.dlfl.mesh import Mesh
from livemod.runner import LiveSession, ManualNotifier, preview
from livemod.runner.results import RunResult, snapshot_mesh

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

    worker = preview.PreviewWorker(lambda result, arrays: posted.append(result.run_id),
                                   lambda result: True, compute)
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
