"""Conformance of the thesis commands to the appendix of Tett (2007) and API.md.

Names, argument order and defaults, result forms, argument errors that name the
argument and keep the mesh, and the thesis's example scripts run end to end
(Python 3 forms).
"""

from __future__ import annotations

import inspect
import time
from collections.abc import Iterator
from math import cos, pi, sin
from pathlib import Path
from typing import Any

import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import (
    RunContext,
    Scene,
    face_size_histogram,
    genus,
    use_run,
    use_scene,
    validate,
)
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.shapes import cube
from tests.meshes import counts, snapshot

# every command the appendix (and API.md) lists, with its optional arguments'
# defaults in the documented order ("*" marks a variadic tail livemod parses)
DOCUMENTED: dict[str, tuple[tuple[str, Any], ...]] = {
    "createVertex": (("position", (0.0, 0.0, 0.0)),),
    "removeVertex": (("vertexid", inspect.Parameter.empty),),
    "insertEdge": (("c1", inspect.Parameter.empty), ("c2", inspect.Parameter.empty),
                   ("check", True)),
    "deleteEdge": (("edgeid", inspect.Parameter.empty), ("cleanup", True)),
    "subdivideEdge": (("args", "*"),),
    "collapseEdge": (("edgeid", inspect.Parameter.empty), ("cleanup", True)),
    "createFace": (("points", inspect.Parameter.empty), ("bothNew", False)),
    "faces": (("selected", False),), "edges": (("selected", False),),
    "verts": (("selected", False),), "corners": (("selected", False),),
    "walk": (("faceid", inspect.Parameter.empty),),
    "cornerWalk": (("faceid", inspect.Parameter.empty),),
    "saveCorner": (("c", inspect.Parameter.empty),),
    "restoreCorner": (("cornerid", inspect.Parameter.empty),),
    "load": (("filename", inspect.Parameter.empty),),
    "save": (("filename", inspect.Parameter.empty),),
    "kill": (("objectid", inspect.Parameter.empty),),
    "switch": (("objectid", inspect.Parameter.empty),),
    "printObject": (),
    "vertexInfo": (("vertexid", inspect.Parameter.empty),),
    "edgeInfo": (("edgeid", inspect.Parameter.empty),),
    "faceInfo": (("faceid", inspect.Parameter.empty),),
    "cornerInfo": (("c", inspect.Parameter.empty),),
    "centroid": (("vertexids", None),),
    "subdivideFace": (("faceid", inspect.Parameter.empty), ("usequads", True)),
    "subdivideFaces": (("faceids", None), ("usequads", True)),
    "dual": (("accurate", False),),
    "connectEdges": (("e1", inspect.Parameter.empty), ("e2", inspect.Parameter.empty),
                     ("loopCheck", False)),
    "connectCorners": (("c1", inspect.Parameter.empty), ("c2", inspect.Parameter.empty),
                       ("numsegs", 1), ("maxconn", -1), ("dual", False)),
    "connectFaces": (("f1", inspect.Parameter.empty), ("f2", inspect.Parameter.empty),
                     ("numsegs", 1), ("maxconn", -1)),
    "addHandle": (("interp", inspect.Parameter.empty), ("c1", inspect.Parameter.empty),
                  ("c2", inspect.Parameter.empty), ("numsegs", inspect.Parameter.empty),
                  ("w1", 25.0), ("w2", 25.0), ("maxconn", -1), ("twists", 0)),
    "rind": (("facelist", inspect.Parameter.empty), ("useScaling", inspect.Parameter.empty),
             ("percent", inspect.Parameter.empty), ("uniform", True)),
    "wireframe": (("thickness", 0.1), ("split", True)),
    "column": (("thickness", inspect.Parameter.empty), ("segments", inspect.Parameter.empty)),
    "step": (("label", "step"),),
}
# parsed from *args (x, y, z or a tuple) or keyed by type/scheme: checked by calls
VARIADIC = ("next", "prev", "getCorner", "vertexEdges", "translate", "scale", "move",
            "extrude", "subdivide")


@pytest.fixture()
def cube_scene(topmod_samples: Path) -> Iterator[Scene]:
    """TopMod's cube (edge 2, 8/12/6) as the current object; files read from a folder
    of stand-ins for TopMod's samples."""
    bound = Scene()
    bound.add(cube(), "cube")
    with use_scene(bound), use_run(RunContext(directory=str(topmod_samples))):
        yield bound


@pytest.fixture()
def empty_scene(topmod_samples: Path) -> Iterator[Scene]:
    """A scene with no object, reading files from a folder of stand-ins for TopMod's
    samples."""
    bound = Scene()
    with use_scene(bound), use_run(RunContext(directory=str(topmod_samples))):
        yield bound


