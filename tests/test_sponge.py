"""Menger sponge remeshing: TopMod's cube counts, the clean surface, geometry, bad input."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import (
    DLFLError,
    face_size_histogram,
    from_polygons,
    genus,
    num_components,
    validate,
)
from livemod.dlfl.shapes import cube, icosahedron, tetrahedron, torus
from livemod.dlfl.sponge import sponge
from tests.meshes import assert_refused, assert_refused_quietly, point_sphere, snapshot


def test_cube_matches_topmod():
    m = cube()
    sponge(m)
    validate(m)
    assert m.counts() == (64, 156, 84)
    assert face_size_histogram(m) == {2: 12, 4: 72}
    assert genus(m) == 5 and num_components(m) == 1


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


@pytest.mark.parametrize("t", [0.0, -0.5, 1.0, 3.0])
def test_bad_thickness_leaves_the_mesh_unchanged(t):
    m = cube()
    before = snapshot(m)
    with pytest.raises(DLFLError):
        sponge(m, t)
    assert snapshot(m) == before


def two_gons():
    """Two 2-gons glued into a sphere (2/2/2)."""
    return from_polygons([[0, 0, 0], [1, 0, 0]], [[0, 1], [1, 0]])


@pytest.mark.parametrize("make", [two_gons, point_sphere])
def test_bad_meshes_are_refused(make):
    with pytest.raises(DLFLError):
        sponge(make(), 0.1)


@pytest.mark.parametrize(("thickness", "message"), [
    (None, "thickness must be a number"), (1 + 1j, "thickness must be a number"),
    (1.7976931348623157e308, "its numbers overflow"),
])
def test_thickness_of_the_wrong_kind_or_size_is_refused(thickness, message):
    assert_refused(cube(), lambda m: sponge(m, thickness), message)


@pytest.mark.parametrize(("thickness", "message"), [
    (1e308, r"thickness 1e\+308 would move vertex 0 to \[-?inf.*overflow"),
    (1e300, "would invert the crust"),  # pushed 1e300 inward, the copy is inside out
])
def test_a_thickness_that_overflows_prints_no_numpy_warning(thickness, message):
    assert_refused_quietly(cube(), lambda m: sponge(m, thickness), message)
