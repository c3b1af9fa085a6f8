"""Pictures drawn a slice at a time: the window's budget of primitives a frame."""

from __future__ import annotations

from livemod.dlfl import mesh_arrays
from livemod.dlfl.shapes import torus
from livemod.viewer.headless import Offscreen, framed_camera
from livemod.viewer.renderer import Style
from livemod.viewer.slices import SliceBudget


def test_the_budget_follows_the_rate_the_slices_were_drawn_at() -> None:
    budget = SliceBudget(150_000, seconds=0.05, least=10_000)  # (the window: 50,000)
    assert budget.primitives == 150_000  # nothing measured yet
    budget.measured(150_000, 0.15)  # three times too slow: a third would do
    assert budget.primitives == (150_000 + 50_000) // 2
    budget.measured(100_000, 0.01)  # cheap frames: more a frame
    assert budget.primitives == (100_000 + 500_000) // 2
    budget.measured(0, 1.0)  # a frame that drew no slice says nothing
    assert budget.primitives == 300_000
    for _ in range(20):
        budget.measured(1_000, 10.0)
    assert budget.primitives == 10_000  # never below the least


def test_the_renderer_says_how_much_of_a_sliced_picture_a_draw_drew(
        offscreen: Offscreen) -> None:
    renderer = offscreen.renderer
    first, second = mesh_arrays(torus(12, 8)), mesh_arrays(torus(20, 14))
    camera = framed_camera(second)
    renderer.set_mesh(first)
    assert renderer.draw(offscreen.target, camera, Style(), budget=100)
    assert renderer.sliced == 0  # drawn whole
    renderer.set_mesh(second)  # 560 triangles (with their wire) and the marks' pass
    drawn = []
    while not renderer.draw(offscreen.target, camera, Style(), budget=200):
        drawn.append(renderer.sliced)
    drawn.append(renderer.sliced)
    assert drawn == [200, 200, 161]
    assert renderer.draw(offscreen.target, camera, Style(), budget=200)  # whole, kept
    assert renderer.sliced == 0



def test_the_labels_of_a_sliced_picture_are_drawn_in_a_call_of_their_own(
        offscreen: Offscreen) -> None:
    renderer = offscreen.renderer
    first, second = mesh_arrays(torus(12, 8)), mesh_arrays(torus(20, 14))
    camera = framed_camera(second)
    style = Style(labels=frozenset({"faces"}))
    renderer.set_mesh(first)
    assert renderer.draw(offscreen.target, camera, style, budget=200)
    renderer.set_mesh(second)
    drawn = []
    while not renderer.draw(offscreen.target, camera, style, budget=200):
        drawn.append(renderer.sliced)
    drawn.append(renderer.sliced)
    assert drawn == [200, 200, 161, 0]  # the last call lays out and draws the labels
    sliced = offscreen.target.read(components=3)
    camera.yaw += 1.0
    renderer.draw(offscreen.target, camera, style)  # (another view: forget the kept one)
    camera.yaw -= 1.0
    renderer.draw(offscreen.target, camera, style)
    assert offscreen.target.read(components=3) == sliced
