"""Thesis commands rind, wireframe, column and the sculpting extras on the current scene."""

from __future__ import annotations

import numpy as np
import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import Scene, face_size_histogram, genus, use_scene, validate
from livemod.dlfl.commands import (
    column,
    convexHull,
    createVertex,
    crust,
    dualConvexHull,
    faces,
    load,
    menger,
    meshsmooth,
    multiConnectFaces,
    planarize,
    punch,
    rind,
    sierpinsky,
    spheralize,
    wireframe,
)
from livemod.dlfl.errors import GeometryError, InvalidArgumentError, UnknownIdError
from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import cube
from tests.meshes import counts, snapshot


def test_star_import_gives_the_commands():
    for name in ("rind", "wireframe", "column", "sierpinsky", "menger", "meshsmooth",
                 "planarize", "spheralize", "crust", "convexHull", "dualConvexHull",
                 "multiConnectFaces"):
        assert name in dlfl.__all__
        assert callable(getattr(dlfl, name))


def test_rind_by_thickness(scene):
    rind([faces()[0]], False, 0.5)
    assert counts(scene) == (16, 28, 14)


def test_rind_by_scaling_two_holes(scene):
    rind([0, 5], True, 0.8)
    assert counts(scene) == (16, 32, 16) and genus(scene.mesh) == 1


def test_rind_accepts_one_face_id(scene):
    rind(0, False, 0.25, False)
    assert counts(scene) == (16, 28, 14)


def test_wireframe_defaults(scene):
    wireframe()
    assert counts(scene) == (48, 120, 64)
    assert face_size_histogram(scene.mesh) == {3: 16, 4: 48}


def test_column(scene):
    column(0.25, 4)
    assert counts(scene) == (96, 216, 112) and genus(scene.mesh) == 5


def test_extras(scene):
    sierpinsky()
    assert counts(scene) == (20, 60, 32)
    load("cube")
    menger()
    assert counts(scene) == (64, 156, 84)
    load("cube")
    crust(0.5)
    assert counts(scene) == (16, 24, 12)
    for op in (meshsmooth, planarize, spheralize):
        op()
        assert counts(scene) == (16, 24, 12)


def test_menger_without_a_thickness_fits_it_to_the_mesh(scene):
    assert menger() == 0.67  # the cube: TopMod's default as it is
    load("tetrahedron")  # its inner shell collapses at 1/3: 0.67 of that is used
    assert menger() == pytest.approx(0.67 / 3)
    validate(scene.mesh)
    load("tetrahedron")
    with pytest.raises(GeometryError, match="thickness 0.67 is too large for this mesh"):
        menger(0.67)


def test_convex_hull_of_the_cube_is_twelve_triangles(scene):
    convexHull()
    assert counts(scene) == (8, 18, 12) and face_size_histogram(scene.mesh) == {3: 12}


def test_dual_convex_hull_of_the_cube_is_an_octahedron(scene):
    dualConvexHull()
    assert counts(scene) == (6, 12, 8) and genus(scene.mesh) == 0
    dualConvexHull()
    assert counts(scene) == (8, 12, 6)


def test_convex_hull_of_a_torus_closes_it(scene):
    load("torus")
    convexHull()
    validate(scene.mesh)
    assert genus(scene.mesh) == 0 and set(face_size_histogram(scene.mesh)) == {3}


@pytest.mark.parametrize("op", [convexHull, dualConvexHull])
def test_hulls_of_too_few_or_coplanar_vertices_are_refused_unchanged(op):
    with use_scene(Scene()) as sc:
        for p in [(0, 0, 0), (1, 0, 0), (0, 1, 0)]:
            createVertex(p)
        before = snapshot(sc.mesh)
        with pytest.raises(InvalidArgumentError, match="at least 4 points, got 3"):
            op()
        assert snapshot(sc.mesh) == before
        createVertex((1, 1, 0))
        before = snapshot(sc.mesh)
        with pytest.raises(GeometryError, match="not all in one plane"):
            op()
        assert snapshot(sc.mesh) == before


def test_load_a_sample_by_name_then_wireframe(scene):
    load("soccerball")
    wireframe(0.05)
    assert genus(scene.mesh) == 90 - 60 + 1


@pytest.mark.parametrize(("call", "error"), [
    (lambda: rind([99], False, 0.5), UnknownIdError),
    (lambda: rind(["a"], False, 0.5), InvalidArgumentError),
    (lambda: rind(None, False, 0.5), InvalidArgumentError),
    (lambda: rind([0], False, 5.0), GeometryError),
    (lambda: rind([0], True, 0.0), InvalidArgumentError),
    (lambda: wireframe(-1.0), InvalidArgumentError),
    (lambda: column(0.25, 0), InvalidArgumentError),
    (lambda: column(0.25, "four"), InvalidArgumentError),
    (lambda: column(0.0, 4), InvalidArgumentError),
    (lambda: menger(0.0), InvalidArgumentError),
])
def test_bad_arguments_raise_and_leave_the_object_unchanged(scene, call, error):
    before = snapshot(scene.mesh)
    with pytest.raises(error):
        call()
    assert snapshot(scene.mesh) == before


# -- multiConnectFaces (the scene's cube: face 0 at y = 1, 5 at y = -1, 2 and 4 at
# z = -1 and z = 1)

def test_multi_connect_faces_is_the_convex_hull_handle(scene):
    multiConnectFaces([0, 2, 4])
    assert counts(scene) == (20, 42, 20) and genus(scene.mesh) == 2


