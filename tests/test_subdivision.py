"""Remeshing schemes: TopMod's cube table, counts on other meshes, genus, odd inputs."""

from __future__ import annotations

import inspect
import warnings

import numpy as np
import pytest

from livemod.dlfl import DLFLError, Mesh, budget, mesh_arrays, validate
from livemod.dlfl.analysis import face_centroid, face_size_histogram, genus, num_components
from livemod.dlfl.errors import (
    BudgetExceededError,
    GeometryError,
    InvalidArgumentError,
    UnknownIdError,
)
from livemod.dlfl.shapes import cube, grid, load_shape, torus
from livemod.dlfl.subdivision import COMPOSITES, SCHEMES, subdivide, subdivide_faces
from livemod.dlfl.subdivision._sizes import SIZES
from tests.meshes import (
    assert_refused_quietly,
    assert_scales,
    euler_ok,
    path_face,
    snapshot,
    two_cubes,
)
from tests.meshes import cube as unit_cube
from tests.meshes import torus as small_torus

# TOPMOD.md section 3, row by row: scheme -> (V, E, F, {face size: count})
CUBE_TABLE = {
    "loop": (20, 48, 30, {3: 24, 4: 6}),
    "checker": (56, 108, 54, {4: 54}),
    "simplest": (12, 24, 14, {3: 8, 4: 6}),
    "vertex-cut": (24, 36, 14, {3: 8, 8: 6}),
    "pentagon": (38, 60, 24, {5: 24}),
    "pentagon-preserve": (44, 72, 30, {4: 6, 5: 24}),
    "dual-pentagon": (44, 72, 30, {4: 6, 5: 24}),
    "honeycomb": (24, 36, 14, {4: 6, 6: 8}),
    "doo-sabin": (24, 48, 26, {3: 8, 4: 18}),
    "doo-sabin-bc": (48, 84, 38, {3: 8, 4: 24, 8: 6}),
    "doo-sabin-bc-new": (56, 84, 30, {5: 24, 8: 6}),
    "corner-cut": (24, 48, 26, {3: 8, 4: 18}),
    "modified-corner-cut": (24, 48, 26, {3: 8, 4: 18}),
    "root4": (32, 48, 18, {4: 6, 6: 12}),
    "catmull-clark": (26, 48, 24, {4: 24}),
    "star": (38, 108, 72, {3: 72}),
    "sqrt3": (14, 36, 24, {3: 24}),
    "fractal": (26, 72, 48, {3: 48}),
    "stellate": (14, 24, 12, {4: 12}),
    "double-stellate": (38, 72, 36, {4: 36}),
    "dome": (716, 1392, 678, {4: 672, 16: 6}),
    "dual-12.6.4": (48, 72, 26, {4: 12, 6: 8, 8: 6}),
    "loop-style": (20, 48, 30, {3: 24, 4: 6}),
    "linear-vertex": (26, 48, 24, {4: 24}),
    "allfaces": (26, 48, 24, {4: 24}),
    "triangulate": (14, 36, 24, {3: 24}),
    "dual": (6, 12, 8, {3: 8}),
    "root3": (14, 36, 24, {3: 24}),
    "root-3": (14, 36, 24, {3: 24}),
    "cubic-pentagonalization": (38, 60, 24, {5: 24}),
    "dual-pentagonalization": (24, 60, 38, {3: 32, 4: 6}),
    "dual-pentagon-preserving": (32, 72, 42, {3: 24, 4: 18}),
    "six-preserving-loop-style": (20, 48, 30, {3: 24, 4: 6}),
    "dual-loop": (32, 48, 18, {4: 6, 6: 12}),
    "12.6.4": (26, 72, 48, {3: 48}),
    "dual-checkerboard": (56, 108, 54, {4: 54}),
    "sierpinsky": (20, 60, 32, {3: 24, 6: 8}),
}
# schemes whose results TOPMOD.md gives with options
CUBE_OPTIONS = {"linear-vertex": {"usequads": False}}

ALL_SCHEMES = sorted(set(SCHEMES) - {"subdivide-all-edges"})
# implemented by the sculpting family (wireframe.py, sierpinsky.py), registered here
DELEGATED = {"modified-corner-cut", "sierpinsky"}
OWN_SCHEMES = sorted(set(ALL_SCHEMES) - DELEGATED)


def checked(mesh: Mesh) -> tuple[int, int, int]:
    validate(mesh)
    assert euler_ok(mesh)
    return mesh.counts()


