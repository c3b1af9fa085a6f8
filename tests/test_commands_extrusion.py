"""Thesis commands extrude, connectEdges, connectCorners, connectFaces, addHandle."""

from __future__ import annotations

import math

import numpy as np
import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import (
    DLFLError,
    InvalidArgumentError,
    Scene,
    face_size_histogram,
    genus,
    use_scene,
    validate,
)
from livemod.dlfl import extrusion as _extrusion
from livemod.dlfl.commands import addHandle, connectCorners, connectEdges, connectFaces, extrude
from livemod.dlfl.errors import GeometryError, UnknownIdError
from livemod.dlfl.shapes import cube
from tests.meshes import counts, snapshot


def test_star_import_gives_the_commands():
    for name in ("extrude", "connectEdges", "connectCorners", "connectFaces", "addHandle"):
        assert name in dlfl.__all__


def test_thesis_tower(scene):
    face = 0
    for i in range(36):
        t = 2 * math.pi * i / 36
        face = extrude("doo-sabin", face, 0.5 + 0.3 * math.sin(t), 1, 0, 0.9 + 0.1 * math.sin(t))
        assert isinstance(face, int)
    assert counts(scene) == (8 + 4 * 36, 12 + 8 * 36, 6 + 4 * 36)


@pytest.mark.parametrize(("call", "expected"), [
    (lambda: extrude("cubical", 0), (12, 20, 10)),
    (lambda: extrude("cubical", 0, 2, 3), (20, 36, 18)),
    (lambda: extrude("octa", 0, 2, 0, 1, mesh=True), (12, 20, 10)),
    (lambda: extrude("octa", 0, 2, 30), (12, 24, 14)),  # the thesis's rotation second
    (lambda: extrude("octa", 0, num=3), (20, 48, 30)),
    (lambda: extrude("octa", 0, 2.0, 0.0, 1.0, num=3, flag=False), (20, 48, 30)),  # all 7
    (lambda: extrude("octa", 0, mesh=False), (12, 24, 14)),
    (lambda: extrude("dodeca", 0, 2, 2, 0, 1, True), (32, 48, 18)),
    (lambda: extrude("icosa", 0), (20, 48, 30)),
    (lambda: extrude("cuboctahedral", 0), (16, 32, 18)),
    (lambda: extrude("planar-offset", 0, 0.5, 0, 0.2), (12, 20, 10)),
    (lambda: extrude("cubical", 0, dist=2, num=3, rot=10, sf=0.9), (20, 36, 18)),
    (lambda: extrude("octa", 0, flag=True), (12, 20, 10)),
    (lambda: extrude("dodeca", 0, num=2, flag=True), (32, 48, 18)),
])
def test_extrude_types_and_option_orders(scene, call, expected):
    end = call()
    assert isinstance(end, int) and scene.mesh.has_face(end)
    assert counts(scene) == expected


# each kind's positional options and the library arguments they become
MAPPINGS = {
    "doo-sabin": {"distance": 1.25, "segments": 3, "twist": 7.5, "scale": 0.5},
    "dodeca": {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5,
               "hexagonalize": True},
    "icosa": {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5},
    "octa": {"distance": 1.25, "rotation": 3, "scale": 7.5},
    "stellate": {"distance": 1.25},
    "double-stellate": {"distance": 1.25},
    "cubical": {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5},
    "dome": {"distance": 1.25, "rotation": 3, "scale": 7.5},
    "cuboctahedral": {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5},
    "hex-tile": {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5},
    "planar-offset": {"distance": 1.25, "rotation": 3, "thickness": 7.5, "fractional": 0.5},
}
POSITIONAL = (1.25, 3, 7.5, 0.5, True)


@pytest.fixture
def library_calls(monkeypatch):
    """The keyword arguments the command passes to the library, call by call."""
    calls: list[dict] = []

    def record(mesh, face, kind, **arguments):
        calls.append({"kind": kind, **arguments})
        return 0

    monkeypatch.setattr(_extrusion, "extrude", record)
    monkeypatch.setattr(_extrusion, "extrude_fan", record)
    return calls


