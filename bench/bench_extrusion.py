"""Benchmarks of extrusions and handles (medians of several runs).

Run: ``python bench/bench_extrusion.py [--repeat N]``. Targets (issue 4): 1,000
chained Doo-Sabin extrusions on a cube (the thesis's towers) in at most 0.5 s.
Prints a Markdown table for docs/performance.md.
"""

from __future__ import annotations

import argparse
import math
import os
from collections.abc import Callable

from timing import median_times

from livemod.dlfl.connect import connect_faces, hermite_handle
from livemod.dlfl.extrusion import extrude
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.shapes import cube, torus


def chained(kind: str, count: int, scale: float = 1.0) -> Callable[[], Mesh]:
    """``count`` extrusions of ``kind``, each on the face the previous one returned,
    the distance driven by a sine as in the thesis's towers. (A Doo-Sabin step halves
    a quad, so its scale is 2 to keep 1,000 steps from shrinking to nothing.)"""
    def run() -> Mesh:
        m = cube()
        face = 0
        for i in range(count):
            t = 2 * math.pi * i / 36
            face = extrude(m, face, kind, 0.5 + 0.3 * math.sin(t), 1, 5.0 * math.sin(t), scale)
        return m
    return run


def every_face_of_a_torus(kind: str) -> Callable[[], Mesh]:
    """One extrusion of every face of a 100 x 100 torus (10,000 faces)."""
    def run() -> Mesh:
        m = torus(100, 100)
        for face in m.face_ids().tolist():
            extrude(m, face, kind, 0.1)
        return m
    return run


def handles(kind: str, segments: int) -> Callable[[], Mesh]:
    """A handle between cube faces 0 and 1 with ``segments`` segments."""
    def run() -> Mesh:
        m = cube()
        c1, c2 = m.corner_at(0, 0), m.corner_at(1, 0)
        if kind == "hermite":
            hermite_handle(m, c1, c2, segments)
        else:
            connect_faces(m, m.corner_at(0, 0), m.corner_at(5, 4), segments)
        return m
    return run


CASES: list[tuple[str, Callable[[], Mesh], float | None]] = [
    ("1,000 chained doo-sabin extrusions on a cube", chained("doo-sabin", 1000, 2.0), 0.5),
    ("1,000 chained cubical extrusions on a cube", chained("cubical", 1000), None),
    ("100 chained dodeca extrusions on a cube", chained("dodeca", 100), None),
    ("doo-sabin on every face of a 10,000-face torus", every_face_of_a_torus("doo-sabin"), None),
    ("connectFaces cube top-bottom, 1,000 segments", handles("connect", 1000), None),
    ("hermite handle, 1,000 segments", handles("hermite", 1000), None),
]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    print(f"load average before: {os.getloadavg()[0]:.1f}")
    print("| operation | median wall (s) | median CPU (s) | target (s) |")
    print("|---|---|---|---|")
    for label, func, target in CASES:
        wall, cpu = median_times(func, args.repeat)
        verdict = "" if target is None else f"{target} ({'met' if wall <= target else 'MISSED'})"
        print(f"| {label} | {wall:.3f} | {cpu:.3f} | {verdict} |", flush=True)
    print(f"load average after: {os.getloadavg()[0]:.1f}")


if __name__ == "__main__":
    main()