@pytest.mark.parametrize("scheme", sorted(CUBE_TABLE))
def test_cube_table_row(scheme):
    v, e, f, sizes = CUBE_TABLE[scheme]
    m = cube()
    subdivide(m, scheme)
    assert checked(m) == (v, e, f)
    assert dict(face_size_histogram(m)) == sizes
    assert genus(m) == (5 if scheme == "sierpinsky" else 0)


# -- the registry: every scheme is whole (docs/architecture.md, "A subdivision scheme")

def test_every_registered_scheme_has_a_cube_row():
    missing = sorted(set(ALL_SCHEMES) - set(CUBE_TABLE))
    assert not missing, (f"schemes without a row in CUBE_TABLE (tests/test_subdivision.py), "
                         f"their (V, E, F, face sizes) on the cube: {missing}")


def test_every_scheme_built_here_has_its_size_from_counts():
    """The face budget refuses a too-large result from ``SIZES`` before building;
    an alias (the same function under another name) shares its scheme's entry."""
    missing = [name for name, scheme in SCHEMES.items() if name not in COMPOSITES
               and not {other for other, f in SCHEMES.items() if f is scheme} & set(SIZES)]
    assert not missing, (f"schemes without their result's size in SIZES "
                         f"(livemod/dlfl/subdivision/_sizes.py): {missing}")


@pytest.mark.parametrize("name", sorted(SCHEMES))
def test_every_scheme_takes_the_mesh_then_keyword_options_and_max_faces(name):
    """``scheme_options`` (and so ``subdivide(name, *options)`` in a script) reads a
    scheme's options from its keyword-only parameters, in their order."""
    mesh, *options = inspect.signature(SCHEMES[name]).parameters.values()
    assert mesh.kind is inspect.Parameter.POSITIONAL_OR_KEYWORD, name
    positional = [p.name for p in options if p.kind is not inspect.Parameter.KEYWORD_ONLY]
    assert not positional, (f"scheme {name!r}: options {positional} must be keyword-only "
                            f"(after '*'): scripts pass options by the signature's order")
    assert "max_faces" in [p.name for p in options], (
        f"scheme {name!r} takes no max_faces: the face budget needs it")


def test_gui_stellate_is_linear_vertex_with_triangles():
    m = cube()
    subdivide(m, "linear-vertex", usequads=False)
    assert checked(m) == (14, 36, 24)
    assert dict(face_size_histogram(m)) == {3: 24}


def _counts(mesh: Mesh) -> dict[str, int]:
    a = mesh_arrays(mesh)
    v, e, f = a.counts
    return {"V": v, "E": e, "F": f, "C": len(a.corner_vertex)}


# new (V, E, F) from old V, E, F, C on closed meshes whose vertices have valence >= 3
FORMULAS = {
    "loop": lambda V, E, F, C: (V + E, 2 * E + C, F + C),
    "loop-style": lambda V, E, F, C: (V + E, 2 * E + C, F + C),
    "checker": lambda V, E, F, C: (V + 2 * C, E + 4 * C, F + 2 * C),
    "simplest": lambda V, E, F, C: (E, C, F + V),
    "vertex-cut": lambda V, E, F, C: (C, E + C, F + V),
    "pentagon": lambda V, E, F, C: (V + C + F, 2 * C + E, C),
    "pentagon-preserve": lambda V, E, F, C: (V + E + C, 3 * C, F + C),
    "honeycomb": lambda V, E, F, C: (C, C + E, F + V),
    "doo-sabin": lambda V, E, F, C: (C, 2 * C, F + E + V),
    "corner-cut": lambda V, E, F, C: (C, 2 * C, F + E + V),
    "modified-corner-cut": lambda V, E, F, C: (C, 2 * C, F + E + V),
    "root4": lambda V, E, F, C: (V + C, 2 * C, F + E),
    "catmull-clark": lambda V, E, F, C: (V + E + F, 2 * E + C, C),
    "linear-vertex": lambda V, E, F, C: (V + E + F, 2 * E + C, C),
    "star": lambda V, E, F, C: (V + F + C, E + 4 * C, 3 * C),
    "sqrt3": lambda V, E, F, C: (V + F, 3 * E, 2 * E),
    "fractal": lambda V, E, F, C: (V + E + F, 3 * C, 2 * C),
    "stellate": lambda V, E, F, C: (V + F, C, E),
    "double-stellate": lambda V, E, F, C: (V + F + C, 3 * C, E + C),
    "dual": lambda V, E, F, C: (F, E, V),
    "dual-12.6.4": lambda V, E, F, C: (2 * C, 3 * C, F + E + V),
    "doo-sabin-bc-new": lambda V, E, F, C: (V + 2 * C, 3 * C + E, F + C),
    "dome": lambda V, E, F, C: (V + 3 * E + 28 * C, 4 * E + 56 * C, F + 28 * C),
}