@pytest.mark.parametrize("kind", MAPPINGS)
def test_each_kinds_positional_options_reach_the_library(scene, library_calls, kind):
    expected = MAPPINGS[kind]
    extrude(kind, 0, *POSITIONAL[:len(expected)])
    assert library_calls == [{"kind": kind, **expected, "max_faces": None}]  # the scene's budget


OCTA_ALL = {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5, "dual_mesh": True}


@pytest.mark.parametrize(("kind", "keywords", "expected"), [
    ("doo-sabin", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5}, MAPPINGS["doo-sabin"]),
    ("dodeca", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5, "flag": True}, MAPPINGS["dodeca"]),
    ("icosa", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5}, MAPPINGS["icosa"]),
    ("octa", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5, "flag": True}, OCTA_ALL),
    ("stellate", {"dist": 1.25}, MAPPINGS["stellate"]),
    ("double-stellate", {"dist": 1.25}, MAPPINGS["double-stellate"]),
    ("cubical", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5}, MAPPINGS["cubical"]),
    ("octa", {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5, "mesh": True},
     OCTA_ALL),
    ("dodeca", {"distance": 1.25, "segments": 3, "twist": 7.5, "scale": 0.5,
                "hexagonalize": True}, MAPPINGS["dodeca"]),
])
def test_topmods_and_the_thesiss_keywords_reach_the_library(scene, library_calls, kind,
                                                            keywords, expected):
    extrude(kind, 0, **keywords)
    assert library_calls == [{"kind": kind, **expected, "max_faces": None}]


def test_octa_reads_the_thesiss_order_distance_rotation_scale(scene):
    """``extrude("octa", f, 1.0, 30, 0.8)`` is a 30 degree turn, not 30 segments."""
    end = extrude("octa", 0, 1.0, 30, 0.8)
    assert counts(scene) == (12, 24, 14)
    library = cube()
    same = _extrusion.extrude(library, 0, "octa", distance=1.0, rotation=30, scale=0.8)
    assert snapshot(scene.mesh) == snapshot(library) and end == same


def test_octa_segments_build_the_same_mesh_every_way(scene):
    from livemod.dlfl.shapes import cube

    ways = [lambda: extrude("octa", 0, 1.5, 20, 0.8, segments=3), lambda: extrude("o", 0, 1.5,
            num=3, rot=20, sf=0.8), lambda: extrude("octa", 0, 1.5, 20, 0.8, num=3, mesh=False)]
    library = cube()
    end = _extrusion.extrude(library, 0, "octa", 1.5, 3, 20, 0.8)
    for way in ways:
        other = Scene()
        other.add(cube())
        with use_scene(other):
            assert way() == end
        assert snapshot(other.mesh) == snapshot(library)
    assert counts(scene) == (8, 12, 6)


@pytest.mark.parametrize("kind", MAPPINGS)
def test_too_many_options_are_refused_for_every_kind(scene, kind):
    count = len(MAPPINGS[kind])
    before = snapshot(scene.mesh)
    with pytest.raises(InvalidArgumentError, match=f"takes at most {count} options .* got {count + 1}"):
        extrude(kind, 0, *([1] * (count + 1)))
    assert snapshot(scene.mesh) == before


@pytest.mark.parametrize(("kind", "keywords", "message"), [
    ("cubical", {"flag": True}, "extrude\\('cubical'\\) has no option 'flag'"),
    ("stellate", {"num": 2}, "extrude\\('stellate'\\) has no option 'num'; options: distance"),
    ("octa", {"twist": 2}, "has no option 'twist'; options: distance, rotation, scale, "
     "segments, mesh$"),
    ("dodeca", {"angle": 30, "distance": 2}, "the GUI shape \\(angle\\) places the rings itself; "
     "it takes no distance"),
    ("cubical", {"l1": 2}, "has no option 'l1'"),
    ("dodeca", {"rotation": 2}, "has no option 'rotation'"),
    ("cubical", {"dist": 1, "distance": 2}, "option 'distance' given twice"),
    ("octa", {"distance": 1, "dist": 2}, "option 'dist' \\(= 'distance'\\) given twice"),
])
def test_unknown_and_repeated_keywords_are_refused(scene, kind, keywords, message):
    before = snapshot(scene.mesh)
    with pytest.raises(InvalidArgumentError, match=message):
        extrude(kind, 0, **keywords)
    assert snapshot(scene.mesh) == before


