"""File I/O benchmark: a 1,000,000-quad torus, livemod against trimesh.

Plain script (not a test). Prints the median of several runs of each step,
side by side with trimesh in the same run: OBJ load and write, then loading the
same torus as binary STL (2,000,000 triangles, welded: trimesh's default
``process=True`` merges vertices too) and as binary PLY:

    python bench/bench_io.py [--runs 3] [--grid 1000] [--skip-obj]

Targets (issue 2): load <= 2.0 s and >= 2x faster than
``trimesh.load(path, process=False)``; write <= 1.8 s.

``--dlfl`` times TopMod's ``.dlfl`` instead, next to OBJ on the same tori
(``--dlfl-grids``, default 316 and 1225: 99,856 and 1,500,625 quads), and
prints the .dlfl/OBJ ratios (target: within 2x of OBJ):

    python bench/bench_io.py --dlfl [--runs 5] [--dlfl-grids 316,1225]

``--export`` writes the torus as GLB (target <= 1.0 s) and 3MF (<= 3 s), loads the
GLB back with trimesh and compares its triangle count (issue 28):

    python bench/bench_io.py --export [--runs 3] [--grid 1000]
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from timing import median_times  # noqa: E402

from livemod.dlfl import Mesh, from_polygons  # noqa: E402
from livemod.dlfl.io import load_mesh, save_mesh, write_obj  # noqa: E402
from livemod.dlfl.io.obj import obj_bytes  # noqa: E402


def torus(grid: int) -> Mesh:
    """A ``grid`` x ``grid`` quad torus (radii 2 and 0.5)."""
    i, j = np.meshgrid(np.arange(grid), np.arange(grid), indexing="ij")
    u, v = 2 * np.pi * i / grid, 2 * np.pi * j / grid
    ring = 2.0 + 0.5 * np.cos(v)
    positions = np.stack([ring * np.cos(u), ring * np.sin(u), 0.5 * np.sin(v)], -1)
    i1, j1 = (i + 1) % grid, (j + 1) % grid
    quads = np.stack([i * grid + j, i1 * grid + j, i1 * grid + j1, i * grid + j1], -1)
    return from_polygons(positions.reshape(-1, 3), quads.reshape(-1, 4))


def export_synced(peer: object, path: Path) -> None:
    """trimesh's export made durable like ``write_obj`` (which fsyncs before renaming)."""
    peer.export(path)  # type: ignore[attr-defined]
    with open(path, "rb") as handle:
        os.fsync(handle.fileno())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--grid", type=int, default=1000)
    parser.add_argument("--skip-obj", action="store_true", help="only the STL and PLY loads")
    parser.add_argument("--dlfl", action="store_true", help="only .dlfl against OBJ")
    parser.add_argument("--dlfl-grids", default="316,1225",
                        help="torus grid sizes for --dlfl, comma-separated")
    parser.add_argument("--export", action="store_true", help="only GLB and 3MF writes")
    args = parser.parse_args()
    if args.export:
        bench_export(torus(args.grid), args.runs)
        return
    if args.dlfl:
        bench_dlfl([int(g) for g in args.dlfl_grids.split(",")], args.runs)
        return
    mesh = torus(args.grid)
    try:
        import trimesh
    except ImportError:
        trimesh = None
    if not args.skip_obj:
        bench_obj(mesh, trimesh, args.runs)
    bench_other_formats(mesh, trimesh, args.runs)


def bench_export(mesh: Mesh, runs: int) -> None:
    """Median GLB and 3MF write times of ``mesh``, and a check of the GLB by trimesh."""
    import trimesh

    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for suffix in ("glb", "3mf"):
            path = Path(folder) / f"torus.{suffix}"
            rows.append((f"livemod save_mesh .{suffix}",
                         median_times(lambda p=path: save_mesh(mesh, p), runs),
                         path.stat().st_size / 1e6))
        glb = Path(folder) / "torus.glb"
        wall, cpu = median_times(lambda: trimesh.load(glb, force="mesh", process=False), runs)
        peer = trimesh.load(glb, force="mesh", process=False)
    triangles = 2 * mesh.counts()[2]
    load = os.getloadavg()[0]
    print(f"torus F={mesh.counts()[2]} quads ({triangles} triangles), median of {runs} runs, "
          f"load average {load:.1f} (a shared machine: wall times are noisy)")
    print(f"| {'step':26s} | {'MB':>6s} | {'wall s':>7s} | {'CPU s':>7s} |")
    print(f"|{'-' * 28}|{'-' * 8}|{'-' * 9}|{'-' * 9}|")
    for name, (w, c), size in rows:
        print(f"| {name:26s} | {size:6.1f} | {w:7.2f} | {c:7.2f} |")
    print(f"| {'trimesh.load .glb':26s} | {'':6s} | {wall:7.2f} | {cpu:7.2f} |")
    print(f"trimesh read {len(peer.faces)} triangles and {len(peer.vertices)} vertices "
          f"(expected {triangles} and {4 * mesh.counts()[2]}: a vertex per face corner): "
          f"{'same' if len(peer.faces) == triangles else 'DIFFERENT'}")
    print("targets: GLB <= 1.0 s, 3MF <= 3 s")


