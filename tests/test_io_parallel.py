"""Passes on a few threads, results in order (livemod.dlfl.io._parallel)."""

from __future__ import annotations

import threading
import time

import pytest

from livemod.dlfl.io._parallel import MAX_THREADS, io_threads, map_in_order


def test_results_come_in_input_order_whatever_order_they_finish_in() -> None:
    def slow_for_small(x: int) -> int:
        time.sleep(0.002 * (10 - x % 10))
        return x * x

    assert list(map_in_order(slow_for_small, range(40), threads=3)) == [x * x for x in range(40)]


def test_work_runs_on_other_threads_and_only_a_few_ahead() -> None:
    started: list[int] = []
    names: set[str] = set()
    lock = threading.Lock()

    def note(x: int) -> int:
        with lock:
            started.append(x)
            names.add(threading.current_thread().name)
        return x

    results = map_in_order(note, range(100), threads=2)
    assert next(results) == 0
    time.sleep(0.05)
    with lock:
        assert len(started) <= 2 + 1 + 1  # the one taken, and at most threads + 1 ahead
    assert list(results) == list(range(1, 100))
    assert all(name.startswith("livemod-io") for name in names)


@pytest.mark.parametrize("threads", [1, 2])
def test_an_error_reaches_the_caller_at_its_item(threads: int) -> None:
    def fail_at_five(x: int) -> int:
        if x == 5:
            raise ValueError("item 5 is bad")
        return x

    results = map_in_order(fail_at_five, range(20), threads=threads)
    assert [next(results) for _ in range(5)] == [0, 1, 2, 3, 4]
    with pytest.raises(ValueError, match="item 5"):
        next(results)


def test_one_item_or_one_thread_runs_in_the_calling_thread() -> None:
    me = threading.current_thread()
    assert list(map_in_order(lambda x: threading.current_thread() is me, [1])) == [True]
    assert all(map_in_order(lambda x: threading.current_thread() is me, range(5), threads=1))
    assert list(map_in_order(lambda x: x, [])) == []


def test_thread_count_is_bounded() -> None:
    assert 1 <= io_threads() <= MAX_THREADS