def topmod_mesh(name: str) -> Mesh:
    """The built-in shape with the counts and genus of TopMod's sample ``name``.obj."""
    return load_shape(name)


TEST_MESHES = {
    "tetrahedron": lambda: topmod_mesh("tetrahedron"),
    "octahedron": lambda: topmod_mesh("octahedron"),
    "dodecahedron": lambda: topmod_mesh("dodecahedron"),
    "icosahedron": lambda: topmod_mesh("icosahedron"),
    "torus": lambda: torus(8, 6),
    "genus3": lambda: topmod_mesh("genus3hexa1"),
}


@pytest.mark.parametrize("name", sorted(TEST_MESHES))
@pytest.mark.parametrize("scheme", sorted(FORMULAS))
def test_counts_follow_the_rule_and_genus_is_kept(scheme, name):
    m = TEST_MESHES[name]()
    before, old_genus = _counts(m), genus(m)
    subdivide(m, scheme)
    assert checked(m) == FORMULAS[scheme](**before)
    assert genus(m) == old_genus


GENUS_KEEPING = sorted(set(ALL_SCHEMES) - {"sierpinsky"})


@pytest.mark.parametrize("scheme", GENUS_KEEPING)
def test_genus_three_is_kept_by_every_scheme(scheme):
    m = topmod_mesh("genus3hexa1")
    subdivide(m, scheme)
    checked(m)
    assert genus(m) == 3


@pytest.mark.parametrize("scheme", GENUS_KEEPING)
def test_torus_genus_is_kept(scheme):
    m = torus(6, 4)
    subdivide(m, scheme)
    checked(m)
    assert genus(m) == 1


@pytest.mark.parametrize("scheme", ALL_SCHEMES)  # the delegated ones set them aside too
def test_several_components_and_point_spheres_survive(scheme):
    m = two_cubes()
    m.create_vertex((9.0, 9.0, 9.0))
    subdivide(m, scheme)
    checked(m)
    assert num_components(m) == 3
    a = mesh_arrays(m)
    assert np.isclose(a.positions, [9.0, 9.0, 9.0]).all(axis=1).sum() == 1


@pytest.mark.parametrize("scheme", ALL_SCHEMES)
def test_point_spheres_keep_their_colours(scheme):
    m = two_cubes()
    blue = m.create_vertex((9.0, 9.0, 9.0))
    m.create_vertex((8.0, 8.0, 8.0))  # no colour: must not get one
    m.set_face_color(m.vertex_faces(blue)[0], (0.0, 0.0, 1.0))
    subdivide(m, scheme)
    checked(m)
    spheres = [v for v in m.vertex_ids().tolist() if m.is_point_sphere(v)]
    colours = {tuple(m.position(v).tolist()): m.face_color(m.vertex_faces(v)[0])
               for v in spheres}
    assert colours == {(9.0, 9.0, 9.0): (0.0, 0.0, 1.0), (8.0, 8.0, 8.0): None}


def pyramid(n: int) -> Mesh:
    """An n-sided pyramid: apex of valence n, an n-gon base, n triangles."""
    from livemod.dlfl import from_polygons

    angles = 2 * np.pi * np.arange(n) / n
    base = np.stack([np.cos(angles), np.sin(angles), np.zeros(n)], axis=1)
    positions = np.concatenate([base, [[0.0, 0.0, 1.0]]])
    faces = [list(range(n - 1, -1, -1))] + [[i, (i + 1) % n, n] for i in range(n)]
    return from_polygons(positions, faces)


@pytest.mark.parametrize("n", range(3, 9))
@pytest.mark.parametrize("scheme", ["catmull-clark", "doo-sabin", "loop"])
def test_ngons_and_valence_3_to_8(scheme, n):
    m = pyramid(n)
    before = _counts(m)
    subdivide(m, scheme)
    assert checked(m) == FORMULAS[scheme](**before)
    assert genus(m) == 0
    # symmetric input, symmetric output: the n-fold rotation maps the points onto themselves
    angle = 2 * np.pi / n
    rotation = np.array([[np.cos(angle), -np.sin(angle), 0], [np.sin(angle), np.cos(angle), 0],
                         [0, 0, 1]])
    assert invariant_under(mesh_arrays(m).positions, rotation)


