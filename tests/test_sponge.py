"""Menger sponge remeshing: TopMod's cube counts, the clean surface, geometry, bad input."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from livemod.dlfl import (
    face_size_histogram,
    from_polygons,
    genus,
    num_components,
    validate,
)
from livemod.dlfl.analysis import face_centroids, face_normals
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.errors import GeometryError, InvalidArgumentError
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.shapes import cube, grid, icosahedron, octahedron, tetrahedron, torus
from livemod.dlfl.sponge import TOPMOD_THICKNESS, shell_limit, sponge
from tests.meshes import (
    assert_refused,
    assert_refused_quietly,
    colour_counts,
    point_sphere,
    rainbow_cube,
    scaled_cube,
    snapshot,
    split_edge_cube,
)


def test_cube_matches_topmod():
    m = cube()
    assert sponge(m) == TOPMOD_THICKNESS  # the edge-2 cube's limit is 1: 0.67 as given
    validate(m)
    assert m.counts() == (64, 156, 84)
    assert face_size_histogram(m) == {2: 12, 4: 72}
    assert genus(m) == 5 and num_components(m) == 1
    # TopMod's 0.67 puts the inner shell's 8 corners at +-(1 - 0.67)
    inner = m.positions_view()[(np.abs(m.positions_view()) < 0.5).all(axis=1)]
    np.testing.assert_allclose(np.abs(inner), 0.33, atol=1e-12)
    assert len(inner) == 8


def sponge_counts(v: int, e: int) -> tuple[int, int, int]:
    """The sponge's counts on a closed mesh of ``v`` vertices and ``e`` edges
    (``c = 2e`` corners), from the construction in :mod:`livemod.dlfl.sponge`:
    vertices: the originals, one trisection and one inset point per corner and
    the inner shell's copy of each vertex, ``2v + 2c``; faces: three quads per
    corner (corner, side, tunnel) and one 2-gon per edge, ``3c + e``; edges: half
    the face sides, ``(4 * 3c + 2e) / 2 = 6c + e``. The cube's 8/12 give 64/156/84."""
    c = 2 * e
    return 2 * v + 2 * c, 6 * c + e, 3 * c + e


def open_sponge_counts(v: int, e: int) -> tuple[int, int, int]:
    """The counts when no joining edge collapses: every corner keeps its own
    disc corner, ``v + 3c`` vertices; faces: the ``3c`` quads, a joining quad per
    edge and a vertex face per vertex, ``3c + e + v``; edges: ``(12c + 4e + c) / 2``."""
    c = 2 * e
    return v + 3 * c, (12 * c + 4 * e + c) // 2, 3 * c + e + v


def test_sponge_counts_give_topmods_on_the_cube():
    assert sponge_counts(8, 12) == (64, 156, 84)


@pytest.mark.parametrize(("shape", "merged"), [(tetrahedron, True), (torus, False)])
def test_default_works_on_meshes_thinner_than_topmods_cube(shape, merged):
    # 0.67 turns their inner shells inside out (the unit tetrahedron's collapses at
    # its inradius 1/3, the torus's tube at about 0.41): the default takes 0.67 of
    # the limit instead, the cube's proportion. TopMod's edge collapse merges the
    # tetrahedron's inner shell and none of the torus's (see the tests below)
    m = shape()
    v, e, f = m.counts()
    g, limit = genus(m), shell_limit(mesh_arrays(m))
    assert limit < TOPMOD_THICKNESS
    assert sponge(m) == pytest.approx(TOPMOD_THICKNESS * limit)
    validate(m)
    assert m.counts() == (sponge_counts(v, e) if merged else open_sponge_counts(v, e))
    assert genus(m) == 2 * g + f - 1 and num_components(m) == 1


def test_default_inner_shell_of_the_tetrahedron_is_it_shrunk_like_the_cubes():
    # a uniform offset t of a regular tetrahedron scales it by 1 - t / r about its
    # centre (r = 1/3 for the unit one); 0.67 r leaves 0.33, as on the cube
    m = tetrahedron()
    corners = m.positions_view().copy()
    sponge(m)
    pos = m.positions_view()
    gaps = np.linalg.norm(pos[None] - 0.33 * corners[:, None], axis=-1).min(axis=1)
    np.testing.assert_allclose(gaps, 0, atol=1e-12)


def test_shell_limits_of_the_regular_solids_are_their_inradii():
    assert shell_limit(mesh_arrays(cube())) == pytest.approx(1.0)
    assert shell_limit(mesh_arrays(tetrahedron())) == pytest.approx(1 / 3)
    # the inradius of the icosahedron of circumradius 1
    assert shell_limit(mesh_arrays(icosahedron())) == pytest.approx(
        np.sqrt((5 + 2 * np.sqrt(5)) / 15))


