"""Hulls of more than hull._LARGE points (the batched quickhull under the wrapping),
at their real sizes: the vertex sets and volumes of scipy's Qhull (an independent
implementation), every point inside, faces sorted from their least index and the
same on every call, convex_hull and its dual valid closed convex meshes, and
degenerate sets refused as small ones are."""

from __future__ import annotations

import importlib
from collections.abc import Callable

import numpy as np
import pytest
from scipy.spatial import ConvexHull

from livemod.dlfl import Mesh, euler_characteristic, mesh_arrays, validate
from livemod.dlfl.build import point_cloud
from livemod.dlfl.errors import GeometryError
from tests.meshes import assert_refused_quietly

hull = importlib.import_module("livemod.dlfl.hull")


def unit_sphere(n: int, seed: int) -> np.ndarray:
    """``n`` random points on the unit sphere: every one a hull vertex."""
    points = np.random.default_rng(seed).normal(size=(n, 3))
    return points / np.linalg.norm(points, axis=1)[:, None]


def rotation(seed: int) -> np.ndarray:
    """A random ``(3, 3)`` rotation."""
    return np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))[0]


def lattice(n: int) -> np.ndarray:
    """The ``n x n x n`` integer points: squares with points on every edge."""
    axis = np.arange(n, dtype=float)
    return np.stack(np.meshgrid(axis, axis, axis, indexing="ij"), axis=-1).reshape(-1, 3)


# points in general position: no four of them on one plane but by chance
GENERAL = {
    "sphere": lambda: unit_sphere(3000, 1),
    "cube cloud": lambda: np.random.default_rng(2).uniform(-1, 1, size=(6000, 3)),
    "gaussian cloud": lambda: np.random.default_rng(3).normal(size=(5000, 3)),
    "ball in a shell": lambda: np.concatenate([unit_sphere(1500, 4),
                                               0.9 * unit_sphere(1500, 5)]),
    "flat ellipsoid": lambda: (unit_sphere(3000, 6) * [1.0, 0.1, 0.01]) @ rotation(7).T,
}

# many points on one plane, line or point
DEGENERATE = {
    "lattice": lambda: lattice(11),
    "rotated lattice": lambda: lattice(11) @ rotation(8).T,
    "rounded sphere": lambda: np.round(unit_sphere(4000, 9), 2),
    "cylinder": lambda: np.concatenate([
        np.stack([np.cos(t := np.linspace(0, 2 * np.pi, 600, endpoint=False)), np.sin(t),
                  np.full(600, z)], axis=1) for z in (-1.0, 1.0)]),
}


def volume(points: np.ndarray, polygons: list[list[int]]) -> float:
    """The volume inside closed outward ``polygons``, each cut into a fan."""
    centre = points.mean(axis=0)
    total = 0.0
    for poly in polygons:
        a, rest = points[poly[0]] - centre, points[poly[1:]] - centre
        total += float(np.linalg.det(np.stack([np.broadcast_to(a, rest[:-1].shape),
                                               rest[:-1], rest[1:]], axis=1)).sum())
    return total / 6.0