def invariant_under(points: np.ndarray, matrix: np.ndarray) -> bool:
    """Whether ``matrix`` maps the point set onto itself (to 1e-9)."""
    moved = points @ matrix.T
    gaps = np.linalg.norm(moved[:, None, :] - points[None, :, :], axis=2).min(axis=1)
    return bool((gaps < 1e-9).all())


def face_visiting_vertices_twice() -> Mesh:
    """The cube with an edge from a top corner to a bottom corner: 8/13/5, genus 1;
    the merged face visits both end vertices twice."""
    m = cube()
    top = next(f for f in m.face_ids() if np.allclose(
        [m.position(v)[1] for v in m.face_vertices(f)], 1.0))
    bottom = next(f for f in m.face_ids() if np.allclose(
        [m.position(v)[1] for v in m.face_vertices(f)], -1.0))
    m.insert_edge(m.face_corners(top)[0], m.face_corners(bottom)[0])
    assert m.counts() == (8, 13, 5) and genus(m) == 1
    return m


@pytest.mark.parametrize("scheme", OWN_SCHEMES)
def test_faces_visiting_a_vertex_twice(scheme):
    m = face_visiting_vertices_twice()
    before = _counts(m)
    subdivide(m, scheme)
    checked(m)
    assert genus(m) == 1
    if scheme in FORMULAS:
        assert m.counts() == FORMULAS[scheme](**before)


PER_FACE = ["catmull-clark", "loop", "doo-sabin", "linear-vertex", "pentagon", "fractal",
            "star", "checker", "dome", "honeycomb", "vertex-cut", "simplest"]


@pytest.mark.parametrize("scheme", OWN_SCHEMES)
def test_open_grid_gives_a_valid_mesh(scheme):
    m = grid(3, 2)
    subdivide(m, scheme)
    checked(m)


@pytest.mark.parametrize("scheme", PER_FACE)
def test_faces_made_from_a_hole_stay_holes(scheme):
    m = grid(3, 2)
    subdivide(m, scheme)
    assert any(m.is_hole(f) for f in m.face_ids())


def test_doo_sabin_joins_a_valence_two_vertex_by_one_edge():
    m = cube()
    subdivide(m, "subdivide-all-edges")
    assert checked(m) == (20, 24, 6)
    subdivide(m, "doo-sabin")
    assert checked(m) == (48, 84, 38)


def _cube_with_dangling_edge() -> Mesh:
    """The cube plus an edge from a corner of its second face to a new vertex."""
    m = cube()
    v = m.create_vertex((0.5, 0.5, 2.0))
    m.insert_edge(m.face_corners(m.face_ids()[1])[0], m.vertex_corners(v)[0])
    return m


@pytest.mark.parametrize("scheme", ["doo-sabin", "corner-cut"])
def test_doo_sabin_turns_a_valence_one_vertex_quad_into_a_triangle(scheme):
    m = _cube_with_dangling_edge()
    assert checked(m) == (9, 13, 6)
    subdivide(m, scheme)
    # V = C = 26; F = F + E + 8 vertices of valence >= 3; genus 0 gives E
    assert checked(m) == (26, 51, 27)
    # F-faces: 5 quads and the hexagon that walks the dangling edge; edge faces:
    # 12 quads and the dangling edge's triangle; vertex faces: 7 triangles and
    # a quad at the valence-4 end (the valence-1 end gets none)
    assert dict(face_size_histogram(m)) == {3: 1 + 7, 4: 5 + 12 + 1, 6: 1}


def test_doo_sabin_of_a_lone_edge_is_two_two_gons():
    m = Mesh()
    a, b = m.create_vertex((0.0, 0.0, 0.0)), m.create_vertex((1.0, 0.0, 0.0))
    m.insert_edge(m.vertex_corners(a)[0], m.vertex_corners(b)[0])
    subdivide(m, "doo-sabin")
    assert checked(m) == (2, 2, 2)
    assert dict(face_size_histogram(m)) == {2: 2}


