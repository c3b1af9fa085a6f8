"""livemod.view.show: the live window on a model built in Python, without a script.

The window runs in a process of its own; under Xvfb it is a real glfw window, and
what it echoes (each result it takes, as ``livemod view`` says it) reaches this
process's stderr, read with ``capfd``.
"""

from __future__ import annotations

import io
import re
import threading
import time
from pathlib import Path

import pytest

from livemod.dlfl import Scene, mesh_arrays
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.io import save_mesh
from livemod.dlfl.shapes import cube, tetrahedron
from livemod.runner import run_script
from livemod.view import (
    ShownSession,
    WindowUnavailable,
    open_windows,
    show,
    shown_result,
    window_sessions,
)
from livemod.viewer.window import LiveViewer, ViewOptions, close_viewer, create_viewer

from .test_viewer_window import _has_run, _wait, xvfb_display  # noqa: F401  (a fixture)
from .viewer_support import press_key

SMALL = (320, 240)


def _said(capfd: pytest.CaptureFixture[str], pattern: str, timeout: float = 60.0) -> str:
    """What the window process has said on stderr once a line matches ``pattern``."""
    said = ""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        said += capfd.readouterr().err
        if re.search(pattern, said, flags=re.M):
            return said
        time.sleep(0.05)
    raise AssertionError(f"no line matching {pattern!r} in {said!r}")


def _closing_the_first_window(capfd: pytest.CaptureFixture[str], pattern: str,
                              said: list[str]) -> threading.Thread:
    """A thread that closes the first window :func:`show` opens once the window has
    said a line matching ``pattern`` (within 60 s each), putting what it said into
    ``said``: closed earlier, on a loaded machine, it would not have shown anything."""
    def close_it() -> None:
        deadline = time.monotonic() + 60.0
        while not open_windows() and time.monotonic() < deadline:
            time.sleep(0.05)
        try:
            said.append(_said(capfd, pattern))
        finally:
            for window in open_windows():
                window.close()

    closer = threading.Thread(target=close_it, daemon=True)
    closer.start()
    return closer


@pytest.mark.usefixtures("xvfb_display")
def test_a_window_opens_on_a_mesh_takes_updates_and_closes(capfd: pytest.CaptureFixture[str]):
    window = show(cube(), block=False, size=SMALL, title="cube")
    try:
        assert window.is_open and open_windows() == [window]
        _said(capfd, r"^run 1: ok, 0 steps, V=8 E=12 F=6, ")
        window.update(mesh_arrays(tetrahedron()))
        _said(capfd, r"^run 2: ok, 0 steps, V=4 E=6 F=4, ")
    finally:
        window.close()
    assert not window.is_open and open_windows() == [] and window.wait(0)
    with pytest.raises(WindowUnavailable, match="the window of cube was closed"):
        window.update(cube())


@pytest.mark.usefixtures("xvfb_display")
def test_show_blocks_until_the_window_is_closed(capfd: pytest.CaptureFixture[str]):
    scene = Scene()
    scene.add(cube(), "a cube")
    scene.add(tetrahedron(), "a tetrahedron")
    said: list[str] = []
    # the current object, the tetrahedron, is the one counted
    closer = _closing_the_first_window(capfd, r"^run 1: ok, 0 steps, V=4 E=6 F=4, ", said)
    window = show(scene, size=SMALL)  # returns once the thread has closed it
    assert not window.is_open
    closer.join(10.0)
    assert not closer.is_alive() and len(said) == 1


def test_without_a_display_show_says_why_and_leaves_nothing_running(
        monkeypatch: pytest.MonkeyPatch):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    with pytest.raises(WindowUnavailable, match=r"^cannot open a window \(.*\)\. There is "
                                                r"no display"):
        show(cube(), block=False)
    assert open_windows() == []


def test_show_takes_meshes_scenes_and_results_and_refuses_the_rest(tmp_path: Path):
    assert shown_result(cube(), "cube").arrays.counts == (8, 12, 6)
    assert shown_result(cube(), "cube").current_object == (0, "cube")
    scene = Scene()
    scene.add(cube(), "left")
    scene.add(tetrahedron(), "right")
    shown = shown_result(scene, "scene", run_id=3)
    assert shown.run_id == 3 and shown.arrays.counts == (4, 6, 4)
    assert [(oid, name) for oid, name, _ in shown.other_objects] == [(0, "left")]
    script = tmp_path / "model.py"
    script.write_text("from livemod.dlfl import *\nload('cube')\ndual()\n")
    result = run_script(script)
    assert shown_result(result, "x", run_id=5) == _replaced(result, run_id=5)
    with pytest.raises(InvalidArgumentError, match="show takes a Mesh, MeshArrays, Scene or "
                                                   "RunResult, not str"):
        show("cube.obj")


def _replaced(result: object, **fields: object) -> object:
    import dataclasses

    return dataclasses.replace(result, **fields)  # type: ignore[type-var]


def _headless_window(session: ShownSession, echo: io.StringIO) -> LiveViewer:
    """A headless window over ``session``, as the window's process makes it."""
    return create_viewer(ViewOptions("shown", backend="headless", size=SMALL, samples=0,
                                     vsync=False, echo=echo,
                                     session_factory=window_sessions(session, "shown")))


def test_a_script_dropped_on_a_shown_window_runs_as_livemod_view_runs_it(
        monkeypatch: pytest.MonkeyPatch, tmp_path: Path):
    import livemod.viewer.window as window

    made: list[tuple[str, str | None, ViewOptions]] = []

    def sessions(options: ViewOptions):
        return lambda script, mesh: made.append((script, mesh, options)) or "live"

    monkeypatch.setattr(window, "live_sessions", sessions)
    create = window_sessions(ShownSession(shown_result(cube(), "cube")), "shown")
    script = str(tmp_path / "dropped.py")
    assert create(script, None) == "live"
    assert [(s, m, o.script) for s, m, o in made] == [(script, None, script)]


def test_the_window_shows_posted_models_and_has_no_steps_to_play(tmp_path: Path):
    session = ShownSession(shown_result(cube(), "cube"))
    echo = io.StringIO()
    viewer = _headless_window(session, echo)
    try:
        _wait(viewer, _has_run(1))
        assert viewer.result.arrays.counts == (8, 12, 6)
        session.post(shown_result(tetrahedron(), "cube", run_id=2))
        _wait(viewer, _has_run(2))
        assert viewer.result.arrays.counts == (4, 6, 4)
        for key in ("SPACE", "RIGHT", "LEFT", "END", "R"):  # nothing to step through
            press_key(viewer, key)
        _wait(viewer, lambda v: not v.waiting)
        assert viewer.result.run_id == 2 and viewer.result.arrays.counts == (4, 6, 4)
        mesh_file = tmp_path / "dropped.obj"
        save_mesh(cube(), str(mesh_file))
        viewer.on_files_dropped_event(0, 0, [str(mesh_file)])  # a dropped mesh is shown
        _wait(viewer, lambda v: v.result is not None and v.result.arrays.counts == (8, 12, 6))
    finally:
        close_viewer(viewer)
    assert "run 2: ok, 0 steps, V=4 E=6 F=4" in echo.getvalue()
