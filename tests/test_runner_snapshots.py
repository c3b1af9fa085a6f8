"""The snapshot cache: a byte budget, least recently used evicted first."""

from __future__ import annotations

from livemod.dlfl import from_polygons
from livemod.runner.results import RunResult, snapshot_mesh
from livemod.runner.snapshots import SnapshotCache, result_bytes


def paused(run_id: int, index: int) -> RunResult:
    arrays = snapshot_mesh(from_polygons([(0, 0, 0), (1, 0, 0), (0, 1, float(index))],
                                         [(0, 1, 2)]))
    return RunResult(run_id, "s.py", "paused", (), index, arrays, None, None, 0.0, False)


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
