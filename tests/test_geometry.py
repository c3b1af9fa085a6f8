"""Geometry-only operations and TopMod's cleanup helpers."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from livemod.dlfl import Mesh, face_size_histogram, validate
from livemod.dlfl.analysis import face_normals
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.geometry import (
    cleanup_2gons,
    cleanup_winged_vertices,
    edge_cleanup,
    mesh_smooth,
    planarize,
    spheralize,
    split_valence2_vertices,
)
from livemod.dlfl.shapes import cube, grid, spherical_cube, torus
from tests.meshes import assert_refused, assert_refused_quietly, assert_scales, snapshot
from tests.meshes import cube as unit_cube


def bumped_cube():
    m = cube()
    m.set_position(0, (1.3, 1.2, 1.1))
    return m


def non_planarity(mesh):
    """Largest distance of a corner from its face's centroid plane."""
    a = mesh_arrays(mesh)
    normals = face_normals(a)[a.corner_face]
    sums = np.zeros((len(a.face_ids), 3))
    np.add.at(sums, a.corner_face, a.positions[a.corner_vertex])
    centres = (sums / a.face_sizes[:, None])[a.corner_face]
    return np.abs(np.einsum("ij,ij->i", a.positions[a.corner_vertex] - centres, normals)).max()


def test_smoothing_keeps_the_cube_and_its_topology():
    m = cube()
    mesh_smooth(m, 3)
    validate(m)
    assert m.counts() == (8, 12, 6)
    np.testing.assert_allclose(m.positions_view(), cube().positions_view(), atol=1e-12)


def test_smoothing_moves_only_tangentially():
    m = spherical_cube(4)
    before = m.positions_view()
    mesh_smooth(m)
    after = m.positions_view()
    assert not np.allclose(before, after)
    # a round mesh stays nearly round: tangential moves barely change the radius
    assert np.abs(np.linalg.norm(after, axis=1) - 1).max() < 0.1


def test_smoothing_rejects_negative_iterations():
    with pytest.raises(InvalidArgumentError):
        mesh_smooth(cube(), -1)


def test_planarize_flattens_faces():
    m = bumped_cube()
    before = non_planarity(m)
    planarize(m)
    validate(m)
    assert m.counts() == (8, 12, 6)
    assert non_planarity(m) < before / 5


def test_planarize_rejects_negative_steps():
    with pytest.raises(InvalidArgumentError):
        planarize(cube(), -3)


def test_spheralize_puts_vertices_on_the_unit_sphere_about_the_centroid():
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * 3 + 5)
    spheralize(m)
    np.testing.assert_allclose(np.linalg.norm(m.positions_view(), axis=1), 1.0)
    np.testing.assert_allclose(m.positions_view(), cube().positions_view() / np.sqrt(3))


def test_edge_cleanup_removes_a_face_diagonal():
    m = cube()
    c = m.face_corners(0)
    m.insert_edge(c[0], c[2])
    assert m.counts() == (8, 13, 7)
    assert edge_cleanup(m) == 1
    validate(m)
    assert m.counts() == (8, 12, 6)
    assert edge_cleanup(cube()) == 0


def test_edge_cleanup_of_given_edges_looks_at_those_only():
    m = cube()
    c = m.face_corners(0)
    diagonal = m.insert_edge(c[0], c[2])
    others = [e for e in m.edge_ids().tolist() if e != diagonal]
    assert edge_cleanup(m, others) == 0
    assert m.counts() == (8, 13, 7)
    assert edge_cleanup(m, [diagonal]) == 1
    validate(m)
    assert m.counts() == (8, 12, 6)


def test_cleanup_2gons():
    m = cube()
    c = m.face_corners(0)
    m.insert_edge(c[0], c[1])  # adjacent corners: a 2-gon
    assert face_size_histogram(m)[2] == 1
    assert cleanup_2gons(m) == 1
    validate(m)
    assert m.counts() == (8, 12, 6)


def test_cleanup_winged_vertices_undoes_an_edge_split():
    m = cube()
    m.subdivide_edge(0)
    assert cleanup_winged_vertices(m) == 1
    validate(m)
    assert m.counts() == (8, 12, 6)


