"""TopMod's normals (livemod.dlfl.normals): the rule on non-planar faces, and the
operations that move along a normal landing where the rule puts them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from livemod.dlfl import shapes
from livemod.dlfl._vectors import cross_rows
from livemod.dlfl.analysis import corner_normals, face_normals, genus
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.build import from_polygons
from livemod.dlfl.extrusion import extrude, extrude_fan
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.normals import (
    inset_offsets,
    polygon_normal,
    reversed_rings,
    ring_normals,
    small_polygon_normal,
)
from livemod.dlfl.rind import crust
from livemod.dlfl.subdivision import subdivide
from livemod.dlfl.validate import validate

# a unit square with corner 2 lifted by 1: no two corners share a plane
LIFTED_QUAD = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 1.0], [0.0, 1.0, 0.0]]
# (next - p) x (prev - p) at each corner, worked out by hand
LIFTED_QUAD_CROSSES = [(0, 0, 1), (0, -1, 1), (-1, -1, 1), (-1, 0, 1)]


def unit(v: object) -> np.ndarray:
    arr = np.asarray(v, dtype=float)
    return arr / np.linalg.norm(arr)


def rule(points: list[list[float]]) -> tuple[np.ndarray, np.ndarray]:
    """TopMod's rule written out corner by corner for the tests: ``(corner
    normals (k, 3), face normal (3,))`` of one polygon."""
    p = np.asarray(points, dtype=float)
    k = len(p)
    newell = sum(np.cross(p[i], p[(i + 1) % k]) for i in range(k))
    normals, winged = [], []
    for i in range(k):
        ahead, behind = p[(i + 1) % k] - p[i], p[i - 1] - p[i]
        ua, ub = unit(ahead), unit(behind)
        winged.append(k > 3 and np.linalg.norm(ua + ub) < 1e-5)
        cross = np.cross(ahead, behind)
        n = unit(cross) if np.linalg.norm(cross) > 0 else np.zeros(3)
        if k > 3 and np.linalg.norm(np.cross(ua, ub)) >= 1e-5 and cross @ newell < 0:
            n = -n
        normals.append(n)
    for i in (i for i in range(k) if winged[i]):
        for step in range(1, k // 2 + 1):
            near = [j for j in ((i - step) % k, (i + step) % k) if not winged[j]]
            if near:
                normals[i] = normals[near[0]]
                break
    return np.array(normals), unit(sum(normals))


def polygon_mesh(points: list[list[float]]) -> Mesh:
    """A two-sided polygon: the front face is face 0."""
    return from_polygons(np.array(points), [list(range(len(points))),
                                            list(range(len(points)))[::-1]])


def all_forms(points: list[list[float]]) -> list[np.ndarray]:
    """The face normal of ``points`` by every entry point livemod has."""
    k = len(points)
    mesh = polygon_mesh(points)
    return [np.array(small_polygon_normal(points)), polygon_normal(np.array(points)),
            ring_normals(np.array(points), np.arange(k), np.array([0, k])).face[0],
            face_normals(mesh)[0]]


# -- the rule, pinned by hand ---------------------------------------------------------

def test_a_non_planar_quad_has_the_normalised_sum_of_its_corner_normals() -> None:
    expected_corners = np.array([unit(c) for c in LIFTED_QUAD_CROSSES])
    s2, s3 = 1 / math.sqrt(2), 1 / math.sqrt(3)
    expected_face = unit([-(s2 + s3), -(s2 + s3), 1 + 2 * s2 + s3])
    np.testing.assert_allclose(corner_normals(polygon_mesh(LIFTED_QUAD))[:4],
                               expected_corners, atol=1e-15)
    for normal in all_forms(LIFTED_QUAD):
        np.testing.assert_allclose(normal, expected_face, atol=1e-15)
    # not the Newell normal (-1, -1, 2) / sqrt 6, which this face would give
    assert np.linalg.norm(expected_face - unit([-1, -1, 2])) > 0.05


def test_a_concave_corner_is_flipped_and_only_it() -> None:
    # an L-shaped hexagon with its inner corner (3) lifted by 0.5
    ell = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0.5], [1, 2, 0], [0, 2, 0]]
    rn = ring_normals(np.array(ell, dtype=float), np.arange(6), np.array([0, 6]))
    assert rn.concave.tolist() == [False, False, False, True, False, False]
    # at (1, 1, .5): next - p = (0, 1, -.5), prev - p = (1, 0, -.5), cross (-.5, -.5, -1)
    np.testing.assert_allclose(rn.corner[3], unit([0.5, 0.5, 1]), atol=1e-15)
    np.testing.assert_allclose(rn.corner[0], [0, 0, 1], atol=1e-15)
    for normal in all_forms(ell):
        np.testing.assert_allclose(normal, unit(rn.corner.sum(axis=0)), atol=1e-15)


def test_a_flat_l_shape_has_one_normal_everywhere() -> None:
    ell = [[0, 0, 0], [2, 0, 0], [2, 1, 0], [1, 1, 0], [1, 2, 0], [0, 2, 0]]
    rn = ring_normals(np.array(ell, dtype=float), np.arange(6), np.array([0, 6]))
    np.testing.assert_allclose(rn.corner, np.tile([0.0, 0.0, 1.0], (6, 1)), atol=1e-15)
    assert rn.concave.tolist() == [False, False, False, True, False, False]


def test_a_straight_corner_copies_its_nearest_neighbour_the_previous_on_a_tie() -> None:
    # a square 2 across, lifted at (2, 2), with a point half way along its first side
    pts = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 2, 1], [0, 2, 0]]
    rn = ring_normals(np.array(pts, dtype=float), np.arange(5), np.array([0, 5]))
    assert rn.winged.tolist() == [False, True, False, False, False]
    np.testing.assert_allclose(rn.corner[1], [0, 0, 1], atol=1e-15)  # corner 0's
    # at (2, 0, 0): next - p = (0, 2, 1), prev - p = (-1, 0, 0): cross (0, -1, 2)
    np.testing.assert_allclose(rn.corner[2], unit([0, -1, 2]), atol=1e-15)
    for normal in all_forms(pts):
        np.testing.assert_allclose(normal, unit(rn.corner.sum(axis=0)), atol=1e-15)
    # walked the other way round, the previous neighbour is the lifted side's corner
    back = pts[::-1]
    rb = ring_normals(np.array(back, dtype=float), np.arange(5), np.array([0, 5]))
    np.testing.assert_allclose(rb.corner[3], rb.corner[2], atol=0)
    np.testing.assert_allclose(rb.corner[3], -unit([0, -1, 2]), atol=1e-15)


def test_two_straight_corners_in_a_row_copy_their_own_nearest() -> None:
    pts = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0], [3, 2, 1], [0, 2, 0]]
    rn = ring_normals(np.array(pts, dtype=float), np.arange(6), np.array([0, 6]))
    assert rn.source.tolist() == [0, 0, 3, 3, 4, 5]
    assert all(np.allclose(n, rule(pts)[1]) for n in all_forms(pts))


def test_a_triangle_is_never_concave_and_a_straight_one_has_no_normal() -> None:
    assert all_forms([[0, 0, 0], [1, 0, 0], [0, 1, 0]])[0].tolist() == [0, 0, 1]
    for normal in all_forms([[0, 0, 0], [1, 0, 0], [2, 0, 0]]):
        assert normal.tolist() == [0, 0, 0]


@pytest.mark.parametrize("scale, offset", [(1e-150, 0.0), (1e150, 0.0), (1.0, 1e9),
                                           (2.0**-1060, 0.0)])
def test_scale_and_offset_do_not_change_the_normal(scale: float, offset: float) -> None:
    for pts in (LIFTED_QUAD, [[0, 0, 0], [1, 0, 0], [2, 0, 0], [2, 2, 1], [0, 2, 0]]):
        moved = (np.array(pts, dtype=float) * scale + offset).tolist()
        for normal in all_forms(moved):
            np.testing.assert_allclose(normal, rule(pts)[1], atol=1e-12)


def test_turning_the_mesh_turns_its_normals() -> None:
    # TopMod's concave test projected each face on a coordinate plane, so turning
    # a warped face could flip corners; livemod's does not depend on the axes
    mesh = shapes.genus3_hexa(1)
    a = mesh_arrays(mesh)
    turn, _ = np.linalg.qr(np.random.default_rng(3).normal(size=(3, 3)))
    turned = ring_normals(a.positions @ turn.T, a.corner_vertex, a.face_offsets)
    np.testing.assert_allclose(turned.face, face_normals(a) @ turn.T, atol=1e-12)
    assert (turned.concave == ring_normals(a.positions, a.corner_vertex,
                                           a.face_offsets).concave).all()


def split_spherical_cube() -> Mesh:
    """The spherical cube with every third edge split at its midpoint: warped
    quads and pentagons with straight corners."""
    mesh = shapes.spherical_cube()
    for edge in mesh.edge_ids().tolist()[::3]:
        mesh.subdivide_edge(edge)
    return mesh


@pytest.mark.parametrize("make", [split_spherical_cube, lambda: shapes.genus3_hexa(1)])
def test_every_form_agrees_with_the_rule_on_every_face(make: object) -> None:
    a = mesh_arrays(make())  # type: ignore[operator]
    faces = face_normals(a)
    corners = corner_normals(a)
    for f in range(len(a.face_ids)):
        ring = slice(a.face_offsets[f], a.face_offsets[f + 1])
        points = a.positions[a.corner_vertex[ring]].tolist()
        want_corners, want_face = rule(points)
        np.testing.assert_allclose(corners[ring], want_corners, atol=1e-12)
        np.testing.assert_allclose(faces[f], want_face, atol=1e-12)
        np.testing.assert_allclose(small_polygon_normal(points), want_face, atol=1e-12)


def test_reversed_rings_reverse_every_ring() -> None:
    back = reversed_rings(np.array([0, 3, 4, 8]))
    assert back.tolist() == [2, 1, 0, 3, 7, 6, 5, 4]
    assert back[back].tolist() == list(range(8))


# -- operations land where the rule puts them --------------------------------------

def face_points(mesh: Mesh, face: int) -> list[list[float]]:
    return [mesh.position(v).tolist() for v in mesh.face_vertices(face)]


def has_point(mesh: Mesh, point: np.ndarray, tol: float = 1e-12) -> bool:
    a = mesh_arrays(mesh)
    return bool(np.linalg.norm(a.positions - point, axis=1).min() < tol)


@pytest.mark.parametrize("face", [0, 17, 40])
def test_stellate_and_cubical_extrusions_move_along_the_rule(face: int) -> None:
    mesh = shapes.spherical_cube()
    points = np.array(face_points(mesh, face))
    normal = rule(points.tolist())[1]
    fan = extrude_fan(mesh, face, "stellate", 0.5)
    validate(mesh)
    apex = set.intersection(*(set(mesh.face_vertices(f)) for f in fan)).pop()
    np.testing.assert_allclose(mesh.position(apex), points.mean(axis=0) + 0.5 * normal,
                               atol=1e-15)

    mesh = shapes.spherical_cube()
    end = extrude(mesh, face, "cubical", 0.5)
    validate(mesh)
    np.testing.assert_allclose(face_points(mesh, end), points + 0.5 * normal, atol=1e-15)
    assert genus(mesh) == 0


def test_star_lifts_each_face_centre_along_the_rule() -> None:
    mesh = shapes.spherical_cube()
    centres = [np.mean(face_points(mesh, f), axis=0) + 0.3 * rule(face_points(mesh, f))[1]
               for f in mesh.face_ids().tolist()]
    subdivide(mesh, "star", offset=0.3)
    validate(mesh)
    assert mesh.counts() == (98 + 96 + 384, 192 * 9, 96 * 12) and genus(mesh) == 0
    assert all(has_point(mesh, c) for c in centres)


def test_fractal_lifts_each_face_centre_along_the_rule() -> None:
    mesh = shapes.spherical_cube()
    expected = []
    for f in mesh.face_ids().tolist():
        p = np.array(face_points(mesh, f))
        mids = (p + np.roll(p, -1, axis=0)) / 2  # the split face's corners 1, 3, 5, 7
        l1 = np.linalg.norm(mids[0] - mids[2]) / 2  # to the opposite midpoint
        l2 = np.linalg.norm(mids[0] - mids[1])
        expected.append(p.mean(axis=0) + math.sqrt(l2 * l2 - l1 * l1) * rule(p.tolist())[1])
    subdivide(mesh, "fractal", offset=1.0)
    validate(mesh)
    assert mesh.counts() == (98 + 192 + 96, 192 * 6, 96 * 8)
    assert all(has_point(mesh, c) for c in expected)


def test_the_checker_inset_moves_a_straight_corner_square_to_its_next_edge() -> None:
    mesh = shapes.cube()
    edge = mesh.face_edges(0)[0]
    mid = mesh.subdivide_edge(edge)[0]
    a = mesh_arrays(mesh)
    move = inset_offsets(a.positions, a.corner_vertex, a.face_offsets, 0.25)
    for c in np.flatnonzero(a.corner_vertex == list(a.vertex_ids).index(mid)):
        f = a.corner_face[c]
        nxt = c + 1 if c + 1 < a.face_offsets[f + 1] else a.face_offsets[f]
        along = a.positions[a.corner_vertex[nxt]] - a.positions[a.corner_vertex[c]]
        np.testing.assert_allclose(move[c], 0.25 * unit(np.cross(face_normals(a)[f], along)),
                                   atol=1e-15)
    subdivide(mesh, "checker", thickness=0.25)
    validate(mesh)
    assert genus(mesh) == 0


def test_the_crust_moves_a_split_edge_point_by_its_reversed_faces_normals() -> None:
    mesh = split_spherical_cube()
    a = mesh_arrays(mesh)
    mid = int(np.flatnonzero(np.bincount(a.corner_vertex) == 2)[0])
    # the inner copy is the mesh reversed: its corner normals, turned back out
    back = reversed_rings(a.face_offsets)
    rings = [a.corner_vertex[back][a.face_offsets[f]:a.face_offsets[f + 1]]
             for f in range(len(a.face_ids))]
    normals = []
    for ring in rings:
        if mid in ring.tolist():
            corner_normal = rule(a.positions[ring].tolist())[0][ring.tolist().index(mid)]
            normals.append(-corner_normal)
    m = np.mean(normals, axis=0)
    expected = a.positions[mid] - m * np.mean([0.05 / (m @ n) for n in normals])
    crust(mesh, 0.05)
    validate(mesh)
    assert genus(mesh) == 0 and mesh.counts() == (2 * a.counts[0], 2 * a.counts[1],
                                                   2 * a.counts[2])
    assert has_point(mesh, expected)


# -- dome, the fans and checker on TopMod's kinds of warped meshes ------------------

WARPED = {"spherical cube": shapes.spherical_cube, "genus-3 hexagons": lambda: shapes.genus3_hexa(1),
          "hexagon donut": lambda: shapes.donut_hexa(1)}


def ds_step(points: np.ndarray, distance: float, scale: float) -> np.ndarray:
    """One Doo-Sabin extrusion ring as TopMod builds it, written out: the points
    moved ``distance`` along the rule's face normal, the Doo-Sabin weights, then
    scaled by ``scale`` about their centroid."""
    k = len(points)
    i = np.arange(k)
    weights = (3 + 2 * np.cos(2 * np.pi * (i[:, None] - i[None, :]) / k)) / (4 * k)
    np.fill_diagonal(weights, 0.25 + 5 / (4 * k))
    moved = points + (distance * rule(points.tolist())[1] if distance else 0.0)
    ring = weights @ moved
    centre = ring.mean(axis=0)
    return centre + scale * (ring - centre)


def warped_faces(mesh: Mesh) -> list[int]:
    """The faces of ``mesh`` whose corners do not lie in one plane (at 1e-6)."""
    out = []
    for f in mesh.face_ids().tolist():
        p = np.array(face_points(mesh, f))
        if np.linalg.svd(p - p.mean(axis=0), compute_uv=False)[-1] > 1e-6:
            out.append(f)
    return out


@pytest.mark.parametrize("name", sorted(WARPED))
def test_the_dome_extrusion_steps_along_each_rings_own_normal(name: str) -> None:
    mesh = WARPED[name]()
    face = warped_faces(mesh)[len(warped_faces(mesh)) // 2]
    points = np.array(face_points(mesh, face))
    for d, s in zip((0.3, 0.18, 0.1, 0.05, 0.025), (1.7, 1.6, 1.4, 1.2, 1.1), strict=True):
        points = ds_step(points, 2.0 * d, s)
    apex = points.mean(axis=0) + 0.02 * rule(points.tolist())[1]
    v, e, f = mesh.counts()
    k = len(points)
    fan = extrude_fan(mesh, face, "dome", 2.0)
    validate(mesh)
    assert mesh.counts() == (v + 5 * k + 1, e + 11 * k, f + 5 * k + k - 1) and len(fan) == k
    assert has_point(mesh, apex) and has_point(mesh, points[0]) and has_point(mesh, points[-1])


def split_in_four(points: np.ndarray) -> np.ndarray:
    """A polygon's corners with the points 1/4, 1/2 and 3/4 along each side: every
    point but the corners is a straight (180 degree) corner."""
    ahead = np.roll(points, -1, axis=0)
    return np.concatenate([points[:, None] + t * (ahead - points)[:, None]
                           for t in (0.0, 0.25, 0.5, 0.75)], axis=1).reshape(-1, 3)


@pytest.mark.parametrize("name", sorted(WARPED))
def test_the_dome_scheme_extrudes_each_split_face_along_the_rule(name: str) -> None:
    mesh = WARPED[name]()
    rings = []
    for face in mesh.face_ids().tolist()[::7]:  # each face's rings are its own
        points = split_in_four(np.array(face_points(mesh, face)))
        for d, s in zip((0, 0.3, 0.18, 0.1, 0.05, 0.025, 0.01),
                        (1.6, 1.7, 1.6, 1.4, 1.2, 1.1, 0.01), strict=True):
            points = ds_step(points, 0.5 * d, s)
        rings.append(points)
    v, e, f = mesh.counts()
    subdivide(mesh, "dome", length=0.5)
    validate(mesh)
    split = 8 * e  # the split faces' corners; each gets a quad on each of 7 rings
    assert mesh.counts() == (v + 3 * e + 7 * split, 4 * e + 14 * split, f + 7 * split)
    assert genus(mesh) == genus(WARPED[name]())
    assert all_present(mesh, np.concatenate(rings), 1e-12)


def all_present(mesh: Mesh, points: np.ndarray, tol: float) -> bool:
    """Whether every one of ``points`` ``(n, 3)`` is within ``tol`` of a vertex."""
    positions = mesh_arrays(mesh).positions
    return all(
        bool((np.linalg.norm(chunk[:, None] - positions[None], axis=2).min(axis=1) < tol).all())
        for chunk in np.array_split(points, max(1, len(points) // 100)))


@pytest.mark.parametrize("name", sorted(WARPED))
def test_the_fans_move_along_the_rule_on_warped_faces(name: str) -> None:
    mesh = WARPED[name]()
    faces = warped_faces(mesh)
    for face in faces[:: max(1, len(faces) // 4)]:
        points = np.array(face_points(mesh, face))
        normal = rule(points.tolist())[1]
        for kind, count in (("stellate", 1), ("double-stellate", 3)):
            work = WARPED[name]()
            fan = extrude_fan(work, face, kind, 0.4)
            validate(work)
            assert len(fan) == count * len(points)
            apex = set.intersection(*(set(work.face_vertices(f)) for f in fan)) \
                if kind == "stellate" else {work.num_vertices - 1 - len(points)}
            np.testing.assert_allclose(work.position(apex.pop()),
                                       points.mean(axis=0) + 0.4 * normal, atol=1e-14)


def test_checker_on_the_genus_3_mesh_flips_the_inset_at_its_concave_corners() -> None:
    mesh = shapes.genus3_hexa(1)
    a = mesh_arrays(mesh)
    expected, unflipped = [], []
    for f in range(len(a.face_ids)):
        p = a.positions[a.corner_vertex[a.face_offsets[f]:a.face_offsets[f + 1]]]
        newell = sum(np.cross(p[i], p[(i + 1) % len(p)]) for i in range(len(p)))
        for i in range(len(p)):
            ahead, behind = p[(i + 1) % len(p)] - p[i], p[i - 1] - p[i]
            move = 0.25 * (ahead + behind)
            if np.cross(ahead, behind) @ newell < 0:  # concave: TopMod turns it round
                unflipped.append(p[i] + move)
                move = -move
            expected.append(p[i] + move)
    assert len(unflipped) == 2  # the mesh's two concave corners
    subdivide(mesh, "checker", thickness=0.25)
    validate(mesh)
    assert genus(mesh) == 3 and mesh.counts() == (161 + 2 * 494, 9 * 494 // 2, 82 + 2 * 494)
    assert all_present(mesh, np.array(expected), 1e-13)
    assert not any(has_point(mesh, q, 1e-3) for q in unflipped)


def test_cross_rows_is_np_cross_bit_for_bit() -> None:
    rng = np.random.default_rng(7)
    a = rng.normal(size=(500, 3)) * 10.0 ** rng.integers(-200, 200, size=(500, 1))
    b = rng.normal(size=(500, 3)) * 10.0 ** rng.integers(-200, 200, size=(500, 1))
    a[:3] = [[np.inf, 1, 0], [np.nan, 0, 0], [0, 0, 0]]
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        assert np.array_equal(cross_rows(a, b), np.cross(a, b), equal_nan=True)
