"""Extrusions: TopMod's counts on the cube (TOPMOD.md §4), positions against the
rules, chained towers, and bad input that leaves the mesh unchanged."""

from __future__ import annotations

import math
import re
import warnings
from pathlib import Path

import numpy as np
import pytest

from livemod.dlfl import (
    DLFLError,
    Mesh,
    Scene,
    commands,
    face_size_histogram,
    from_polygons,
    genus,
    use_scene,
    validate,
)
from livemod.dlfl.analysis import face_centroid, face_normal, face_points
from livemod.dlfl.connect import (
    bezier_handle,
    connect_corners,
    connect_faces,
    connect_faces_closest,
    dual_connect_faces,
    hermite_handle,
)
from livemod.dlfl.errors import (
    BudgetExceededError,
    GeometryError,
    InvalidArgumentError,
    UnknownIdError,
)
from livemod.dlfl.extrusion import (
    KINDS,
    doo_sabin_weights,
    extrude,
    extrude_fan,
    resolve_kind,
    small_polygon_normal,
)
from livemod.dlfl.multihandle import (
    multi_face_handle,
    multi_face_handle_closest_edges,
    multi_face_handle_fitted,
)
from livemod.dlfl.shapes import cube, dodecahedron, tetrahedron
from tests.meshes import (
    CUBE_FACES,
    CUBE_POSITIONS,
    assert_refused,
    assert_refused_quietly,
    assert_scales,
    euler_ok,
    rainbow_cube,
    snapshot,
)

TOP = 0  # cube face 0: vertices 0..3 at y = +1, normal +y


def checked(mesh: Mesh) -> tuple[int, int, int]:
    validate(mesh)
    assert euler_ok(mesh)
    return mesh.counts()


# kind, options, counts, face sizes (TOPMOD.md §4, one extrusion of cube face 0)
CUBE_TABLE = [
    ("cubical", {}, (12, 20, 10), {4: 10}),
    ("cubical", {"segments": 3}, (20, 36, 18), {4: 18}),
    ("doo-sabin", {}, (12, 20, 10), {4: 10}),
    ("octa", {}, (12, 24, 14), {3: 8, 4: 6}),
    ("octa", {"dual_mesh": True}, (12, 20, 10), {3: 4, 4: 2, 5: 4}),
    ("dodeca", {}, (20, 32, 14), {4: 6, 5: 8}),
    ("dodeca", {"segments": 2, "hexagonalize": True}, (32, 48, 18), {4: 6, 5: 8, 8: 4}),
    ("icosa", {}, (20, 48, 30), {3: 24, 4: 6}),
    ("cuboctahedral", {}, (16, 32, 18), {3: 8, 4: 10}),
    ("hex-tile", {}, (16, 24, 10), {4: 2, 5: 8}),
    ("planar-offset", {}, (12, 20, 10), {4: 10}),
]
FAN_TABLE = [
    ("stellate", (9, 16, 9), {3: 4, 4: 5}, 4),
    ("double-stellate", (13, 28, 17), {3: 12, 4: 5}, 12),
    ("dome", (29, 56, 29), {3: 4, 4: 25}, 4),
]


@pytest.mark.parametrize(("kind", "options", "counts", "sizes"), CUBE_TABLE)
def test_cube_counts_match_topmod(kind, options, counts, sizes):
    m = cube()
    end = extrude(m, TOP, kind, **options)
    assert checked(m) == counts
    assert face_size_histogram(m) == sizes
    assert genus(m) == 0
    assert m.has_face(end) and m.face_size(end) == 4


@pytest.mark.parametrize(("kind", "counts", "sizes", "fan_size"), FAN_TABLE)
def test_fan_counts_match_topmod(kind, counts, sizes, fan_size):
    m = cube()
    fan = extrude_fan(m, TOP, kind, 1.0)
    assert checked(m) == counts
    assert face_size_histogram(m) == sizes
    assert len(fan) == fan_size and all(m.face_size(f) == 3 for f in fan)


# -- the registry: every kind is whole (docs/architecture.md, "An extrusion kind")

def test_every_kind_is_in_one_of_the_tables():
    tabled = {row[0] for row in CUBE_TABLE} | {row[0] for row in FAN_TABLE}
    assert not set(KINDS) - tabled, (
        f"kinds without a row in CUBE_TABLE (ending in a face) or FAN_TABLE (ending in a "
        f"fan) of tests/test_extrusion.py: {sorted(set(KINDS) - tabled)}")
    assert not tabled - set(KINDS), f"table rows of no kind: {sorted(tabled - set(KINDS))}"


def test_every_kind_is_documented_for_scripts():
    """Its row in the kinds table of docs/extrusions.md, and its line (with its
    options) in the help of the thesis command ``extrude``."""
    rows = {line.split("|")[1].strip() for line in DOC.read_text(encoding="utf-8").splitlines()
            if line.startswith("| ")}
    missing = [kind for kind in KINDS if kind not in rows]
    assert not missing, f"kinds without a row in the table of docs/extrusions.md: {missing}"
    help_text = commands.extrude.__doc__ or ""
    missing = [kind for kind in KINDS if not re.search(rf"[* ]{re.escape(kind)}\b(?!-)", help_text)]
    assert not missing, (f"kinds the docstring of extrude in livemod/dlfl/commands/"
                         f"extrusion.py does not list: {missing}")


