"""Sculpting cuts (livemod.dlfl.cutting) and their commands: cut vertices, edges, faces
at an offset and by planes, peeling by a plane; truncate."""

from __future__ import annotations

from functools import partial

import numpy as np
import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import Mesh, Selection, cutting, face_size_histogram, genus, validate
from livemod.dlfl.analysis import corner_normals, face_normals, face_points
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.build import from_polygons
from livemod.dlfl.commands import cutEdges, cutFaces, cutVertices, truncate
from livemod.dlfl.cutting import truncate as truncate_mesh
from livemod.dlfl.errors import GeometryError, InvalidArgumentError, UnknownIdError
from livemod.dlfl.shapes import cube, grid, icosahedron, spherical_cube, torus
from livemod.dlfl.subdivision import vertex_cut
from tests.meshes import (
    assert_refused,
    canonical,
    colour_counts,
    counts,
    euler_ok,
    path_face,
    point_sphere,
    rainbow_cube,
    snapshot,
    two_cubes,
)
from tests.meshes import triangle as open_triangle

# the cuts with their points offset along the edges (the plane cuts are further down)
cut_vertices = partial(cutting.cut_vertices, placement="offset")
cut_edges = partial(cutting.cut_edges, placement="offset")
cut_faces = partial(cutting.cut_faces, placement="offset")


def checked(mesh: Mesh, op, *args) -> list[int]:
    """Run ``op(mesh, *args)``; the mesh stays valid, Euler-consistent, same genus."""
    before = genus(mesh)
    caps = op(mesh, *args)
    validate(mesh)
    assert euler_ok(mesh)
    assert genus(mesh) == before
    return caps


def neighbours(mesh: Mesh, v: int) -> list[int]:
    return [mesh.corner_vertex(mesh.corner_next(c)) for c in mesh.vertex_corners(v)]


def new_points(before: Mesh, after: Mesh) -> list[tuple[float, ...]]:
    """Sorted positions of the vertices ``after`` has and ``before`` had not."""
    new = sorted(set(after.vertex_ids().tolist()) - set(before.vertex_ids().tolist()))
    return sorted(tuple(np.round(after.position(v), 9)) for v in new)


def along(mesh: Mesh, pairs: list[tuple[int, int]], t: float) -> list[tuple[float, ...]]:
    """Sorted points ``t`` of the way from ``a`` to ``b`` for each ``(a, b)``."""
    return sorted(tuple(np.round((1 - t) * mesh.position(a) + t * mesh.position(b), 9))
                  for a, b in pairs)


def bumpy_icosahedron() -> Mesh:
    """An icosahedron with every vertex moved a little: no symmetry left."""
    m = icosahedron()
    rng = np.random.default_rng(7)
    m.set_positions(m.vertex_ids(), m.positions_view() * rng.uniform(0.8, 1.2, (12, 1)))
    return m


# -- TopMod's cube ---------------------------------------------------------------------

def test_cut_one_cube_vertex():
    m = cube()
    around = m.vertex_faces(0)
    caps = checked(m, cut_vertices, [0])
    assert m.counts() == (10, 15, 7)
    assert face_size_histogram(m) == {3: 1, 4: 3, 5: 3}
    assert m.face_size(caps[0]) == 3 and not m.has_vertex(0)
    assert [m.face_size(f) for f in around] == [5, 5, 5]  # the faces around keep their ids


def test_cut_one_cube_edge():
    m = cube()
    a, b = m.edge_vertices(0)
    caps = checked(m, cut_edges, [0])
    assert m.counts() == (10, 15, 7)
    assert face_size_histogram(m) == {4: 5, 5: 2}
    assert m.face_size(caps[0]) == 4
    assert not (m.has_edge(0) or m.has_vertex(a) or m.has_vertex(b))


def test_cut_one_cube_face_makes_a_lower_box():
    m = cube()
    caps = checked(m, cut_faces, [0])  # the top face, y = 1
    assert m.counts() == (8, 12, 6)
    assert face_size_histogram(m) == {4: 6}
    assert sorted(set(m.positions_view()[:, 1].tolist())) == [-1.0, 0.5]
    assert np.allclose([m.position(v)[1] for v in m.face_vertices(caps[0])], 0.5)


