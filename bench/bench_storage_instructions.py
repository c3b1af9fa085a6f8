"""Instructions the mesh's hot paths cost, counted by callgrind (plain python, not a test).

    python bench/bench_storage_instructions.py [--tree PATH [PATH ...]] [--only NAME ...] [--jobs N]

Each workload runs in a child under ``valgrind --tool=callgrind`` at two sizes;
the difference of the totals over the difference of the sizes is what one unit
costs (an insert/delete pair, one chained extrusion, one quad of a bulk build
alone or followed by Catmull-Clark, one face laid out for the renderer), startup
cancelled out. ``--tree`` runs the
same children against other source trees (e.g. a checkout of ``main``), so that
a change to the storage can be compared with the code before it, unit by unit,
without the noise of wall-clock times on a shared machine (see
bench_step_instructions.py for the step recording).
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
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

SETUP = """
import math, os, sys
import numpy as np
from livemod.dlfl import from_polygons, mesh_arrays
from livemod.dlfl.extrusion import extrude
from livemod.dlfl.shapes import cube
n = int(sys.argv[1])
"""

FINISH = """
sys.stdout.flush()
os._exit(0)
"""


@dataclass(frozen=True)
class Workload:
    """A child script doing ``n`` units of work (``n`` is in its globals)."""

    name: str
    unit: str
    body: str
    small: int
    large: int


TORUS = """
side = int(math.isqrt(n))
i, j = np.meshgrid(np.arange(side), np.arange(side), indexing="ij")
u, v = 2 * np.pi * i.ravel() / side, 2 * np.pi * j.ravel() / side
pos = np.stack([(3 + np.cos(v)) * np.cos(u), (3 + np.cos(v)) * np.sin(u), np.sin(v)], axis=1)
a, b = i * side + j, ((i + 1) % side) * side + j
c, d = ((i + 1) % side) * side + (j + 1) % side, i * side + (j + 1) % side
quads = np.stack([a.ravel(), b.ravel(), c.ravel(), d.ravel()], axis=1)
"""

WORKLOADS = (
    Workload("insert/delete pair", "pair", """
m = cube()
insert, delete = m.insert_edge, m.delete_edge
for _ in range(n):
    delete(insert(0, 2))
""", 2_000, 22_000),
    Workload("doo-sabin chain", "extrusion", """
m, face = cube(), 0
for i in range(n):
    t = 2 * math.pi * i / 36
    face = extrude(m, face, "doo-sabin", 0.5 + 0.3 * math.sin(t), 1, 5.0 * math.sin(t), 2.0)
""", 100, 600),
    Workload("cubical chain", "extrusion", """
m, face = cube(), 0
for i in range(n):
    t = 2 * math.pi * i / 36
    face = extrude(m, face, "cubical", 0.5 + 0.3 * math.sin(t), 1, 5.0 * math.sin(t), 1.0)
""", 100, 600),
    Workload("bulk build (torus)", "quad", TORUS + """
mesh = from_polygons(pos, quads)
""", 100 ** 2, 400 ** 2),
    Workload("mesh_arrays + fans", "face", TORUS + """
from livemod.viewer.geometry import build_geometry
mesh = from_polygons(pos, quads)
mesh.delete_edge(int(mesh.edge_ids()[0]))  # a free slot: the general layout path
arrays = mesh_arrays(mesh)
build_geometry(arrays)
""", 100 ** 2, 400 ** 2),
    Workload("build + catmull-clark", "quad", TORUS + """
from livemod.dlfl.subdivision import subdivide
mesh = from_polygons(pos, quads)
subdivide(mesh, "catmull-clark")
""", 100 ** 2, 400 ** 2),
)

COLLECTED = re.compile(r"Collected\s*:\s*(\d+)")


def instructions(folder: str, tree: str, workload: Workload, n: int) -> int:
    """Callgrind's instruction total for ``workload`` at ``n`` on source ``tree``.

    Raises:
        RuntimeError: the child failed, or callgrind printed no total.
    """
    # one hash seed, and numpy's BLAS without worker threads (valgrind runs threads
    # one at a time, and idle ones spin for a varying number of instructions)
    env = dict(os.environ, PYTHONPATH=tree, PYTHONHASHSEED="0", OPENBLAS_NUM_THREADS="1",
               OMP_NUM_THREADS="1", MKL_NUM_THREADS="1")
    out = os.path.join(folder, f"{abs(hash((tree, workload.name, n)))}.out")
    code = SETUP + workload.body + FINISH
    args = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}",
            sys.executable, "-c", code, str(n)]
    # run in the scratch folder: ``python -c`` puts its working directory first on
    # sys.path, ahead of PYTHONPATH, and the checkout's own livemod would win
    done = subprocess.run(args, capture_output=True, text=True, env=env, cwd=folder)
    found = COLLECTED.search(done.stderr)
    if done.returncode != 0 or found is None:
        raise RuntimeError(f"{workload.name} {n} on {tree}: {done.stderr[-2000:]}")
    return int(found.group(1))


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--tree", nargs="*", default=[str(ROOT)],
                        help="source trees to compare (default: this one)")
    parser.add_argument("--only", nargs="*", help="workload names (default: all)")
    parser.add_argument("--jobs", type=int, default=os.cpu_count() or 1,
                        help="callgrind children at a time")
    args = parser.parse_args(argv)
    chosen = [w for w in WORKLOADS if not args.only or w.name in args.only]
    trees = [str(Path(t).resolve()) for t in args.tree]
    with tempfile.TemporaryDirectory() as folder, ThreadPoolExecutor(args.jobs) as pool:
        futures = {(t, w.name, n): pool.submit(instructions, folder, t, w, n)
                   for w in chosen for t in trees for n in (w.small, w.large)}
        for w in chosen:
            line = [f"{w.name:22s}"]
            for t in trees:
                small, large = futures[t, w.name, w.small].result(), futures[t, w.name, w.large].result()
                line.append(f"{(large - small) / (w.large - w.small):12,.0f}")
            print(" ".join(line) + f"  instructions per {w.unit}", flush=True)
    print("trees: " + ", ".join(trees))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
