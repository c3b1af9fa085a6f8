"""Benchmarks of the DLFL core (issue 2, "Performance"); figures go to docs/performance.md.

Run ``python bench/bench_core.py [--quick]``. Each figure is the median of
several runs, as wall-clock time and as process CPU time (on a shared machine
the CPU time is the steadier of the two). Peers are measured in the same run
when they are installed.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np
from timing import median_times

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from livemod.dlfl import from_polygons, mesh_arrays  # noqa: E402

CUBE_POSITIONS = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0],
                  [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]
CUBE_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]


def torus_quads(n: int, m: int) -> tuple[np.ndarray, np.ndarray]:
    """``(n*m, 3)`` positions and ``(n*m, 4)`` int64 quads of an n x m torus."""
    i, j = np.meshgrid(np.arange(n), np.arange(m), indexing="ij")
    u, v = 2 * np.pi * i.ravel() / n, 2 * np.pi * j.ravel() / m
    ring = 3.0 + np.cos(v)
    pos = np.stack([ring * np.cos(u), ring * np.sin(u), np.sin(v)], axis=1)
    a, b = i * m + j, ((i + 1) % n) * m + j
    c, d = ((i + 1) % n) * m + (j + 1) % m, i * m + (j + 1) % m
    return pos, np.stack([a.ravel(), b.ravel(), c.ravel(), d.ravel()], axis=1)


def bench_pair(pairs: int, repeats: int) -> None:
    mesh = from_polygons(CUBE_POSITIONS, CUBE_FACES)
    insert, delete = mesh.insert_edge, mesh.delete_edge

    def run() -> None:
        for _ in range(pairs):
            delete(insert(0, 2))

    wall, cpu = median_times(run, repeats)
    print(f"livemod insert_edge+delete_edge pair on a cube face: "
          f"{wall / pairs * 1e6:.2f} us wall, {cpu / pairs * 1e6:.2f} us CPU")
    bench_openmesh_pair(pairs, repeats)


def bench_openmesh_pair(pairs: int, repeats: int) -> None:
    """OpenMesh's Python binding: split a cube face by a diagonal and merge it back.

    OpenMesh only marks removed elements deleted; its memory grows with the
    history until ``garbage_collection()``. Both ways are measured.
    """
    try:
        import openmesh  # type: ignore[import-not-found]
    except ImportError:
        print("openmesh: not installed")
        return
    for collect in (False, True):
        mesh = openmesh.PolyMesh(np.array(CUBE_POSITIONS, float), np.array(CUBE_FACES))
        boundary = mesh.halfedge_handle(mesh.face_handle(0))

        def run(mesh=mesh, boundary=boundary, collect=collect) -> None:
            for _ in range(pairs):
                # the diagonal from the end of `boundary` to the start of the one before it
                heh = mesh.insert_edge(boundary, mesh.prev_halfedge_handle(boundary))
                mesh.remove_edge(mesh.edge_handle(heh))
                if collect:
                    mesh.garbage_collection()
                    boundary = mesh.halfedge_handle(mesh.face_handle(0))

        wall, cpu = median_times(run, repeats)
        how = "with garbage_collection() per pair" if collect else "deleted elements kept"
        print(f"openmesh pair ({how}): {wall / pairs * 1e6:.2f} us wall, "
              f"{cpu / pairs * 1e6:.2f} us CPU")


def bench_bulk(n: int, repeats: int) -> None:
    pos, quads = torus_quads(n, n)
    corners = quads.size
    wall, cpu = median_times(lambda: from_polygons(pos, quads), repeats)
    print(f"build {n * n:,}-quad torus (from_polygons on an (F, 4) array): "
          f"{wall:.3f} s wall, {cpu:.3f} s CPU")
    mesh = from_polygons(pos, quads)
    wall, cpu = median_times(lambda: mesh_arrays(mesh), repeats)
    print(f"export it (mesh_arrays): {wall:.3f} s wall, {cpu:.3f} s CPU")
    peak = peak_build_bytes(n)
    print(f"peak memory of the build: {peak / 2**20:.0f} MiB = {peak / corners:.0f} bytes per corner")
    bench_openmesh_bulk(pos, quads, repeats)


PEAK_SCRIPT = """
import sys, tracemalloc
sys.path.insert(0, {root!r}); sys.path.insert(0, {bench!r})
from bench_core import torus_quads
from livemod.dlfl import from_polygons
pos, quads = torus_quads({n}, {n})
tracemalloc.start()
mesh = from_polygons(pos, quads)
print(tracemalloc.get_traced_memory()[1])
"""


def peak_build_bytes(n: int) -> int:
    """Peak bytes numpy and Python allocate while building (fresh process, input excluded)."""
    script = PEAK_SCRIPT.format(root=str(ROOT), bench=str(ROOT / "bench"), n=n)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True)
    return int(out.stdout.split()[-1])


def bench_openmesh_bulk(pos: np.ndarray, quads: np.ndarray, repeats: int) -> None:
    try:
        import openmesh
    except ImportError:
        return
    wall, cpu = median_times(lambda: openmesh.PolyMesh(pos, quads), repeats)
    print(f"openmesh PolyMesh(points, faces): {wall:.3f} s wall, {cpu:.3f} s CPU")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--quick", action="store_true", help="small sizes, for a smoke run")
    args = parser.parse_args()
    bench_pair(2_000 if args.quick else 20_000, 3 if args.quick else 7)
    bench_bulk(100 if args.quick else 1000, 3 if args.quick else 5)


if __name__ == "__main__":
    main()
