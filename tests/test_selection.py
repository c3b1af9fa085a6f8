"""Selection helpers: by size, valence, normal, predicate, area; matching; loops and rings."""

from __future__ import annotations

import random
import warnings
from collections import Counter

import pytest

from livemod.dlfl import DLFLError, Mesh, from_polygons, mesh_arrays
from livemod.dlfl.errors import InvalidArgumentError, UnknownIdError
from livemod.dlfl.selection import (
    KINDS,
    checkerboard,
    edge_loop,
    edge_ring,
    face_loop,
    faces_by_area,
    faces_by_normal,
    faces_by_size,
    faces_by_vertex_valence,
    faces_where,
    grow,
    invert,
    matching_edges,
    matching_faces,
    matching_vertices,
    select_all,
    shrink,
    similar_faces,
    vertex_valences,
)
from livemod.dlfl.shapes import cube, genus3_hexa, grid, soccer_ball, torus
from livemod.dlfl.subdivision import catmull_clark
from tests.meshes import (
    PARALLEL_EDGE_SOUP,
    TETRA_POSITIONS,
    assert_refused,
    path_face,
    stack_parallel_edges,
    triangle,
)
from tests.meshes import cube as unit_cube
from tests.meshes import tetrahedron as unit_tetrahedron
from tests.meshes import torus as unit_torus


def test_faces_by_size_on_the_soccer_ball():
    m = soccer_ball()
    assert len(faces_by_size(m, 5)) == 12
    assert len(faces_by_size(m, 6)) == 20
    assert len(faces_by_size(m, [5, 6])) == 32
    assert faces_by_size(m, 3) == []


def test_faces_by_size_leaves_holes_out():
    g = grid(2, 2)
    assert len(faces_by_size(g, 8)) == 0 and len(faces_by_size(g, 4)) == 4


def test_faces_by_vertex_valence():
    m = genus3_hexa(1)
    assert len(faces_by_vertex_valence(m, 3)) < 82
    touching_4 = faces_by_vertex_valence(m, 4, every=False)
    assert 0 < len(touching_4) <= 11 * 4
    assert faces_by_vertex_valence(cube(), 3) == list(range(6))


def test_faces_by_normal():
    c = cube()
    assert faces_by_normal(c, (0, 1, 0)) == [0]
    assert faces_by_normal(c, (0, -5, 0)) == [5]
    assert faces_by_normal(c, (1, 1, 0), max_angle=46) == [0, 1]
    with pytest.raises(InvalidArgumentError):
        faces_by_normal(c, (0, 0, 0))


def test_faces_where_a_predicate_holds():
    c = cube()
    assert faces_where(c, lambda f: f % 2 == 0) == [0, 2, 4]


def test_matching_faces_edges_vertices():
    m = soccer_ball()
    pent = faces_by_size(m, 5)[0]
    assert len(matching_faces(m, pent)) == 12
    assert len(matching_vertices(m, int(m.vertex_ids()[0]))) == 60
    assert len(matching_edges(m, int(m.edge_ids()[0]))) == 90
    assert vertex_valences(cube()) == {v: 3 for v in range(8)}


def test_faces_by_area():
    c = cube()
    assert faces_by_area(c, 0) == list(range(6))
    c.set_position(0, (2, 2, 2))
    assert 0 not in faces_by_area(c, 5, delta=0.01)
    with pytest.raises(UnknownIdError):
        faces_by_area(c, 99)


def test_checkerboard_on_a_grid_and_a_torus():
    g = grid(4, 4)
    picked = checkerboard(g, int(g.face_ids()[0]))
    assert len(picked) == 8
    t = torus(8, 6)
    assert len(checkerboard(t, 0)) == 24
    with pytest.raises(UnknownIdError):
        checkerboard(t, 999)


def test_edge_loops_rings_and_face_loops_on_a_torus():
    t = torus(8, 6)
    # edge 0 runs around the 6-sided tube; edge 1 around the 8 rings
    lengths = sorted((len(edge_loop(t, e)), len(edge_ring(t, e)), len(face_loop(t, e)))
                     for e in (0, 1))
    assert lengths == [(6, 8, 8), (8, 6, 6)]


def test_loops_stop_at_other_valences_and_rings_at_other_sizes():
    c = cube()
    assert edge_loop(c, 0) == [0]
    ring = edge_ring(c, 0)
    assert len(ring) == 4 and len(face_loop(c, 0)) == 4
    g = grid(4, 1)
    assert len(edge_ring(g, int(g.edge_ids()[0]))) == 5


def quad_sphere():
    """The cube after one Catmull-Clark step: 26/48/24 quads, 8 vertices of
    valence 3 (the cube's corners) and 18 of valence 4."""
    m = cube()
    catmull_clark(m)
    return m


