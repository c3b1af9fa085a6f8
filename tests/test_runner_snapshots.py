"""The snapshot cache: a byte budget, least recently used evicted first."""

from __future__ import annotations

from livemod.dlfl import from_polygons
from livemod.runner.results import RunResult, snapshot_mesh
from livemod.runner.snapshots import SnapshotCache, result_bytes


def paused(run_id: int, index: int) -> RunResult:
    arrays = snapshot_mesh(from_polygons([(0, 0, 0), (1, 0, 0), (0, 1, float(index))],
                                         [(0, 1, 2)]))
    return RunResult.paused(run_id, "s.py", (), index, arrays, 0.0)


def test_budget_evicts_least_recently_used():
    size = result_bytes(paused(1, 0))
    cache = SnapshotCache(budget=3 * size)
    cache.reset(1)
    for k in range(3):
        cache.put(paused(1, k))
    assert cache.get(0) is not None  # 0 is now the most recently used
    cache.put(paused(1, 3))
    assert len(cache) == 3 and cache.nbytes <= 3 * size
    assert cache.get(1) is None and cache.get(0) is not None and cache.get(3) is not None


def test_other_runs_and_oversized_results_are_not_kept():
    cache = SnapshotCache(budget=10)
    cache.reset(2)
    cache.put(paused(2, 0))  # bigger than the budget
    cache.budget = 10**9
    cache.put(paused(1, 0))  # an older run
    assert len(cache) == 0
    cache.put(paused(2, 5))
    assert cache.get(5) is not None
    cache.reset(3)
    assert len(cache) == 0 and cache.nbytes == 0


def test_other_objects_one_by_one_and_joined_are_counted_once() -> None:
    from livemod.dlfl.scene import Scene
    from livemod.dlfl.shapes import cube, tetrahedron
    from livemod.runner.results import object_fields
    from livemod.runner.snapshots import arrays_bytes

    scene = Scene()
    scene.add(tetrahedron(), "tet")
    scene.add(cube(), "box")
    scene.add(cube(), "current")
    fields = object_fields(scene)
    assert [(oid, name) for oid, name, _ in fields["other_objects"]] == [(0, "tet"), (1, "box")]
    assert fields["others"].counts == (12, 18, 10)
    assert fields["current_object"] == (2, "current")
    parts = [arrays for _, _, arrays in fields["other_objects"]]
    assert all(not arrays.positions.flags.writeable for arrays in (*parts, fields["others"]))
    result = RunResult.finished(1, "s.py", (), None, 0.0, **fields)
    assert result_bytes(result) == sum(map(arrays_bytes, (*parts, fields["others"])))
    scene.kill(1)
    lone = object_fields(scene)
    assert lone["current_object"] == (2, "current")
    assert object_fields(Scene())["current_object"] is None
    assert lone["others"] is lone["other_objects"][0][2]  # one object: no second copy
    result = RunResult.finished(1, "s.py", (), None, 0.0, **lone)
    assert result_bytes(result) == arrays_bytes(lone["others"])
