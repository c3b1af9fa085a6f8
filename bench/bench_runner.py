"""Runner benchmarks (plain python; prints medians of several runs).

    python bench/bench_runner.py [--quick]

1. Overhead of step recording (and of the cancellation checks compiled into the
   script) on a straight run of 10,000 small commands, against the same code
   exec'd with no step hook and no checks; and the record alone on createVertex,
   least of interleaved timings and timed in pairs. Target: at most 10 %.
2. Save-to-result latency for a 20-command script on a 10,000-face mesh, through
   a real LiveSession and watchdog: time from ``os.replace`` to the result in the
   queue, minus the debounce. Target: at most 100 ms plus the debounce.
3. Cancel latency of ``while True: pass`` after the next save (minus debounce),
   and save-to-result latency while the old run is blocked in ``time.sleep`` or
   ``Event.wait``, where it is abandoned after the grace (minus debounce).
   Target: the next result within 1 s plus its own run time.
4. A batch of 32 variants on 2 processes against one after another. Target: 1.7x.
5. Stepping back from step 999 of a 1,000-step script on a 100,000-face mesh:
   seconds per step back (cache hit, and replay) and the growth of peak memory.
6. What giving the process back costs a run, timed in pairs: a one-line script
   run with the process state restored against the same run with a state that
   restores nothing, as a live session's runs (the library pictured once) and
   as headless runs (the whole process pictured and restored a run).
"""

from __future__ import annotations

import argparse
import gc
import os
import queue
import resource
import statistics
import subprocess
import sys
import tempfile
import time
import timeit

from livemod.dlfl import from_polygons
from livemod.dlfl.run_context import RunContext, use_run
from livemod.dlfl.scene import Scene, use_scene
from livemod.runner import LiveSession, execute
from livemod.runner.execute import RunLease, capture_process
from livemod.runner.process import ProcessState

# the step-overhead workloads, their loops ``{n}`` long (bench_step_instructions.py
# runs the same scripts under callgrind)
SMALL_TEMPLATE = (
    "from livemod.dlfl import *\n"
    "for i in range({n}):\n"
    "    createVertex((i * 0.1, 0.0, 0.0))\n"
)

# the thesis's Fig. 24, a triangle from three createVertex and three insertEdge,
# {n} times: a script of small commands the way the thesis writes them
TRIANGLES_TEMPLATE = (
    "from livemod.dlfl import *\n"
    "for i in range({n}):\n"
    "    x = i * 2.0\n"
    "    a, _ = createVertex((x, 0.0, 0.0))\n"
    "    b, _ = createVertex((x + 1.0, 0.0, 0.0))\n"
    "    c, _ = createVertex((x, 1.0, 0.0))\n"
    "    _, a, b, _, _ = insertEdge(a, b)\n"
    "    _, b, c, _, _ = insertEdge(b, c)\n"
    "    insertEdge(c, a)\n"
)

MIXED_TEMPLATE = (
    "from livemod.dlfl import *\n"
    "es = edges()\n"
    "for i in range({n}):\n"
    "    v = subdivideEdge(es[i])[0]\n"
    "    move([v], (0.0, 0.0, 0.001))\n"
)

EXTRUSION_TEMPLATE = (
    "from livemod.dlfl import *\n"
    "from livemod.dlfl import current_scene, from_polygons\n"
    "P = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]\n"
    "Q = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]\n"
    "current_scene().add(from_polygons(P, Q))\n"
    "face = faces()[1]\n"
    "for i in range({n}):\n"
    "    face = extrude('cubical', face, 0.1)\n"
)

SMALL_COMMANDS = SMALL_TEMPLATE.format(n=10000)
TRIANGLES = TRIANGLES_TEMPLATE.format(n=1667)  # 10,002 steps
MIXED_COMMANDS = MIXED_TEMPLATE.format(n=5000)
EXTRUSIONS = EXTRUSION_TEMPLATE.format(n=2000)

TWENTY_COMMANDS = (
    "{marker}\n"
    "es = edges()\n"
    "for i in range(10):\n"
    "    subdivideEdge(es[i])\n"
    "    move(verts()[-1:], (0.0, 0.0, 0.01 * i))\n"
)