def test_loops_and_rings_on_a_quad_sphere():
    m = quad_sphere()
    valence = vertex_valences(m)
    found = Counter()
    for e in m.edge_ids().tolist():
        ends = tuple(sorted(valence[v] for v in m.edge_vertices(e)))
        found[ends, len(edge_loop(m, e)), len(edge_ring(m, e)), len(face_loop(m, e))] += 1
    # a loop from a face centre closes round the cube through 4 faces (8 edges);
    # one from a corner (valence 3) stops at the next corner, 2 edges on; every
    # ring and face loop circles a band of 8 quads
    assert found == {((4, 4), 8, 8, 8): 24, ((3, 4), 2, 8, 8): 24}


def test_a_closed_loop_is_the_same_from_every_edge_of_it():
    m = quad_sphere()
    edge = next(e for e in m.edge_ids().tolist() if len(edge_loop(m, e)) == 8)
    loop = edge_loop(m, edge)
    assert all(sorted(edge_loop(m, e)) == sorted(loop) for e in loop)
    assert len(set(loop)) == 8


def test_checkerboard_spreads_over_a_quad_sphere():
    # faces across a cube edge share just its midpoint: the rule reaches all 24
    m = quad_sphere()
    assert checkerboard(m, int(m.face_ids()[0])) == m.face_ids().tolist()
    assert checkerboard(cube(), 0) == [0]  # the cube's faces share edges or nothing


@pytest.mark.parametrize(("make", "counts"), [
    # faces grown once and twice from the first face, twice then shrunk; edges grown
    # from the first edge, vertices from the first vertex
    (cube, (5, 6, 6, 5, 4)),
    (lambda: torus(8, 6), (5, 13, 5, 7, 5)),
    (quad_sphere, (5, 12, 5, 6, 4)),  # its first face, edge and vertex touch a valence 3
])
def test_grow_and_shrink_count_exactly(make, counts):
    m = make()
    face, edge, vertex = (int(ids[0]) for ids in (m.face_ids(), m.edge_ids(), m.vertex_ids()))
    once = grow(m, [face])
    twice = grow(m, once)
    assert (len(once), len(twice), len(shrink(m, twice)), len(grow(m, [edge], "edges")),
            len(grow(m, [vertex], "vertices"))) == counts
    assert shrink(m, once) == [face]
    assert shrink(m, select_all(m)) == select_all(m)


def test_grow_and_shrink_follow_topmods_neighbours():
    t = torus(8, 6)
    once = grow(t, [0])
    assert once == sorted({0, *(f for e in t.face_edges(0) for f in t.edge_faces(e))})
    edges = grow(t, [0], "edges")
    assert edges == sorted({e for v in t.edge_vertices(0) for e in t.vertex_edges(v)})
    assert shrink(t, once) == [0] and shrink(t, [0]) == []


def test_select_all_and_invert_count_every_kind():
    t = torus(8, 6)
    assert [len(select_all(t, kind)) for kind in KINDS] == [48, 96, 48, 192]
    assert len(invert(t, [0, 1, 999])) == 46
    assert invert(t, select_all(t, "verts"), "vertices") == []
    g = grid(2, 2)  # its hole face is never selected
    assert len(select_all(g)) == 4 and len(invert(g, [])) == 4


def test_similar_faces_by_size_area_and_colour():
    m = soccer_ball()
    pentagon = faces_by_size(m, 5)[0]
    assert len(similar_faces(m, pentagon)) == 12
    assert similar_faces(m, pentagon, "area", 1e-9) == faces_by_size(m, 5)
    for face in faces_by_size(m, 5)[:3]:
        m.set_face_color(face, (0.5, 0.25, 1.0))
    m.set_face_color(faces_by_size(m, 5)[3], (0.5, 0.25, 0.9))
    assert similar_faces(m, pentagon, "colour") == faces_by_size(m, 5)[:3]
    assert similar_faces(m, pentagon, "color", 0.2) == faces_by_size(m, 5)[:4]
    uncoloured = similar_faces(m, faces_by_size(m, 6)[0], "colour")
    assert len(uncoloured) == m.num_faces - 4
    with pytest.raises(InvalidArgumentError, match="not 'shade'"):
        similar_faces(m, pentagon, "shade")


@pytest.mark.parametrize("rule", [
    lambda m, a: edge_loop(a, 5), lambda m, a: edge_ring(a, 5), lambda m, a: face_loop(a, 5),
    lambda m, a: checkerboard(a, 3), lambda m, a: matching_edges(a, 5),
    lambda m, a: matching_vertices(a, 3), lambda m, a: matching_faces(a, 3),
    lambda m, a: grow(a, [3]), lambda m, a: shrink(a, [3, 4]), lambda m, a: invert(a, [3]),
])
def test_a_mesh_and_its_arrays_give_the_same_selection(rule):
    m = torus(8, 6)
    assert rule(m, m) == rule(m, mesh_arrays(m))


