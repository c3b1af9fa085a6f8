"""Measurements of picked elements in the HUD (GL-free), on meshes whose sizes are known,
and of the whole mesh shown, off the main thread."""

from __future__ import annotations

import math

import numpy as np
import pytest

from livemod.dlfl import Mesh, enclosed_volume, from_polygons, mesh_arrays, shapes
from livemod.dlfl.scene import Selection
from livemod.viewer import measure
from livemod.viewer.measure import (
    WholeMesh,
    WholeMeshMeasurer,
    corner_angle,
    face_area_normal,
    measure_lines,
)

# a 2 x 2 x 2 cube centred on the origin, faces outward
P = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
     (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
F = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3), (7, 6, 5, 4)]


@pytest.fixture
def cube():
    mesh = from_polygons(P, F)
    return mesh, mesh_arrays(mesh)


def test_one_face_tells_its_sides_area_and_normal(cube) -> None:
    mesh, arrays = cube
    top = mesh.face_ids()[0]
    assert measure_lines(Selection(faces=(top,)), arrays) == [
        f"face {top}: 4 sides, area 4, normal (0, 1, 0)"]
    area, normal = face_area_normal(arrays, 0)
    assert area == pytest.approx(4.0) and normal.tolist() == pytest.approx([0, 1, 0])


def test_several_faces_add_their_areas(cube) -> None:
    mesh, arrays = cube
    assert measure_lines(Selection(faces=tuple(mesh.face_ids()[:3])), arrays) == [
        "3 faces: area 12"]


def test_an_edge_tells_its_length_and_ends(cube) -> None:
    mesh, arrays = cube
    edge = mesh.edge_ids()[0]
    ends = sorted(mesh.edge_vertices(edge))
    line = measure_lines(Selection(edges=(edge,)), arrays)[0]
    assert line.startswith(f"edge {edge}: length 2, vertices ")
    assert sorted(int(v) for v in line.rsplit(" ", 1)[1].split("-")) == ends
    assert measure_lines(Selection(edges=tuple(mesh.edge_ids())), arrays) == [
        "12 edges: length 24"]


def test_vertices_tell_position_valence_distance_and_extent(cube) -> None:
    mesh, arrays = cube
    v0, v6 = mesh.vertex_ids()[0], mesh.vertex_ids()[6]
    assert measure_lines(Selection(vertices=(v0,)), arrays) == [
        f"vertex {v0} at (1, 1, 1), valence 3"]
    distance = f"{2 * math.sqrt(3):.4g}"
    assert measure_lines(Selection(vertices=(v0, v6)), arrays) == [
        f"vertices {v0}-{v6}: distance {distance}, delta (-2, -2, -2)"]
    three = tuple(mesh.vertex_ids()[:3])
    assert measure_lines(Selection(vertices=three), arrays) == ["3 vertices: extent (2, 0, 2)"]


def test_a_corner_tells_its_face_vertex_and_angle() -> None:
    # a right triangle's corners: 90, 45 and 45 degrees
    mesh = from_polygons([(0, 0, 0), (1, 0, 0), (0, 1, 0)], [(0, 1, 2)])
    arrays = mesh_arrays(mesh)
    angles = sorted(corner_angle(arrays, c) for c in range(3))
    assert angles == pytest.approx([45.0, 45.0, 90.0])
    cid = int(arrays.corner_ids[0])
    face, vertex = int(arrays.face_ids[arrays.corner_face[0]]), int(arrays.vertex_ids[arrays.corner_vertex[0]])
    assert measure_lines(Selection(corners=(cid,)), arrays) == [
        f"corner {cid}: face {face} at vertex {vertex}, angle 90.0 deg"]
    many = measure_lines(Selection(corners=tuple(int(c) for c in arrays.corner_ids)), arrays)
    assert len(many) == 3 and many[-1] == f"... {len(arrays.corner_ids) - 2} more corners"