@pytest.mark.parametrize("scheme", sorted(set(SCHEMES) - {"sierpinsky"}))
def test_every_scheme_keeps_a_dangling_edge_mesh_valid(scheme):
    m = _cube_with_dangling_edge()
    subdivide(m, scheme)
    checked(m)
    assert genus(m) == 0


def test_path_face_does_not_crash_catmull_clark():
    m = path_face()
    subdivide(m, "catmull-clark")
    checked(m)


# -- selected faces -------------------------------------------------------------

def test_one_face_without_quads_gives_triangles():
    m = cube()
    f = m.face_ids()[0]
    subdivide_faces(m, [f], usequads=False)
    assert checked(m) == (9, 16, 9)
    assert dict(face_size_histogram(m)) == {3: 4, 4: 5}


def test_one_face_with_quads_splits_its_edges():
    m = cube()
    subdivide_faces(m, [m.face_ids()[0]])
    assert checked(m) == (13, 20, 9)
    assert dict(face_size_histogram(m)) == {4: 5, 5: 4}


def test_shared_edge_is_split_once():
    m = cube()
    f0 = m.face_ids()[0]
    e = m.face_edges(f0)[0]
    f1 = next(f for f in m.edge_faces(e) if f != f0)
    subdivide_faces(m, [f0, f1])
    assert checked(m) == (17, 27, 12)


def test_subdivide_faces_refuses_unknown_face_and_keeps_the_mesh():
    m = cube()
    before = snapshot(m)
    with pytest.raises(UnknownIdError, match="face id 999"):
        subdivide_faces(m, [999])
    assert snapshot(m) == before


# -- errors and the budget ----------------------------------------------------

def test_unknown_scheme_lists_the_valid_names():
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="unknown subdivision scheme 'catmul'.*catmull-clark"):
        subdivide(m, "catmul")
    assert snapshot(m) == before


@pytest.mark.parametrize(("scheme", "options", "message", "error"), [
    ("catmull-clark", {"depth": 2}, "no option 'depth'", InvalidArgumentError),
    ("catmull-clark", {"levels": 0}, "levels must be a positive integer", InvalidArgumentError),
    ("catmull-clark", {"levels": 1.5}, "levels must be a positive integer", InvalidArgumentError),
    ("checker", {"thickness": 0.7}, "thickness must be in", InvalidArgumentError),
    ("checker", {"thickness": 0}, "thickness must be in \\(0, 0.5\\]: 0 puts",
     InvalidArgumentError),
    ("dual-checkerboard", {"thickness": 0}, "thickness must be in \\(0, 0.5\\]: 0 puts",
     InvalidArgumentError),
    ("checker", {"thickness": "thin"}, "thickness must be a number", InvalidArgumentError),
    ("corner-cut", {"alpha": 0.1}, "alpha must be in", InvalidArgumentError),
    ("vertex-cut", {"offset": float("nan")}, "offset must be finite", InvalidArgumentError),
    ("root-3", {"scale": 2}, "no option 'scale'", InvalidArgumentError),
    ("dual-loop", {"max_faces": 20}, "would produce", BudgetExceededError),
    ("star", {"offset": True}, "offset must be a number", InvalidArgumentError),
])
def test_bad_options_raise_and_keep_the_mesh(scheme, options, message, error):
    m = cube()
    before = snapshot(m)
    with pytest.raises(error, match=message):
        subdivide(m, scheme, **options)
    assert snapshot(m) == before


def test_face_budget_names_the_count_before_building():
    m = cube()
    before = snapshot(m)
    with pytest.raises(BudgetExceededError, match="would produce 24 faces, more than the budget of 10"):
        subdivide(m, "catmull-clark", max_faces=10)
    assert snapshot(m) == before


def test_session_budget_setting(monkeypatch):
    monkeypatch.setattr(budget, "_session_default", None)
    budget.set_default_face_budget(100)
    m = cube()
    subdivide(m, "catmull-clark")
    subdivide(m, "catmull-clark")
    with pytest.raises(BudgetExceededError, match="would produce 384 faces"):
        subdivide(m, "catmull-clark")
    assert m.counts() == (98, 192, 96)


def test_default_budget_is_twenty_million(monkeypatch):
    monkeypatch.delenv(budget.ENVIRONMENT_VARIABLE, raising=False)
    assert budget.face_budget() == budget.DEFAULT_FACE_BUDGET == 20_000_000


def test_fresh_ids_after_remeshing():
    m = cube()
    old = set(m.face_ids().tolist())
    subdivide(m, "catmull-clark")
    assert not old & set(m.face_ids().tolist())


