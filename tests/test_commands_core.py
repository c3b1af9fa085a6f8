"""Tests of livemod.dlfl.commands.core: the thesis's core commands on a scene."""

from __future__ import annotations

import builtins

import numpy as np
import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import DLFLError, Scene, genus, use_scene
from livemod.dlfl.commands.core import (
    centroid,
    collapseEdge,
    cornerInfo,
    corners,
    cornerWalk,
    createFace,
    createVertex,
    deleteEdge,
    edgeInfo,
    edges,
    faceInfo,
    faces,
    freezeTrans,
    getCorner,
    insertEdge,
    kill,
    load,
    move,
    next,  # noqa: A004  (the thesis's name shadows the built-in on purpose)
    prev,
    printObject,
    removeVertex,
    restoreCorner,
    save,
    saveCorner,
    scale,
    spliceCorners,
    step,
    subdivideEdge,
    switch,
    translate,
    trisectEdge,
    vertexEdges,
    vertexInfo,
    verts,
    walk,
)
from livemod.dlfl.errors import GeometryError, InvalidArgumentError, UnknownIdError
from tests.meshes import counts, cube, snapshot


@pytest.fixture()
def scene():
    with use_scene(Scene()) as bound:
        yield bound


@pytest.fixture()
def cube_scene(scene):
    scene.add(cube(), "cube")
    return scene


def test_thesis_figure_24_triangle(scene):
    (c1, obj), (c2, _), (c3, _) = (createVertex(p) for p in ((0, 0, 0), (1, 0, 0), (0, 1, 0)))
    assert obj == 0 and counts(scene) == (3, 0, 3)
    _, a, b, _, _ = insertEdge(c1, c2)
    assert counts(scene) == (3, 1, 2)
    _, p3, _, _, _ = insertEdge(c3, b)
    assert counts(scene) == (3, 2, 1)
    insertEdge(p3, (p3[0], c1[1]))
    assert counts(scene) == (3, 3, 2)
    assert sorted(len(walk(f)[0]) for f in faces()) == [3, 3]


def test_thesis_figure_20_face_loop(cube_scene, capsys):
    for f in faces():
        print(f)
    assert capsys.readouterr().out.split() == [str(f) for f in range(6)]


def test_star_import_gives_the_commands():
    names: dict[str, object] = {}
    exec("from livemod.dlfl import *", names)
    for name in ("createVertex", "insertEdge", "faces", "walk", "next", "printObject", "step"):
        assert name in names
    assert "Mesh" not in names and "np" not in names
    assert set(dlfl.commands.core.__all__) <= set(names)


def test_star_import_gives_the_error_commands_raise_so_scripts_can_catch_it():
    names: dict[str, object] = {}
    with use_scene(Scene()):
        exec("from livemod.dlfl import *\n"
             "try:\n"
             "    deleteEdge(99)\n"
             "except DLFLError as exc:\n"
             "    caught = str(exc)\n", names)
    assert names["DLFLError"] is dlfl.DLFLError
    assert "99" in str(names["caught"])


def test_a_script_can_catch_a_deleted_id_by_its_kind(cube_scene):
    names: dict[str, object] = {}
    exec("from livemod.dlfl import *\n"
         "deleteEdge(0)\n"
         "try:\n"
         "    deleteEdge(0)\n"
         "except UnknownIdError as exc:\n"
         "    caught = exc\n"
         "try:\n"
         "    deleteEdge('zero')\n"
         "except InvalidArgumentError as exc:\n"
         "    refused = exc\n", names)
    assert str(names["caught"]) == "edge 0 was deleted"
    assert isinstance(names["caught"], LookupError) and isinstance(names["caught"], DLFLError)
    assert str(names["refused"]) == "expected an edge id (an integer), got 'zero'"
    assert isinstance(names["refused"], ValueError)
    assert {"UnknownIdError", "InvalidArgumentError", "NonManifoldError", "GeometryError",
            "BudgetExceededError", "FileFormatError"} <= set(dlfl.__all__)


