"""The patch preview: computed off the caller's thread, posted as a second result."""

from __future__ import annotations

import threading

import pytest

from livemod.dlfl import from_polygons
from livemod.dlfl.mesh import Mesh
from livemod.runner import LiveSession, ManualNotifier, preview
from livemod.runner.results import snapshot_mesh

from .runner_scripts.support import closing_session, next_result, script_path, started_session

QUAD = ([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 1, 2, 3)])


def test_preview_subdivides_a_copy_level_times(monkeypatch):
    calls = []

    def fake_subdivide(mesh: Mesh, scheme: str) -> None:
        calls.append(scheme)
        mesh.create_face([(5, 5, 5), (6, 5, 5), (6, 6, 5)])  # in place, like the real one

    monkeypatch.setattr(preview, "_subdivide_function", lambda: fake_subdivide)
    mesh = from_polygons(*QUAD)
    before = mesh.counts()
    arrays = preview.preview_arrays(mesh, scheme="doo-sabin", levels=2)
    assert calls == ["doo-sabin", "doo-sabin"]
    assert mesh.counts() == before
    assert arrays is not None and arrays.counts[2] == before[2] + 4
    assert not arrays.positions.flags.writeable


def test_no_preview_without_the_module_or_over_budget(monkeypatch):
    mesh = from_polygons(*QUAD)
    monkeypatch.setattr(preview, "_subdivide_function", lambda: None)
    assert preview.preview_arrays(mesh) is None
    monkeypatch.setattr(preview, "_subdivide_function", lambda: lambda m, s: None)
    assert preview.preview_arrays(mesh, face_budget=10) is None
    assert preview.preview_arrays(Mesh()) is None


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
