"""Graph helpers (livemod.dlfl._graph): cycles of permutations, vertex rings."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl._graph import MAX_WALK, cycle_labels, one_cycle_each


def test_every_group_one_cycle() -> None:
    # groups {0}, {1, 2}, {3, 4, 5}: a fixed point, a swap and a 3-cycle
    perm = np.array([0, 2, 1, 4, 5, 3])
    group = np.array([0, 1, 1, 2, 2, 2])
    assert one_cycle_each(perm, group, np.array([1, 2, 3])) is True


@pytest.mark.parametrize("perm", [[0, 2, 1, 3, 5, 4], [0, 1, 2, 4, 5, 3], [0, 2, 1, 4, 3, 5]])
def test_a_group_split_into_two_cycles_is_found(perm: list[int]) -> None:
    group = np.array([0, 1, 1, 2, 2, 2])
    assert one_cycle_each(np.array(perm), group, np.array([1, 2, 3])) is False
    labels = cycle_labels(np.array(perm))
    assert len(set(labels[group == 1].tolist()) | set(labels[group == 2].tolist())) > 2


def test_large_groups_and_empty_input() -> None:
    n = MAX_WALK + 1
    assert one_cycle_each(np.roll(np.arange(n), 1), np.zeros(n, dtype=np.int64),
                          np.array([n])) is None
    empty = np.zeros(0, dtype=np.int64)
    assert one_cycle_each(empty, empty, np.array([0, 0])) is True


def test_groups_without_elements_are_skipped() -> None:
    perm = np.array([1, 0])
    assert one_cycle_each(perm, np.array([2, 2]), np.array([0, 0, 2])) is True