def test_split_valence2_vertices_pushes_the_pair_apart():
    m = cube()
    (v,) = m.subdivide_edge(0)
    origin = m.position(v)
    new = split_valence2_vertices(m, 0.2)
    validate(m)
    assert len(new) == 1 and m.counts() == (10, 14, 6)
    d = m.position(v) - m.position(new[0])
    assert np.isclose(np.linalg.norm(d), 0.4)
    np.testing.assert_allclose((m.position(v) + m.position(new[0])) / 2, origin)


def _neighbours(mesh: Mesh, v: int) -> set[int]:
    return {u for e in mesh.vertex_edges(v) for u in mesh.edge_vertices(e) if u != v}


def _split_pairs(mesh: Mesh, offset: float) -> list[tuple[int, int, np.ndarray]]:
    """Split ``mesh``'s valence-2 vertices; ``(vertex, new vertex, old position)``
    of each pair (the new ids come in the order of the vertices split)."""
    old = {v: mesh.position(v) for v in mesh.vertex_ids().tolist() if mesh.valence(v) == 2}
    new = split_valence2_vertices(mesh, offset)
    assert len(new) == len(old)
    return [(v, n, o) for (v, o), n in zip(old.items(), new, strict=True)]


def _far_ends(mesh: Mesh, v: int, new: int) -> tuple[int, int]:
    """The other neighbour of each of a split pair: ``v``'s, then ``new``'s."""
    (far_v,) = _neighbours(mesh, v) - {new}
    (far_new,) = _neighbours(mesh, new) - {v}
    return far_v, far_new


def assert_each_moved_toward_its_neighbour(mesh: Mesh, pairs, lengths=None) -> None:
    """Each of a split pair left the old position ``o`` toward its own other
    neighbour (a swapped pair folds the edge back or crosses the corner's edges).
    With ``lengths`` (the pair's two push distances), also where exactly: along
    ``normalize(d_own - d_other)``, ``d`` the unit directions from ``o``."""
    for v, new, o in pairs:
        far_v, far_new = _far_ends(mesh, v, new)
        for moved, far in ((v, far_v), (new, far_new)):
            assert (mesh.position(moved) - o) @ (mesh.position(far) - o) > 0, (moved, far)
        if lengths is None:
            continue
        d_v, d_new = (_unit_vector(mesh.position(far) - o) for far in (far_v, far_new))
        s_v, s_new = lengths(mesh, o, far_v, far_new)
        np.testing.assert_allclose(mesh.position(v), o + s_v * _unit_vector(d_v - d_new))
        np.testing.assert_allclose(mesh.position(new), o + s_new * _unit_vector(d_new - d_v))


def _unit_vector(x: np.ndarray) -> np.ndarray:
    return x / np.linalg.norm(x)


def _cube_with_split_edges() -> Mesh:
    """The edge-2 cube with the midpoints of three edges (one per axis) added:
    three valence-2 vertices, each on a straight line between two corners."""
    m = cube()
    for axis in range(3):
        edge = next(e for e in m.edge_ids().tolist()
                    if np.ptp([m.position(u)[axis] for u in m.edge_vertices(e)]) == 2)
        m.subdivide_edge(edge)
    return m


@pytest.mark.parametrize(("offset", "push"), [(-0.1, 0.1), (0.25, 0.25)])
def test_split_valence2_vertices_keep_the_order_along_a_straight_edge(offset, push):
    # was -1, +0.1, -0.1, +1 along the edge: each vertex pushed toward the other's
    # neighbour, folding the edge back on itself. Each half of an edge 2 is 1 long,
    # so offset -0.1 pushes 0.1 x 1 = 0.1; the faces stay flat squares.
    m = _cube_with_split_edges()
    normals = face_normals(mesh_arrays(m))
    pairs = _split_pairs(m, offset)
    validate(m)
    assert m.counts() == (8 + 6, 12 + 6, 6)
    assert_each_moved_toward_its_neighbour(m, pairs, lambda *_: (push, push))
    for v, new, _ in pairs:
        far_v, far_new = _far_ends(m, v, new)
        # in order along the line: far_v, v, new, far_new
        line = m.position(far_new) - m.position(far_v)
        steps = [m.position(u) @ line for u in (far_v, v, new, far_new)]
        assert steps == sorted(steps)
    np.testing.assert_allclose(face_normals(mesh_arrays(m)), normals, atol=1e-12)


