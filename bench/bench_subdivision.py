"""Remeshing benchmarks (issue 3), with peers side by side where they install.

Run: ``python bench/bench_subdivision.py [--quick]``. Prints a markdown report
(medians of several runs, seconds) for docs/performance.md:

* Catmull-Clark of the cube, 5 levels (6 -> 6,144 quads);
* Catmull-Clark one level 98,304 -> 393,216 quads, DLFL in and out, against
  pymeshlab's same step (its quads given as a polygon mesh);
* Loop one level 81,920 -> 327,680 triangles against pymeshlab and trimesh;
* Doo-Sabin at the same size as Catmull-Clark;
* every scheme at 10k, 100k and 1M input quads (a quad torus), with the ratio to
  Catmull-Clark on the same input;
* the cost of ``mesh_arrays`` and ``from_corner_arrays`` inside one step;
* peak memory (RSS, in a child process) while subdividing to 1.5M quads.
"""

from __future__ import annotations

import argparse
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
    """A median wall time in seconds that also carries the median CPU time."""

    cpu: float


def median_time(run: Callable[[], object], repeats: int, setup: Callable[[], object] | None = None
                ) -> Timing:
    """Median wall (and CPU) time of ``run`` over ``repeats`` calls (``setup`` not timed).

    The CPU time of the process is reported too: on the shared 2-core machine
    other jobs inflate wall times.
    """
    walls, cpus = [], []
    for _ in range(repeats):
        if setup is not None:
            setup()
        cpu, start = time.process_time(), time.perf_counter()
        run()
        walls.append(time.perf_counter() - start)
        cpus.append(time.process_time() - cpu)
    out = Timing(statistics.median(walls))
    out.cpu = statistics.median(cpus)
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
    """
    holder: list[Mesh] = []

    def setup() -> None:
        holder[:] = [mesh.copy()]

    setup()
    subdivide(holder[0], scheme, max_faces=10**9)

    return median_time(lambda: subdivide(holder[0], scheme, max_faces=10**9), repeats, setup)


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


def bench_all_schemes(sizes: list[str], repeats: int) -> list[Row]:
    rows: list[Row] = []
    schemes = sorted(set(SCHEMES) - {"modified-corner-cut", "sierpinsky"})
    for label in sizes:
        mesh = torus(*SIZES[label])
        cc = time_scheme(mesh, "catmull-clark", repeats)
        rows.append((f"catmull-clark, {label} quads", "livemod", fmt(cc), "1.00"))
        for scheme in schemes:
            if scheme == "catmull-clark":
                continue
            if scheme == "dome" and label == "1M":
                rows.append((f"{scheme}, {label} quads", "livemod",
                             "skipped (112M faces, over the 20M budget)", ""))
                continue
            seconds = time_scheme(mesh, scheme, repeats)
            rows.append((f"{scheme}, {label} quads", "livemod", fmt(seconds),
                         f"{seconds.cpu / cc.cpu:.2f}"))
    return rows


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


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="fewer runs, no 1M inputs")
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()
    repeats = 2 if args.quick else args.repeats
    rows = [*bench_cube_levels(max(repeats, 15)), *bench_catmull_clark(repeats),
            *bench_loop(repeats), *bench_core_costs(repeats), *bench_peak_memory()]
    print("| case | library | median wall (CPU) |\n|---|---|---|")
    for row in rows:
        print("| " + " | ".join(row[:3]) + " |")
    sizes = ["10k", "100k"] if args.quick else ["10k", "100k", "1M"]
    print("\n| scheme, input | library | median wall (CPU) | CPU / catmull-clark |"
          "\n|---|---|---|---|")
    for row in bench_all_schemes(sizes, 1 if args.quick else 3):
        print("| " + " | ".join(row) + " |")


if __name__ == "__main__":
    main()
