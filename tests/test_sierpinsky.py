"""Sierpinsky (TopMod's multiConnectMidpoints): counts, genus, ids, bad input."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import face_size_histogram, from_polygons, genus, validate
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.shapes import cube, octahedron, tetrahedron, torus
from livemod.dlfl.sierpinsky import sierpinsky
from tests.meshes import colour_counts, point_sphere, rainbow_cube, snapshot


def test_cube_matches_topmod():
    m = cube()
    sierpinsky(m)
    validate(m)
    assert m.counts() == (20, 60, 32)
    assert face_size_histogram(m) == {3: 24, 6: 8}
    assert genus(m) == 5


def test_midpoints_sit_on_the_old_edges():
    m = cube()
    old = {e: tuple(m.edge_vertices(e)) for e in m.edge_ids().tolist()}
    ref = cube()
    mids = sierpinsky(m)
    assert len(mids) == 12
    for e, v in zip(old, mids, strict=True):
        a, b = old[e]
        np.testing.assert_allclose(m.position(v), (ref.position(a) + ref.position(b)) / 2)


def test_old_vertex_ids_are_kept():
    m = cube()
    before = set(m.vertex_ids().tolist())
    sierpinsky(m)
    assert before <= set(m.vertex_ids().tolist())


@pytest.mark.parametrize("shape", [tetrahedron, octahedron, torus])
def test_other_meshes_stay_valid(shape):
    m = shape()
    v, e, f = m.counts()
    g = genus(m)
    sierpinsky(m)
    validate(m)
    assert m.counts()[0] == v + e
    assert face_size_histogram(m)[3] == sum(m.face_size(x) == 3 for x in m.face_ids().tolist())
    assert genus(m) >= g


def two_gons():
    """Two 2-gons glued into a sphere (2/2/2)."""
    return from_polygons([[0, 0, 0], [1, 0, 0]], [[0, 1], [1, 0]])


@pytest.mark.parametrize("make", [two_gons, point_sphere])
def test_bad_input_leaves_the_mesh_unchanged(make):
    m = make()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError):
        sierpinsky(m)
    assert snapshot(m) == before


def test_sculpting_a_mesh_with_self_loops():
    from livemod.dlfl.rind import rind
    from livemod.dlfl.sponge import sponge
    from livemod.dlfl.wireframe import wireframe

    for op, g in ((lambda m: rind(m, [], 0.05), 10), (lambda m: wireframe(m, 0.05), 60 - 20 + 1),
                  (lambda m: sponge(m, 0.05), 2 * 5 + 32 - 1)):
        m = cube()
        sierpinsky(m)
        op(m)
        validate(m)
        assert genus(m) == g


def test_a_corners_triangle_takes_its_face_colour_and_a_vertex_face_none():
    m = rainbow_cube()
    sierpinsky(m)
    validate(m)
    # 4 corner triangles per face; 8 vertex faces around old vertices
    assert colour_counts(m) == {**{f: 4 for f in range(6)}, None: 8}
