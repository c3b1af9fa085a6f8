"""Convex hulls: the coplanar rule, closed outward faces, TopMod's convex hull and
its dual (exact counts, positions), degenerate input refused without a change, and
the triangle lookup for small point sets giving exactly what turning gives, and the
same hulls at every scale."""

from __future__ import annotations

import importlib
import warnings
from collections.abc import Callable
from unittest import mock

import numpy as np
import pytest

from livemod.dlfl import (
    DLFLError,
    Mesh,
    euler_characteristic,
    face_size_histogram,
    from_polygons,
    mesh_arrays,
    validate,
)
from livemod.dlfl._hull_faces import check_closed, flat_faces
from livemod.dlfl.analysis import face_normals, face_points, polygon_normal
from livemod.dlfl.build import point_cloud
from livemod.dlfl.errors import GeometryError, InvalidArgumentError
from livemod.dlfl.shapes import cube, dodecahedron, grid, icosahedron, octahedron, torus
from livemod.dlfl.subdivision import subdivide
from tests.meshes import assert_refused_quietly, assert_scales, point_sphere
from tests.meshes import tetrahedron as unit_tetrahedron
from tests.meshes import triangle as open_triangle

# the module, not the ``hull`` names a star import might shadow
hull = importlib.import_module("livemod.dlfl.hull")
hull_polygons, hull_triangles = hull.hull_polygons, hull.hull_triangles
convex_hull, dual_convex_hull = hull.convex_hull, hull.dual_convex_hull

CORNERS = np.array([[x, y, z] for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)], float)


def cycles(faces: list[list[int]]) -> list[tuple[int, ...]]:
    """Faces as cycles that start at their smallest index, sorted."""
    return sorted(tuple(f[f.index(min(f)):] + f[:f.index(min(f))]) for f in faces)


def assert_closed_and_outward(points: np.ndarray, polygons: list[list[int]]) -> None:
    """Each side is met once each way, V - E + F = 2, and every point lies on or
    below the plane of every polygon, whose corners turn counter-clockwise."""
    sides = [(a, b) for p in polygons for a, b in zip(p, p[1:] + p[:1], strict=True)]
    assert len(set(sides)) == len(sides) and all((b, a) in set(sides) for a, b in sides)
    used = {v for p in polygons for v in p}
    assert len(used) - len(sides) // 2 + len(polygons) == 2
    centre = points[sorted(used)].mean(axis=0)
    for p in polygons:
        q = points[p]
        normal = polygon_normal(q)
        assert normal @ (q[0] - centre) > 0  # outward
        assert ((points - q[0]) @ normal <= 1e-9).all()


def checked(mesh: Mesh) -> tuple[int, int, int]:
    validate(mesh)
    assert euler_characteristic(mesh) == 2
    return mesh.counts()


# -- hull_polygons and the coplanar rule ------------------------------------------------


def test_the_cube_corners_give_six_outward_quads():
    polygons = hull_polygons(CORNERS)
    assert sorted(len(p) for p in polygons) == [4] * 6
    assert_closed_and_outward(CORNERS, polygons)


def test_a_point_on_a_hull_edge_is_a_corner_of_both_faces_beside_it():
    points = np.concatenate([CORNERS, [[0.5, 1, 1]]])  # on the edge y = z = 1
    polygons = hull_polygons(points)
    assert sorted(len(p) for p in polygons) == [4, 4, 4, 4, 5, 5]
    assert sum(8 in p for p in polygons) == 2
    assert_closed_and_outward(points, polygons)


def test_points_on_one_edge_follow_each_other_along_it():
    along = [[0.5, 1, 1], [-0.5, 1, 1], [0.0, 1, 1]]
    points = np.concatenate([CORNERS, along])
    polygons = hull_polygons(points)
    assert_closed_and_outward(points, polygons)
    top = next(p for p in polygons if 8 in p and all(points[v][2] == 1 for v in p))
    xs = [points[v][0] for v in top if points[v][1] == 1 and points[v][2] == 1]
    assert xs in (sorted(xs), sorted(xs)[::-1]) and len(xs) == 5


