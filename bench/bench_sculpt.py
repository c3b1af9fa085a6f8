"""Benchmarks of rind, wireframe, columns and the other sculpting operations (medians).

Run: ``python bench/bench_sculpt.py [--repeat N] [--only TEXT]``. Targets (issue 4):
wireframe of a 100,000-face mesh in at most 2 s; rind of a 100,000-face mesh in at
most 2 s. The input is a 400 x 250 quad torus (100,000 faces); building it is not
timed. Issue 30: truncate to 236,000 faces (12.8 s) and sierpinsky to 2,100,000
faces (37 s) within 3x Catmull-Clark at the same output size: those rows are timed
beside Catmull-Clark on the torus whose result has as many faces, and the CPU ratio
printed. Prints a Markdown table for docs/performance.md.
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Callable

from timing import median_times

from livemod.dlfl.cutting import truncate
from livemod.dlfl.geometry import mesh_smooth
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.rind import rind
from livemod.dlfl.selection import checkerboard
from livemod.dlfl.shapes import cube, torus
from livemod.dlfl.sierpinsky import sierpinsky
from livemod.dlfl.sponge import sponge
from livemod.dlfl.subdivision import catmull_clark
from livemod.dlfl.wireframe import columns, modified_corner_cut, wireframe

BIG = (400, 250)  # 100,000 quads


def big_torus() -> Mesh:
    return torus(*BIG, major=4.0, minor=1.0)


def every_tenth_face(mesh: Mesh) -> list[int]:
    """Every tenth face in rows of the torus, so no two punched faces share an edge."""
    ids = mesh.face_ids().tolist()
    return ids[::10]


CASES: list[tuple[str, Callable[[], Mesh], Callable[[Mesh], object], str]] = [
    ("wireframe, 100,000-face torus", big_torus, lambda m: wireframe(m, 0.01), "2 s"),
    ("rind, 100,000-face torus, 10,000 faces punched", big_torus,
     lambda m: rind(m, every_tenth_face(m), 0.05), "2 s"),
    ("crust only, 100,000-face torus", big_torus, lambda m: rind(m, (), 0.05), ""),
    ("modified corner cut, 100,000-face torus", big_torus,
     lambda m: modified_corner_cut(m, 0.01), ""),
    ("Menger sponge, 100,000-face torus", big_torus, lambda m: sponge(m, 0.05), ""),
    ("mesh smooth, 100,000-face torus", big_torus, mesh_smooth, ""),
    ("columns (4 segments), 900-face torus", lambda: torus(30, 30, 4.0, 1.0),
     lambda m: columns(m, 0.02, 4), ""),
    ("sierpinsky, 2,500-face torus", lambda: torus(50, 50, 4.0, 1.0), sierpinsky, ""),
    ("checkerboard selection, 2,500-face torus", lambda: torus(50, 50, 4.0, 1.0),
     lambda m: checkerboard(m, 0), ""),
    ("wireframe, cube", cube, lambda m: wireframe(m, 0.1), ""),
    ("truncate, 343 x 343 torus (out: 235,298 faces)", lambda: torus(343, 343, 4.0, 1.0),
     truncate, ""),
    ("catmull-clark, 243 x 243 torus (out: 236,196 faces)", lambda: torus(243, 243, 4.0, 1.0),
     catmull_clark, ""),
    ("sierpinsky, 650 x 650 torus (out: 2,112,500 faces)", lambda: torus(650, 650, 4.0, 1.0),
     sierpinsky, ""),
    ("catmull-clark, 727 x 727 torus (out: 2,114,116 faces)", lambda: torus(727, 727, 4.0, 1.0),
     catmull_clark, ""),
]

# (operation, Catmull-Clark at the same output size): issue 30's target, within 3x
RATIOS = [("truncate, 343", "catmull-clark, 243"), ("sierpinsky, 650", "catmull-clark, 727")]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--only", default="", help="run only cases whose label has this text")
    args = parser.parse_args()
    print(f"cpus: {os.cpu_count()}, load: {os.getloadavg()[0]:.1f}, "
          f"repeat: {args.repeat} (median)\n")
    print("| operation | median wall | median CPU | target |")
    print("|---|---|---|---|")
    cpus: dict[str, float] = {}
    for label, make, run, target in CASES:
        if args.only not in label:
            continue
        wall, cpu = median_times(run, args.repeat, setup=make)
        cpus[label] = cpu
        verdict = ""
        if target:
            limit = float(target.split()[0])
            verdict = f"{target} ({'met' if wall <= limit else 'MISSED'})"
        print(f"| {label} | {wall:.3f} s | {cpu:.3f} s | {verdict} |", flush=True)
    for op, peer in RATIOS:
        mine = [cpu for label, cpu in cpus.items() if label.startswith(op)]
        theirs = [cpu for label, cpu in cpus.items() if label.startswith(peer)]
        if mine and theirs:
            ratio = mine[0] / theirs[0]
            print(f"\n{op}...: {ratio:.2f}x Catmull-Clark's CPU at the same output size "
                  f"(target 3x: {'met' if ratio <= 3 else 'MISSED'})")


if __name__ == "__main__":
    main()
