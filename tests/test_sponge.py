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
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.errors import GeometryError, InvalidArgumentError
from livemod.dlfl.shapes import cube, grid, icosahedron, tetrahedron, torus
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


def test_sponge_counts_give_topmods_on_the_cube():
    assert sponge_counts(8, 12) == (64, 156, 84)


@pytest.mark.parametrize("shape", [tetrahedron, torus])
def test_default_works_on_meshes_thinner_than_topmods_cube(shape):
    # 0.67 turns their inner shells inside out (the unit tetrahedron's collapses at
    # its inradius 1/3, the torus's tube at about 0.41): the default takes 0.67 of
    # the limit instead, the cube's proportion
    m = shape()
    v, e, f = m.counts()
    g, limit = genus(m), shell_limit(mesh_arrays(m))
    assert limit < TOPMOD_THICKNESS
    assert sponge(m) == pytest.approx(TOPMOD_THICKNESS * limit)
    validate(m)
    assert m.counts() == sponge_counts(v, e)
    assert face_size_histogram(m) == {2: e, 4: 6 * e}
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
