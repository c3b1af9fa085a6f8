"""Timing from_polygons on soups of parallel edges that share vertices (the multi-edge
pairing of livemod/dlfl/_multi_edges.py): exact refusals, the bounded search, long laps.

Run ``python bench/bench_build_pairing.py [--repeat N]``. Each figure is the median of
N runs (default 7), in wall and process CPU time. The target of every case is "well
under a second" (the search's budget, ``MULTI_EDGE_WORK``, is set for that); before the
exact refusals 60 pillows at one vertex took 23 s, and before the seeded order 4,001
laps of one face took 9 s. tests/test_build_pairing.py counts the work of these cases.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable
from pathlib import Path

import numpy as np
from timing import median_times

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from livemod.dlfl import from_polygons  # noqa: E402
from livemod.dlfl.errors import DLFLError  # noqa: E402

SEARCHED_IN_VAIN = [[1, 2, 0, 2], [1, 0, 1, 0], [0, 2, 1], [0, 1, 2]]

CASES: dict[str, list[list[int]]] = {
    "60 pillows at one vertex (refused at once)":
        [[0, i] for i in range(1, 61) for _ in range(2)],
    "a chain of 60 pillows (refused at once)": [[i, i + 1] for i in range(60) for _ in range(2)],
    "groups the search gives up on": SEARCHED_IN_VAIN,
    "the same with 1,000 more parallel edges each":
        SEARCHED_IN_VAIN + [[0, 1]] * 1000 + [[0, 2]] * 1000,
    "one face going 3,001 times round two vertices (builds)": [[0, 1] * 3001],
    "one face going 4,001 times round two vertices (builds)": [[0, 1] * 4001],
    "one face going 4,000 times round two vertices (refused)": [[0, 1] * 4000],
}


def build_or_refuse(faces: list[list[int]]) -> Callable[[], str]:
    """A call that builds ``faces`` and says whether it was built or refused."""
    positions = np.zeros((max(map(max, faces)) + 1, 3))

    def run() -> str:
        try:
            from_polygons(positions, faces)
        except DLFLError:
            return "refused"
        return "built"

    return run


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=7, help="runs per case (median)")
    args = parser.parse_args(argv)
    for label, faces in CASES.items():
        run = build_or_refuse(faces)
        outcome = run()
        wall, cpu = median_times(run, args.repeat)
        print(f"{label}: {outcome}, {wall * 1000:.1f} ms wall, {cpu * 1000:.1f} ms CPU "
              "(target: well under 1 s)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