def test_truncate_the_cube():
    m = cube()
    faces = m.face_ids().tolist()
    caps = checked(m, truncate_mesh)
    assert m.counts() == (24, 36, 14)
    assert face_size_histogram(m) == {3: 8, 8: 6}
    assert [m.face_size(f) for f in faces] == [8] * 6  # the old faces keep their ids
    assert len(caps) == 8 and all(m.face_size(c) == 3 for c in caps)


def test_cutting_every_vertex_is_truncation():
    m = cube()
    checked(m, cut_vertices, m.vertex_ids().tolist())
    assert m.counts() == (24, 36, 14)


# -- positions -------------------------------------------------------------------------

@pytest.mark.parametrize("t", [0.25, 0.1, 0.6])
def test_vertex_cut_points_lie_offset_along_each_edge(t):
    m = bumpy_icosahedron()
    before = m.copy()
    checked(m, cut_vertices, [0], t)
    assert new_points(before, m) == along(before, [(0, u) for u in neighbours(before, 0)], t)


def test_edge_cut_points_lie_offset_along_the_other_edges():
    m = bumpy_icosahedron()
    before = m.copy()
    e = m.vertex_edges(0)[0]
    a, b = m.edge_vertices(e)
    checked(m, cut_edges, [e], 0.3)
    pairs = [(v, u) for v in (a, b) for u in neighbours(before, v) if u not in (a, b)]
    assert new_points(before, m) == along(before, pairs, 0.3)


def test_face_cut_points_lie_offset_along_the_edges_leaving_it():
    m = bumpy_icosahedron()
    before = m.copy()
    ring = m.face_vertices(0)
    checked(m, cut_faces, [0], 0.4)
    pairs = [(v, u) for v in ring for u in neighbours(before, v) if u not in ring]
    assert new_points(before, m) == along(before, pairs, 0.4)


def test_everything_outside_the_cut_keeps_its_id_and_place():
    m = cube()
    before = m.copy()
    checked(m, cut_vertices, [0])
    for v in range(1, 8):
        assert np.array_equal(m.position(v), before.position(v))
    untouched = [f for f in before.face_ids().tolist() if 0 not in before.face_vertices(f)]
    for f in untouched:
        assert m.face_vertices(f) == before.face_vertices(f)


def test_truncate_matches_the_vertex_cut_scheme():
    for make in (cube, icosahedron, lambda: torus(4, 3)):
        local, remeshed = make(), make()
        checked(local, truncate_mesh, 0.2)
        vertex_cut(remeshed, offset=0.2)
        assert canonical(local) == canonical(remeshed)


# -- other meshes ----------------------------------------------------------------------

def test_icosahedron_vertex():
    m = icosahedron()
    checked(m, cut_vertices, [0])
    assert m.counts() == (16, 35, 21)
    assert face_size_histogram(m) == {3: 15, 4: 5, 5: 1}


def test_torus_cuts_keep_genus_one():
    m = torus(8, 6)
    caps = checked(m, cut_faces, [0], 0.3)
    assert m.counts() == (52, 100, 48)
    assert m.face_size(caps[0]) == 8  # two edges leave each corner of a quad
    checked(m, cut_edges, [m.face_edges(20)[0]])
    checked(m, cut_vertices, [40, 45])
    checked(m, truncate_mesh, 0.2)
    assert genus(m) == 1


def test_far_apart_vertices_take_offsets_up_to_one():
    m = cube()
    checked(m, cut_vertices, [0, 6], 0.75)  # opposite corners: no shared edge
    assert m.counts() == (12, 18, 8)


def test_adjacent_vertices_get_separate_faces():
    m = cube()
    a, b = m.edge_vertices(0)
    caps = checked(m, cut_vertices, [a, b], 0.4)
    assert m.counts() == (12, 18, 8) and len(set(caps)) == 2


def test_edges_sharing_a_vertex_make_one_face():
    m = cube()
    path = m.vertex_edges(0)[:2]
    caps = checked(m, cut_edges, path)
    assert len(caps) == 1 and m.face_size(caps[0]) == 5
    assert m.counts() == (10, 15, 7)


def test_separate_edges_get_faces_in_the_order_given():
    m = cube()
    x = 0
    y = next(e for e in m.edge_ids().tolist()
             if not set(m.edge_vertices(e)) & set(m.edge_vertices(x)))
    middle = {e: (m.position(m.edge_vertices(e)[0]) + m.position(m.edge_vertices(e)[1])) / 2
              for e in (x, y)}
    caps = checked(m, cut_edges, [y, x])
    assert m.counts() == (12, 18, 8)
    for cap, e in zip(caps, (y, x), strict=True):
        centre = np.mean([m.position(v) for v in m.face_vertices(cap)], axis=0)
        assert np.linalg.norm(centre - middle[e]) < 0.5


