"""The batched quickhull (livemod.dlfl._quickhull) under hull_polygons for large sets:
its triangulation is a closed convex hull, and it verifies only the triangles
turning would reach as they are (test_hull.py compares the two walks)."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl._quickhull import quickhull, verified_triangles


def unit_sphere(n: int, seed: int) -> np.ndarray:
    points = np.random.default_rng(seed).normal(size=(n, 3))
    return points / np.linalg.norm(points, axis=1)[:, None]


def lattice(n: int) -> np.ndarray:
    return np.array([[x, y, z] for x in range(n) for y in range(n) for z in range(n)], float)


SETS = {
    "sphere": lambda: unit_sphere(500, 1),
    "cloud": lambda: np.random.default_rng(2).uniform(-1, 1, size=(800, 3)),
    "lattice": lambda: lattice(5),
    "ball and shell": lambda: np.concatenate([unit_sphere(200, 3),
                                              0.5 * unit_sphere(300, 4)]),
}


@pytest.mark.parametrize("name", sorted(SETS))
def test_the_triangles_close_a_convex_hull_of_every_point(name):
    points = SETS[name]()
    eps = 1e-9 * float(np.ptp(points, axis=0).max())
    found = quickhull(points, eps)
    assert found is not None
    tri, nbr = found
    # every side meets its reverse in the triangle across it
    f, j = np.divmod(np.arange(3 * len(tri)), 3)
    g = nbr[f, j]
    a, b = tri[f, j], tri[f, (j + 1) % 3]
    assert ((tri[g] == b[:, None]) & (np.roll(tri[g], -1, axis=1) == a[:, None])).any(axis=1).all()
    vertices = np.unique(tri)
    assert len(vertices) - 3 * len(tri) // 2 + len(tri) == 2  # a sphere
    # no point above any triangle by more than the tolerance
    p0, p1, p2 = (points[tri[:, k]] for k in range(3))
    normal = np.cross(p1 - p0, p2 - p0)
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    height = points @ normal.T - np.einsum("ij,ij->i", normal, p0)
    assert height.max() <= eps
    if name == "sphere":
        assert len(vertices) == len(points)


def test_the_same_points_give_the_same_triangles():
    points = unit_sphere(300, 5)
    first, second = quickhull(points, 2e-9), quickhull(points.copy(), 2e-9)
    assert first is not None and second is not None
    assert np.array_equal(first[0], second[0]) and np.array_equal(first[1], second[1])


def test_a_triangle_with_a_fourth_point_on_its_plane_is_left_to_turning():
    tetra = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    # the centre of face (1, 2, 3), lifted well under the tolerance
    points = np.concatenate([tetra, [[1 / 3, 1 / 3, 1 / 3 + 1e-12]]])
    found = quickhull(points, 1e-9)
    assert found is not None
    tri = found[0]
    ok = verified_triangles(points, tri, 1e-9, 1.0)
    clear = {tuple(sorted(t)) for t in tri[ok].tolist()}
    assert clear == {(0, 1, 2), (0, 1, 3), (0, 2, 3)}


def test_a_thin_triangle_is_left_to_turning():
    # a point 5 tolerances off the edge 0 - 1 (inside): sides nearly in line with it
    tetra = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    points = np.concatenate([tetra, [[0.5, 3.5e-9, 3.5e-9]]])
    found = quickhull(points, 1e-9)
    assert found is not None
    ok = verified_triangles(points, found[0], 1e-9, 1.0)
    assert {tuple(sorted(t)) for t in found[0][ok].tolist()} == {(0, 2, 3), (1, 2, 3)}