@pytest.mark.parametrize("scale", [1e-200, 1e200])
def test_shell_limit_scales_with_the_mesh(scale):
    m = torus()
    m.set_positions(m.vertex_ids(), m.positions_view() * scale)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert shell_limit(mesh_arrays(m)) == pytest.approx(shell_limit(mesh_arrays(torus())) * scale)


def test_a_flat_open_sheet_has_no_limit():
    assert shell_limit(mesh_arrays(grid(2, 2))) == np.inf


@pytest.mark.parametrize("shape", [tetrahedron, torus])
def test_a_thickness_just_below_the_limit_works_and_the_limit_is_refused(shape):
    limit = shell_limit(mesh_arrays(shape()))
    m = shape()
    sponge(m, 0.99 * limit)
    validate(m)
    assert_refused(shape(), lambda m: sponge(m, limit), "too large for this mesh",
                   error=GeometryError)


def test_topmods_thickness_on_the_tetrahedron_is_refused_naming_the_limit():
    assert_refused(tetrahedron(), lambda m: sponge(m, 0.67),
                   r"thickness 0\.67 is too large for this mesh: its inner shell collapses "
                   r"or turns over from thickness 0\.333333 on; .* default here is 0\.223333",
                   error=GeometryError)


def test_clean_surface_is_the_level_one_menger_sponge():
    m = cube()
    sponge(m, 2 / 3, keep_2gons=False)
    validate(m)
    assert m.counts() == (64, 144, 72) and genus(m) == 5
    # every vertex is a point of the 4 x 4 x 4 lattice at -1, -1/3, 1/3, 1
    lattice = np.array([-1, -1 / 3, 1 / 3, 1])
    pos = m.positions_view()
    assert np.abs(pos[..., None] - lattice).min(axis=-1).max() < 1e-12
    # the 8 lattice points inside the cube are the inner shell
    assert (np.abs(pos) < 0.5).all(axis=1).sum() == 8


@pytest.mark.parametrize("shape", [tetrahedron, icosahedron, torus])
def test_genus_counts_one_tunnel_per_face(shape):
    m = shape()
    g, f = genus(m), m.counts()[2]
    sponge(m, 0.05)
    validate(m)
    assert genus(m) == 2 * g + f - 1


@pytest.mark.parametrize(("t", "error"), [
    (0.0, InvalidArgumentError), (-0.5, InvalidArgumentError),
    (1.0, GeometryError), (3.0, GeometryError),  # the inner shell turns over
])
def test_bad_thickness_leaves_the_mesh_unchanged(t, error):
    m = cube()
    before = snapshot(m)
    with pytest.raises(error):
        sponge(m, t)
    assert snapshot(m) == before


def two_gons():
    """Two 2-gons glued into a sphere (2/2/2)."""
    return from_polygons([[0, 0, 0], [1, 0, 0]], [[0, 1], [1, 0]])


@pytest.mark.parametrize("make", [two_gons, point_sphere])
def test_bad_meshes_are_refused(make):
    with pytest.raises(InvalidArgumentError):
        sponge(make(), 0.1)


@pytest.mark.parametrize(("thickness", "message", "error"), [
    ("0.5", "thickness must be a number", InvalidArgumentError),
    (1 + 1j, "thickness must be a number", InvalidArgumentError),
    (1.7976931348623157e308, "its numbers overflow", GeometryError),
])
def test_thickness_of_the_wrong_kind_or_size_is_refused(thickness, message, error):
    assert_refused(cube(), lambda m: sponge(m, thickness), message, error=error)


@pytest.mark.parametrize(("thickness", "message"), [
    (1e308, r"thickness 1e\+308 would move vertex 0 to \[-?inf.*overflow"),
    # pushed 1e300 inward, the copy is inside out
    (1e300, r"thickness 1e\+300 is too large .* from thickness 1 on"),
])
def test_a_thickness_that_overflows_prints_no_numpy_warning(thickness, message):
    assert_refused_quietly(cube(), lambda m: sponge(m, thickness), message)


def test_a_corners_faces_take_its_face_colour_and_the_2gons_none():
    m = rainbow_cube()
    sponge(m)
    validate(m)
    # three quads per corner (4 corners a face); one 2-gon per edge
    assert colour_counts(m) == {**{f: 12 for f in range(6)}, None: 12}


# -- straight vertices and tiny meshes


