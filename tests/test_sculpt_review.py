"""Regression tests from the review of the handle, rind, wireframe, sponge,
sierpinsky and cutting operations (notes/sculpt_review.md)."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.dlfl import Mesh, from_polygons, genus, validate
from livemod.dlfl.connect import hermite_handle
from livemod.dlfl.errors import GeometryError, InvalidArgumentError
from livemod.dlfl.rind import rind
from livemod.dlfl.shapes import cube, icosahedron
from livemod.dlfl.sponge import sponge
from livemod.dlfl.wireframe import columns, modified_corner_cut
from tests.meshes import assert_refused, assert_scales


def _ends(m: Mesh) -> tuple[int, int]:
    """A corner of the cube's first face and one of the opposite face."""
    f0, f1 = m.face_ids()[:2].tolist()
    return m.face_corners(f0)[0], m.face_corners(f1)[0]


def _scaled_cube(scale: float) -> Mesh:
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * scale)
    return m


def _u_prism() -> Mesh:
    """A U-shaped prism (a slot 1 wide, 1 deep): concave, 16/24/10."""
    outline = [(0, 0), (3, 0), (3, 2), (2, 2), (2, 1), (1, 1), (1, 2), (0, 2)]
    n = len(outline)
    points = [(x, y, 0.0) for x, y in outline] + [(x, y, 1.0) for x, y in outline]
    faces = [list(range(n))[::-1], list(range(n, 2 * n))]
    faces += [[i, (i + 1) % n, (i + 1) % n + n, i + n] for i in range(n)]
    return from_polygons(np.array(points), faces)


# -- hermite_handle: twists ----------------------------------------------------------

@pytest.mark.parametrize("twists", [1.5, float("nan"), float("inf"), "2", True, 10**400])
def test_hermite_twists_that_are_not_a_whole_number_of_turns_are_refused(twists):
    # int(twists) truncated 1.5 to 1 unseen and raised ValueError/OverflowError on the rest
    m = cube()
    c1, c2 = _ends(m)
    assert_refused(m, lambda m: hermite_handle(m, c1, c2, 4, twists=twists), "twists",
                   error=InvalidArgumentError)


@pytest.mark.parametrize("twists", [2.0, np.int64(-1), -3])
def test_hermite_whole_twists_of_any_type_and_sign_work(twists):
    m = cube()
    c1, c2 = _ends(m)
    hermite_handle(m, c1, c2, 4, twists=twists)
    validate(m)
    assert m.counts() == (20, 40, 20) and genus(m) == 1


@pytest.mark.parametrize(("option", "message"), [
    ({"twists": "x"}, "twists"), ({"pinch": float("nan")}, "pinch"),
    ({"bubble": 0.0}, "bubble")])
def test_a_one_segment_hermite_handle_still_checks_its_options(option, message):
    # one segment is a plain connect_faces, which silently ignored bad options
    m = cube()
    c1, c2 = _ends(m)
    assert_refused(m, lambda m: hermite_handle(m, c1, c2, 1, **option), message,
                   error=InvalidArgumentError)


def test_the_hermite_handle_of_a_tiny_mesh_is_the_scaled_unit_one():
    # the centroids' distance was compared with an absolute 1e-12: "different centroids"
    def op(m: Mesh, s: float) -> None:
        c1, c2 = _ends(m)
        hermite_handle(m, c1, c2, 4, 25.0 * s, 25.0 * s)

    assert_scales(cube, op, scale=1e-150)


# -- rind and sponge: the inversion check at any scale ----------------------------------

@pytest.mark.parametrize("scale", [1e-13, 1e-150])
@pytest.mark.parametrize("thickness", [1.5, 3.0])
def test_a_rind_that_inverts_a_tiny_mesh_is_refused(scale, thickness):
    # absolute cut-offs (edges 1e-24 squared, areas 1e-12) left out every edge
    # and face of a tiny mesh, so a copy pushed through the middle passed
    m = _scaled_cube(scale)
    assert_refused(m, lambda m: rind(m, [m.face_ids()[0]], thickness * scale), "invert",
                   error=GeometryError)


@pytest.mark.parametrize("scale", [1e-13, 1e-150])
def test_a_sponge_too_thick_for_a_tiny_mesh_is_refused(scale):
    m = _scaled_cube(scale)
    assert_refused(m, lambda m: sponge(m, 1.5 * scale), "too large for this mesh",
                   error=GeometryError)


def test_the_rind_of_a_tiny_mesh_still_works():
    m = _scaled_cube(1e-150)
    rind(m, [m.face_ids()[0]], 0.5e-150)
    validate(m)
    assert m.counts() == (16, 28, 14)


def test_a_negative_thickness_that_turns_a_slot_floor_over_is_refused():
    # outward, the U's slot walls (1 apart) meet at 0.5: its floor reversed unchecked
    assert_refused(_u_prism(), lambda m: rind(m, [], -0.6), "-0.6 would invert",
                   error=GeometryError)


def test_a_negative_thickness_that_fits_the_slot_works():
    m = _u_prism()
    rind(m, [], -0.3)
    validate(m)
    assert m.counts() == (32, 48, 20)


# -- wireframe and columns of tiny meshes -------------------------------------------------

@pytest.mark.parametrize("make", [cube, icosahedron])
def test_the_corner_cut_of_a_tiny_mesh_is_the_scaled_unit_one(make):
    # neighbours closer than an absolute 1e-3 were taken for a 2-gon's: every
    # corner of a mesh 1e-150 across was cut toward the wrong corner
    assert_scales(make, lambda m, s: modified_corner_cut(m, 0.1 * s), scale=1e-150)


def test_the_columns_of_a_tiny_mesh_are_the_scaled_unit_ones():
    # rings sat an absolute 1e-4 out, where rings 1e-151 wide round to points
    # ("a convex hull needs 4 points not all in one plane")
    assert_scales(cube, lambda m, s: columns(m, 0.1 * s, 4), scale=1e-150)
