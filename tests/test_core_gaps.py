"""The core gaps left by the DLFL core review: multi-edge pairing in from_polygons
and the hole flag of a merging insert_edge."""

from __future__ import annotations

import itertools
import random
import warnings

import numpy as np
import pytest

from livemod.dlfl import DLFLError, Mesh, from_polygons, mesh_arrays, validate
from livemod.dlfl.analysis import component_genera
from livemod.dlfl.errors import NonManifoldError, UnknownIdError
from tests.meshes import (
    TETRA_POSITIONS,
    canonical,
    cube,
    euler_ok,
    path_face,
    tetrahedron,
    torus,
    triangle,
)

REPRO_FACES = [[1, 2], [2, 1, 3], [2, 3, 1], [1, 2], [1, 2], [2, 3], [1, 2], [0, 3], [1, 2],
               [1, 2], [1, 2], [1, 2], [1, 2], [1, 3, 0, 3]]


def polygons_of(mesh: Mesh) -> tuple[np.ndarray, list[np.ndarray]]:
    """The mesh's positions and every face (holes included) as a vertex-index list."""
    a = mesh_arrays(mesh)
    faces = np.split(a.corner_vertex, a.face_offsets[1:-1]) if len(a.face_ids) else []
    return a.positions, faces


def rebuild(mesh: Mesh) -> Mesh:
    """mesh -> polygons -> from_polygons, checked by validate()."""
    rebuilt = from_polygons(*polygons_of(mesh))
    validate(rebuilt)
    return rebuilt


def assert_same_surface(rebuilt: Mesh, mesh: Mesh) -> None:
    assert canonical(rebuilt) == canonical(mesh)
    assert sorted(component_genera(rebuilt)) == sorted(component_genera(mesh))
    assert euler_ok(rebuilt)


# -- 1. from_polygons pairs parallel sides whenever a manifold pairing exists -----------


def test_the_reviewers_soup_with_ten_parallel_edges_builds() -> None:
    mesh = from_polygons(TETRA_POSITIONS, REPRO_FACES)
    validate(mesh)
    assert mesh.counts() == (4, 16, 14)
    assert component_genera(mesh) == [0]
    a = mesh_arrays(mesh)
    ends = np.sort(a.edge_vertices, axis=1).tolist()
    assert ends.count([1, 2]) == 10


def long_sequence(seed: int, steps: int, start: Mesh) -> Mesh:
    """A seeded run of co-facial and merging inserts and deletes, checked after each
    step and round-tripped through polygons every step."""
    rng = random.Random(seed)
    m = start
    for _ in range(steps):
        corners = m.corner_ids().tolist()
        roll = rng.random()
        if roll < 0.5:
            ring = m.face_corners(m.corner_face(rng.choice(corners)))
            if len(ring) >= 2:
                c1, c2 = rng.sample(ring, 2)
                m.insert_edge(c1, c2)
        elif roll < 0.65:
            c1 = rng.choice(corners)
            others = [c for c in corners if m.corner_face(c) != m.corner_face(c1)]
            if others:
                m.insert_edge(c1, rng.choice(others))
        elif m.num_edges > 1:
            m.delete_edge(rng.choice(m.edge_ids().tolist()), cleanup=False)
        validate(m)
        ends = mesh_arrays(m).edge_vertices
        if (ends[:, 0] != ends[:, 1]).all():  # a self-loop is no polygon side
            assert_same_surface(rebuild(m), m)
    return m


def test_a_long_operator_sequence_round_trips_through_polygons() -> None:
    m = long_sequence(22, 150, tetrahedron())
    assert m.num_edges > 6


def stack_parallel_edges(mesh: Mesh, rng: random.Random, pairs: list[tuple[int, int]],
                         count: int) -> Mesh:
    """Insert ``count`` edges, each between the corners at two vertices of one of
    ``pairs`` in one face (a 2-gon or a split face: parallel edges)."""
    for _ in range(count):
        a, b = rng.choice(pairs)
        faces = [f for f in mesh.face_ids().tolist()
                 if {a, b} <= set(mesh.face_vertices(f))]
        f = rng.choice(faces)
        ca = rng.choice([c for c in mesh.face_corners(f) if mesh.corner_vertex(c) == a])
        cb = rng.choice([c for c in mesh.face_corners(f) if mesh.corner_vertex(c) == b])
        mesh.insert_edge(ca, cb) if rng.random() < 0.5 else mesh.insert_edge(cb, ca)
        if rng.random() < 0.2 and mesh.num_edges > 6:
            mesh.delete_edge(rng.choice(mesh.edge_ids().tolist()), cleanup=False)
        validate(mesh)
    return mesh