def test_every_documented_command_is_in_the_star_import():
    names: dict[str, Any] = {}
    exec("from livemod.dlfl import *", names)  # noqa: S102  (what a script does)
    missing = [n for n in (*DOCUMENTED, *VARIADIC, "DLFLError") if n not in names]
    assert missing == []
    assert issubclass(names["DLFLError"], ValueError)


@pytest.mark.parametrize("name", sorted(DOCUMENTED))
def test_positional_order_and_defaults_match_the_appendix(name):
    """The positional parameters are the appendix's (livemod's additions, TopMod's
    GUI options among them, are keyword-only)."""
    params = [p for p in inspect.signature(getattr(dlfl, name)).parameters.values()
              if p.kind is not p.KEYWORD_ONLY]
    got = tuple((p.name, "*" if p.kind is p.VAR_POSITIONAL else p.default) for p in params)
    assert got == DOCUMENTED[name]


def test_core_results_have_the_documented_forms(empty_scene):
    (corner, obj) = dlfl.createVertex((0, 0, 0))
    assert (corner, obj) == ((0, 0), 0)
    b, _ = dlfl.createVertex((1, 0, 0))
    result = dlfl.insertEdge(corner, b)
    assert len(result) == 5 and result[0] == 0
    assert all(isinstance(c, tuple) and len(c) == 2 for c in result[1:])
    assert dlfl.faces() == (0,) and dlfl.verts() == (0, 1) and dlfl.edges() == (0,)
    assert isinstance(dlfl.corners(), tuple)
    assert dlfl.deleteEdge(0) == [-1]  # two point-spheres: nothing left (TopMod's [-1])


def test_edge_results_on_the_cube(cube_scene):
    assert dlfl.walk(0) == ([0, 1, 2, 3], [0, 1, 2, 3])
    assert dlfl.cornerWalk(0) == [(0, 0), (0, 1), (0, 2), (0, 3)]
    assert dlfl.subdivideEdge(0) == [8]
    assert dlfl.subdivideEdge(3, 1) == [9, 10]
    assert dlfl.collapseEdge(0) == 0
    assert counts(cube_scene) == (10, 14, 6)
    assert dlfl.createFace([(0, 0, 5), (1, 0, 5), (0, 1, 5)]) == (6, 7)


def test_delete_edge_merge_and_split_results(cube_scene):
    assert dlfl.deleteEdge(0) == [0]  # two faces merged
    edge, *_ = dlfl.insertEdge((0, 0), (0, 2))  # splits face 0
    assert dlfl.deleteEdge(edge) == [0]


def test_object_results(cube_scene, tmp_path):
    assert dlfl.save(str(tmp_path / "c.obj")) is True
    assert dlfl.load(str(tmp_path / "c.obj")) == 1 and cube_scene.current == 1
    assert dlfl.switch(0) == 0
    assert dlfl.kill(1) is None and sorted(cube_scene.objects) == [0]


def test_info_keys_match_the_thesis(cube_scene):
    assert set(dlfl.vertexInfo(0)) == {"id", "type", "coords", "valence"}
    assert set(dlfl.edgeInfo(0)) == {"id", "type", "midpoint", "normal", "cornerA",
                                     "cornerB", "cornerC", "cornerD", "length"}
    assert set(dlfl.faceInfo(0)) == {"id", "type", "centroid", "normal", "size", "color"}
    assert {"face", "vertex", "edge", "type"} <= set(dlfl.cornerInfo((0, 0)))
    assert dlfl.centroid([0, 1]) == (1.0, 1.0, 0.0)