def bench_other_formats(mesh: Mesh, trimesh: object, runs: int) -> None:
    """Median load times of ``mesh`` written as binary STL and PLY, with trimesh's."""
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for suffix in ("stl", "ply"):
            path = Path(folder) / f"torus.{suffix}"
            save_mesh(mesh, path)
            rows.append((f"livemod load_mesh .{suffix}",
                         median_times(load_mesh, runs, setup=lambda p=path: p)))
            if trimesh is not None:
                rows.append((f"trimesh.load .{suffix}", median_times(
                    trimesh.load, runs, setup=lambda p=path: p)))  # type: ignore[attr-defined]
    print(f"STL and PLY loads of the same torus, median of {runs} runs:")
    print(f"| {'step':30s} | {'wall s':>7s} | {'CPU s':>7s} |")
    print(f"|{'-' * 32}|{'-' * 9}|{'-' * 9}|")
    for name, (wall, cpu) in rows:
        print(f"| {name:30s} | {wall:7.2f} | {cpu:7.2f} |")


def bench_obj(mesh: Mesh, trimesh: object, runs: int) -> None:
    """OBJ text, write and load of ``mesh``, with trimesh's load and export."""
    with tempfile.TemporaryDirectory() as folder:
        ours = Path(folder) / "torus.obj"
        rows = [("livemod OBJ text (obj_bytes)", median_times(lambda: obj_bytes(mesh), runs)),
                ("livemod write_obj", median_times(lambda: write_obj(mesh, ours), runs))]
        size_mb = ours.stat().st_size / 1e6
        rows.append(("livemod load_mesh", median_times(lambda: load_mesh(ours), runs)))
        if trimesh is not None:
            peer = trimesh.load(ours, process=False)
            rows.append(("trimesh.load(process=False)",
                         median_times(lambda: trimesh.load(ours, process=False), runs)))
            theirs = Path(folder) / "trimesh.obj"
            rows.append(("trimesh export", median_times(lambda: peer.export(theirs), runs)))
            rows.append(("trimesh export + fsync",
                         median_times(lambda: export_synced(peer, theirs), runs)))
    report(rows, mesh, size_mb, runs)


def bench_dlfl(grids: list[int], runs: int) -> None:
    """Median write and load times of .dlfl and OBJ on tori of ``grids`` x ``grids``
    quads, with the .dlfl/OBJ ratios and the load average before and after."""
    print(f"# .dlfl against OBJ, median of {runs} runs (wall s / CPU s of this process)")
    print("| faces | format | MB | write wall | write CPU | load wall | load CPU |")
    print("|---|---|---|---|---|---|---|")
    ratios = []
    for grid in grids:
        mesh = torus(grid)
        before = os.getloadavg()[0]
        times = {fmt: _format_times(mesh, fmt, runs) for fmt in ("obj", "dlfl")}
        for fmt, (size_mb, write, load) in times.items():
            print(f"| {mesh.counts()[2]:,} | {fmt} | {size_mb:.1f} | {write[0]:.2f} | "
                  f"{write[1]:.2f} | {load[0]:.2f} | {load[1]:.2f} |")
        (_, w_obj, l_obj), (_, w_dlfl, l_dlfl) = times["obj"], times["dlfl"]
        ratios.append((mesh.counts()[2], [w_dlfl[i] / w_obj[i] for i in (0, 1)],
                       [l_dlfl[i] / l_obj[i] for i in (0, 1)], before, os.getloadavg()[0]))
        del mesh
    print()
    print("| faces | .dlfl/OBJ write (wall, CPU) | .dlfl/OBJ load (wall, CPU) | load average |")
    print("|---|---|---|---|")
    for faces, write, load, before, after in ratios:
        print(f"| {faces:,} | {write[0]:.2f}x, {write[1]:.2f}x | {load[0]:.2f}x, {load[1]:.2f}x "
              f"| {before:.1f} -> {after:.1f} |")


def _format_times(mesh: Mesh, fmt: str, runs: int,
                  ) -> tuple[float, tuple[float, float], tuple[float, float]]:
    """``(file MB, write medians, load medians)`` of ``mesh`` saved as ``fmt``."""
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / f"torus.{fmt}"
        write = median_times(lambda: save_mesh(mesh, path), runs)
        load = median_times(lambda: load_mesh(path), runs)
        return path.stat().st_size / 1e6, write, load


def report(rows: list[tuple[str, tuple[float, float]]], mesh: Mesh, size_mb: float,
           runs: int) -> None:
    v, e, f = mesh.counts()
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"torus: V={v} E={e} F={f} quads, OBJ {size_mb:.1f} MB, median of {runs} runs, "
          f"load average {load:.1f}")
    print(f"| {'step':30s} | {'wall s':>7s} | {'CPU s':>7s} |")
    print(f"|{'-' * 32}|{'-' * 9}|{'-' * 9}|")
    for name, (wall, cpu) in rows:
        print(f"| {name:30s} | {wall:7.2f} | {cpu:7.2f} |")
    times = dict(rows)
    if "trimesh.load(process=False)" in times:
        for kind, i in (("wall", 0), ("CPU", 1)):
            load_ratio = times["trimesh.load(process=False)"][i] / times["livemod load_mesh"][i]
            write_ratio = times["trimesh export + fsync"][i] / times["livemod write_obj"][i]
            print(f"speed-up over trimesh ({kind}): load {load_ratio:.1f}x (target >= 2x), "
                  f"durable write {write_ratio:.1f}x")
    print(f"targets: load <= 2.0 s (wall {times['livemod load_mesh'][0]:.2f}, "
          f"CPU {times['livemod load_mesh'][1]:.2f}), write <= 1.8 s "
          f"(wall {times['livemod write_obj'][0]:.2f}, CPU {times['livemod write_obj'][1]:.2f}; "
          f"text alone wall {times['livemod OBJ text (obj_bytes)'][0]:.2f})")


if __name__ == "__main__":
    main()
