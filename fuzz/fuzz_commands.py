"""A long run of the command fuzz: random thesis commands with bad arguments mixed in.

Run from the repository root: ``python fuzz/fuzz_commands.py [--seeds A:B] [--steps N]``.
Each seed starts a fresh scene and makes ``--steps`` calls (tests/command_fuzz.py
says what is drawn and what is checked: a refusal is a DLFLError and leaves the
scene byte-identical, every mesh passes validate, no numpy warning). Prints the
figures (calls, refusals by type, broken contracts, calls over 5 s) and each
broken contract with its seed and step, which replay it: the run is
deterministic per seed. Exit status 1 when a contract was broken.
"""

from __future__ import annotations

import argparse
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from tests.command_fuzz import describe, run  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--seeds", default="0:20", help="range of seeds, START:STOP")
    parser.add_argument("--steps", type=int, default=300, help="calls per seed")
    args = parser.parse_args()
    start, stop = (int(part) for part in args.seeds.split(":"))
    began = time.perf_counter()
    with tempfile.TemporaryDirectory() as directory:
        report = run(range(start, stop), args.steps, directory)
    print(f"seeds {start}:{stop}, {args.steps} steps each")
    print(describe(report, time.perf_counter() - began), end="")
    return 1 if report.failures else 0


if __name__ == "__main__":
    raise SystemExit(main())
