"""A hull's faces as flat arrays (livemod.dlfl._hull_faces): the closure check
refuses every surface that is no sphere, and the rings of faces around each point
(the dual's faces) are the ones walked face by face from their definition."""

from __future__ import annotations

import importlib

import numpy as np
import pytest

from livemod.dlfl import mesh_arrays
from livemod.dlfl._hull_faces import check_closed, flat_faces, vertex_face_rings
from livemod.dlfl.errors import GeometryError
from livemod.dlfl.shapes import cube, torus

hull = importlib.import_module("livemod.dlfl.hull")


def walked_rings(polygons: list[list[int]]) -> list[list[int]]:
    """For each point (ascending), the faces around it from the first face it is a
    corner of: after face ``f`` comes the face with the side from the point to
    its predecessor in ``f``, walked one face at a time."""
    side_face = {(p, poly[(i + 1) % len(poly)]): f
                 for f, poly in enumerate(polygons) for i, p in enumerate(poly)}
    rings = []
    for p in sorted({p for poly in polygons for p in poly}):
        start = next(f for f, poly in enumerate(polygons) if p in poly)
        ring, f = [], start
        while not ring or f != start:
            ring.append(f)
            poly = polygons[f]
            f = side_face[(p, poly[poly.index(p) - 1])]
        rings.append(ring)
    return rings


def unit_sphere(n: int, seed: int) -> np.ndarray:
    points = np.random.default_rng(seed).normal(size=(n, 3))
    return points / np.linalg.norm(points, axis=1)[:, None]


LATTICE = np.array([[x, y, z] for x in range(4) for y in range(3) for z in range(5)], float)


@pytest.mark.parametrize("points", [unit_sphere(16, 1), unit_sphere(400, 2), LATTICE,
                                    cube().positions_view()],
                         ids=["16 on a sphere", "400 on a sphere", "lattice", "cube"])
def test_the_rings_are_the_faces_walked_around_each_point(points):
    polygons = hull.hull_polygons(points)
    faces, offsets = vertex_face_rings(*flat_faces(polygons))
    rings = [faces[a:b].tolist() for a, b in zip(offsets[:-1], offsets[1:], strict=True)]
    assert rings == walked_rings(polygons)


def test_a_point_with_many_faces_gets_its_whole_ring():
    # a double cone: 500 triangles around each apex, 4 around each rim point
    polygons = [[0, 2 + i, 2 + (i + 1) % 500] for i in range(500)]
    polygons += [[1, 2 + (i + 1) % 500, 2 + i] for i in range(500)]
    check_closed(*flat_faces(polygons))
    faces, offsets = vertex_face_rings(*flat_faces(polygons))
    assert np.diff(offsets).tolist() == [500, 500] + [4] * 500
    rings = [faces[a:b].tolist() for a, b in zip(offsets[:-1], offsets[1:], strict=True)]
    assert rings == walked_rings(polygons)


def test_no_faces_are_no_hull():
    with pytest.raises(GeometryError, match="does not close up"):
        check_closed(*flat_faces([]))


def test_a_closed_torus_is_refused():
    arrays = mesh_arrays(torus(6, 5))
    with pytest.raises(GeometryError, match="does not close up"):
        check_closed(arrays.corner_vertex, arrays.face_offsets)
