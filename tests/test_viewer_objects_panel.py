"""The object list (GL-free): rows, hit testing, scrolling, Tab's cycle and what stays
hidden across runs."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from livemod.dlfl.scene import Scene
from livemod.dlfl.shapes import cube, octahedron, tetrahedron
from livemod.runner.results import object_fields, snapshot_scene
from livemod.viewer.objects_panel import (
    ObjectPanel,
    ObjectRow,
    kept_hidden,
    next_alone,
    result_rows,
    visible_objects,
)
from livemod.viewer.params_panel import Hit

SIZE = (800, 600)


def _result_of(scene: Scene) -> SimpleNamespace:
    return SimpleNamespace(arrays=snapshot_scene(scene), **object_fields(scene))


def _three() -> Scene:
    scene = Scene()
    scene.add(tetrahedron(), "tet")
    scene.add(octahedron())
    scene.add(cube(), "box")
    return scene


def test_rows_list_every_object_in_order_with_the_current_one_marked() -> None:
    scene = _three()
    scene.switch(1)
    rows = result_rows(_result_of(scene))
    assert rows == (ObjectRow(0, "tet", 4, 4), ObjectRow(1, "", 6, 8, current=True),
                    ObjectRow(2, "box", 8, 6))
    assert rows[0].text() == "0 tet   V 4  F 4"
    assert rows[1].text() == "1   V 6  F 8  (current)"


def test_a_result_without_objects_lists_none() -> None:
    assert result_rows(_result_of(Scene())) == ()
    panel = ObjectPanel()
    panel.sync((), frozenset())
    assert panel.rows == () and panel.hit(790, 20, SIZE) is None
    assert panel.quads(SIZE).shape == (0, 13)


def test_tab_shows_each_alone_then_all_again() -> None:
    ids, hidden, seen = [3, 5, 9], frozenset(), []
    for _ in range(4):
        hidden = next_alone(ids, hidden)
        seen.append(sorted(hidden))
    assert seen == [[5, 9], [3, 9], [3, 5], []]
    assert next_alone(ids, frozenset({3})) == {5, 9}  # from a chosen set: the first alone
    assert next_alone([4], frozenset()) == {4} - {4}  # one object: it alone is all of them
    assert next_alone([], frozenset()) == frozenset()


def test_what_stays_hidden_when_a_new_result_arrives() -> None:
    # hidden objects that still exist stay hidden, new ones are shown
    assert kept_hidden(frozenset({1}), frozenset({0, 2}), [0, 1, 2, 3]) == {1}
    # a hidden object the result lacks stays hidden (a playback step before it was made)
    assert kept_hidden(frozenset({1, 2}), frozenset({0}), [0, 2]) == {1, 2}
    # every object that was shown is gone: all are shown again
    assert kept_hidden(frozenset({0}), frozenset({1}), [0, 2]) == frozenset()
    # all hidden on purpose (nothing was shown): they stay hidden
    assert kept_hidden(frozenset({0, 1}), frozenset(), [0, 1]) == {0, 1}


def test_visible_objects_leave_out_the_hidden_ones() -> None:
    objects = [(0, "a", "A"), (1, "b", "B"), (2, "c", "C")]
    assert visible_objects(objects, frozenset({1})) == [(0, "a", "A"), (2, "c", "C")]
    assert visible_objects(objects, frozenset({0, 1, 2})) == []


def _panel(count: int, current: int = 0) -> ObjectPanel:
    panel = ObjectPanel()
    panel.sync([ObjectRow(i, f"o{i}", 4, 4, current=i == current) for i in range(count)],
               frozenset({2}))
    return panel


def _row_y(panel: ObjectPanel, line: int) -> float:
    """Framebuffer y of the middle of the ``line``-th drawn row (0 = the header)."""
    _, y, _, row_height = panel.frame(SIZE)
    return y + 6 + (line + 0.5) * row_height


def test_clicks_hit_rows_and_header_buttons() -> None:
    panel = _panel(4)
    x, _, width, _ = panel.frame(SIZE)
    assert panel.hit(x + 20, _row_y(panel, 1), SIZE) == Hit(0, "current")
    assert panel.hit(x + 20, _row_y(panel, 3), SIZE) == Hit(2, "toggle")
    assert panel.hit(x + 20, _row_y(panel, 0), SIZE) == Hit(-1, "name")
    assert panel.hit(x + width - 8, _row_y(panel, 0), SIZE) == Hit(-1, "none")
    parts = [panel.hit(px, _row_y(panel, 0), SIZE).part for px in range(int(x), int(x + width))]
    assert [part for i, part in enumerate(parts) if i == 0 or parts[i - 1] != part] == [
        "name", "all", "name", "none"]  # the header's two buttons, right-aligned
    assert panel.hit(x - 5, _row_y(panel, 1), SIZE) is None  # left of the panel
    assert panel.hit(x + 20, _row_y(panel, 5), SIZE) is None  # below the last row


def test_the_panel_sits_where_the_window_puts_it() -> None:
    panel = _panel(3)
    first = panel.hit(700, _row_y(panel, 1), SIZE)
    panel.top = 200.0
    assert panel.hit(700, _row_y(panel, 1), SIZE) == first == Hit(0, "current")
    assert panel.hit(700, 100.0, SIZE) is None


def test_a_long_list_scrolls_within_its_length() -> None:
    panel = _panel(100)
    fitting = panel.fitting_rows(SIZE)
    assert 10 < fitting < 100
    assert panel.shown_rows(SIZE) == range(0, fitting)
    panel.scroll(5, SIZE)
    assert panel.shown_rows(SIZE) == range(5, 5 + fitting)
    assert panel.hit(700, _row_y(panel, 1), SIZE) == Hit(5, "toggle")
    panel.scroll(1000, SIZE)
    assert panel.shown_rows(SIZE) == range(100 - fitting, 100)
    panel.scroll(-1000, SIZE)
    assert panel.shown_rows(SIZE).start == 0
    assert panel.fitting_rows((800, 10)) == 1  # a tiny window still shows one row


def test_quads_draw_a_box_per_object_ticked_or_not() -> None:
    panel = _panel(4)
    quads = panel.quads(SIZE)
    solid = quads[:, 11]  # the palette slot of each quad
    assert int((solid == 14).sum()) == 3  # objects 0 (current), 1 and 3 ticked
    assert int((solid == 13).sum()) == 1  # object 2 hidden
    assert int((solid == 8).sum()) == 1  # the panel's box
    assert np.all(quads[:, 0] >= panel.frame(SIZE)[0])
    state = panel.state()
    panel.current_hidden = True  # the current object unticked too
    solid = panel.quads(SIZE)[:, 11]
    assert int((solid == 14).sum()) == 2 and int((solid == 13).sum()) == 2
    assert panel.state() != state


def test_the_row_under_the_pointer_is_highlighted_when_a_click_would_toggle_it() -> None:
    panel = _panel(4)
    x = panel.frame(SIZE)[0] + 20
    plain = panel.quads(SIZE)
    panel.point_at(panel.hit(x, _row_y(panel, 3), SIZE))
    assert panel.hover == 2
    lit = panel.quads(SIZE)
    assert len(lit) == len(plain) + 1 and int((lit[:, 11] == 15).sum()) == 1
    row = lit[lit[:, 11] == 15][0]
    assert row[1] <= _row_y(panel, 3) <= row[1] + row[6]  # the box spans that row
    panel.point_at(panel.hit(x, _row_y(panel, 1), SIZE))  # the current object toggles too
    assert panel.hover == 0
    for over in (_row_y(panel, 0), _row_y(panel, 9)):
        panel.point_at(panel.hit(x, over, SIZE))  # the header, off the panel
        assert panel.hover is None
    panel.hover = 3
    panel.sync(panel.rows[:2], frozenset())  # a run with fewer objects
    assert panel.hover is None