def heights(points: np.ndarray, corners: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """``(n,)``: how far each point lies above the highest plane of the polygons
    (``corners`` of polygon ``f`` at ``offsets[f]:offsets[f + 1]``), each plane
    through the polygon's centroid along its Newell normal."""
    starts = offsets[:-1]
    following = np.arange(1, len(corners) + 1)
    following[offsets[1:] - 1] = starts
    here, there = points[corners], points[corners[following]]
    normals = np.add.reduceat(np.cross(here, there), starts, axis=0)
    normals /= np.linalg.norm(normals, axis=1)[:, None]
    centres = np.add.reduceat(here, starts, axis=0) / np.diff(offsets)[:, None]
    levels = np.einsum("ij,ij->i", normals, centres)
    top = np.full(len(points), -np.inf)
    for start in range(0, len(normals), 2000):
        block = slice(start, start + 2000)
        top = np.maximum(top, (points @ normals[block].T - levels[block]).max(axis=1))
    return top


def flat(polygons: list[list[int]]) -> tuple[np.ndarray, np.ndarray]:
    """``(corners, offsets)`` of ``polygons``."""
    offsets = np.cumsum([0, *map(len, polygons)])
    return np.array([v for poly in polygons for v in poly]), offsets


@pytest.mark.parametrize("name", sorted(GENERAL))
def test_a_large_hull_has_qhulls_vertices_and_volume(name):
    points = GENERAL[name]()
    polygons = hull.hull_polygons(points)
    qhull = ConvexHull(points)
    assert sorted({v for poly in polygons for v in poly}) == sorted(qhull.vertices.tolist())
    assert volume(points, polygons) == pytest.approx(qhull.volume, rel=1e-9)


@pytest.mark.parametrize("name", sorted(DEGENERATE))
def test_a_large_degenerate_hull_has_qhulls_corners_and_volume(name):
    points = DEGENERATE[name]()
    polygons = hull.hull_polygons(points)
    qhull = ConvexHull(points)
    ours = {v for poly in polygons for v in poly}
    # Qhull's vertices are the corners (of repeated points, any copy); ours add the
    # points on hull edges
    assert set(map(tuple, points[qhull.vertices])) <= set(map(tuple, points[sorted(ours)]))
    assert volume(points, polygons) == pytest.approx(qhull.volume, rel=1e-9)
    extent = float(np.ptp(points, axis=0).max())
    # each of ours lies on a face of Qhull's hull
    on_a_facet = np.abs(points[sorted(ours)] @ qhull.equations[:, :3].T
                        + qhull.equations[:, 3]).min(axis=1)
    assert on_a_facet.max() <= 1e-9 * extent


@pytest.mark.parametrize("name", sorted(GENERAL | DEGENERATE))
def test_every_point_lies_inside_a_large_hull(name):
    points = (GENERAL | DEGENERATE)[name]()
    extent = float(np.ptp(points, axis=0).max())
    assert heights(points, *flat(hull.hull_polygons(points))).max() <= 1e-9 * extent


def test_a_large_hulls_faces_come_sorted_from_their_least_index():
    points = unit_sphere(4000, 10)
    polygons = hull.hull_polygons(points)
    assert all(poly[0] == min(poly) for poly in polygons)
    firsts = [(poly[0], poly[1]) for poly in polygons]
    assert firsts == sorted(firsts) and len(set(firsts)) == len(firsts)
    # the same points give the same faces, whatever came before
    hull.hull_polygons(unit_sphere(3000, 11))
    assert hull.hull_polygons(points.copy()) == polygons


def test_the_faces_of_a_large_lattice_are_its_six_sides_with_their_edge_points():
    polygons = hull.hull_polygons(lattice(11))
    # a side: 4 corners and 9 points on each of its 4 edges, nothing from inside it
    assert sorted(map(len, polygons)) == [40] * 6
    assert all(poly[0] == min(poly) for poly in polygons)


def hulled(op: Callable[[Mesh], None], points: np.ndarray) -> Mesh:
    """``op`` on a point cloud of ``points``, the result valid and a sphere."""
    mesh = point_cloud(points)
    op(mesh)
    validate(mesh)
    assert euler_characteristic(mesh) == 2
    return mesh


def test_convex_hull_of_a_large_mesh_is_valid_closed_and_sorted():
    points = unit_sphere(3000, 12)
    mesh = hulled(hull.convex_hull, points)
    assert mesh.counts() == (3000, 3 * 3000 - 6, 2 * 3000 - 4)
    np.testing.assert_array_equal(mesh.positions_view(), points)
    arrays = mesh_arrays(mesh)
    faces = arrays.corner_vertex.reshape(-1, 3).tolist()
    firsts = [(min(face), face[(face.index(min(face)) + 1) % 3]) for face in faces]
    assert firsts == sorted(firsts)


def test_the_dual_of_a_large_hull_is_valid_closed_and_convex():
    mesh = hulled(hull.dual_convex_hull, unit_sphere(3000, 13))
    assert mesh.counts() == (2 * 3000 - 4, 3 * 3000 - 6, 3000)
    arrays = mesh_arrays(mesh)
    dual = arrays.positions
    extent = float(np.ptp(dual, axis=0).max())
    # convex: every vertex lies on or below every face
    assert heights(dual, arrays.corner_vertex, arrays.face_offsets).max() <= 1e-9 * extent


def test_repeats_and_points_within_the_tolerance_change_no_face_of_a_large_hull():
    points = unit_sphere(1500, 14)
    # repeats, and copies less than the tolerance inside: the earlier point stands
    crowded = np.concatenate([points, points[300::-1], points[300:600] * (1 - 1e-11)])
    assert hull.hull_polygons(crowded) == hull.hull_polygons(points)


@pytest.mark.parametrize(("points", "message"), [
    (np.c_[np.random.default_rng(15).uniform(-1, 1, size=(2000, 2)), np.zeros(2000)],
     "not all in one plane"),
    (np.c_[np.random.default_rng(16).uniform(-1, 1, size=(2000, 2)),
           np.random.default_rng(17).normal(size=2000) * 1e-12], "not all in one plane"),
    (np.outer(np.linspace(-1, 1, 2000), [1.0, 2.0, 3.0]), "not all in one plane"),
    (np.tile([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]], (700, 1)), "not all in one plane"),
], ids=["plane", "plane within the tolerance", "line", "three points repeated"])
@pytest.mark.parametrize("op", [hull.convex_hull, hull.dual_convex_hull])
def test_large_degenerate_sets_are_refused_and_left_unchanged(points, message, op):
    with pytest.raises(GeometryError, match=message):
        hull.hull_polygons(points)
    assert_refused_quietly(point_cloud(points), op, message)