def test_the_sponge_of_a_cube_with_a_split_edge_takes_the_default_thickness():
    m = split_edge_cube()
    assert sponge(m) == 0.67
    validate(m)
    p = m.positions_view()
    # the split vertex's inner copy is on the inner shell's edge, not the outer one
    assert any(np.allclose(q, [0.33, 0.33, 0], atol=1e-12) for q in p)
    assert not any(np.allclose(q, [1, 1, 0], atol=1e-12) for q in p[9:])


@pytest.mark.parametrize("scale", [1e-13, 1e-150])
def test_a_sponge_too_thick_for_a_tiny_mesh_is_refused(scale):
    m = scaled_cube(scale)
    assert_refused(m, lambda m: sponge(m, 1.5 * scale), "too large for this mesh",
                   error=GeometryError)


# -- TopMod's edge collapse ("Edge Collapse Threshold Factor")

FACTORS = [0, 0.0005, 0.3, 1, 2.5, 1e6]


def rotated_box() -> Mesh:
    """A 2 x 5 x 1.4 box, turned and moved off the origin: right angles only."""
    m = cube()
    turn = np.array([[0.36, 0.48, -0.8], [-0.8, 0.6, 0], [0.48, 0.64, 0.6]])
    m.set_positions(m.vertex_ids(), m.positions_view() * [1, 2.5, 0.7] @ turn.T + [3, -1, 2])
    return m


@pytest.mark.parametrize("keep", [True, False])
@pytest.mark.parametrize("make", [cube, rotated_box, split_edge_cube])
def test_at_right_angles_every_factor_gives_the_merged_shell(make, keep):
    # the discs of two faces meeting at a right angle share their corners on
    # the common edge (each is t in from the edge and t below its face): every
    # joining edge has no length and collapses whatever the factor
    results = set()
    for factor in FACTORS:
        m = make()
        sponge(m, 0.3, collapse=factor, keep_2gons=keep)
        validate(m)
        results.add(snapshot(m))
    assert len(results) == 1
    v, e, _ = make().counts()
    expected = sponge_counts(v, e)
    assert m.counts() == (expected if keep else (expected[0], expected[1] - e, expected[2] - e))


def test_the_boxs_inner_shell_is_its_planes_moved_in_by_the_thickness():
    m = rotated_box()
    a = mesh_arrays(m)
    centres, normals = face_centroids(a), face_normals(a)
    sponge(m, 0.3, collapse=0.5)
    inner = m.positions_view()[-8:]
    # each inner vertex lies 0.3 inside three of the six face planes
    depth = np.einsum("fk,ifk->if", normals, centres[None] - inner[:, None]).round(9)
    assert np.array_equal(np.sort(depth, axis=1)[:, :3], np.full((8, 3), 0.3))


def disc_corner(points: np.ndarray, t: float) -> np.ndarray:
    """The disc corner of a convex face's first corner (``points`` ``(k, 3)`` in
    ring order): TopMod's planar offset ``t (pvec + nvec)`` with unit edge
    vectors, then ``t`` against the face normal."""
    p, nxt, prv = points[0], points[1], points[-1]
    pvec, nvec = (prv - p) / np.linalg.norm(prv - p), (nxt - p) / np.linalg.norm(nxt - p)
    normal = np.cross(nxt - p, prv - p)
    return p + t * (pvec + nvec) - t * normal / np.linalg.norm(normal)


def test_the_octahedrons_joining_edges_collapse_above_their_length():
    # at a vertex of the octahedron (unit axes) the two discs across an edge have
    # corners t (e_a + e_b) - t n_a and t (e_a + e_c) - t n_b from it: with the
    # edge directions 1/sqrt(2) and the normals 1/sqrt(3) along the axes, they
    # are t (sqrt(2) - 2 / sqrt(3)) = 0.2595 t apart, nothing crosses, so a
    # factor above 0.2595 collapses all of them and one below none
    t = 0.3
    # faces (0, 2, 4) and (2, 0, 5) of shapes.octahedron, from vertex 0 (1, 0, 0)
    top = np.array([[1.0, 0, 0], [0, 1, 0], [0, 0, 1]])
    below = np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]])
    apart = np.linalg.norm(disc_corner(top, t) - disc_corner(below, t))
    assert apart == pytest.approx(t * (np.sqrt(2) - 2 / np.sqrt(3)))
    m = octahedron()
    sponge(m, t, collapse=0.25)
    validate(m)
    # nothing collapses: 6 + 3 * 24 vertices; 3 * 24 quads, 12 joining quads and
    # 6 vertex quads; (12 * 24 + 4 * 12 + 24) / 2 edges
    assert m.counts() == (78, 180, 90) == open_sponge_counts(6, 12)
    assert face_size_histogram(m) == {4: 90}
    assert genus(m) == 7
    # the disc corners are where TopMod put them
    gaps = np.linalg.norm(m.positions_view() - disc_corner(top, t), axis=1)
    assert gaps.min() < 1e-12
    for factor in (0.27, 1, 3):
        m = octahedron()
        sponge(m, t, collapse=factor)
        validate(m)
        assert m.counts() == (60, 156, 84) == sponge_counts(6, 12)
        assert face_size_histogram(m) == {2: 12, 4: 72}