def test_insert_edge_returns_its_corners_in_edge_info_order(cube_scene):
    e, ca, cb, cc, cd = insertEdge((0, 0), (0, 2))
    assert counts(cube_scene) == (8, 13, 7)
    assert ca[1] == 0 and cb[1] == 2
    assert cc == next(ca) and cd == next(cb)
    assert cc[1] == 2 and cd[1] == 0
    info = edgeInfo(e)
    assert [info[k] for k in ("cornerA", "cornerB", "cornerC", "cornerD")] == [ca, cb, cc, cd]
    assert info["length"] == pytest.approx(np.sqrt(2))
    np.testing.assert_allclose(info["midpoint"], [0.5, 0.5, 0.0])


def test_ambiguous_corner_names_the_corner_ids(cube_scene):
    insertEdge((0, 0), (1, 4))  # top to bottom: the merged face visits 0 and 4 twice
    (face,) = {f for f in faces() if 0 in walk(f)[0] and walk(f)[0].count(0) == 2}
    ids = [c for c in cube_scene.mesh.face_corners(face) if cube_scene.mesh.corner_vertex(c) == 0]
    with pytest.raises(InvalidArgumentError, match=f"ambiguous.*{ids[0]}, {ids[1]}"):
        insertEdge((face, 0), (2, 1))
    # a corner a command returned carries its id and stays usable
    first = [c for c in cornerWalk(face) if c[1] == 0][0]
    assert next(first)[0] == face


def test_remove_vertex(scene):
    (corner, _) = createVertex((1, 2, 3))
    removeVertex(corner[1])
    assert counts(scene) == (0, 0, 0)


def test_remove_vertex_takes_the_corner_create_vertex_returns(cube_scene):
    # on the cube the point-spheres' face and vertex ids differ: (6, 8), (7, 9)
    (first, _), (second, _) = createVertex((5, 0, 0)), createVertex((7, 0, 0))
    assert (first, second) == ((6, 8), (7, 9))
    removeVertex(first)
    assert counts(cube_scene) == (9, 12, 7) and verts() == (*range(8), 9)
    assert vertexInfo(9)["coords"] == (7, 0, 0)
    removeVertex(tuple(second))  # a plain tuple, as a script might rebuild it
    assert counts(cube_scene) == (8, 12, 6)


def test_remove_vertex_refuses_topmods_reversed_pair(cube_scene):
    (corner, _) = createVertex((5, 0, 0))
    before = snapshot(cube_scene.mesh)
    with pytest.raises(UnknownIdError, match=r"face 8 does not exist; removeVertex takes "
                       r"\(faceid, vertexid\).*write \(6, 8\)"):
        removeVertex((8, 6))
    with pytest.raises(InvalidArgumentError, match="vertex 0 has 3 edge end"):
        removeVertex((0, 0))  # a corner of the cube: not a point-sphere
    with pytest.raises(InvalidArgumentError, match="expected a vertex id \\(an integer\\), got 'x'"):
        removeVertex("x")
    assert snapshot(cube_scene.mesh) == before


def test_remove_vertex_with_edges_is_refused(cube_scene):
    with pytest.raises(InvalidArgumentError, match="only a point-sphere"):
        removeVertex(0)
    assert counts(cube_scene) == (8, 12, 6)


def test_delete_subdivide_collapse(cube_scene):
    e = cube_scene.mesh.corner_edge(0)
    assert len(subdivideEdge(e)) == 1 and counts(cube_scene) == (9, 13, 6)
    assert len(subdivideEdge(3, e)) == 2 and counts(cube_scene) == (11, 15, 6)
    survivor = collapseEdge(e)
    assert survivor == 0 and counts(cube_scene) == (10, 14, 6)
    assert len(deleteEdge(int(edges()[-1]))) == 1 and counts(cube_scene) == (10, 13, 5)
    with pytest.raises(InvalidArgumentError, match="subdivideEdge takes"):
        subdivideEdge(1, 2, 3)