def test_octa_segments_given_twice(scene):
    with pytest.raises(InvalidArgumentError, match="option 'num' \\(= 'segments'\\) given twice"):
        extrude("octa", 0, 2, 30, segments=3, num=3)
    assert counts(scene) == (8, 12, 6)


@pytest.mark.parametrize(("kind", "expected", "fan"), [
    ("stellate", (9, 16, 9), 4), ("double-stellate", (13, 28, 17), 12), ("dome", (29, 56, 29), 4),
])
def test_fan_types_return_a_face_and_the_fan_by_keyword(scene, kind, expected, fan):
    first_side = scene.mesh.face_edges(0)[0] if kind != "dome" else None
    face = extrude(kind, 0, 1.0)
    assert counts(scene) == expected and scene.mesh.face_size(face) == 3
    if first_side is not None:  # the triangle over the face's first side
        assert first_side in scene.mesh.face_edges(face)
    other = Scene()
    other.add(cube())
    with use_scene(other):
        triangles = extrude(kind, 0, 1.0, fan=True)
    assert snapshot(other.mesh) == snapshot(scene.mesh)
    assert len(triangles) == fan and triangles[0] == face
    assert all(other.mesh.face_size(t) == 3 for t in triangles)
    if kind != "double-stellate":  # one apex: a single fan
        apex = set.intersection(*(set(other.mesh.face_vertices(t)) for t in triangles))
        assert len(apex) == 1


def test_a_fan_face_chains(scene):
    face = extrude("stellate", 0, 1.0)
    end = extrude("cubical", face, 0.5)
    assert counts(scene) == (12, 22, 12) and scene.mesh.face_size(end) == 3
    validate(scene.mesh)


def test_doo_sabin_rotation_is_topmods_twist(scene):
    twisted = extrude("doo-sabin", 0, 1.0, 1, 0.5)
    keyword = Scene()
    keyword.add(cube())
    with use_scene(keyword):
        same = extrude("doo-sabin", 0, distance=1.0, rotation=0.5)
    assert [scene.mesh.position(v).tolist() for v in scene.mesh.face_vertices(twisted)] == \
        [keyword.mesh.position(v).tolist() for v in keyword.mesh.face_vertices(same)]


@pytest.mark.parametrize(("name", "expected"), [
    ("d", (12, 20, 10)),  # TopMod's prefix order: doo-sabin first
    ("doub", (13, 28, 17)),
    ("cub", (12, 20, 10)),  # cubical before cuboctahedral
    ("Octa", (12, 24, 14)),
])
def test_type_prefixes(scene, name, expected):
    extrude(name, 0)
    assert counts(scene) == expected


@pytest.mark.parametrize(("call", "message", "error"), [
    (lambda: extrude("twirl", 0), "valid types: doo-sabin, dodeca, icosa, octa",
     InvalidArgumentError),
    (lambda: extrude("stellate", 0, 1, 2), "at most 1 options", InvalidArgumentError),
    (lambda: extrude("cubical", 0, spin=3), "no option 'spin'", InvalidArgumentError),
    (lambda: extrude("cubical", 0, 2, distance=3), "given twice", InvalidArgumentError),
    (lambda: extrude("cubical", 42), "face 42 does not exist", UnknownIdError),
    (lambda: extrude("cubical", 0, 2, 0), "segments", InvalidArgumentError),
    (lambda: connectFaces(0, 0), "two different faces", InvalidArgumentError),
    (lambda: connectCorners((0, 0), (5, 0)), "no corner at vertex 0", UnknownIdError),
    (lambda: connectCorners((0, 0), (5, 4), 1, -1, "duel"), "'dual'", InvalidArgumentError),
    (lambda: addHandle("spline", (0, 0), (1, 0), 4), "'hermite' or 'bezier'", InvalidArgumentError),
    (lambda: addHandle("bezier", (0, 0), (1, 0), 4, 1, 1, -1, 2), "takes no maxconn, twists",
     InvalidArgumentError),
    (lambda: connectEdges((0, 5), (1, 0)), "is not on face", InvalidArgumentError),
    (lambda: connectEdges(3, (1, 0)), "edgeid, faceid", InvalidArgumentError),
])
def test_bad_arguments_raise_and_change_nothing(scene, call, message, error):
    before = snapshot(scene.mesh)
    with pytest.raises(error, match=message):
        call()
    assert snapshot(scene.mesh) == before


