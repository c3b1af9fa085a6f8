"""from_polygons on groups of parallel edges that share vertices: exact refusals
come without a search, the search is bounded, and its giving up says so.

The work is counted, not timed (bench/bench_build_pairing.py times these cases): the
corners the rings are walked through, in which the search's budget is set, and the
passes over one end of a group's sides."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pytest

import livemod.dlfl._multi_edges as multi_edges
from livemod.dlfl import from_polygons, validate
from livemod.dlfl.errors import NonManifoldError

# every pairing of these leaves a vertex split, yet neither exact obstruction
# (parity, separation) sees it: only the search can say, and it gives up
SEARCHED_IN_VAIN = [[1, 2, 0, 2], [1, 0, 1, 0], [0, 2, 1], [0, 1, 2]]


@dataclass
class Work:
    """What the pairing did: searches run, ring corners walked in them, side passes."""

    searches: int = 0
    search_corners: int = 0
    passes: int = 0


@pytest.fixture
def work(monkeypatch: pytest.MonkeyPatch) -> Work:
    """Count the pairing's work from now on (see :class:`Work`)."""
    counted = Work()
    rings, ring_count, walk = multi_edges._Rings, multi_edges._Rings.ring_count, multi_edges._Rings.walk
    link_cycles = multi_edges._link_cycles

    def counting_rings(self: multi_edges._Rings, vertex: int) -> int:
        if counted.searches:
            counted.search_corners += len(self.corners_at[vertex])
        return ring_count(self, vertex)

    def counting_walk(self: multi_edges._Rings, *args: object) -> bool:
        counted.searches += 1
        return walk(self, *args)  # type: ignore[arg-type]

    def counting_passes(sides: list[int], *args: object) -> list[list[int]]:
        counted.passes += 1
        return link_cycles(sides, *args)  # type: ignore[arg-type]

    monkeypatch.setattr(rings, "ring_count", counting_rings)
    monkeypatch.setattr(rings, "walk", counting_walk)
    monkeypatch.setattr(multi_edges, "_link_cycles", counting_passes)
    return counted


def _refuse(faces: list[list[int]]) -> str:
    """The message from_polygons refuses ``faces`` with (it must)."""
    with pytest.raises(NonManifoldError) as err:
        from_polygons(np.zeros((max(map(max, faces)) + 1, 3)), faces)
    return str(err.value)


def _no_walk(*args: object) -> bool:
    raise AssertionError("the random search ran")


@pytest.mark.parametrize("spokes", [40, 60])
def test_pillows_meeting_at_one_vertex_are_refused_at_once(spokes: int, work: Work) -> None:
    faces = [[0, i] for i in range(1, spokes + 1) for _ in range(2)]
    message = _refuse(faces)
    assert work.searches == 0  # the search took 23 s on 60 of them
    assert message == (
        "polygons: vertices 0 and 1 are joined by 2 edges that cannot be arranged into a manifold")


def test_a_chain_of_pillows_is_refused_without_a_search(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(multi_edges._Rings, "walk", _no_walk)
    faces = [[i, i + 1] for i in range(60) for _ in range(2)]
    assert _refuse(faces).endswith("cannot be arranged into a manifold")


@pytest.mark.parametrize("faces", [
    [[2, 1, 0, 1], [2, 1, 0], [0, 1, 2]],
    [[0, 1, 2], [1, 0, 2], [2, 0], [1, 0, 2, 0]],
])
def test_an_odd_number_of_split_rings_is_refused_without_a_search(
    monkeypatch: pytest.MonkeyPatch, faces: list[list[int]]
) -> None:
    monkeypatch.setattr(multi_edges._Rings, "walk", _no_walk)
    assert _refuse(faces).endswith("cannot be arranged into a manifold")


def test_a_search_that_finds_nothing_says_it_gave_up(work: Work) -> None:
    message = _refuse(SEARCHED_IN_VAIN)
    assert work.searches == 1 and 0 < work.search_corners <= multi_edges.MULTI_EDGE_WORK
    assert message == (
        "polygons: vertices 0 and 1 are joined by 3 edges, which share vertices with 2 other "
        "groups of parallel edges; the search for a manifold arrangement of them gave up "
        "after 20000 steps (one may still exist)")


@pytest.mark.parametrize(("extra", "steps"), [(100, 487), (1000, 49)])
def test_the_search_is_bounded_however_many_corners_it_counts(
        extra: int, steps: int, work: Work) -> None:
    faces = SEARCHED_IN_VAIN + [[0, 1]] * extra + [[0, 2]] * extra
    message = _refuse(faces)
    # fewer steps on larger rings: the corners walked stay within the same budget
    assert f"gave up after {steps} steps" in message
    assert work.searches == 1 and 0 < work.search_corners <= multi_edges.MULTI_EDGE_WORK


def test_groups_sharing_a_vertex_that_need_the_search_still_build() -> None:
    faces = [[0, 1], [0, 1, 2], [0, 1, 0, 2], [0, 2, 0, 2], [2, 0], [1, 0, 2]]
    mesh = from_polygons(np.eye(3), faces)
    validate(mesh)
    assert (mesh.num_vertices, mesh.num_edges, mesh.num_faces) == (3, 9, 6)


@pytest.mark.parametrize("rounds", [3001, 3000])
def test_one_face_going_round_two_vertices_many_times_is_paired_quickly(
        rounds: int, work: Work) -> None:
    # linked in side order, the sides at vertex 1 fell into `rounds` cycles,
    # merged two at a time with a full pass over the sides each: quadratic
    faces = [[0, 1] * rounds]
    if rounds % 2:
        mesh = from_polygons(np.eye(3)[:2], faces)
        validate(mesh)
        assert (mesh.num_vertices, mesh.num_edges, mesh.num_faces) == (2, rounds, 1)
    else:  # an even number of rounds is the parity obstruction
        with pytest.raises(NonManifoldError, match=f"joined by {rounds} edges that cannot be arranged"):
            from_polygons(np.eye(3)[:2], faces)
    # a seeded random order leaves about ln(3000) = 8 cycles: a few passes, not 1,500
    assert work.passes <= 12


TETRAHEDRON_AT_1 = [[1, 2, 3], [1, 3, 4], [1, 4, 2], [2, 4, 3]]


@pytest.mark.parametrize("touching", [TETRAHEDRON_AT_1, [[1]]])
def test_a_bow_tie_beside_parallel_edges_is_named_not_the_vertex_pairing_mends(
    touching: list[list[int]],
) -> None:
    # vertex 1 is split whatever the pairing; vertex 0 only by an unsolved one
    # (the three edges alone build), which was named instead
    faces = [[1, 0, 1, 0, 1, 0]] + touching
    validate(from_polygons(np.eye(3)[:2], faces[:1]))
    with pytest.raises(NonManifoldError) as err:
        from_polygons(np.zeros((5, 3)), faces)
    assert str(err.value) == (
        "polygons: vertex 1 is non-manifold: its faces form 2 separate fans (a bow-tie)")
