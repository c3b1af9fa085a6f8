"""Regressions from the review of the DLFL core (notes/core_review.md).

Each test failed before its fix: bad arguments reached numpy or Python and came
back as ValueError / TypeError, or were silently taken for something else,
instead of a DLFLError that names the argument and leaves the mesh unchanged.
"""

from __future__ import annotations

import pytest

from livemod.dlfl import DLFLError, Mesh, validate
from livemod.dlfl.errors import InvalidArgumentError, UnknownIdError
from livemod.dlfl.geometry import cleanup_2gons, edge_cleanup
from livemod.dlfl.selection import checkerboard, faces_by_area, faces_by_normal
from livemod.dlfl.transform import move_vertices, transform, translate
from tests.meshes import assert_refused, cube


@pytest.mark.parametrize("text", ["123", b"123", bytearray(b"123")])
def test_a_string_is_not_a_position(text):
    # "123" unpacked into the point (1, 2, 3) and b"123" into (49, 50, 51)
    assert_refused(Mesh(), lambda m: m.create_vertex(text), "expected a position",
                   error=InvalidArgumentError)
    assert_refused(cube(), lambda m: m.set_position(0, text), "expected a position",
                   error=InvalidArgumentError)
    assert_refused(Mesh(), lambda m: m.create_face([text, (0, 0, 0)]), "expected a position",
                   error=InvalidArgumentError)


def test_set_hole_refuses_a_string_flag():
    # "False" is truthy: the face became a hole
    assert_refused(cube(), lambda m: m.set_hole(0, "False"), "hole must be True or False",
                   error=InvalidArgumentError)
    m = cube()
    m.set_hole(0, 1)
    assert m.is_hole(0)
    m.set_hole(0, False)
    assert not m.is_hole(0)


def test_validate_names_a_free_slot_outside_the_table():
    m = cube()
    m._e.free.append(m._e.n + 5)  # IndexError inside validate before the fix
    with pytest.raises(DLFLError, match="free list holds slot 17, outside the 12 used slots"):
        validate(m)
    m = cube()
    m._e.free.append(-1)  # indexed the last slot silently
    with pytest.raises(DLFLError, match="free list holds slot -1"):
        validate(m)


@pytest.mark.parametrize("edges", [5, "01", [0, 1.5]])
def test_edge_cleanup_refuses_edges_that_are_not_ids(edges):
    # 5 raised TypeError; 1.5 was skipped as if it were a deleted edge
    assert_refused(cube(), lambda m: edge_cleanup(m, edges), "edges must",
                   error=InvalidArgumentError)


@pytest.mark.parametrize("matrix", ["abc", [[1, 2], [3]]])
def test_transform_refuses_a_matrix_that_is_not_numbers(matrix):
    assert_refused(cube(), lambda m: transform(m, matrix), "matrix must be a finite 3x3 array",
                   error=InvalidArgumentError)


def test_move_vertices_refuses_a_string_flag():
    assert_refused(cube(), lambda m: move_vertices(m, [0], (1, 1, 1), relative="False"),
                   "relative must be True or False", error=InvalidArgumentError)


def test_transform_of_a_deleted_vertex_says_it_was_deleted():
    m = cube()
    m.collapse_edge(0)
    gone = next(v for v in range(8) if not m.has_vertex(v))
    assert_refused(m, lambda m: translate(m, (1, 0, 0), vertices=[gone]),
                   f"vertex {gone} was deleted", error=UnknownIdError)
    assert_refused(m, lambda m: translate(m, (1, 0, 0), vertices=[99]), "vertex 99 does not exist",
                   error=UnknownIdError)


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
    assert_refused(cube(), call, message, error=InvalidArgumentError)


def test_selection_of_a_deleted_face_says_it_was_deleted():
    m = cube()
    m.delete_edge(0)  # the second face of edge 0 goes
    gone = next(f for f in range(6) if not m.has_face(f))
    for call in (faces_by_area, checkerboard):
        assert_refused(m, lambda m, call=call: call(m, gone), f"face {gone} was deleted",
                       error=UnknownIdError)


def test_faces_by_normal_takes_a_huge_direction():
    # the norm of (1e308, 1e308, 0) overflows unless scaled first
    assert faces_by_normal(cube(), (1e308, 0, 0)) == faces_by_normal(cube(), (1, 0, 0))


def test_cleanup_2gons_keeps_a_lone_edge():
    # its 2-corner face runs along both sides of one edge: deleting that edge
    # (with cleanup) removed both vertices, the whole component
    m = cube()
    a, b = m.create_vertex((5, 0, 0)), m.create_vertex((6, 0, 0))
    m.insert_edge(m.vertex_corner(a), m.vertex_corner(b))
    m.insert_edge(0, 1)  # a 2-gon inside the bottom face of the cube
    assert cleanup_2gons(m) == 1
    validate(m)
    assert m.counts() == (10, 13, 7) and m.has_vertex(a) and m.has_vertex(b)
