"""Thesis commands extrude, connectEdges, connectCorners, connectFaces, addHandle."""

from __future__ import annotations

import math

import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import Scene, face_size_histogram, genus, use_scene
from livemod.dlfl import extrusion as _extrusion
from livemod.dlfl.commands import addHandle, connectCorners, connectEdges, connectFaces, extrude
from livemod.dlfl.errors import GeometryError, InvalidArgumentError, UnknownIdError
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
    (lambda: extrude("octa", 0, 2, 1, 0, 1, True), (12, 20, 10)),
    (lambda: extrude("octa", 0, 2, 3), (20, 48, 30)),  # TopMod's num second
    (lambda: extrude("octa", 0, num=3), (20, 48, 30)),
    (lambda: extrude("octa", 0, 2.0, 3, 0.0, 1.0, False), (20, 48, 30)),  # all 7 arguments
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
    "octa": {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5, "dual_mesh": True},
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


@pytest.mark.parametrize(("kind", "keywords"), [
    ("doo-sabin", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5}),
    ("dodeca", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5, "flag": True}),
    ("icosa", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5}),
    ("octa", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5, "flag": True}),
    ("stellate", {"dist": 1.25}),
    ("double-stellate", {"dist": 1.25}),
    ("cubical", {"dist": 1.25, "num": 3, "rot": 7.5, "sf": 0.5}),
    ("octa", {"distance": 1.25, "segments": 3, "rotation": 7.5, "scale": 0.5, "mesh": True}),
    ("dodeca", {"distance": 1.25, "segments": 3, "twist": 7.5, "scale": 0.5,
                "hexagonalize": True}),
])
def test_topmods_and_the_thesiss_keywords_match_the_positions(scene, library_calls, kind,
                                                              keywords):
    extrude(kind, 0, **keywords)
    assert library_calls == [{"kind": kind, **MAPPINGS[kind], "max_faces": None}]


def test_octa_segments_build_the_same_mesh_every_way(scene):
    from livemod.dlfl.shapes import cube

    ways = [lambda: extrude("octa", 0, 1.5, 3, 20, 0.8), lambda: extrude("o", 0, 1.5, num=3,
            rot=20, sf=0.8), lambda: extrude("octa", 0, 1.5, 3, 20, 0.8, False)]
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
    ("octa", {"twist": 2}, "has no option 'twist'; options: distance, segments, rotation"),
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
        extrude("octa", 0, 2, 3, num=3)
    assert counts(scene) == (8, 12, 6)


@pytest.mark.parametrize(("kind", "expected", "fan"), [
    ("stellate", (9, 16, 9), 4), ("double-stellate", (13, 28, 17), 12), ("dome", (29, 56, 29), 4),
])
def test_fan_types_return_the_triangles(scene, kind, expected, fan):
    triangles = extrude(kind, 0, 1.0)
    assert counts(scene) == expected
    assert len(triangles) == fan and all(scene.mesh.face_size(t) == 3 for t in triangles)


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
    (lambda: addHandle("bezier", (0, 0), (1, 0), 4, 1, 1, -1, 2), "no maxconn or twists",
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


def test_each_command_is_one_step(scene):
    labels: list[str] = []
    scene.step_hook = labels.append
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
