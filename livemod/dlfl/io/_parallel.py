"""Running the readers' and writers' passes on a few threads, results in order.

The passes over 65,536 lines are whole-array numpy steps, and numpy lets go of
the GIL inside them (``fromstring`` included), so two passes on two threads
take little more than one. :func:`map_in_order` keeps a few passes in flight and
hands the results back in input order, so a writer can stream them to its file
and a reader can merge them as if they had run one after another.
"""

from __future__ import annotations

import itertools
import os
from collections import deque
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import Future, ThreadPoolExecutor
from typing import TypeVar

T = TypeVar("T")
R = TypeVar("R")

# more threads than this gain little on memory-bound passes, and each one in
# flight holds its temporaries (tens of MB for a pass of 65,536 lines)
MAX_THREADS = 4


def io_threads() -> int:
    """How many threads the passes use: the CPUs this process may run on, at most
    :data:`MAX_THREADS`."""
    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        cpus = os.cpu_count() or 1
    return max(1, min(MAX_THREADS, cpus))


def map_in_order(fn: Callable[[T], R], items: Iterable[T], threads: int | None = None,
                 ) -> Iterator[R]:
    """``fn(item)`` for every item, in the items' order, computed on ``threads`` threads.

    At most ``threads + 1`` results are computed ahead of the one the caller
    waits for, so memory stays bounded however long ``items`` is. One item, or
    one thread, runs in the calling thread.

    Args:
        fn: a function safe to call from several threads at once.
        items: its arguments.
        threads: how many threads (default :func:`io_threads`).

    Yields:
        The results, in the order of ``items``.

    Raises:
        Whatever ``fn`` raises, when its result is reached; the passes still in
        flight are finished or cancelled first.
    """
    count = io_threads() if threads is None else threads
    todo = iter(items)
    head = list(itertools.islice(todo, 2))
    if count <= 1 or len(head) < 2:  # nothing to overlap
        yield from map(fn, itertools.chain(head, todo))
        return
    yield from _threaded(fn, head, todo, count)


def _threaded(fn: Callable[[T], R], head: list[T], todo: Iterator[T], count: int,
              ) -> Iterator[R]:
    """:func:`map_in_order` on a pool of ``count`` threads, ``head`` the first items."""
    pool = ThreadPoolExecutor(max_workers=count, thread_name_prefix="livemod-io")
    pending: deque[Future[R]] = deque(pool.submit(fn, item) for item in head)
    try:
        while pending:
            for item in itertools.islice(todo, count + 1 - len(pending)):
                pending.append(pool.submit(fn, item))
            yield pending.popleft().result()
    finally:
        pool.shutdown(wait=True, cancel_futures=True)
