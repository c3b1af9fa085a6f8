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