def test_delete_edge_returns_minus_one_when_no_face_is_left(scene):
    (a, _), (b, _) = createVertex((0, 0, 0)), createVertex((1, 0, 0))
    e = insertEdge(a, b)[0]
    assert deleteEdge(e) == [-1]  # both sides were point-spheres: cleaned up, as in TopMod
    assert counts(scene) == (0, 0, 0)
    (a, _), (b, _) = createVertex((0, 0, 0)), createVertex((1, 0, 0))
    e = insertEdge(a, b)[0]
    assert len(deleteEdge(e, False)) == 2 and counts(scene) == (2, 0, 2)


def test_trisect_edge_by_offset(cube_scene):
    m = cube_scene.mesh
    new = trisectEdge(0, 0.25, False)  # edge 0 runs from (0, 0, 0) to (0, 1, 0)
    assert counts(cube_scene) == (10, 14, 6) and new == [8, 9]
    assert [vertexInfo(v)["coords"] for v in new] == [(0, 0.25, 0), (0, 0.75, 0)]
    assert walk(0)[0] == [0, 8, 9, 3, 2, 1] and m.edge_vertices(0) == (0, 8)
    trisectEdge(1, 0.0, False)  # clamped to 0.01 from each end
    np.testing.assert_allclose([vertexInfo(v)["coords"] for v in verts()[-2:]],
                               [(0.01, 1, 0), (0.99, 1, 0)])
    trisectEdge(2, 5.0, False)  # clamped to length/2 - 0.01
    np.testing.assert_allclose([vertexInfo(v)["coords"] for v in verts()[-2:]],
                               [(1, 0.51, 0), (1, 0.49, 0)])
    assert counts(cube_scene) == (14, 18, 6)


def test_trisect_edge_by_scale(cube_scene):
    new = trisectEdge(0, 0.5, True)  # p = num * end + (1 - num) * midpoint
    assert counts(cube_scene) == (10, 14, 6)
    assert [vertexInfo(v)["coords"] for v in new] == [(0, 0.25, 0), (0, 0.75, 0)]
    trisectEdge(1, 2.0, True)  # clamped to 0.99
    np.testing.assert_allclose([vertexInfo(v)["coords"] for v in verts()[-2:]],
                               [(0.005, 1, 0), (0.995, 1, 0)])
    trisectEdge(2, -1.0, True)  # clamped to 0.01
    np.testing.assert_allclose([vertexInfo(v)["coords"] for v in verts()[-2:]],
                               [(1, 0.505, 0), (1, 0.495, 0)])


def test_trisect_edge_refuses_an_offset_on_a_short_edge(cube_scene):
    move([3], (0, 0.03, 0), False)  # edge 0 is now 0.03 long
    before = snapshot(cube_scene.mesh)
    with pytest.raises(GeometryError, match="edge 0 is 0.03 long: an offset trisection needs"):
        trisectEdge(0, 0.01, False)
    assert snapshot(cube_scene.mesh) == before
    trisectEdge(0, 0.5, True)  # a scale factor always fits
    assert counts(cube_scene) == (10, 14, 6)


def test_splice_corners_of_one_face(cube_scene):
    survivor = spliceCorners((0, 0), (0, 2))  # across the bottom face's diagonal
    assert survivor == 0 and counts(cube_scene) == (7, 10, 5)
    assert vertexInfo(0)["coords"] == (0.5, 0.5, 0) and 2 not in verts()
    assert genus(cube_scene.mesh) == 0


def test_splice_corners_of_two_faces(cube_scene):
    survivor = spliceCorners((0, 0), (1, 6))  # bottom to the opposite top corner
    assert survivor == 0 and counts(cube_scene) == (7, 12, 5)
    assert vertexInfo(0)["coords"] == (0.5, 0.5, 0.5) and genus(cube_scene.mesh) == 1


def test_splice_corners_with_point_spheres(cube_scene):
    (a, _), (b, _) = createVertex((4, 0, 0)), createVertex((6, 0, 0))
    assert spliceCorners(a, b) == 8 and counts(cube_scene) == (9, 12, 7)
    assert vertexInfo(8)["type"] == "point-sphere" and vertexInfo(8)["coords"] == (5, 0, 0)
    assert spliceCorners((6, 8), (0, 0)) == 0  # the cube's vertex stays, at the midpoint
    assert counts(cube_scene) == (8, 12, 6) and vertexInfo(0)["coords"] == (2.5, 0, 0)