def test_catmull_clark_levels_equal_repeated_steps():
    once = cube()
    subdivide(once, "catmull-clark", levels=3)
    repeated = cube()
    for _ in range(3):
        subdivide(repeated, "catmull-clark")
    assert checked(once) == checked(repeated) == (386, 768, 384)
    assert np.array_equal(mesh_arrays(once).positions, mesh_arrays(repeated).positions)


def test_catmull_clark_levels_budget_counts_the_last_level():
    m = cube()
    with pytest.raises(BudgetExceededError, match="would produce 1,536 faces"):
        subdivide(m, "catmull-clark", levels=4, max_faces=1000)


def _layout_meshes() -> list[Mesh]:
    mixed = torus(7, 5)
    subdivide(mixed, "triangulate")
    subdivide(mixed, "pentagon")
    return [cube(), mixed, grid(3, 2), face_visiting_vertices_twice(), pyramid(70),
            topmod_mesh("genus3hexa1")]


@pytest.mark.parametrize("index", range(6))
def test_vertex_rings_walk_equals_pointer_doubling(index):
    from livemod.dlfl._graph import cycle_layout, walk_rings
    from livemod.dlfl.subdivision._layout import read_topology

    t = read_topology(_layout_meshes()[index])
    expected = cycle_layout(t.vprev)
    walked = walk_rings(t.vprev, t.cv, t.valence)
    if int(t.valence.max()) > 64:  # the 70-gon's apex: pointer doubling instead
        assert walked is None
    else:
        assert walked is not None
        assert all(np.array_equal(a, b) for a, b in zip(walked, expected, strict=True))
    assert all(np.array_equal(a, b) for a, b in zip(t.vertex_rings(), expected, strict=True))


def test_walk_refuses_a_vertex_with_two_fans():
    from livemod.dlfl._graph import walk_rings

    # corners 0..3 at one vertex, in two cycles (0 1) and (2 3)
    perm = np.array([1, 0, 3, 2])
    assert walk_rings(perm, np.zeros(4, dtype=np.int64), np.array([4])) is None


@pytest.mark.parametrize("index", range(6))
def test_ring_sums_equal_bincount_sums(index):
    from livemod.dlfl.subdivision._layout import group_sum, read_topology, ring_sums

    t = read_topology(_layout_meshes()[index])
    assert np.array_equal(ring_sums(t.offsets, t.pos, t.cv),
                          group_sum(t.face, t.pos[t.cv], t.nf))


def test_ring_sums_of_many_runs_of_sizes():
    from livemod.dlfl.subdivision._layout import group_sum, ring_sums

    rng = np.random.default_rng(3)
    sizes = np.concatenate([rng.integers(1, 6, size=200), np.full(50, 4)])
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    values = rng.normal(size=(40, 3))
    index = rng.integers(0, 40, size=int(offsets[-1]))
    ring = np.repeat(np.arange(len(sizes)), sizes)
    expected = group_sum(ring, values[index], len(sizes))
    assert np.array_equal(ring_sums(offsets, values, index), expected)
    few = slice(200, 251)  # one run: the column-wise path
    assert np.array_equal(ring_sums(offsets[few] - offsets[200], values,
                                    index[offsets[200]:]), expected[200:])


def _faces_of(mesh: Mesh, points: list[int]) -> list[tuple[int, ...]]:
    """Each face as its cycle of ``points`` (one per vertex) from the least, sorted."""
    a = mesh_arrays(mesh)
    faces = []
    for start, stop in zip(a.face_offsets[:-1].tolist(), a.face_offsets[1:].tolist(), strict=True):
        ring = [points[v] for v in a.corner_vertex[start:stop].tolist()]
        k = min(range(len(ring)), key=lambda i: ring[i:] + ring[:i])
        faces.append(tuple(ring[k:] + ring[:k]))
    return sorted(faces)


def assert_same_mesh(mesh: Mesh, other: Mesh, tolerance: float = 1e-9) -> None:
    """``mesh`` is ``other`` up to the order of its elements: each vertex lies within
    ``tolerance`` of one of ``other``'s, the same points and the same oriented
    faces (as cycles of points; points within ``tolerance`` count as one)."""
    p, q = mesh_arrays(mesh).positions, mesh_arrays(other).positions
    assert p.shape == q.shape and mesh.counts() == other.counts()
    close = np.linalg.norm(q[:, None, :] - q[None, :, :], axis=2) <= tolerance
    label = close.argmax(axis=1)  # the first of other's points close to each
    distance = np.linalg.norm(p[:, None, :] - q[None, :, :], axis=2)
    nearest = distance.argmin(axis=1)
    assert distance[np.arange(len(p)), nearest].max(initial=0.0) <= tolerance
    mine, theirs = label[nearest].tolist(), label.tolist()
    assert sorted(mine) == sorted(theirs)
    assert _faces_of(mesh, mine) == _faces_of(other, theirs)


