"""Selection commands: TopMod's selection tools returning ids to pass on."""

from __future__ import annotations

import pytest

import livemod.dlfl as dlfl
from livemod.dlfl import DLFLError, Scene, genus, num_components, use_scene, validate
from livemod.dlfl import selection as library
from livemod.dlfl.commands import (
    checkerboard,
    clear_selection,
    edge_loop,
    edge_ring,
    face_loop,
    faces,
    grow_selection,
    invert_selection,
    rind,
    select_all,
    shrink_selection,
    similar_edges,
    similar_faces,
    similar_vertices,
)
from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import torus
from tests.meshes import counts, snapshot


@pytest.fixture
def torus_scene():
    """A scene holding an 8 x 6 quad torus (48 faces, every vertex of valence 4)."""
    bound = Scene()
    bound.add(torus(8, 6), "torus")
    with use_scene(bound):
        yield bound


def test_star_import_gives_the_commands():
    for name in ("edge_loop", "edge_ring", "face_loop", "checkerboard", "similar_faces",
                 "similar_edges", "similar_vertices", "grow_selection", "shrink_selection",
                 "invert_selection", "select_all", "clear_selection"):
        assert name in dlfl.__all__


def test_a_face_loop_goes_straight_into_rind(torus_scene):
    band = face_loop(1)
    assert len(band) == 6
    rind(band, False, 0.1)
    # the crust (two tori, 96/192/96) loses the band's 12 faces and the 12 edges
    # between them, and gains 12 quads and 12 edges joining the band's two borders
    validate(torus_scene.mesh)
    assert counts(torus_scene) == (96, 192, 96) and genus(torus_scene.mesh) == 1
    assert num_components(torus_scene.mesh) == 1


@pytest.mark.parametrize(("command", "rule", "element"), [
    (edge_loop, library.edge_loop, 0), (edge_ring, library.edge_ring, 0),
    (face_loop, library.face_loop, 0), (checkerboard, library.checkerboard, 0),
    (similar_edges, library.matching_edges, 3), (similar_vertices, library.matching_vertices, 3),
    (similar_faces, library.matching_faces, 3),
])
def test_each_command_returns_the_librarys_ids(torus_scene, command, rule, element):
    assert command(element) == rule(torus_scene.mesh, element)


def test_a_list_gives_the_union_in_the_order_found(torus_scene):
    first, second = edge_loop(0), edge_loop(1)
    assert edge_loop([0, 1]) == first + [e for e in second if e not in first]
    assert len(checkerboard([0, 1])) == 48  # the two colours of the board


def test_grow_shrink_invert_and_all_read_the_picks(torus_scene):
    assert grow_selection([0]) == library.grow(torus_scene.mesh, [0])
    torus_scene.selection = Selection(faces=(0,), edges=(0,))
    assert len(grow_selection()) == 5 and len(grow_selection(kind="edges")) == 7
    assert shrink_selection(grow_selection()) == [0]
    assert len(invert_selection()) == 47 and len(invert_selection(kind="edges")) == 95
    assert [len(select_all(kind)) for kind in ("faces", "edges", "verts", "corners")] == \
        [48, 96, 48, 192]
    assert select_all() == list(faces())


def test_clear_selection_forgets_the_picks_of_every_kind(torus_scene):
    torus_scene.selection = Selection(faces=(0, 1), edges=(0,), vertices=(2,))
    grown = grow_selection()
    assert clear_selection() == [] and torus_scene.selection == Selection()
    assert faces(True) == () and grow_selection() == [] and len(grown) == 8
    assert invert_selection(kind="vertices") == select_all("vertices")


def test_similar_faces_by_area(torus_scene):
    # 6 faces round the tube: 3 areas, each a ring of 8 and its mirror across the
    # equator
    same = similar_faces(0, "area", 1e-9)
    assert len(same) == 16 and 0 in same


@pytest.mark.parametrize(("call", "message"), [
    (lambda: edge_loop(999), "edge 999 does not exist"),
    (lambda: checkerboard("0"), "faceid"),
    (lambda: similar_faces(0, "shade"), "faces are compared by 'size', 'area', 'colour'"),
    (lambda: grow_selection([0], "corners"), "corners neither grow"),
    (lambda: select_all("loops"), "kind must be one of"),
    (lambda: invert_selection(kind="loops"), "kind must be one of"),
])
def test_bad_selections_are_refused_and_change_nothing(torus_scene, call, message):
    before = snapshot(torus_scene.mesh)
    with pytest.raises(DLFLError, match=message):
        call()
    assert snapshot(torus_scene.mesh) == before