@pytest.mark.parametrize("seed", range(40))
def test_many_parallel_edges_round_trip_through_polygons(seed: int) -> None:
    rng = random.Random(seed)
    pairs = [(1, 2)] if seed % 2 else rng.sample(list(itertools.combinations(range(4), 2)), 3)
    mesh = stack_parallel_edges(tetrahedron(), rng, pairs, rng.randint(20, 40))
    ends = mesh_arrays(mesh).edge_vertices
    if (ends[:, 0] == ends[:, 1]).any():
        return  # a self-loop is no polygon side
    assert_same_surface(rebuild(mesh), mesh)


def test_parallel_edges_on_a_handle_round_trip() -> None:
    rng = random.Random(7)
    mesh = cube()
    # a merging insert between two faces makes a handle (genus 1)
    mesh.insert_edge(mesh.face_corners(0)[0], mesh.face_corners(1)[0])
    mesh = stack_parallel_edges(mesh, rng, [(0, 4), (0, 1)], 20)
    assert component_genera(mesh) == [1]
    assert_same_surface(rebuild(mesh), mesh)


def manifold_pairing_exists(faces: list[list[int]], num_vertices: int) -> bool:
    """Brute force for a closed soup: some pairing of each edge's sides leaves
    every vertex one ring of corners (independent of the builder)."""
    corners = [(f, i) for f, face in enumerate(faces) for i in range(len(face))]
    index = {c: k for k, c in enumerate(corners)}
    nxt = [index[(f, (i + 1) % len(faces[f]))] for f, i in corners]
    vert = [faces[f][i] for f, i in corners]
    groups: dict[tuple[int, int], tuple[list[int], list[int]]] = {}
    for k in range(len(corners)):
        u, w = vert[k], vert[nxt[k]]
        groups.setdefault((min(u, w), max(u, w)), ([], []))[u > w].append(k)
    if any(len(fwd) != len(back) for fwd, back in groups.values()):
        return False
    per_group = [[(fwd, perm) for perm in itertools.permutations(back)]
                 for fwd, back in groups.values()]
    for choice in itertools.product(*per_group):
        mate = [0] * len(corners)
        for fwd, back in choice:
            for f, b in zip(fwd, back, strict=True):
                mate[f], mate[b] = b, f
        if all(ring_is_one_cycle(v, vert, nxt, mate) for v in range(num_vertices)):
            return True
    return False


def ring_is_one_cycle(v: int, vert: list[int], nxt: list[int], mate: list[int]) -> bool:
    at = [k for k in range(len(vert)) if vert[k] == v]
    x, length = nxt[mate[at[0]]], 1
    while x != at[0]:
        x, length = nxt[mate[x]], length + 1
    return length == len(at)


def builds(faces: list[list[int]], num_vertices: int) -> bool:
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            validate(from_polygons(np.eye(max(num_vertices, 3))[:num_vertices], faces))
    except DLFLError:
        return False
    return True


def random_closed_soup(rng: random.Random) -> list[list[int]]:
    """2-gons and triangles on vertices 0, 1, 2, each edge used as often both ways:
    parallel edges on all three vertex pairs, sharing vertices."""
    pool = [[0, 1], [1, 2], [0, 2], [0, 1, 2], [0, 2, 1]]
    faces = [rng.choice(pool) for _ in range(rng.randint(2, 6))]
    surplus = faces.count([0, 1, 2]) - faces.count([0, 2, 1])
    return faces + [[0, 2, 1]] * max(surplus, 0) + [[0, 1, 2]] * max(-surplus, 0)


def test_from_polygons_builds_exactly_the_soups_a_brute_force_can_pair() -> None:
    rng = random.Random(3)
    seen = [0, 0]
    for _ in range(120):
        faces = random_closed_soup(rng)
        if {v for f in faces for v in f} != {0, 1, 2} or len(faces) > 7:
            continue
        expected = manifold_pairing_exists(faces, 3)
        assert builds(faces, 3) == expected, faces
        seen[expected] += 1
    assert min(seen) >= 10  # both answers were exercised


def test_a_soup_that_cannot_be_paired_is_refused_by_name() -> None:
    faces = [[0, 1, 2], [0, 1, 2], [0, 2, 1], [0, 2, 1]]
    assert not manifold_pairing_exists(faces, 3)
    with pytest.raises(NonManifoldError, match=r"^polygons: vertices 0 and 1 are joined by 2 edges "
                       r"that cannot be arranged into a manifold$"):
        from_polygons(np.eye(3), faces)


# -- 2. insert_edge between a face and a hole: a hole, whatever the order --------------


def face_and_hole(mesh: Mesh) -> tuple[int, int]:
    face, hole = sorted(mesh.face_ids().tolist(), key=mesh.is_hole)
    assert not mesh.is_hole(face) and mesh.is_hole(hole)
    return face, hole


