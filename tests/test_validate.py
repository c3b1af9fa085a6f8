"""Tests of livemod.dlfl.validate: each corruption is reported precisely."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import InvalidMeshError, Mesh, validate
from tests.meshes import cube, path_face, point_sphere, torus, two_cubes


@pytest.mark.parametrize("make", [cube, two_cubes, torus, path_face, point_sphere, Mesh])
def test_valid_meshes_pass(make):
    validate(make())


def corrupt(mesh: Mesh, kind: str, field: str, slot: int, value) -> Mesh:
    table = {"corner": mesh._c, "edge": mesh._e, "face": mesh._f, "vertex": mesh._v}[kind]
    table.arrays[field][slot] = value
    return mesh


@pytest.mark.parametrize(("kind", "field", "slot", "value", "message"), [
    ("corner", "next", 0, 99, "corner 0 has a dangling next link"),
    ("corner", "prev", 5, -3, "corner 5 has a dangling prev link"),
    ("corner", "face", 2, 40, "corner 2 has a dangling face link"),
    ("corner", "vertex", 7, 8, "corner 7 has a dangling vertex link"),
    ("corner", "edge", 3, 12, "corner 3 has a dangling edge link"),
    ("corner", "next", 0, 2, "next and prev links disagree"),
    ("corner", "face", 1, 1, "corner 0 links to a corner of another face"),
    ("face", "corner", 1, 0, "face 1 has a head corner that is dead or belongs to another face"),
    ("edge", "c1", 0, 0, "edge 0 has the same corner on both sides"),
    ("vertex", "corner", 3, 0, "vertex 3 points to a corner that is dead or at another vertex"),
    ("vertex", "position", 2, np.nan, "vertex 2 has a position that is not finite"),
])
def test_corruptions_are_named(kind, field, slot, value, message):
    m = corrupt(cube(), kind, field, slot, value)
    with pytest.raises(InvalidMeshError, match=f"^invalid mesh: .*{message}"):
        validate(m)


def test_edge_side_that_does_not_point_back():
    m = cube()
    e0, e1 = m._c.arrays["edge"][0], m._c.arrays["edge"][1]
    m._c.arrays["edge"][0], m._c.arrays["edge"][1] = e1, e0
    with pytest.raises(InvalidMeshError, match="edge 0 has a side corner that does not point back"):
        validate(m)


def test_edge_sides_at_the_wrong_ends():
    m = cube()
    m._c.arrays["vertex"][0] = 2  # corner 0 now sits at vertex 2
    with pytest.raises(InvalidMeshError, match="edge 3 has sides that do not meet at its second end"):
        validate(m)


def test_edge_sides_that_do_not_meet_at_the_first_end():
    m = cube()
    ea, ca = m._e.arrays, m._c.arrays
    # swap the sides of edge 0: now its c1 runs from c0's far end
    ea["c0"][0], ea["c1"][0] = ea["c1"][0], ea["c0"][0]
    ca["vertex"][ca["next"][ea["c1"][0]]] = 5
    with pytest.raises(InvalidMeshError, match="edge 0 has sides that do not meet at its first end"):
        validate(m)


def test_two_rings_in_one_face():
    m = cube()
    nxt, prv = m._c.arrays["next"], m._c.arrays["prev"]
    # split face 0's ring [0, 1, 2, 3] into [0, 1] and [2, 3]
    nxt[1], prv[0] = 0, 1
    nxt[3], prv[2] = 2, 3
    with pytest.raises(InvalidMeshError, match="7 corner rings for 6 faces: face 0 has corners outside"):
        validate(m)


def test_edgeless_corner_in_a_ring():
    m = cube()
    m._c.arrays["edge"][0] = -1
    with pytest.raises(InvalidMeshError, match="edge 0 has a side corner that does not point back to it"):
        validate(m)


def test_non_manifold_vertex_fans():
    m = two_cubes()
    # glue vertex 8 (second cube) onto vertex 0: two fans at one vertex
    ca = m._c.arrays
    ca["vertex"][ca["vertex"] == 8] = 0
    m._v.ids[8] = -1
    m._v.free.append(8)
    with pytest.raises(InvalidMeshError, match="vertex 0 has 2 separate fans"):
        validate(m)


def test_id_map_corruptions():
    m = cube()
    m._e.ids[3] = 5
    with pytest.raises(InvalidMeshError, match="edge ids are not unique"):
        validate(m)
    m = cube()
    m._f.moved[77] = 2
    with pytest.raises(InvalidMeshError, match="face id map sends 77 to slot 2, which holds 2"):
        validate(m)
    m = cube()
    m._v.ids[1] = 100
    with pytest.raises(InvalidMeshError, match="vertex id 100 is not below the id counter 8"):
        validate(m)
    m = cube()
    m._c.free.append(4)
    with pytest.raises(InvalidMeshError, match="corner table counts 23 live elements but 24"):
        validate(m)


def test_id_map_misses_a_moved_id():
    m = cube()
    v = m.create_vertex()
    m.remove_vertex(v)
    w = m.create_vertex()  # lands in the freed slot, recorded in `moved`
    del m._v.moved[w]
    with pytest.raises(InvalidMeshError, match=f"vertex id map misses id {w}, stored away from its"):
        validate(m)


def test_corners_without_faces():
    m = Mesh()
    m._v.reserve(1)
    m._v.alloc()
    with pytest.raises(InvalidMeshError, match="no corners but has vertices"):
        validate(m)


def test_a_face_colour_out_of_range_or_a_bad_flag_is_reported():
    m = cube()
    m.set_face_color(2, (0.5, 0.5, 0.5))
    validate(m)
    m._f.arrays["color"][m._f.slot(2)] = (0.5, np.nan, 0.5)
    with pytest.raises(InvalidMeshError, match=r"face 2 has colour flag 1 and colour \[0.5, nan"):
        validate(m)
    m = cube()
    m.set_face_color(1, (0.5, 0.5, 0.5))  # the face table has colour fields from now on
    m._f.colored[m._f.slot(4)] = 7
    with pytest.raises(InvalidMeshError, match="face 4 has colour flag 7"):
        validate(m)


# -- a free list holding a slot outside the table is named, not an IndexError


def test_validate_names_a_free_slot_outside_the_table():
    m = cube()
    m._e.free.append(m._e.n + 5)  # IndexError inside validate before the fix
    with pytest.raises(InvalidMeshError, match="free list holds slot 17, outside the 12 used slots"):
        validate(m)
    m = cube()
    m._e.free.append(-1)  # indexed the last slot silently
    with pytest.raises(InvalidMeshError, match="free list holds slot -1"):
        validate(m)