VARIANT = (
    "from livemod.dlfl import *\n"
    "from livemod.dlfl import current_scene, from_polygons\n"
    "n = int(size)\n"
    "pts = [(x, y, 0.0) for y in range(n + 1) for x in range(n + 1)]\n"
    "quads = [(y * (n + 1) + x, y * (n + 1) + x + 1, (y + 1) * (n + 1) + x + 1,"
    " (y + 1) * (n + 1) + x) for y in range(n) for x in range(n)]\n"
    "current_scene().add(from_polygons(pts, quads))\n"
    "for e in edges()[:3000]:\n"
    "    subdivideEdge(e)\n"
)


def grid_mesh(n: int):
    """An ``n`` x ``n`` grid of quads (``n * n`` faces plus the hole)."""
    pts = [(x, y, 0.0) for y in range(n + 1) for x in range(n + 1)]
    quads = [(y * (n + 1) + x, y * (n + 1) + x + 1, (y + 1) * (n + 1) + x + 1,
              (y + 1) * (n + 1) + x) for y in range(n) for x in range(n)]
    return from_polygons(pts, quads)


def median_of(fn, repeats: int) -> float:
    return statistics.median(fn() for _ in range(repeats))


def bench_step_overhead(folder: str, repeats: int, source: str = SMALL_COMMANDS,
                        base: Scene | None = None, steps: int = 10000,
                        ) -> dict[str, tuple[float, float, float]]:
    """(median wall, median CPU, least CPU) seconds of ``source`` run three ways: the runner's
    execute, a bare exec, and a bare exec with a no-op step hook (the core's own
    cost of calling a hook). Each starts from a copy of ``base`` (or empty)."""
    path = os.path.join(folder, "small.py")
    with open(path, "w") as handle:
        handle.write(source)

    def runner() -> None:
        outcome = execute(path, source=source, base=base)
        assert outcome.status == "ok" and len(outcome.steps) == steps, outcome.error

    def bare(hook=None) -> None:
        code = compile(source, path, "exec")
        scene = base.copy() if base is not None else Scene()
        with use_scene(scene), use_run(RunContext(step_hook=hook)):
            exec(code, {"__name__": "__main__"})

    ways = {"runner": runner, "bare": bare, "noop hook": lambda: bare(lambda label: None)}
    times: dict[str, list[tuple[float, float]]] = {name: [] for name in ways}
    for fn in ways.values():
        fn()  # warm up imports and caches
    for _ in range(repeats):
        for name, fn in ways.items():  # interleaved, so load changes hit all alike
            # the previous way's scene is garbage now: collect it before the clock
            # starts, or the next way pays for it
            gc.collect()
            wall, cpu = time.perf_counter(), time.process_time()
            fn()
            times[name].append((time.perf_counter() - wall, time.process_time() - cpu))
    return {name: (statistics.median(t[0] for t in runs), statistics.median(t[1] for t in runs),
                   min(t[1] for t in runs))
            for name, runs in times.items()}


def print_overhead(title: str, ways: dict[str, tuple[float, float, float]],
                   repeats: int) -> None:
    """Medians (wall and CPU), and the overhead from the least CPU times, which load
    from other processes inflates least."""
    (rw, rc, rm), (bw, bc, bm), (nw, nc, nm) = (
        ways["runner"], ways["bare"], ways["noop hook"])
    print(f"{title} (median of {repeats}, wall/CPU ms): runner {rw * 1e3:.0f}/{rc * 1e3:.0f}, "
          f"bare exec {bw * 1e3:.0f}/{bc * 1e3:.0f}, bare + no-op hook {nw * 1e3:.0f}/"
          f"{nc * 1e3:.0f}; overhead {100 * (rc / bc - 1):+.1f} % (median CPU), "
          f"{100 * (rm / bm - 1):+.1f} % (least CPU; no-op hook alone "
          f"{100 * (nm / bm - 1):+.1f} %)")


