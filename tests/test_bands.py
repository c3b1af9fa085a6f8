"""Tests of livemod.dlfl.bands: the quad and triangle bands between two faces."""

from __future__ import annotations

from livemod.dlfl import genus, validate
from livemod.dlfl.bands import edges_since, quad_band, triangle_band
from tests.meshes import cube, euler_ok

BOTTOM_CORNER, TOP_CORNER = 0, 4  # corners of cube faces 0 and 1, both at vertex 0 / 4


def test_a_quad_band_joins_two_squares_with_a_ring_of_four_quads():
    m = cube()
    first = m.next_ids()[1]
    quad_band(m, BOTTOM_CORNER, TOP_CORNER)
    validate(m)
    assert euler_ok(m)
    assert m.counts() == (8, 16, 8) and genus(m) == 1
    new = edges_since(m, first)
    assert new == [12, 13, 14, 15]
    ring = {f for e in new for f in m.edge_faces(e)}
    assert sorted(m.face_size(f) for f in ring) == [4, 4, 4, 4]


def test_a_triangle_band_joins_two_squares_with_eight_triangles():
    m = cube()
    first = m.next_ids()[1]
    triangle_band(m, BOTTOM_CORNER, TOP_CORNER)
    validate(m)
    assert m.counts() == (8, 20, 12) and genus(m) == 1
    new = edges_since(m, first)
    assert len(new) == 8
    ring = {f for e in new for f in m.edge_faces(e)}
    assert sorted(m.face_size(f) for f in ring) == [3] * 8


def test_a_quad_band_between_a_square_and_a_pentagon_ends_in_a_triangle():
    m = cube()
    m.subdivide_edge(m.face_edges(1)[0])  # the top (and one side) become pentagons
    first = m.next_ids()[1]
    quad_band(m, BOTTOM_CORNER, TOP_CORNER)
    validate(m)
    assert m.counts() == (9, 18, 9) and genus(m) == 1
    # the merged 11-gon loses two corners a quad: four quads leave a triangle
    ring = {f for e in edges_since(m, first) for f in m.edge_faces(e)}
    assert sorted(m.face_size(f) for f in ring) == [3, 4, 4, 4, 4]


def test_edges_since_lists_only_the_new_edges_still_live():
    m = cube()
    first = m.next_ids()[1]
    assert edges_since(m, first) == []
    a, b = m.insert_edge(0, 2), m.insert_edge(4, 6)
    assert edges_since(m, first) == [a, b]
    m.delete_edge(a)
    assert edges_since(m, first) == [b]
