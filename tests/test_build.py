"""Tests of livemod.dlfl.build: the polygon-soup builder and the trusted fast path."""

from __future__ import annotations

import itertools
import random
import warnings

import numpy as np
import pytest

from livemod.dlfl import (
    DLFLError,
    DLFLRepairWarning,
    Mesh,
    from_corner_arrays,
    from_polygons,
    genus,
    mesh_arrays,
    num_components,
    validate,
)
from livemod.dlfl.analysis import component_genera, enclosed_volume
from livemod.dlfl.build import join_meshes
from livemod.dlfl.errors import InvalidArgumentError, NonManifoldError
from tests.meshes import (
    CUBE_FACES,
    CUBE_POSITIONS,
    PARALLEL_EDGE_SOUP,
    TETRA_POSITIONS,
    canonical,
    cube,
    euler_ok,
    stack_parallel_edges,
    tetrahedron,
    torus_polygons,
)

SQUARE = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]


def built(positions, faces, **kwargs):
    mesh = from_polygons(positions, faces, **kwargs)
    validate(mesh)
    assert euler_ok(mesh)
    return mesh


def test_closed_cube_keeps_soup_order_for_ids():
    m = built(CUBE_POSITIONS, CUBE_FACES)
    assert m.counts() == (8, 12, 6)
    assert [m.face_vertices(f) for f in range(6)] == CUBE_FACES
    assert m.face_corners(2) == [8, 9, 10, 11]
    assert not any(m.is_hole(f) for f in range(6))
    np.testing.assert_allclose(m.position(6), [1, 1, 1])


@pytest.mark.parametrize(("n", "m"), [(3, 3), (4, 7), (40, 25)])
def test_quad_torus_from_an_array(n, m):
    pos, quads = torus_polygons(n, m)
    mesh = built(pos, quads)
    assert mesh.counts() == (n * m, 2 * n * m, n * m)
    assert genus(mesh) == 1


def test_flat_indices_with_offsets():
    m = built(SQUARE + [[0.5, 0.5, 1]], [0, 1, 2, 3, 1, 0, 4], offsets=[0, 4, 7])
    assert [m.face_size(f) for f in m.face_ids().tolist() if not m.is_hole(f)] == [4, 3]


def test_first_ids_offset_every_kind():
    m = built(CUBE_POSITIONS, CUBE_FACES, first_ids=(10, 20, 30, 40))
    assert m.vertex_ids()[0] == 10 and m.edge_ids()[0] == 20
    assert m.face_ids()[0] == 30 and m.corner_ids()[0] == 40
    assert m.next_ids() == (18, 32, 36, 64)


def test_open_square_gets_one_flagged_hole():
    m = built(SQUARE, [[0, 1, 2, 3]])
    assert m.counts() == (4, 4, 2)
    assert [m.is_hole(f) for f in m.face_ids().tolist()] == [False, True]
    assert m.face_vertices(int(m.face_ids()[1])) == [1, 0, 3, 2]


def test_open_cylinder_gets_two_holes():
    faces = CUBE_FACES[2:]  # the four sides of the cube
    m = built(CUBE_POSITIONS, faces)
    holes = [f for f in m.face_ids().tolist() if m.is_hole(f)]
    assert len(holes) == 2 and all(m.face_size(f) == 4 for f in holes)
    assert m.counts() == (8, 12, 6)


def test_unused_vertices_become_point_spheres():
    m = built(SQUARE + [[5, 5, 5], [6, 6, 6]], [[0, 1, 2, 3]])
    assert m.counts() == (6, 4, 4)
    assert m.is_point_sphere(4) and m.is_point_sphere(5)
    assert num_components(m) == 3


def test_one_corner_faces_are_point_spheres():
    m = built([[0, 0, 0]], [[0]])
    assert m.counts() == (1, 0, 1) and m.is_point_sphere(0)