def test_an_edge_joining_two_groups_merges_them():
    m = torus(8, 6)
    a, b, c = 0, 1, 2  # vertices along one ring of the torus
    ab, bc = (next(e for e in m.vertex_edges(u) if set(m.edge_vertices(e)) == {u, w})
              for u, w in ((a, b), (b, c)))
    far = next(e for e in m.vertex_edges(c) if e != bc)
    caps = checked(m, cut_edges, [ab, far, bc])
    assert len(caps) == 1  # ab and far joined through bc: one path, one face


def test_opposite_faces_cut_together():
    m = cube()
    checked(m, cut_faces, [0, 5])
    assert m.counts() == (8, 12, 6)
    assert sorted(set(m.positions_view()[:, 1].tolist())) == [-0.5, 0.5]


def test_a_concave_vertex_is_cut_too():
    m = cube()
    m.set_position(0, (0.2, 0.2, 0.2))  # pushed inside: TopMod's plane missed it
    checked(m, cut_vertices, [0])
    assert m.counts() == (10, 15, 7)


def test_open_mesh_boundary_vertex_cap_is_a_face():
    m = open_triangle()
    holes = [f for f in m.face_ids().tolist() if m.is_hole(f)]
    caps = checked(m, cut_vertices, [0])
    assert m.face_size(caps[0]) == 2 and not m.is_hole(caps[0])
    assert [f for f in m.face_ids().tolist() if m.is_hole(f)] == holes
    g = grid()
    checked(g, truncate_mesh)
    assert sum(g.is_hole(f) for f in g.face_ids().tolist()) == 1


def test_a_face_that_visits_the_vertex_twice():
    m = path_face()
    caps = checked(m, cut_vertices, [1])
    assert m.face_size(caps[0]) == 2


def test_nothing_to_cut_is_a_no_op():
    m = cube()
    before = m.copy()
    assert cut_vertices(m, []) == cut_edges(m, []) == cut_faces(m, []) == []
    assert canonical(m) == canonical(before)


def test_repeated_ids_count_once():
    m = cube()
    assert len(checked(m, cut_vertices, [0, 0])) == 1
    assert m.counts() == (10, 15, 7)


# -- refused input ---------------------------------------------------------------------

def self_loop_cube() -> Mesh:
    """The cube with a self-loop at vertex 0 (a handle through two of its corners)."""
    m = cube()
    c1, c2 = m.vertex_corners(0)[:2]
    m.insert_edge(c1, c2)
    return m


def dangling_cube() -> tuple[Mesh, int]:
    """The cube with an edge from vertex 0 to a new vertex of valence 1."""
    m = cube()
    v = m.create_vertex((2, 2, 2))
    m.insert_edge(m.vertex_corner(0), m.vertex_corner(v))
    return m, v


@pytest.mark.parametrize(("offset", "message"), [
    (0, "strictly between 0 and 1"), (1, "strictly between 0 and 1"),
    (-0.25, "strictly between"), (1.5, "strictly between"), (float("nan"), "finite"),
    (float("inf"), "finite"), ("0.25", "must be a number"), (True, "must be a number"),
])
def test_offsets_out_of_range(offset, message):
    for op in (cut_vertices, cut_edges, cut_faces):
        assert_refused(cube(), lambda m, op=op: op(m, [0], offset), f"offset .*{message}",
                       error=InvalidArgumentError)
    assert_refused(cube(), lambda m: truncate_mesh(m, offset), f"offset .*{message}",
                   error=InvalidArgumentError)


def test_offsets_that_would_cross_on_a_shared_edge():
    a, b = cube().edge_vertices(0)
    assert_refused(cube(), lambda m: cut_vertices(m, [a, b], 0.5),
                   r"edge 0 is cut from both ends: offset must be below 0.5",
                   error=InvalidArgumentError)
    assert_refused(cube(), lambda m: truncate_mesh(m, 0.5), "offset must be below 0.5",
                   error=InvalidArgumentError)


