"""The mesh on screen (over EGL): which mesh of a result is drawn, and its framing."""

from __future__ import annotations

import threading
import time
from types import SimpleNamespace

import pytest

import livemod.viewer.display as display_module
import livemod.viewer.uploads as uploads
from livemod.dlfl import mesh_arrays
from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import cube, octahedron, tetrahedron, torus
from livemod.viewer.camera import Camera
from livemod.viewer.display import MeshDisplay
from livemod.viewer.look import Look
from livemod.viewer.measure import WholeMeshMeasurer
from livemod.viewer.objects import SceneObjects
from livemod.viewer.picking import Picking
from livemod.viewer.runs import RunTracker

from .conftest import OFFSCREEN_SIZE


def _display(renderer, picks: Selection | None = None) -> tuple[MeshDisplay, Camera, list[str]]:
    camera, said = Camera(), []
    objects = SceneObjects(RunTracker(), Look(), said.append, renderer.set_others)
    picking = Picking(lambda: None, print, picks)
    display = MeshDisplay(renderer, camera, WholeMeshMeasurer(), picking,
                          objects, Look(), lambda: OFFSCREEN_SIZE, said.append)
    return display, camera, said


def _result(arrays, status="ok", partial=None, preview=None) -> SimpleNamespace:
    error = None if status == "ok" else SimpleNamespace(message="ValueError: no")
    return SimpleNamespace(run_id=1, status=status, arrays=arrays, partial=partial,
                           preview=preview, error=error, others=None, other_objects=())


def test_a_result_shows_its_mesh_framed_once(offscreen) -> None:
    renderer = offscreen.renderer
    display, camera, _ = _display(renderer)
    good = mesh_arrays(cube())
    display.show(_result(good))
    assert renderer.arrays is good and display.fit_bounds is not None
    camera.orbit(30.0, 0.0)
    turned = camera.copy()
    display.show(_result(mesh_arrays(cube())))  # the same bounds: the camera stays
    assert camera.yaw == turned.yaw and camera.distance == turned.distance
    preview = mesh_arrays(octahedron())
    shown = renderer.arrays
    display.show(_result(shown, preview=preview))  # posted again with its preview
    assert renderer.arrays is shown and renderer.preview is preview
    display.show(_result(None))  # the script left no mesh
    assert renderer.arrays is None


def test_showing_a_mesh_uploads_its_selection_flags_once(
        offscreen, monkeypatch: pytest.MonkeyPatch) -> None:
    renderer = offscreen.renderer
    picks = Selection(faces=(2,), vertices=(0, 1))
    display, _, _ = _display(renderer, picks)
    flagged: list[tuple[int, ...]] = []
    real = uploads.MeshGPU.set_flags

    def counted(self, face, edge, vertex) -> None:
        flagged.append(tuple(int(f.sum()) for f in (face, edge, vertex)))
        real(self, face, edge, vertex)

    monkeypatch.setattr(uploads.MeshGPU, "set_flags", counted)
    renderer.set_selection(picks)  # as the window hands over every pick
    assert flagged == []  # nothing uploaded yet
    display.show(_result(mesh_arrays(cube())))
    assert flagged == [(1, 0, 2)]  # once, although the upload and the display hand it over
    renderer.set_selection(Selection(edges=(3,)))
    assert flagged[1:] == [(0, 1, 0)]  # a new selection is uploaded again


def test_e_shows_the_failed_runs_mesh_and_back(offscreen) -> None:
    renderer = offscreen.renderer
    display, _, said = _display(renderer)
    display.toggle_partial(None)
    assert said == ["no failed run to show: E shows the mesh a failed run left"]
    good, partial = mesh_arrays(cube()), mesh_arrays(tetrahedron())
    failed = _result(good, "error", partial=partial)
    display.show(failed)
    assert renderer.arrays is good  # the last good mesh stays
    display.toggle_partial(failed)
    assert renderer.arrays is partial and display.show_partial
    display.toggle_partial(failed)
    assert renderer.arrays is good and said[1:] == [
        "showing the mesh as the failed run left it", "showing the last good mesh"]
    display.forget()
    assert not display.show_partial and display.fit_bounds is None


def test_a_big_mesh_is_prepared_off_the_thread_and_uploaded_over_frames(
        offscreen, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(display_module, "PREPARED_CORNERS", 100)
    monkeypatch.setattr(uploads, "SLICE_BYTES", 8192)
    renderer = offscreen.renderer
    display, camera, _ = _display(renderer)
    try:
        small = mesh_arrays(cube())                    # 24 corners: at once
        display.show(_result(small))
        assert renderer.arrays is small and not display.pending
        big = mesh_arrays(torus(30, 20))               # 2,400 corners: over frames
        display.show(_result(big))
        assert display.content[0] is big and display.pending and renderer.arrays is small
        assert "livemod-buffers" in {thread.name for thread in threading.enumerate()}
        frames, deadline = 0, time.monotonic() + 30
        while display.pending and time.monotonic() < deadline:
            assert renderer.arrays is small             # the old mesh until the new is whole
            display.advance()
            frames += 1
        assert renderer.arrays is big and frames > 2
        assert display.fit_bounds is not None and display.fit_bounds[1][0] > 2.0
        # a newer result supersedes one still on its way
        display.show(_result(mesh_arrays(torus(20, 20))))
        newest = mesh_arrays(octahedron())
        display.show(_result(newest))
        assert renderer.arrays is newest and not display.pending
        for _ in range(20):
            display.advance()
        assert renderer.arrays is newest
    finally:
        display.close()
