"""Instructions a recorded step costs, counted by callgrind (plain python, not a test).

    python bench/bench_step_instructions.py [--only NAME ...] [--jobs N] [--sim]

Wall and CPU times on the shared development machines vary by +-15 % from run
to run, too much to tell 8 % from 10 %; callgrind's instruction counts do not
vary. Each workload runs in child processes under ``valgrind --tool=callgrind``
at two sizes, both bare (compiled and exec'd with the scene bound, no step hook
in the run context,
none of the runner's cancel checks) and through ``livemod.runner.execute``.
Everything but the loop is the same at both sizes, so the difference of the two
totals over the difference of the step counts is what one step costs, startup
(interpreter, numpy, imports, base mesh) cancelled out. The overhead is
recorded / bare - 1 per step: the target of the issue is at most 10 %.

Instructions are not time: with ``--sim`` callgrind also simulates the caches
and branch predictors, and the recorded step's extra misses and mispredictions
(the interpreter dispatches more bytecodes, and the recording touches code and
memory a bare step does not) make its share of CPU time larger than its share
of instructions.
"""

from __future__ import annotations

import argparse
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass

from bench_runner import EXTRUSION_TEMPLATE, MIXED_TEMPLATE, SMALL_TEMPLATE, TRIANGLES_TEMPLATE

# the child: the same imports and base scene for both modes and both sizes, so
# that only the loop's length differs between the two sizes of one mode
CHILD = """
import os
import sys
from livemod.dlfl import current_run, from_polygons
from livemod.dlfl.scene import Scene, use_scene
from livemod.runner import execute

mode, path, grid, steps = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
with open(path) as handle:
    source = handle.read()
base = None
if grid:
    pts = [(x, y, 0.0) for y in range(grid + 1) for x in range(grid + 1)]
    quads = [(y * (grid + 1) + x, y * (grid + 1) + x + 1, (y + 1) * (grid + 1) + x + 1,
              (y + 1) * (grid + 1) + x) for y in range(grid) for x in range(grid)]
    base = Scene()
    base.add(from_polygons(pts, quads))
if mode == "bare":
    code = compile(source, path, "exec")
    scene = base.copy() if base is not None else Scene()
    with use_scene(scene):
        exec(code, {"__name__": "__main__"})
    assert current_run().step_hook is None
else:
    outcome = execute(path, source=source, base=base)
    assert outcome.status == "ok" and len(outcome.steps) == steps, outcome.error
# the run is over: what the interpreter's teardown frees and collects is not part
# of it (it would count the final full collection walking the recorded steps)
sys.stdout.flush()
os._exit(0)
"""


@dataclass(frozen=True)
class Workload:
    """A script whose loop runs ``{n}`` times, ``per_iteration`` steps each.

    ``grid`` > 0 starts it from a ``grid`` x ``grid`` quad mesh.
    """

    name: str
    template: str
    small: int
    large: int
    per_iteration: int = 1
    grid: int = 0

    def steps(self, n: int) -> int:
        return n * self.per_iteration


WORKLOADS = (
    Workload("createVertex", SMALL_TEMPLATE, 1000, 11000),
    Workload("triangles", TRIANGLES_TEMPLATE, 200, 1867, per_iteration=6),
    Workload("subdivideEdge/move", MIXED_TEMPLATE, 500, 5500, per_iteration=2, grid=100),
    Workload("cubical extrusion", EXTRUSION_TEMPLATE, 200, 1200),
)

COLLECTED = re.compile(r"Collected\s*:\s*([\d ]+)")
# the events callgrind collects with --cache-sim=yes --branch-sim=yes, in order
SIM_EVENTS = ["Ir", "Dr", "Dw", "I1mr", "D1mr", "D1mw", "ILmr", "DLmr", "DLmw",
              "Bc", "Bcm", "Bi", "Bim"]
SIM_FLAGS = ["--cache-sim=yes", "--branch-sim=yes"]