@pytest.mark.parametrize(("face", "axis", "sign"), [(0, 1, 1.0), (3, 0, -1.0)])
def test_three_cubical_segments_step_the_full_distance_each(face, axis, sign):
    m = cube()
    ends = []
    current = face
    for _ in range(3):
        current = extrude(m, current, "cubical", 2.0)
        ends.append(face_points(m, current)[:, axis])
    assert np.allclose(ends, sign * np.array([[3.0] * 4, [5.0] * 4, [7.0] * 4]), atol=1e-12)
    fresh = cube()
    end = extrude(fresh, face, "cubical", 2.0, segments=3)
    assert np.allclose(face_points(fresh, end), face_points(m, current), atol=1e-12)


def rotate_about(points: np.ndarray, axis: np.ndarray, degrees: float) -> np.ndarray:
    """Right-handed rotation about ``axis`` through the points' centroid (Rodrigues)."""
    c = points.mean(axis=0)
    t = math.radians(degrees)
    r = points - c
    return c + r * math.cos(t) + np.cross(axis, r) * math.sin(t) + np.outer(r @ axis, axis) * (1 - math.cos(t))


def test_cubical_positions_follow_the_rule():
    m = cube()
    p, n = face_points(m, TOP), face_normal(m, TOP)
    end = extrude(m, TOP, "cubical", 1.5, rotation=30.0, scale=-0.5)
    c = p.mean(axis=0)
    expected = rotate_about(c + 0.5 * (p - c), n, 30.0) + 1.5 * n
    assert np.allclose(face_points(m, end), expected, atol=1e-9)
    assert checked(m) == (12, 20, 10)


def test_doo_sabin_positions_follow_the_rule():
    m = cube()
    p, n = face_points(m, TOP), face_normal(m, TOP)
    end = extrude(m, TOP, "doo-sabin", 0.5, twist=0.25, scale=0.8)
    q = 0.75 * p + 0.25 * np.roll(p, -1, axis=0) + 0.5 * n
    w = np.array([[9, 3, 1, 3], [3, 9, 3, 1], [1, 3, 9, 3], [3, 1, 3, 9]]) / 16
    inner = w @ q
    c = inner.mean(axis=0)
    assert np.allclose(face_points(m, end), c + 0.8 * (inner - c), atol=1e-9)
    assert np.allclose(doo_sabin_weights(4), w, atol=1e-15)


def test_octa_end_face_is_the_moved_edge_midpoints():
    m = cube()
    p, n = face_points(m, TOP), face_normal(m, TOP)
    end = extrude(m, TOP, "octa", 1.0)
    mids = (p + np.roll(p, -1, axis=0)) / 2 + n
    assert np.allclose(face_points(m, end), mids, atol=1e-9)


def test_octa_scales_and_rotates_the_midpoints():
    m = cube()
    p, n = face_points(m, TOP), face_normal(m, TOP)
    end = extrude(m, TOP, "octa", 0.75, rotation=-20.0, scale=1.5)
    mids = (p + np.roll(p, -1, axis=0)) / 2 + 0.75 * n
    c = mids.mean(axis=0)
    assert np.allclose(face_points(m, end), rotate_about(c + 1.5 * (mids - c), n, -20.0), atol=1e-9)


def test_stellate_apex_is_centroid_plus_distance_along_normal():
    m = cube()
    c, n = face_centroid(m, TOP), face_normal(m, TOP)
    fan = extrude_fan(m, TOP, "stellate", 1.25)
    apex = set.intersection(*(set(m.face_vertices(f)) for f in fan)).pop()
    assert np.allclose(m.position(apex), c + 1.25 * n, atol=1e-12)


def test_double_stellate_positions():
    m = cube()
    p, n = face_points(m, TOP), face_normal(m, TOP)
    c = p.mean(axis=0)
    extrude_fan(m, TOP, "double-stellate", 0.7)
    new = [m.position(v) for v in m.vertex_ids() if v >= 8]
    expected = [c + 0.7 * n] + [(c + p[i] + p[(i + 1) % 4]) / 3 for i in range(4)]
    assert sorted(map(tuple, np.round(new, 9))) == sorted(map(tuple, np.round(expected, 9)))


def test_planar_offset_insets_along_the_edge_vectors():
    m = cube()
    p, n = face_points(m, TOP), face_normal(m, TOP)
    end = extrude(m, TOP, "planar-offset", 0.5, thickness=0.25)
    offset = 0.25 * ((np.roll(p, 1, axis=0) - p) + (np.roll(p, -1, axis=0) - p))
    assert np.allclose(face_points(m, end), p + offset + 0.5 * n, atol=1e-12)


@pytest.mark.parametrize("kind", ["dodeca", "icosa"])
def test_compound_kinds_end_a_full_distance_away(kind):
    m = cube()
    c, n = face_centroid(m, TOP), face_normal(m, TOP)
    end = extrude(m, TOP, kind, 3.0)
    assert np.allclose(face_centroid(m, end), c + 3.0 * n, atol=1e-9)


def test_dome_ends_in_a_low_apex():
    m = cube()
    fan = extrude_fan(m, TOP, "dome", 2.0)
    tops = [m.position(v)[1] for f in fan for v in m.face_vertices(f)]
    assert max(tops) == pytest.approx(1.0 + 2.0 * (0.3 + 0.18 + 0.1 + 0.05 + 0.025 + 0.01))


def test_thesis_tower_of_chained_doo_sabin_extrusions():
    m = cube()
    face = TOP
    for i in range(36):
        t = 2 * math.pi * i / 36
        face = extrude(m, face, "doo-sabin", 0.5 + 0.3 * math.sin(t), 1, 0.0, 0.9 + 0.1 * math.sin(t))
    assert checked(m) == (8 + 4 * 36, 12 + 8 * 36, 6 + 4 * 36)
    assert face_size_histogram(m) == {4: 6 + 4 * 36}


