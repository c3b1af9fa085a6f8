"""Tests of livemod.dlfl.scene: objects, the current object, the selection and binding."""

from __future__ import annotations

import threading

import numpy as np
import pytest

from livemod.dlfl import (
    Mesh,
    Scene,
    Selection,
    UnknownIdError,
    current_scene,
    use_scene,
)
from livemod.dlfl.scene import default_scene, reset_default_scene
from tests.meshes import cube


def test_objects_and_current():
    s = Scene()
    assert s.current is None
    a = s.add(cube(), "a")
    b = s.add(Mesh(), "b")
    assert (a, b) == (0, 1) and s.current == b
    assert s.mesh.counts() == (0, 0, 0)
    assert s.switch(a) == a and s.mesh.counts() == (8, 12, 6)
    s.kill(a)
    assert s.current == b and list(s.objects) == [b]
    s.kill(b)
    assert s.current is None
    assert s.mesh.counts() == (0, 0, 0) and s.current == 2  # created on demand


def test_unknown_objects_are_refused():
    s = Scene()
    s.add(cube())
    with pytest.raises(UnknownIdError, match=r"object 5 does not exist \(objects: 0\)"):
        s.switch(5)
    with pytest.raises(UnknownIdError, match="object '0' does not exist"):
        s.kill("0")  # type: ignore[arg-type]
    assert Scene().current_object.mesh.counts() == (0, 0, 0)


def test_copy_is_deep():
    s = Scene()
    s.add(cube(), "c")
    s.selection = Selection(faces=(1,))
    s.face_budget = 50
    dup = s.copy()
    s.mesh.insert_edge(0, 2)
    s.current_object.origin[0] = 4.0
    assert dup.mesh.counts() == (8, 12, 6)
    assert dup.current_object.origin[0] == 0.0
    assert dup.selection.faces == (1,) and dup.objects[0].name == "c"
    assert dup.face_budget == 50
    assert dup.add(Mesh()) == 1


def test_selection_is_empty():
    assert Selection().is_empty()
    assert not Selection(corners=(3,)).is_empty()


def test_selection_parses_the_select_options_and_writes_them_back():
    picked = Selection.parse(["faces=12,31", "corners=88", "Faces=31, 5", "verts=2",
                              "vertices=7"])
    assert picked == Selection(faces=(12, 31, 5), vertices=(2, 7), corners=(88,))
    singular = Selection.parse(["face=12,31", "corner=88", "face=5", "vert=2", "vertex=7"])
    assert singular == picked
    assert Selection.parse(["edge=4", "edges=6"]) == Selection(edges=(4, 6))
    assert picked.options() == ("--select faces=12,31,5 --select verts=2,7 "
                                "--select corners=88")
    again = picked.options().replace("--select ", "").split()
    assert Selection.parse(again) == picked
    assert Selection().options() == "" and Selection.parse([]) == Selection()


@pytest.mark.parametrize(("text", "wrong"), [
    ("fcae=1", r"the kind must be one of faces, edges, vertices, corners \(or its singular"),
    ("12", "the kind must be one of"),
    ("faces=", "'' is not an id"),
    ("faces=1,,2", "'' is not an id"),
    ("faces=-1", "'-1' is not an id"),
    ("edges=1.5", "'1.5' is not an id"),
    ("corners=٣", "'٣' is not an id"),   # a digit, but not one a user types as an id
])
def test_selection_parse_names_what_is_wrong(text, wrong):
    with pytest.raises(ValueError, match=f"--select '{text}': {wrong}"):
        Selection.parse([text])


def test_selection_adding_keeps_order_and_each_id_once():
    picked = Selection(faces=(3, 1)).adding("faces", [1, 4, 4, 2])
    assert picked == Selection(faces=(3, 1, 4, 2))
    assert picked.adding("corners", ()) == picked


def test_selection_adding_takes_numpy_ids_as_ints():
    picked = Selection().adding("vertices", np.array([11, 3, 11]))
    assert picked.vertices == (11, 3) and all(type(i) is int for i in picked.vertices)
    assert repr(picked.vertices) == "(11, 3)"
    with pytest.raises(TypeError):
        Selection().adding("faces", [1.5])


def test_use_scene_binds_per_thread():
    mine = Scene()
    seen: dict[str, Scene] = {}

    def other_thread() -> None:
        seen["other"] = current_scene()

    with use_scene(mine):
        assert current_scene() is mine
        t = threading.Thread(target=other_thread)
        t.start()
        t.join()
    assert seen["other"] is default_scene()
    assert current_scene() is default_scene()


def test_reset_default_scene():
    old = default_scene()
    new = reset_default_scene()
    assert new is not old and default_scene() is new and new.objects == {}