def _count(folder: str, workload: Workload, mode: str, n: int, sim: bool) -> list[int]:
    """Callgrind's totals for one child running ``workload`` at ``n``: the
    instructions, or with ``sim`` every event of ``SIM_EVENTS``.

    The script file has the same name at both sizes (only its loop bound
    differs), so every path the child touches is the same length.

    Raises:
        RuntimeError: the child failed, or callgrind printed no total.
    """
    sub = os.path.join(folder, f"{mode}-{n:06d}-{WORKLOADS.index(workload)}")
    os.makedirs(sub, exist_ok=True)
    path = os.path.join(sub, "script.py")
    with open(path, "w") as handle:
        handle.write(workload.template.format(n=f"{n:6d}"))
    # one hash seed, and numpy's BLAS without worker threads (valgrind runs threads
    # one at a time, and idle ones spin for a varying number of instructions)
    env = dict(os.environ, PYTHONHASHSEED="0", OPENBLAS_NUM_THREADS="1",
               OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    args = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={sub}/callgrind.out",
            *(SIM_FLAGS if sim else []), sys.executable, "-c", CHILD, mode, path,
            str(workload.grid), str(workload.steps(n))]
    done = subprocess.run(args, capture_output=True, text=True, env=env)
    found = COLLECTED.search(done.stderr)
    if done.returncode != 0 or found is None:
        raise RuntimeError(f"{workload.name} {mode} {n}: {done.stderr[-2000:]}")
    return [int(x) for x in found.group(1).split()]


def per_step(workload: Workload, small: list[int], large: list[int]) -> list[float]:
    """Each event per step, from the totals of the small and the large run."""
    steps = workload.steps(workload.large) - workload.steps(workload.small)
    return [(b - a) / steps for a, b in zip(small, large, strict=True)]


def sim_line(bare: list[float], runner: list[float]) -> str:
    """Cache misses and mispredicted branches per step, bare -> recorded: what
    makes a recorded step cost more time than its share of instructions."""
    bare_of, runner_of = (dict(zip(SIM_EVENTS, bare, strict=True)),
                          dict(zip(SIM_EVENTS, runner, strict=True)))
    groups = {"L1 instruction misses": ["I1mr"], "L1 data misses": ["D1mr", "D1mw"],
              "last-level misses": ["ILmr", "DLmr", "DLmw"], "mispredicted branches": ["Bcm", "Bim"]}
    parts = [f"{name} {sum(bare_of[e] for e in events):,.0f} -> "
             f"{sum(runner_of[e] for e in events):,.0f}" for name, events in groups.items()]
    return "    per step, bare -> recorded: " + ", ".join(parts)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", nargs="*", help="workload names (default: all)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="callgrind children at a time")
    parser.add_argument("--sim", action="store_true",
                        help="also simulate caches and branch prediction (twice as slow)")
    args = parser.parse_args(argv)
    chosen = [w for w in WORKLOADS if not args.only or w.name in args.only]
    print(f"python {sys.version.split()[0]}; callgrind instructions per step "
          "(large minus small run, over the steps between)")
    with tempfile.TemporaryDirectory() as folder, ThreadPoolExecutor(args.jobs) as pool:
        # submit every child first, so that they keep the cores busy throughout
        futures = {(w.name, mode, n): pool.submit(_count, folder, w, mode, n, args.sim)
                   for w in chosen for mode in ("bare", "runner") for n in (w.small, w.large)}
        for w in chosen:
            bare, runner = (per_step(w, futures[w.name, mode, w.small].result(),
                                     futures[w.name, mode, w.large].result())
                            for mode in ("bare", "runner"))
            b, r = bare[0], runner[0]
            print(f"{w.name:20s} bare {b:10,.0f}  recorded {r:10,.0f}  "
                  f"step +{r - b:7,.0f}  overhead {100 * (r / b - 1):+6.2f} %", flush=True)
            if args.sim:
                print(sim_line(bare, runner), flush=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