@pytest.mark.parametrize(("shape", "face_size"), [(tetrahedron, 3), (dodecahedron, 5)])
def test_other_polygons(shape, face_size):
    for kind in ("cubical", "doo-sabin", "octa", "dodeca", "icosa", "cuboctahedral"):
        m = shape()
        face = int(m.face_ids()[0])
        assert m.face_size(face) == face_size
        end = extrude(m, face, kind, 0.5)
        checked(m)
        assert m.face_size(end) == face_size and genus(m) == 0
    m = shape()
    v, e, f = m.counts()
    extrude(m, int(m.face_ids()[0]), "cubical", 0.5)
    assert checked(m) == (v + face_size, e + 2 * face_size, f + face_size)


def test_extrusions_touch_only_new_elements_and_the_face():
    m = cube()
    before = {v: m.position(v) for v in m.vertex_ids()}
    extrude(m, TOP, "cubical", 1.0)
    for v, p in before.items():
        assert np.array_equal(m.position(v), p)


def test_small_polygon_normal_matches_the_analysis_rule():
    rng = np.random.default_rng(4)
    from livemod.dlfl.analysis import polygon_normal

    for k in (3, 4, 5, 8):
        for _ in range(20):
            pts = rng.normal(size=(k, 3))
            assert np.allclose(small_polygon_normal(pts.tolist()), polygon_normal(pts), atol=1e-12)


@pytest.mark.parametrize("scale", [1e-200, 1e200, 1e300])
def test_small_polygon_normal_does_not_depend_on_the_scale(scale):
    # the raw corner cross products underflowed (zero normal: "degenerate")
    # or overflowed (NaN) beyond about 1e+-77
    rng = np.random.default_rng(5)
    from livemod.dlfl.analysis import polygon_normal

    for k in (3, 4, 7):
        pts = rng.normal(size=(k, 3))
        np.testing.assert_allclose(small_polygon_normal((pts * scale).tolist()),
                                   polygon_normal(pts), atol=1e-12)



def test_small_polygon_normal_of_a_subnormal_face():
    # the rescale's factor 2**1064 alone overflowed (OverflowError: math range error)
    square = [[0.0, 0.0, 0.0], [5e-320, 0.0, 0.0], [5e-320, 5e-320, 0.0], [0.0, 5e-320, 0.0]]
    assert small_polygon_normal(square) == (0.0, 0.0, 1.0)

def test_small_polygon_normal_far_from_the_origin_keeps_its_sign():
    # the Newell vector of raw coordinates 1e9 away cancelled to noise, and the
    # corners were flipped to agree with it: about one square in four came out
    # pointing down
    rng = np.random.default_rng(0)
    for _ in range(40):
        square = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], float)
        square[:, :2] += rng.normal(size=(4, 2)) * 0.01
        far = square + [1e9, -1e9, 0.7e9]
        np.testing.assert_allclose(small_polygon_normal(far.tolist()), [0, 0, 1], atol=1e-6)


@pytest.mark.parametrize("scale", [1e-200, 1e200])
@pytest.mark.parametrize("kind", ["cubical", "doo-sabin", "octa", "dodeca", "stellate"])
def test_extruding_a_huge_or_tiny_mesh_is_the_scaled_unit_extrusion(kind, scale):
    # such faces were refused as degenerate, or their normal was NaN
    def op(m: Mesh, s: float) -> None:
        run = extrude_fan if KINDS[kind].fan is not None else extrude
        run(m, TOP, kind, 0.5 * s)

    assert_scales(cube, op, scale)


def test_kind_names_resolve_exactly_then_by_prefix():
    assert resolve_kind("Doo-Sabin") == "doo-sabin"
    assert resolve_kind("dual") == "octa"
    assert resolve_kind("double") == "double-stellate"
    assert resolve_kind("ico") == "icosa"
    with pytest.raises(InvalidArgumentError, match="ambiguous.*cubical"):
        resolve_kind("cub")


# -- bad input ---------------------------------------------------------------------

def bad_cases(m: Mesh):
    gone_face = int(m.next_ids()[2]) + 5
    return [
        (lambda: extrude(m, gone_face, "cubical"), UnknownIdError, "does not exist"),
        (lambda: extrude(m, TOP, "twirl"), InvalidArgumentError,
         "valid kinds: doo-sabin, dodeca, icosa, octa"),
        (lambda: extrude(m, TOP, "cubical", segments=0), InvalidArgumentError, "segments"),
        (lambda: extrude(m, TOP, "cubical", segments=1.5), InvalidArgumentError, "segments"),
        (lambda: extrude(m, TOP, "cubical", distance=math.nan), InvalidArgumentError, "finite"),
        (lambda: extrude(m, TOP, "stellate", segments=2), InvalidArgumentError,
         "stellate extrusion ends in a fan of triangles: it has no segments, got segments=2"),
        (lambda: extrude_fan(m, TOP, "cubical"), InvalidArgumentError, "use extrude"),
        (lambda: extrude(m, "0", "cubical"), InvalidArgumentError, "face id"),
    ]


@pytest.mark.parametrize("case", range(8))
def test_bad_input_raises_and_leaves_the_mesh_unchanged(case):
    m = cube()
    call, error, message = bad_cases(m)[case]
    before = snapshot(m)
    with pytest.raises(error, match=message):
        call()
    assert snapshot(m) == before