def test_points_inside_a_face_or_the_hull_are_left_out():
    points = np.concatenate([CORNERS, [[0, 0, 0], [1, 0, 0], [0.2, -0.3, 1]]])
    assert cycles(hull_polygons(points)) == cycles(hull_polygons(CORNERS))


def test_a_repeated_point_is_left_out_for_the_earlier_one():
    points = np.concatenate([CORNERS[7:], CORNERS, [[1, 1, 1 + 1e-12]]])  # 0 = 8 = 9
    used = {v for p in hull_polygons(points) for v in p}
    assert used == set(range(8))


def test_every_edge_midpoint_of_the_cube_makes_six_octagons():
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8)
             if np.abs(CORNERS[a] - CORNERS[b]).sum() == 2]
    points = np.concatenate([CORNERS, [(CORNERS[a] + CORNERS[b]) / 2 for a, b in edges]])
    polygons = hull_polygons(points)
    assert sorted(len(p) for p in polygons) == [8] * 6
    assert_closed_and_outward(points, polygons)


def test_points_on_a_sphere_are_all_hull_vertices():
    rng = np.random.default_rng(7)
    points = rng.normal(size=(300, 3))
    points /= np.linalg.norm(points, axis=1)[:, None]
    polygons = hull_polygons(points)
    assert len(polygons) == 2 * 300 - 4 and {v for p in polygons for v in p} == set(range(300))
    assert_closed_and_outward(points, polygons)


def test_points_inside_a_cloud_are_left_out():
    rng = np.random.default_rng(3)
    points = np.concatenate([CORNERS * 2, rng.uniform(-1.9, 1.9, size=(60, 3))])
    assert cycles(hull_polygons(points)) == cycles(hull_polygons(CORNERS * 2))


@pytest.mark.parametrize("scale", [1e-200, 1e200])
def test_hull_polygons_do_not_depend_on_the_scale(scale):
    points = mesh_arrays(cube()).positions
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert cycles(hull_polygons(points * scale)) == cycles(hull_polygons(points))


def test_hull_polygons_do_not_depend_on_a_far_offset():
    points = np.concatenate([CORNERS, [[0.5, 1, 1]]])
    assert cycles(hull_polygons(points + 1e6)) == cycles(hull_polygons(points))


@pytest.mark.parametrize(("points", "message", "error"), [
    (CORNERS[:3], "at least 4 points, got 3", InvalidArgumentError),
    (np.zeros((0, 3)), "at least 4 points, got 0", InvalidArgumentError),
    (CORNERS[[0, 2, 4, 6]], "not all in one plane; these 4 points are coplanar", GeometryError),
    (np.array([[0, 0, 0], [1, 1, 1], [2, 2, 2], [3, 3, 3.0]]), "not all in one plane",
     GeometryError),
    (np.ones((5, 3)), "not all in one plane", GeometryError),
    (np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, np.nan]]), "finite points", GeometryError),
    (np.array([[-1.7e308, 0, 0], [1.7e308, 0, 0], [0, 1, 0], [0, 0, 1]]), "finite points",
     GeometryError),
    (np.zeros((4, 2)), r"\(n, 3\) points", InvalidArgumentError),
])
def test_degenerate_points_are_refused_by_name(points, message, error):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(error, match=message):
            hull_polygons(points)


def test_hull_triangles_of_the_cube_are_twelve_and_none_is_flat():
    triangles = hull_triangles(CORNERS)
    assert len(triangles) == 12
    assert_closed_and_outward(CORNERS, triangles)


def test_a_face_without_side_points_becomes_a_fan_from_its_last_corner():
    for poly in hull_polygons(CORNERS):
        fan = [[poly[-1], poly[i], poly[i + 1]] for i in range(len(poly) - 2)]
        assert set(cycles(fan)) <= set(cycles(hull_triangles(CORNERS)))


def test_triangles_of_faces_with_points_on_every_side_are_never_flat():
    tetra = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    mids = [(tetra[a] + tetra[b]) / 2 for a in range(4) for b in range(a + 1, 4)]
    points = np.concatenate([tetra, mids])
    triangles = hull_triangles(points)
    assert len(triangles) == 16  # each face: 6 points, 4 triangles
    assert_closed_and_outward(points, triangles)
    for t in triangles:
        q = points[t]
        assert np.linalg.norm(np.cross(q[1] - q[0], q[2] - q[0])) > 1e-6


