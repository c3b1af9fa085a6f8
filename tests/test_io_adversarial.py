"""Adversarial input through every reader, on a small seeded budget (a few seconds).

Valid files of every format, then the same files mutated (bytes replaced,
inserted, deleted, spans doubled, the file cut, digit runs stretched past 300
digits), read with every boundary the readers cut at made small: a reader must
return a mesh that validates or raise one of the project's errors, nothing
else (an IndexError, an OverflowError, a numpy warning made an error here).
The long run of the same is fuzz/fuzz_readers.py.
"""

from __future__ import annotations

import random

import pytest

from livemod.dlfl import DLFLError, validate
from tests.io_inputs import FORMATS, bumpy_grid, mutate, quiet_read
from tests.test_io_boundaries import small_boundaries  # noqa: F401  (a fixture)

SEED = 30  # issue 30


@pytest.mark.usefixtures("small_boundaries")
@pytest.mark.parametrize("name", sorted(FORMATS))
def test_mutated_files_give_a_mesh_or_a_project_error(name: str) -> None:
    make, read = FORMATS[name]
    rng = random.Random(f"{SEED}-{name}")
    refused = 0
    for trial in range(40):
        source = make(bumpy_grid(rng.randrange(1, 4), rng.randrange(1, 4), trial), rng)
        data = mutate(source, rng, rng.randrange(1, 6))
        try:
            mesh = quiet_read(read, data)
        except DLFLError:
            refused += 1
            continue
        validate(mesh)
    assert refused > 0  # the edits did make files unreadable, and each was refused cleanly