def test_multi_connect_faces_takes_the_selection(scene):
    scene.selection = dlfl.Selection(faces=(0, 2, 4))
    multiConnectFaces(faces(True), 1.0, 0.5, True)
    assert counts(scene) == (20, 42, 20) and genus(scene.mesh) == 2
    load("cube")
    scene.selection = dlfl.Selection(faces=(0, 5))
    multiConnectFaces(method="closest-edge")  # no ids: the selection
    assert counts(scene) == (8, 16, 8) and genus(scene.mesh) == 1


def test_multi_connect_faces_scale_and_extrude_reach_the_hub(scene):
    multiConnectFaces([0, 5], 1.0, 1.0)
    # the hub is the box of the pushed faces, y = +-2, around the cube (inside out)
    hub = [scene.mesh.position(v)[1] for v in scene.mesh.vertex_ids() if v >= 8]
    assert counts(scene) == (16, 32, 16) and sorted(set(hub)) == [-2.0, 2.0]


def test_multi_connect_faces_fitted(scene):
    multiConnectFaces([0, 5], method="fitted", minFactor=0.01)
    hub = {scene.mesh.position(v)[1] for v in scene.mesh.vertex_ids() if v >= 8}
    assert counts(scene) == (16, 32, 16) and genus(scene.mesh) == 1
    assert hub == {-0.015625, 0.015625}  # 0.984375 of the way to the centre


def test_multi_connect_faces_is_one_step(scene, run):
    labels: list[str] = []
    run.step_hook = labels.append
    multiConnectFaces([0, 5], method="closest-edge")
    multiConnectFaces([1, 3])
    assert labels == ["multiConnectFaces", "multiConnectFaces"]


@pytest.mark.parametrize(("call", "message", "error"), [
    (lambda: multiConnectFaces([0, 5], method="convex"), "method must be one of 'hull'",
     InvalidArgumentError),
    (lambda: multiConnectFaces([0, 5], extrude=1.0, method="closest-edge"),
     "method 'closest-edge' does not use extrude", InvalidArgumentError),
    (lambda: multiConnectFaces([0, 5], maxOffsets=True, method="fitted"),
     "method 'fitted' does not use maxOffsets", InvalidArgumentError),
    (lambda: multiConnectFaces([0, 5], minFactor=0.1), "method 'hull' does not use minFactor",
     InvalidArgumentError),
    (lambda: multiConnectFaces([0]), "needs two or more different faces", InvalidArgumentError),
    (lambda: multiConnectFaces([0, 99]), "face 99 does not exist", UnknownIdError),
    (lambda: multiConnectFaces("0, 5"), "faces must be a list of ids", InvalidArgumentError),
    (lambda: multiConnectFaces([0, 5], maxOffsets="no"), "max_offsets must be True or False",
     InvalidArgumentError),
    (lambda: multiConnectFaces([0, 5], method="fitted", minFactor=-1.0),
     "min_factor must be a positive number", InvalidArgumentError),
])
def test_multi_connect_faces_bad_arguments_leave_the_object_unchanged(scene, call, message, error):
    before = snapshot(scene.mesh)
    with pytest.raises(error, match=message):
        call()
    assert snapshot(scene.mesh) == before


def test_a_crust_is_punched_in_later_steps(scene, run):
    crust(0.5)
    outer = faces()[:6]
    labels: list[str] = []
    run.step_hook = labels.append
    tube = punch([outer[0]])
    assert counts(scene) == (16, 28, 14) and len(tube) == 4
    punch(outer[5])
    assert counts(scene) == (16, 32, 16) and genus(scene.mesh) == 1
    assert labels == ["punch", "punch"]
    validate(scene.mesh)


def test_punch_takes_the_selection_and_rinds_leftover_faces(scene):
    rind([0], False, 0.5)
    rest = faces()[:5]
    scene.selection = Selection(faces=(rest[0],))
    punch()
    assert counts(scene) == (16, 28, 14)  # the two holes share an edge: one opening


def test_rind_and_punch_without_cleanup_keep_the_double_walls(scene):
    rind([0, 1], False, 0.5, cleanup=False)
    walls = counts(scene)
    other = Scene()
    other.add(cube())
    with use_scene(other):
        crust(0.5)
        outer = faces()[:6]
        punch([outer[0], outer[1]], cleanup=False)
    assert counts(other) == walls == (16, 32, 16)


@pytest.mark.parametrize(("call", "message"), [
    (lambda: punch([0]), "punch needs a crust: make one on this object"),
    (lambda: (crust(0.5), punch([0])), "face 0 is not a face of the crust still to punch"),
    (lambda: (crust(0.5), punch(faces()[:1]), punch(faces()[:1])), "still to punch"),
])
def test_punching_without_a_crust_or_twice_is_refused(scene, call, message):
    with pytest.raises(InvalidArgumentError, match=message):
        call()


def test_crust_by_scaling_and_wireframe_by_width(scene):
    crust(scale=0.5)
    assert counts(scene) == (16, 24, 12)
    inner = [scene.mesh.position(v) for v in scene.mesh.vertex_ids().tolist()[8:]]
    assert abs(np.array(inner)).max() == 0.5
    load("cube")
    wireframe(0.1, width=0.4)
    wide = snapshot(scene.mesh)
    assert counts(scene) == (48, 120, 64)
    load("cube")
    wireframe(0.1)
    assert snapshot(scene.mesh) != wide


def test_menger_keeps_or_drops_topmods_two_gons(scene):
    menger(keep2gons=False)
    assert counts(scene) == (64, 144, 72) and genus(scene.mesh) == 5