def test_ids_the_mesh_lacks_are_left_out_and_nothing_is_measured_without_a_mesh(cube) -> None:
    mesh, arrays = cube
    top = mesh.face_ids()[0]
    assert measure_lines(Selection(faces=(10_000, top)), arrays) == [
        f"face {top}: 4 sides, area 4, normal (0, 1, 0)"]
    assert measure_lines(Selection(faces=(10_000,)), arrays) == []
    assert measure_lines(Selection(faces=(top,)), None) == []
    assert measure_lines(Selection(), arrays) == []


def test_a_degenerate_face_has_no_normal() -> None:
    mesh = from_polygons([(0, 0, 0), (1, 0, 0), (2, 0, 0)], [(0, 1, 2)])
    area, normal = face_area_normal(mesh_arrays(mesh), 0)
    assert area == 0.0 and np.all(normal == 0)


def test_a_point_sphere_has_valence_zero_and_no_angle() -> None:
    mesh = Mesh()
    v = mesh.create_vertex((1.0, 2.0, 3.0))
    arrays = mesh_arrays(mesh)
    assert measure_lines(Selection(vertices=(v,)), arrays) == [
        f"vertex {v} at (1, 2, 3), valence 0"]
    assert corner_angle(arrays, 0) == 0.0


def test_the_whole_mesh_is_measured_at_once_or_when_large_off_the_main_thread(
        monkeypatch) -> None:
    import livemod.viewer.measure as measure

    measurer = WholeMeshMeasurer()
    try:
        assert measurer.facts() is None  # nothing shown yet
        measurer.measure(mesh_arrays(shapes.cube()))
        assert measurer.facts() == WholeMesh(0, pytest.approx(8.0))  # small: at once
        monkeypatch.setattr(measure, "MEASURE_AT_ONCE", 10)  # every mesh is large now
        measurer.measure(mesh_arrays(shapes.cube()))
        measurer.measure(mesh_arrays(shapes.torus(40, 30)))  # the cube's answer is dropped
        assert measurer.wait(30) == WholeMesh(1, pytest.approx(
            enclosed_volume(mesh_arrays(shapes.torus(40, 30)))))
        measurer.measure(mesh_arrays(from_polygons(np.eye(3), [(0, 1, 2)])))  # open
        assert measurer.wait(30) == WholeMesh(0, None)
        measurer.measure(None)
        assert measurer.facts() is None and measurer.wait() is None
    finally:
        measurer.close()



def test_a_background_measurement_that_fails_is_logged_and_says_nothing(
        monkeypatch, caplog) -> None:
    import livemod.viewer.measure as measure

    def broken(arrays):
        raise FloatingPointError("no volume")

    monkeypatch.setattr(measure, "MEASURE_AT_ONCE", 10)
    monkeypatch.setattr(measure, "measure_whole", broken)
    measurer = WholeMeshMeasurer()
    try:
        with caplog.at_level("ERROR", logger="livemod.measure"):
            measurer.measure(mesh_arrays(shapes.cube()))
            assert measurer.wait(30) is None
            measurer.close(wait=True)  # the log is written by the done callback
    finally:
        measurer.close()
    assert "measuring the mesh shown failed" in caplog.text and "no volume" in caplog.text


def test_a_face_far_from_the_origin_keeps_its_area_and_normal() -> None:
    far = 1e8
    square = [(far, far, 0.0), (far + 1, far, 0.0), (far + 1, far + 1, 0.0), (far, far + 1, 0.0)]
    arrays = mesh_arrays(from_polygons(square, [(0, 1, 2, 3)]))
    area, normal = face_area_normal(arrays, 0)
    assert area == pytest.approx(1.0, rel=1e-6)
    assert np.allclose(np.abs(normal), (0, 0, 1))



def test_a_measurer_closed_for_another_script_measures_again(monkeypatch) -> None:
    """The window closes its measurer with the session when a script is dropped on
    it; measuring the next script's large mesh must still work."""
    monkeypatch.setattr(measure, "MEASURE_AT_ONCE", 0)  # every mesh in the background
    measurer = WholeMeshMeasurer()
    measurer.close()
    measurer.measure(mesh_arrays(shapes.cube()))
    facts = measurer.wait(10.0)
    assert facts is not None and facts.genus == 0
    measurer.close()
