"""Driving a headless LiveViewer in tests, and what several viewer test modules share."""

from __future__ import annotations

import dataclasses
import subprocess
import sys
import time
from pathlib import Path

import moderngl
import numpy as np

from livemod.dlfl import from_polygons, mesh_arrays
from livemod.runner.playback import PlaybackState, PlaybackView
from livemod.viewer.window import run_frames


def frames_until(viewer, done, timeout: float = 30.0) -> None:  # noqa: ANN001
    """Run ``viewer``'s frames (5 ms apart) until ``done(viewer)`` holds; fail the
    test after ``timeout`` seconds."""
    deadline = time.monotonic() + timeout

    def stop(v) -> bool:  # noqa: ANN001
        time.sleep(0.005)
        return done(v) or time.monotonic() > deadline

    run_frames(viewer, until=stop)
    assert done(viewer), "timed out waiting for the viewer"


def press_key(viewer, name: str, shift: bool = False, ctrl: bool = False,  # noqa: ANN001
              release: bool = True) -> None:
    """Press (and let go of) key ``name`` through the window's own key handling, as
    the toolkit sends it (the headless backend has no key codes: the name stands
    for its code)."""
    from moderngl_window.context.base.keys import KeyModifiers

    modifiers = KeyModifiers()
    modifiers.shift, modifiers.ctrl = shift, ctrl
    viewer._key_names[name] = name
    viewer.on_key_event(name, viewer.wnd.keys.ACTION_PRESS, modifiers)
    if release:
        viewer.on_key_event(name, viewer.wnd.keys.ACTION_RELEASE, modifiers)


class FakePlayback:
    """A session's playback controls that record the calls they get, in order, and
    answer as told: ``coming[name]`` (True unless set) says whether the call's result
    is on its way; the rate halves and doubles between 0.25 and 64."""

    def __init__(self) -> None:
        self.calls: list[tuple] = []
        self.coming: dict[str, bool] = {}
        self.state = PlaybackState.FINISHED
        self.play_rate = 2.0

    @property
    def playback(self) -> PlaybackView:
        return PlaybackView(self.state, None, self.play_rate)

    def _call(self, name: str, *args: object) -> bool:
        self.calls.append((name, *args))
        return self.coming.get(name, True)

    def faster(self) -> float:
        self.play_rate = min(self.play_rate * 2, 64.0)
        return self.play_rate

    def slower(self) -> float:
        self.play_rate = max(self.play_rate / 2, 0.25)
        return self.play_rate

    def toggle_play(self) -> bool:
        return self._call("toggle_play")

    def play(self, rate: float | None = None) -> bool:
        return self._call("play", rate)

    def pause(self) -> bool:
        return self._call("pause")

    def resume(self) -> bool:
        return self._call("resume")

    def run_to_end(self) -> bool:
        return self._call("run_to_end")

    def step_forward(self) -> bool:
        return self._call("step_forward")

    def step_back(self) -> bool:
        return self._call("step_back")

    def goto_step(self, k: int) -> bool:
        return self._call("goto_step", k)

    def cancel(self) -> bool:
        return self._call("cancel")

    def reload(self) -> None:
        self._call("reload")



# the 2 x 2 x 2 box around the origin, as polygons
BOX_POSITIONS = [(1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
                 (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1)]
BOX_FACES = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3),
             (7, 6, 5, 4)]


def cube_with(bad: dict[int, tuple[float, float, float]]):
    """The arrays of the 2-unit cube with the positions of vertices ``bad`` replaced."""
    arrays = mesh_arrays(from_polygons(BOX_POSITIONS, BOX_FACES))
    positions = np.array(arrays.positions)
    for vertex, position in bad.items():
        positions[vertex] = position
    return dataclasses.replace(arrays, positions=positions)


def gl_objects(value, seen: set[int] | None = None) -> list:
    """Every moderngl object reachable from ``value``'s attributes (recursively)."""
    seen = set() if seen is None else seen
    if id(value) in seen or isinstance(value, str | bytes | np.ndarray | int | float):
        return []
    seen.add(id(value))
    kinds = (moderngl.Buffer, moderngl.VertexArray, moderngl.Texture, moderngl.Program,
             moderngl.Framebuffer, moderngl.Renderbuffer)
    if isinstance(value, kinds):
        found = [value]
        if isinstance(value, moderngl.Framebuffer) and \
                not isinstance(value.mglo, moderngl.InvalidObject):
            found += [a for a in (*value.color_attachments, value.depth_attachment) if a]
        return found
    if isinstance(value, dict):
        items = list(value.values())
    elif isinstance(value, list | tuple):
        items = list(value)
    elif hasattr(value, "__dict__") and type(value).__module__.startswith("livemod.viewer"):
        items = [v for k, v in vars(value).items() if k != "ctx"]
    else:
        return []
    return [obj for item in items for obj in gl_objects(item, seen)]


def run_probe(module: str, probe: str, script: Path) -> str:
    """Run ``tests.<module>.<probe>(script)`` in a fresh Python process (GLX and EGL
    contexts do not mix in one process, and an X error ends the process); fail the
    test when it fails. Returns what it printed."""
    root = Path(__file__).resolve().parent.parent
    code = (f"import sys; sys.path.insert(0, {str(root)!r}); "
            f"from tests.{module} import {probe}; {probe}({str(script)!r})")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=90, cwd=root)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout
