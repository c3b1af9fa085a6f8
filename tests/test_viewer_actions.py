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


@pytest.fixture
def window(tmp_path: Path, monkeypatch: pytest.MonkeyPatch,
           ) -> Iterator[tuple[LiveViewer, io.StringIO]]:
    # into the test's folder before the session pictures the process (F12 writes its
    # screenshots there): under load a first run may be abandoned, and while it lives
    # every run gives back the folder the session first saw (docs/guide.md)
    monkeypatch.chdir(tmp_path)
    script = tmp_path / "model.py"
    script.write_text("load('cube')\nload('tetrahedron')\nsubdivide('catmull-clark')\n")
    echo = io.StringIO()
    viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(240, 160),
                                       samples=0, vsync=False, echo=echo))
    yield viewer, echo
    close_viewer(viewer)


def test_every_binding_has_a_handler_and_every_handler_a_binding(window) -> None:
    viewer, _ = window
    bound = {binding.action for binding in KEY_BINDINGS}
    assert set(viewer.actions) == bound
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
