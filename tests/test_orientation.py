"""Orientation: a mesh or its components turned inside out, ids kept."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import DLFLError, enclosed_volume, face_normals, genus, validate
from livemod.dlfl.errors import UnknownIdError
from livemod.dlfl.orientation import component_faces, reverse_orientation
from livemod.dlfl.shapes import cube, grid, torus
from tests.meshes import point_sphere, snapshot, two_cubes


def test_reversing_the_cube_turns_every_face_inward_and_keeps_the_ids():
    m = cube()
    before, normals, rings = snapshot(m), face_normals(m), {
        f: m.face_vertices(f) for f in m.face_ids().tolist()}
    volume = enclosed_volume(m)
    reverse_orientation(m)
    validate(m)
    assert m.counts() == (8, 12, 6) and genus(m) == 0
    np.testing.assert_array_equal(face_normals(m), -normals)
    assert enclosed_volume(m) == pytest.approx(-volume)
    for face, ring in rings.items():  # the same head, the rest in the other order
        assert m.face_vertices(face) == [ring[0], *ring[:0:-1]]
    reverse_orientation(m)
    assert snapshot(m) == before


def test_a_faces_component_turns_and_the_others_stay():
    m = two_cubes()
    normals = face_normals(m)
    assert component_faces(m, [0]) == list(range(6))
    reverse_orientation(m, [2])
    validate(m)
    np.testing.assert_array_equal(face_normals(m)[:6], -normals[:6])
    np.testing.assert_array_equal(face_normals(m)[6:], normals[6:])


@pytest.mark.parametrize("make", [lambda: torus(4, 3), lambda: grid(3, 2), point_sphere])
def test_tori_open_grids_and_point_spheres_stay_valid(make):
    m = make()
    before = snapshot(m)
    reverse_orientation(m)
    validate(m)
    reverse_orientation(m)
    assert snapshot(m) == before


def test_reversing_part_of_a_component_is_refused_naming_an_edge():
    m = cube()
    before = snapshot(m)
    with pytest.raises(DLFLError, match="edge .* has one side in the faces to reverse and "
                       "one outside; reverse whole components"):
        m.reverse_faces([0])
    assert snapshot(m) == before


def test_an_unknown_face_is_refused():
    m = cube()
    with pytest.raises(UnknownIdError, match="face 40 does not exist"):
        reverse_orientation(m, [0, 40])
    assert snapshot(m) == snapshot(cube())


def test_a_face_of_an_empty_mesh_is_refused_as_unknown():
    from livemod.dlfl import Mesh

    m = Mesh()
    with pytest.raises(UnknownIdError, match=r"^face 0 does not exist \(deleted or never made\)$"):
        reverse_orientation(m, [0])
    reverse_orientation(m)  # the whole of an empty mesh: nothing to turn
    assert m.counts() == (0, 0, 0)