def test_two_gons_pair_with_one_fan_per_vertex():
    # two triangles with two 2-gons between them: four sides use the pair {0, 1}
    # in each direction, and the pairing must leave one fan at every vertex
    m = built([[0, 0, 1], [0, 0, -1], [1, 0, 0]], [[0, 1, 2], [1, 0], [0, 1], [1, 0, 2]])
    assert m.counts() == (3, 5, 4)
    assert component_genera(m) == [0]
    assert sorted(m.valence(v) for v in range(3)) == [2, 4, 4]


def test_three_two_gons_make_a_beach_ball():
    m = built([[0, 0, 1], [0, 0, -1]], [[0, 1], [0, 1], [0, 1]])
    assert m.counts() == (2, 3, 3)
    assert m.valence(0) == 3 and m.valence(1) == 3


def test_two_gon_pair_is_a_sphere():
    m = built([[0, 0, 1], [0, 0, -1]], [[0, 1], [1, 0]])
    assert m.counts() == (2, 2, 2) and genus(m) == 0


def test_edge_used_by_three_faces_is_refused_naming_them():
    pos = SQUARE + [[0.5, 0.5, 1], [0.5, 0.5, -1]]
    faces = [[0, 1, 4], [1, 0, 5], [0, 1, 2]]
    with pytest.raises(NonManifoldError) as info:
        from_polygons(pos, faces)
    message = str(info.value)
    assert "edge (0, 1)" in message and "3 face sides" in message
    assert "face 0" in message and "face 1" in message and "face 2" in message


def test_error_names_source_and_lines():
    pos = SQUARE + [[0.5, 0.5, 1], [0.5, 0.5, -1]]
    faces = [[0, 1, 4], [1, 0, 5], [0, 1, 2]]
    with pytest.raises(NonManifoldError, match=r"^model\.obj:12: .*line 12, line 13, line 15"):
        from_polygons(pos, faces, source="model.obj", face_lines=[12, 13, 15])


def test_bow_tie_vertex_is_refused():
    pos = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [-1, 0, 0], [-1, -1, 0]]
    with pytest.raises(NonManifoldError, match="vertex 0 is non-manifold"):
        from_polygons(pos, [[0, 1, 2], [0, 3, 4]])


def test_closed_bow_tie_of_two_tetrahedra_is_refused():
    tet = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]
    other = [[v if v == 0 else v + 3 for v in f] for f in tet]
    pos = np.random.default_rng(1).normal(size=(7, 3))
    with pytest.raises(NonManifoldError, match="vertex 0 is non-manifold.*2 separate fans"):
        from_polygons(pos, tet + other)


def test_inconsistent_orientation_is_repaired_with_a_note():
    faces = [list(f) for f in CUBE_FACES]
    faces[3] = faces[3][::-1]
    with pytest.warns(DLFLRepairWarning, match="re-oriented 1 faces"):
        m = from_polygons(CUBE_POSITIONS, faces)
    validate(m)
    assert m.counts() == (8, 12, 6)
    assert len(m.notes) == 1 and "face 3" in m.notes[0]
    assert m.face_vertices(0) == CUBE_FACES[0]


def test_moebius_band_is_refused():
    n = 5
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
    inner = np.stack([np.cos(angles), np.sin(angles), np.zeros(n)], axis=1) * 2
    pos = np.concatenate([inner, inner * 1.5])
    quads = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n - 1)]
    quads.append([n - 1, n, 0, 2 * n - 1])  # the half twist
    with pytest.raises(NonManifoldError, match="not orientable"):
        from_polygons(pos, quads)


@pytest.mark.parametrize(("faces", "pattern"), [
    ([[0, 1, 7]], "uses vertex index 7, but there are 4 vertices"),
    ([[0, 1, -1]], "uses vertex index -1"),
    ([[0, 1, 1, 2]], "visits vertex 1 twice in a row"),
])
def test_bad_indices_are_refused(faces, pattern):
    with pytest.raises(InvalidArgumentError, match=pattern):
        from_polygons(SQUARE, faces)


