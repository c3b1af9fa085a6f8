"""Selection helpers: by size, valence, normal, predicate, area; matching; loops and rings."""

from __future__ import annotations

import pytest

from livemod.dlfl.errors import InvalidArgumentError, UnknownIdError
from livemod.dlfl.selection import (
    checkerboard,
    edge_loop,
    edge_ring,
    face_loop,
    faces_by_area,
    faces_by_normal,
    faces_by_size,
    faces_by_vertex_valence,
    faces_where,
    matching_edges,
    matching_faces,
    matching_vertices,
    vertex_valences,
)
from livemod.dlfl.shapes import cube, genus3_hexa, grid, soccer_ball, torus


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
