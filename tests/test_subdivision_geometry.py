"""Remeshing positions against hand-derived formulas on TopMod's cube (+-1) and octahedron."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

from livemod.dlfl import Mesh, from_polygons, mesh_arrays, validate
from livemod.dlfl.shapes import cube, grid, load_shape
from livemod.dlfl.subdivision import subdivide
from tests.meshes import assert_scales


def positions(mesh: Mesh) -> np.ndarray:
    validate(mesh)
    return mesh_arrays(mesh).positions


def orbit(*point: float) -> np.ndarray:
    """Every signed permutation of ``point`` (the cube's symmetry orbit), unique."""
    out = set()
    for perm in itertools.permutations(point):
        for signs in itertools.product((1, -1), repeat=3):
            out.add(tuple(round(s * x, 12) + 0.0 for s, x in zip(signs, perm, strict=True)))
    return np.array(sorted(out))


def same_points(got: np.ndarray, *expected: np.ndarray) -> bool:
    """Equal as point sets to 1e-9 relative (multiplicities ignored)."""
    want = np.concatenate(expected)
    scale = max(1.0, float(np.abs(want).max()))

    def covered(a: np.ndarray, b: np.ndarray) -> bool:
        gaps = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2).min(axis=1)
        return bool((gaps < 1e-9 * scale).all())

    return covered(got, want) and covered(want, got)


CORNERS = orbit(1, 1, 1)
CENTRES = orbit(1, 0, 0)
MIDPOINTS = orbit(1, 1, 0)


def run(scheme: str, mesh: Mesh | None = None, **options: object) -> np.ndarray:
    m = cube() if mesh is None else mesh
    subdivide(m, scheme, **options)
    return positions(m)


def test_catmull_clark_puts_old_corners_at_five_ninths():
    got = run("catmull-clark")
    assert same_points(got, orbit(5 / 9, 5 / 9, 5 / 9), orbit(0.75, 0.75, 0), CENTRES)


def test_catmull_clark_twice_stays_symmetric():
    m = cube()
    subdivide(m, "catmull-clark")
    subdivide(m, "catmull-clark")
    pos = positions(m)
    for matrix in SYMMETRIES:
        assert same_points(pos @ matrix.T, pos)


SYMMETRIES = [np.diag([-1.0, 1, 1]), np.array([[0.0, 1, 0], [1, 0, 0], [0, 0, 1]]),
              np.array([[0.0, 0, 1], [1, 0, 0], [0, 1, 0]])]


@pytest.mark.parametrize("scheme", ["catmull-clark", "doo-sabin", "loop", "honeycomb",
                                    "root4", "checker", "fractal", "star", "dual-12.6.4",
                                    "doo-sabin-bc-new", "dome", "pentagon-preserve"])
def test_symmetric_input_gives_symmetric_output(scheme):
    pos = run(scheme)
    for matrix in SYMMETRIES:
        assert same_points(pos @ matrix.T, pos)


def test_doo_sabin_quad_weights():
    # (9 p_i + 3 p_prev + 3 p_next + p_opposite) / 16 on a face of the +-1 cube
    assert same_points(run("doo-sabin"), orbit(0.5, 0.5, 1))


def test_corner_cut_with_alpha_nine_sixteenths_is_doo_sabin_on_quads():
    assert same_points(run("corner-cut", alpha=9 / 16), orbit(0.5, 0.5, 1))


def test_corner_cut_alpha_moves_points():
    # quads: w_ii = a, w_adjacent = (1 - a) 3/7, w_opposite = (1 - a)/7
    a = 0.75
    s = a - (1 - a) / 7
    assert same_points(run("corner-cut", alpha=a), orbit(s, s, 1))


def test_doo_sabin_keeps_a_regular_grid_planar():
    m = grid(5, 4)  # in the plane y = 0
    subdivide(m, "doo-sabin")
    pos = positions(m)
    assert np.allclose(pos[:, 1], 0.0, atol=1e-12)
    assert np.ptp(pos[:, 0]) > 4 and np.ptp(pos[:, 2]) > 3


def test_loop_on_the_octahedron():
    m = load_shape("octahedron")  # TopMod's: vertices on the axes at distance 1
    # valence 4: beta = (5/8 - (3/8)^2)/4 = 31/256, neighbours sum to 0: v' = (1 - 4 beta) v
    # edge point: 3/8 of both ends + 1/8 of both opposite vertices (which cancel)
    assert same_points(run("loop", m), orbit(33 / 64, 0, 0), orbit(0.375, 0.375, 0))


