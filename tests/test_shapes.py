"""Built-in shapes: exact counts, genus, face sizes and valences, checked against the
figures of TopMod's sample files."""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from livemod.dlfl import face_size_histogram, genus, num_components, validate
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.io import read_obj
from livemod.dlfl.shapes import (
    SHAPES,
    cube,
    donut_hexa,
    genus3_hexa,
    genus_torus,
    grid,
    hex_refine,
    hex_torus,
    load_shape,
    spherical_cube,
    torus,
)
from tests.test_io_obj import CUBE as TOPMOD_CUBE_OBJ  # TopMod's cube.obj, commas and all

# TopMod's sample files, as counted: name -> ((V, E, F), face sizes, genus, valences)
SAMPLES = {
    "cube": ((8, 12, 6), {4: 6}, 0, {3: 8}),
    "tetrahedron": ((4, 6, 4), {3: 4}, 0, {3: 4}),
    "octahedron": ((6, 12, 8), {3: 8}, 0, {4: 6}),
    "icosahedron": ((12, 30, 20), {3: 20}, 0, {5: 12}),
    "dodecahedron": ((20, 30, 12), {5: 12}, 0, {3: 20}),
    "soccerball": ((60, 90, 32), {5: 12, 6: 20}, 0, {3: 60}),
    "geodesicdome": ((272, 810, 540), {3: 540}, 0, {5: 12, 6: 260}),
    "buckminster": ((540, 810, 272), {5: 12, 6: 260}, 0, {3: 540}),
    "sphericalcube": ((98, 192, 96), {4: 96}, 0, {3: 8, 4: 90}),
    "donuthexa1": ((100, 150, 50), {6: 50}, 1, {3: 100}),
    "donuthexa3": ((1600, 2400, 800), {6: 800}, 1, {3: 1600}),
    "genus3hexa1": ((161, 247, 82), {6: 80, 7: 2}, 3, {3: 150, 4: 11}),
    "genus3hexa3": ((2631, 3952, 1317), {6: 1315, 7: 2}, 3, {3: 2620, 4: 11}),
}


def valences(mesh):
    """Vertex valence -> how many vertices have it."""
    return dict(Counter(mesh.valence(v) for v in mesh.vertex_ids().tolist()))


@pytest.mark.parametrize("name", sorted(SAMPLES))
def test_same_counts_sizes_genus_and_valences_as_topmods_file(name):
    m = load_shape(name)
    validate(m)
    assert (m.counts(), face_size_histogram(m), genus(m), valences(m)) == SAMPLES[name]
    assert num_components(m) == 1


def test_soccer_ball_has_the_files_size_and_equal_edges():
    m = load_shape("soccerball")
    radii = np.linalg.norm(m.positions_view(), axis=1)
    np.testing.assert_allclose(radii, 1.652, atol=1e-3)
    lengths = [np.linalg.norm(m.position(a) - m.position(b))
               for a, b in (m.edge_vertices(e) for e in m.edge_ids().tolist())]
    np.testing.assert_allclose(lengths, lengths[0])


@pytest.mark.parametrize("name", ["geodesicdome", "buckminster", "sphericalcube"])
def test_spherical_shapes_lie_on_the_unit_sphere(name):
    radii = np.linalg.norm(load_shape(name).positions_view(), axis=1)
    np.testing.assert_allclose(radii, 1.0)


def test_cube_is_topmods_cube_obj():
    ours, theirs = cube(), read_obj(TOPMOD_CUBE_OBJ)
    np.testing.assert_allclose(ours.positions_view(), theirs.positions_view())
    assert [ours.face_vertices(f) for f in ours.face_ids().tolist()] == [
        [v - int(theirs.vertex_ids()[0]) for v in theirs.face_vertices(f)]
        for f in theirs.face_ids().tolist()
    ]


@pytest.mark.parametrize("g", [0, 1, 2, 3, 5])
def test_tori_of_any_genus(g):
    m = genus_torus(g)
    validate(m)
    assert genus(m) == g and num_components(m) == 1
    assert set(face_size_histogram(m)) == {4}


def test_torus_and_hex_torus():
    t = torus(8, 6)
    validate(t)
    assert t.counts() == (48, 96, 48) and genus(t) == 1
    h = hex_torus(12, 4)
    validate(h)
    assert h.counts() == (96, 144, 48) and face_size_histogram(h) == {6: 48} and genus(h) == 1


def test_hex_refine_keeps_hexagons():
    m = hex_refine(hex_torus())
    validate(m)
    assert m.counts() == (400, 600, 200) and face_size_histogram(m) == {6: 200}
    assert donut_hexa(2).counts() == (400, 600, 200)
    assert genus3_hexa(2).counts() == (655, 988, 329)


def test_grid_is_open():
    g = grid(3, 2)
    validate(g)
    assert g.counts() == (12, 17, 7)
    assert face_size_histogram(g) == {4: 6}


def test_spherical_cube_divisions():
    m = spherical_cube(2)
    validate(m)
    assert m.counts() == (26, 48, 24)


@pytest.mark.parametrize("call", [
    lambda: genus_torus(-1), lambda: genus_torus(1, 0.0), lambda: spherical_cube(0),
    lambda: torus(2, 5), lambda: hex_torus(3, 2), lambda: grid(0, 3), lambda: donut_hexa(4),
    lambda: genus3_hexa(0), lambda: load_shape("teapot"),
])
def test_bad_arguments_raise(call):
    with pytest.raises(InvalidArgumentError):
        call()


def test_every_registered_shape_loads_valid():
    for name in SHAPES:
        validate(load_shape(name))
    assert load_shape("SoccerBall.obj").counts() == (60, 90, 32)