@pytest.mark.parametrize("hole_first", [False, True])
def test_inserting_between_a_face_and_a_hole_gives_a_hole(hole_first: bool) -> None:
    m = triangle()
    face, hole = face_and_hole(m)
    c_face, c_hole = m.face_corners(face)[0], m.face_corners(hole)[0]
    args = (c_hole, c_face) if hole_first else (c_face, c_hole)
    e = m.insert_edge(*args)
    validate(m)
    assert m.counts() == (3, 4, 1)
    (merged,) = m.face_ids().tolist()
    assert merged == (hole if hole_first else face)  # the first corner's face survives
    assert m.is_hole(merged)
    # deleting the edge splits the hole; both parts keep its flag, as delete_edge says
    assert m.delete_edge(e, cleanup=False) == [merged, m.face_ids().tolist()[-1]]
    validate(m)
    assert m.counts() == (3, 3, 2)
    assert [m.is_hole(f) for f in m.face_ids().tolist()] == [True, True]


def test_inserting_between_two_faces_gives_a_face() -> None:
    m = cube()
    m.insert_edge(m.face_corners(0)[0], m.face_corners(1)[0])
    validate(m)
    assert not any(m.is_hole(f) for f in m.face_ids().tolist())


# -- 3. messages for ids below a bulk build's first id; matching_edges vectorized ------


def test_an_id_below_the_first_id_of_a_build_is_not_called_deleted() -> None:
    m = from_polygons(TETRA_POSITIONS, [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
                      first_ids=(5, 7, 9, 11))
    with pytest.raises(UnknownIdError, match=r"^vertex 2 was deleted or never existed \(this mesh "
                       r"was built with vertex ids from 5\)$"):
        m.position(2)
    with pytest.raises(UnknownIdError, match=r"^face 0 was deleted or never existed"):
        m.face_size(0)
    with pytest.raises(UnknownIdError, match=r"^vertex 9 does not exist$"):
        m.position(9)
    e = m.edge_ids().tolist()[0]
    m.delete_edge(e, cleanup=False)
    with pytest.raises(UnknownIdError, match=rf"^edge {e} was deleted$"):
        m.edge_vertices(e)
    copy = m.copy()
    with pytest.raises(UnknownIdError, match=r"^vertex 4 was deleted or never existed"):
        copy.position(4)


def test_ids_of_a_mesh_built_from_zero_keep_their_messages() -> None:
    m = cube()
    m.delete_edge(3, cleanup=False)
    with pytest.raises(UnknownIdError, match=r"^edge 3 was deleted$"):
        m.edge_vertices(3)
    with pytest.raises(UnknownIdError, match=r"^edge 12 does not exist$"):
        m.edge_vertices(12)


def matching_edges_one_by_one(mesh: Mesh, edge: int) -> list[int]:
    """The former per-edge implementation of selection.matching_edges."""
    from livemod.dlfl.selection import vertex_valences

    valence = vertex_valences(mesh)
    u, w = mesh.edge_vertices(edge)
    key = sorted((valence[u], valence[w]))
    return [e for e in mesh.edge_ids().tolist()
            if sorted(valence[v] for v in mesh.edge_vertices(e)) == key]


def meshes_for_matching() -> list[Mesh]:
    odd = cube()
    odd.insert_edge(odd.face_corners(0)[0], odd.face_corners(0)[2])  # valences 4 and 4
    odd.delete_edge(5, cleanup=False)  # a gap in the edge ids
    stacked = stack_parallel_edges(tetrahedron(), random.Random(1), [(1, 2), (0, 3)], 12)
    built = from_polygons(TETRA_POSITIONS, REPRO_FACES, first_ids=(3, 4, 5, 6))
    looped = path_face()  # its face visits vertex 1 twice: joining those corners is a loop
    twice = [c for c in looped.face_corners(0) if looped.corner_vertex(c) == 1]
    looped.insert_edge(*twice)
    ends = mesh_arrays(looped).edge_vertices
    assert (ends[:, 0] == ends[:, 1]).any()
    return [cube(), torus(5, 4), odd, stacked, built, triangle(), looped]


def test_matching_edges_gives_what_the_per_edge_version_gave() -> None:
    from livemod.dlfl.selection import matching_edges

    for mesh in meshes_for_matching():
        for e in mesh.edge_ids().tolist():
            assert matching_edges(mesh, e) == matching_edges_one_by_one(mesh, e)


def test_matching_edges_of_a_deleted_edge_says_so() -> None:
    from livemod.dlfl.selection import matching_edges

    m = cube()
    m.delete_edge(0, cleanup=False)
    with pytest.raises(UnknownIdError, match=r"^edge 0 was deleted$"):
        matching_edges(m, 0)
    with pytest.raises(UnknownIdError, match=r"^edge 40 does not exist$"):
        matching_edges(m, 40)
