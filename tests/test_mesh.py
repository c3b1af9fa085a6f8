"""Tests of livemod.dlfl.mesh: the minimal operators with TopMod's exact counts."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import DLFLError, Mesh, from_polygons, genus, num_components, validate
from livemod.dlfl.errors import InvalidArgumentError, UnknownIdError
from tests.meshes import (
    TETRA_POSITIONS,
    assert_refused,
    checked,
    corner_structure,
    cube,
    path_face,
    snapshot,
    tetrahedron,
    three_point_spheres,
    torus,
    triangle,
)

# -- insert_edge ---------------------------------------------------------------

def test_cube_diagonal_insert_splits_the_face():
    m = cube()
    e = m.insert_edge(0, 2)
    assert checked(m) == (8, 13, 7)
    assert genus(m) == 0
    assert m.edge_corners(e) == (0, 2)
    assert sorted(m.face_size(f) for f in m.edge_faces(e)) == [3, 3]


def test_cofacial_insert_keeps_corner1_and_corners_after_corner2():
    m = cube()
    face = m.corner_face(0)
    m.insert_edge(0, 2)
    assert m.corner_face(0) == face and m.corner_face(3) == face
    new = m.corner_face(1)
    assert new != face and m.corner_face(2) == new
    assert m.face_vertices(new)[1:] == [1, 2] or sorted(m.face_vertices(new)) == [0, 2, 3]


def test_insert_edge_far_corners_are_new_copies():
    m = cube()
    before = set(m.corner_ids().tolist())
    e = m.insert_edge(0, 2)
    c0, c1 = m.edge_corners(e)
    after0, after1 = m.corner_next(c0), m.corner_next(c1)
    assert {after0, after1}.isdisjoint(before)
    assert m.corner_vertex(after0) == m.corner_vertex(c1)
    assert m.corner_vertex(after1) == m.corner_vertex(c0)


def test_top_to_bottom_corner_insert_adds_a_handle():
    m = cube()
    e = m.insert_edge(0, 4)  # bottom face at vertex 0, top face at vertex 4
    assert checked(m) == (8, 13, 5)
    assert genus(m) == 1
    assert m.edge_faces(e)[0] == m.edge_faces(e)[1]
    assert m.face_size(m.edge_faces(e)[0]) == 10


def test_merged_face_visits_a_vertex_twice_and_corner_at_is_ambiguous():
    m = cube()
    e = m.insert_edge(0, 4)
    face = m.edge_faces(e)[0]
    assert m.face_vertices(face).count(0) == 2
    at_zero = [c for c in m.face_corners(face) if m.corner_vertex(c) == 0]
    with pytest.raises(InvalidArgumentError) as info:
        m.corner_at(face, 0)
    message = str(info.value)
    assert "ambiguous" in message
    assert all(str(c) in message for c in at_zero)


def test_adjacent_corner_insert_gives_a_two_gon():
    m = cube()
    e = m.insert_edge(0, 1)
    assert checked(m) == (8, 13, 7)
    assert sorted(m.face_size(f) for f in m.edge_faces(e)) == [2, 4]


def test_self_loop_inside_a_face():
    m2 = path_face()
    # face [0, 1, 2, 1] has two corners at vertex 1: joining them is a self-loop
    c1, c3 = 1, 3
    e2 = m2.insert_edge(c1, c3)
    assert checked(m2) == (3, 3, 2)
    v0, v1 = m2.edge_vertices(e2)
    assert v0 == v1 == 1
    assert m2.valence(1) == 4
    assert m2.delete_edge(e2) and checked(m2) == (3, 2, 1)


def test_three_point_spheres_make_a_triangle():
    m, (p1, p2, p3) = three_point_spheres()
    assert checked(m) == (3, 0, 3)
    e1 = m.insert_edge(m.vertex_corner(p1), m.vertex_corner(p2))
    assert checked(m) == (3, 1, 2)
    assert m.face_size(m.edge_faces(e1)[0]) == 2
    m.insert_edge(m.vertex_corner(p3), m.vertex_corner(p2))
    assert checked(m) == (3, 2, 1)
    (face,) = {m.corner_face(c) for c in m.vertex_corners(p2)}
    assert sorted(m.face_vertices(face)) == sorted([p1, p2, p2, p3])
    m.insert_edge(m.corner_at(face, p3), m.corner_at(face, p1))
    assert checked(m) == (3, 3, 2)
    assert sorted(m.face_size(f) for f in m.face_ids().tolist()) == [3, 3]


def test_two_point_spheres_joined_then_deleted_with_cleanup():
    m, (p1, p2, _) = three_point_spheres()
    m.remove_vertex(_)
    e = m.insert_edge(m.vertex_corner(p1), m.vertex_corner(p2))
    assert checked(m) == (2, 1, 1)
    assert m.delete_edge(e) == []
    assert checked(m) == (0, 0, 0)


def test_two_point_spheres_joined_then_deleted_without_cleanup():
    m, (p1, p2, p3) = three_point_spheres()
    m.remove_vertex(p3)
    e = m.insert_edge(m.vertex_corner(p1), m.vertex_corner(p2))
    faces = m.delete_edge(e, cleanup=False)
    assert checked(m) == (2, 0, 2)
    assert len(faces) == 2
    assert m.is_point_sphere(p1) and m.is_point_sphere(p2)


def test_insert_between_components_joins_them():
    from tests.meshes import two_cubes

    m = two_cubes()
    assert num_components(m) == 2
    m.insert_edge(0, 24)  # a corner of each cube
    assert checked(m) == (16, 25, 11)
    assert num_components(m) == 1 and genus(m) == 0


def test_point_sphere_joined_to_a_cube_corner():
    m = cube()
    p = m.create_vertex((2.0, 2.0, 2.0))
    assert checked(m) == (9, 12, 7)
    e = m.insert_edge(m.vertex_corner(p), 0)
    assert checked(m) == (9, 13, 6)
    assert m.valence(p) == 1
    assert m.face_size(m.edge_faces(e)[0]) == 6


def test_insert_same_corner_twice_is_refused():
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="corner 3 twice"):
        m.insert_edge(3, 3)
    assert snapshot(m) == before


# -- delete_edge ---------------------------------------------------------------

def test_delete_a_cube_edge_merges_two_faces():
    m = cube()
    e = m.corner_edge(0)
    faces = m.delete_edge(e)
    assert checked(m) == (8, 11, 5)
    assert len(faces) == 1 and m.face_size(faces[0]) == 6


@pytest.mark.parametrize(("make", "c1", "c2"), [
    (cube, 0, 2), (cube, 0, 1), (cube, 2, 0), (tetrahedron, 0, 2), (path_face, 1, 3),
])
def test_cofacial_insert_then_delete_restores_every_id(make, c1, c2):
    m = make()
    before = snapshot(m)[:-1]
    m.delete_edge(m.insert_edge(c1, c2))
    validate(m)
    assert snapshot(m)[:-1] == before


@pytest.mark.parametrize(("make", "c1", "c2"), [(cube, 0, 4), (tetrahedron, 0, 3), (torus, 0, 5)])
def test_merging_insert_then_delete_restores_all_but_the_face_id(make, c1, c2):
    m = make()
    before = corner_structure(m)
    faces = m.face_ids().tolist()
    m.delete_edge(m.insert_edge(c1, c2))
    validate(m)
    assert corner_structure(m) == before
    assert len(set(m.face_ids().tolist()) - set(faces)) == 1


def test_delete_edge_splitting_a_face_gives_two_faces():
    m = cube()
    e = m.insert_edge(0, 4)
    faces = m.delete_edge(e)
    assert checked(m) == (8, 12, 6) and genus(m) == 0
    assert sorted(m.face_size(f) for f in faces) == [4, 4]


def test_delete_dangling_edge_with_and_without_cleanup():
    for cleanup, expected in ((True, (8, 12, 6)), (False, (9, 12, 7))):
        m = cube()
        p = m.create_vertex((2.0, 2.0, 2.0))
        e = m.insert_edge(m.vertex_corner(p), 0)
        m.delete_edge(e, cleanup=cleanup)
        assert checked(m) == expected
        assert m.has_vertex(p) is not cleanup


def test_delete_edge_of_a_two_gon():
    m = cube()
    e = m.insert_edge(0, 1)
    faces = m.delete_edge(e)
    assert checked(m) == (8, 12, 6) and len(faces) == 1


def test_delete_cube_edges_until_a_tree_remains():
    m = cube()
    # keep deleting edges between different faces: the faces merge into one
    while m.num_faces > 1:
        e = next(e for e in m.edge_ids().tolist() if len(set(m.edge_faces(e))) == 2)
        m.delete_edge(e)
        checked(m)
    assert m.counts() == (8, 7, 1)
    # now every edge has the one face on both sides: deleting a leaf edge drops a vertex
    while m.num_edges:
        m.delete_edge(int(m.edge_ids()[0]))
        checked(m)
    assert m.counts() == (0, 0, 0)


# -- subdivide_edge --------------------------------------------------------------

def test_subdivide_cube_edge():
    m = cube()
    e = m.corner_edge(0)
    (v,) = m.subdivide_edge(e)
    assert checked(m) == (9, 13, 6)
    a, b = m.edge_vertices(e)
    assert a == 0 and b == v
    np.testing.assert_allclose(m.position(v), [0.0, 0.5, 0.0])


def test_subdivide_edge_in_n_divisions_places_points_evenly():
    m = cube()
    e = m.corner_edge(0)  # vertex 0 -> vertex 3
    p0, p1 = m.position(0), m.position(3)
    new = m.subdivide_edge(e, 4)
    assert checked(m) == (11, 15, 6)
    assert len(new) == 3
    for i, v in enumerate(new, start=1):
        np.testing.assert_allclose(m.position(v), p0 + (p1 - p0) * i / 4)
    assert m.face_size(m.corner_face(0)) == 7


def test_subdivide_edge_one_division_is_a_no_op():
    m = cube()
    before = snapshot(m)
    assert m.subdivide_edge(m.corner_edge(0), 1) == []
    assert snapshot(m) == before


@pytest.mark.parametrize("bad", [0, -2, 2.5, "3", True])
def test_subdivide_edge_refuses_bad_divisions(bad):
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="divisions"):
        m.subdivide_edge(m.corner_edge(0), bad)
    assert snapshot(m) == before


def test_subdivide_a_self_loop():
    m = path_face()
    e = m.insert_edge(1, 3)
    (v,) = m.subdivide_edge(e)
    assert checked(m) == (4, 4, 2)
    assert m.valence(v) == 2


# -- collapse_edge ---------------------------------------------------------------

def test_collapse_a_cube_edge():
    m = cube()
    e = m.corner_edge(0)  # vertex 0 -> vertex 3
    survivor = m.collapse_edge(e)
    assert checked(m) == (7, 11, 6)
    assert survivor == 0 and not m.has_vertex(3)
    np.testing.assert_allclose(m.position(0), [0.0, 0.5, 0.0])
    assert sorted(m.face_size(f) for f in m.face_ids().tolist()) == [3, 3, 4, 4, 4, 4]


def test_collapse_a_tetrahedron_edge_cleans_up_two_gons():
    m = tetrahedron()
    m.collapse_edge(m.corner_edge(0))
    assert checked(m) == (3, 3, 2)
    assert sorted(m.face_size(f) for f in m.face_ids().tolist()) == [3, 3]


def test_collapse_without_cleanup_keeps_two_gons():
    m = tetrahedron()
    m.collapse_edge(m.corner_edge(0), cleanup=False)
    assert checked(m) == (3, 5, 4)
    assert sorted(m.face_size(f) for f in m.face_ids().tolist()) == [2, 2, 3, 3]


def test_collapse_a_self_loop_deletes_it():
    m = path_face()
    e = m.insert_edge(1, 3)
    assert m.collapse_edge(e) == 1
    assert checked(m) == (3, 2, 1)


def test_collapse_the_edge_of_two_joined_point_spheres():
    m, (p1, p2, p3) = three_point_spheres()
    e = m.insert_edge(m.vertex_corner(p1), m.vertex_corner(p2))
    v = m.collapse_edge(e)
    assert checked(m) == (2, 0, 2)
    np.testing.assert_allclose(m.position(v), [0.5, 0.0, 0.0])
    assert m.is_point_sphere(v) and m.has_vertex(p3)


def test_collapse_a_dangling_edge():
    m = cube()
    p = m.create_vertex((0.0, 0.0, 2.0))
    e = m.insert_edge(m.vertex_corner(p), 0)
    v = m.collapse_edge(e)
    assert checked(m) == (8, 12, 6)
    assert v == 0 and not m.has_vertex(p)
    np.testing.assert_allclose(m.position(0), [0.0, 0.0, 1.0])


def test_collapse_all_edges_of_a_triangle():
    m = triangle()
    m.collapse_edge(m.corner_edge(0))
    assert checked(m) == (2, 1, 1)
    m.collapse_edge(int(m.edge_ids()[0]))
    assert checked(m) == (1, 0, 1)


# -- create_vertex / remove_vertex / create_face -------------------------------

def test_create_and_remove_a_point_sphere():
    m = cube()
    v = m.create_vertex([1, 2, 3])
    assert checked(m) == (9, 12, 7)
    assert m.is_point_sphere(v) and m.valence(v) == 0
    assert m.face_size(m.corner_face(m.vertex_corner(v))) == 1
    m.remove_vertex(v)
    assert checked(m) == (8, 12, 6)


def test_remove_vertex_with_edges_is_refused():
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="vertex 0 has 3 edge end"):
        m.remove_vertex(0)
    assert snapshot(m) == before


def test_create_face_makes_a_two_sided_polygon():
    m = Mesh()
    front, back = m.create_face([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)])
    assert checked(m) == (4, 4, 2)
    vs = m.face_vertices(front)
    assert m.face_vertices(back) == [vs[0], *vs[:0:-1]]
    assert m.create_face([(0, 0, 1), (1, 0, 1)]) and checked(m) == (6, 6, 4)


@pytest.mark.parametrize("points", [
    [], [(0, 0, 0)], [(0, 0), (1, 1)], [(0, 0, 0), "abc"], 5, "abc", None,
])
def test_create_face_refuses_bad_points(points):
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError):
        m.create_face(points)
    assert snapshot(m) == before


def test_one_gon_from_a_soup():
    from livemod.dlfl import from_polygons

    m = from_polygons([[0, 0, 0], [1, 0, 0]], [[0], [1]])
    assert checked(m) == (2, 0, 2)
    assert m.is_point_sphere(0) and m.is_point_sphere(1)


# -- ids and bad input ---------------------------------------------------------

def test_ids_are_never_reused():
    m = cube()
    seen = {kind: set(ids.tolist()) for kind, ids in (
        ("e", m.edge_ids()), ("f", m.face_ids()), ("c", m.corner_ids()), ("v", m.vertex_ids()))}
    for _ in range(20):
        e = m.insert_edge(0, 2)
        assert e not in seen["e"]
        seen["e"].add(e)
        for f in m.edge_faces(e):
            seen["f"].add(f)
        m.delete_edge(e)
        v = m.create_vertex()
        assert v not in seen["v"]
        seen["v"].add(v)
        m.remove_vertex(v)
    validate(m)


def test_deleted_ids_raise_naming_them():
    m = cube()
    e = m.corner_edge(0)
    m.delete_edge(e)
    with pytest.raises(UnknownIdError, match=f"edge {e} was deleted"):
        m.delete_edge(e)
    with pytest.raises(UnknownIdError, match="edge 99 does not exist"):
        m.edge_corners(99)
    v = m.create_vertex()
    m.remove_vertex(v)
    with pytest.raises(UnknownIdError, match=f"vertex {v} was deleted"):
        m.position(v)
    with pytest.raises(UnknownIdError, match="face 999 does not exist"):
        m.face_corners(999)
    with pytest.raises(UnknownIdError, match="corner -1 does not exist"):
        m.corner_next(-1)


def test_a_deleted_id_is_a_lookup_error():
    m = cube()
    e, v = m.corner_edge(0), m.create_vertex()
    m.delete_edge(e)
    m.remove_vertex(v)
    for call, message in [(lambda: m.edge_corners(e), f"^edge {e} was deleted$"),
                          (lambda: m.position(v), f"^vertex {v} was deleted$"),
                          (lambda: m.positions(np.array([0, v])), f"^vertex {v} was deleted$"),
                          (lambda: m.face_points(99), "^face 99 does not exist$")]:
        with pytest.raises(LookupError, match=message) as info:
            call()
        assert type(info.value) is UnknownIdError and isinstance(info.value, DLFLError)


@pytest.mark.parametrize("bad", [1.0, "2", None, (0, 1), True, [3]])
def test_wrong_kind_of_argument_is_refused(bad):
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="expected a corner id"):
        m.insert_edge(bad, 2)
    with pytest.raises(InvalidArgumentError, match="expected a edge id|expected an edge id"):
        m.delete_edge(bad)
    with pytest.raises(InvalidArgumentError, match="expected a vertex id"):
        m.remove_vertex(bad)
    assert snapshot(m) == before


def test_numpy_integers_are_accepted_as_ids():
    m = cube()
    first, second, third = np.array([0, 2, 12])  # numpy scalars, as from id arrays
    e = m.insert_edge(first, second)
    assert e == third
    assert m.delete_edge(third) == [0]
    validate(m)


def test_failing_operators_leave_the_mesh_unchanged():
    m = torus()
    e = m.insert_edge(0, 2)
    dead = m.corner_edge(1)
    m.delete_edge(dead)
    before = snapshot(m)
    attempts = [
        (lambda: m.insert_edge(0, 10_000), UnknownIdError),
        (lambda: m.insert_edge(1, 1), InvalidArgumentError),
        (lambda: m.delete_edge(dead), UnknownIdError),
        (lambda: m.collapse_edge(dead), UnknownIdError),
        (lambda: m.subdivide_edge(dead, 3), UnknownIdError),
        (lambda: m.subdivide_edge(e, 0), InvalidArgumentError),
        (lambda: m.remove_vertex(0), InvalidArgumentError),
        (lambda: m.create_vertex((1, 2)), InvalidArgumentError),
        (lambda: m.create_face([(0, 0, 0)]), InvalidArgumentError),
        (lambda: m.set_position(0, (1, 2, "x")), InvalidArgumentError),
        (lambda: m.corner_at(0, 11), UnknownIdError),
    ]
    for attempt, error in attempts:
        with pytest.raises(error):
            attempt()
        assert snapshot(m) == before


def test_memory_does_not_grow_with_history():
    m = cube()
    caps = [t.capacity for t in (m._c, m._e, m._f, m._v)]
    for _ in range(100_000):
        m.delete_edge(m.insert_edge(0, 2))
    validate(m)
    # a table grows at most once (doubling) to make room for the transient elements
    tables = (m._c, m._e, m._f, m._v)
    assert all(t.capacity <= max(2 * c, 16) for t, c in zip(tables, caps, strict=True))
    # slots ever used: the two corner copies, the edge and the face of one insert
    assert [t.n for t in tables] == [26, 13, 7, 8]
    assert all(len(t.moved) <= t.count for t in (m._c, m._e, m._f, m._v))
    assert m.next_ids()[1] == 12 + 100_000


# -- queries -------------------------------------------------------------------

def test_vertex_rotation_queries():
    m = cube()
    assert m.valence(0) == 3
    assert sorted(m.vertex_faces(0)) == [0, 2, 5]
    assert len(m.vertex_edges(0)) == 3
    for c in m.vertex_corners(0):
        assert m.corner_vertex(m.corner_vnext(c)) == 0
    assert m.corner_at(0, 3) == 1


def test_corner_walk_queries():
    m = cube()
    assert m.face_corners(0) == [0, 1, 2, 3]
    assert m.face_vertices(1) == [4, 5, 6, 7]
    assert [m.corner_next(c) for c in range(4)] == [1, 2, 3, 0]
    assert [m.corner_prev(c) for c in range(4)] == [3, 0, 1, 2]
    assert len(m.face_edges(0)) == 4
    assert m.face_corner(2) == 8


def test_hole_flags():
    m = triangle()
    holes = [f for f in m.face_ids().tolist() if m.is_hole(f)]
    assert len(holes) == 1
    m.set_hole(holes[0], False)
    assert not m.is_hole(holes[0])
    # splitting a hole gives two holes
    hole = m.corner_face(m.edge_corners(m.corner_edge(0))[1])
    m.set_hole(hole)
    ring = m.face_corners(hole)
    e = m.insert_edge(ring[0], ring[1])
    assert all(m.is_hole(f) for f in m.edge_faces(e))


def test_deleting_an_edge_between_a_face_and_a_hole_opens_the_face():
    from livemod.dlfl import from_polygons
    from tests.meshes import CUBE_FACES, CUBE_POSITIONS

    box = from_polygons(CUBE_POSITIONS, CUBE_FACES[:-1])  # one side open: a hole face
    hole = next(f for f in box.face_ids().tolist() if box.is_hole(f))
    for edge in box.face_edges(hole):  # sides in either order: the hole may be c0 or c1
        m = box.copy()
        (merged,) = m.delete_edge(edge)
        validate(m)
        assert m.is_hole(merged) and m.face_size(merged) == 6
        assert sum(not m.is_hole(f) for f in m.face_ids().tolist()) == 4
    m = box.copy()  # two surface faces merge into a surface face
    inner = next(e for e in m.edge_ids().tolist()
                 if not any(m.is_hole(f) for f in m.edge_faces(e)))
    (merged,) = m.delete_edge(inner)
    assert not m.is_hole(merged)


# -- one-corner faces (regressions found by the property tests) ------------------

def two_one_gons_on_a_loop() -> Mesh:
    """A triangle collapsed twice without cleanup: one vertex, one loop, two 1-gons."""
    m = triangle()
    m.collapse_edge(m.corner_edge(0), cleanup=False)
    m.collapse_edge(int(m.edge_ids()[0]), cleanup=False)
    return m


def test_collapse_without_cleanup_leaves_one_gons_on_a_loop():
    m = two_one_gons_on_a_loop()
    assert checked(m) == (1, 1, 2)
    assert [m.face_size(f) for f in m.face_ids().tolist()] == [1, 1]
    v = int(m.vertex_ids()[0])
    assert m.valence(v) == 2 and not m.is_point_sphere(v)


def test_merging_insert_copies_a_one_gon_corner_that_has_a_loop():
    m = two_one_gons_on_a_loop()
    c1, c2 = (m.face_corners(f)[0] for f in m.face_ids().tolist())
    e = m.insert_edge(c1, c2)
    assert checked(m) == (1, 2, 1)
    assert m.face_size(m.edge_faces(e)[0]) == 4
    m.delete_edge(e)
    assert checked(m) == (1, 1, 2)


def test_collapsing_the_last_loop_keeps_its_vertex():
    m = two_one_gons_on_a_loop()
    v = m.collapse_edge(int(m.edge_ids()[0]))  # cleanup on: the vertex still survives
    assert checked(m) == (1, 0, 1) and m.is_point_sphere(v)
    m2 = triangle()
    m2.collapse_edge(m2.corner_edge(0), cleanup=False)
    v2 = m2.collapse_edge(int(m2.edge_ids()[0]), cleanup=True)
    assert checked(m2) == (1, 0, 1) and m2.has_vertex(v2)


def test_deleting_the_loop_between_two_one_gons():
    for cleanup, expected in ((False, (1, 0, 1)), (True, (0, 0, 0))):
        m = two_one_gons_on_a_loop()
        m.delete_edge(int(m.edge_ids()[0]), cleanup)
        assert checked(m) == expected


def test_split_delete_keeps_both_side_corners():
    m = cube()
    e = m.insert_edge(0, 4)  # merges two faces; the copies sit after the sides
    c0, c1 = m.edge_corners(e)
    faces = m.delete_edge(e)
    assert m.corner_face(c0) == faces[0] and m.corner_face(c1) == faces[1]
    assert sorted(m.corner_ids().tolist()) == list(range(24))


BIG = 1.7e308  # the sum or difference of two such coordinates is past the float range


def test_collapse_between_far_out_ends_stays_finite():
    m = Mesh()
    m.create_face([(BIG, 0, 0), (BIG, BIG, 0), (0, -BIG, 0)])
    edge = int(m.edge_ids()[0])
    survivor = m.collapse_edge(edge)
    checked(m)
    np.testing.assert_allclose(m.position(survivor), (BIG, BIG / 2, 0))


def test_subdivide_between_far_out_ends_stays_finite():
    m = Mesh()
    m.create_face([(-BIG, BIG, 0), (BIG, -BIG, 0)])
    new = m.subdivide_edge(int(m.edge_ids()[0]), 4)
    checked(m)
    np.testing.assert_allclose([m.position(v)[0] for v in new], [-BIG / 2, 0, BIG / 2])


def test_subdividing_into_more_parts_than_a_mesh_holds_is_refused():
    assert_refused(cube(), lambda m: m.subdivide_edge(0, 2**30),
                   "divisions=1073741824 would make at least 2,147,483,648 corners",
                   error=InvalidArgumentError)
    assert_refused(cube(), lambda m: m.subdivide_edge(0, 0), "divisions must be an integer >= 1",
                   error=InvalidArgumentError)


# -- bulk accessors ----------------------------------------------------------------

def test_face_points_follow_the_ring_from_the_head():
    m = cube()
    for face in m.face_ids().tolist():
        expected = [m.position(v) for v in m.face_vertices(face)]
        np.testing.assert_array_equal(m.face_points(face), expected)
    m.insert_edge(0, 2)  # the new face's ring starts at a copied corner
    face = m.corner_face(1)
    np.testing.assert_array_equal(m.face_points(face),
                                  m.positions(m.face_vertices(face)))
    with pytest.raises(UnknownIdError, match="^face 99 does not exist$"):
        m.face_points(99)


def test_face_points_repeat_a_vertex_the_face_visits_twice():
    m = path_face()  # vertices 0, 1, 2, 1 at x = 0, 1, 2
    face = int(m.face_ids()[0])
    assert m.face_vertices(face) == [0, 1, 2, 1]
    assert m.face_points(face)[:, 0].tolist() == [0, 1, 2, 1]


# -- face colours --------------------------------------------------------------

RED, BLUE = (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)


def test_a_split_face_gives_its_colour_to_the_new_face():
    m = cube()
    m.set_face_color(0, RED)
    e = m.insert_edge(0, 2)
    new = [f for f in m.edge_faces(e) if f != 0]
    assert len(new) == 1 and m.face_color(new[0]) == RED
    checked(m)
    assert m.delete_edge(e) == [0]  # merged back into the coloured face
    assert m.face_color(0) == RED and np.isnan(m.face_colors()[1:]).all()


def test_deleting_an_edge_with_one_face_on_both_sides_colours_both_parts():
    m = cube()
    e = m.insert_edge(0, 4)  # faces 0 and 1 merge into face 0: a handle
    m.set_face_color(0, RED)
    parts = m.delete_edge(e)
    assert len(parts) == 2 and [m.face_color(f) for f in parts] == [RED, RED]
    checked(m)


def test_a_merge_keeps_the_first_face_colour_or_else_the_second():
    m = cube()
    m.set_face_color(1, BLUE)
    # corner 0 is in face 0 (no colour), corner 4 in face 1 (blue): a handle merge
    m.insert_edge(0, 4)
    assert m.face_color(0) == BLUE
    m2 = cube()
    m2.set_face_color(0, RED)
    m2.set_face_color(1, BLUE)
    m2.insert_edge(0, 4)
    assert m2.face_color(0) == RED
    checked(m2)


def red_face_by(route: str) -> tuple[Mesh, int]:
    """A cube whose face 0 is red, the colour come by ``route``; the mesh, the face."""
    from livemod.dlfl import mesh_arrays
    from livemod.dlfl.build import from_corner_arrays
    from livemod.dlfl.subdivision import subdivide

    painted = cube()
    painted.set_face_color(0, RED)
    if route == "set_face_color":
        return painted, 0
    if route == "copy":
        return painted.copy(), 0
    if route == "a rebuild in place":
        subdivide(painted, "catmull-clark")  # face 0's four children are red
        return painted, next(f for f in painted.face_ids().tolist() if painted.face_color(f))
    a = mesh_arrays(cube())
    colors = np.full((6, 3), np.nan, np.float32)
    colors[0] = RED
    return from_corner_arrays(a.positions, a.face_offsets, a.corner_vertex, a.corner_mate,
                              face_colors=colors), 0


@pytest.mark.parametrize("route", ["set_face_color", "copy", "a rebuild in place",
                                   "from_corner_arrays"])
def test_a_split_and_its_undoing_keep_colours_however_they_came(route):
    # the operators skip colour work on a mesh that never had a colour: every
    # way a colour arrives must tell them it has
    m, face = red_face_by(route)  # the merge below takes the red face's colour
    ring = m.face_corners(face)
    e = m.insert_edge(ring[0], ring[2])
    assert [m.face_color(f) for f in m.edge_faces(e)] == [RED, RED]
    checked(m)
    m.delete_edge(e)
    handle = m.insert_edge(m.face_corner(face), m.face_corner(m.corner_face(
        m.corner_vnext(m.face_corner(face)))))  # faces merge: a handle
    parts = m.delete_edge(handle)  # one face on both sides: it splits again
    assert len(parts) == 2 and [m.face_color(f) for f in parts] == [RED, RED]
    checked(m)


def test_new_faces_of_create_vertex_and_create_face_have_no_colour_in_reused_slots():
    m = cube()
    m.set_face_color(0, RED)
    m.insert_edge(0, 2)
    e = m.edge_ids()[-1]
    m.delete_edge(int(e))  # frees the coloured new face's slot
    v = m.create_vertex((5, 5, 5))
    assert m.face_color(m.corner_face(m.vertex_corner(v))) is None
    front, back = m.create_face([(0, 0, 3), (1, 0, 3), (0, 1, 3)])
    assert m.face_color(front) is None and m.face_color(back) is None


# -- insert_edge between a face and a hole gives a hole, whatever the order


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


# -- unknown ids: messages for ids below a bulk build's first id


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


# -- arguments of the wrong type: a string is no position, no hole flag


@pytest.mark.parametrize("text", ["123", b"123", bytearray(b"123")])
def test_a_string_is_not_a_position(text):
    # "123" unpacked into the point (1, 2, 3) and b"123" into (49, 50, 51)
    assert_refused(Mesh(), lambda m: m.create_vertex(text), "expected a position",
                   error=InvalidArgumentError)
    assert_refused(cube(), lambda m: m.set_position(0, text), "expected a position",
                   error=InvalidArgumentError)
    assert_refused(Mesh(), lambda m: m.create_face([text, (0, 0, 0)]), "expected a position",
                   error=InvalidArgumentError)


