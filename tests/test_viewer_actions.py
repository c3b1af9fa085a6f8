"""The action table: every key binding resolves to a handler, which runs."""

from __future__ import annotations

import io
from collections.abc import Iterator
from pathlib import Path

import pytest

from livemod.viewer.actions import check_bindings
from livemod.viewer.controls import KEY_BINDINGS, Binding
from livemod.viewer.window import LiveViewer, ViewOptions, close_viewer, create_viewer

from .viewer_support import frames_until, press_key


def _window_on(script: Path, source: str) -> Iterator[tuple[LiveViewer, io.StringIO]]:
    """A headless window watching ``script`` (written with ``source``) and its echo."""
    script.write_text(source)
    echo = io.StringIO()
    viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(240, 160),
                                       samples=0, vsync=False, echo=echo))
    yield viewer, echo
    close_viewer(viewer)


@pytest.fixture
def window(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
           ) -> Iterator[tuple[LiveViewer, io.StringIO]]:
    # into the test's folder before the session pictures the process (F12 writes its
    # screenshots there): under load a first run may be abandoned, and while it lives
    # every run gives back the folder the session first saw (docs/guide.md)
    monkeypatch.chdir(tmp_path)
    yield from _window_on(tmp_path / "model.py",
                          "load('cube')\nload('tetrahedron')\nsubdivide('catmull-clark')\n")


def test_every_binding_has_a_handler_and_every_handler_a_binding(window) -> None:
    viewer, _ = window
    bound = {binding.action for binding in KEY_BINDINGS}
    unbound = sorted(set(viewer.actions) - bound)
    assert not unbound, (f"actions of window_actions (livemod/viewer/actions.py) no "
                         f"binding of KEY_BINDINGS (livemod/viewer/controls.py) names: {unbound}")
    assert set(viewer.actions) == bound  # (a binding without a handler: refused at opening)
    assert all(callable(handler) for handler in viewer.actions.values())


def test_a_binding_without_a_handler_is_refused_with_its_key() -> None:
    bindings = (Binding("Q", "", "quit", "close"), Binding("F", "ctrl", "labels_faces", "x"))
    check_bindings({"quit": lambda: None, "labels_faces": lambda: None}, bindings)
    with pytest.raises(LookupError, match=r"no handler: Ctrl\+F: labels_faces$"):
        check_bindings({"quit": lambda: None}, bindings)


def test_every_key_runs_through_the_windows_key_handling(window, tmp_path) -> None:
    """Each binding pressed as the toolkit sends it runs its handler (Q last: it
    closes the window)."""
    viewer, echo = window
    frames_until(viewer, lambda v: v.result is not None and not v.waiting)
    ran: list[str] = []
    for action in list(viewer.actions):
        handler = viewer.actions[action]
        viewer.actions[action] = lambda a=action, h=handler: (ran.append(a), h())
    ordered = sorted(KEY_BINDINGS, key=lambda b: b.action == "quit")
    for binding in ordered:
        press_key(viewer, binding.key, shift=binding.modifiers == "shift",
                  ctrl=binding.modifiers == "ctrl")
    assert ran == [binding.action for binding in ordered]
    assert viewer.wnd.is_closing
    assert sorted(p.name for p in tmp_path.glob("model_*.png")) == ["model_000.png",
                                                                    "model_001.png"]


@pytest.fixture
def quad_sphere_window(tmp_path: Path) -> Iterator[tuple[LiveViewer, io.StringIO]]:
    """A window showing the cube after one Catmull-Clark step (24 quads), run."""
    for viewer, echo in _window_on(tmp_path / "sphere.py",
                                   "load('cube')\nsubdivide('catmull-clark')\n"):
        frames_until(viewer, lambda v: v.result is not None and not v.waiting)
        yield viewer, echo


def test_topmods_selection_keys_edit_the_picks_and_echo_them(quad_sphere_window) -> None:
    from livemod.dlfl import selection as rules
    from livemod.dlfl.scene import Selection

    viewer, echo = quad_sphere_window
    arrays = viewer.renderer.arrays
    valence = rules.vertex_valences(arrays)
    # an edge between two valence-4 vertices: its loop closes round the cube (8 edges)
    edge = next(int(e) for e, (u, v) in zip(arrays.edge_ids, arrays.edge_vertices, strict=True)
                if valence[int(arrays.vertex_ids[u])] == valence[int(arrays.vertex_ids[v])] == 4)
    viewer.set_selection(Selection(edges=(edge,)))
    press_key(viewer, "L", shift=True)
    loop = viewer.picking.selection.edges
    assert sorted(loop) == sorted(rules.edge_loop(arrays, edge)) and len(loop) == 8
    assert f"--select edges={','.join(map(str, loop))}" in echo.getvalue()
    press_key(viewer, "ESCAPE")
    viewer.set_selection(Selection(edges=(edge,)))
    press_key(viewer, "P", ctrl=True)
    assert viewer.picking.selection == Selection(faces=tuple(rules.face_loop(arrays, edge)),
                                                 edges=(edge,))
    assert len(viewer.picking.selection.faces) == 8
    viewer.set_selection(Selection(faces=(int(arrays.face_ids[0]),)))
    press_key(viewer, "EQUAL", ctrl=True)
    assert len(viewer.picking.selection.faces) == 5
    press_key(viewer, "MINUS", ctrl=True)
    assert viewer.picking.selection.faces == (int(arrays.face_ids[0]),)
    press_key(viewer, "I", ctrl=True)
    assert len(viewer.picking.selection.faces) == 23
    press_key(viewer, "A", ctrl=True)
    assert len(viewer.picking.selection.faces) == 24
    assert viewer.renderer.selection == viewer.picking.selection  # drawn as picked