def bench_hook_cost(repeats: int, n: int = 20000) -> dict[str, float]:
    """Least seconds per command over ``repeats`` interleaved timings (load inflates
    the least least) of createVertex called from a loop compiled as the script, as
    in a run. Keys: "none" (no hook), and the extra seconds of "runner" (the
    recorder installed as a straight run installs it: its lean hook records a
    known caller's steps), "hook" (every step through the runner's full hook, as in
    runs that may pause) and "noop" (a hook that does nothing); "read" is reading
    one recorded step back as a StepRecord."""
    from livemod.dlfl import createVertex
    from livemod.runner.playback import Playback
    from livemod.runner.recording import RunControl, StepRecorder

    script = "/bench/fake_script.py"
    namespace: dict = {"createVertex": createVertex}
    exec(compile("def loop(n):\n    for i in range(n):\n        createVertex((0.0, 0.0, 0.0))\n",
                 script, "exec"), namespace)

    def recorded(scene: Scene, control: RunControl | None) -> RunContext:
        recorder = StepRecorder(script, scene, control)
        recorder.install()
        return recorder.run

    setups = {"none": lambda scene: RunContext(),
              "noop": lambda scene: RunContext(step_hook=lambda label: None),
              "runner": lambda scene: recorded(scene, None),
              "hook": lambda scene: recorded(scene, RunControl(Playback()))}
    best = dict.fromkeys(setups, float("inf"))
    for _ in range(repeats):
        for name, setup in setups.items():
            scene = Scene()
            with use_scene(scene), use_run(setup(scene)):
                cpu = time.process_time()
                namespace["loop"](n)
                best[name] = min(best[name], (time.process_time() - cpu) / n)
    recorder = StepRecorder(script, Scene(), None)
    recorder.install()
    with use_scene(recorder.scene), use_run(recorder.run):
        namespace["loop"](1000)
    read = min(timeit.repeat(lambda: list(recorder.steps), number=1, repeat=repeats)) / 1000
    extra = {name: best[name] - best["none"] for name in ("runner", "hook", "noop")}
    return {"none": best["none"], **extra, "read": read}


CREATE_VERTEX_BODY = "createVertex((0.0, 0.0, 0.0))"
TRIANGLE_BODY = ("x = i * 2.0; a, _ = createVertex((x, 0.0, 0.0)); "
                 "b, _ = createVertex((x + 1.0, 0.0, 0.0)); c, _ = createVertex((x, 1.0, 0.0)); "
                 "_, a, b, _, _ = insertEdge(a, b); _, b, c, _, _ = insertEdge(b, c); "
                 "insertEdge(c, a)")


def bench_hook_pairs(pairs: int, n: int = 20000, body: str = CREATE_VERTEX_BODY,
                     ) -> tuple[float, float, float]:
    """The step record's overhead timed in pairs: a bare loop running ``body`` ``n``
    times (createVertex, or the thesis's triangle) and a recorded one back to back,
    in random order, ``pairs`` times.
    Returns the (first quartile, median, third quartile) of the pairs' ratios minus
    one: a pair shares the machine's state of the moment, so slow drifts of a shared
    VM cancel out of each ratio (the least of interleaved timings does not)."""
    import random

    from livemod.dlfl import createVertex, insertEdge
    from livemod.runner.recording import StepRecorder

    script = "/bench/fake_script.py"
    namespace: dict = {"createVertex": createVertex, "insertEdge": insertEdge}
    exec(compile(f"def loop(n):\n    for i in range(n):\n        {body}\n",
                 script, "exec"), namespace)

    def timed(recorded: bool) -> float:
        scene = Scene()
        recorder = StepRecorder(script, scene, None)
        if recorded:
            recorder.install()
        with use_scene(scene), use_run(recorder.run):
            namespace["loop"](1)  # the first step finds the script's frame
            started = time.perf_counter()
            namespace["loop"](n)
            return time.perf_counter() - started

    ratios = []
    for _ in range(pairs):
        if random.random() < 0.5:
            bare = timed(False)
            recorded = timed(True)
        else:
            recorded = timed(True)
            bare = timed(False)
        ratios.append(recorded / bare - 1.0)
    quartiles = statistics.quantiles(ratios, n=4)
    return quartiles[0], quartiles[1], quartiles[2]