# -- convex_hull ----------------------------------------------------------------------


def test_convex_hull_of_the_cube_is_twelve_triangles_as_topmod():
    m = cube()
    positions = m.positions_view()
    convex_hull(m)
    assert checked(m) == (8, 18, 12)
    assert face_size_histogram(m) == {3: 12}
    np.testing.assert_array_equal(m.positions_view(), positions)


@pytest.mark.parametrize(("make", "counts"), [
    (unit_tetrahedron, (4, 6, 4)),
    (octahedron, (6, 12, 8)),
    (icosahedron, (12, 30, 20)),
    (dodecahedron, (20, 54, 36)),  # 12 pentagons, 3 triangles each
])
def test_convex_hull_of_convex_solids_keeps_their_vertices(make, counts):
    m = make()
    convex_hull(m)
    assert checked(m) == counts and set(face_size_histogram(m)) == {3}


def test_every_vertex_of_a_torus_is_inside_or_on_its_hull():
    m = torus(8, 6)
    before = m.positions_view()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no re-orientation repairs either
        convex_hull(m)
    checked(m)
    normals = face_normals(m)
    for f, normal in zip(m.face_ids().tolist(), normals, strict=True):
        q = face_points(m, f)[0]
        assert ((before - q) @ normal <= 1e-9).all()
    # the hull's vertices are the outer ring's: the torus's own positions
    assert {tuple(p) for p in m.positions_view()} <= {tuple(p) for p in before}


def test_convex_hull_keeps_a_vertex_on_a_hull_edge():
    m = cube()
    m.subdivide_edge(m.edge_ids()[0])
    convex_hull(m)
    # two faces of the hull are pentagons (3 triangles each), four are quads
    assert checked(m) == (9, 21, 14)
    for f in m.face_ids().tolist():
        q = face_points(m, f)
        assert np.linalg.norm(np.cross(q[1] - q[0], q[2] - q[0])) > 1e-9


def test_convex_hull_of_a_huge_cube_is_the_scaled_unit_one():
    assert_scales(cube, lambda m, s: convex_hull(m), 1e300)


@pytest.mark.parametrize(("make", "message"), [
    (open_triangle, "at least 4 points, got 3"),
    (point_sphere, "at least 4 points, got 1"),
    (Mesh, "at least 4 points, got 0"),
    (lambda: grid(3, 3), "not all in one plane"),
    (lambda: from_polygons([[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]], [[0, 1, 2, 3]]),
     "not all in one plane"),
])
@pytest.mark.parametrize("op", [convex_hull, dual_convex_hull])
def test_degenerate_meshes_are_refused_and_left_unchanged(make, message, op):
    assert_refused_quietly(make(), op, message)


# -- dual_convex_hull --------------------------------------------------------------------


def test_dual_convex_hull_of_the_cube_is_an_octahedron_touching_its_corners():
    m = cube()
    dual_convex_hull(m)
    assert checked(m) == (6, 12, 8) and face_size_histogram(m) == {3: 8}
    expected = [[0, -3, 0], [3, 0, 0], [0, 0, 3], [-3, 0, 0], [0, 0, -3], [0, 3, 0]]
    assert sorted(map(tuple, m.positions_view())) == sorted(map(tuple, np.array(expected, float)))
    # each octahedron face passes through one cube corner (cube() is [-1, 1]^3)
    for f, normal in zip(m.face_ids().tolist(), face_normals(m), strict=True):
        q = face_points(m, f)[0]
        assert np.isclose(np.abs((CORNERS - q) @ normal).min(), 0)
        assert normal @ q > 0  # outward