def test_loop_moves_every_old_vertex_from_the_old_positions():
    """TopMod's quirk (docs/topmod.md): its loopSubdivide moved the old vertices in
    place one after another, so on this tetrahedron vertex 1 averaged vertex 0's
    new place and went to (0.109, -0.391, -0.391). Loop's rule on the old
    positions keeps the tetrahedron's symmetry."""
    corners = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], dtype=np.float64)
    m = from_polygons(corners, [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]])
    got = run("loop", m)
    # valence 3: beta = (5/8 - (3/8 + cos(2 pi/3)/4)^2)/3 = 3/16 and the three
    # neighbours sum to -v: v' = (1 - 9/16) v - 3/16 v = v/4; edge points: 3/8 of
    # both ends + 1/8 of the two others (-(ends)): (ends)/4
    old = corners / 4
    edges = np.array([(corners[i] + corners[j]) / 4 for i, j in itertools.combinations(range(4), 2)])
    assert len(got) == 10 and same_points(got, old, edges)
    assert sorted(np.round(np.linalg.norm(got, axis=1), 12)) == sorted(
        [round(math.sqrt(3) / 4, 12)] * 4 + [0.5] * 6)


def test_loop_style_length():
    # v' = 0.5 v + 0.5 mean(neighbours); at (1,1,1) the mean is (1/3, 1/3, 1/3)
    assert same_points(run("loop-style", length=0.5), orbit(2 / 3, 2 / 3, 2 / 3), MIDPOINTS)


def test_linear_vertex_and_simplest_do_not_smooth():
    assert same_points(run("linear-vertex"), CORNERS, MIDPOINTS, CENTRES)
    assert same_points(run("simplest"), MIDPOINTS)


def test_vertex_cut_offset():
    assert same_points(run("vertex-cut", offset=0.25), orbit(1, 1, 0.5))
    assert same_points(run("vertex-cut", offset=0.1), orbit(1, 1, 0.8))


def test_pentagon_trisects_and_moves_every_joined_point():
    assert same_points(run("pentagon"), CORNERS, orbit(1, 1, 1 / 3), CENTRES)
    pos = run("pentagon", offset=0.5)
    # every trisection point is joined in one face and moves half way to that face's
    # centroid: (1/3, 1, 1) -> (1/6, 1/2, 1). TopMod left the last joined point of
    # each face in place (QUIRK); livemod moves all 24.
    moved = pos[~_in(pos, np.concatenate([CORNERS, CENTRES]))]
    assert len(moved) == 24
    assert np.allclose(np.sort(np.abs(moved), axis=1), [1 / 6, 0.5, 1.0], rtol=1e-9)


def _in(points: np.ndarray, candidates: np.ndarray) -> np.ndarray:
    gaps = np.linalg.norm(points[:, None, :] - candidates[None, :, :], axis=2).min(axis=1)
    return gaps < 1e-9


def test_pentagon_preserve_scales_the_midpoint_polygon():
    assert same_points(run("pentagon-preserve"), CORNERS, MIDPOINTS, orbit(0.75, 0, 1))
    assert same_points(run("pentagon-preserve", scale=0.5), CORNERS, MIDPOINTS, orbit(0.5, 0, 1))


HONEYCOMB_ALPHA = 1 / math.sqrt(2) - 0.25 + 5 / 16
HONEYCOMB_S = HONEYCOMB_ALPHA - (1 - HONEYCOMB_ALPHA) / 7


def test_honeycomb_weights_on_the_midpoints():
    assert same_points(run("honeycomb"), orbit(HONEYCOMB_S, 0, 1))


def test_root4_inner_points_and_weight():
    s = HONEYCOMB_S
    assert same_points(run("root4"), CORNERS, orbit(s, s, 1))
    moved = (2 * s + 1) / 3
    assert same_points(run("root4", weight=1.0), orbit(moved, moved, moved), orbit(s, s, 1))


def test_root4_twist_rotates_the_inner_polygon():
    pos = run("root4", twist=0.5)
    # twist 0.5 takes the weights over the midpoints: honeycomb's points
    assert same_points(pos, CORNERS, orbit(HONEYCOMB_S, 0, 1))


def test_checker_inset_and_trisection():
    assert same_points(run("checker"), CORNERS, orbit(0.34, 0.34, 1), orbit(1, 1, 0.34))
    assert same_points(run("checker", thickness=0.25), CORNERS, orbit(0.5, 0.5, 1),
                       orbit(1, 1, 0.5))


def test_fractal_centre_height():
    # square of side 2: L2 = sqrt(2), L1 = 1, d = offset * 1 above the face centre
    assert same_points(run("fractal"), CORNERS, MIDPOINTS, orbit(2, 0, 0))
    assert same_points(run("fractal", offset=0.5), CORNERS, MIDPOINTS, orbit(1.5, 0, 0))


def test_star_offset_moves_only_the_first_centres():
    assert same_points(run("star", offset=0.5), CORNERS, orbit(1.5, 0, 0),
                       orbit(0, 2 / 3, 1))