def test_missing_and_deleted_ids():
    assert_refused(cube(), lambda m: cut_vertices(m, [0, 99]), "vertex 99 does not exist",
                   error=UnknownIdError)
    assert_refused(cube(), lambda m: cut_edges(m, [99]), "edge 99 does not exist",
                   error=UnknownIdError)
    assert_refused(cube(), lambda m: cut_faces(m, [99]), "face 99 does not exist",
                   error=UnknownIdError)
    m = cube()
    cut_vertices(m, [0])
    assert_refused(m, lambda m: cut_vertices(m, [0]), "vertex 0 was deleted", error=UnknownIdError)
    assert_refused(cube(), lambda m: cut_vertices(m, [0.5]), "vertices must hold ids",
                   error=InvalidArgumentError)
    assert_refused(cube(), lambda m: cut_faces(m, 3), "faces must be a list of ids",
                   error=InvalidArgumentError)


def test_point_spheres():
    assert_refused(point_sphere(), lambda m: cut_vertices(m, [0]), "vertex 0 is a point-sphere",
                   error=InvalidArgumentError)
    assert_refused(point_sphere(), lambda m: cut_faces(m, [0]), "face of point-sphere 0",
                   error=InvalidArgumentError)
    m = point_sphere()
    assert checked(m, truncate_mesh) == [] and m.counts() == (1, 0, 1)


def test_hole_faces():
    m = open_triangle()
    hole = next(f for f in m.face_ids().tolist() if m.is_hole(f))
    assert_refused(m, lambda m: cut_faces(m, [hole]), f"face {hole} is a hole",
                   error=InvalidArgumentError)


def test_self_loops_and_lone_edges():
    assert_refused(self_loop_cube(), lambda m: cut_vertices(m, [0]), "vertex 0 has a self-loop",
                   error=InvalidArgumentError)
    loop = int(self_loop_cube().edge_ids()[-1])  # the last edge made
    assert_refused(self_loop_cube(), lambda m: cut_edges(m, [loop]), f"edge {loop} is a self-loop",
                   error=InvalidArgumentError)
    assert_refused(self_loop_cube(), lambda m: truncate_mesh(m), "self-loop",
                   error=InvalidArgumentError)
    m, v = dangling_cube()
    assert_refused(m, lambda m: cut_vertices(m, [v]), f"vertex {v}: only 1 edge",
                   error=InvalidArgumentError)


def test_edges_closing_a_cycle():
    m = cube()
    assert_refused(m, lambda m: cut_edges(m, m.face_edges(0)), "close a cycle",
                   error=InvalidArgumentError)


def test_faces_sharing_a_vertex():
    assert_refused(cube(), lambda m: cut_faces(m, [0, 1]), "face 0 and face 1 share vertex",
                   error=InvalidArgumentError)


def test_a_face_visiting_a_vertex_twice():
    assert_refused(path_face(), lambda m: cut_faces(m, [0]), "visits vertex 1 more than once",
                   error=InvalidArgumentError)


