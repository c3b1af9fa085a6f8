"""Helpers shared by the runner tests (not a test module)."""

from __future__ import annotations

import contextlib
import importlib
import os
import queue
import sys
import time
from collections.abc import Callable

import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.runner import LiveSession, Playback, RunControl, RunResult, execute
from livemod.runner.playback import Action
from livemod.runner.results import snapshot_scene

HERE = os.path.dirname(os.path.abspath(__file__))
WAIT = 10.0  # generous: CI machines are slow and shared


def script_path(name: str) -> str:
    return os.path.join(HERE, name)


def next_result(session: LiveSession, where: Callable[[RunResult], bool] = lambda r: True,
                timeout: float = WAIT) -> RunResult:
    """The next result matching ``where`` (others are skipped)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            result = session.results.get(timeout=0.02)
        except queue.Empty:
            continue
        if where(result):
            return result
    raise AssertionError(f"no matching result within {timeout} s")


def drain(session: LiveSession, quiet: float = 0.6, limit: float = WAIT) -> list[RunResult]:
    """All results until none has come for ``quiet`` seconds."""
    got: list[RunResult] = []
    deadline = time.monotonic() + limit
    last = time.monotonic()
    while time.monotonic() - last < quiet and time.monotonic() < deadline:
        try:
            got.append(session.results.get(timeout=0.02))
            last = time.monotonic()
        except queue.Empty:
            pass
    return got


def settle(session: LiveSession, quiet: float = 0.7) -> list[RunResult]:
    """The first result (waiting up to WAIT s), then all others until ``quiet`` s pass
    without one; preview copies left out."""
    first = next_result(session, lambda r: r.preview is None)
    return [first, *main_results(drain(session, quiet=quiet))]


def main_results(results: list[RunResult]) -> list[RunResult]:
    """Results without the second, preview-carrying copies."""
    return [r for r in results if r.preview is None]


def write_by_rename(path: str, text: str) -> None:
    """Atomic save: write a temp file, then ``os.replace`` it over the script."""
    tmp = path + ".tmp~save"
    with open(tmp, "w", encoding="utf-8") as handle:
        handle.write(text)
    os.replace(tmp, path)


def write_in_place(path: str, text: str) -> None:
    """Truncate-and-write save (VS Code, nano)."""
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(text)


def write_vim_style(path: str, text: str) -> None:
    """Vim's move-away save: rename old to ``path~``, write new, delete the backup."""
    backup = path + "~"
    os.replace(path, backup)
    with open(path, "w", encoding="utf-8") as handle:
        handle.write(text)
    os.remove(backup)


def straight_snapshots(path: str, seed: int = 0) -> tuple[list[MeshArrays | None], MeshArrays]:
    """Snapshots after every step of one uninterrupted run, and the final outcome's arrays.

    The run pauses at every step only long enough to take the snapshot (it plays at
    a huge rate), all in this thread.
    """
    playback = Playback(rate=1e9)
    playback.apply(Action.PLAY)  # no run yet: playing from step 0 ...
    playback.apply(Action.NEW_RUN)  # ... in the run started below
    snaps: list[MeshArrays | None] = []
    control = RunControl(playback, lambda index, steps, scene, run: snaps.append(
        snapshot_scene(scene)))
    outcome = execute(path, seed=seed, control=control)
    assert outcome.status == "ok", outcome.error
    final = snapshot_scene(outcome.scene)
    assert final is not None
    return snaps, final


def same_mesh(a: MeshArrays | None, b: MeshArrays | None) -> bool:
    """Equal topology and positions."""
    assert a is not None and b is not None
    return (
        np.array_equal(a.face_offsets, b.face_offsets)
        and np.array_equal(a.corner_vertex, b.corner_vertex)
        and np.array_equal(a.face_ids, b.face_ids)
        and np.allclose(a.positions, b.positions)
    )


@contextlib.contextmanager
def started_session(path, **options):  # noqa: ANN001, ANN003, ANN201  (a LiveSession)
    """A started LiveSession on ``path`` with a manual notifier, closed afterwards."""
    from livemod.runner import LiveSession, ManualNotifier

    live = LiveSession(str(path), notifier=ManualNotifier(), **options)
    with closing_session(live):
        live.start()
        yield live


@contextlib.contextmanager
def closing_session(live):  # noqa: ANN001, ANN201  (a LiveSession)
    """Yield ``live``; close it afterwards and check its threads have ended."""
    try:
        yield live
    finally:
        live.close()
        assert live.join(10)


@contextlib.contextmanager
def manual_session(path, **options):  # noqa: ANN001, ANN003, ANN201
    """``(session, notifier)``: a started LiveSession on ``path`` whose file events
    a ManualNotifier gives (``notifier.fire(path)``), debounced 50 ms, with no
    preview unless ``options`` say otherwise; closed afterwards."""
    from livemod.runner import LiveSession, ManualNotifier

    notifier = ManualNotifier()
    live = LiveSession(str(path), notifier=notifier, **{"debounce": 0.05, "preview": False,
                                                         **options})
    with closing_session(live):
        live.start()
        yield live, notifier


def vertices_script(n: int) -> str:
    """A script that makes ``n`` point-spheres (``n`` steps, ``n`` vertices)."""
    return f"for i in range({n}):\n    createVertex((i, 0, 0))\n"


def vertex_count(result: RunResult) -> int:
    """The vertices of a result's mesh (the result must have one)."""
    assert result.arrays is not None, result.error
    return result.arrays.counts[0]


def wait_until(condition, timeout: float = 10.0):  # noqa: ANN001, ANN201
    """Poll ``condition`` every 5 ms until it gives something truthy, and return
    that; fail the test after ``timeout`` seconds."""
    deadline = time.monotonic() + timeout
    while not (value := condition()):
        assert time.monotonic() < deadline, "timed out"
        time.sleep(0.005)
    return value


def host_imports(folder, monkeypatch, name: str, text: str):  # noqa: ANN001, ANN201
    """Write ``name``.py in ``folder`` and import it as the host would (before
    any run): a helper module the runs must import afresh and give back."""
    (folder / f"{name}.py").write_text(text)
    monkeypatch.syspath_prepend(str(folder))
    monkeypatch.delitem(sys.modules, name, raising=False)
    return importlib.import_module(name)
