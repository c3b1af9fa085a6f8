"""Timing shared by the benchmark scripts (``python bench/bench_*.py``).

Every figure is a median over several runs, in wall time and in this process's
CPU time: the development machines are shared, and when other jobs compete for
the two cores the wall time grows while the CPU time stays close to what the
work costs on a quiet machine.
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable
from typing import Any


def median_times(
    run: Callable[..., object], repeats: int, setup: Callable[[], Any] | None = None
) -> tuple[float, float]:
    """Median ``(wall seconds, CPU seconds)`` of ``repeats`` calls of ``run``.

    With ``setup``, each call is ``run(setup())`` and the setup is not timed.
    """
    walls, cpus = [], []
    for _ in range(repeats):
        args = () if setup is None else (setup(),)
        wall, cpu = time.perf_counter(), time.process_time()
        result = run(*args)
        walls.append(time.perf_counter() - wall)
        cpus.append(time.process_time() - cpu)
        # freed after the clocks stop: a 1M-face mesh's arrays take ~0.1 s to
        # give back here, which is not the work being timed
        del result
    return statistics.median(walls), statistics.median(cpus)