def test_connect_faces_picks_closest_corners(scene):
    assert connectFaces(0, 5) is None
    assert counts(scene) == (8, 16, 8) and genus(scene.mesh) == 1


def test_connect_faces_segments_and_maxconn(scene):
    connectFaces(0, 5, 3)
    assert counts(scene) == (16, 32, 16)
    other = Scene()
    other.add(cube())
    with use_scene(other):
        connectFaces(0, 5, 3, 1)
    assert counts(other) == (16, 24, 12)


def test_connect_corners_dual(scene):
    connectCorners((0, 0), (5, 4), 1, -1, "dual")
    assert counts(scene) == (8, 20, 12)
    assert face_size_histogram(scene.mesh) == {3: 8, 4: 4}


def test_add_handle_hermite_and_bezier(scene):
    addHandle("hermite", (0, 0), (1, 0), 10)
    assert counts(scene) == (44, 88, 44) and genus(scene.mesh) == 1
    other = Scene()
    other.add(cube())
    with use_scene(other):
        addHandle("bezier", (0, 0), (1, 0), 10, 5, 5)
    assert counts(other) == (44, 88, 44)


def test_connect_edges(scene):
    m = scene.mesh
    e1, e2 = m.face_edges(0)[0], m.face_edges(5)[0]
    connectEdges((e1, 0), (e2, 5))
    assert counts(scene) == (8, 14, 6)


def test_each_command_is_one_step(scene, run):
    labels: list[str] = []
    run.step_hook = labels.append
    extrude("dodeca", 0)
    connectFaces(1, 3)
    assert labels == ["extrude", "connectFaces"]


def test_extrude_failing_in_a_later_segment_changes_nothing(scene):
    before = snapshot(scene.mesh)
    with pytest.raises(GeometryError, match="dodeca extrusion of face 0 cannot be built: "
                       "a point it makes on the way overflows"):
        extrude("dodeca", 0, 1e308, 2)
    assert snapshot(scene.mesh) == before


@pytest.mark.parametrize("pair", [(None, 0), (0, None), (1.5, 0), ("0", 0)])
def test_connect_edges_refuses_a_half_edge_that_is_not_two_ids(scene, pair):
    before = snapshot(scene.mesh)
    with pytest.raises(InvalidArgumentError, match="must hold ids"):
        connectEdges(pair, (1, 1))
    assert snapshot(scene.mesh) == before


# -- the kinds' registry: every kind carries its script options ----------------------

# the appendix of Tett (2007): extrude's types and their options, in its order
THESIS_OPTIONS = {
    "doo-sabin": ("distance", "segments", "rotation", "scale"),
    "dodeca": ("distance", "segments", "twist", "scale", "hexagonalize"),
    "icosa": ("distance", "segments", "rotation", "scale"),
    "octa": ("distance", "rotation", "scale"),
    "stellate": ("distance",),
    "double-stellate": ("distance",),
    "cubical": ("distance", "segments", "rotation", "scale"),
}


def test_topmods_seven_types_come_first_with_the_thesiss_options():
    assert list(_extrusion.KINDS)[:7] == list(THESIS_OPTIONS)
    for kind, options in THESIS_OPTIONS.items():
        assert _extrusion.KINDS[kind].options == options