def test_deleted_face_and_point_sphere_are_refused():
    m = cube()
    end = extrude(m, TOP, "cubical")
    edge = m.face_edges(end)[0]
    both = set(m.edge_faces(edge))
    (kept,) = m.delete_edge(edge)  # the two faces merge; one id is gone for good
    (gone,) = both - {kept}
    before = snapshot(m)
    with pytest.raises(UnknownIdError, match=f"face {gone} does not exist"):
        extrude(m, gone, "doo-sabin")
    assert snapshot(m) == before
    p = Mesh()
    v = p.create_vertex((0, 0, 0))
    with pytest.raises(InvalidArgumentError, match="corner"):
        extrude(p, p.corner_face(p.vertex_corner(v)), "cubical")


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_degenerate_face_is_refused_by_every_kind(kind):
    m = Mesh()
    front, _ = m.create_face([(0, 0, 0), (1, 0, 0), (2, 0, 0)])  # collinear: no normal
    before = snapshot(m)
    run = extrude_fan if KINDS[kind].fan is not None else extrude
    with pytest.raises(GeometryError, match="degenerate"):
        run(m, front, kind)
    assert snapshot(m) == before


def test_dodeca_scales_each_sub_step_by_the_sixth_root():
    m = cube()
    p = face_points(m, TOP)
    end = extrude(m, TOP, "dodeca", 3.0, scale=0.64)
    q = face_points(m, end)
    # the end square: the first cubical copy, scaled three times by 0.64^(1/6), with
    # the dual step's midpoint square in between (a 45 degree turn, half the area)
    size = np.linalg.norm(q - q.mean(axis=0), axis=1)
    start = np.linalg.norm(p - p.mean(axis=0), axis=1)
    assert np.allclose(size, start * 0.64 ** 0.5 * math.sqrt(0.5), atol=1e-9)


def test_random_sequences_stay_valid_and_refusals_change_nothing():
    import random

    rng = random.Random(11)
    for _ in range(25):
        m = rng.choice([cube, dodecahedron, tetrahedron])()
        for _ in range(4):
            face = rng.choice(m.face_ids().tolist())
            kind = rng.choice(sorted(KINDS))
            before = snapshot(m)
            try:
                if KINDS[kind].fan is not None:
                    extrude_fan(m, face, kind, rng.uniform(-1, 1))
                else:
                    extrude(m, face, kind, rng.uniform(-1, 2), rng.randint(1, 2),
                            rng.uniform(-40, 40), rng.uniform(0.5, 1.5))
            except DLFLError:
                assert snapshot(m) == before
            validate(m)
        f1, f2 = rng.sample(m.face_ids().tolist(), 2)
        c1, c2 = m.face_corner(f1), m.face_corner(f2)
        before = snapshot(m)
        join = rng.choice(["connect", "hermite", "multi"])
        try:
            if join == "connect":
                connect_faces(m, c1, c2, rng.randint(1, 3))
            elif join == "hermite":
                hermite_handle(m, c1, c2, rng.randint(1, 3), 2.0, 2.0)
            else:
                multi_face_handle(m, [f1, f2])
        except DLFLError:
            assert snapshot(m) == before
        checked(m)


def test_rotation_is_right_handed_about_the_normal():
    m = cube()
    end = extrude(m, TOP, "cubical", 1.0, rotation=90.0)
    # about +y, a right-handed quarter turn takes (x, z) to (z, -x): v0 (1, 1, 1) -> (1, 2, -1)
    assert np.allclose(m.position(m.face_vertices(end)[0]), [1.0, 2.0, -1.0], atol=1e-12)


def _face_with_a_dangling_edge() -> tuple[Mesh, int]:
    m = cube()
    top = int(m.face_ids()[0])
    spoke_end = m.create_vertex((0.3, 1.0, -0.4))
    m.insert_edge(int(m.face_corners(top)[0]), int(m.vertex_corners(spoke_end)[0]))
    return m, top


@pytest.mark.parametrize(("kind", "run"), [("icosa", extrude), ("double-stellate", extrude_fan)])
def test_kinds_that_need_a_simple_face_refuse_one_with_a_dangling_edge(kind, run) -> None:
    m, top = _face_with_a_dangling_edge()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match=f"face {top} visits vertex .* more than once .*{kind}"):
        run(m, top, kind)
    assert snapshot(m) == before  # was left half-extruded before the check
    extrude(m, top, "cubical")     # the other kinds take such a face
    validate(m)


# -- failures part-way (later segments and sub-steps) ---------------------------------

def shifted_cube() -> Mesh:
    """TopMod's cube moved to (5, 5, 5): scaling a face by 1e-11 twice about its
    centroid rounds all its points onto the centroid, a degenerate face."""
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() + 5.0)
    return m


def zero_edge_cube() -> Mesh:
    """The unit cube with vertex 1 moved onto vertex 0: face 0 keeps a normal, but
    a stellation of it has a triangle with no area."""
    pos = CUBE_POSITIONS.copy()
    pos[1] = pos[0]
    return from_polygons(pos, CUBE_FACES)


# kind, options, cause: each builds its first segment (or sub-step) and used to
# raise in a later one, with the mesh already changed
PART_WAY = [
    ("cubical", {"distance": 1e308, "segments": 2}, "overflows"),
    ("planar-offset", {"distance": 1e308, "segments": 2}, "overflows"),
    ("cubical", {"scale": 1e-11, "segments": 3}, "degenerate"),
    ("doo-sabin", {"scale": 1e-11, "segments": 3}, "degenerate"),
    ("octa", {"scale": 1e-11, "segments": 3}, "degenerate"),
    ("dodeca", {"distance": 1e308, "segments": 2}, "overflows"),
    ("icosa", {"scale": 1e-11, "segments": 2}, "degenerate"),
    ("icosa", {"distance": 1e308}, "overflows"),
    ("cuboctahedral", {"scale": 1e-11, "segments": 2}, "degenerate"),
    ("hex-tile", {"scale": 1e-11, "segments": 2}, "degenerate"),
    ("dome", {"scale": 1e-11}, "degenerate"),
    ("dome", {"distance": 1e308}, "overflows"),
]


