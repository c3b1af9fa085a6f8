"""Tests of livemod.dlfl.arrays: the dense layout of a mesh."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import (
    InvalidArgumentError,
    Mesh,
    from_corner_arrays,
    from_polygons,
    mesh_arrays,
    validate,
)
from livemod.dlfl.arrays import concatenate_arrays
from tests.meshes import (
    CUBE_FACES,
    CUBE_OUTWARD,
    CUBE_POSITIONS,
    corner_structure,
    cube,
    path_face,
    torus,
)


def test_fresh_cube_layout():
    a = mesh_arrays(cube())
    assert a.counts == (8, 12, 6)
    assert a.face_offsets.tolist() == [0, 4, 8, 12, 16, 20, 24]
    assert a.corner_vertex.reshape(6, 4).tolist() == CUBE_FACES
    assert a.corner_ids.tolist() == list(range(24))
    np.testing.assert_array_equal(a.positions, CUBE_POSITIONS)
    assert a.face_sizes.tolist() == [4] * 6
    assert not a.face_hole.any()


def test_mates_and_edges_are_consistent():
    a = mesh_arrays(torus(5, 3))
    has = a.corner_mate >= 0
    assert has.all()
    assert np.array_equal(a.corner_mate[a.corner_mate], np.arange(len(a.corner_ids)))
    assert np.array_equal(a.corner_edge[a.corner_mate], a.corner_edge)
    # a corner's mate starts where the corner's edge ends
    assert np.array_equal(a.corner_vertex[a.corner_mate], a.corner_vertex[a.corner_next])
    ends = a.edge_vertices
    assert np.array_equal(ends[:, 0], a.corner_vertex[a.edge_corners[:, 0]])
    assert np.array_equal(a.corner_prev[a.corner_next], np.arange(len(a.corner_ids)))


def test_vnext_walks_around_the_vertex():
    a = mesh_arrays(cube())
    vn = a.corner_vnext
    assert np.array_equal(a.corner_vertex[vn], a.corner_vertex)
    assert np.array_equal(vn[vn[vn]], np.arange(24))  # valence 3 everywhere


def test_layout_after_edits_follows_rings_from_heads():
    m = cube()
    m.insert_edge(0, 2)
    m.delete_edge(m.corner_edge(5))
    m.create_vertex((5.0, 5.0, 5.0))
    a = mesh_arrays(m)
    for i, f in enumerate(a.face_ids.tolist()):
        ring = a.corner_ids[a.face_offsets[i]:a.face_offsets[i + 1]].tolist()
        assert ring == m.face_corners(f)
    assert a.vertex_ids.tolist() == m.vertex_ids().tolist()
    assert (a.corner_edge < 0).sum() == 1  # the point-sphere


def test_permuted_ids_in_a_full_table_are_laid_out_by_ring():
    # regression: every slot live and no free slot, but ids no longer in slot order
    m = path_face()
    # a sequence found by the property tests: corners 16 and 17 end up in slots 1, 3
    m.delete_edge(0, cleanup=False)
    m.insert_edge(0, 3)
    m.delete_edge(1, cleanup=False)
    m.insert_edge(m.corner_next(0), 2)
    assert m._c.moved and m._c.n - len(m._c.free) == 4
    a = mesh_arrays(m)
    for i, f in enumerate(a.face_ids.tolist()):
        assert a.corner_ids[a.face_offsets[i]:a.face_offsets[i + 1]].tolist() == m.face_corners(f)


def test_round_trip_through_from_corner_arrays():
    m = torus(4, 4)
    m.insert_edge(0, 2)
    m.subdivide_edge(3, 3)
    a = mesh_arrays(m)
    rebuilt = from_corner_arrays(a.positions, a.face_offsets, a.corner_vertex, a.corner_mate,
                                 a.face_hole)
    validate(rebuilt)
    b = mesh_arrays(rebuilt)
    for name in ("positions", "face_offsets", "corner_vertex", "corner_mate", "face_hole"):
        assert np.array_equal(getattr(a, name), getattr(b, name)), name


def test_round_trip_through_the_soup_builder():
    m = cube()
    m.insert_edge(0, 2)
    a = mesh_arrays(m)
    faces = [a.corner_vertex[a.face_offsets[i]:a.face_offsets[i + 1]].tolist()
             for i in range(len(a.face_ids))]
    again = from_polygons(a.positions, faces)
    assert corner_structure(again)[1:] == corner_structure(from_polygons(a.positions, faces))[1:]
    assert mesh_arrays(again).counts == (8, 13, 7)


def test_empty_mesh():
    a = mesh_arrays(Mesh())
    assert a.counts == (0, 0, 0)
    assert a.face_offsets.tolist() == [0]
    assert a.edge_corners.shape == (0, 2)


def test_surface_polygons_leave_out_holes_and_point_spheres():
    # an open quad (one hole face) plus an unused vertex (a point-sphere face)
    m = from_polygons([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (5, 5, 5)], [(0, 1, 2, 3)])
    a = mesh_arrays(m)
    assert a.face_sizes.tolist() == [4, 4, 1]
    assert a.face_is_surface.tolist() == [True, False, False]
    sizes, vertices = a.surface_polygons()
    assert sizes.tolist() == [4]
    assert vertices.tolist() == [0, 1, 2, 3]


def test_concatenated_arrays_are_the_disjoint_union_of_the_parts():
    from livemod.dlfl import genus
    from livemod.dlfl.arrays import concatenate_arrays

    parts = [cube(), torus(5, 3), path_face(), Mesh()]
    point = Mesh()
    point.create_vertex((9.0, 9.0, 9.0))  # a point-sphere: mate and edge -1 stay -1
    parts.append(point)
    snapshots = [mesh_arrays(p) for p in parts]
    joined = concatenate_arrays(snapshots)
    assert joined.counts == tuple(sum(s.counts[k] for s in snapshots) for k in range(3))
    union = from_corner_arrays(joined.positions, joined.face_offsets, joined.corner_vertex,
                               joined.corner_mate)
    validate(union)
    again = mesh_arrays(union)
    for name in ("positions", "face_offsets", "corner_vertex", "corner_face", "corner_mate",
                 "corner_edge", "edge_corners"):
        assert np.array_equal(getattr(again, name), getattr(joined, name)), name
    assert genus(union) == sum(genus(p) for p in parts[:3])
    assert np.array_equal(joined.face_ids, np.concatenate([s.face_ids for s in snapshots]))


def test_concatenate_arrays_needs_a_part():
    from livemod.dlfl.arrays import concatenate_arrays

    with pytest.raises(InvalidArgumentError, match="at least one"):
        concatenate_arrays([])


def test_arrays_are_read_only_copies_that_later_edits_do_not_change():
    mesh = cube()
    arrays = mesh_arrays(mesh)
    before = arrays.positions.copy()
    with pytest.raises(ValueError, match="read-only"):
        arrays.positions[0, 0] = 9.0
    with pytest.raises(ValueError, match="read-only"):
        arrays.corner_vertex[:] = 0
    mesh.set_positions([0], (9.0, 9.0, 9.0))
    mesh.insert_edge(*mesh.face_corners(0)[::2])
    np.testing.assert_array_equal(arrays.positions, before)
    assert arrays.counts == (8, 12, 6)
    writable = np.array(arrays.positions)
    writable[0, 0] = 1.0  # a copy is the caller's own


def test_fan_triangles_of_a_pentagon_start_at_its_head():
    a = mesh_arrays(from_polygons([(0, 0, 0), (1, 0, 0), (1.5, 1, 0), (0.5, 1.6, 0), (-0.5, 1, 0)],
                                  [(0, 1, 2, 3, 4)]))
    corners, faces = a.fan_triangles()
    assert corners.tolist() == [[0, 1, 2], [0, 2, 3], [0, 3, 4]]  # the hole face 1 gives none
    assert faces.tolist() == [0, 0, 0] and corners.dtype == faces.dtype == np.int64


def test_fan_triangles_leave_out_holes_two_gons_and_point_spheres():
    m = from_polygons([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (2, 2, 2), (3, 3, 3)],
                      [(0, 1, 2, 3), (4, 5), (5, 4)])
    m.create_vertex((9, 9, 9))
    a = mesh_arrays(m)
    corners, faces = a.fan_triangles()
    drawn = ~a.face_hole & (a.face_sizes >= 3)
    assert faces.tolist() == np.repeat(np.flatnonzero(drawn), a.face_sizes[drawn] - 2).tolist()
    assert len(faces) == 2 and not a.face_hole[0] and a.face_hole.sum() == 1
    assert corners.tolist() == [[0, 1, 2], [0, 2, 3]]  # the quad, from its head


def test_fan_triangles_of_an_edited_torus_cover_each_face_once():
    m = torus(5, 3)
    m.insert_edge(0, 2)  # a triangle and a fresh face, laid out through the ring order
    m.delete_edge(int(m.edge_ids()[3]))  # a hexagon
    a = mesh_arrays(m)
    corners, faces = a.fan_triangles()
    assert np.bincount(faces, minlength=len(a.face_ids)).tolist() == (a.face_sizes - 2).tolist()
    first = corners[:, 1] == corners[:, 0] + 1
    last = corners[:, 2] == a.face_offsets[faces + 1] - 1
    assert first.sum() == last.sum() == len(a.face_ids)  # one first and one last per face
    validate(m)


def test_triangles_name_the_vertices_and_the_face_of_each_fan_triangle():
    a = mesh_arrays(cube())
    vertices, faces = a.triangles()
    expected = [[[f[0], f[1], f[2]], [f[0], f[2], f[3]]] for f in CUBE_FACES]
    assert vertices.tolist() == [t for pair in expected for t in pair]
    assert faces.tolist() == np.repeat(np.arange(6), 2).tolist()
    assert vertices.dtype == faces.dtype == np.int64
    corners, fan_faces = a.fan_triangles()  # the same triangulation, by vertex
    assert np.array_equal(vertices, a.corner_vertex[corners]) and np.array_equal(faces, fan_faces)
    p = a.positions[vertices]
    normals = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    outward = np.repeat(np.array(CUBE_OUTWARD, dtype=float), 2, axis=0)
    assert np.allclose(normals, outward)  # counter-clockwise from outside, area 1/2 each


def test_triangles_of_an_edited_mesh_are_counted_per_face_and_leave_out_holes():
    m = from_polygons([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)], [(0, 1, 2, 3)])
    c0 = m.face_corners(m.face_ids()[0])[0]
    m.insert_edge(c0, m.corner_next(m.corner_next(c0)))  # two triangles, ids moved
    a = mesh_arrays(m)
    vertices, faces = a.triangles()
    assert np.bincount(faces, minlength=len(a.face_ids)).tolist() == [
        0 if hole else size - 2 for hole, size in zip(a.face_hole, a.face_sizes, strict=True)]
    assert sorted(map(sorted, vertices.tolist())) == [[0, 1, 2], [0, 2, 3]]
    validate(m)


def test_face_colors_follow_the_face_order_and_are_read_only():
    m = cube()
    m.set_face_color(4, (0.0, 1.0, 0.0))
    a = mesh_arrays(m)
    assert a.face_colors is not None and not a.face_colors.flags.writeable
    assert a.face_colors[4].tolist() == [0.0, 1.0, 0.0]
    assert np.isnan(np.delete(a.face_colors, 4, axis=0)).all()
    assert mesh_arrays(cube()).face_colors is None


def test_face_colors_after_edits_follow_the_ids():
    m = cube()
    m.set_face_color(2, (0.5, 0.5, 0.5))
    e = m.insert_edge(8, 10)  # splits face 2; the new face (id 6) takes its colour
    m.delete_edge(m.insert_edge(0, 2))
    a = mesh_arrays(m)
    colored = a.face_ids[~np.isnan(a.face_colors[:, 0])].tolist()
    assert colored == sorted(m.edge_faces(e))


def test_concatenated_arrays_pad_parts_without_colours():
    coloured = cube()
    coloured.set_face_color(0, (1.0, 0.0, 0.0))
    joined = concatenate_arrays([mesh_arrays(cube()), mesh_arrays(coloured)])
    assert joined.face_colors is not None and joined.face_colors.shape == (12, 3)
    assert np.isnan(joined.face_colors[:6]).all()
    assert joined.face_colors[6].tolist() == [1.0, 0.0, 0.0]
    assert concatenate_arrays([mesh_arrays(cube())] * 2).face_colors is None