@pytest.mark.parametrize(("make", "counts"), [
    (unit_tetrahedron, (4, 6, 4)),
    (octahedron, (8, 12, 6)),
    (icosahedron, (20, 30, 12)),
    (dodecahedron, (12, 30, 20)),
    (lambda: torus(8, 6), None),
])
def test_dual_convex_hull_swaps_vertices_and_faces(make, counts):
    m, hulled = make(), make()
    convex_hull(hulled)  # its vertices are the hull's
    faces = len(hull_polygons(hulled.positions_view()))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no re-orientation repairs either
        dual_convex_hull(m)
    v, _, f = checked(m)
    assert (v, f) == (faces, hulled.num_vertices)
    assert counts is None or m.counts() == counts


def test_the_dual_of_the_triangulated_hull_is_the_dual_of_the_cube():
    m, n = cube(), cube()
    convex_hull(m)
    dual_convex_hull(m)
    dual_convex_hull(n)
    assert m.counts() == n.counts() == (6, 12, 8)
    np.testing.assert_allclose(m.positions_view(), n.positions_view())


def test_the_dual_of_the_dual_of_the_cube_is_a_cube():
    m = cube()
    dual_convex_hull(m)
    dual_convex_hull(m)
    assert checked(m) == (8, 12, 6) and face_size_histogram(m) == {4: 6}
    p = m.positions_view()
    assert np.allclose(np.abs(p), np.abs(p[0]))  # a cube about the origin


def test_dual_convex_hull_of_a_huge_cube_is_the_scaled_unit_one():
    assert_scales(cube, lambda m, s: dual_convex_hull(m), 1e300)


def test_a_dual_beyond_the_float_range_is_refused():
    flat = from_polygons(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.3, 0.3, 3e-9]]) * 1e300,
                         [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])
    assert_refused_quietly(flat, dual_convex_hull, "beyond the float range")


# -- looking triangles up (up to hull._SMALL points) gives what turning gives --------------


def rotated(points: np.ndarray, seed: int) -> np.ndarray:
    """``points`` turned by a random rotation: coplanar up to rounding only."""
    q = np.linalg.qr(np.random.default_rng(seed).normal(size=(3, 3)))[0]
    return points @ q.T


def cube_with_midpoints() -> np.ndarray:
    """The cube's 8 corners and 12 edge midpoints (its faces: octagons)."""
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8)
             if np.abs(CORNERS[a] - CORNERS[b]).sum() == 2]
    return np.concatenate([CORNERS, [(CORNERS[a] + CORNERS[b]) / 2 for a, b in edges]])


def lattice(nx: int, ny: int, nz: int) -> np.ndarray:
    """The ``nx x ny x nz`` integer points, many in each plane and line."""
    return np.array([[x, y, z] for x in range(nx) for y in range(ny) for z in range(nz)], float)


def unit_sphere(n: int, seed: int) -> np.ndarray:
    """``n`` random points on the unit sphere: every face a triangle."""
    points = np.random.default_rng(seed).normal(size=(n, 3))
    return points / np.linalg.norm(points, axis=1)[:, None]


def column_joints() -> list[np.ndarray]:
    """The point sets ``columns`` takes the hull of (one per vertex) on a few meshes."""
    recorded = []

    def record(points: np.ndarray, tolerance: float = 1e-9) -> list[list[int]]:
        recorded.append(np.array(points))
        return hull_polygons(points, tolerance)

    wireframe = importlib.import_module("livemod.dlfl.wireframe")
    joints = importlib.import_module("livemod.dlfl._column_joints")
    with mock.patch.object(joints, "hull_polygons", record):
        for make, segments in [(lambda: torus(6, 5), 4), (cube, 5), (icosahedron, 3),
                               (octahedron, 6), (lambda: torus(5, 4), 8)]:
            wireframe.columns(make(), 0.1, segments)
    return recorded


def degenerate_sets() -> list[np.ndarray]:
    """Points with many in one plane or line, repeats, and their rotations."""
    rng = np.random.default_rng(11)
    centres = np.array([[0, 0, 1], [0, 0, -1], [1, 0, 0], [0, 1, 0], [0, 0, 0.0]])
    sets = [cube_with_midpoints(), np.concatenate([cube_with_midpoints(), centres]),
            lattice(3, 3, 3), lattice(4, 3, 2), lattice(2, 2, 5),
            np.concatenate([CORNERS[7:], CORNERS, [[1, 1, 1 + 1e-12]]])]
    sets += [rng.integers(-2, 3, size=(n, 3)).astype(float) for n in range(6, 33, 2)]
    return sets + [rotated(points, seed) for seed, points in enumerate(sets[:6])]