@pytest.mark.parametrize(("kind", "options", "cause"), PART_WAY)
def test_an_extrusion_failing_part_way_leaves_the_mesh_unchanged(kind, options, cause):
    m = shifted_cube()
    before = snapshot(m)
    run = extrude_fan if KINDS[kind].fan is not None else extrude
    with pytest.raises(GeometryError, match=f"{kind} extrusion of face {TOP} cannot be built: .*"
                       f"{cause}.*the mesh is unchanged"):
        run(m, TOP, kind, **options)
    assert snapshot(m) == before


def test_double_stellate_refuses_a_face_whose_stellation_is_degenerate():
    m = zero_edge_cube()
    before = snapshot(m)
    with pytest.raises(GeometryError, match="double-stellate extrusion of face 0 cannot be built: "
                       "a face it makes on the way is degenerate"):
        extrude_fan(m, 0, "double-stellate", 1.0)
    assert snapshot(m) == before


def test_a_first_step_that_overflows_names_the_point():
    m = cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * 4.0)  # corners 4 from the centroid
    before = snapshot(m)
    with pytest.raises(GeometryError, match=r"would put a point at \[.*inf.*overflow"):
        extrude(m, TOP, "cubical", scale=1e308)
    assert snapshot(m) == before


@pytest.mark.parametrize(("kind", "options"), [
    (kind, options) for kind, options, cause in PART_WAY if cause == "overflows"] + [
    ("doo-sabin", {"distance": 1e308, "twist": 1e308}),
    ("octa", {"distance": -1e308, "scale": 1e308}), ("planar-offset", {"thickness": 1e308})])
def test_an_extrusion_that_overflows_prints_no_numpy_warning(kind, options):
    run = extrude_fan if KINDS[kind].fan is not None else extrude
    assert_refused_quietly(shifted_cube(), lambda m: run(m, TOP, kind, **options), "overflow")


@pytest.mark.parametrize("kind", list(KINDS))
def test_extruding_a_face_near_the_float_range_prints_no_numpy_warning(kind):
    near = from_polygons(CUBE_POSITIONS * 1.7e308 - 0.85e308, CUBE_FACES)
    run = extrude_fan if KINDS[kind].fan is not None else extrude
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        before = snapshot(near)
        try:
            run(near, TOP, kind)
        except DLFLError as exc:
            assert "overflow" in str(exc)
            assert snapshot(near) == before
        else:
            validate(near)


@pytest.mark.parametrize(("kind", "segments", "budget", "error", "message"), [
    ("cubical", 10**30, None, BudgetExceededError,
     "cubical extrusion would produce more than 10\\^18 faces"),
    # past the face budget's first, then past what a mesh can hold
    ("dodeca", 600_000_000, None, BudgetExceededError,
     "would produce 24,000,000,024 corners, more than the budget"),
    ("dodeca", 600_000_000, 10**12, InvalidArgumentError,
     "would make at least 2,400,000,000 corners, more than a mesh can hold \\(2,147,483,647\\)"),
    ("doo-sabin", 1.5, None, InvalidArgumentError, "segments must be an integer >= 1, got 1.5"),
    ("icosa", 0, None, InvalidArgumentError, "segments must be an integer >= 1, got 0"),
])
def test_segment_counts_a_mesh_cannot_hold_are_refused_at_once(kind, segments, budget, error,
                                                              message):
    assert_refused(cube(), lambda m: extrude(m, 0, kind, 0.5, segments, max_faces=budget),
                   message, error=error)


# -- hole faces --------------------------------------------------------------------

def open_box() -> tuple[Mesh, int]:
    """The unit cube without its bottom, 8/12/6: the bottom loop is a hole face,
    returned with the mesh."""
    m = from_polygons(CUBE_POSITIONS, CUBE_FACES[1:])
    (hole,) = [f for f in m.face_ids().tolist() if m.is_hole(f)]
    return m, hole


@pytest.mark.parametrize("kind", list(KINDS))
def test_a_hole_face_is_refused_by_every_kind(kind):
    # before: a cap detached from the surface, its walls holes too
    m, hole = open_box()
    run = extrude_fan if KINDS[kind].fan is not None else extrude
    assert_refused(m, lambda m: run(m, hole, kind), f"face {hole} is a hole",
                   error=InvalidArgumentError)


def test_a_hole_face_is_refused_with_segments_and_by_the_thesis_command():
    m, hole = open_box()
    assert_refused(m, lambda m: extrude(m, hole, "dodeca", segments=3, hexagonalize=True),
                   f"face {hole} is a hole .* cannot be extruded", error=InvalidArgumentError)
    scene = Scene()
    scene.add(m, "box")
    with use_scene(scene):
        assert_refused(m, lambda _: commands.extrude("cubical", hole), f"face {hole} is a hole",
                       error=InvalidArgumentError)


def test_a_face_next_to_a_hole_still_extrudes_and_the_hole_stays():
    m, hole = open_box()
    side = next(f for f in m.face_ids().tolist()
                if f != hole and set(m.face_vertices(f)) & set(m.face_vertices(hole)))
    extrude(m, side, "cubical")
    assert checked(m) == (12, 20, 10)
    assert [f for f in m.face_ids().tolist() if m.is_hole(f)] == [hole]
    assert m.face_size(hole) == 4


