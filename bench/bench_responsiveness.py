"""How soon livemod answers while a run never ends (plain python; prints medians).

    python bench/bench_responsiveness.py [--repeat N]

1. Each control of a LiveSession (pause, step, goto, play, resume, run to the end,
   reload, parameters, selection) called while the worker loops on ``createVertex``
   forever: the call must return at once. Target: a few ms (the tests once bounded
   each at 0.5 s).
2. Cancelling ``createVertex(...); while True: pass`` through its ``RunControl``: time
   from ``cancel()`` to the worker's end (the loop's compiled check). Target: well
   under 1 s (the tests once bounded it at 1 s).
3. A save while the run cannot check for cancellation, so the session interrupts it
   every ``_FORCE_AFTER`` (0.1 s; a run no interrupt stops is abandoned after
   ``GRACE``, which bench_runner.py times): an endless generator expression, and a
   loop in a helper module. Time from ``reload()`` to the new run's result. Target:
   well under 1 s (the tests once bounded them at 2 s).
4. Ctrl-C (SIGINT to the process group) of ``livemod batch -j 2`` whose running
   variants never end: time to the process's exit. Target: well under 1 s (the test
   once bounded it at 2.5 s).

The tests (test_runner_playback, test_runner_races, test_runner_execute,
test_runner_watch, test_runner_cli) check the same behaviour without a clock: every
control returns, the run ends, the interrupt stopped it (no run is left in the
background), the batch exits with 130. The cancel of ``while True: pass`` by a save
is bench_runner.py's.
"""

from __future__ import annotations

import argparse
import os
import queue
import signal
import statistics
import subprocess
import sys
import tempfile
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from livemod.runner import LiveSession, ManualNotifier, RunControl, execute  # noqa: E402

ENDLESS_COMMANDS = "while True:\n    createVertex((0, 0, 0))\n"
ENDLESS_GENERATOR = "any(False for _ in iter(int, 1))\n"
CHECKED_LOOP = "createVertex((0, 0, 0))\nwhile True:\n    pass\n"
HELPER_LOOP = "import spinner\ncreateVertex((0, 0, 0))\nspinner.spin()\n"
SPINNER = "def spin():\n    while True:\n        pass\n"
ENDLESS_VARIANTS = (
    "import time\n"
    "n = param('n', 0)\n"
    "load('cube')\n"
    "while n >= 2:  # variants 0 and 1 finish, the others would run for ever\n"
    "    time.sleep(0.01)\n")
TWO_VERTICES = "createVertex((0, 0, 0))\ncreateVertex((1, 0, 0))\n"


def _started(script: Path) -> LiveSession:
    live = LiveSession(str(script), notifier=ManualNotifier(), preview=False)
    live.start()
    deadline = time.monotonic() + 10
    while live.activity is None and time.monotonic() < deadline:
        time.sleep(0.01)
    return live


def _closed(live: LiveSession) -> None:
    live.close()
    live.join(10)


def _controls(live: LiveSession) -> dict[str, Callable[[], Any]]:
    return {"pause": live.pause, "step_forward": live.step_forward,
            "step_back": live.step_back, "goto_step(3)": lambda: live.goto_step(3),
            "play(5)": lambda: live.play(5.0), "resume": live.resume,
            "run_to_end": live.run_to_end, "reload": live.reload,
            "set_parameters": lambda: live.set_parameters({"a": 1}),
            "set_selection": lambda: live.set_selection(None)}


def bench_controls(folder: Path, repeats: int) -> None:
    script = folder / "busy.py"
    script.write_text(ENDLESS_COMMANDS)
    live = _started(script)
    try:
        times: dict[str, list[float]] = {name: [] for name in _controls(live)}
        for _ in range(repeats):
            for name, control in _controls(live).items():
                started = time.perf_counter()
                control()
                times[name].append(time.perf_counter() - started)
    finally:
        _closed(live)
    for name, spent in times.items():
        print(f"  {name}: median {1000 * statistics.median(spent):.2f} ms, "
              f"max {1000 * max(spent):.2f} ms")


def _report(label: str, spent: list[float]) -> None:
    print(f"  {label}: median {1000 * statistics.median(spent):.1f} ms, "
          f"max {1000 * max(spent):.1f} ms  target well under 1 s")


def bench_checked_cancel(folder: Path, repeats: int) -> None:
    script = folder / "loop.py"
    script.write_text(CHECKED_LOOP)
    spent = []
    for _ in range(repeats):
        control = RunControl()
        worker = threading.Thread(target=execute, args=(str(script),), kwargs={"control": control})
        worker.start()
        time.sleep(0.2)  # under way
        started = time.perf_counter()
        control.cancel()
        worker.join(10)
        spent.append(time.perf_counter() - started)
    _report("cancel() to the worker's end", spent)


def bench_forced_stop(folder: Path, repeats: int, name: str, script_text: str) -> None:
    script = folder / f"{name}.py"
    (folder / "spinner.py").write_text(SPINNER)
    spent = []
    for _ in range(repeats):
        script.write_text(script_text)
        live = _started(script)
        try:
            script.write_text(TWO_VERTICES)
            started = time.perf_counter()
            live.reload()
            while live.results.get(timeout=10).status != "ok":
                pass
            spent.append(time.perf_counter() - started)
        except queue.Empty:
            print(f"  {name}: not stopped within 10 s")
            return
        finally:
            _closed(live)
    _report(f"{name}: reload() to the next run's result", spent)


def bench_batch_interrupt(folder: Path, repeats: int) -> None:
    script = folder / "variants.py"
    script.write_text(ENDLESS_VARIANTS)
    spent = []
    for _ in range(repeats):
        proc = subprocess.Popen(
            [sys.executable, "-m", "livemod.runner.cli", "batch", str(script), "--param",
             "n=0:7:8", "-o", str(folder / "out" / "{n}.obj"), "-j", "2"],
            start_new_session=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
        assert proc.stderr is not None
        for _ in range(2):  # a progress line per finished variant: 0 and 1 are done
            proc.stderr.readline()
        started = time.perf_counter()
        os.killpg(proc.pid, signal.SIGINT)
        proc.communicate(timeout=30)
        spent.append(time.perf_counter() - started)
    _report("SIGINT to the batch's exit", spent)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="runs per measure (median)")
    args = parser.parse_args(argv)
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        print("controls while a run never ends (target: a few ms each):")
        bench_controls(folder, args.repeat)
        print("stopping runs that never end:")
        bench_checked_cancel(folder, args.repeat)
        bench_forced_stop(folder, args.repeat, "an endless generator expression",
                          ENDLESS_GENERATOR)
        bench_forced_stop(folder, args.repeat, "a loop in a helper module", HELPER_LOOP)
        bench_batch_interrupt(folder, args.repeat)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