def test_a_whole_component_cannot_be_cut_away():
    m = Mesh()
    front, _ = m.create_face([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    assert_refused(m, lambda m: cut_faces(m, [front]), r"only 0 edge\(s\) leave it",
                   error=InvalidArgumentError)


# -- plane placement (TopMod's) and peeling -------------------------------------------

def peeled(mesh: Mesh, *args, **kwargs) -> list[int]:
    """``cutting.cut_plane(mesh, *args, **kwargs)``; the mesh stays valid and
    Euler-consistent (its genus may fall: the plane can cut a handle)."""
    caps = cutting.cut_plane(mesh, *args, **kwargs)
    validate(mesh)
    assert euler_ok(mesh)
    return caps


def on_plane(mesh: Mesh, vertices: list[int], point: object, normal: object) -> bool:
    n = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    return all(abs(float((mesh.position(v) - np.asarray(point)) @ n)) < 1e-12 for v in vertices)


def new_vertices(before: Mesh, after: Mesh) -> list[int]:
    return sorted(set(after.vertex_ids().tolist()) - set(before.vertex_ids().tolist()))


@pytest.mark.parametrize("op, ids, expected", [
    (cutting.cut_vertices, [0], ((10, 15, 7), {3: 1, 4: 3, 5: 3})),
    (cutting.cut_edges, [0], ((10, 15, 7), {4: 5, 5: 2})),
    (cutting.cut_faces, [0], ((8, 12, 6), {4: 6})),
])
def test_plane_cuts_of_the_cube_are_topmods(op, ids, expected):
    # each plane passes through the points 0.25 along the edges: the same points
    m, offset_cut = cube(), cube()
    caps = checked(m, op, ids)
    op(offset_cut, ids, placement="offset")
    assert (m.counts(), face_size_histogram(m)) == expected and len(caps) == 1
    assert canonical(m) == canonical(offset_cut)


def test_a_vertex_cut_of_a_warped_mesh_ends_on_its_plane():
    m = spherical_cube()
    v = next(v for v in m.vertex_ids().tolist() if m.valence(v) == 4)
    before = m.copy()
    far = neighbours(m, v)
    a = mesh_arrays(m)
    corners = np.flatnonzero(a.vertex_ids[a.corner_vertex] == v)
    normal = corner_normals(a)[corners].mean(axis=0)
    point = np.mean([m.position(v) + 0.3 * (m.position(w) - m.position(v)) for w in far], axis=0)
    caps = checked(m, cutting.cut_vertices, [v], 0.3)
    new = new_vertices(before, m)
    assert m.counts() == (98 + 3, 192 + 4, 96 + 1) and len(new) == 4
    assert on_plane(m, new, point, normal)
    assert sorted(m.face_vertices(caps[0])) == new
    for w in far:  # each new point on the edge to a neighbour, between the two
        p, q = before.position(v), before.position(w)
        assert any(np.linalg.norm(np.cross(m.position(x) - p, q - p)) < 1e-12 for x in new)


def test_an_offset_past_the_neighbours_cuts_the_cube_through_its_centre():
    m = cube()
    corner = next(v for v in m.vertex_ids().tolist() if (m.position(v) > 0).all())
    # the points 1.5 along the corner's edges average to the centre: plane x + y + z = 0
    caps = checked(m, cutting.cut_vertices, [corner], 1.5)
    assert m.counts() == (10, 15, 7) and face_size_histogram(m) == {3: 3, 5: 3, 6: 1}
    assert on_plane(m, m.face_vertices(caps[0]), (0, 0, 0), (1, 1, 1))
    assert sorted(np.abs(face_points(m, caps[0])).sum(axis=1).round(12).tolist()) == [2.0] * 6


def test_peeling_the_cube_by_a_plane():
    m = cube()
    before = m.copy()
    caps = peeled(m, (0, 0.5, 0), (0, 1, 0))
    assert m.counts() == (8, 12, 6) and face_size_histogram(m) == {4: 6}
    assert on_plane(m, m.face_vertices(caps[0]), (0, 0.5, 0), (0, 1, 0))
    assert len(new_vertices(before, m)) == 4


def test_peeling_a_torus_through_two_rings_of_its_vertices():
    # torus(8, 6) about the y axis: rings 2 and 6 lie on x = 0 and become the caps;
    # rings 7, 0, 1 (18 vertices, 42 edges, 24 quads with rings 2 and 6) go
    m = torus(8, 6)
    before = m.copy()
    caps = peeled(m, (0, 0, 0), (1, 0, 0))
    assert m.counts() == (48 - 18, 96 - 42, 48 - 24 + 2) and genus(m) == 0
    assert [m.face_size(f) for f in caps] == [6, 6] and new_vertices(before, m) == []


def test_peeling_the_top_off_a_torus_leaves_two_caps():
    # the 16 vertices above y = 0.3 go with their 24 edges and 8 quads; the 16
    # edges down to y = 0 are cut, and 16 quads get a new side each: two loops
    m = torus(8, 6)
    caps = peeled(m, (0, 0.3, 0), (0, 1, 0))
    assert m.counts() == (48, 96 - 24 + 16, 48 - 8 + 2) and genus(m) == 0
    assert sorted(m.face_size(f) for f in caps) == [8, 8]
    assert all(on_plane(m, m.face_vertices(f), (0, 0.3, 0), (0, 1, 0)) for f in caps)


def u_prism() -> Mesh:
    """A U-shaped prism, 16/24/10: its top and bottom are U-shaped octagons."""
    u = [(0, 0), (3, 0), (3, 2), (2, 2), (2, 1), (1, 1), (1, 2), (0, 2)]
    pos = [(x, y, z) for z in (0, 1) for x, y in u]
    sides = [[i, (i + 1) % 8, 8 + (i + 1) % 8, 8 + i] for i in range(8)]
    return from_polygons(np.array(pos, dtype=float), [list(range(8))[::-1], list(range(8, 16)),
                                                      *sides])


def test_a_face_crossed_four_times_loses_each_piece_on_its_own():
    # y = 1.5 crosses the U's top and bottom four times each: both arm tips go
    m = u_prism()
    caps = peeled(m, (0, 1.5, 0), (0, 1, 0))
    assert m.counts() == (16, 24, 10) and face_size_histogram(m) == {4: 8, 8: 2}
    assert len(caps) == 2 and all(m.face_size(f) == 4 for f in caps)
    assert all(on_plane(m, m.face_vertices(f), (0, 1.5, 0), (0, 1, 0)) for f in caps)


def test_a_seed_limits_the_cut_to_its_own_part():
    m = two_cubes()  # unit cubes at x = 0 and x = 3
    seed = next(v for v in m.vertex_ids().tolist() if (m.position(v) == 1).all())
    peeled(m, (0, 0.5, 0), (0, 1, 0), seed=seed)
    assert m.counts() == (16, 24, 12)
    assert sorted(set(m.positions_view()[:, 1].round(12).tolist())) == [0.0, 0.5, 1.0]


def test_peel_cuts_the_whole_mesh_by_each_plane():
    # the plane of cube 0's face x = 1 (offset 0.25: x = 0.75) leaves the other cube
    # wholly beyond it: peeled, it goes (without a cap); cut locally, it stays
    face = next(f for f in range(6) if (face_points(two_cubes(), f)[:, 0] == 1).all())
    local, peeled = two_cubes(), two_cubes()
    checked(local, cutting.cut_faces, [face])
    cutting.cut_faces(peeled, [face], peel=True)
    validate(peeled)
    assert local.counts() == (16, 24, 12) and peeled.counts() == (8, 12, 6)
    assert peeled.positions_view()[:, 0].max() == 0.75


def test_plane_cut_refusals():
    m = cube()
    m.set_position(0, (0.2, 0.2, 0.2))  # pushed in: it lies before its own plane
    assert_refused(m, lambda m: cutting.cut_vertices(m, [0]), "near side of its cutting plane",
                   GeometryError)
    assert_refused(cube(), lambda m: cutting.cut_vertices(m, [0], 0), "offset must be a number > 0")
    assert_refused(cube(), lambda m: cutting.cut_vertices(m, [0], placement="edge"),
                   "placement must be one of 'plane', 'offset'")
    assert_refused(cube(), lambda m: cutting.cut_edges(m, [0], placement="offset", peel=True),
                   "needs placement='plane'")
    assert_refused(cube(), lambda m: cutting.cut_plane(m, (0, 0, 0), (0, 0, 0)),
                   "normal must not be zero")
    assert_refused(cube(), lambda m: cutting.cut_plane(m, (0, 0), (0, 1, 0)),
                   "point must be three finite numbers")
    low = next(v for v in cube().vertex_ids().tolist() if cube().position(v)[1] < 0)
    assert_refused(cube(), lambda m: cutting.cut_plane(m, (0, 0.5, 0), (0, 1, 0), seed=low),
                   f"seed vertex {low} lies on the near side")


def test_a_plane_beyond_the_mesh_cuts_nothing():
    m = cube()
    before = snapshot(m)
    assert cutting.cut_plane(m, (0, 2, 0), (0, 1, 0)) == [] and snapshot(m) == before


def test_the_plane_through_a_face_is_its_centroid_and_normal():
    m = spherical_cube()
    point, normal = cutting.plane_of_face(m, 5)
    np.testing.assert_allclose(point, face_points(m, 5).mean(axis=0), atol=1e-15)
    np.testing.assert_allclose(normal, face_normals(m)[list(m.face_ids()).index(5)], atol=1e-15)


# -- commands --------------------------------------------------------------------------

def test_star_import_gives_the_cutting_commands():
    for name in ("cutVertices", "cutEdges", "cutFaces", "cutPlane", "truncate"):
        assert name in dlfl.__all__ and callable(getattr(dlfl, name))


def test_commands_default_to_the_selection(scene):
    scene.selection = Selection(vertices=(0,))
    caps = cutVertices()
    assert counts(scene) == (10, 15, 7) and scene.mesh.face_size(caps[0]) == 3
    scene.selection = Selection(faces=(caps[0],))
    cutFaces(offset=0.5)
    assert counts(scene) == (10, 15, 7)
    scene.selection = Selection()
    assert cutEdges() == []


def test_commands_take_ids(scene):
    cutEdges(0)
    assert counts(scene) == (10, 15, 7)
    cutFaces([5], 0.5)
    validate(scene.mesh)


def test_truncate_command_records_one_step(scene, run):
    labels: list[str] = []
    run.step_hook = labels.append
    assert len(truncate()) == 8
    assert counts(scene) == (24, 36, 14) and labels == ["truncate"]


def test_cut_plane_command_takes_a_plane_or_a_face(scene):
    caps = dlfl.cutPlane((0, 0.5, 0), (0, 1, 0))
    assert counts(scene) == (8, 12, 6) and len(caps) == 1
    assert dlfl.cutPlane(faceid=caps[0]) == []  # nothing lies beyond the new top
    assert counts(scene) == (8, 12, 6)
    validate(scene.mesh)


def test_cutting_commands_take_placement_and_peel(scene):
    cutVertices(0, 0.25, "offset")
    assert counts(scene) == (10, 15, 7)
    cutFaces([1], 0.25, peel=True)
    validate(scene.mesh)


def test_refused_command_leaves_the_object(scene):
    mesh = scene.mesh
    assert_refused(mesh, lambda _: cutFaces([0, 1], placement="offset"), "share vertex",
                   error=InvalidArgumentError)
    assert_refused(mesh, lambda _: cutVertices(0, 2.0, "offset"), "offset",
                   error=InvalidArgumentError)
    assert_refused(mesh, lambda _: cutVertices("0"), "vertexids must be a list of ids",
                   error=InvalidArgumentError)
    assert_refused(mesh, lambda _: dlfl.cutPlane((0, 0, 0)), "needs point and normal, or faceid",
                   error=InvalidArgumentError)
    assert_refused(mesh, lambda _: dlfl.cutPlane((0, 0, 0), (0, 1, 0), faceid=0), "not both",
                   error=InvalidArgumentError)


# -- face colours --------------------------------------------------------------------

def test_a_cap_has_no_colour_and_the_faces_cut_keep_theirs():
    m = rainbow_cube()
    (cap,) = cut_vertices(m, [0])
    validate(m)
    assert m.face_color(cap) is None
    assert colour_counts(m) == {**{f: 1 for f in range(6)}, None: 1}
    m = rainbow_cube()
    (cap,) = cut_faces(m, [0])
    assert m.face_color(cap) is None
    assert colour_counts(m) == {**{f: 1 for f in range(1, 6)}, None: 1}


def test_truncate_keeps_every_face_colour_and_gives_the_caps_none():
    m = rainbow_cube()
    caps = truncate_mesh(m)
    validate(m)
    assert all(m.face_color(cap) is None for cap in caps) and len(caps) == 8
    assert colour_counts(m) == {**{f: 1 for f in range(6)}, None: 8}


@pytest.mark.parametrize("cut", [
    partial(cutting.cut_vertices, vertices=[0]), partial(cutting.cut_edges, edges=[0]),
    partial(cutting.cut_faces, faces=[0]),
    partial(cutting.cut_plane, point=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 1.0)),
])
def test_plane_cuts_refuse_coordinates_their_arithmetic_would_overflow(cut) -> None:
    mesh = dlfl.shapes.cube()
    a = mesh_arrays(mesh)
    mesh.set_positions(a.vertex_ids, a.positions * 1.2e308)
    before = mesh_arrays(mesh).positions.copy()
    with np.errstate(over="raise", invalid="raise"), pytest.raises(GeometryError, match=r"^a plane cut needs coordinates within 1e\+150; "
                                               r"this mesh has one of 1.2e\+308 \(scale it down"):
        cut(mesh)
    assert mesh.counts() == (8, 12, 6)
    assert np.array_equal(mesh_arrays(mesh).positions, before)
    validate(mesh)


@pytest.mark.parametrize("cut", [cutting.cut_vertices, cutting.cut_edges, cutting.cut_faces])
def test_plane_cuts_refuse_an_offset_that_overflows(cut) -> None:
    mesh = dlfl.shapes.cube()
    with np.errstate(over="raise", invalid="raise"), pytest.raises(
            InvalidArgumentError, match=r"^offset 1e\+308 puts the plane's points beyond 1e\+150 "
                                        r"from the origin; use a smaller offset$"):
        cut(mesh, [0], 1e308)
    assert mesh.counts() == (8, 12, 6)
    validate(mesh)