def _library_parameter(kind: str, option: str) -> str:
    return _extrusion.KINDS[kind].library_names.get(option, option)


@pytest.mark.parametrize("kind", list(_extrusion.KINDS))
def test_every_script_option_of_every_kind_reaches_a_library_argument(kind):
    import inspect

    from livemod.dlfl.commands.extrusion import SHAPE_KEYWORDS, kind_keywords

    spec = _extrusion.KINDS[kind]
    parameters = set(inspect.signature(_extrusion.extrude).parameters)
    names = kind_keywords(kind)
    assert len(set(names)) == len(names)
    for option in names:
        if option in SHAPE_KEYWORDS:
            assert spec.shape is not None and hasattr(spec.shape, option)
        else:
            assert _library_parameter(kind, option) in parameters, option
    for topmod_name, option in spec.topmod_names.items():
        assert option in names, (topmod_name, option)
    for alias in spec.aliases:
        assert _extrusion.resolve_kind(alias) == kind


def test_every_library_option_is_some_kinds_script_option():
    import inspect

    from livemod.dlfl.commands.extrusion import kind_keywords

    reached = {_library_parameter(kind, option) for kind in _extrusion.KINDS
               for option in kind_keywords(kind)}
    parameters = set(inspect.signature(_extrusion.extrude).parameters)
    assert parameters - reached == {"mesh", "face", "kind", "max_faces", "shape"}


@pytest.mark.parametrize("kind", list(THESIS_OPTIONS))
def test_every_prefix_of_a_topmod_type_is_its_first_match_in_topmods_order(kind):
    from livemod.dlfl.commands.extrusion import _kind

    order = list(THESIS_OPTIONS)
    for end in range(1, len(kind) + 1):
        prefix = kind[:end]
        assert _kind(prefix) == next(k for k in order if k.startswith(prefix)), prefix


@pytest.mark.parametrize("kind", list(_extrusion.KINDS))
def test_every_kind_runs_with_each_option_by_keyword(scene, kind):
    from livemod.dlfl.commands.extrusion import kind_keywords

    values = {"distance": 0.5, "segments": 1, "rotation": 10.0, "twist": 10.0, "scale": 0.9,
              "hexagonalize": False, "mesh": True, "thickness": 0.2, "fractional": True,
              "angle": 45.0, "l1": 0.5, "l2": 0.8, "l3": 0.8}
    keywords = {name: values[name] for name in kind_keywords(kind)
                if name not in ("angle", "l1", "l2", "l3")}
    face = extrude(kind, 0, **keywords)
    assert scene.mesh.has_face(face)
    validate(scene.mesh)


@pytest.mark.parametrize(("kind", "keywords", "shape"), [
    ("dodeca", {"angle": 35}, (35.0, 0.5, 1.0, 1.0)),
    ("dodeca", {"l1": 0.6, "l3": 0.9, "segments": 2, "hexagonalize": True}, (40.0, 0.6, 1.0, 0.9)),
    ("icosa", {"l2": 0.9}, (50.0, 0.5, 0.9, 0.8)),
])
def test_the_gui_shape_keywords_fill_in_the_guis_defaults(scene, kind, keywords, shape):
    end = extrude(kind, 0, **keywords)
    library = cube()
    rest = {k: v for k, v in keywords.items() if k in ("segments", "hexagonalize")}
    same = _extrusion.extrude(library, 0, kind, shape=_extrusion.Shape(*shape), **rest)
    assert end == same and snapshot(scene.mesh) == snapshot(library)


def test_a_list_of_faces_extrudes_each_and_returns_their_end_faces(scene):
    ends = extrude("cubical", [0, 5], 1.0)
    assert len(ends) == 2 and all(scene.mesh.face_size(f) == 4 for f in ends)
    assert counts(scene) == (16, 28, 14)
    fans = extrude("stellate", ends, 0.5, fan=True)
    assert [len(fan) for fan in fans] == [4, 4] and counts(scene) == (18, 36, 20)
    validate(scene.mesh)


