"""Commands of TopMod's cleanup helpers and of orientation on the current scene."""

from __future__ import annotations

import numpy as np
import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import DLFLError, face_normals, face_size_histogram, validate
from livemod.dlfl.commands import (
    cleanup2gons,
    cleanupWingedVertices,
    collapseEdge,
    edgeCleanup,
    edges,
    faces,
    load,
    menger,
    reverseOrientation,
    splitValence2Vertices,
    subdivide,
    subdivideEdge,
)
from tests.meshes import counts, snapshot


def test_star_import_gives_the_commands():
    for name in ("edgeCleanup", "cleanup2gons", "cleanupWingedVertices",
                 "splitValence2Vertices", "reverseOrientation"):
        assert name in dlfl.__all__


def test_edge_cleanup_merges_coplanar_faces_back_into_the_cube(scene):
    subdivide("triangulate")
    assert counts(scene) == (14, 36, 24)
    assert edgeCleanup() == 24
    assert counts(scene) == (8, 12, 6)
    validate(scene.mesh)


def _spokes(mesh) -> list[int]:
    """After ``triangulate`` on the cube: the edges to a face centre (valence 4)."""
    return [e for e in edges() if 4 in [mesh.valence(v) for v in mesh.edge_vertices(e)]]


def test_edge_cleanup_of_listed_edges_only(scene):
    subdivide("triangulate")
    assert edgeCleanup(_spokes(scene.mesh)[:2]) == 2 and counts(scene) == (14, 34, 22)


def test_cleanup_2gons_removes_topmods_sponge_2gons(scene):
    menger()
    assert cleanup2gons() == 12
    assert counts(scene) == (64, 144, 72) and face_size_histogram(scene.mesh) == {4: 72}


def test_winged_vertices_are_removed_and_split(scene):
    subdivideEdge(edges()[0])
    before = snapshot(scene.mesh)
    assert cleanupWingedVertices() == 1 and counts(scene) == (8, 12, 6)
    load("cube")
    subdivideEdge(edges()[0])
    assert before == snapshot(scene.mesh)
    new = splitValence2Vertices()
    assert len(new) == 1 and counts(scene) == (10, 14, 6)
    assert face_size_histogram(scene.mesh) == {4: 4, 6: 2}
    validate(scene.mesh)


def test_collapse_edge_keeps_the_two_gons_without_cleanup(scene):
    subdivide("triangulate")
    collapseEdge(_spokes(scene.mesh)[0], False)
    assert face_size_histogram(scene.mesh) == {2: 2, 3: 22}
    load("cube")
    subdivide("triangulate")
    collapseEdge(_spokes(scene.mesh)[0])
    assert face_size_histogram(scene.mesh) == {3: 22}
    validate(scene.mesh)


def test_reverse_orientation_of_the_object_and_of_a_faces_piece(scene):
    normals = face_normals(scene.mesh)
    reverseOrientation()
    validate(scene.mesh)
    np.testing.assert_array_equal(face_normals(scene.mesh), -normals)
    reverseOrientation(faces()[3])
    np.testing.assert_array_equal(face_normals(scene.mesh), normals)


@pytest.mark.parametrize("call", [
    lambda: edgeCleanup("all"), lambda: splitValence2Vertices(float("nan")),
    lambda: reverseOrientation([99]), lambda: collapseEdge(0, "no"),
])
def test_bad_arguments_change_nothing(scene, call):
    before = snapshot(scene.mesh)
    with pytest.raises(DLFLError):
        call()
    assert snapshot(scene.mesh) == before
