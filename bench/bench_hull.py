"""Benchmarks of the convex hull (``livemod.dlfl.hull``) and of ``columns``, its
main caller (one small hull per mesh vertex); figures go to docs/performance.md.

Run: ``python bench/bench_hull.py [--repeat N] [--before REV] [--large [--large-before |
--against DIR --pairs N]]``.
``--large`` times instead ``convex_hull`` and ``dual_convex_hull`` of 1,500, 6,000
and 24,600 points on a sphere (issue 30: 0.5 s, 2.0 s and 38 s; target: 24,600
well under a second), CPU medians, with ``--large-before`` the hull.py of
``--before`` too (minutes at 24,600 points). With ``--against DIR`` (a copy of
another tree, ``git archive main | tar -x -C DIR``) each operation runs in fresh
processes, alternately on ``DIR``'s livemod and on this one, ``--pairs`` times:
medians of the CPU times and each pair's ratio (this / DIR), which a busy
machine's load affects less than the times themselves. Each figure is the
median of ``--repeat`` runs in one process, wall and CPU time. The same cases are
timed with ``livemod/dlfl/hull.py`` as of git revision ``--before`` (default: the
gift-wrapping routine as first committed, before small hulls looked their
triangles up), loaded beside the current one, and the two must give the same
polygons. Target: ``columns(torus(30, 30), 0.1, 4)`` in at most 0.5 s (it took
0.56 s with the all-triples routine gift wrapping replaced), and 2,000 points on
a sphere no more than ~20 % slower than before.
"""

from __future__ import annotations

import argparse
import importlib
import os
import statistics
import subprocess
import sys
import tracemalloc
import types
from collections.abc import Callable
from pathlib import Path
from unittest import mock

import numpy as np
from timing import median_times

from livemod.dlfl.build import point_cloud
from livemod.dlfl.shapes import torus

ROOT = Path(__file__).resolve().parents[1]
BEFORE = "18c571b"
hull = importlib.import_module("livemod.dlfl.hull")
wireframe = importlib.import_module("livemod.dlfl.wireframe")

Hull = Callable[[np.ndarray], list[list[int]]]