@pytest.mark.parametrize(("command", "args", "error", "message"), [
    (trisectEdge, (99, 0.3, True), UnknownIdError, "edge 99 does not exist"),
    (trisectEdge, (0, "x", True), InvalidArgumentError, "num must be a number, got 'x'"),
    (trisectEdge, (0, float("nan"), False), InvalidArgumentError, "num must be finite"),
    (trisectEdge, (0, 0.3, "yes"), InvalidArgumentError, "scale must be True or False, got 'yes'"),
    (spliceCorners, ((0, 0), (2, 0)), InvalidArgumentError,
     "both at vertex 0: splicing needs corners at two"),
    (spliceCorners, ((0, 0), (0, 0)), InvalidArgumentError, "both at vertex 0"),
    (spliceCorners, ((0, 0), (0, 6)), UnknownIdError, "face 0 has no corner at vertex 6"),
    (spliceCorners, ((0, 0), "x"), InvalidArgumentError, "c2 must be a \\(faceid, vertexid\\) tuple"),
])
def test_trisect_and_splice_refuse_bad_arguments(cube_scene, command, args, error, message):
    before = snapshot(cube_scene.mesh)
    with pytest.raises(error, match=message):
        command(*args)
    assert snapshot(cube_scene.mesh) == before


def test_trisect_and_splice_are_commands(cube_scene, run):
    assert {"trisectEdge", "spliceCorners"} <= set(dlfl.__all__)
    labels: list[str] = []
    run.step_hook = labels.append
    trisectEdge(0, 0.3, True)
    spliceCorners((0, 0), (0, 2))
    assert labels == ["trisectEdge", "spliceCorners"]


def test_create_face(scene):
    front, back = createFace([(0, 0, 0), (1, 0, 0), (0, 1, 0)])
    assert counts(scene) == (3, 3, 2)
    assert walk(front)[0] == [walk(back)[0][0], *walk(back)[0][:0:-1]]
    np.testing.assert_allclose(faceInfo(front)["normal"], [0, 0, 1])
    np.testing.assert_allclose(faceInfo(back)["normal"], [0, 0, -1])


def test_listings_and_walks(cube_scene):
    assert faces() == tuple(range(6))
    assert edges() == tuple(range(12)) and verts() == tuple(range(8))
    assert len(corners()) == 24 and corners()[:4] == ((0, 0), (0, 3), (0, 2), (0, 1))
    vs, es = walk(1)
    assert vs == [4, 5, 6, 7] and len(es) == 4
    assert cornerWalk(1) == [(1, 4), (1, 5), (1, 6), (1, 7)]
    assert next((1, 7)) == (1, 4) and prev((1, 4)) == (1, 7)
    assert builtins.next(iter([1, 2])) == next(iter([1, 2]))
    assert next(iter([]), "done") == "done"


def test_holes_are_not_listed_as_faces(scene):
    scene.add(dlfl.from_polygons([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]))
    assert faces() == (0,)
    assert faceInfo(1)["type"] == "hole"


def test_selection(cube_scene, run):
    cube_scene.selection = dlfl.Selection(faces=(2, 99), edges=(1,), vertices=(3,),
                                          corners=(5,))
    assert faces(True) == (2,) and edges(True) == (1,) and verts(True) == (3,)
    assert corners(True) == ((1, 5),)
    assert run.unselected_reads == set()
    cube_scene.selection = dlfl.Selection()
    assert faces(True) == () and corners(True) == ()
    assert run.unselected_reads == {"faces", "corners"}  # the run's note names them
    assert dlfl.RunContext().unselected_reads == set()


def test_picks_the_mesh_lacks_are_left_out_and_noted(cube_scene, run):
    cube_scene.selection = dlfl.Selection(faces=(2, 99, 98), vertices=(3, 50), corners=(500,))
    assert faces(True) == (2,) and verts(True) == (3,) and corners(True) == ()
    assert faces(True) == (2,)  # asked again: noted once
    assert run.missing_picks == dlfl.Selection(faces=(99, 98), vertices=(50,),
                                               corners=(500,))
    assert dlfl.RunContext().missing_picks == dlfl.Selection()  # a run's own record


def test_get_save_restore_corner(cube_scene):
    e = cube_scene.mesh.corner_edge(0)
    assert getCorner(e, 0) == (0, 0)
    with pytest.raises(InvalidArgumentError, match=f"edge {e} does not border face 3"):
        getCorner(e, 3)
    cid = saveCorner((0, 3))
    insertEdge((0, 0), (0, 2))  # face 0 splits; the corner moves on with its id
    assert restoreCorner(cid)[1] == 3
    with pytest.raises(UnknownIdError, match="does not exist"):
        restoreCorner(10_000)


def test_info_commands(cube_scene, capsys):
    printObject()
    out = capsys.readouterr().out
    assert "Number of vertices : 8" in out and "Number of edges : 12" in out
    assert "Genus : 0" in out
    info = vertexInfo(6)
    assert info["valence"] == 3 and info["coords"] == (1, 1, 1) and info["type"] == "normal"
    assert faceInfo(1)["size"] == 4 and faceInfo(1)["centroid"] == (0.5, 0.5, 1.0)
    ci = cornerInfo((0, 3))
    assert (ci["face"], ci["vertex"], ci["id"]) == (0, 3, 1)
    assert len(vertexEdges(0)) == 3
    assert centroid() == (0.5, 0.5, 0.5)
    assert centroid([0, 1]) == (0.5, 0.0, 0.0)
    with pytest.raises(InvalidArgumentError, match="at least one vertex"):
        centroid([])


def test_bad_corner_arguments(cube_scene):
    with pytest.raises(InvalidArgumentError, match="c1 must be a \\(faceid, vertexid\\) tuple"):
        insertEdge("x", (0, 2))
    with pytest.raises(UnknownIdError, match="face 0 has no corner at vertex 6"):
        insertEdge((0, 6), (0, 2))
    with pytest.raises(UnknownIdError, match="face 42 does not exist"):
        next((42, 0))
    assert counts(cube_scene) == (8, 12, 6)


def test_transforms(cube_scene):
    translate(1, 2, 3)
    np.testing.assert_allclose(vertexInfo(0)["coords"], [1, 2, 3])
    scale((2, 2, 2))  # about the object's origin, now (1, 2, 3)
    np.testing.assert_allclose(vertexInfo(6)["coords"], [3, 4, 5])
    translate((0, 0, 0), False)  # absolute: the origin goes back to 0
    np.testing.assert_allclose(vertexInfo(0)["coords"], [0, 0, 0])
    move([6], (1, 0, 0))
    np.testing.assert_allclose(vertexInfo(6)["coords"], [3, 2, 2])
    move([6], (0, 0, 0), False)
    np.testing.assert_allclose(vertexInfo(6)["coords"], [0, 0, 0])
    translate(5, 0, 0)
    freezeTrans()
    translate((0, 0, 0), relative=False)  # the frozen placement is the new origin
    np.testing.assert_allclose(vertexInfo(0)["coords"], [5, 0, 0])
    with pytest.raises(InvalidArgumentError, match="translate takes"):
        translate(1, 2)


def test_step_hook_called_once_per_outermost_command(cube_scene, run):
    labels: list[str] = []
    run.step_hook = labels.append
    insertEdge((0, 0), (0, 2))
    collapseEdge(int(edges()[-1]))  # collapse deletes edges internally: still one step
    step("checkpoint")
    faces()
    assert labels == ["insertEdge", "collapseEdge", "checkpoint"]


def test_objects_load_switch_kill(scene, tmp_path, topmod_samples):
    first = load(str(topmod_samples / "cube.obj"))
    assert counts(scene) == (8, 12, 6)
    (_, second) = createVertex((0, 0, 0))
    assert second == first
    other = load(str(topmod_samples / "cube.obj"))
    assert other != first and scene.current == other
    deleteEdge(0)
    assert switch(first) == first and counts(scene) == (9, 12, 7)
    kill(first)
    assert scene.current == other and counts(scene) == (8, 11, 5)
    with pytest.raises(UnknownIdError, match=f"object {first} does not exist"):
        switch(first)
    path = tmp_path / "out.obj"
    assert save(str(path)) is True
    assert load(str(path)) != other and counts(scene) == (8, 11, 5)


@pytest.mark.parametrize(("command", "args", "error", "message"), [
    (load, (None,), InvalidArgumentError, "load takes a file name"),
    (load, (5,), InvalidArgumentError, "load takes a file name"),
    (save, (None,), InvalidArgumentError, "save takes a file name"),
    (save, ("/nonexistent-dir/x.obj",), InvalidArgumentError,
     "cannot save '/nonexistent-dir/x.obj'"),
    (move, (None, (1, 2, 3)), InvalidArgumentError, "move takes a list of vertex ids"),
    (centroid, (5,), InvalidArgumentError, "centroid takes a list of vertex ids"),
    (next, (None,), InvalidArgumentError, "next takes a corner or an iterator"),
    (vertexInfo, ("x",), InvalidArgumentError, "expected a vertex id"),
    (kill, ("x",), UnknownIdError, "object 'x' does not exist"),
])
def test_junk_arguments_raise_dlfl_errors(cube_scene, command, args, error, message):
    with pytest.raises(error, match=message):
        command(*args)
    assert counts(cube_scene) == (8, 12, 6)


NAN, INF = float("nan"), float("inf")


@pytest.mark.parametrize(("call", "message"), [
    (lambda d: d.createVertex((INF, 0, 0)), "three finite numbers, got \\(inf, 0, 0\\)"),
    (lambda d: d.createFace([(0, 0, 0), (1, 0, 0), (NAN, 1, 0)]), "three finite numbers"),
    (lambda d: d.move([0], (NAN, 0, 0)), "three finite numbers"),
    (lambda d: d.translate(INF, 0, 0), "three finite numbers"),
    (lambda d: d.scale((NAN, 1, 1)), "three finite numbers"),
    (lambda d: d.rind([0], False, NAN), "percent must be finite, got nan"),
    (lambda d: d.rind([0], True, INF), "percent must be finite, got inf"),
    (lambda d: d.rind([0], False, "thin"), "percent must be a number, got 'thin'"),
    (lambda d: d.addHandle("hermite", (0, 0), (5, 4), 5, NAN, 25), "w1 must be finite"),
    (lambda d: d.addHandle("bezier", (0, 0), (5, 4), 5, 25, INF), "w2 must be finite"),
    (lambda d: d.extrude("cubical", 0, "x"), "distance must be a number, got 'x'"),
    (lambda d: d.extrude("cubical", 0, 1.0, 1, NAN), "rotation must be finite"),
    (lambda d: d.wireframe("x"), "thickness must be a number, got 'x'"),
    (lambda d: d.column(INF, 4), "thickness must be finite"),
])
def test_numbers_that_are_not_finite_are_refused_and_the_mesh_kept(cube_scene, call, message):
    before = snapshot(cube_scene.mesh)
    with pytest.raises(InvalidArgumentError, match=message):
        call(dlfl)
    assert snapshot(cube_scene.mesh) == before


@pytest.mark.parametrize(("command", "args"), [
    ("translate", (1e308, 0.0, 0.0)), ("scale", ((1e308, 1.0, 1.0),)),
    ("move", ([0], (1e308, 0.0, 0.0)))])
def test_moves_that_overflow_to_infinity_are_refused(cube_scene, command, args):
    getattr(dlfl, command)(*args)  # far, but finite
    before = snapshot(cube_scene.mesh)
    with pytest.raises(GeometryError, match=r"would move vertex \d+ to \[.*inf.*nothing is moved"):
        getattr(dlfl, command)(*args)
    assert snapshot(cube_scene.mesh) == before


