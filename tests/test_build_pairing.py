"""from_polygons on groups of parallel edges that share vertices: exact refusals
come without a search, the search is bounded, and its giving up says so."""

from __future__ import annotations

import time

import numpy as np
import pytest

import livemod.dlfl._multi_edges as multi_edges
from livemod.dlfl import from_polygons, validate
from livemod.dlfl.errors import DLFLError

# every pairing of these leaves a vertex split, yet neither exact obstruction
# (parity, separation) sees it: only the search can say, and it gives up
SEARCHED_IN_VAIN = [[1, 2, 0, 2], [1, 0, 1, 0], [0, 2, 1], [0, 1, 2]]


def _refuse(faces: list[list[int]]) -> tuple[float, str]:
    """Seconds from_polygons took to refuse ``faces`` (it must), and its message."""
    start = time.perf_counter()
    with pytest.raises(DLFLError) as err:
        from_polygons(np.zeros((max(map(max, faces)) + 1, 3)), faces)
    return time.perf_counter() - start, str(err.value)


def _no_walk(*args: object) -> bool:
    raise AssertionError("the random search ran")


@pytest.mark.parametrize("spokes", [40, 60])
def test_pillows_meeting_at_one_vertex_are_refused_at_once(spokes: int) -> None:
    faces = [[0, i] for i in range(1, spokes + 1) for _ in range(2)]
    seconds, message = _refuse(faces)
    assert seconds < 1.0
    assert message == (
        "polygons: vertices 0 and 1 are joined by 2 edges that cannot be arranged into a manifold")


def test_a_chain_of_pillows_is_refused_without_a_search(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(multi_edges._Rings, "walk", _no_walk)
    faces = [[i, i + 1] for i in range(60) for _ in range(2)]
    seconds, message = _refuse(faces)
    assert seconds < 1.0
    assert message.endswith("cannot be arranged into a manifold")


@pytest.mark.parametrize("faces", [
    [[2, 1, 0, 1], [2, 1, 0], [0, 1, 2]],
    [[0, 1, 2], [1, 0, 2], [2, 0], [1, 0, 2, 0]],
])
def test_an_odd_number_of_split_rings_is_refused_without_a_search(
    monkeypatch: pytest.MonkeyPatch, faces: list[list[int]]
) -> None:
    monkeypatch.setattr(multi_edges._Rings, "walk", _no_walk)
    assert _refuse(faces)[1].endswith("cannot be arranged into a manifold")


def test_a_search_that_finds_nothing_says_it_gave_up() -> None:
    seconds, message = _refuse(SEARCHED_IN_VAIN)
    assert seconds < 1.0
    assert message == (
        "polygons: vertices 0 and 1 are joined by 3 edges, which share vertices with 2 other "
        "groups of parallel edges; the search for a manifold arrangement of them gave up "
        "after 20000 steps (one may still exist)")


@pytest.mark.parametrize("extra", [100, 1000])
def test_the_search_is_bounded_however_many_corners_it_counts(extra: int) -> None:
    faces = SEARCHED_IN_VAIN + [[0, 1]] * extra + [[0, 2]] * extra
    seconds, message = _refuse(faces)
    assert seconds < 1.0
    assert "gave up after" in message


def test_groups_sharing_a_vertex_that_need_the_search_still_build() -> None:
    faces = [[0, 1], [0, 1, 2], [0, 1, 0, 2], [0, 2, 0, 2], [2, 0], [1, 0, 2]]
    mesh = from_polygons(np.eye(3), faces)
    validate(mesh)
    assert (mesh.num_vertices, mesh.num_edges, mesh.num_faces) == (3, 9, 6)


@pytest.mark.parametrize("rounds", [3001, 3000])
def test_one_face_going_round_two_vertices_many_times_is_paired_quickly(rounds: int) -> None:
    # linked in side order, the sides at vertex 1 fell into `rounds` cycles,
    # merged two at a time with a full recount each: seconds (quadratic)
    faces = [[0, 1] * rounds]
    start = time.perf_counter()
    if rounds % 2:
        mesh = from_polygons(np.eye(3)[:2], faces)
        validate(mesh)
        assert (mesh.num_vertices, mesh.num_edges, mesh.num_faces) == (2, rounds, 1)
    else:  # an even number of rounds is the parity obstruction
        with pytest.raises(DLFLError, match=f"joined by {rounds} edges that cannot be arranged"):
            from_polygons(np.eye(3)[:2], faces)
    assert time.perf_counter() - start < 1.0


TETRAHEDRON_AT_1 = [[1, 2, 3], [1, 3, 4], [1, 4, 2], [2, 4, 3]]


@pytest.mark.parametrize("touching", [TETRAHEDRON_AT_1, [[1]]])
def test_a_bow_tie_beside_parallel_edges_is_named_not_the_vertex_pairing_mends(
    touching: list[list[int]],
) -> None:
    # vertex 1 is split whatever the pairing; vertex 0 only by an unsolved one
    # (the three edges alone build), which was named instead
    faces = [[1, 0, 1, 0, 1, 0]] + touching
    validate(from_polygons(np.eye(3)[:2], faces[:1]))
    with pytest.raises(DLFLError) as err:
        from_polygons(np.zeros((5, 3)), faces)
    assert str(err.value) == (
        "polygons: vertex 1 is non-manifold: its faces form 2 separate fans (a bow-tie)")
