"""TopMod's corner patches (livemod.dlfl.patches) against the rule itself.

``reference_nets`` below transcribes the rule of TOPMOD.md section 7 one corner
at a time through the mesh's public accessors, with nothing shared with the
vectorized module; the tests compare the two, then check what the rule
promises: shared boundaries, unit normals, the quads' face point, outward
orientation, and that no valid mesh makes the preview fail.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from livemod.dlfl import DLFLError, Mesh, from_polygons, mesh_arrays, validate
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.patches import (
    FLAT,
    CornerPatches,
    bernstein,
    cycle_layout,
    doo_sabin_weights,
    evaluate_patches,
    grid_triangles,
    mesh_surface,
    patch_control_points,
)
from livemod.dlfl.shapes import SHAPES, genus_torus, grid
from livemod.dlfl.shapes import torus as shape_torus
from tests.meshes import cube, path_face, point_sphere, tetrahedron, torus, triangle, two_cubes

# -- the rule, one corner at a time ------------------------------------------------


def doo_sabin(points: list[np.ndarray]) -> list[np.ndarray]:
    """TopMod's Doo-Sabin points of a polygon (one point: itself)."""
    n = len(points)
    if n == 1:
        return [points[0].copy()]
    out = []
    for i in range(n):
        total = np.zeros(3)
        for j in range(n):
            weight = (0.25 + 5.0 / (4 * n) if i == j
                      else (3.0 + 2.0 * math.cos(2.0 * math.pi * (i - j) / n)) / (4 * n))
            total += weight * points[j]
        out.append(total)
    return out


