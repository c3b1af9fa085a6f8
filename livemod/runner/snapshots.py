"""A memory-budgeted cache of the paused results of the current run.

Going back a step shows a cached snapshot at once when it is still here;
otherwise the session replays the script to that step. The budget bounds
memory whatever the number of steps or the size of the mesh (a 100,000-face
snapshot is some tens of MB, so the default keeps about ten of them).
"""

from __future__ import annotations

import dataclasses
from collections import OrderedDict

from livemod.dlfl.arrays import MeshArrays

from .results import RunResult

DEFAULT_BUDGET = 256 * 2**20  # bytes


def arrays_bytes(arrays: MeshArrays | None) -> int:
    """Bytes held by the numpy arrays of ``arrays`` (0 for None)."""
    if arrays is None:
        return 0
    return sum(int(getattr(arrays, f.name).nbytes) for f in dataclasses.fields(arrays)
               if getattr(arrays, f.name) is not None)


def result_bytes(result: RunResult) -> int:
    """Bytes of the snapshots ``result`` holds (mesh, preview, other objects joined
    and one by one; a lone other object is both, and counted once)."""
    parts = [a for _, _, a in result.other_objects if a is not result.others]
    return sum(arrays_bytes(a) for a in (result.arrays, result.preview, result.others, *parts))


class SnapshotCache:
    """Paused results of one run by step index, least recently used evicted first.

    Not thread-safe: the session calls it under its own lock.
    """

    def __init__(self, budget: int = DEFAULT_BUDGET) -> None:
        self.budget = budget
        self.run_id: int | None = None
        self._items: OrderedDict[int, RunResult] = OrderedDict()
        self._bytes = 0

    @property
    def nbytes(self) -> int:
        """Bytes of the snapshots held now (kept within the memory budget)."""
        return self._bytes

    def reset(self, run_id: int) -> None:
        """Forget everything; cache results of run ``run_id`` from now on."""
        self.run_id = run_id
        self._items.clear()
        self._bytes = 0

    def put(self, result: RunResult) -> None:
        """Keep a paused ``result`` of the current run (replacing one at the same step)."""
        if result.run_id != self.run_id or result.step_index is None:
            return
        size = result_bytes(result)
        if size > self.budget:
            return
        self._drop(result.step_index)
        self._items[result.step_index] = result
        self._bytes += size
        while self._bytes > self.budget:
            self._drop(next(iter(self._items)))

    def get(self, index: int) -> RunResult | None:
        """The cached result at step ``index`` of the current run, or None."""
        result = self._items.get(index)
        if result is not None:
            self._items.move_to_end(index)
        return result

    def indexes(self) -> frozenset[int]:
        """The steps held now."""
        return frozenset(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def _drop(self, index: int) -> None:
        old = self._items.pop(index, None)
        if old is not None:
            self._bytes -= result_bytes(old)