def test_the_default_factor_is_an_absolute_001():
    # 0 (and anything up to 0.001) means TopMod's 0.01: the octahedron's joining
    # edges at t = 0.03 are 0.0078 long and collapse, at t = 0.04 0.0104 and stay
    for factor in (0, 0.001):
        small, large = octahedron(), octahedron()
        sponge(small, 0.03, collapse=factor)
        sponge(large, 0.04, collapse=factor)
        assert small.counts() == sponge_counts(6, 12)
        assert large.counts() == open_sponge_counts(6, 12)
    m = octahedron()
    sponge(m, 0.04, collapse=0.0011)  # a factor: 0.04 * 0.0011, nothing collapses
    assert m.counts() == open_sponge_counts(6, 12)


def test_the_tetrahedrons_joining_edges_are_crossed_and_all_collapse():
    # each joining edge is sqrt(8/3) - 1 = 0.633 times the thickness long, but
    # crossed: at a vertex, disc A's side along A's other edge and disc B's side
    # along B's are mirror images in the plane through their common edge and the
    # centre, and at the tetrahedron's 70.5 degree edges disc A's corner lies on
    # B's side of that plane, so the two sides cross in it. TopMod collapses every
    # joining edge whatever the factor: the merged shell, 0.33 of the tetrahedron
    t = TOPMOD_THICKNESS / 3
    corners = tetrahedron().positions_view()
    # faces (0, 1, 2) and (0, 3, 1) share the edge 0-1; their discs' corners at 0
    apart = np.linalg.norm(disc_corner(corners[[0, 1, 2]], t) - disc_corner(corners[[0, 3, 1]], t))
    assert apart == pytest.approx(t * (np.sqrt(8 / 3) - 1))
    for factor in FACTORS:
        m = tetrahedron()
        sponge(m, collapse=factor)
        validate(m)
        assert m.counts() == sponge_counts(4, 6) and genus(m) == 3
        gaps = np.linalg.norm(m.positions_view()[-4:] - 0.33 * corners, axis=1)
        np.testing.assert_allclose(gaps, 0, atol=1e-12)


def torus_joining_lengths(t: float) -> dict[float, int]:
    """The joining edges of ``torus()`` (8 x 6) at thickness ``t``, from TopMod's
    formula, counted by length over ``t``: both discs' corners at every vertex
    across each edge."""
    m = torus()
    a = mesh_arrays(m)
    found: dict[float, int] = {}
    for c in range(len(a.corner_vertex)):
        across = a.corner_vnext[c]
        ends = [_disc_of(a, c, t), _disc_of(a, int(across), t)]
        key = round(float(np.linalg.norm(ends[1] - ends[0])) / t, 4)
        found[key] = found.get(key, 0) + 1
    return found


def _disc_of(a, corner: int, t: float) -> np.ndarray:
    face = a.corner_face[corner]
    ring = np.arange(a.face_offsets[face], a.face_offsets[face + 1])
    ring = np.roll(ring, -int(np.flatnonzero(ring == corner)[0]))
    return disc_corner(a.positions[a.corner_vertex[ring]], t)


