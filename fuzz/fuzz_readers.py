"""Long fuzz run of every reader (OBJ, .dlfl, STL, PLY, OFF): mutated valid files, at real and small boundaries.

Plain script (not a test; tests/test_io_adversarial.py runs the same on a small
budget in CI):

    python fuzz/fuzz_readers.py [--seconds 300] [--seed 0] [--hang 10]

Each input is a valid file of one format (tests/io_inputs.py) from a random
mesh, mutated a few times; every fourth is read with the readers' block and
pass sizes made small. A crash is any exception other than the project's
errors (DLFLError and its subclasses); a mesh that reads must validate; a hang
is a read that takes longer than --hang seconds. Prints how many inputs were
tried, crashes and hangs per format, and writes each failing input to
livemod-fuzz-failures/ in the system's temporary folder, to be replayed.
Exits 1 if anything failed.
"""

from __future__ import annotations

import argparse
import random
import signal
import sys
import tempfile
import time
import traceback
import warnings
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from livemod.dlfl import DLFLError, validate  # noqa: E402
from livemod.dlfl.io import _lines, _ply_ascii, dlflfile, obj  # noqa: E402
from tests.io_inputs import FORMATS, bumpy_grid, mutate, quiet_read  # noqa: E402

SMALL = [(_lines, "_BLOCK", 48), (_lines, "_NEWLINE_BLOCK", 40), (obj, "_LINES_PER_PASS", 3),
         (dlflfile, "_LINES_PER_PASS", 3), (_ply_ascii, "_LINES_PER_PASS", 3),
         (_ply_ascii, "_BYTES_PER_SCAN", 32), (_ply_ascii, "_LINE_PATH_MIN_BYTES", 0)]
REAL = [(module, name, getattr(module, name)) for module, name, _ in SMALL]


class Hang(Exception):
    pass


def _alarm(signum: int, frame: object) -> None:
    raise Hang


def one_input(name: str, rng: random.Random, small: bool, hang: float) -> tuple[str, bytes]:
    """Read one mutated file: ``("ok" | "refused" | "crash" | "hang", bytes)``."""
    make, read = FORMATS[name]
    mesh = bumpy_grid(rng.randrange(1, 12), rng.randrange(1, 12), rng.randrange(2**32))
    data = mutate(make(mesh, rng), rng, rng.randrange(1, 10))
    for module, attr, value in (SMALL if small else REAL):
        setattr(module, attr, value)
    signal.setitimer(signal.ITIMER_REAL, hang)
    try:
        validate(quiet_read(read, data))
        return "ok", data
    except DLFLError:
        return "refused", data
    except Hang:
        return "hang", data
    except Exception:  # noqa: BLE001  (what the run is looking for)
        traceback.print_exc()
        return "crash", data
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=300)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--hang", type=float, default=10)
    args = parser.parse_args()
    signal.signal(signal.SIGALRM, _alarm)
    warnings.simplefilter("error", RuntimeWarning)  # an unchecked overflow is a crash too
    rng = random.Random(args.seed)
    outcomes: dict[str, Counter[str]] = {name: Counter() for name in FORMATS}
    failures = Path(tempfile.gettempdir()) / "livemod-fuzz-failures"
    deadline, tried = time.monotonic() + args.seconds, 0
    while time.monotonic() < deadline:
        name = rng.choice(sorted(FORMATS))
        outcome, data = one_input(name, rng, small=tried % 4 == 0, hang=args.hang)
        outcomes[name][outcome] += 1
        tried += 1
        if outcome in ("crash", "hang"):
            failures.mkdir(exist_ok=True)
            (failures / f"{outcome}-{name}-{args.seed}-{tried}.bin").write_bytes(data)
    print(f"{'format':15} {'tried':>7} {'ok':>7} {'refused':>8} {'crashes':>8} {'hangs':>6}")
    for name, seen in outcomes.items():
        print(f"{name:15} {sum(seen.values()):7} {seen['ok']:7} {seen['refused']:8} "
              f"{seen['crash']:8} {seen['hang']:6}")
    bad = sum(seen["crash"] + seen["hang"] for seen in outcomes.values())
    print(f"inputs tried: {tried}, crashes and hangs: {bad}")
    return 1 if bad else 0


if __name__ == "__main__":
    raise SystemExit(main())