def load_revision(rev: str) -> types.ModuleType | None:
    """``livemod/dlfl/hull.py`` as of git revision ``rev``, as a module of the
    ``livemod.dlfl`` package beside the current one; ``None`` without it."""
    try:
        source = subprocess.run(["git", "show", f"{rev}:livemod/dlfl/hull.py"], cwd=ROOT,
                                capture_output=True, text=True, check=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return None
    module = types.ModuleType(f"livemod.dlfl._hull_{rev}")
    module.__package__ = "livemod.dlfl"
    sys.modules[module.__name__] = module
    exec(compile(source, f"{rev}:livemod/dlfl/hull.py", "exec"), module.__dict__)
    return module


def unit_sphere(n: int, seed: int = 0) -> np.ndarray:
    """``(n, 3)`` random points on the unit sphere (every one a hull vertex)."""
    points = np.random.default_rng(seed).normal(size=(n, 3))
    return points / np.linalg.norm(points, axis=1)[:, None]


def column_joints() -> list[np.ndarray]:
    """The 900 point sets (16 points each) that ``columns(torus(30, 30), 0.1, 4)``
    takes the hull of."""
    recorded: list[np.ndarray] = []

    def record(points: np.ndarray, tolerance: float = 1e-9) -> list[list[int]]:
        recorded.append(np.array(points))
        return hull.hull_polygons(points, tolerance)

    with mock.patch.object(wireframe, "hull_polygons", record):
        wireframe.columns(torus(30, 30), 0.1, 4)
    return recorded


def hull_cases() -> list[tuple[str, list[np.ndarray]]]:
    """``(label, point sets)``: each case times one hull of every set."""
    lattice = np.array([[x, y, z] for x in range(3) for y in range(3) for z in range(3)], float)
    return [
        ("hulls of those 900 joints alone", column_joints()),
        ("16 points on a sphere, 100 sets", [unit_sphere(16, s) for s in range(100)]),
        ("32 points on a sphere, 30 sets", [unit_sphere(32, s) for s in range(30)]),
        ("3 x 3 x 3 lattice (27 points, square faces), 20 times", [lattice] * 20),
        ("300 points on a sphere", [unit_sphere(300)]),
        ("2,000 points on a sphere", [unit_sphere(2000)]),
    ]


def timed(run: Callable[[], object], repeat: int) -> str:
    """``"wall / CPU"``, medians of ``repeat`` runs, in s (ms below a tenth of one)."""
    wall, cpu = median_times(run, repeat)
    if wall < 0.1:
        return f"{wall * 1e3:.1f} ms / {cpu * 1e3:.1f} ms"
    return f"{wall:.3f} s / {cpu:.3f} s"


def peak_bytes(hull_polygons: Hull, points: np.ndarray) -> int:
    """Peak bytes Python and numpy allocate for one hull of ``points``."""
    tracemalloc.start()
    hull_polygons(points)
    peak = tracemalloc.get_traced_memory()[1]
    tracemalloc.stop()
    return peak


def row(label: str, now: Callable[[], object], then: Callable[[], object] | None,
        repeat: int) -> None:
    """One table row: ``then`` (the revision before, if any) and ``now`` timed."""
    before = timed(then, repeat) if then is not None else "—"
    print(f"| {label} | {before} | {timed(now, repeat)} |", flush=True)


def hull_rows(old: types.ModuleType | None, repeat: int) -> None:
    """The hull cases, each also with the lookup off when it applies."""
    for label, sets in hull_cases():
        if old is not None:  # the same polygons, set for set
            assert all(old.hull_polygons(p) == hull.hull_polygons(p) for p in sets), label
        then = None if old is None else lambda sets=sets: [old.hull_polygons(p) for p in sets]
        row(label, lambda sets=sets: [hull.hull_polygons(p) for p in sets], then, repeat)
        if len(sets[0]) <= hull._SMALL:
            with mock.patch.object(hull, "_SMALL", 0):
                row(f"{label}, triangle lookup off", lambda sets=sets: [
                    hull.hull_polygons(p) for p in sets], None, repeat)


def columns(hull_polygons: Hull | None = None) -> None:
    """The target case, with ``hull_polygons`` for the joints (default: the current)."""
    with mock.patch.object(wireframe, "hull_polygons", hull_polygons or hull.hull_polygons):
        wireframe.columns(torus(30, 30), 0.1, 4)


LARGE = (1500, 6000, 24600)


def large_rows(old: types.ModuleType | None, repeat: int) -> None:
    """The hulls of issue 30, now and (``old``) before: seed 1, on which gift
    wrapping closes up at every size (on some seeds it refuses: four points
    within the tolerance of one circle)."""
    print("| operation | before wall / CPU | now wall / CPU |")
    print("|---|---|---|")
    for n in LARGE:
        points = unit_sphere(n, 1)
        for name in ("convex_hull", "dual_convex_hull"):
            now = getattr(hull, name)
            then = None if old is None else getattr(old, name)
            label = f"{name}, {n:,} points on a sphere"
            before = "—" if then is None else timed_on(then, points, 1)
            print(f"| {label} | {before} | {timed_on(now, points, repeat)} |", flush=True)


# one operation in a fresh process: CPU seconds and the result's counts
_CHILD = """
import sys, time
import numpy as np
from livemod.dlfl import hull
from livemod.dlfl.build import point_cloud
op, n = sys.argv[1], int(sys.argv[2])
points = np.random.default_rng(1).normal(size=(n, 3))
points /= np.linalg.norm(points, axis=1)[:, None]
mesh = point_cloud(points)
cpu = time.process_time()
getattr(hull, op)(mesh)
print(time.process_time() - cpu, *mesh.counts())
"""


def child_cpu(tree: Path, op: str, n: int) -> tuple[float, tuple[int, ...]]:
    """CPU seconds of ``op`` on ``unit_sphere(n, 1)`` in a fresh process on the
    livemod of ``tree``, and the result's counts."""
    env = {**os.environ, "PYTHONPATH": str(tree)}
    out = subprocess.run([sys.executable, "-c", _CHILD, op, str(n)], env=env, cwd=tree,
                         capture_output=True, text=True, check=True).stdout.split()
    return float(out[0]), tuple(map(int, out[1:]))


def alternating_rows(base: Path, pairs: int) -> None:
    """The hulls of issue 30 on ``base``'s livemod and on this one, in fresh
    processes taken alternately (see the module's doc); both must give the same
    counts."""
    print(f"| operation | {base} CPU | this tree CPU | ratios, pair by pair |")
    print("|---|---|---|---|")
    for n in LARGE:
        for name in ("convex_hull", "dual_convex_hull"):
            then, now = [], []
            for _ in range(pairs):
                (before, counts), (after, ours) = (child_cpu(base, name, n),
                                                   child_cpu(ROOT, name, n))
                assert counts == ours, (name, n, counts, ours)
                then.append(before)
                now.append(after)
            ratios = ", ".join(f"{b / a:.2f}" for a, b in zip(then, now, strict=True))
            print(f"| `{name}`, {n:,} points on a sphere | {statistics.median(then):.3f} s | "
                  f"{statistics.median(now):.3f} s | {ratios} |", flush=True)


def timed_on(op: Callable[..., None], points: np.ndarray, repeat: int) -> str:
    """:func:`timed` of ``op`` on a fresh point cloud of ``points`` each run."""
    wall, cpu = median_times(op, repeat, setup=lambda: point_cloud(points))
    return f"{wall:.3f} s / {cpu:.3f} s"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--before", default=BEFORE, help="git revision to compare with")
    parser.add_argument("--large", action="store_true", help="time the large hulls only")
    parser.add_argument("--large-before", action="store_true",
                        help="with --large, time the revision --before too (minutes)")
    parser.add_argument("--against", type=Path,
                        help="with --large, a tree to time alternately with this one")
    parser.add_argument("--pairs", type=int, default=5, help="with --against: how many pairs")
    args = parser.parse_args()
    if args.large and args.against is not None:
        print(f"cpus: {os.cpu_count()}, load: {os.getloadavg()[0]:.1f}, pairs: {args.pairs} "
              "(medians; fresh processes, alternately)\n")
        alternating_rows(args.against, args.pairs)
        print(f"\nload after: {os.getloadavg()[0]:.1f}")
        return
    if args.large:
        print(f"cpus: {os.cpu_count()}, load: {os.getloadavg()[0]:.1f}, repeat: {args.repeat} "
              "(median; before: one run)\n")
        large_rows(load_revision(args.before) if args.large_before else None, args.repeat)
        return
    old = load_revision(args.before)
    print(f"cpus: {os.cpu_count()}, load: {os.getloadavg()[0]:.1f}, repeat: {args.repeat} "
          f"(median), before: {args.before if old is not None else 'not found'}\n")
    print(f"| case | before ({args.before}) wall / CPU | now wall / CPU |")
    print("|---|---|---|")
    row("columns(torus(30, 30), 0.1, 4), 900 joints (target 0.5 s)", columns,
        None if old is None else lambda: columns(old.hull_polygons), args.repeat)
    hull_rows(old, args.repeat)
    sphere = unit_sphere(2000)
    before = "—" if old is None else f"{peak_bytes(old.hull_polygons, sphere) / 2**20:.2f} MiB"
    print(f"| peak memory, 2,000 points on a sphere | {before} | "
          f"{peak_bytes(hull.hull_polygons, sphere) / 2**20:.2f} MiB |")


if __name__ == "__main__":
    main()
