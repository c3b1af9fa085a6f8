"""Tests of livemod.dlfl._operators: the slot-level bodies behind Mesh's operators.

Their behaviour is tested through the public operators in tests/test_mesh.py; here,
what is particular to the bodies: the inlined copies of table methods agree with
them, and the hot pair reaches its bodies in one call.
"""

from __future__ import annotations

import sys
from pathlib import Path
from types import FrameType
from typing import Any

import numpy as np

from livemod.dlfl import validate
from livemod.dlfl._operators import alloc
from livemod.dlfl._table import Table
from tests.meshes import cube


def table_state(table: Table) -> tuple[Any, ...]:
    return (table.n, list(table.free), dict(table.moved), table.next_id,
            table.ids[: table.n].tolist(), table.live_ids().tolist())


def test_alloc_takes_a_free_slot_exactly_as_the_table_would():
    tables = [Table("edge", {"c0": (np.int32, ())}) for _ in range(2)]
    for table in tables:
        table.reserve(4)
        slots = [table.alloc() for _ in range(4)]
        table.release(slots[1])
        table.release(slots[3])
        table.live_ids()  # fills the sorted cache, which a new element must drop
    fast, general = tables
    assert [alloc(fast), alloc(fast)] == [general.alloc(), general.alloc()] == [3, 1]
    assert table_state(fast) == table_state(general)
    assert fast.live_ids().tolist() == [0, 2, 4, 5]
    assert alloc(fast) == general.alloc() == 4  # no free slot left: the general path
    assert table_state(fast) == table_state(general)


def test_the_insert_delete_pair_calls_its_bodies_directly():
    # every Python call on this path costs the interactive pair about 1 %
    # (bench/bench_storage_instructions.py): the entry points call their
    # bodies with no wrapper between them
    mesh = cube()
    mesh.delete_edge(mesh.insert_edge(0, 2))  # the tables have room from now on
    calls: list[tuple[str, str]] = []

    def record(frame: FrameType, event: str, arg: object) -> None:
        name = Path(frame.f_code.co_filename).name
        if event == "call" and name in ("mesh.py", "_operators.py"):
            calls.append((name, frame.f_code.co_name))

    sys.setprofile(record)
    try:
        mesh.delete_edge(mesh.insert_edge(0, 2))
    finally:
        sys.setprofile(None)
    assert calls == [("mesh.py", "insert_edge"), ("_operators.py", "insert_cofacial"),
                     ("_operators.py", "alloc"), ("_operators.py", "alloc"),
                     ("mesh.py", "delete_edge"), ("_operators.py", "delete_merge")]
    validate(mesh)
    assert mesh.counts() == (8, 12, 6)