@pytest.mark.parametrize("options", [{"kind": "hex-tile"}, {"kind": "octa", "dual_mesh": True}])
def test_a_step_that_deletes_an_edge_along_a_hole_grows_the_hole(options):
    """These steps delete the face's old edges, merging each neighbour with a new
    triangle; where the neighbour is the hole, the triangle joins the opening (it
    used to turn the hole into a drawn face and close the box)."""
    m, hole = open_box()
    side = next(f for f in m.face_ids().tolist()
                if f != hole and set(m.face_vertices(f)) & set(m.face_vertices(hole)))
    extrude(m, side, **options)
    validate(m)
    holes = [f for f in m.face_ids().tolist() if m.is_hole(f)]
    assert len(holes) == 1  # the merged face keeps the first side's id, maybe not the hole's
    assert m.face_size(holes[0]) == 5  # the old ring plus a new vertex between two ends


# -- hex-tile counts -----------------------------------------------------------------

# One hex-tile step on an n-gon (extrudeHexTileFace, TOPMOD.md §4):
#   dual step (midpoint n-gon as a two-sided polygon + 2n band triangles):
#       V + n, E + n + 2n, F + 2 - 1 + (2n - 1) = F + 2n   (the first band edge merges)
#   its dual_mesh deletes the face's n old edges, each merging two faces: E - n, F - n
#   cubical step on the dual n-gon: V + n, E + n + n, F + n
#   deleting the dual n-gon's n edges: E - n, F - n
# so V + 2n, E + 3n, F + n per step, ending in an n-gon again. The cube (8/12/6,
# n = 4): 16/24/10 after 1 segment, 24/36/14 after 2 (not 28/44/18: that is
# TopMod's binding's dodeca-then-hex-tile variant, 20/32/14 + 8/12/4).
@pytest.mark.parametrize(("segments", "counts", "sizes"), [
    (1, (16, 24, 10), {4: 2, 5: 8}),
    (2, (24, 36, 14), {4: 2, 5: 8, 6: 4}),
])
def test_hex_tile_counts(segments, counts, sizes):
    m = cube()
    end = extrude(m, TOP, "hex-tile", segments=segments)
    assert checked(m) == counts
    assert face_size_histogram(m) == sizes  # adjacent segments' pentagons make hexagons
    assert m.face_size(end) == 4 and genus(m) == 0


def test_topmods_binding_variant_is_dodeca_then_hex_tile():
    m = cube()
    extrude(m, extrude(m, TOP, "dodeca"), "hex-tile")
    assert checked(m) == (28, 44, 18)
    assert face_size_histogram(m) == {4: 6, 5: 8, 6: 4}


# -- every V/E/F figure of docs/extrusions.md ------------------------------------------

DOC = Path(__file__).resolve().parents[1] / "docs" / "extrusions.md"
FIGURE = re.compile(r"\b\d+/\d+/\d+\b")


def _connect(run):
    """``run(mesh, top_corner, bottom_corner)`` on the cube's top (face 0, at
    vertex 0) and bottom (face 5, at vertex 4) corners, the doc's top–bottom."""
    return lambda m: run(m, m.corner_at(0, 0), m.corner_at(5, 4))


def _handle(run):
    """``run(mesh, c1, c2)`` on faces 0 and 1 at vertex 0, the doc's faces 0–1."""
    return lambda m: run(m, m.corner_at(0, 0), m.corner_at(1, 0))


# (a text only the doc's row or bullet holds, its V/E/F figure, what makes it from
# TopMod's cube); rows that say "as above" are keyed to the row they refer to
DOC_FIGURES = [
    ("| cubical |", "12/20/10", lambda m: extrude(m, TOP, "cubical")),
    ("| doo-sabin |", "12/20/10", lambda m: extrude(m, TOP, "doo-sabin")),
    ("| octa |", "12/24/14", lambda m: extrude(m, TOP, "octa")),
    ("| octa |", "12/20/10", lambda m: extrude(m, TOP, "octa", dual_mesh=True)),
    ("| dodeca |", "20/32/14", lambda m: extrude(m, TOP, "dodeca")),
    ("| dodeca |", "32/48/18",
     lambda m: extrude(m, TOP, "dodeca", segments=2, hexagonalize=True)),
    ("| icosa |", "20/48/30", lambda m: extrude(m, TOP, "icosa")),
    ("| cuboctahedral |", "16/32/18", lambda m: extrude(m, TOP, "cuboctahedral")),
    ("| hex-tile |", "16/24/10", lambda m: extrude(m, TOP, "hex-tile")),
    ("| hex-tile |", "24/36/14", lambda m: extrude(m, TOP, "hex-tile", segments=2)),
    ("| planar-offset |", "12/20/10", lambda m: extrude(m, TOP, "planar-offset")),
    ("| stellate |", "9/16/9", lambda m: extrude_fan(m, TOP, "stellate")),
    ("| double-stellate |", "13/28/17", lambda m: extrude_fan(m, TOP, "double-stellate")),
    ("| dome |", "29/56/29", lambda m: extrude_fan(m, TOP, "dome")),
    ("binding's own multi-segment variant", "28/44/18",
     lambda m: extrude(m, extrude(m, TOP, "dodeca"), "hex-tile")),
    ("binding's own multi-segment variant", "24/36/14",
     lambda m: extrude(m, TOP, "hex-tile", segments=2)),
    ("`connect_faces(mesh", "8/16/8", _connect(connect_faces)),
    ("`connect_faces(mesh", "16/32/16", _connect(lambda m, a, b: connect_faces(m, a, b, 3))),
    ("`connect_faces(mesh", "8/16/8", lambda m: connect_faces_closest(m, 0, 5)),
    ("`connect_faces(mesh", "16/32/16", lambda m: connect_faces_closest(m, 0, 5, 3)),
    ("`dual_connect_faces`", "8/20/12", _connect(dual_connect_faces)),
    ("`dual_connect_faces`", "8/20/12",
     _connect(lambda m, a, b: connect_corners(m, a, b, dual=True))),
    ("`hermite_handle`", "44/88/44", _handle(lambda m, a, b: hermite_handle(m, a, b, 10))),
    ("`bezier_handle`", "44/88/44", _handle(lambda m, a, b: bezier_handle(m, a, b, 10))),
    ("`multi_face_handle(", "20/42/20", lambda m: multi_face_handle(m, [0, 2, 4])),
    ("`multi_face_handle_closest_edges(", "8/16/8",
     lambda m: multi_face_handle_closest_edges(m, [0, 5])),
    ("`multi_face_handle_fitted(", "16/32/16", lambda m: multi_face_handle_fitted(m, [0, 5])),
]