# composites computed in one step -> (middle scheme, its options)
ONE_STEP = [
    ("12.6.4", "dual-12.6.4", {}), ("12.6.4", "dual-12.6.4", {"scale": 1.0}),
    ("12.6.4", "dual-12.6.4", {"scale": -0.4}),
    ("dual-pentagon-preserving", "pentagon-preserve", {"scale": 0.3}),
    ("dual-pentagon-preserving", "pentagon-preserve", {}),
    ("dual-loop", "loop", {}), ("root3", "honeycomb", {}), ("root-3", "honeycomb", {}),
    ("six-preserving-loop-style", "root4", {}),
    ("six-preserving-loop-style", "root4", {"weight": 0.4, "twist": 0.2}),
    ("dual-pentagonalization", "pentagon", {}),
    ("dual-pentagonalization", "pentagon", {"offset": 0.3}),
]


@pytest.mark.parametrize(("composite", "middle", "options"), ONE_STEP)
@pytest.mark.parametrize("index", range(6))
def test_one_step_composite_equals_its_three_steps(composite, middle, options, index):
    direct, steps = _layout_meshes()[index], _layout_meshes()[index]
    subdivide(direct, composite, **options)
    for scheme, kwargs in (("dual", {}), (middle, options), ("dual", {})):
        subdivide(steps, scheme, **kwargs)
    validate(direct)
    assert_same_mesh(direct, steps)


@pytest.mark.parametrize("index", range(6))
def test_doo_sabin_bc_equals_its_two_steps(index):
    direct, steps = _layout_meshes()[index], _layout_meshes()[index]
    subdivide(direct, "doo-sabin-bc")
    subdivide(steps, "subdivide-all-edges")
    subdivide(steps, "doo-sabin")
    a, b = mesh_arrays(direct), mesh_arrays(steps)
    for field in ("positions", "face_offsets", "face_hole", "corner_vertex", "corner_mate",
                  "edge_corners"):
        assert np.array_equal(getattr(a, field), getattr(b, field)), field


# (a corner cut of 1e160 and a fractal of a 1e300 torus were here: both were
# refused through t * t and L * L overflowing, and both are fine meshes; the
# corner cut's own overflow is in test_wireframe)
@pytest.mark.parametrize(("scheme", "options", "size"), [
    ("root4", {"weight": 1e308}, 1.0), ("loop-style", {"length": 1e308}, 1.0),
    ("fractal", {"offset": 1e308}, 1.0),
])
def test_options_that_overflow_are_refused_before_the_mesh_changes(scheme, options, size):
    m = small_torus()
    m.set_positions(m.vertex_ids(), m.positions_view() * size)
    before = snapshot(m)
    # the corner cut names its own overflow; the others are caught as the mesh is built
    with pytest.raises(GeometryError, match="not finite: the arguments are too large|numbers overflow"):
        subdivide(m, scheme, **options)
    assert snapshot(m) == before


_OVERFLOWING_OPTIONS = [
    ("root4", {"weight": 1e308}), ("root4", {"twist": 1e308}), ("loop-style", {"length": 1e308}),
    ("fractal", {"offset": 1e308}), ("pentagon", {"offset": 1e308}),
    ("pentagon-preserve", {"scale": 1.7e308}), ("dual-12.6.4", {"scale": 1e308}),
    ("dual-pentagon", {"scale": 1.7e308}), ("dual-pentagonalization", {"offset": 1e308}),
    ("six-preserving-loop-style", {"twist": 1e308}), ("dome", {"length": 1e308}),
    ("dome", {"scale": 1e308}), ("doo-sabin-bc-new", {"scale": 1e308}),
    ("doo-sabin-bc-new", {"length": 1e308}),
]


@pytest.mark.parametrize(("scheme", "options"), _OVERFLOWING_OPTIONS)
def test_options_that_overflow_are_refused_quietly(scheme, options):
    # each printed numpy's overflow / invalid-value warnings before the refusal
    assert_refused_quietly(small_torus(), lambda m: subdivide(m, scheme, **options),
                           "not finite: the arguments are too large")