def test_double_stellate_offset_and_curve():
    assert same_points(run("double-stellate", offset=0.5), CORNERS, orbit(1.5, 0, 0),
                       orbit(0, 2 / 3, 3.5 / 3))
    pos = run("double-stellate", curve=1.0)
    # the second centre of triangle (1,1,1), (-1,1,1), (0,0,1) rises by its unit normal
    assert same_points(pos, CORNERS, CENTRES, orbit(0, 2 / 3, 2))


def test_stellate_sqrt3_dual_use_centroids():
    assert same_points(run("stellate"), CORNERS, CENTRES)
    assert same_points(run("sqrt3"), CORNERS, CENTRES)
    assert same_points(run("dual"), CENTRES)
    assert same_points(run("dual", accurate=True), CENTRES)


def test_dual_12_6_4_scale():
    assert same_points(run("dual-12.6.4"), orbit(0.7, 0.7 / 3, 1))
    assert same_points(run("dual-12.6.4", scale=1.0), orbit(1, 1 / 3, 1))


def _ds_weights(n: int) -> np.ndarray:
    k = (np.arange(n)[:, None] - np.arange(n)[None, :]) % n
    w = (3 + 2 * np.cos(2 * np.pi * k / n)) / (4 * n)
    return np.where(k == 0, 0.25 + 5 / (4 * n), w)


def test_doo_sabin_bc_new_ring_and_length():
    # the 8-gon (corners and midpoints of the face z = 1) through Doo-Sabin weights
    ring = np.array([[1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]],
                    dtype=float)
    inner = _ds_weights(8) @ ring
    at_corner, at_mid = np.abs(inner[0]), np.abs(inner[1])
    expected = (orbit(at_corner[0], at_corner[1], 1), orbit(at_mid[0], at_mid[1], 1))
    assert same_points(run("doo-sabin-bc-new"), CORNERS, *expected)
    half = (1 + at_corner[0] * 2 / 3 + 1 / 3) / 2
    assert same_points(run("doo-sabin-bc-new", length=0.5), orbit(half, half, half), *expected)


def test_dome_end_faces_rise_by_the_summed_distances():
    pos = run("dome")
    assert math.isclose(pos.max(), 1 + 0.665, rel_tol=1e-12)
    pos = run("dome", length=2.0)
    assert math.isclose(pos.max(), 1 + 1.33, rel_tol=1e-12)


@pytest.mark.parametrize("shape", ["torus", "sphericalcube", "soccerball"])
def test_dome_keeps_a_flat_rings_normal_to_within_rounding(shape, monkeypatch):
    # a flat ring stays flat through the steps, so dome measures its normal once;
    # measuring every ring afresh at every step (TopMod's way) gives the same mesh
    # to within rounding
    from livemod.dlfl.subdivision import extra

    kept = load_shape(shape)
    subdivide(kept, "dome")
    monkeypatch.setattr(extra, "_FLAT", -1.0)  # no ring counts as flat
    fresh = load_shape(shape)
    subdivide(fresh, "dome")
    a, b = mesh_arrays(kept), mesh_arrays(fresh)
    assert np.array_equal(a.corner_vertex, b.corner_vertex)
    np.testing.assert_allclose(a.positions, b.positions, rtol=0, atol=1e-12)


def test_catmull_clark_on_an_ngon_is_the_rule():
    # a lone pentagon prism check: every face point is its centroid, every old
    # vertex follows (Q + 2R + (n - 3) v) / n with n = 3
    m = load_shape("dodecahedron")
    a = mesh_arrays(m)
    subdivide(m, "catmull-clark")
    pos = positions(m)
    centroids = np.array([a.positions[a.corner_vertex[a.face_offsets[f]:a.face_offsets[f + 1]]]
                          .mean(axis=0) for f in range(len(a.face_ids))])
    assert same_points(pos[-len(centroids):], centroids)
    v = 0
    corners = np.flatnonzero(a.corner_vertex == v)
    q = centroids[a.corner_face[corners]].mean(axis=0)
    nxt = a.corner_next
    r = (0.5 * (a.positions[v] + a.positions[a.corner_vertex[nxt[corners]]])).mean(axis=0)
    assert np.allclose(pos[0], (q + 2 * r) / 3, rtol=1e-9, atol=1e-12)


# -- the rules on TopMod's solids, by an independent per-face loop ---------------

SOLIDS = ["tetrahedron", "octahedron", "dodecahedron", "icosahedron"]


def _faces_and_points(name: str) -> tuple[Mesh, list[list[int]], np.ndarray]:
    m = load_shape(name)
    a = mesh_arrays(m)
    faces = [a.corner_vertex[a.face_offsets[f]:a.face_offsets[f + 1]].tolist()
             for f in range(len(a.face_ids))]
    return m, faces, a.positions