def near_tolerance_sets() -> list[np.ndarray]:
    """Lattices shaken by about the tolerance (many are refused, the same way),
    and points on a hull edge near a corner just off its line."""
    rng = np.random.default_rng(5)
    sets = [lattice(3, 3, 3) + rng.normal(size=(27, 3)) * scale * 2
            for scale in (3e-10, 1e-9, 3e-9, 1e-8) for _ in range(5)]
    tetra = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    for off in (0.3e-9, 3e-9, 3e-8):
        sets.append(np.concatenate([tetra, [[1e-3, off, 0], [2e-3, 0, off]]]))
        sets.append(np.concatenate([tetra, [[0.5, off, off]]]))
    return sets


POINT_SETS: dict[str, Callable[[], list[np.ndarray]]] = {
    "random spheres": lambda: [unit_sphere(n, seed) for n in range(4, 33) for seed in (1, 2)],
    "random clouds": lambda: [np.random.default_rng(n).uniform(-1, 1, size=(n, 3))
                              for n in range(4, 33)],
    "degenerate": degenerate_sets,
    "tiny, huge and far": lambda: [points * scale + offset
                                   for points in (cube_with_midpoints(), unit_sphere(20, 3))
                                   for scale in (1e-200, 1e200, 1.0)
                                   for offset in (0.0, 1e6 * scale)],
    "column joints": column_joints,
    "near the tolerance": near_tolerance_sets,
}


def hull_with(points: np.ndarray, small: int, monkeypatch: pytest.MonkeyPatch) -> object:
    """Polygons, normals (bit for bit) and triangles with the lookup up to ``small``
    points, or the error's message."""
    monkeypatch.setattr(hull, "_SMALL", small)
    try:
        found = hull._wrap_hull(points)
        triangles = hull_triangles(points)
    except DLFLError as error:
        return str(error)
    normals = [hull._resolved(found.points, n).tolist() for n in found.normals]
    return found.polygons, normals, triangles


@pytest.mark.parametrize("name", sorted(POINT_SETS))
def test_looking_triangles_up_gives_what_turning_gives(name, monkeypatch):
    sets = POINT_SETS[name]()
    assert sets and all(len(points) <= 64 for points in sets)
    for points in sets:
        assert hull_with(points, 64, monkeypatch) == hull_with(points, 0, monkeypatch)


def test_every_face_of_points_on_a_sphere_is_looked_up():
    points = unit_sphere(hull._SMALL, 4)
    extent = float(np.ptp(points, axis=0).max())
    table = hull._triangle_table(points, 1e-9 * extent, extent)
    assert len(table) == 3 * (2 * len(points) - 4)
    assert cycles([poly for poly, _ in table.values()]) == sorted(
        cycles(hull_polygons(points)) * 3)


def test_most_faces_of_a_column_joint_are_looked_up():
    points = column_joints()[0]
    extent = float(np.ptp(points, axis=0).max())
    looked_up = {tuple(poly) for poly, _ in hull._triangle_table(points, 1e-9 * extent,
                                                                 extent).values()}
    triangles = [p for p in hull_polygons(points) if len(p) == 3]
    assert triangles and looked_up == set(map(tuple, triangles))


def test_a_side_in_line_with_a_point_is_left_to_turning():
    tetra = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    # inside, 5 tolerances from the edge 0 - 1 (3.5 from either face beside it)
    points = np.concatenate([tetra, [[0.5, 3.5e-9, 3.5e-9]]])
    table = hull._triangle_table(points, 1e-9, 1.0)
    assert {tuple(sorted(poly)) for poly, _ in table.values()} == {(0, 2, 3), (1, 2, 3)}
    assert hull_polygons(points) == hull_polygons(tetra)


