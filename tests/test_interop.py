"""The trimesh bridge: livemod meshes to trimesh and back, read by trimesh itself."""

from __future__ import annotations

import sys

import numpy as np
import pytest
import trimesh

from livemod.dlfl import DLFLError, genus, mesh_arrays, validate
from livemod.dlfl.errors import InvalidArgumentError
from livemod.interop import FACE_ID, from_trimesh, to_trimesh
from tests.meshes import (
    CUBE_FACES,
    coloured_cube,
    cube,
    expected_written_colors,
    point_sphere,
    torus,
    triangle,
)


def test_a_cube_becomes_a_closed_trimesh_of_its_fan_triangles():
    mesh = cube()
    tm = to_trimesh(mesh)
    a = mesh_arrays(mesh)
    assert np.array_equal(tm.vertices, a.positions)
    assert tm.faces.tolist() == a.triangles()[0].tolist()
    assert tm.face_attributes[FACE_ID].tolist() == np.repeat(a.face_ids, 2).tolist()
    # trimesh's own checks: closed, consistently wound outward, the unit cube's volume
    assert tm.is_watertight and tm.is_winding_consistent
    assert tm.volume == pytest.approx(1.0) and tm.area == pytest.approx(6.0)
    assert [sorted(set(tm.faces[tm.face_attributes[FACE_ID] == f].ravel().tolist()))
            for f in a.face_ids] == [sorted(face) for face in CUBE_FACES]


def test_a_torus_keeps_its_genus_and_a_mesh_with_a_hole_stays_open():
    tm = to_trimesh(torus(6, 4))
    assert tm.is_watertight and tm.euler_number == 0  # genus 1
    assert len(tm.faces) == 2 * 24
    lone = mesh_arrays(triangle())  # one triangle and its hole face; a MeshArrays does too
    assert lone.face_hole.tolist() == [False, True]
    open_tm = to_trimesh(lone)
    assert open_tm.faces.tolist() == [[0, 1, 2]] and not open_tm.is_watertight


def test_vertices_no_triangle_uses_are_kept_in_id_order():
    mesh = cube()
    mesh.create_vertex((5.0, 6.0, 7.0))  # a point-sphere: no triangle
    tm = to_trimesh(mesh)
    assert len(tm.vertices) == 9 and tm.vertices[8].tolist() == [5.0, 6.0, 7.0]
    assert len(tm.faces) == 12
    assert point_sphere().counts() == (1, 0, 1)
    assert len(to_trimesh(point_sphere()).faces) == 0


def test_an_icosphere_from_trimesh_is_a_valid_sphere_of_triangles():
    tm = trimesh.creation.icosphere(subdivisions=2)
    mesh = from_trimesh(tm)
    validate(mesh)
    assert mesh.counts() == (len(tm.vertices), len(tm.edges_unique), len(tm.faces))
    assert mesh.counts() == (162, 480, 320) and genus(mesh) == 0
    back = to_trimesh(mesh)  # the round trip gives trimesh its own arrays back
    assert np.array_equal(back.vertices, tm.vertices)
    assert back.faces.tolist() == tm.faces.tolist()


def test_an_open_trimesh_gets_a_hole_face_per_boundary_loop():
    tm = trimesh.creation.box()
    tm.update_faces(np.arange(len(tm.faces)) != 0)  # one triangle out: a triangular hole
    mesh = from_trimesh(tm)
    validate(mesh)
    a = mesh_arrays(mesh)
    assert int(a.face_hole.sum()) == 1 and a.face_sizes[a.face_hole].tolist() == [3]
    assert mesh.counts() == (8, 18, 11 + 1)
    assert len(to_trimesh(mesh).faces) == 11  # the hole is not drawn back


def test_from_trimesh_refuses_a_scene_and_what_is_not_a_manifold():
    with pytest.raises(InvalidArgumentError, match=r"not Scene \(join a trimesh.Scene first"):
        from_trimesh(trimesh.Scene(trimesh.creation.box()))
    with pytest.raises(InvalidArgumentError, match="takes a trimesh.Trimesh, not list"):
        from_trimesh([[0, 0, 0]])  # type: ignore[arg-type]
    fin = trimesh.Trimesh(vertices=[[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]],
                          faces=[[0, 1, 2], [0, 1, 3], [0, 1, 4]], process=False)
    with pytest.raises(DLFLError, match=r"^the trimesh mesh: edge \(0, 1\) is used by 3"):
        from_trimesh(fin)


def test_the_bridges_say_how_to_install_trimesh(monkeypatch: pytest.MonkeyPatch):
    monkeypatch.setitem(sys.modules, "trimesh", None)  # what an import of a missing one does
    with pytest.raises(ImportError, match=r"^to_trimesh needs trimesh: pip install trimesh$"):
        to_trimesh(cube())
    with pytest.raises(ImportError, match=r"^from_trimesh needs trimesh"):
        from_trimesh(object())  # type: ignore[arg-type]


def test_face_colours_go_to_every_triangle_of_their_face():
    mesh = coloured_cube()
    tm = to_trimesh(mesh)
    assert tm.visual.kind == "face"
    expected = np.rint(expected_written_colors(mesh) * 255).astype(np.uint8)
    faces = tm.face_attributes[FACE_ID]
    assert np.array_equal(tm.visual.face_colors[:, :3], expected[faces])
    assert (tm.visual.face_colors[:, 3] == 255).all()
    assert to_trimesh(cube()).visual.kind is None  # no colours, none made up


def test_a_trimesh_in_face_colours_comes_back_coloured_by_triangle():
    tm = trimesh.creation.icosphere(subdivisions=1)
    rgba = np.zeros((len(tm.faces), 4), dtype=np.uint8)
    rgba[:, 0] = np.arange(len(tm.faces)) * 3
    rgba[:, 3] = 128
    tm.visual.face_colors = rgba
    mesh = from_trimesh(tm)
    validate(mesh)
    colors = mesh.face_colors()
    assert colors is not None
    assert np.allclose(colors, rgba[:, :3] / 255)
    back = to_trimesh(mesh)
    assert np.array_equal(back.visual.face_colors[:, :3], rgba[:, :3])


def test_vertex_colours_are_not_taken_as_face_colours():
    tm = trimesh.creation.icosphere(subdivisions=1)
    tm.visual.vertex_colors = np.tile([10, 20, 30, 255], (len(tm.vertices), 1))
    assert tm.visual.kind == "vertex"
    assert from_trimesh(tm).face_colors() is None