@pytest.mark.parametrize(("call", "error", "message"), [
    (lambda a: edge_loop(a, 999), UnknownIdError, "edge 999 does not exist"),
    (lambda a: checkerboard(a, 1.5), InvalidArgumentError, "expected a face id"),
    (lambda a: grow(a, [0], "corners"), InvalidArgumentError, "corners neither grow"),
    (lambda a: select_all(a, "loops"), InvalidArgumentError, "kind must be one of"),
    (lambda a: invert(a, "0"), DLFLError, "ids"),
])
def test_bad_selections_are_refused_on_arrays(call, error, message):
    with pytest.raises(error, match=message):
        call(mesh_arrays(cube()))


def test_faces_of_infinite_area_match_each_other_without_a_warning():
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * 1e200)  # areas overflow to inf
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert faces_by_area(m, 0) == list(range(6))


# -- matching_edges: the vectorized version gives what the per-edge one gave


def matching_edges_one_by_one(mesh: Mesh, edge: int) -> list[int]:
    """The former per-edge implementation of selection.matching_edges."""
    valence = vertex_valences(mesh)
    u, w = mesh.edge_vertices(edge)
    key = sorted((valence[u], valence[w]))
    return [e for e in mesh.edge_ids().tolist()
            if sorted(valence[v] for v in mesh.edge_vertices(e)) == key]


def meshes_for_matching() -> list[Mesh]:
    odd = unit_cube()
    odd.insert_edge(odd.face_corners(0)[0], odd.face_corners(0)[2])  # valences 4 and 4
    odd.delete_edge(5, cleanup=False)  # a gap in the edge ids
    stacked = stack_parallel_edges(unit_tetrahedron(), random.Random(1), [(1, 2), (0, 3)], 12)
    built = from_polygons(TETRA_POSITIONS, PARALLEL_EDGE_SOUP, first_ids=(3, 4, 5, 6))
    looped = path_face()  # its face visits vertex 1 twice: joining those corners is a loop
    twice = [c for c in looped.face_corners(0) if looped.corner_vertex(c) == 1]
    looped.insert_edge(*twice)
    ends = mesh_arrays(looped).edge_vertices
    assert (ends[:, 0] == ends[:, 1]).any()
    return [unit_cube(), unit_torus(5, 4), odd, stacked, built, triangle(), looped]


def test_matching_edges_gives_what_the_per_edge_version_gave() -> None:
    for mesh in meshes_for_matching():
        for e in mesh.edge_ids().tolist():
            assert matching_edges(mesh, e) == matching_edges_one_by_one(mesh, e)


def test_matching_edges_of_a_deleted_edge_says_so() -> None:
    m = unit_cube()
    m.delete_edge(0, cleanup=False)
    with pytest.raises(UnknownIdError, match=r"^edge 0 was deleted$"):
        matching_edges(m, 0)
    with pytest.raises(UnknownIdError, match=r"^edge 40 does not exist$"):
        matching_edges(m, 40)


# -- bad arguments and deleted faces are refused by name; huge directions work


@pytest.mark.parametrize(("call", "message"), [
    (lambda m: faces_by_normal(m, "abc"), "direction must be three finite numbers"),
    (lambda m: faces_by_normal(m, (1, 0)), "direction must be three finite numbers"),
    (lambda m: faces_by_normal(m, (0, 0, float("nan"))), "direction must be three finite"),
    (lambda m: faces_by_normal(m, (0, 0, 0)), "direction must not be zero"),
    (lambda m: faces_by_normal(m, (1, 0, 0), "x"), "max_angle must be a number"),
    (lambda m: faces_by_area(m, 0, "x"), "delta must be a number"),
    (lambda m: faces_by_area(m, 1.0), "expected a face id"),
    (lambda m: checkerboard(m, 1.0), "expected a face id"),
])
def test_selection_refuses_bad_arguments(call, message):
    assert_refused(unit_cube(), call, message, error=InvalidArgumentError)


def test_selection_of_a_deleted_face_says_it_was_deleted():
    m = unit_cube()
    m.delete_edge(0)  # the second face of edge 0 goes
    gone = next(f for f in range(6) if not m.has_face(f))
    for call in (faces_by_area, checkerboard):
        assert_refused(m, lambda m, call=call: call(m, gone), f"face {gone} was deleted",
                       error=UnknownIdError)


def test_faces_by_normal_takes_a_huge_direction():
    # the norm of (1e308, 1e308, 0) overflows unless scaled first
    assert faces_by_normal(unit_cube(), (1e308, 0, 0)) == faces_by_normal(unit_cube(), (1, 0, 0))