def test_split_valence2_vertices_push_each_by_a_tenth_of_its_own_edge():
    # TopMod's offset <= 0: the vertex moves 0.1 x its kept edge's length, the new
    # one 0.1 x the length of the edge it was put on (here 0.5 and 1.5, in some order)
    m = cube()
    a, b = m.edge_vertices(0)
    (v,) = m.subdivide_edge(0)
    m.set_position(v, 0.75 * m.position(a) + 0.25 * m.position(b))
    pairs = _split_pairs(m, -0.1)
    validate(m)
    assert_each_moved_toward_its_neighbour(
        m, pairs, lambda mesh, o, far_v, far_new: tuple(
            0.1 * np.linalg.norm(mesh.position(far) - o) for far in (far_v, far_new)))


def _segments_cross(p: np.ndarray, q: np.ndarray, r: np.ndarray, s: np.ndarray) -> bool:
    """Whether the 2D segments pq and rs cross at a point inside both."""
    def side(a, b, c):
        return np.sign((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    return side(p, q, r) * side(p, q, s) < 0 and side(r, s, p) * side(r, s, q) < 0


def _crossing_sides(mesh: Mesh, face: int) -> list[tuple[int, int]]:
    """Pairs of non-adjacent sides of ``face`` that cross, in the xz plane."""
    ring = [mesh.position(mesh.corner_vertex(c))[[0, 2]] for c in mesh.face_corners(face)]
    sides = [(ring[i], ring[(i + 1) % len(ring)]) for i in range(len(ring))]
    return [(i, j) for i in range(len(sides)) for j in range(i + 2, len(sides))
            if (i, j) != (0, len(sides) - 1) and _segments_cross(*sides[i], *sides[j])]


def test_split_valence2_vertices_at_the_corners_of_an_open_grid_do_not_cross():
    # a 2 x 2 grid's four corners have valence 2 (two unit edges at right angles);
    # the swapped pair crossed the corner quad's sides. Each moves 0.1 x 1 along the
    # chord of its neighbours, toward its own
    m = grid(2, 2)
    pairs = _split_pairs(m, -0.1)
    validate(m)
    assert m.counts() == (9 + 4, 12 + 4, 5)
    assert_each_moved_toward_its_neighbour(m, pairs, lambda *_: (0.1, 0.1))
    a = mesh_arrays(m)
    quads = a.face_ids[~a.face_hole].tolist()
    assert sorted(m.face_size(f) for f in quads) == [5, 5, 5, 5]
    assert all(not _crossing_sides(m, f) for f in a.face_ids.tolist())
    # every face still faces +y, the grid's side
    np.testing.assert_allclose(face_normals(a)[~a.face_hole], [[0, 1, 0]] * 4, atol=1e-12)


def test_geometry_ops_keep_torus_topology():
    m = torus()
    before = snapshot(m)
    for op in (mesh_smooth, planarize, spheralize):
        op(m)
        validate(m)
    after = snapshot(m)
    assert after[2:] != () and m.counts() == (48, 96, 48)
    assert before[0] != after[0]


@pytest.mark.parametrize(("call", "message"), [
    (lambda m: mesh_smooth(m, 1.5), "iterations must be an integer >= 0"),
    (lambda m: mesh_smooth(m, "2"), "iterations must be an integer >= 0"),
    (lambda m: planarize(m, None), "steps must be an integer >= 0"),
    (lambda m: planarize(m, 2.5), "steps must be an integer >= 0"),
    (lambda m: split_valence2_vertices(m, "2"), "offset must be a number"),
])
def test_arguments_of_the_wrong_type_are_refused(call, message):
    assert_refused(cube(), call, message, error=InvalidArgumentError)


def _far_cube_with_valence2_vertices() -> Mesh:
    """A unit cube with a valence-2 vertex on edge 0-1, then one on edge 2-6 moved
    to (1.79e308, 1.79e308, 0): its new neighbour's push overflows."""
    m = unit_cube()
    for ends in ((0, 1), (2, 6)):
        edge = next(e for e in m.edge_ids().tolist() if set(m.edge_vertices(e)) == set(ends))
        new = m.subdivide_edge(edge)[0]
    m.set_position(new, (1.79e308, 1.79e308, 0.0))
    return m


def test_split_valence2_vertices_that_overflow_change_nothing():
    # the first split succeeds, the second overflows
    assert_refused_quietly(_far_cube_with_valence2_vertices(),
                           lambda m: split_valence2_vertices(m, -1.0),
                           r"splitting valence-2 vertex \d+ by .* would put .* not finite")


def _cube_with_valence2_vertices() -> Mesh:
    m = unit_cube()
    for edge in m.edge_ids()[:2].tolist():
        m.subdivide_edge(edge)
    return m


@pytest.mark.parametrize("scale", [1e160, 1e300])
def test_a_huge_mesh_splits_valence2_vertices_like_the_unit_one(scale):
    # the edge lengths and directions were measured raw: inf, then a NaN position
    # ("expected a position ... of three finite numbers") for a result that exists
    assert_scales(_cube_with_valence2_vertices, lambda m, s: split_valence2_vertices(m, -1.0),
                  scale)


@pytest.mark.parametrize("scale", [1e160, 1.5e308])
def test_a_huge_mesh_spheralizes_like_the_unit_one(scale):
    # raw norms overflowed to inf (every vertex went to the origin); the centroid's
    # sum overflowed near the float maximum
    small, big = unit_cube(), unit_cube()
    big.set_positions(big.vertex_ids(), big.positions_view() * scale)
    spheralize(small)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        spheralize(big)
    np.testing.assert_allclose(big.positions_view(), small.positions_view(), atol=1e-15)


def test_a_mesh_near_the_float_maximum_smooths_like_the_unit_one():
    # the face centroids' sums overflowed: "positions must be finite numbers"
    assert_scales(_diagonal_bumped_cube, lambda m, s: mesh_smooth(m, 2), 1e308)


def _spread_cube() -> Mesh:
    """A unit cube moved 1 along x but for vertex 0, moved to x = -1."""
    m = unit_cube()
    m.set_positions(m.vertex_ids(), m.positions_view() + [1.0, 0.0, 0.0])
    m.set_position(0, (-1.0, 0.0, 0.0))
    return m


def test_a_mesh_spread_over_the_float_range_smooths_like_the_unit_one():
    # vertex 0's move (about 2.1e308) overflowed: refused, though it ends in range
    assert_scales(_spread_cube, lambda m, s: mesh_smooth(m, 2), 8e307)


def test_cleanup_winged_vertices_keeps_a_vertex_whose_faces_are_2gons():
    m = Mesh()
    m.create_face([(0, 0, 0), (1, 0, 0), (0, 1, 0)])  # two-sided: every vertex has valence 2
    assert cleanup_winged_vertices(m) == 1  # then the other two sit on two 2-gons
    validate(m)
    assert m.counts() == (2, 2, 2)


def _diagonal_bumped_cube():
    m = bumped_cube()
    c = m.face_corners(2)  # a flat face (vertex 0 is the bumped one): a removable diagonal
    m.insert_edge(c[0], c[2])
    return m


@pytest.mark.parametrize("op", [lambda m, s: mesh_smooth(m, 3),
                                lambda m, s: planarize(m, 20), lambda m, s: edge_cleanup(m)])
def test_a_huge_mesh_smooths_and_flattens_like_the_unit_one(op):
    # the face normals of raw products overflowed past ~1e77 and came out zero
    assert_scales(_diagonal_bumped_cube, op)


# -- edge_cleanup refuses edges that are not ids; cleanup_2gons keeps a lone edge


@pytest.mark.parametrize("edges", [5, "01", [0, 1.5]])
def test_edge_cleanup_refuses_edges_that_are_not_ids(edges):
    # 5 raised TypeError; 1.5 was skipped as if it were a deleted edge
    assert_refused(unit_cube(), lambda m: edge_cleanup(m, edges), "edges must",
                   error=InvalidArgumentError)


def test_cleanup_2gons_keeps_a_lone_edge():
    # its 2-corner face runs along both sides of one edge: deleting that edge
    # (with cleanup) removed both vertices, the whole component
    m = unit_cube()
    a, b = m.create_vertex((5, 0, 0)), m.create_vertex((6, 0, 0))
    m.insert_edge(m.vertex_corner(a), m.vertex_corner(b))
    m.insert_edge(0, 1)  # a 2-gon inside the bottom face of the cube
    assert cleanup_2gons(m) == 1
    validate(m)
    assert m.counts() == (10, 13, 7) and m.has_vertex(a) and m.has_vertex(b)