@pytest.mark.parametrize(("call", "message"), [
    (lambda: extrude("cubical", "0"), "faceid must be a face id or a list of face ids"),
    (lambda: extrude("cubical", [0, 0]), "face 0 is given twice"),
    (lambda: extrude("cubical", 0, fan=True), "ends in a face, not a fan"),
    (lambda: extrude("stellate", 0, fan="yes"), "fan"),
])
def test_bad_face_lists_and_fan_requests_change_nothing(scene, call, message):
    before = snapshot(scene.mesh)
    with pytest.raises(DLFLError, match=message):
        call()
    assert snapshot(scene.mesh) == before


def test_connect_faces_takes_topmods_pinch_profile(scene):
    connectFaces(0, 5, 4, pinch=0.5)
    assert counts(scene) == (20, 40, 20) and genus(scene.mesh) == 1
    middle = [p for p in scene.mesh.positions_view() if abs(p[1]) < 1e-12]
    assert len(middle) == 4 and np.allclose(np.abs(middle), [0.5, 0.0, 0.5])
    other = Scene()
    other.add(cube())
    with use_scene(other):
        connectFaces(0, 5, 4, pinch=0.5, pinchCenter=0.25, bubble=2.0)
    library = cube()
    from livemod.dlfl.connect import connect_faces_closest

    connect_faces_closest(library, 0, 5, 4, pinch=0.5, pinch_center=0.25, bubble=2.0)
    assert snapshot(other.mesh) == snapshot(library) != snapshot(scene.mesh)


def test_connect_corners_takes_the_pinch_but_not_on_a_dual_band(scene):
    connectCorners((0, 0), (5, 4), 4, pinch=0.5)
    assert counts(scene) == (20, 40, 20)
    other = Scene()
    other.add(cube())
    with use_scene(other):
        before = snapshot(other.mesh)
        with pytest.raises(InvalidArgumentError,
                           match="a 'dual' \\(triangle\\) band takes no pinch"):
            connectCorners((0, 0), (5, 4), 4, -1, "dual", bubble=2.0)
        assert snapshot(other.mesh) == before


def test_add_handle_takes_the_pinch_profile_of_topmods_gui(scene):
    """Add Handle SI's pinch spin boxes: the Hermite rings scale as a tube's do."""
    addHandle("hermite", (0, 0), (1, 0), 4, 5, 5, pinch=0.5, pinchCenter=0.25, bubble=2.0)
    assert counts(scene) == (20, 40, 20) and genus(scene.mesh) == 1
    validate(scene.mesh)
    from livemod.dlfl.connect import hermite_handle

    plain, pinched = cube(), cube()
    hermite_handle(plain, plain.corner_at(0, 0), plain.corner_at(1, 0), 4, 5, 5)
    hermite_handle(pinched, pinched.corner_at(0, 0), pinched.corner_at(1, 0), 4, 5, 5,
                   pinch=0.5, pinch_center=0.25, bubble=2.0)
    assert snapshot(scene.mesh) == snapshot(pinched) != snapshot(plain)


@pytest.mark.parametrize(("call", "error", "message"), [
    (lambda: addHandle("bezier", (0, 0), (1, 0), 4, pinch=0.5), InvalidArgumentError,
     "a bezier handle takes no maxconn, twists, pinch"),
    (lambda: addHandle("hermite", (0, 0), (1, 0), 4, pinch=np.array([1.0, 2.0])),
     InvalidArgumentError, "pinch must be a"),
    (lambda: connectFaces(0, 5, 4, pinchCenter=float("nan")), InvalidArgumentError,
     "pinchCenter"),
    (lambda: connectCorners((0, 0), (5, 4), 4, -1, "dual", pinch="1"), InvalidArgumentError,
     "pinch must be a"),
    (lambda: connectFaces(0, 5, 4, pinchCenter=1.0), DLFLError, "pinch_center must lie"),
])
def test_bad_pinch_profiles_are_refused_by_type(scene, call, error, message):
    before = snapshot(scene.mesh)
    with pytest.raises(error, match=message):
        call()
    assert snapshot(scene.mesh) == before