@pytest.mark.parametrize("polygons", [
    [[0, 2, 1], [0, 1, 3], [1, 2, 3]],  # a face missing
    [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 3, 2]],  # a face twice
    [[0, 1, 2], [0, 1, 3], [1, 2, 3], [0, 3, 2]],  # a face turned over
    [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2], [4, 6, 5], [4, 5, 7], [5, 6, 7], [4, 7, 6]],
    [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2], [0, 6, 5], [0, 5, 7], [5, 6, 7], [0, 7, 6]],
])
@pytest.mark.parametrize("check", [hull._check_closed,
                                   lambda polygons: check_closed(*flat_faces(polygons))],
                         ids=["small hulls", "large hulls"])
def test_polygons_that_are_no_closed_sphere_are_refused(polygons, check):
    check([[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]])  # a tetrahedron
    with pytest.raises(GeometryError, match="does not close up"):
        check(polygons)


@pytest.mark.parametrize("thickness", [0.0, 0.5, 0.99, 1.01, 2.0, 1e3, 1e5, 1e9])
def test_flat_points_are_told_as_by_their_least_squares_plane(thickness):
    rng = np.random.default_rng(int(thickness * 100) % 997)
    for n in (4, 16, 200):
        slab = np.column_stack([rng.uniform(-1, 1, size=(n, 2)), np.zeros(n)])
        slab[rng.integers(n), 2] = thickness * 1e-9
        points = rotated(slab, n)
        eps = 1e-9 * float(np.ptp(points, axis=0).max())
        centred = points - points.mean(axis=0)
        normal = np.linalg.svd(centred, full_matrices=False)[2][-1]
        flat = not np.abs(centred @ normal).max() > eps
        if flat:
            with pytest.raises(GeometryError, match="coplanar"):
                hull._check_not_flat(points, eps)
        else:
            hull._check_not_flat(points, eps)


# -- the same hull at every scale ----------------------------------------------------------

# every tolerance is relative to the points' extent (and points outside the float
# band are framed by a power of two), so a set scaled anywhere gives the same hull
SCALES = [1e-150, 1e-6, 1.0, 1e6, 1e150]


def hub_points() -> np.ndarray:
    """The hub of the multi-face handle on the unit cube's faces 0, 2, 4 (bottom,
    -y, +y) pushed out 0.5: 12 points, 6 quads and 2 hexagons."""
    square = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    bottom = np.c_[square, np.full(4, -0.5)]
    minus_y, plus_y = (np.c_[square[:, 0], np.full(4, y), square[:, 1]] for y in (-0.5, 1.5))
    return np.concatenate([bottom, minus_y, plus_y])


def quiet_hull(points: np.ndarray) -> list[list[int]]:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return hull_polygons(points)


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize(("make", "sizes"), [
    (hub_points, [4] * 6 + [6] * 2),
    (cube_with_midpoints, [8] * 6),
    (lambda: np.concatenate([CORNERS, [[0, 0, 0], [1, 0, 0], [0.5, 1, 1]]]), [4] * 4 + [5] * 2),
], ids=["hub", "midpoints", "inside-centre-edge"])
def test_hull_polygons_are_the_same_at_every_scale(make, sizes, scale):
    points = make()
    polygons = quiet_hull(points * scale)
    assert sorted(len(p) for p in polygons) == sizes
    assert cycles(polygons) == cycles(hull_polygons(points))
    assert_closed_and_outward(points, polygons)


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize(("height", "sizes"), [
    (0.1e-9, [4] * 6),  # well within the tolerance of the +x face: inside it, left out
    (4e-9, [3] * 4 + [4] * 5),  # well beyond it: the apex of a flat pyramid
])
def test_the_tolerance_is_relative_to_the_extent_at_every_scale(height, sizes, scale):
    # CORNERS span 2: the tolerance is 2e-9, the point is height * 2 off the face
    points = np.concatenate([CORNERS, [[1 + 2 * height, 0, 0]]])
    polygons = quiet_hull(points * scale)
    assert sorted(len(p) for p in polygons) == sizes
    assert cycles(polygons) == cycles(hull_polygons(points))