def _neighbours(faces: list[list[int]], count: int) -> list[set[int]]:
    out: list[set[int]] = [set() for _ in range(count)]
    for face in faces:
        for i, v in enumerate(face):
            out[v].add(face[(i + 1) % len(face)])
            out[v].add(face[i - 1])
    return out


@pytest.mark.parametrize("name", SOLIDS)
def test_doo_sabin_rule_on_topmod_solids(name):
    m, faces, p = _faces_and_points(name)
    expected = []
    for face in faces:
        n = len(face)
        for i in range(n):
            w = [(3 + 2 * math.cos(2 * math.pi * (i - j) / n)) / (4 * n) for j in range(n)]
            w[i] = 0.25 + 5 / (4 * n)
            expected.append(sum(wj * p[v] for wj, v in zip(w, face, strict=True)))
    assert same_points(run("doo-sabin", m), np.array(expected))


@pytest.mark.parametrize("name", SOLIDS)
def test_catmull_clark_rule_on_topmod_solids(name):
    m, faces, p = _faces_and_points(name)
    centroid = [p[face].mean(axis=0) for face in faces]
    edge_faces: dict[tuple[int, ...], list[int]] = {}
    for f, face in enumerate(faces):
        for i, v in enumerate(face):
            edge_faces.setdefault(tuple(sorted((v, face[(i + 1) % len(face)]))), []).append(f)
    edge_points = [(p[u] + p[w] + centroid[f] + centroid[g]) / 4
                   for (u, w), (f, g) in edge_faces.items()]
    vertices = []
    for v, around in enumerate(_neighbours(faces, len(p))):
        n = len(around)
        q = np.mean([centroid[f] for f, face in enumerate(faces) if v in face], axis=0)
        r = np.mean([(p[v] + p[w]) / 2 for w in around], axis=0)
        vertices.append((q + 2 * r + (n - 3) * p[v]) / n)
    assert same_points(run("catmull-clark", m), np.array(vertices), np.array(edge_points),
                       np.array(centroid))


@pytest.mark.parametrize("name", ["tetrahedron", "octahedron", "icosahedron"])
def test_loop_rule_on_topmod_triangle_solids(name):
    m, faces, p = _faces_and_points(name)
    vertices = []
    for v, around in enumerate(_neighbours(faces, len(p))):
        n = len(around)
        beta = (5 / 8 - (3 / 8 + math.cos(2 * math.pi / n) / 4) ** 2) / n
        vertices.append((1 - n * beta) * p[v] + beta * sum(p[w] for w in around))
    opposite: dict[tuple[int, ...], list[int]] = {}
    for face in faces:
        for i in range(3):
            u, w, o = face[i], face[(i + 1) % 3], face[(i + 2) % 3]
            opposite.setdefault(tuple(sorted((u, w))), []).append(o)
    edge_points = [3 / 8 * (p[u] + p[w]) + 1 / 8 * (p[o1] + p[o2])
                   for (u, w), (o1, o2) in opposite.items()]
    assert same_points(run("loop", m), np.array(vertices), np.array(edge_points))


def test_catmull_clark_rule_on_the_torus():
    from livemod.dlfl.shapes import torus

    m = torus(8, 6)
    before = mesh_arrays(m)
    subdivide(m, "catmull-clark")
    pos = positions(m)
    # regular valence-4 quad grid: every new point is an affine combination with
    # weights summing to 1, and the 8-fold rotation about the axis is kept
    assert len(pos) == len(before.positions) + 2 * len(before.face_ids) + len(before.face_ids)
    angle = 2 * math.pi / 8
    rotation = np.array([[math.cos(angle), -math.sin(angle), 0],
                         [math.sin(angle), math.cos(angle), 0], [0, 0, 1]])
    axis_is_z = np.ptp(before.positions[:, 2]) < np.ptp(before.positions[:, 0])
    if not axis_is_z:
        rotation = rotation[[0, 2, 1]][:, [0, 2, 1]]
    assert same_points(pos @ rotation.T, pos)


@pytest.mark.parametrize(("scheme", "options"), [
    ("checker", {}), ("dual-checkerboard", {}), ("double-stellate", {"curve": 0.2}),
])
def test_a_huge_mesh_subdivides_like_the_scaled_unit_one(scheme, options):
    # the schemes' face normals and corner tests took raw cross products, which
    # overflowed past ~1e77: concave corners and normals came out wrong
    def made():
        mesh = cube()
        mesh.set_position(0, tuple(0.8 * mesh.position(0)))  # one concave-ish corner
        return mesh

    def scheme_scaled(mesh, s):  # its options are lengths: they scale with the mesh
        subdivide(mesh, scheme, **{k: v * s for k, v in options.items()})
    assert_scales(made, scheme_scaled)
