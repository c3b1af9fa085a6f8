"""Remeshing benchmarks (issue 3), with peers side by side where they install.

Run: ``python bench/bench_subdivision.py [--quick]``; ``--only-schemes --schemes a,b
--sizes 10k,100k,1M`` runs part of the every-scheme table, ``--per-row`` gives each
(scheme, size) its own process. Prints a markdown report (medians of several runs,
seconds) for docs/performance.md:

* Catmull-Clark of the cube, 5 levels (6 -> 6,144 quads);
* Catmull-Clark one level 98,304 -> 393,216 quads, DLFL in and out, against
  pymeshlab's same step (its quads given as a polygon mesh);
* Loop one level 81,920 -> 327,680 triangles against pymeshlab, trimesh and libigl;
* Doo-Sabin at the same size as Catmull-Clark;
* every scheme at 10k, 100k and 1M input quads (a quad torus), with the ratio to
  Catmull-Clark on the same input, measured in the same child process (one per
  size), with glibc told to keep freed memory (``--default-malloc`` not): see
  :func:`bench_all_schemes`;
* the cost of ``mesh_arrays`` and ``from_corner_arrays`` inside one step;
* peak memory (RSS, in a child process) while subdividing to 1.5M quads.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import time
from collections.abc import Callable

import numpy as np

from livemod.dlfl import Mesh, from_corner_arrays, mesh_arrays
from livemod.dlfl.shapes import cube, icosahedron, torus
from livemod.dlfl.subdivision import SCHEMES, subdivide

Row = tuple[str, ...]  # case, library, time[, ratio]


class Timing(float):
    """A median wall time in seconds that also carries the median CPU time, and
    the median user and system parts of it."""

    cpu: float
    user: float
    sys: float


def _cpu_times() -> tuple[float, float]:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime, r.ru_stime


def median_time(run: Callable[[], object], repeats: int, setup: Callable[[], object] | None = None
                ) -> Timing:
    """Median wall (and CPU) time of ``run`` over ``repeats`` calls (``setup`` not timed).

    The CPU time of the process is reported too: on the shared 2-core machine
    other jobs inflate wall times. Its system part is mostly page faults on
    freshly mapped memory.
    """
    walls, users, systems = [], [], []
    for _ in range(repeats):
        if setup is not None:
            setup()
        (user, system), start = _cpu_times(), time.perf_counter()
        run()
        walls.append(time.perf_counter() - start)
        user_end, system_end = _cpu_times()
        users.append(user_end - user)
        systems.append(system_end - system)
    out = Timing(statistics.median(walls))
    out.cpu = statistics.median(u + s for u, s in zip(users, systems, strict=True))
    out.user, out.sys = statistics.median(users), statistics.median(systems)
    return out


def fmt(seconds: Timing, unit: str = "s") -> str:
    scale = 1e3 if unit == "ms" else 1.0
    return f"{seconds * scale:.3f} {unit} (CPU {seconds.cpu * scale:.3f})"


def levels(mesh: Mesh, scheme: str, count: int) -> Mesh:
    for _ in range(count):
        subdivide(mesh, scheme)
    return mesh


def time_scheme(mesh: Mesh, scheme: str, repeats: int) -> Timing:
    """Median time of one step of ``scheme`` on copies of ``mesh`` (copy not timed).

    One untimed warm-up run first: the first large allocation of a process pays
    for fresh pages (the first Catmull-Clark step on 1M quads costs 2.5x the next).
    The previous result is dropped before the next copy is made, so at most one
    result and one copy are alive besides ``mesh``.
    """
    holder: list[Mesh] = []

    def setup() -> None:
        holder.clear()
        holder.append(mesh.copy())

    setup()
    subdivide(holder[0], scheme, max_faces=10**9)
    seconds = median_time(lambda: subdivide(holder[0], scheme, max_faces=10**9), repeats, setup)
    holder.clear()
    return seconds


def quads_of(mesh: Mesh) -> tuple[np.ndarray, np.ndarray]:
    a = mesh_arrays(mesh)
    return a.positions, a.corner_vertex.reshape(-1, 4)


def triangles_of(mesh: Mesh) -> tuple[np.ndarray, np.ndarray]:
    a = mesh_arrays(mesh)
    return a.positions, a.corner_vertex.reshape(-1, 3)


def bench_cube_levels(repeats: int) -> list[Row]:
    rows: list[Row]
    holder: list[Mesh] = []

    def setup() -> None:
        holder[:] = [cube()]

    def one_call() -> None:
        subdivide(holder[0], "catmull-clark", levels=5)

    def five_calls() -> None:
        levels(holder[0], "catmull-clark", 5)

    one = median_time(one_call, repeats, setup)
    five = median_time(five_calls, repeats, setup)
    rows = [("Catmull-Clark, cube 5 levels (6,144 quads), levels=5", "livemod", fmt(one, "ms")),
            ("Catmull-Clark, cube 5 levels, five separate calls", "livemod", fmt(five, "ms"))]
    return rows


def pymeshlab_step(filter_name: str, vertices: np.ndarray, faces: np.ndarray,
                   repeats: int) -> str:
    try:
        import pymeshlab
    except ImportError:
        return "not installed"
    holder: list[object] = []

    def setup() -> None:
        ms = pymeshlab.MeshSet()
        if faces.shape[1] == 4:
            ms.add_mesh(pymeshlab.Mesh(vertex_matrix=vertices,
                                       face_list_of_indices=faces.tolist()))
        else:
            ms.add_mesh(pymeshlab.Mesh(vertex_matrix=vertices, face_matrix=faces))
        holder[:] = [ms]

    def run() -> None:
        getattr(holder[0], filter_name)(iterations=1)

    return fmt(median_time(run, repeats, setup))


def bench_catmull_clark(repeats: int) -> list[Row]:
    mesh = levels(cube(), "catmull-clark", 7)  # 98,304 quads
    rows: list[Row] = [("Catmull-Clark 98,304 -> 393,216 quads (DLFL in and out)", "livemod",
             fmt(time_scheme(mesh, 'catmull-clark', repeats)))]
    vertices, faces = quads_of(mesh)
    rows.append(("", "pymeshlab", pymeshlab_step(
        "meshing_surface_subdivision_catmull_clark", vertices, faces, repeats)))
    rows.append(("Doo-Sabin, same input", "livemod",
                 fmt(time_scheme(mesh, 'doo-sabin', repeats))))
    return rows


def bench_loop(repeats: int) -> list[Row]:
    mesh = levels(icosahedron(), "loop", 6)  # 81,920 triangles
    rows: list[Row] = [("Loop 81,920 -> 327,680 triangles", "livemod",
             fmt(time_scheme(mesh, 'loop', repeats)))]
    vertices, faces = triangles_of(mesh)
    rows.append(("", "pymeshlab", pymeshlab_step(
        "meshing_surface_subdivision_loop", vertices, faces, repeats)))
    try:
        from trimesh.remesh import subdivide_loop
    except ImportError:
        rows.append(("", "trimesh", "not installed"))
    else:
        seconds = median_time(lambda: subdivide_loop(vertices, faces, iterations=1), repeats)
        rows.append(("", "trimesh", fmt(seconds)))
    try:
        import igl  # libigl's Python bindings (pip install libigl)
    except ImportError:
        rows.append(("", "libigl", "not installed"))
    else:
        seconds = median_time(lambda: igl.loop(vertices, faces, 1), repeats)
        rows.append(("", "libigl", fmt(seconds)))
    return rows


def bench_core_costs(repeats: int) -> list[Row]:
    mesh = levels(cube(), "catmull-clark", 7)
    arrays_s = median_time(lambda: mesh_arrays(mesh), repeats)
    out = levels(mesh.copy(), "catmull-clark", 1)
    a = mesh_arrays(out)
    build_s = median_time(lambda: from_corner_arrays(
        a.positions, a.face_offsets, a.corner_vertex, a.corner_mate, a.face_hole), repeats)
    rows: list[Row] = [
        ("mesh_arrays of 98,304 quads (inside one CC step)", "livemod", fmt(arrays_s)),
        ("from_corner_arrays of 393,216 quads", "livemod", fmt(build_s))]
    return rows


SIZES = {"10k": (100, 100), "100k": (316, 316), "1M": (1000, 1000)}
# schemes whose result at an input size would exceed the default face budget
OVER_BUDGET = {("dome", "1M"): "skipped (28.3M faces per 1M quads: 28M over the 20M budget)"}
# keep freed memory inside the process (see bench_all_schemes)
WARM_HEAP = "glibc.malloc.mmap_max=0:glibc.malloc.trim_threshold=1000000000000"


def every_scheme() -> list[str]:
    """Every scheme name except Catmull-Clark (the reference) and the delegated ones."""
    return sorted(set(SCHEMES) - {"modified-corner-cut", "sierpinsky", "catmull-clark"})


def time_rows(label: str, schemes: list[str], repeats: int) -> list[dict[str, object]]:
    """Catmull-Clark, then each of ``schemes``, on the quad torus of ``label``.

    Each row: scheme, size, median wall, CPU, user and system seconds.
    """
    mesh = torus(*SIZES[label])
    rows: list[dict[str, object]] = []
    for scheme in ["catmull-clark", *schemes]:
        if (scheme, label) in OVER_BUDGET:
            rows.append({"scheme": scheme, "size": label, "skipped": OVER_BUDGET[scheme, label]})
            continue
        t = time_scheme(mesh, scheme, repeats)
        rows.append({"scheme": scheme, "size": label, "wall": float(t), "cpu": t.cpu,
                     "user": t.user, "sys": t.sys})
    return rows


def run_child(label: str, schemes: list[str], repeats: int, warm_heap: bool
              ) -> list[dict[str, object]]:
    """:func:`time_rows` in a fresh Python process (rows come back as JSON lines)."""
    env = dict(os.environ)
    if warm_heap:
        env["GLIBC_TUNABLES"] = WARM_HEAP
    command = [sys.executable, __file__, "--child", label, "--schemes", ",".join(schemes),
               "--repeats", str(repeats)]
    out = subprocess.run(command, capture_output=True, text=True, check=True, env=env).stdout
    return [json.loads(line) for line in out.splitlines() if line.startswith("{")]


def bench_all_schemes(sizes: list[str], schemes: list[str], repeats: int, warm_heap: bool,
                      per_row: bool) -> list[Row]:
    """Every scheme per input size, with its CPU time over Catmull-Clark's in the same process.

    Each size runs in a fresh process (``per_row``: each scheme too, with its
    own Catmull-Clark), so no row inherits the heap or the meshes of another.
    With ``warm_heap`` glibc keeps freed memory (no ``mmap`` per big array, no
    trimming): on this VM the balloon driver hands memory freed for 2 s back to
    the host, and touching it again costs ~3 s of system time per GB.
    """
    rows: list[Row] = []
    for label in sizes:
        groups = [[s] for s in schemes] if per_row else [schemes]
        results = [run_child(label, group, repeats, warm_heap) for group in groups]
        cc = results[0][0]
        rows.append(_row(cc, cc))
        rows.extend(_row(r, group[0]) for group in results for r in group[1:])
    return rows


def _row(result: dict[str, object], cc: dict[str, object]) -> Row:
    case = f"{result['scheme']}, {result['size']} quads"
    if "skipped" in result:
        return (case, "livemod", str(result["skipped"]), "", "")
    cpu, user, system = (float(result[k]) for k in ("cpu", "user", "sys"))  # type: ignore[arg-type]
    timing = f"{float(result['wall']):.3f} s (CPU {cpu:.3f})"  # type: ignore[arg-type]
    return (case, "livemod", timing, f"{user:.3f} / {system:.3f}",
            f"{cpu / float(cc['cpu']):.2f}")  # type: ignore[arg-type]


PEAK_SNIPPET = """
import resource
from livemod.dlfl.shapes import cube
from livemod.dlfl.subdivision import subdivide
m = cube()
for _ in range(8):
    subdivide(m, "catmull-clark")
