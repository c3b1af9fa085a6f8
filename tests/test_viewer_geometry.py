"""The render buffers (GL-free): fan triangles, pick ids, guide lines, vertex normals."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import from_polygons, mesh_arrays
from livemod.dlfl.shapes import cube, grid
from livemod.viewer.geometry import build_geometry, decode_pick, fan_triangles, finite_bounds

from .viewer_support import cube_with


def test_fans_cover_every_face_and_skip_holes() -> None:
    arrays = mesh_arrays(grid(3, 2))
    triangles, tri_face, _ = fan_triangles(arrays)
    solid = ~arrays.face_hole
    assert arrays.face_hole.any()
    assert len(triangles) == int((arrays.face_sizes[solid] - 2).sum())
    assert set(tri_face.tolist()) == set(np.flatnonzero(solid).tolist())
    # every triangle's vertices belong to its face
    for (a, b, c), face in zip(triangles.tolist(), tri_face.tolist(), strict=True):
        ring = arrays.corner_vertex[arrays.face_offsets[face]:arrays.face_offsets[face + 1]]
        assert {a, b, c} <= set(ring.tolist())


def test_geometry_of_a_pentagon_and_a_triangle() -> None:
    mesh = from_polygons([(0, 0, 0), (1, 0, 0), (1.5, 1, 0), (0.5, 1.6, 0), (-0.5, 1, 0)],
                         [(0, 1, 2, 3, 4)])
    geometry = build_geometry(mesh_arrays(mesh))
    assert geometry.positions.dtype == np.float32
    assert geometry.triangles.tolist() == [[0, 1, 2], [0, 2, 3], [0, 3, 4]]
    assert geometry.lines.shape == (5, 2)
    np.testing.assert_allclose(geometry.bounds, [[-0.5, 0, 0], [1.5, 1.6, 0]])


def test_pick_ids_decode() -> None:
    assert decode_pick(0) is None
    assert decode_pick((2 << 28) | 13) == (2, 12)


def test_crease_shading_is_flat_across_sharp_edges_and_smooth_across_the_others() -> None:
    from livemod.dlfl import face_normals, mesh_arrays
    from livemod.dlfl.shapes import cube, icosahedron
    from livemod.viewer.geometry import build_geometry, crease_shading

    arrays = mesh_arrays(cube())
    shading = crease_shading(arrays)                   # 90 degrees: every edge is sharp
    assert shading.normals.dtype == np.float32 and len(shading.positions) == 24
    faces = build_geometry(arrays).triangle_face
    normals = face_normals(arrays)[faces]
    for k in range(3):                                 # each corner has its face's normal
        np.testing.assert_allclose(shading.normals[shading.triangles[:, k]], normals,
                                   atol=1e-6)
    geometry = build_geometry(arrays)
    np.testing.assert_array_equal(shading.positions[shading.triangles],
                                  geometry.positions[geometry.triangles])
    rounded = crease_shading(arrays, crease_angle=91.0)  # no edge sharp: one per vertex
    assert len(rounded.positions) == 8
    np.testing.assert_allclose(np.abs(rounded.normals), 1 / np.sqrt(3), atol=1e-6)
    ball = mesh_arrays(icosahedron())                    # 41.8 degrees apart: smooth
    smooth = crease_shading(ball)
    assert len(smooth.positions) == 12
    np.testing.assert_allclose(np.einsum("ij,ij->i", smooth.normals,
                                         smooth.positions / np.linalg.norm(
                                             smooth.positions, axis=1, keepdims=True)),
                               1.0, atol=1e-6)
    assert len(crease_shading(ball, crease_angle=40.0).positions) == 60


def test_crease_sectors_split_a_vertex_between_its_sharp_edges() -> None:
    from livemod.viewer.geometry import _sectors

    # rings: 0..3 with one sharp link (1 -> 2), 4..6 all smooth, 7..8 all sharp
    smooth_to_next = np.array([1, 0, 1, 1, 1, 1, 1, 0, 0], dtype=bool)
    sectors = _sectors(smooth_to_next, np.array([0, 4, 7, 9]))
    assert sectors.tolist() == [0, 0, 0, 0, 3, 3, 3, 1, 2]


def test_bounds_leave_out_positions_that_are_not_finite() -> None:
    arrays = cube_with({0: (np.nan, 1.0, 1.0), 6: (-np.inf, -1.0, -1.0)})
    geometry = build_geometry(arrays)
    assert geometry.nonfinite == 2
    # vertex 0 was the only one at max x = 1 with y = z = 1; 6 the only -x, -y, -z
    assert geometry.bounds.tolist() == [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
    assert np.isfinite(geometry.center).all() and geometry.radius == pytest.approx(3 ** 0.5)
    assert finite_bounds(np.full((3, 3), np.nan)).tolist() == [[0.0] * 3, [0.0] * 3]
    assert build_geometry(mesh_arrays(cube())).nonfinite == 0


def test_visible_labels_are_those_in_view_nearest_the_eye_first() -> None:
    from livemod.viewer.camera import Camera
    from livemod.viewer.geometry import visible_labels

    camera = Camera(yaw=0.0, pitch=0.0)
    camera.fit_points(np.array([[-1.0, -1.0, 0.0], [1.0, 1.0, 0.0]]), 1.0)
    view = camera.view_projection(1.0)
    eye = camera.eye()
    anchors = np.array([[0.0, 0.0, 0.0],                 # in view
                        [0.5, 0.5, 0.5],                 # in view, nearer the eye
                        [50.0, 0.0, 0.0],                # beside the view
                        eye + (eye - [0.0, 0.0, 0.0]),   # behind the eye
                        [-0.5, 0.2, -0.5]])              # in view, farther
    columns = anchors.T.astype(np.float32)
    assert visible_labels(columns, view, 10).tolist() == [0, 1, 4]
    assert visible_labels(columns, view, 2).tolist() == [0, 1]
    assert visible_labels(columns, None, 2).tolist() == [0, 1]
    assert visible_labels(np.zeros((3, 0), np.float32), view, 5).tolist() == []


def test_face_colours_are_packed_as_rgba8_with_alpha_for_the_faces_that_have_one():
    m = cube()
    m.set_face_color(1, (1.0, 0.5, 0.0))
    packed = build_geometry(mesh_arrays(m)).face_colors
    assert packed.dtype == np.uint32 and len(packed) == 6
    assert packed[1] == 255 | 128 << 8 | 0 << 16 | 255 << 24
    assert (np.delete(packed, 1) == 0).all()
    assert len(build_geometry(mesh_arrays(cube())).face_colors) == 0


def test_label_anchors_hold_the_float32_columns_of_the_labelled() -> None:
    from livemod.viewer.geometry import label_anchors

    arrays = mesh_arrays(grid(3, 2))                   # 6 faces and the boundary's hole
    holes = np.flatnonzero(arrays.face_hole)
    assert len(holes) == 1 and len(arrays.face_ids) == 7
    made = label_anchors(arrays, ("faces", "edges", "vertices"))
    faces, edges, vertices = made["faces"], made["edges"], made["vertices"]
    assert faces.labelled.tolist() == [i for i in range(7) if i != holes[0]]
    assert edges.labelled.tolist() == list(range(len(arrays.edge_ids)))
    assert np.array_equal(vertices.points, arrays.positions)
    assert np.allclose(edges.points, arrays.positions[arrays.edge_vertices].mean(axis=1))
    for anchors in made.values():
        assert anchors.columns.dtype == np.float32 and anchors.columns.flags.c_contiguous
        assert np.array_equal(anchors.columns,
                              anchors.points[anchors.labelled].T.astype(np.float32))
    assert list(label_anchors(arrays, ("edges",))) == ["edges"]
