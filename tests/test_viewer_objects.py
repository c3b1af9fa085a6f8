"""The scene objects controller (GL-free): which objects are drawn, Tab, the list."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from livemod.dlfl.scene import Scene
from livemod.dlfl.shapes import cube, octahedron, tetrahedron
from livemod.runner.results import object_fields, snapshot_scene
from livemod.viewer.look import Look
from livemod.viewer.objects import SceneObjects
from livemod.viewer.params_panel import Hit
from livemod.viewer.runs import RunTracker


def _result(*shapes, killed: tuple[int, ...] = ()) -> SimpleNamespace:
    scene = Scene()
    for name, shape in shapes:
        scene.add(shape(), name)
    for oid in killed:
        scene.kill(oid)
    return SimpleNamespace(run_id=1, status="ok", steps=(), step_index=None, error=None,
                           arrays=snapshot_scene(scene), **object_fields(scene))


THREE = (("tet", tetrahedron), ("oct", octahedron), ("box", cube))


@pytest.fixture
def objects() -> tuple[SceneObjects, list, list[str]]:
    runs, drawn, said = RunTracker(), [], []
    control = SceneObjects(runs, Look(), said.append, drawn.append)
    result = _result(*THREE)
    control.sync(result)
    runs.take(result)
    return control, drawn, said


def test_tab_shows_each_other_object_alone_then_all(objects) -> None:
    control, drawn, said = objects
    control._look.change(others=False)  # A hid them: Tab shows them again
    control.cycle()
    assert control.hidden == {1} and control._look.style.others
    assert drawn[-1].counts == (4, 6, 4)  # the tetrahedron alone
    assert said[-1] == "other objects: object 0 'tet' alone (of 2; Tab: next)"
    control.cycle()
    control.cycle()
    assert control.hidden == frozenset() and said[-1] == "other objects: all 2"
    assert drawn[-1].counts == (10, 18, 12)


def test_the_list_ticks_unticks_and_hides_the_current_object(objects) -> None:
    control, drawn, said = objects
    control.toggle_list()
    assert control.listed and control.list_shown(True) and not control.list_shown(False)
    control.press(Hit(0, "toggle"))
    assert control.hidden == {0} and control.note() == "object 1 'oct' alone (of 2; Tab: next)"
    control.press(Hit(-1, "none"))
    assert control.hidden == {0, 1} and drawn[-1] is None
    assert control.note() == "0 of 2 shown (L: list)"
    control.press(Hit(2, "current"))
    assert not control._look.style.current and said[-1] == "current object: hidden"
    control.press(Hit(-1, "all"))  # all: the current object too
    assert control.hidden == frozenset() and control._look.style.current
    control.press(Hit(-1, "name"))  # the header's name: nothing
    assert said[-1] == "other objects: all 2"


def test_what_is_hidden_stays_hidden_across_results(objects) -> None:
    control, _, _ = objects
    control.set_hidden(frozenset({1}))  # object 0 shown alone
    again = _result(*THREE)
    control.sync(again)  # the same objects: still hidden
    assert control.hidden == {1}
    control._runs.take(again)
    fewer = _result(*THREE, killed=(0,))  # the one shown is gone: all are shown again
    control.sync(fewer)
    assert control.hidden == frozenset()


def test_a_scene_of_one_object_has_none_to_cycle(objects) -> None:
    control, _, said = objects
    one = _result(("box", cube))
    control.sync(one)
    control._runs.take(one)
    control.cycle()
    assert said == ["the scene has no other objects"]
    control.forget()
    control.toggle_list()
    assert said[-1] == "the scene has no objects to list"