def test_empty_face_and_bad_positions_are_refused():
    with pytest.raises(InvalidArgumentError, match="face 0 has no vertices"):
        from_polygons(SQUARE, [0, 1, 2], offsets=[0, 0, 3])
    with pytest.raises(InvalidArgumentError, match="vertex 2 has a position that is not finite"):
        from_polygons([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]], [[0, 1, 2]])


def test_empty_soup_gives_an_empty_mesh():
    m = from_polygons(np.zeros((0, 3)), [])
    validate(m)
    assert m.counts() == (0, 0, 0)


def test_from_corner_arrays_round_trips_mesh_arrays():
    pos, quads = torus_polygons(5, 4)
    a = mesh_arrays(from_polygons(pos, quads))
    m = from_corner_arrays(a.positions, a.face_offsets, a.corner_vertex, a.corner_mate,
                           a.face_hole)
    validate(m)
    b = mesh_arrays(m)
    assert np.array_equal(a.corner_vertex, b.corner_vertex)
    assert np.array_equal(a.corner_mate, b.corner_mate)
    assert component_genera(m) == [1]


def test_two_multi_edge_groups_sharing_a_vertex():
    # regression (found by the property tests): a tetrahedron with one edge
    # collapsed, no cleanup; two vertex pairs are each joined by two edges and
    # pairing one group must not be judged before the other is paired
    m = built([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 2, 1], [0, 1], [1, 2], [0, 1, 2]])
    assert m.counts() == (3, 5, 4)
    assert [m.valence(v) for v in range(3)] == [3, 4, 3]


def test_mesh_does_not_alias_the_input_positions():
    positions = np.array(SQUARE, dtype=np.float64)
    m = built(positions, [[0, 1, 2, 3]])
    m.set_position(0, (5.0, 5.0, 5.0))
    positions[1] = (9.0, 9.0, 9.0)
    assert positions[0].tolist() == [0, 0, 0]
    assert m.position(1).tolist() == [1, 0, 0]


def test_bow_tie_error_names_the_file_line():
    pos = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [-1, 0, 0], [-1, -1, 0]]
    with pytest.raises(NonManifoldError, match=r"^shape\.obj:7: vertex 0 is non-manifold"):
        from_polygons(pos, [[0, 1, 2], [0, 3, 4]], source="shape.obj", face_lines=[7, 9])


def test_moebius_error_names_the_file_line():
    n = 5
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
    inner = np.stack([np.cos(angles), np.sin(angles), np.zeros(n)], axis=1) * 2
    quads = [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n - 1)]
    quads.append([n - 1, n, 0, 2 * n - 1])
    lines = [20 + i for i in range(n)]
    with pytest.raises(NonManifoldError, match=r"^band\.obj:2\d: line 2\d cannot be oriented"):
        from_polygons(np.concatenate([inner, inner * 1.5]), quads, source="band.obj",
                      face_lines=lines)


def test_many_flipped_faces_are_all_restored():
    pos, quads = torus_polygons(12, 9)
    rng = np.random.default_rng(7)
    flipped = rng.random(len(quads)) < 0.5
    assert 2 * flipped.sum() < len(quads)  # the majority keeps its orientation
    soup = quads.copy()
    soup[flipped] = np.concatenate([soup[flipped][:, :1], soup[flipped][:, :0:-1]], axis=1)
    with pytest.warns(DLFLRepairWarning, match=f"re-oriented {int(flipped.sum())} faces"):
        repaired = from_polygons(pos, soup)
    validate(repaired)
    expected = mesh_arrays(from_polygons(pos, quads))
    assert np.array_equal(mesh_arrays(repaired).corner_vertex, expected.corner_vertex)
    assert np.array_equal(mesh_arrays(repaired).corner_mate, expected.corner_mate)