def centroid_and_normal(points: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    centroid = np.mean(points, axis=0)
    normal = np.zeros(3)
    for i in range(len(points)):
        normal += np.cross(points[i - 1] - centroid, points[i] - centroid)
    spread = sum(np.dot(p - centroid, p - centroid) for p in points)
    length = np.linalg.norm(normal)
    return centroid, normal / length if length > FLAT * spread else np.zeros(3)


def unit(v: np.ndarray) -> np.ndarray:
    length = np.linalg.norm(v)
    return v / length if length > 0 else v


def project(p: np.ndarray, at: np.ndarray, normal: np.ndarray) -> np.ndarray:
    return p - np.dot(p - at, normal) * normal


def distance_to_line(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> float:
    along = b - a
    t = np.dot(p - a, along) / np.dot(along, along) if np.dot(along, along) > 0 else 0.0
    return float(np.linalg.norm(p - (a + t * along)))


def intersect(p00: np.ndarray, p01: np.ndarray, p10: np.ndarray, p11: np.ndarray) -> np.ndarray:
    """TopMod's intersectCoplanarLines (half way when both ends are on the line)."""
    d0, d1 = distance_to_line(p10, p00, p01), distance_to_line(p11, p00, p01)
    frac = d0 / (d0 + d1) if d0 + d1 > 0 else 0.5
    return p10 + frac * (p11 - p10)


def project_and_intersect(p00: np.ndarray, p01: np.ndarray, p10: np.ndarray, p11: np.ndarray,
                          at: np.ndarray, normal: np.ndarray) -> np.ndarray:
    return intersect(*(project(p, at, normal) for p in (p00, p01, p10, p11)))


def reference_nets(mesh: Mesh) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """``{corner id: (points (4, 4, 3), normals (4, 4, 3))}`` for every corner with
    an edge, by the rule; vertex rings start at the corner first in
    :func:`mesh_arrays` order, faces at their head (as the module does)."""
    dense = {int(c): k for k, c in enumerate(mesh_arrays(mesh).corner_ids)}
    level1: dict[int, np.ndarray] = {}
    ds2: dict[int, list[np.ndarray]] = {c: [np.zeros(3)] * 4 for c in dense}
    fpoint, epoint, vpoint = {}, {}, {}
    for f in mesh.face_ids().tolist():
        ring = mesh.face_corners(f)
        first = doo_sabin([mesh.position(mesh.corner_vertex(c)) for c in ring])
        level1.update(zip(ring, first, strict=True))
        second = doo_sabin(first)
        for c, p in zip(ring, second, strict=True):
            ds2[c][2] = p
        fpoint[f] = centroid_and_normal(second)
    for e in mesh.edge_ids().tolist():
        c0, c1 = mesh.edge_corners(e)
        quad = [mesh.corner_next(c0), c0, mesh.corner_next(c1), c1]
        points = doo_sabin([level1[c] for c in quad])
        for c, slot, p in zip(quad, (3, 1, 3, 1), points, strict=True):
            ds2[c][slot] = p
        epoint[e] = centroid_and_normal(points)
    ring_of = {}
    for v in mesh.vertex_ids().tolist():
        ring = mesh.vertex_corners(v)
        start = min(range(len(ring)), key=lambda k: dense[ring[k]])
        ring = ring[start:] + ring[:start]
        points = doo_sabin([level1[c] for c in ring])
        for c, p in zip(ring, points, strict=True):
            ds2[c][0] = p
        centroid, normal = centroid_and_normal(points)
        vpoint[v] = (centroid, -normal)
        ring_of.update({c: ring for c in ring})
    nets = {c: corner_net(mesh, c, ds2, vpoint, epoint, fpoint)
            for c in dense if mesh.corner_edge(c) >= 0}
    passes(mesh, nets, ring_of)
    return nets


def corner_net(mesh: Mesh, c: int, ds2: dict, vpoint: dict, epoint: dict,
               fpoint: dict) -> tuple[np.ndarray, np.ndarray]:
    """TopMod's createPatches for one corner: cp[i][j], cn[i][j]."""
    nxt, prv = mesh.corner_next(c), mesh.corner_prev(c)
    vn = mesh.corner_vnext(c)
    vp = next(k for k in mesh.vertex_corners(mesh.corner_vertex(c)) if mesh.corner_vnext(k) == c)
    cp = np.zeros((4, 4, 3))
    cn = np.zeros((4, 4, 3))
    cp[0][0], cn[0][0] = vpoint[mesh.corner_vertex(c)]
    cp[1][0], cp[1][1], cp[0][1] = ds2[vn][0], ds2[c][0], ds2[vp][0]
    cp[3][0], cn[3][0] = epoint[mesh.corner_edge(c)]
    cp[3][1], cp[2][1], cp[2][0] = ds2[nxt][3], ds2[c][1], ds2[vn][3]
    cp[3][3], cn[3][3] = fpoint[mesh.corner_face(c)]
    cp[2][3], cp[2][2], cp[3][2] = ds2[prv][2], ds2[c][2], ds2[nxt][2]
    cp[0][3], cn[0][3] = epoint[mesh.corner_edge(prv)]
    cp[0][2], cp[1][2], cp[1][3] = ds2[vp][1], ds2[c][3], ds2[prv][1]
    pi = project_and_intersect
    new = {
        (1, 0): pi(cp[0][0], cp[3][0], cp[1][1], cp[1][0], cp[0][0], cn[0][0]),
        (2, 0): pi(cp[0][0], cp[3][0], cp[2][1], cp[2][0], cp[3][0], cn[3][0]),
        (3, 1): pi(cp[3][0], cp[3][3], cp[2][1], cp[3][1], cp[3][0], cn[3][0]),
        (3, 2): pi(cp[3][0], cp[3][3], cp[2][2], cp[3][2], cp[3][3], cn[3][3]),
        (2, 3): pi(cp[3][3], cp[0][3], cp[2][2], cp[2][3], cp[3][3], cn[3][3]),
        (1, 3): pi(cp[3][3], cp[0][3], cp[1][2], cp[1][3], cp[0][3], cn[0][3]),
        (0, 2): pi(cp[0][3], cp[0][0], cp[1][2], cp[0][2], cp[0][3], cn[0][3]),
        (0, 1): pi(cp[0][3], cp[0][0], cp[1][1], cp[0][1], cp[0][0], cn[0][0]),
    }
    for (i, j), p in new.items():
        cp[i][j] = p
    for (i, j), (k, m) in {(1, 1): (0, 0), (2, 1): (3, 0), (2, 2): (3, 3),
                           (1, 2): (0, 3)}.items():
        cp[i][j] = project(cp[i][j], cp[k][m], cn[k][m])
    nearest = {(1, 0): (0, 0), (1, 1): (0, 0), (0, 1): (0, 0), (2, 0): (3, 0), (2, 1): (3, 0),
               (3, 1): (3, 0), (3, 2): (3, 3), (2, 2): (3, 3), (2, 3): (3, 3), (0, 2): (0, 3),
               (1, 2): (0, 3), (1, 3): (0, 3)}
    for (i, j), (k, m) in nearest.items():
        cp[i][j] = cp[k][m] + (cp[i][j] - cp[k][m]) * 4.0 / 3.0
    n00, n30, n33, n03 = cn[0][0], cn[3][0], cn[3][3], cn[0][3]
    cn[1][0], cn[0][1] = unit(3 * n00 + n30), unit(3 * n00 + n03)
    cn[1][1] = unit(6 * n00 + n03 + n30)
    cn[2][0], cn[3][1] = unit(3 * n30 + n00), unit(3 * n30 + n33)
    cn[2][1] = unit(6 * n30 + n00 + n33)
    cn[0][2], cn[1][3] = unit(3 * n03 + n00), unit(3 * n03 + n33)
    cn[1][2] = unit(6 * n03 + n00 + n33)
    cn[2][3], cn[3][2] = unit(3 * n33 + n03), unit(3 * n33 + n30)
    cn[2][2] = unit(6 * n33 + n03 + n30)
    return cp, cn


def passes(mesh: Mesh, nets: dict, ring_of: dict) -> None:
    """The quad face point, the per-edge re-snapping, the valence-4 vertex fix."""
    def cp(c: int) -> np.ndarray:
        return nets[c][0]

    for f in mesh.face_ids().tolist():
        ring = mesh.face_corners(f)
        if len(ring) == 4:
            ip = intersect(cp(ring[0])[3][2], cp(ring[2])[3][2], cp(ring[0])[2][3],
                           cp(ring[2])[2][3])
            for c in ring:
                cp(c)[3][3] = ip
    for e in mesh.edge_ids().tolist():
        c0, c1 = mesh.edge_corners(e)
        ip = intersect(cp(c0)[2][0], cp(c1)[2][0], cp(c0)[3][1], cp(c1)[3][1])
        cp(c0)[3][0] = cp(c1)[3][0] = ip
        cp(mesh.corner_next(c0))[0][3] = cp(mesh.corner_next(c1))[0][3] = ip
    for ring in {id(r): r for r in ring_of.values()}.values():
        if len(ring) == 4 and all(c in nets for c in ring):
            ip = intersect(cp(ring[0])[1][0], cp(ring[2])[1][0], cp(ring[0])[0][1],
                           cp(ring[2])[0][1])
            for c in ring:
                cp(c)[0][0] = ip


def with_two_gon() -> Mesh:
    """The unit cube with an edge beside one of its edges: a 2-gon appears."""
    mesh = cube()
    corner = mesh.face_corners(0)[0]
    mesh.insert_edge(corner, mesh.corner_next(corner))
    return mesh


def pyramid() -> Mesh:
    """A pentagonal pyramid: a vertex of five corners, five of three."""
    base = [(math.cos(2 * math.pi * k / 5), math.sin(2 * math.pi * k / 5), 0.0) for k in range(5)]
    faces = [[4, 3, 2, 1, 0]] + [[k, (k + 1) % 5, 5] for k in range(5)]
    return from_polygons([*base, (0.0, 0.0, 1.2)], faces)


def with_point_sphere() -> Mesh:
    mesh = cube()
    mesh.create_vertex((3.0, 0.0, 0.0))
    return mesh


MESHES = {
    "cube": cube, "tetrahedron": tetrahedron, "torus": lambda: torus(5, 4),
    "genus 3": lambda: genus_torus(3), "valence 3 and 5": pyramid, "2-gon": with_two_gon,
    "point-sphere": with_point_sphere, "hole": triangle, "open grid": lambda: grid(4, 3),
    "two cubes": two_cubes,
    "face through a vertex twice": path_face,
}


def size_of(mesh: Mesh) -> float:
    positions = mesh_arrays(mesh).positions
    return float(np.ptp(positions, axis=0).max()) if len(positions) else 1.0


# -- the nets against the rule -------------------------------------------------------


@pytest.mark.parametrize("name", MESHES)
def test_nets_are_the_rule_corner_by_corner(name: str) -> None:
    mesh = MESHES[name]()
    validate(mesh)
    arrays = mesh_arrays(mesh)
    net = patch_control_points(mesh)
    expected = reference_nets(mesh)
    drawn = [int(c) for c, f in zip(arrays.corner_ids, arrays.corner_face, strict=True)
             if mesh.corner_edge(int(c)) >= 0 and not arrays.face_hole[f]]
    assert [int(arrays.corner_ids[c]) for c in net.corners] == drawn
    points = np.array([expected[c][0] for c in drawn]).reshape(-1, 4, 4, 3)
    normals = np.array([expected[c][1] for c in drawn]).reshape(-1, 4, 4, 3)
    np.testing.assert_allclose(net.points, points, rtol=0, atol=1e-12 * size_of(mesh))
    np.testing.assert_allclose(net.normals, normals, rtol=0, atol=1e-12)


def test_patch_corners_are_the_level2_centroids_the_rule_names() -> None:
    # a tetrahedron has no quad and no vertex of four corners: no pass moves the
    # vertex and face points, only edge points are re-snapped
    mesh = tetrahedron()
    arrays = mesh_arrays(mesh)
    net = patch_control_points(mesh)
    for p, c in enumerate(net.corners):
        corner = int(arrays.corner_ids[c])
        face = mesh.face_corners(mesh.corner_face(corner))
        level1 = doo_sabin([mesh.position(mesh.corner_vertex(k)) for k in face])
        face_point = sum(doo_sabin(level1)) / len(face)
        np.testing.assert_allclose(net.points[p, 3, 3], face_point, atol=1e-14)
        ring = mesh.vertex_corners(mesh.corner_vertex(corner))
        around = []
        for k in ring:
            own = mesh.face_corners(mesh.corner_face(k))
            around.append(doo_sabin([mesh.position(mesh.corner_vertex(j)) for j in own])
                          [own.index(k)])
        np.testing.assert_allclose(net.points[p, 0, 0], sum(doo_sabin(around)) / len(ring),
                                   atol=1e-14)


def test_doo_sabin_weights_sum_to_one_and_match_the_rule() -> None:
    for n in range(1, 9):
        weights = doo_sabin_weights(n)
        np.testing.assert_allclose(weights.sum(axis=1), 1.0, atol=1e-15)
        points = [np.array([math.cos(k), math.sin(2 * k), k * 0.1]) for k in range(n)]
        np.testing.assert_allclose(weights @ np.array(points), np.array(doo_sabin(points)),
                                   atol=1e-14)


def test_cycle_layout_lays_out_each_cycle_from_its_smallest_element() -> None:
    successor = np.array([3, 0, 5, 1, 4, 2, 6])       # cycles (0 3 1), (2 5), (4), (6)
    order, offsets = cycle_layout(successor, longest=3)
    assert order.tolist() == [0, 3, 1, 2, 5, 4, 6]
    assert offsets.tolist() == [0, 3, 5, 6, 7]
    rng = np.random.default_rng(5)
    successor = rng.permutation(500)
    order, offsets = cycle_layout(successor, longest=500)
    for start, stop in zip(offsets[:-1], offsets[1:], strict=True):
        ring = order[start:stop]
        assert ring[0] == ring.min()
        assert (successor[ring] == np.roll(ring, -1)).all()
    assert sorted(order.tolist()) == list(range(500))


# -- what the rule promises ----------------------------------------------------------


@pytest.mark.parametrize("name", MESHES)
def test_neighbouring_patches_share_their_boundary_curves(name: str) -> None:
    mesh = MESHES[name]()
    arrays = mesh_arrays(mesh)
    net = patch_control_points(mesh)
    density = 5
    grid = evaluate_patches(net, density).positions.reshape(len(net), density + 1,
                                                              density + 1, 3)
    patch_of = {int(c): p for p, c in enumerate(net.corners)}
    shared = 0
    for p, c in enumerate(net.corners):
        # side (i, 0) meets the (0, j) side of the patch across the edge after c;
        # side (3, j) the (i, 3) side of the next corner's patch
        for other, mine, theirs in ((arrays.corner_vnext[c], grid[p, :, 0], lambda q: grid[q, 0]),
                                    (arrays.corner_next[c], grid[p, -1], lambda q: grid[q, :, -1])):
            if int(other) in patch_of:
                shared += 1
                np.testing.assert_allclose(mine, theirs(patch_of[int(other)]),
                                           atol=1e-6 * size_of(mesh))
    assert shared > 0


@pytest.mark.parametrize("name", MESHES)
def test_normals_are_unit_and_point_out_of_convex_shapes(name: str) -> None:
    mesh = MESHES[name]()
    net = patch_control_points(mesh)
    lengths = np.linalg.norm(net.normals, axis=3)
    drawn = np.linalg.norm(evaluate_patches(net, 3).normals, axis=1)
    if name in ("2-gon", "face through a vertex twice", "hole", "open grid"):
        # polygons with no area (2-gons, and the vertex polygons of two corners at
        # a hole's corners) have no normal: zero, where no blend gives one
        assert np.all((np.abs(lengths - 1.0) < 1e-12) | (lengths == 0.0))
        assert np.all((np.abs(drawn - 1.0) < 1e-5) | (drawn == 0.0))
        assert (lengths == 0.0).any()
    else:
        np.testing.assert_allclose(lengths, 1.0, atol=1e-12)
        np.testing.assert_allclose(drawn, 1.0, atol=1e-5)
    tessellation = evaluate_patches(net, 3)
    if name in ("cube", "tetrahedron", "valence 3 and 5"):
        center = mesh_arrays(mesh).positions.mean(axis=0)
        outward = np.einsum("ij,ij->i", tessellation.normals, tessellation.positions - center)
        assert (outward > 0).all()


def test_triangles_turn_the_way_the_normals_point() -> None:
    tessellation = evaluate_patches(patch_control_points(shape_torus(8, 6)), 4)
    p = tessellation.positions.astype(np.float64)
    tri = tessellation.triangles
    facing = np.cross(p[tri[:, 1]] - p[tri[:, 0]], p[tri[:, 2]] - p[tri[:, 0]])
    mean_normal = tessellation.normals[tri].sum(axis=1)
    assert (np.einsum("ij,ij->i", facing, mean_normal) > 0).all()


def test_a_quads_patches_meet_at_the_crossing_of_its_opposite_side_points() -> None:
    mesh = shape_torus(6, 5)
    arrays = mesh_arrays(mesh)
    net = patch_control_points(mesh)
    patch_of = {int(c): p for p, c in enumerate(net.corners)}
    points = net.points
    for face in range(len(arrays.face_ids)):
        ring = [patch_of[c] for c in range(arrays.face_offsets[face],
                                           arrays.face_offsets[face + 1])]
        assert len(ring) == 4
        face_point = points[ring[0], 3, 3]
        for p in ring:
            np.testing.assert_array_equal(points[p, 3, 3], face_point)
        a, b = points[ring[0], 3, 2], points[ring[2], 3, 2]
        c, d = points[ring[0], 2, 3], points[ring[2], 2, 3]
        # on segment c-d, and on the line a-b (to the lines' own skewness)
        assert distance_to_line(face_point, c, d) < 1e-12
        skew = abs(np.dot(np.cross(b - a, d - c), c - a)) / np.linalg.norm(np.cross(b - a, d - c))
        assert distance_to_line(face_point, a, b) <= skew + 1e-12


def test_grid_corners_are_the_patch_corners() -> None:
    net = patch_control_points(cube())
    tessellation = evaluate_patches(net, 2)
    grid = tessellation.positions.reshape(len(net), 3, 3, 3)
    for (a, b), (i, j) in {(0, 0): (0, 0), (2, 0): (3, 0), (2, 2): (3, 3),
                           (0, 2): (0, 3)}.items():
        np.testing.assert_allclose(grid[:, a, b], net.points[:, i, j], atol=1e-6)


def test_bernstein_and_the_grid_triangles() -> None:
    t = np.linspace(0.0, 1.0, 7)
    np.testing.assert_allclose(bernstein(t).sum(axis=1), 1.0)
    assert grid_triangles(2, 1).tolist() == [[0, 2, 3], [0, 3, 1], [4, 6, 7], [4, 7, 5]]
    assert grid_triangles(3, 4).shape == (3 * 2 * 16, 3)


def test_density_outside_its_range_is_refused() -> None:
    net = patch_control_points(cube())
    for bad in (0, 33, 2.0, True, "4"):
        with pytest.raises(InvalidArgumentError, match="density must be an int from 1 to 32"):
            evaluate_patches(net, bad)  # type: ignore[arg-type]


def test_tessellate_is_evaluate_of_the_nets_and_leaves_the_mesh_alone() -> None:
    mesh = genus_torus(3)
    before = mesh_arrays(mesh).positions.copy()
    patches = CornerPatches(mesh)
    some = np.arange(0, mesh.num_corners, 3)
    whole = evaluate_patches(patches.nets(some), 3)
    made = patches.tessellate(3, some)
    np.testing.assert_array_equal(made.positions, whole.positions)
    np.testing.assert_array_equal(made.normals, whole.normals)
    np.testing.assert_array_equal(made.triangles, whole.triangles)
    np.testing.assert_array_equal(mesh_arrays(mesh).positions, before)


def test_the_vertex_surface_runs_through_the_patches_vertex_points() -> None:
    mesh = shape_torus(8, 6)
    patches = CornerPatches(mesh)
    net = patches.nets()
    surface = patches.vertex_surface()
    assert surface.triangles.shape == (48 * 2, 3) and surface.density == 0
    corner_points = net.points[:, 0, 0]
    nearest = np.linalg.norm(surface.positions[:, None] - corner_points[None], axis=2)
    assert len(surface.positions) == 48 and (nearest.min(axis=1) < 1e-6).all()
    np.testing.assert_allclose(np.linalg.norm(surface.normals, axis=1), 1.0, atol=1e-6)
    some = patches.vertex_surface(np.arange(0, 8))         # the corners of two faces
    assert some.triangles.shape == (4, 3) and len(some.positions) == 6


def _colored(mesh: Mesh, faces: dict[int, tuple[float, float, float]]) -> Mesh:
    for face, color in faces.items():
        mesh.set_face_color(face, color)
    return mesh


def test_each_patch_takes_the_colour_of_its_corners_face() -> None:
    mesh = _colored(cube(), {0: (1.0, 0.0, 0.0), 3: (0.0, 0.4, 1.0)})
    arrays = mesh_arrays(mesh)
    patches = CornerPatches(mesh)
    made = patches.tessellate(2)
    assert made.colors is not None and made.colors.shape == (24 * 9, 4)
    faces = np.repeat(arrays.corner_face[patches.surface_corners()], 9)
    expected = np.zeros((6, 4), np.uint8)
    expected[0], expected[3] = (255, 0, 0, 255), (0, 102, 255, 255)
    np.testing.assert_array_equal(made.colors, expected[faces])
    plain = CornerPatches(cube()).tessellate(2)
    assert plain.colors is None                       # no colour anywhere: none made
    np.testing.assert_array_equal(made.positions, plain.positions)
    np.testing.assert_array_equal(made.triangles, plain.triangles)


def test_a_coloured_vertex_surface_shares_points_between_faces_of_one_colour() -> None:
    mesh = _colored(shape_torus(8, 6), {5: (0.0, 1.0, 0.0)})
    arrays = mesh_arrays(mesh)
    patches = CornerPatches(mesh)
    made, plain = patches.vertex_surface(), CornerPatches(shape_torus(8, 6)).vertex_surface()
    # a point per vertex, and one more for each of face 5's four (green beside none)
    assert len(made.positions) == 52 and len(plain.positions) == 48
    assert made.colors is not None and plain.colors is None
    np.testing.assert_array_equal(made.positions[made.triangles], plain.positions[plain.triangles])
    np.testing.assert_array_equal(made.normals[made.triangles], plain.normals[plain.triangles])
    # each triangle's three points carry its face's colour: green for face 5's two
    green = (made.colors[made.triangles] == (0, 255, 0, 255)).all(axis=2)
    assert green.sum(axis=0).tolist() == [2, 2, 2] and (green.all(axis=1) == green[:, 0]).all()
    fan_face = arrays.fan_triangles()[1]
    assert np.flatnonzero(green[:, 0]).tolist() == np.flatnonzero(fan_face == 5).tolist()


def test_faces_of_as_many_colours_as_faces_share_no_point() -> None:
    mesh = _colored(shape_torus(8, 6), {face: (face / 47, 0.5, 1 - face / 47)
                                        for face in range(48)})
    arrays = mesh_arrays(mesh)
    made = CornerPatches(mesh).vertex_surface()
    assert len(made.positions) == 192                              # every corner its own
    fan_face = arrays.fan_triangles()[1]
    want = np.repeat(_face_bytes(arrays)[fan_face][:, None], 3, axis=1)
    np.testing.assert_array_equal(made.colors[made.triangles], want)


def _face_bytes(arrays) -> np.ndarray:  # type: ignore[no-untyped-def]
    rgba = np.zeros((len(arrays.face_ids), 4), np.uint8)
    rgba[:, :3] = np.rint(arrays.face_colors * 255)
    rgba[:, 3] = 255
    return rgba


def test_a_coloured_mesh_surface_shares_points_between_faces_of_one_colour() -> None:
    mesh = _colored(cube(), {2: (0.0, 0.0, 1.0), 4: (0.0, 0.0, 1.0), 1: (1.0, 0.0, 0.0)})
    arrays = mesh_arrays(mesh)
    made, plain = mesh_surface(mesh), mesh_surface(cube())
    assert plain.colors is None and len(plain.positions) == 8
    # each vertex once per colour of its three faces: a y side (blue), an x side (none)
    # and the bottom (none) or the top (red): 2 points at z = -1, 3 at z = +1
    assert len(made.positions) == 4 * 2 + 4 * 3
    np.testing.assert_array_equal(made.positions[made.triangles], plain.positions[plain.triangles])
    np.testing.assert_array_equal(made.normals[made.triangles], plain.normals[plain.triangles])
    corner_colors = made.colors[made.triangles]                     # (T, 3, 4)
    fan_face = arrays.fan_triangles()[1]
    want = np.zeros((6, 4), np.uint8)
    want[[2, 4]], want[1] = (0, 0, 255, 255), (255, 0, 0, 255)
    np.testing.assert_array_equal(corner_colors, np.repeat(want[fan_face][:, None], 3, axis=1))


# -- degenerate meshes: decided, and never a failure -----------------------------------


def test_point_spheres_and_holes_get_no_patch_and_two_gons_get_theirs() -> None:
    assert len(patch_control_points(point_sphere())) == 0
    assert len(patch_control_points(with_point_sphere())) == 24
    assert len(patch_control_points(triangle())) == 3      # the hole's three corners: none
    mesh = with_two_gon()
    arrays = mesh_arrays(mesh)
    net = patch_control_points(mesh)
    two_gon = np.flatnonzero(arrays.face_sizes == 2)
    assert len(two_gon) == 1
    assert np.isin(np.flatnonzero(arrays.corner_face == two_gon[0]), net.corners).all()
    assert len(net) == 26 and np.isfinite(net.points).all()


def test_a_vertex_that_is_not_finite_costs_only_the_patches_around_it() -> None:
    # a mesh refuses such a position, but arrays made by a script's arithmetic
    # (a division by a zero length) may hold one
    arrays = mesh_arrays(shape_torus(12, 10))
    whole = len(patch_control_points(arrays))
    positions = np.array(arrays.positions)
    positions[0] = (np.nan, 0.0, 0.0)
    positions[60] = (np.inf, 0.0, 0.0)
    broken = dataclasses.replace(arrays, positions=positions)
    net = patch_control_points(broken)
    assert 0 < len(net) < whole - 8
    assert np.isfinite(net.points).all()
    tessellation = CornerPatches(broken).tessellate(2)
    assert len(tessellation.triangles) == 8 * len(net)
    assert np.isfinite(tessellation.positions).all()


def test_far_and_huge_coordinates_give_the_same_shape() -> None:
    mesh = cube()
    net = patch_control_points(mesh)
    for scale, offset in ((1e150, 0.0), (1e-150, 0.0), (1.0, 1e9)):
        moved = cube()
        moved.set_positions(moved.vertex_ids(), mesh_arrays(mesh).positions * scale + offset)
        scaled = patch_control_points(moved)
        np.testing.assert_allclose((scaled.points - offset) / scale, net.points,
                                   atol=1e-6 if offset else 1e-12)


@pytest.mark.parametrize("name", sorted(set(SHAPES) - {"buckminister"}))
def test_every_built_in_shape_gives_a_preview(name: str) -> None:
    mesh = SHAPES[name]()
    arrays = mesh_arrays(mesh)
    tessellation = CornerPatches(arrays).tessellate(2)
    drawn = int(arrays.face_sizes[~arrays.face_hole].sum())
    assert len(tessellation.triangles) == 8 * drawn
    assert np.isfinite(tessellation.positions).all()
    assert tessellation.triangles.max() < len(tessellation.positions)


operation = st.tuples(st.sampled_from(["insert", "delete", "split", "collapse", "vertex"]),
                      st.integers(0, 10_000), st.integers(0, 10_000))


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(start=st.sampled_from(sorted(MESHES)), operations=st.lists(operation, max_size=12))
def test_random_operations_never_make_the_preview_fail(start: str,
                                                       operations: list[tuple[str, int, int]]
                                                       ) -> None:
    mesh = MESHES[start]()
    for kind, a, b in operations:
        apply_operation(mesh, kind, a, b)
    validate(mesh)
    arrays = mesh_arrays(mesh)
    tessellation = CornerPatches(arrays).tessellate(2)
    assert np.isfinite(tessellation.positions).all()
    lengths = np.linalg.norm(tessellation.normals, axis=1)
    assert np.all((np.abs(lengths - 1.0) < 1e-5) | (lengths == 0.0))
    assert len(tessellation.triangles) == 0 or tessellation.triangles.max() < len(
        tessellation.positions)


def apply_operation(mesh: Mesh, kind: str, a: int, b: int) -> None:
    """One minimal operator on elements picked by ``a`` and ``b`` (refusals skipped)."""
    corners, edges = mesh.corner_ids().tolist(), mesh.edge_ids().tolist()
    try:
        if kind == "insert" and corners:
            mesh.insert_edge(corners[a % len(corners)], corners[b % len(corners)])
        elif kind == "delete" and edges:
            mesh.delete_edge(edges[a % len(edges)])
        elif kind == "split" and edges:
            mesh.subdivide_edge(edges[a % len(edges)], 2 + b % 2)
        elif kind == "collapse" and edges:
            mesh.collapse_edge(edges[a % len(edges)])
        elif kind == "vertex":
            mesh.create_vertex((a % 7, b % 5, 1.0))
    except DLFLError:
        pass