def _doc_blocks() -> list[str]:
    """The lines of docs/extrusions.md, each bullet joined with its indented lines."""
    blocks: list[str] = []
    for line in DOC.read_text(encoding="utf-8").splitlines():
        if line.startswith("  ") and blocks and blocks[-1].startswith("- "):
            blocks[-1] += " " + line.strip()
        else:
            blocks.append(line)
    return blocks


@pytest.mark.parametrize(("key", "figure", "run"), DOC_FIGURES,
                         ids=[f"{key.strip('|` ')}:{figure}" for key, figure, _ in DOC_FIGURES])
def test_each_documented_figure_is_what_the_code_makes(key, figure, run):
    m = cube()
    run(m)
    assert "/".join(map(str, checked(m))) == figure


def test_the_documented_figures_are_exactly_those_checked():
    blocks = [b for b in _doc_blocks() if FIGURE.search(b)]
    keys = {key for key, _, _ in DOC_FIGURES}
    for key in keys:
        assert sum(key in b for b in blocks) == 1, f"{key!r} must name one row of the doc"
    for block in blocks:
        matching = [k for k in keys if k in block]
        assert len(matching) == 1, f"{block!r} needs one key in DOC_FIGURES, has {matching}"
        (key,) = matching
        checked_here = {figure for k, figure, _ in DOC_FIGURES if k == key}
        assert set(FIGURE.findall(block)) == checked_here, block


@pytest.mark.parametrize("option", ["dual_mesh", "hexagonalize", "fractional"])
def test_an_on_off_option_that_is_not_a_flag_is_refused(option):
    m = cube()
    before = snapshot(m)
    with pytest.raises(InvalidArgumentError, match=f"{option} must be True or False, got 'no'"):
        extrude(m, 0, "octa", **{option: "no"})
    assert snapshot(m) == before


# -- TopMod's GUI shapes of the dodecahedral and icosahedral extrusions ------------

def _unit(v: np.ndarray) -> np.ndarray:
    return v / np.linalg.norm(v)


def _planar(points: list[np.ndarray]) -> np.ndarray:
    """The unit normal of ``points``, asserting they lie in one plane."""
    p = np.array(points)
    normal = _unit(np.cross(p[1] - p[0], p[2] - p[0]))
    np.testing.assert_allclose((p - p[0]) @ normal, 0.0, atol=1e-12)
    return normal


def test_gui_dodeca_shape_tilts_every_pentagon_by_the_angle():
    from livemod.dlfl.extrusion import DODECA_SHAPE, Shape

    m = cube()
    base = face_points(m, TOP)
    end = extrude(m, TOP, "dodeca", shape=Shape(35.0, 0.5, 1.0, 1.0))
    assert checked(m) == (20, 32, 14) and face_size_histogram(m) == {4: 6, 5: 8}
    pentagons = [f for f in m.face_ids().tolist() if m.face_size(f) == 5]
    lower = [f for f in pentagons if len(set(m.face_vertices(f)) & set(range(8))) == 2]
    assert len(lower) == 4
    for f in pentagons:
        normal = _planar([m.position(v) for v in m.face_vertices(f)])
        if f in lower:  # a side face over a base edge, 35 degrees from upright
            assert normal[1] == pytest.approx(-math.sin(math.radians(35.0)))
    top = np.array([m.position(v) for v in m.face_vertices(end)])
    assert _planar(list(top))[1] == pytest.approx(1.0)
    # base side 2: the first ring 2 l1 from the base corners, the end face a square
    # turned by 45 degrees about the axis
    first = [m.position(v) for v in range(8, 12)]
    assert [float(np.linalg.norm(p - b)) for p, b in zip(first, base, strict=True)] == \
        pytest.approx([1.0] * 4)
    assert all(min(abs(p[0]), abs(p[2])) == pytest.approx(0.0, abs=1e-12) for p in top)
    assert Shape(40.0, 0.5, 1.0, 1.0) == DODECA_SHAPE


def test_gui_icosa_shape_places_the_three_rings_by_its_lengths():
    from livemod.dlfl.extrusion import ICOSA_SHAPE, icosa_shape_rings

    m = cube()
    base = face_points(m, TOP)
    extrude(m, TOP, "icosa", shape=ICOSA_SHAPE)
    assert checked(m) == (20, 48, 30) and face_size_histogram(m) == {3: 24, 4: 6}
    rings = icosa_shape_rings(base, np.array([0.0, 1.0, 0.0]), ICOSA_SHAPE)
    mids, copies, apexes = rings[:4], rings[4:8], rings[8:]
    sides = base[[1, 2, 3, 0]] - base
    # each dual point: over its side's midpoint, in the plane through the side
    # tilted 50 degrees, L l1 sqrt(3)/2 away (L = 2)
    for i in range(4):
        offset = mids[i] - (base[i] + sides[i] / 2)
        assert float(np.linalg.norm(offset)) == pytest.approx(2 * 0.5 * math.sqrt(3) / 2)
        assert float(offset @ sides[i]) == pytest.approx(0.0, abs=1e-12)
        normal = _planar([base[i], base[(i + 1) % 4], mids[i]])
        assert abs(normal[1]) == pytest.approx(math.sin(math.radians(50.0)))
    assert np.linalg.norm(apexes - base, axis=1) == pytest.approx([2 * 0.7] * 4)
    assert np.linalg.norm(copies - mids, axis=1) == pytest.approx([2 * 0.8] * 4)
    placed = {tuple(np.round(m.position(v), 12)) for v in m.vertex_ids().tolist() if v >= 8}
    assert placed == {tuple(np.round(p, 12)) for p in rings}