def _wait_for(session: LiveSession, wanted, what: str, timeout: float):
    """The next result for which ``wanted(result)`` holds (others are skipped)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        try:
            result = session.results.get(timeout=0.001)
        except queue.Empty:
            continue
        if wanted(result):
            return result
    raise RuntimeError(f"{what} not shown")


def _wait_ok(session: LiveSession, timeout: float = 30.0):
    return _wait_for(session, lambda r: r.preview is None, "a result", timeout)


def _save(path: str, text: str) -> float:
    tmp = path + ".tmp"
    with open(tmp, "w") as handle:
        handle.write(text)
    saved = time.perf_counter()
    os.replace(tmp, path)
    return saved


def bench_save_latency(folder: str, saves: int, debounce: float) -> tuple[float, float]:
    """(median save-to-result seconds minus debounce, median run seconds)."""
    path = os.path.join(folder, "twenty.py")
    with open(path, "w") as handle:
        handle.write(TWENTY_COMMANDS.format(marker="# 0"))
    base = Scene()
    base.add(grid_mesh(100))
    session = LiveSession(path, debounce=debounce, preview=False, base=base)
    session.start()
    try:
        first = _wait_ok(session)
        assert first.status == "ok", first.error
        assert len(first.steps) == 20 and first.steps[0].counts[2] >= 10000
        latencies, runs = [], []
        for i in range(1, saves + 1):
            time.sleep(0.4)
            saved = _save(path, TWENTY_COMMANDS.format(marker=f"# {i}"))
            result = _wait_ok(session)
            latencies.append(time.perf_counter() - saved - debounce)
            runs.append(result.elapsed)
        return statistics.median(latencies), statistics.median(runs)
    finally:
        session.close()
        session.join()


SPIN = "while True:\n    pass\n"
STUCK = {  # blocks a cancel cannot stop: the run is abandoned after the grace
    "time.sleep(10**6)": "import time\ntime.sleep(10**6)\n",
    "threading.Event().wait()": "import threading\nthreading.Event().wait()\n",
}


def bench_cancel_latency(folder: str, saves: int, debounce: float, block: str = SPIN) -> float:
    """Median seconds from a save to the new result while the old run is in
    ``block`` (a blocked one left behind in the background), minus the debounce."""
    path = os.path.join(folder, "spin.py")
    with open(path, "w") as handle:
        handle.write("createVertex((0, 0, 0))\n")
    session = LiveSession(path, debounce=debounce, preview=False)
    session.start()
    try:
        _wait_ok(session)
        latencies = []
        for i in range(saves):
            _save(path, f"# {i}\n{block}")
            time.sleep(0.5)  # the run is in the block now
            saved = _save(path, f"# {i}\ncreateVertex((0, 0, 0))\n")
            result = _wait_ok(session)
            assert result.status == "ok", result
            latencies.append(time.perf_counter() - saved - debounce)
        return statistics.median(latencies)
    finally:
        session.close()
        session.join()


class _NoState(ProcessState):
    """A process state that pictures and restores nothing (the other half of a pair)."""

    def __init__(self) -> None:  # noqa: D107  (no picture at all)
        self._local = {}
        self.abandoned, self.dirty = 0, False

    def restore(self) -> None:
        pass

    def retake(self) -> None:
        pass

    def close(self) -> None:
        pass


def bench_restore_pairs(folder: str, pairs: int) -> dict[str, tuple[float, float]]:
    """Per run, ``(median extra seconds, median extra fraction)`` of giving the
    process back, timed in pairs of a one-line script (CPU time; the order
    within a pair alternates): ``"session"`` runs share one state (each
    pictures the settings and restores them and the library), ``"headless"``
    runs picture the whole process and restore it."""
    path = os.path.join(folder, "tiny.py")
    with open(path, "w") as handle:
        handle.write("createVertex((0, 0, 0))\n")
    shared, none = capture_process(), _NoState()
    ways = {"session": lambda: execute(path, lease=RunLease(shared)),
            "headless": lambda: execute(path)}
    bare = lambda: execute(path, lease=RunLease(none))  # noqa: E731
    found = {}
    for name, restored in ways.items():
        extra, ratios = [], []
        for i in range(pairs):
            order = (restored, bare) if i % 2 else (bare, restored)
            times = {}
            for run in order:
                started = time.process_time()
                run()
                times[run] = time.process_time() - started
            extra.append(times[restored] - times[bare])
            ratios.append(times[restored] / times[bare] - 1.0)
        found[name] = statistics.median(extra), statistics.median(ratios)
    shared.close()
    return found


BATCH_CHILD = """
import sys, time
from livemod.runner.batch import ProcessPoolVariantExecutor, SerialExecutor, make_variants, run_batch
path, count, jobs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
work = make_variants(path, [{"size": 60 + i % 4} for i in range(count)], None)
executor = ProcessPoolVariantExecutor(jobs) if jobs > 1 else SerialExecutor()
started = time.perf_counter()
results = run_batch(work, executor, quiet=True)
took = time.perf_counter() - started
assert all(r.status == "ok" for r in results), [r.error for r in results]
print(took, sum(r.elapsed for r in results))
"""


def bench_batch(folder: str, variants: int, jobs: int, repeats: int = 3
                ) -> tuple[float, float]:
    """Median (sequential seconds, pooled seconds) for ``variants`` runs of the grid
    script, each batch in a fresh process as ``livemod batch -j 1`` and ``-j jobs``
    would run it (a warm benchmark process would favour the sequential side: its
    heap is already faulted in, a fresh worker's is not)."""
    path = os.path.join(folder, "variant.py")
    with open(path, "w") as handle:
        handle.write(VARIANT)
    runs: dict[int, list[tuple[float, float]]] = {1: [], jobs: []}
    for _ in range(repeats):
        for j in runs:  # alternated, so load changes hit both alike
            out = subprocess.run([sys.executable, "-c", BATCH_CHILD, path, str(variants), str(j)],
                                 check=True, capture_output=True, text=True).stdout.split()
            runs[j].append((float(out[0]), float(out[1])))
    sequential = statistics.median(t for t, _ in runs[1])
    parallel = statistics.median(t for t, _ in runs[jobs])
    busy = statistics.median(b for _, b in runs[jobs]) / statistics.median(b for _, b in runs[1])
    print(f"  (variant run time in the pool / alone: {busy:.2f}, above 1 when the cores "
          f"are shared with other work; variants in flight on average: "
          f"{statistics.median(b for _, b in runs[jobs]) / parallel:.2f} of {jobs}; "
          f"median of {repeats} fresh processes each)")
    return sequential, parallel


LONG_SCRIPT = (
    "es = edges()\n"
    "for i in range(1000):\n"
    "    subdivideEdge(es[i])\n"
)


def _wait_paused(session: LiveSession, k: int, timeout: float = 120.0):
    return _wait_for(session, lambda r: r.status == "paused" and r.step_index == k,
                     f"step {k}", timeout)


def bench_step_back(folder: str) -> tuple[float, float, float, int]:
    """(seconds for a cached step back, seconds for a replayed one, peak MB growth,
    faces) on 1,000 steps of a 100,000-face mesh."""
    path = os.path.join(folder, "long.py")
    with open(path, "w") as handle:
        handle.write(LONG_SCRIPT)
    base = Scene()
    base.add(grid_mesh(316))
    faces = base.mesh.counts()[2]
    peak_before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    session = LiveSession(path, preview=False, base=base, snapshot_budget=64 * 2**20)
    session.pause()
    session.start()
    try:
        _wait_paused(session, 0)
        for k in (997, 998, 999):
            session.goto_step(k)
            _wait_paused(session, k)
        started = time.perf_counter()
        session.step_back()
        _wait_paused(session, 998)
        cached = time.perf_counter() - started
        started = time.perf_counter()
        session.goto_step(500)
        _wait_paused(session, 500)
        replayed = time.perf_counter() - started
    finally:
        session.close()
        session.join()
    grown = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024 - peak_before
    return cached, replayed, grown, faces


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer repeats")
    args = parser.parse_args(argv)
    repeats = 3 if args.quick else 7
    debounce = 0.15
    print(f"python {sys.version.split()[0]}, {os.cpu_count()} cpus")
    with tempfile.TemporaryDirectory() as folder:
        cost = bench_hook_cost(repeats)
        print(f"per step (least of {repeats}, load {os.getloadavg()[0]:.1f}): recording "
              f"{cost['runner'] * 1e6:.2f} us (through the hook, as runs that may pause: "
              f"{cost['hook'] * 1e6:.2f} us), a no-op hook {cost['noop'] * 1e6:.2f} us, one "
              f"createVertex {cost['none'] * 1e6:.2f} us -> recording adds "
              f"{100 * cost['runner'] / cost['none']:.0f} % to the smallest command; reading a "
              f"step back later {cost['read'] * 1e6:.2f} us")
        low, middle, high = bench_hook_pairs(8 * repeats)
        print(f"recording on createVertex timed in pairs (bare and recorded back to back, "
              f"{8 * repeats} pairs of 20,000): {100 * middle:+.1f} % (median of the ratios; "
              f"quartiles {100 * low:+.1f} % .. {100 * high:+.1f} %)")
        low, middle, high = bench_hook_pairs(8 * repeats, 3000, TRIANGLE_BODY)
        print(f"recording on the thesis's triangle (3 createVertex, 3 insertEdge) timed in "
              f"pairs ({8 * repeats} pairs of 18,000 steps): {100 * middle:+.1f} % (median; "
              f"quartiles {100 * low:+.1f} % .. {100 * high:+.1f} %)")
        print_overhead("10,000 createVertex", bench_step_overhead(folder, repeats), repeats)
        print_overhead("10,002 commands of the thesis's triangle", bench_step_overhead(
            folder, repeats, TRIANGLES, steps=10002), repeats)
        base = Scene()
        base.add(grid_mesh(100))
        mixed = bench_step_overhead(folder, repeats, MIXED_COMMANDS, base)
        print_overhead("10,000 subdivideEdge/move on 10,000 faces", mixed, repeats)
        extrusions = bench_step_overhead(folder, repeats, EXTRUSIONS, steps=2000)
        print_overhead("2,000 chained cubical extrusions", extrusions, repeats)
        latency, run = bench_save_latency(folder, 3 * repeats, debounce)
        print(f"save -> result, 20 commands on 10,000 faces: {latency * 1e3:.0f} ms + "
              f"{debounce * 1e3:.0f} ms debounce (run itself {run * 1e3:.0f} ms; "
              f"median of {3 * repeats})")
        cancel = bench_cancel_latency(folder, repeats, debounce)
        print(f"save -> result while `while True: pass` runs: {cancel * 1e3:.0f} ms + "
              f"{debounce * 1e3:.0f} ms debounce (median of {repeats})")
        for block, text in STUCK.items():
            stuck = bench_cancel_latency(folder, repeats, debounce, text)
            print(f"save -> result while the old run is blocked in `{block}`: "
                  f"{stuck * 1e3:.0f} ms + {debounce * 1e3:.0f} ms debounce (median of "
                  f"{repeats}; the old run goes on in the background)")
        for way, (extra, ratio) in bench_restore_pairs(folder, 40 * repeats).items():
            print(f"giving the process back, {way} runs of a one-line script: "
                  f"{extra * 1e6:+.0f} us a run ({100 * ratio:+.0f} %; medians of "
                  f"{40 * repeats} pairs, CPU time)")
        cached, replayed, grown, faces = bench_step_back(folder)
        print(f"step back at step 999 of 1,000 on {faces:,} faces: {cached * 1e3:.0f} ms "
              f"from the snapshot cache, {replayed:.2f} s by replay; peak memory "
              f"+{grown:.0f} MB (64 MB snapshot budget)")
        sequential, parallel = bench_batch(folder, 32, 2)
        print(f"batch of 32 variants: sequential {sequential:.2f} s, 2 processes "
              f"{parallel:.2f} s, speed-up {sequential / parallel:.2f}x")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
