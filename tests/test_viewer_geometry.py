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


def test_guide_lines_grid_spacing_and_axes() -> None:
    from livemod.viewer.renderer import AXIS_COLORS, GRID_COLOR, guide_lines

    bounds = np.array([[-1.0, -2.0, -1.0], [1.0, 3.0, 1.0]])
    (grid, grid_color), *axes = guide_lines(bounds)
    assert grid_color == GRID_COLOR and [color for _, color in axes] == list(AXIS_COLORS)
    assert np.all(grid[:, 1] == -2.0)  # on the ground under the scene
    xs = np.unique(grid[:, 0].round(9))
    step = float(np.diff(xs).min())
    assert step == pytest.approx(0.1)  # size 2 -> 20 cells of 0.1 across it
    assert xs.min() <= -1.0 and xs.max() >= 1.0  # it reaches past the scene
    for k, (ends, _) in enumerate(axes):
        assert ends[0].tolist() == [0.0, 0.0, 0.0]
        assert ends[1][k] == pytest.approx(5.0) and np.count_nonzero(ends[1]) == 1
    big = guide_lines(np.array([[0.0, 0.0, 0.0], [300.0, 1.0, 40.0]]))[0][0]
    assert float(np.diff(np.unique(big[:, 0].round(6))).min()) == pytest.approx(20.0)


def test_vertex_normals_are_unit_sums_of_the_triangles_around() -> None:
    from livemod.dlfl import mesh_arrays
    from livemod.viewer.geometry import build_geometry, vertex_normals

    geometry = build_geometry(mesh_arrays(cube()))
    normals = vertex_normals(geometry.positions, geometry.triangles)
    assert normals.dtype == np.float32 and normals.shape == (8, 3)
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, rtol=1e-6)
    # each corner of the cube points out along its diagonal, up to the fan's
    # uneven split of each square into two triangles
    outward = np.sign(geometry.positions)
    assert np.all(np.sign(normals) == outward)
    lonely = vertex_normals(np.zeros((2, 3)), np.zeros((0, 3), dtype=np.uint32))
    assert np.array_equal(lonely, np.zeros((2, 3), dtype=np.float32))


def test_bounds_leave_out_positions_that_are_not_finite() -> None:
    arrays = cube_with({0: (np.nan, 1.0, 1.0), 6: (-np.inf, -1.0, -1.0)})
    geometry = build_geometry(arrays)
    assert geometry.nonfinite == 2
    # vertex 0 was the only one at max x = 1 with y = z = 1; 6 the only -x, -y, -z
    assert geometry.bounds.tolist() == [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]
    assert np.isfinite(geometry.center).all() and geometry.radius == pytest.approx(3 ** 0.5)
    assert finite_bounds(np.full((3, 3), np.nan)).tolist() == [[0.0] * 3, [0.0] * 3]
    assert build_geometry(mesh_arrays(cube())).nonfinite == 0