@pytest.mark.parametrize("call", [
    lambda: dlfl.faces("no"), lambda: dlfl.edges("yes"), lambda: dlfl.verts(2),
    lambda: dlfl.corners(None), lambda: dlfl.deleteEdge(0, "False"),
    lambda: dlfl.translate(1, 0, 0, "absolute"), lambda: dlfl.move([0], (1, 0, 0), 0.5),
    lambda: dlfl.subdivideFace(0, "quads"), lambda: dlfl.dual("accurate"),
    lambda: dlfl.extrude("octa", 0, 1, 0, 1, mesh="no"),
    lambda: dlfl.extrude("dodeca", 0, 1, 2, 0, 1, [True]),
    lambda: dlfl.connectEdges((0, 0), (1, 1), "check"),
    lambda: dlfl.rind([0], "no", 0.1), lambda: dlfl.rind([0], False, 0.1, "no"),
    lambda: dlfl.crust(0.1, "no"), lambda: dlfl.wireframe(0.1, "no"),
])
def test_an_on_off_option_that_is_not_a_flag_is_refused(cube_scene, call):
    """A string such as "no" would otherwise mean True."""
    before = snapshot(cube_scene.mesh)
    with pytest.raises(InvalidArgumentError, match=r"must be True or False, got"):
        call()
    assert snapshot(cube_scene.mesh) == before


def test_flags_may_be_bools_numpy_bools_or_0_and_1(cube_scene):
    assert dlfl.faces(0) == dlfl.faces(False) == dlfl.faces(np.False_)
    dlfl.translate(1, 2, 3, 1)
    dlfl.move([0], (5, 5, 5), np.bool_(False))
    assert dlfl.centroid([0]) == (5.0, 5.0, 5.0)


def test_numpy_integers_are_ids_like_python_ints(cube_scene):
    """Ids read from numpy arrays (np.argmax, mesh_arrays) work as given."""
    corner = np.int64(cube_scene.mesh.face_corners(0)[0])
    far = np.int32(cube_scene.mesh.face_corners(0)[2])
    edge = dlfl.insertEdge(corner, far)[0]
    assert dlfl.deleteEdge(np.int64(edge)) == [0]
    dlfl.subdivideFace(np.int64(0))
    dlfl.subdivideFaces(np.array(dlfl.faces()[:2]))
    assert cube_scene.switch(np.int64(cube_scene.current)) == cube_scene.current
    assert type(cube_scene.current) is int
    assert dlfl.faceInfo(np.int64(dlfl.faces()[3])) == dlfl.faceInfo(dlfl.faces()[3])
    vertex = dlfl.verts()[0]
    assert dlfl.vertexEdges(np.int64(vertex)) == dlfl.vertexEdges(vertex)


def _run_as_script(source: str) -> dict:
    """Run ``source`` as a script's module body (``__main__``), as livemod runs it."""
    namespace = {"__name__": "__main__"}
    exec(compile(source, "script.py", "exec"), namespace)  # noqa: S102
    return namespace


def test_walk_prints_the_thesiss_walk_at_a_scripts_top_level(cube_scene, capsys):
    m = cube_scene.mesh
    vertices, edges = m.face_vertices(0), m.face_edges(0)
    ran = _run_as_script("from livemod.dlfl import *\nvs, es = walk(0)\n")
    assert (ran["vs"], ran["es"]) == (vertices, edges)
    line = "DLFLFace 0 (4) : " + "".join(
        f"{v}--({e})-->" for v, e in zip(vertices, edges, strict=True)) + f"{vertices[0]}\n"
    assert capsys.readouterr().out == line
    _run_as_script("from livemod.dlfl import *\ndef quiet():\n    return walk(0)\nquiet()\n")
    dlfl.walk(0)  # from a test module, not a script's top level
    assert capsys.readouterr().out == ""


def test_walk_of_a_point_sphere_prints_its_one_vertex(cube_scene, capsys):
    (face, vertex), _ = dlfl.createVertex((5, 0, 0))
    _run_as_script(f"from livemod.dlfl import *\nwalk({face})\n")
    assert capsys.readouterr().out == f"DLFLFace {face} (1) : {vertex}\n"