# the others (corner-cut, doo-sabin, checker, sierpinsky, vertex-cut) were quiet already
@pytest.mark.parametrize("scheme", sorted(set(SCHEMES) - {
    "corner-cut", "doo-sabin", "checker", "sierpinsky", "vertex-cut"}))
def test_a_mesh_near_the_float_maximum_is_refused_quietly(scheme):
    # coordinates of 1.2e308: sums of a few of them overflow in every scheme
    # (left refused: their means would fit, but every scheme sums raw points)
    m = small_torus()
    m.set_positions(m.vertex_ids(), m.positions_view() * (1.2e308 / np.abs(
        m.positions_view()).max()))
    before = snapshot(m)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            subdivide(m, scheme)
        except DLFLError:
            assert snapshot(m) == before
    assert np.isfinite(m.positions_view()).all()


@pytest.mark.parametrize("scale", [1e160, 1e300])
def test_a_huge_mesh_fractalizes_like_the_scaled_unit_one(scale):
    # L2^2 - L1^2 overflowed to inf - inf past ~1e154: NaN centres, refused
    assert_scales(small_torus, lambda m, s: subdivide(m, "fractal"), scale)


@pytest.mark.parametrize("faces", [[0, None], [0.0], "01"])
def test_subdivide_faces_refuses_entries_that_are_not_ids(faces):
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match="face_ids must"):
        subdivide_faces(m, faces)
    assert snapshot(m) == before


# -- face colours ----------------------------------------------------------------

RED, BLUE = (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)


def _bottom_red_top_blue() -> Mesh:
    """The unit cube of tests.meshes with face 0 (z = 0) red and face 1 (z = 1) blue."""
    m = unit_cube()
    m.set_face_color(0, RED)
    m.set_face_color(1, BLUE)
    return m


@pytest.mark.parametrize("scheme", ALL_SCHEMES)
def test_faces_made_inside_a_coloured_face_take_its_colour(scheme):
    m = _bottom_red_top_blue()
    subdivide(m, scheme)
    validate(m)
    a = mesh_arrays(m)
    colors = a.face_colors
    if colors is None:  # a scheme whose faces all lie around old vertices or edges
        assert scheme in NO_FACE_ORIGINS
        return
    assert scheme not in NO_FACE_ORIGINS
    centres = np.array([face_centroid(m, f) for f in a.face_ids.tolist()])
    red = (colors == np.float32(RED)).all(axis=1)
    blue = (colors == np.float32(BLUE)).all(axis=1)
    assert (red | blue | np.isnan(colors[:, 0])).all()
    # children stay near their parent: the red ones low, the blue ones high
    assert red.any() and blue.any()
    assert (centres[red, 2] < 0.5).all() and (centres[blue, 2] > 0.5).all()


# no face of these has a single source face, as no face of them can be a hole: TopMod's
# composites through a dual, faces around old vertices or across old edges (stellate,
# sqrt3)
NO_FACE_ORIGINS = {"dual", "12.6.4", "cubic-pentagonalization", "dual-checkerboard", "dual-loop",
                   "dual-pentagon-preserving", "dual-pentagonalization", "root-3", "root3",
                   "sqrt3", "six-preserving-loop-style", "stellate"}


@pytest.mark.parametrize(("scheme", "options", "red"), [
    ("catmull-clark", {}, 4), ("catmull-clark", {"levels": 2}, 16), ("doo-sabin", {}, 1),
    ("loop", {}, 5), ("triangulate", {}, 4), ("checker", {}, 5)])
def test_a_scheme_colours_exactly_the_children_of_a_face(scheme, options, red):
    m = _bottom_red_top_blue()
    subdivide(m, scheme, **options)
    colors = mesh_arrays(m).face_colors
    assert colors is not None
    assert int((colors == np.float32(RED)).all(axis=1).sum()) == red
    assert int((colors == np.float32(BLUE)).all(axis=1).sum()) == red


def test_a_coloured_hole_keeps_both_its_flag_and_its_colour():
    m = unit_cube()
    m.set_hole(0)
    m.set_face_color(0, RED)
    subdivide(m, "catmull-clark")
    holes = [f for f in m.face_ids().tolist() if m.is_hole(f)]
    assert len(holes) == 4 and all(m.face_color(f) == RED for f in holes)