@pytest.mark.parametrize(("factor", "counts", "sizes"), [
    # none collapses: 48 + 3 * 192 vertices, 576 + 96 + 48 faces
    (0.5, (624, 1440, 720), {4: 720}),
    # the 32 across the ring edges at the equators (0.791): at those 16 vertices
    # two runs of two corners each (-32 vertices, -32 edges); the 16 ring edges'
    # quads and the 16 vertex faces become 2-gons
    (0.8, (592, 1408, 720), {2: 32, 4: 688}),
    # all 96 across ring edges (0.791, 0.834): two runs at every vertex; 48 ring
    # edge quads and 48 vertex faces become 2-gons
    (1.0, (528, 1344, 720), {2: 96, 4: 624}),
    # and the 32 across the tube edges by the outer equator (1.172): vertices at
    # tube rows 0, 1, 5 keep at most one joining edge, so merge whole (a lone one
    # goes too): 24 + 2 * 24 inner vertices; 2-gons: 48 ring quads, 16 tube quads
    # by the equator, 24 vertex faces; triangles: the 16 tube quads with one lone end
    (1.5, (504, 1296, 696), {2: 88, 3: 16, 4: 592}),
    # all: the merged shell
    (3.0, (480, 1248, 672), {2: 96, 4: 576}),
])
def test_the_torus_collapses_its_joining_edges_by_length(factor, counts, sizes):
    t = TOPMOD_THICKNESS * shell_limit(mesh_arrays(torus()))
    # by symmetry five lengths (over t): across the ring edges at the two
    # equators, across the other ring edges, across the tube edges next to the
    # outer equator, the middle ones and those next to the inner one
    assert torus_joining_lengths(t) == {0.7908: 32, 0.8345: 64, 1.1725: 32, 1.8478: 32,
                                        2.5231: 32}
    m = torus()
    sponge(m, collapse=factor)
    validate(m)
    assert m.counts() == counts and face_size_histogram(m) == sizes
    assert genus(m) == 2 * 1 + 48 - 1


def test_two_merged_disc_corners_meet_at_their_midpoint():
    t = TOPMOD_THICKNESS * shell_limit(mesh_arrays(torus()))
    a = mesh_arrays(torus())
    # a corner at vertex 0 (on the outer equator) whose edge runs along the
    # equator: the joining edge across it (0.791 t) collapses at factor 0.8
    cv = a.corner_vertex
    c = next(c for c in range(len(cv)) if cv[c] == 0 and cv[a.corner_next[c]] % 6 == 0)
    across = int(a.corner_vnext[c])
    middle = (_disc_of(a, c, t) + _disc_of(a, across, t)) / 2
    m = torus()
    sponge(m, collapse=0.8)
    assert np.linalg.norm(m.positions_view() - middle, axis=1).min() < 1e-12


@pytest.mark.parametrize("make", [octahedron, torus, tetrahedron])
def test_dropping_the_2gons_keeps_the_rest(make):
    for factor in (0, 1.0, 1.5):
        kept, dropped = make(), make()
        sponge(kept, collapse=factor)
        sponge(dropped, collapse=factor, keep_2gons=False)
        validate(dropped)
        twos = face_size_histogram(kept).get(2, 0)
        v, e, f = kept.counts()
        assert dropped.counts() == (v, e - twos, f - twos)
        assert 2 not in face_size_histogram(dropped) and genus(dropped) == genus(kept)


@pytest.mark.parametrize(("collapse", "message", "error"), [
    (-0.5, "collapse must be a number >= 0, got -0.5", InvalidArgumentError),
    ("1", "collapse must be a number", InvalidArgumentError),
    (float("nan"), "collapse must be finite, got nan", InvalidArgumentError),
])
def test_a_bad_factor_is_refused(collapse, message, error):
    assert_refused(octahedron(), lambda m: sponge(m, 0.1, collapse=collapse), message, error=error)


def test_the_joining_faces_have_no_colour():
    m = rainbow_cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * [1, 1, 1.5])
    sponge(m, 0.3, collapse=0)
    validate(m)
    assert colour_counts(m)[None] == 12


@pytest.mark.parametrize("scale", [1e-150, 1.0, 1e150])
def test_the_crossing_test_reads_the_same_at_any_scale(scale):
    # the tetrahedron's joining edges (0.633 t) outlast the factor 0.5, so only
    # TopMod's crossing test collapses them: at every scale it finds them crossed
    m = scaled_tetrahedron(scale)
    sponge(m, collapse=0.5)
    validate(m)
    assert m.counts() == sponge_counts(4, 6)


def scaled_tetrahedron(scale: float) -> Mesh:
    m = tetrahedron()
    m.set_positions(m.vertex_ids(), m.positions_view() * scale)
    return m


def test_an_open_sheet_gets_its_joining_faces_too():
    # a 3 x 3 grid (16 vertices, 24 edges, 9 quads and its boundary hole): at 0.05
    # the joining edges inside are 0.1 long (two insets side by side), those at
    # the border longer (the hole's disc lies t on the other side of the sheet),
    # and none crosses another: all stay, 16 + 3 * 48 vertices, 144 + 24 + 16 faces
    m = grid(3, 3)
    sponge(m, 0.05)
    validate(m)
    assert m.counts() == open_sponge_counts(16, 24) == (160, 360, 184)