base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
subdivide(m, "catmull-clark")
peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
print(m.counts()[2], base, peak)
"""


def bench_peak_memory() -> list[Row]:
    out = subprocess.run([sys.executable, "-c", PEAK_SNIPPET], capture_output=True, text=True,
                         check=True).stdout.split()
    faces, base, peak = (int(x) for x in out)
    rows: list[Row] = [(f"peak RSS, CC 393,216 -> {faces:,} quads (process total)", "livemod",
                        f"{peak / 1024:.0f} MB (before the step: {base / 1024:.0f} MB)")]
    return rows


def _parse() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="fewer runs, no 1M inputs")
    parser.add_argument("--repeats", type=int, default=5)
    parser.add_argument("--scheme-repeats", type=int, default=3,
                        help="runs per row of the every-scheme table (after a warm-up)")
    parser.add_argument("--schemes", help="comma-separated schemes of the every-scheme table")
    parser.add_argument("--sizes", help="comma-separated input sizes among 10k, 100k, 1M")
    parser.add_argument("--only-schemes", action="store_true",
                        help="only the every-scheme table")
    parser.add_argument("--per-row", action="store_true",
                        help="a fresh process (and Catmull-Clark) per scheme and size")
    parser.add_argument("--default-malloc", action="store_true",
                        help="children use glibc's default allocator settings")
    parser.add_argument("--child", help=argparse.SUPPRESS)
    return parser.parse_args()


def print_table(header: str, rows: list[Row]) -> None:
    print(header)
    for row in rows:
        print("| " + " | ".join(row) + " |")


def main() -> None:
    args = _parse()
    schemes = args.schemes.split(",") if args.schemes else every_scheme()
    if args.child:
        for result in time_rows(args.child, [s for s in schemes if s != "catmull-clark"],
                                args.repeats):
            print(json.dumps(result))
        return
    repeats = 2 if args.quick else args.repeats
    if not args.only_schemes:
        rows = [*bench_cube_levels(max(repeats, 15)), *bench_catmull_clark(repeats),
                *bench_loop(repeats), *bench_core_costs(repeats), *bench_peak_memory()]
        print_table("| case | library | median wall (CPU) |\n|---|---|---|", rows)
    sizes = args.sizes.split(",") if args.sizes else (
        ["10k", "100k"] if args.quick else ["10k", "100k", "1M"])
    print(f"\nload average before: {os.getloadavg()}")
    rows = bench_all_schemes(sizes, [s for s in schemes if s != "catmull-clark"],
                             1 if args.quick else args.scheme_repeats, not args.default_malloc, args.per_row)
    print_table("\n| scheme, input | library | median wall (CPU) | user / system | "
                "CPU / catmull-clark |\n|---|---|---|---|---|", rows)
    print(f"load average after: {os.getloadavg()}")


if __name__ == "__main__":
    main()
