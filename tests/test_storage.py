"""Tests of livemod.dlfl._storage: a mesh's tables, counts, ids and each element's
own row (positions, hole flags, colours), through the Mesh built on them."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import DLFLError, Mesh, validate
from livemod.dlfl._storage import MeshStorage
from livemod.dlfl.errors import InvalidArgumentError, UnknownIdError
from tests.meshes import assert_refused, checked, cube, three_point_spheres, triangle

RED, BLUE = (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)


class TaggedMesh(Mesh):
    """A subclass, as a user might make one: whole-mesh constructors keep it."""


def test_copies_and_adopted_tables_keep_the_class_they_are_made_from():
    tagged = TaggedMesh.from_tables(**two_gon_tables(back_is_hole=False))
    assert type(tagged) is TaggedMesh and type(tagged.copy()) is TaggedMesh
    assert type(cube().copy()) is Mesh and isinstance(tagged, MeshStorage)
    assert checked(tagged.copy()) == (2, 2, 2)


# -- ids -----------------------------------------------------------------------


def test_has_queries_answer_false_for_junk():
    m = cube()
    assert m.has_face(0) and m.has_corner(np.int64(23)) and m.has_vertex(7) and m.has_edge(11)
    for junk in (None, "x", 1.5, (1, 2), [1], -5, 10**9, True, object()):
        assert not (m.has_face(junk) or m.has_edge(junk) or m.has_vertex(junk)
                    or m.has_corner(junk))


def test_copy_is_deep_and_keeps_ids():
    m = cube()
    c = m.copy()
    m.insert_edge(0, 2)
    assert c.counts() == (8, 12, 6)
    validate(c)
    assert c.next_ids() == (8, 12, 6, 24)
    e = c.insert_edge(0, 2)
    assert e == 12
    validate(c)


# -- positions -----------------------------------------------------------------


def test_counts_leave_out_the_free_slots_of_each_table_until_reused():
    m = cube()
    m.delete_edge(m.insert_edge(0, 2))  # frees one edge and one face slot
    e = m.insert_edge(0, 2)
    m.delete_edge(e)
    m.delete_edge(0)  # cube faces 0 and the one across edge 0 merge
    validate(m)
    live = (len(m.vertex_ids()), len(m.edge_ids()), len(m.face_ids()))
    assert m.counts() == live == (8, 11, 5)
    m.insert_edge(0, 2)  # reuses a freed edge slot and a freed face slot
    validate(m)
    assert m.counts() == (len(m.vertex_ids()), len(m.edge_ids()), len(m.face_ids())) == (8, 12, 6)


def test_set_positions_checks_shape():
    m = cube()
    m.set_positions([0, 1], [[9, 9, 9], [8, 8, 8]])
    np.testing.assert_allclose(m.position(1), [8, 8, 8])
    m.set_positions([2, 3], (1, 1, 1))
    np.testing.assert_allclose(m.position(3), [1, 1, 1])
    with pytest.raises(InvalidArgumentError, match="shape"):
        m.set_positions([0, 1], [[1, 2, 3]])
    with pytest.raises(InvalidArgumentError, match="positions must be numbers"):
        m.set_positions([0], ["a", "b", "c"])
    with pytest.raises(InvalidArgumentError, match="sequence of vertex ids"):
        m.set_positions(3, (1, 1, 1))


def test_positions_of_ids_follow_their_order_from_a_list_or_an_array():
    m = cube()
    m.set_positions([5, 2], [[5, 5, 5], [2, 2, 2]])
    for ids in ([5, 2, 5], np.array([5, 2, 5]), np.array([5, 2, 5], dtype=np.int32)):
        got = m.positions(ids)
        assert got.shape == (3, 3) and got.dtype == np.float64
        np.testing.assert_array_equal(got, [[5, 5, 5], [2, 2, 2], [5, 5, 5]])
    got[0] = 0  # a copy: the mesh does not move
    np.testing.assert_array_equal(m.position(5), [5, 5, 5])
    assert m.positions([]).shape == (0, 3)
    assert m.positions(np.array([], dtype=np.int64)).shape == (0, 3)


def test_positions_find_ids_in_reused_slots():
    m, vertices = three_point_spheres()
    m.remove_vertex(vertices[1])
    fresh = m.create_vertex((7.0, 8.0, 9.0))  # lands in the freed slot: a moved id
    np.testing.assert_array_equal(m.positions(np.array([fresh, vertices[2]])),
                                  [[7, 8, 9], [2, 0, 0]])


@pytest.mark.parametrize("ids", [[0, 99, 98], np.array([0, 99, 98])])
def test_positions_name_the_first_id_that_is_not_a_vertex(ids):
    m = cube()
    with pytest.raises(UnknownIdError, match="^vertex 99 does not exist$"):
        m.positions(ids)


@pytest.mark.parametrize("big", [2**63, 2**64 - 1])
def test_positions_name_an_unsigned_id_past_int64_as_it_is(big):
    # a cast to int64 would wrap it to a negative id and name that one
    m = cube()
    with pytest.raises(UnknownIdError, match=f"^vertex {big} does not exist$"):
        m.positions(np.array([0, big], dtype=np.uint64))
    np.testing.assert_array_equal(m.positions(np.array([3, 0], dtype=np.uint64)),
                                  m.positions([3, 0]))


def test_positions_name_a_deleted_vertex_and_refuse_non_integers():
    m, vertices = three_point_spheres()
    m.remove_vertex(vertices[0])
    with pytest.raises(UnknownIdError, match=f"^vertex {vertices[0]} was deleted$"):
        m.positions(np.array(vertices))
    with pytest.raises(InvalidArgumentError, match=r"expected a vertex id \(an integer\), got 1.0"):
        m.positions([vertices[1], 1.0])


# -- holes and colours ---------------------------------------------------------


def test_hole_mask_follows_face_ids():
    m = triangle()
    mask = m.hole_mask()
    assert mask.dtype == bool and mask.shape == (m.num_faces,)
    assert mask.tolist() == [m.is_hole(f) for f in m.face_ids().tolist()]
    assert mask.sum() == 1
    m.set_hole(int(m.face_ids()[0]))
    assert m.hole_mask().sum() == 2
    assert Mesh().hole_mask().shape == (0,)


def test_set_hole_refuses_a_string_flag():
    # "False" is truthy: the face became a hole
    assert_refused(cube(), lambda m: m.set_hole(0, "False"), "hole must be True or False",
                   error=InvalidArgumentError)
    m = cube()
    m.set_hole(0, 1)
    assert m.is_hole(0)
    m.set_hole(0, False)
    assert not m.is_hole(0)


def test_a_face_has_no_colour_until_given_one():
    m = cube()
    assert m.face_color(0) is None
    assert m.face_colors() is None
    m.set_face_color(0, (1, 0.5, 0.25))
    assert m.face_color(0) == (1.0, 0.5, 0.25)
    colors = m.face_colors()
    assert colors is not None and colors.shape == (6, 3) and colors.dtype == np.float32
    assert colors[0].tolist() == [1.0, 0.5, 0.25]
    assert np.isnan(colors[1:]).all()
    m.set_face_color(0, None)
    assert m.face_color(0) is None and m.face_colors() is None


@pytest.mark.parametrize("bad", [(1, 0), (1, 0, 0, 1), "red", None.__class__, (255, 0, 0),
                                 (-0.1, 0, 0), (float("nan"), 0, 0), (True, 0, 0), 5])
def test_a_bad_colour_is_refused_and_changes_nothing(bad):
    m = cube()
    m.set_face_color(1, BLUE)
    assert_refused(m, lambda mesh: mesh.set_face_color(1, bad), "colour must be", DLFLError)
    assert m.face_color(1) == BLUE


def test_a_dead_face_has_no_colour_to_set():
    m = cube()
    with pytest.raises(DLFLError, match="face 99 does not exist"):
        m.set_face_color(99, RED)
    with pytest.raises(DLFLError, match="face 99 does not exist"):
        m.face_color(99)


def test_copies_carry_the_colours_and_stay_apart():
    m = cube()
    m.set_face_color(3, RED)
    other = m.copy()
    assert other.face_color(3) == RED
    other.set_face_color(3, BLUE)
    assert m.face_color(3) == RED


def test_colour_fields_come_with_the_first_colour():
    m = cube()
    before = m.copy()
    assert "colored" not in m._f.arrays  # no colour: 13 bytes a face neither stored nor copied
    m.set_face_color(0, None)
    assert_refused(m, lambda mesh: mesh.set_face_color(1, (2, 0, 0)), "colour must be",
                   InvalidArgumentError)
    assert "colored" not in m._f.arrays and m.face_colors() is None
    m.set_face_color(1, RED)
    assert sorted(m._f.arrays) == ["color", "colored", "corner", "hole"]
    spheres = [m.create_vertex((float(i), 0.0, 0.0)) for i in range(40)]  # the table grows
    assert m.face_color(1) == RED
    assert [m.face_color(f) for f in m.face_ids().tolist() if f != 1] == [None] * 45
    validate(m)
    assert before.face_colors() is None and "colored" not in before._f.arrays
    assert len(spheres) == 40


# -- from_tables ---------------------------------------------------------------


def two_gon_tables(back_is_hole: bool) -> dict[str, dict[str, np.ndarray]]:
    """The tables of a 2-gon: front face 0 (corners 0, 1), back face 1 (corners
    2, 3), one edge a side of each; the back face a hole or not."""
    return {
        "corners": {"next": np.array([1, 0, 3, 2]), "prev": np.array([1, 0, 3, 2]),
                    "face": np.array([0, 0, 1, 1]), "vertex": np.array([0, 1, 1, 0]),
                    "edge": np.array([0, 1, 0, 1])},
        "edges": {"c0": np.array([0, 1]), "c1": np.array([2, 3])},
        "faces": {"corner": np.array([0, 2]), "hole": np.array([0, int(back_is_hole)])},
        "vertices": {"corner": np.array([0, 1]), "position": np.eye(3)[:2]},
    }


def test_from_tables_adopts_the_tables_of_a_two_sided_edge():
    m = Mesh.from_tables(**two_gon_tables(back_is_hole=True), first_ids=(10, 20, 30, 40))
    assert checked(m) == (2, 2, 2)
    assert m.vertex_ids().tolist() == [10, 11] and m.edge_ids().tolist() == [20, 21]
    assert m.face_ids().tolist() == [30, 31] and m.corner_ids().tolist() == [40, 41, 42, 43]
    assert m.face_vertices(30) == [10, 11] and m.hole_mask().tolist() == [False, True]
    assert m.next_ids() == (12, 22, 32, 44)
    assert m.edge_corners(20) == (40, 42)
    with pytest.raises(UnknownIdError, match="vertex 3 was deleted or never existed"):
        m.position(3)


def test_from_tables_gives_the_ids_a_kind_is_given():
    m = Mesh.from_tables(**two_gon_tables(back_is_hole=False), first_ids=(10, 20, 30, 40),
                         ids=(np.array([7, 3]), None, np.array([5, 9]), None))
    assert checked(m) == (2, 2, 2)
    assert m.vertex_ids().tolist() == [3, 7] and m.face_ids().tolist() == [5, 9]
    assert m.edge_ids().tolist() == [20, 21] and m.face_vertices(5) == [7, 3]
    assert m.create_vertex() == 10  # past both the first id and the largest given


def test_from_tables_refuses_missing_fields_and_ragged_tables():
    def tables(**changed: dict) -> dict:
        empty = {"corners": dict.fromkeys(("next", "prev", "face", "vertex", "edge"),
                                          np.zeros(0)),
                 "edges": {"c0": np.zeros(0), "c1": np.zeros(0)},
                 "faces": {"corner": np.zeros(0), "hole": np.zeros(0)},
                 "vertices": {"corner": np.zeros(0), "position": np.zeros((0, 3))}}
        return empty | changed

    assert Mesh.from_tables(**tables()).counts() == (0, 0, 0)
    with pytest.raises(InvalidArgumentError, match=r"^the edge table needs the fields \['c0', 'c1'\], "
                                        r"got \['c0'\]$"):
        Mesh.from_tables(**tables(edges={"c0": np.zeros(0)}))
    with pytest.raises(InvalidArgumentError, match=r"^the face table needs the fields "
                       r"\['corner', 'hole'\] and all or none of \['color', 'colored'\], "
                       r"got \['colored', 'corner', 'hole'\]$"):
        Mesh.from_tables(**tables(faces={"corner": np.zeros(0), "hole": np.zeros(0),
                                         "colored": np.zeros(0)}))
    with pytest.raises(InvalidArgumentError, match="^the face table's fields differ in length: "):
        Mesh.from_tables(**tables(faces={"corner": np.zeros(2), "hole": np.zeros(1)}))