@pytest.mark.parametrize(("call", "message"), [
    (lambda d: d.addHandle("hermite", (0, 0), (1, 4), 3, 25, 25, -1, "x"),
     "^twists must be a whole number of turns, got 'x'$"),
    (lambda d: d.addHandle("hermite", (0, 0), (1, 4), 3, 25, 25, -1, None),
     "^twists must be a whole number of turns, got None$"),
    (lambda d: d.addHandle("hermite", (0, 0), (1, 4), 3, 25, 25, -1, 1.5),
     "^twists must be a whole number of turns, got 1.5$"),
    (lambda d: d.addHandle("hermite", (0, 0), (1, 4), 0), "^numsegs must be an integer >= 1, got 0$"),
    (lambda d: d.addHandle("hermite", (0, 0), (1, 4), 3, "x"), "^w1 must be a number, got 'x'$"),
    (lambda d: d.addHandle("hermite", (0, 0), (1, 4), 3, 25, 25, 1.5),
     r"^maxconn must be an integer \(-1 for all\), got 1.5$"),
    (lambda d: d.addHandle("hermite", (0, 0), (0, 1), 3),
     "^addHandle needs c1 and c2 in two different faces, both are in face 0$"),
    (lambda d: d.connectCorners((0, 0), (1, 4), "x"), "^numsegs must be an integer >= 1, got 'x'$"),
    (lambda d: d.connectCorners((0, 0), (1, 4), 1, None),
     r"^maxconn must be an integer \(-1 for all\), got None$"),
    (lambda d: d.connectCorners((0, 0), (0, 1)),
     "^connectCorners needs c1 and c2 in two different faces, both are in face 0$"),
    (lambda d: d.connectFaces(True, 1), "^f1 must be a face id \\(an integer\\), got True$"),
    (lambda d: d.connectFaces(0, "x"), "^f2 must be a face id \\(an integer\\), got 'x'$"),
    (lambda d: d.connectFaces(0, 0),
     "^connectFaces needs two different faces, f1 and f2 are both face 0$"),
    (lambda d: d.connectFaces(0, 1, 0), "^numsegs must be an integer >= 1, got 0$"),
    (lambda d: d.connectEdges((0, 0), (0, 0)),
     "^connectEdges needs two different edges, e1 and e2 are both on edge 0$"),
    (lambda d: d.extrude("cubical", "x"),
     "^faceid must be a face id or a list of face ids, got 'x'$"),
    (lambda d: d.extrude("cubical", True),
     "^faceid must be a face id or a list of face ids, got True$"),
    (lambda d: d.getCorner(0, True), "^faceid must be a face id \\(an integer\\), got True$"),
    (lambda d: d.getCorner(0, "x"), "^faceid must be a face id \\(an integer\\), got 'x'$"),
    (lambda d: d.getCorner(0, 2), "^edge 0 does not border face 2$"),
    (lambda d: d.insertEdge((0, 0), (0, 0)),
     "^insertEdge needs two different corners, c1 and c2 are both \\(0, 0\\)$"),
    (lambda d: d.createFace("x"), "^points must be a list of \\(x, y, z\\) points, got 'x'$"),
    (lambda d: d.createFace(None), "^points must be a list of \\(x, y, z\\) points, got None$"),
])
def test_bad_arguments_are_named_and_the_mesh_kept(cube_scene, call, message):
    before = snapshot(cube_scene.mesh)
    with pytest.raises(InvalidArgumentError, match=message):
        call(dlfl)
    assert snapshot(cube_scene.mesh) == before


def test_whole_float_twists_are_turns(cube_scene):
    dlfl.addHandle("hermite", (0, 0), (1, 4), 3, 25, 25, -1, 1.0)
    assert counts(cube_scene) == (16, 32, 16)
    validate(cube_scene.mesh)


@pytest.mark.parametrize("empty", [[], ()])
def test_subdivide_faces_of_nothing_keeps_every_id(cube_scene, empty):
    before = snapshot(cube_scene.mesh)
    dlfl.subdivideFaces(empty)
    dlfl.subdivideFaces()  # nothing selected
    assert snapshot(cube_scene.mesh) == before


def test_root4_takes_the_thesis_option_name_a(cube_scene):
    dlfl.subdivide("root4", a=0.1, twist=0.2)
    by_a = snapshot(cube_scene.mesh)
    with use_scene(Scene()) as other:
        other.add(cube(), "cube")
        dlfl.subdivide("root4", weight=0.1, twist=0.2)
        assert snapshot(other.mesh)[:-1] == by_a[:-1]
    with pytest.raises(InvalidArgumentError, match=r"^subdivide\('root4'\): option 'a' \(= 'weight'\) given twice$"):
        dlfl.subdivide("root4", 0.1, a=0.1)


# -- the thesis's example scripts, Python 3 --------------------------------------

def test_figure_20_loop_over_faces(empty_scene, capsys):
    dlfl.load("cube.obj")
    for f in dlfl.faces():
        print(f)
    assert capsys.readouterr().out == "0\n1\n2\n3\n4\n5\n"


def test_figure_23_string_identifiers(empty_scene):
    dlfl.load("cube.obj")
    dlfl.extrude("doo-sabin", dlfl.faces()[0])
    dlfl.subdivide("simplest")
    validate(empty_scene.mesh)
    assert counts(empty_scene) == (20, 40, 22)


