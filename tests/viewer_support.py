"""Driving a headless LiveViewer in tests."""

from __future__ import annotations

import time

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
    """A session's playback controls that record the calls they get, in order."""

    def __init__(self) -> None:
        self.calls: list[tuple] = []

    def __getattr__(self, name: str):  # noqa: ANN204
        if name.startswith("_"):
            raise AttributeError(name)
        return lambda *args: self.calls.append((name, *args))