@pytest.mark.parametrize("scale", SCALES)
@pytest.mark.parametrize(("op", "counts", "sizes"), [
    (convex_hull, (8, 18, 12), {3: 12}),
    (dual_convex_hull, (6, 12, 8), {3: 8}),
], ids=["convex", "dual"])
def test_convex_hull_and_its_dual_are_the_same_at_every_scale(op, counts, sizes, scale):
    m = assert_scales(cube, lambda mesh, _: op(mesh), scale, rtol=1e-12)
    assert checked(m) == counts and face_size_histogram(m) == sizes


# -- walking a batched quickhull (over hull._LARGE points): turning's faces, sorted -------


def hull_walked(points: np.ndarray, large: int, monkeypatch: pytest.MonkeyPatch) -> object:
    """Polygons, ``(F, 3)`` normals and triangles with no triple lookup and the
    quickhull walked above ``large`` points, or the error's message."""
    monkeypatch.setattr(hull, "_LARGE", large)
    monkeypatch.setattr(hull, "_SMALL", 0)
    try:
        found = hull._wrap_hull(points)
        triangles = hull_triangles(points)
    except DLFLError as error:
        return str(error)
    normals = found.normals
    if not isinstance(normals, np.ndarray):
        normals = hull._resolved_all(found.points, normals)
    return found.polygons, normals, triangles


def larger_sets() -> list[np.ndarray]:
    """A few hundred points: spheres, clouds, lattices (squares, points on every
    edge), a rotated lattice, a smooth mesh and a subdivided cube's flat faces."""
    rng = np.random.default_rng(8)
    smooth, flat = cube(), cube()
    subdivide(smooth, "catmull-clark", levels=2)
    for _ in range(2):
        subdivide(flat, "linear-vertex")
    return [unit_sphere(300, 1), rng.uniform(-1, 1, size=(300, 3)), lattice(6, 5, 4),
            rotated(lattice(5, 5, 5), 3), smooth.positions_view(), flat.positions_view()]


def assert_same_faces_sorted(walked: object, turned: object) -> None:
    """``walked`` has ``turned``'s faces and normals, each face from its least
    index and the faces sorted, and triangles that cut those faces."""
    assert not isinstance(walked, str) and not isinstance(turned, str)
    (polygons, normals, triangles), (turned_polygons, turned_normals, _) = walked, turned
    assert list(map(tuple, polygons)) == cycles(polygons) == cycles(turned_polygons)
    rank = {cycles([poly])[0]: k for k, poly in enumerate(turned_polygons)}
    order = [rank[tuple(poly)] for poly in polygons]
    # the same planes to the tolerance: a triangle's is taken across its first side,
    # turning's across the side it was found across (near the tolerance, through
    # other points within it)
    np.testing.assert_allclose(normals, turned_normals[order], rtol=0, atol=1e-9)
    faces = [set(poly) for poly in polygons]
    assert len(triangles) == sum(len(poly) - 2 for poly in polygons)
    assert all(any(set(t) <= face for face in faces) for t in triangles)
    hull._check_closed(triangles)


@pytest.mark.parametrize("name", [*sorted(POINT_SETS), "larger"])
def test_walking_the_quickhull_gives_turnings_faces_sorted(name, monkeypatch):
    sets = larger_sets() if name == "larger" else POINT_SETS[name]()
    for points in sets:
        turned = hull_walked(points, 10**9, monkeypatch)
        walked = hull_walked(points, 3, monkeypatch)
        if isinstance(turned, str):
            if not isinstance(walked, str):
                continue  # turning could not close up; see the next test
            assert walked == turned
        else:
            assert_same_faces_sorted(walked, turned)


def test_where_turning_cannot_close_up_the_quickhull_triangles_are_the_hull(monkeypatch):
    # a lattice shaken by about the tolerance: turning finds faces that do not fit
    points = lattice(3, 3, 3) + np.random.default_rng(5).normal(size=(27, 3)) * 2e-9
    assert isinstance(hull_walked(points, 10**9, monkeypatch), str)
    monkeypatch.setattr(hull, "_LARGE", 3)
    polygons = hull_polygons(points)
    assert all(len(p) == 3 for p in polygons)
    hull._check_closed(polygons)
    mesh = point_cloud(points)
    convex_hull(mesh)
    validate(mesh)
    assert mesh.counts()[2] == len(polygons)