def test_figure_24_triangle_from_core_operators(empty_scene, capsys):
    a, _ = dlfl.createVertex((0, 0, 0))
    b, _ = dlfl.createVertex((1, 0, 0))
    c, _ = dlfl.createVertex((0, 1, 0))
    _, a, b, _, _ = dlfl.insertEdge(a, b)
    _, b, c, _, _ = dlfl.insertEdge(b, c)
    dlfl.insertEdge(c, a)
    dlfl.printObject()
    validate(empty_scene.mesh)
    assert capsys.readouterr().out == ("Number of vertices : 3\nNumber of faces : 2\n"
                                       "Number of edges : 3\nNumber of materials : 1\nGenus : 0\n")


def _doo_sabin_points(points: list[tuple[float, float, float]]) -> list[tuple[float, ...]]:
    n = len(points)
    out = []
    for i in range(n):
        w = [0.25 + 5.0 / (4 * n) if i == j else (3 + 2 * cos(2 * pi * (i - j) / n)) / (4 * n)
             for j in range(n)]
        out.append(tuple(sum(w[j] * points[j][k] for j in range(n)) for k in range(3)))
    return out


def _back(edge: int, front: int) -> int:
    # face ids change as faces are joined: the back is the side not on the front
    info = dlfl.edgeInfo(edge)
    return info["cornerA"][0] if info["cornerA"][0] != front else info["cornerB"][0]


def test_figure_25_doo_sabin_with_core_commands(empty_scene):
    dlfl.load("cube.obj")
    polygon_edge, front_of = {}, {}
    for f in dlfl.faces():
        ring = dlfl.cornerWalk(f)
        front, _ = dlfl.createFace(_doo_sabin_points([dlfl.vertexInfo(v)["coords"] for _, v in ring]))
        for corner, e in zip(ring, dlfl.walk(front)[1], strict=True):
            polygon_edge[corner], front_of[corner] = e, front
    old = [e for e in dlfl.edges() if e not in polygon_edge.values()]
    sides = [(dlfl.edgeInfo(e)["cornerA"], dlfl.edgeInfo(e)["cornerB"]) for e in old]
    for e in old:
        dlfl.deleteEdge(e)
    for a, b in sides:
        ea, eb = polygon_edge[a], polygon_edge[b]
        dlfl.connectEdges((ea, _back(ea, front_of[a])), (eb, _back(eb, front_of[b])))
    validate(empty_scene.mesh)
    assert counts(empty_scene) == (24, 48, 26)  # subdivide("doo-sabin") on the cube
    assert face_size_histogram(empty_scene.mesh) == {3: 8, 4: 18}


def test_figure_26_sine_extrusions(empty_scene):
    dlfl.load("cube.obj")
    face = dlfl.faces()[0]
    for i in range(36):
        t = 2 * pi * i / 36
        face = dlfl.extrude("doo-sabin", face, 0.5 + 0.3 * sin(t), 1, 0, 0.9 + 0.1 * sin(t))
    dlfl.dual()
    dlfl.dual()
    dlfl.subdivide("doo-sabin")
    validate(empty_scene.mesh)
    assert counts(empty_scene) == (600, 1200, 602) and genus(empty_scene.mesh) == 0


def test_figure_27_time_modulated_extrusions_with_wireframe(empty_scene):
    dlfl.load("cube.obj")
    face = dlfl.faces()[0]
    for _ in range(5):
        s = sin(time.time())
        face = dlfl.extrude("cubical", face, 0.5 + 0.3 * s, 1, 0, 0.9 + 0.05 * s)
    dlfl.wireframe(0.1)
    validate(empty_scene.mesh)
    assert counts(empty_scene) == (208, 520, 264)  # the counts do not depend on the time


def test_figure_30_rind_soccerball(empty_scene):
    dlfl.load("soccerball.obj")
    dlfl.dual()
    dlfl.subdivide("checker")
    dlfl.dual()  # TopMod's dual checkerboard
    punch = [f for f in dlfl.faces() if dlfl.faceInfo(f)["size"] == 4
             and any(dlfl.vertexInfo(v)["valence"] == 3 for v in dlfl.walk(f)[0])]
    assert len(punch) == 180
    dlfl.rind(punch, False, 0.05)
    validate(empty_scene.mesh)
    assert genus(empty_scene.mesh) == 59  # 60 triangle-shaped holes


def test_figure_31_wireframe_soccerball_grid(empty_scene, tmp_path):
    for i in range(3):
        dlfl.load("soccerball.obj")
        dlfl.wireframe(0.02 + 0.01 * i)
        dlfl.translate(i * 4.0, 0, 0, True)
        assert dlfl.save(str(tmp_path / f"ball{i:02d}.obj")) is True
        validate(empty_scene.mesh)
    assert len(empty_scene.objects) == 3 and counts(empty_scene) == (360, 900, 480)