def test_a_flipped_first_face_is_the_one_turned_round():
    faces = [list(f) for f in CUBE_FACES]
    faces[0] = faces[0][::-1]  # an exporter got the first face wrong
    with pytest.warns(DLFLRepairWarning, match=r"re-oriented 1 faces \(face 0\)"):
        m = from_polygons(CUBE_POSITIONS, faces)
    validate(m)
    ring = m.face_vertices(0)  # the cube's own face, from the file's first corner
    assert ring == CUBE_FACES[0][3:] + CUBE_FACES[0][:3] and enclosed_volume(m) == 1.0


def test_a_tie_keeps_the_first_face_of_the_component():
    faces = [list(f) for f in CUBE_FACES]
    for f in (1, 2, 3):
        faces[f] = faces[f][::-1]
    with pytest.warns(DLFLRepairWarning, match=r"re-oriented 3 faces \(face 1, face 2, face 3\)"):
        m = from_polygons(CUBE_POSITIONS, faces)
    assert m.face_vertices(0) == CUBE_FACES[0]


def test_each_component_keeps_the_orientation_of_most_of_its_faces():
    faces = [list(f) for f in CUBE_FACES] + [[v + 8 for v in f[::-1]] for f in CUBE_FACES]
    faces[7] = [v + 8 for v in CUBE_FACES[1]]  # one face of the second cube disagrees
    pos = np.concatenate([CUBE_POSITIONS, CUBE_POSITIONS + 3])
    with pytest.warns(DLFLRepairWarning, match="re-oriented 1 faces \\(face 7\\)"):
        m = from_polygons(pos, faces)
    validate(m)
    assert m.face_vertices(6) == [v + 8 for v in CUBE_FACES[0][::-1]]


@pytest.mark.parametrize("lunes", [2, 3, 7, 11])
def test_a_bouquet_of_two_gons_between_two_vertices_builds_a_sphere(lunes: int) -> None:
    # every side pairs with every opposite side, so the pairing must be searched
    # side by side: seven lunes once ran out of tries before finding the cycle
    m = from_polygons([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]], [[0, 1]] * (lunes - 1) + [[1, 0]])
    validate(m)
    assert m.counts() == (2, lunes, lunes) and genus(m) == 0
    assert sorted(len(m.vertex_corners(v)) for v in m.vertex_ids().tolist()) == [lunes, lunes]


def test_join_meshes_keeps_each_mesh_as_a_component_holes_included():

    box = from_polygons(CUBE_POSITIONS, CUBE_FACES[1:])  # open: its top is a hole
    ring = from_polygons(*torus_polygons(5, 3))
    joined = join_meshes([box, ring, box])
    validate(joined)
    assert joined.counts() == tuple(2 * a + b for a, b in zip(box.counts(), ring.counts(),
                                                             strict=True))
    assert sorted(component_genera(joined)) == [0, 0, 1]
    assert sum(joined.is_hole(int(f)) for f in joined.face_ids()) == 2
    assert join_meshes([]).counts() == (0, 0, 0)


def test_from_corner_arrays_takes_face_colours_with_nan_for_none():
    a = mesh_arrays(cube())
    colors = np.full((6, 3), np.nan, np.float32)
    colors[5] = (0.25, 0.5, 1.0)
    m = from_corner_arrays(a.positions, a.face_offsets, a.corner_vertex, a.corner_mate,
                           face_colors=colors)
    validate(m)
    assert m.face_color(5) == (0.25, 0.5, 1.0)
    assert [m.face_color(f) for f in range(5)] == [None] * 5


def test_joined_meshes_keep_their_colours():
    first, second = cube(), cube((3.0, 0.0, 0.0))
    second.set_face_color(1, (0.0, 0.0, 1.0))
    joined = join_meshes([first, second])
    validate(joined)
    assert joined.face_color(7) == (0.0, 0.0, 1.0)
    assert sum(joined.face_color(f) is not None for f in joined.face_ids().tolist()) == 1


# -- from_polygons pairs parallel sides whenever a manifold pairing exists


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


def test_a_soup_with_ten_parallel_edges_builds() -> None:
    mesh = from_polygons(TETRA_POSITIONS, PARALLEL_EDGE_SOUP)
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