def test_a_gui_shape_is_refused_where_the_kind_has_none():
    from livemod.dlfl.extrusion import DODECA_SHAPE

    assert_refused(cube(), lambda m: extrude(m, TOP, "cubical", shape=DODECA_SHAPE),
                   "a cubical extrusion has no shape options")


# -- several faces at once, as TopMod extrudes a selection ---------------------------

def test_extruding_several_faces_is_extruding_each_in_turn():
    from livemod.dlfl.extrusion import extrude_faces

    together, one_by_one = cube(), cube()
    ends = extrude_faces(together, [TOP, 1, 5], "cubical", 0.5, 2, 10.0, 0.9)
    alone = [extrude(one_by_one, f, "cubical", 0.5, 2, 10.0, 0.9) for f in (TOP, 1, 5)]
    assert ends == alone and snapshot(together) == snapshot(one_by_one)
    assert checked(together) == (8 + 24, 12 + 48, 6 + 24)
    assert genus(together) == 0


def test_octa_mesh_on_neighbours_deletes_the_old_edges_after_every_face():
    from livemod.dlfl.extrusion import extrude_faces

    m = cube()
    shared = set(m.face_edges(TOP)) & set(m.face_edges(1))
    assert len(shared) == 1
    extrude_faces(m, [TOP, 1], "octa", 1.0, dual_mesh=True)
    # two octa steps without mesh (16/36/22), then the 7 old edges deleted
    assert checked(m) == (16, 29, 15)
    # of the 16 band triangles, the two over the shared edge merge into a quad and
    # six merge into the cube's side faces (pentagons; hexagons beside both faces)
    assert face_size_histogram(m) == {3: 8, 4: 2 + 1, 5: 2, 6: 2}
    apart = cube()
    extrude_faces(apart, [TOP, 5], "octa", 1.0, dual_mesh=True)
    single = cube()
    extrude(single, TOP, "octa", 1.0, dual_mesh=True)
    extrude(single, 5, "octa", 1.0, dual_mesh=True)
    assert checked(apart) == (16, 28, 14) == checked(single)


def test_several_fans_and_their_triangles():
    from livemod.dlfl.extrusion import extrude_faces

    m = cube()
    fans = extrude_faces(m, [TOP, 5], "stellate", 1.0, fans=True)
    assert checked(m) == (10, 20, 12) and [len(fan) for fan in fans] == [4, 4]
    assert extrude_faces(cube(), [TOP, 5], "stellate", 1.0) == [fan[0] for fan in fans]


def _collinear_bottom() -> Mesh:
    """TopMod's cube with its bottom face (5) squashed onto a line."""
    m = cube()
    for x, v in zip((-1.5, -0.5, 0.5, 1.5), m.face_vertices(5), strict=True):
        m.set_position(v, (x, -1.0, 0.0))
    return m


@pytest.mark.parametrize(("faces", "message"), [
    ([TOP, TOP], "face 0 is given twice"),
    ([TOP, 99], "face 99 does not exist"),
    ([TOP, 5], "face 5 is degenerate"),
    ([TOP, "5"], "must hold ids"),
])
def test_several_faces_are_all_checked_before_any_is_extruded(faces, message):
    from livemod.dlfl.extrusion import extrude_faces

    assert_refused(_collinear_bottom(), lambda m: extrude_faces(m, faces, "cubical"), message)
# -- face colours --------------------------------------------------------------------

GREEN = (0.0, 1.0, 0.5)  # face 0 of rainbow_cube


@pytest.mark.parametrize("kind", sorted(KINDS))
def test_every_face_an_extrusion_makes_takes_the_extruded_faces_colour(kind):
    m = rainbow_cube()
    before = set(m.face_ids().tolist())
    if KINDS[kind].step is None:
        extrude_fan(m, 0, kind, 1.0)
    else:
        assert m.face_color(extrude(m, 0, kind, 1.0)) == GREEN
    validate(m)
    made = [f for f in m.face_ids().tolist() if f not in before]
    assert made and all(m.face_color(f) == GREEN for f in made)
    original = rainbow_cube()
    kept = [f for f in before - {0} if m.has_face(f)]
    assert kept and all(m.face_color(f) == original.face_color(f) for f in kept)


@pytest.mark.parametrize("kind", ["cubical", "doo-sabin", "octa"])
def test_an_uncoloured_face_extrudes_uncoloured_into_a_coloured_face_s_old_slot(kind):
    m = rainbow_cube()
    m.delete_edge(m.face_edges(0)[0])  # face 0 (green) merges away: its slot is free
    merged = next(f for f in m.face_ids().tolist() if m.face_size(f) == 6)
    m.set_face_color(merged, None)
    before = set(m.face_ids().tolist())
    end = extrude(m, merged, kind, 1.0)
    validate(m)
    made = [f for f in m.face_ids().tolist() if f not in before]
    assert end in made and all(m.face_color(f) is None for f in made)
