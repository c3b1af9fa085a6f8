"""Uploads a slice at a time: drawn once whole, superseded by newer content, and
the old picture kept until then (livemod.viewer.uploads and Renderer.stage)."""

from __future__ import annotations

import numpy as np
import pytest

import livemod.viewer.uploads as uploads
from livemod.dlfl import mesh_arrays
from livemod.dlfl.shapes import cube, torus
from livemod.runner.preview import PreviewRequest, make_preview
from livemod.viewer.geometry import prepare_meshes
from livemod.viewer.headless import Offscreen, framed_camera
from livemod.viewer.renderer import Style


def test_tables_and_buffers_written_in_slices_hold_the_whole(
        offscreen: Offscreen, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(uploads, "SLICE_BYTES", 4096)
    ctx = offscreen.ctx
    values = np.arange(20_000, dtype=np.uint32) * 7
    made: list = []
    steps = uploads.table_steps(ctx, values, "u4", made)
    texture = uploads.finished(steps)
    assert texture.size == (4096, 5) and made == [texture]
    read = np.frombuffer(texture.read(), dtype=np.uint32)
    assert np.array_equal(read[:20_000], values) and not read[20_000:].any()
    points = np.random.default_rng(1).random((5000, 3)).astype(np.float32)
    table = uploads.finished(uploads.table_steps(ctx, points, "f4", made))
    assert np.array_equal(np.frombuffer(table.read(), np.float32).reshape(-1, 3)[:5000], points)
    counted = 0
    steps = uploads.buffer_steps(ctx, points, made)
    while True:
        try:
            next(steps)
            counted += 1
        except StopIteration as done:
            buffer = done.value
            break
    assert counted == -(-points.nbytes // 4096)
    assert np.array_equal(np.frombuffer(buffer.read(), np.float32).reshape(-1, 3), points)
    for obj in made:
        obj.release()


def test_a_staged_mesh_is_drawn_once_all_of_it_is_uploaded(
        offscreen: Offscreen, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(uploads, "SLICE_BYTES", 16_384)
    renderer = offscreen.renderer
    old = mesh_arrays(cube())
    renderer.set_mesh(old)
    camera = framed_camera(old)
    before = offscreen.render(camera, Style())
    new = mesh_arrays(torus(30, 20))
    prepared = prepare_meshes(new)
    renderer.stage(new, prepared=prepared)
    version = renderer.version
    steps = 0
    while not renderer.advance(0.0):            # one step a call
        steps += 1
        assert renderer.uploading and renderer.arrays is old and renderer.version == version
        assert np.array_equal(offscreen.render(camera, Style()), before)
    assert steps > 5
    assert not renderer.uploading and renderer.arrays is new and renderer.version > version
    assert not np.array_equal(offscreen.render(camera, Style()), before)


def test_newer_content_supersedes_an_upload_in_progress(
        offscreen: Offscreen, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(uploads, "SLICE_BYTES", 16_384)
    released: list[object] = []
    real_release = uploads.Upload.abandon

    def abandon(self: uploads.Upload) -> None:
        released.extend(self._made)
        real_release(self)

    monkeypatch.setattr(uploads.Upload, "abandon", abandon)
    renderer = offscreen.renderer
    renderer.set_mesh(mesh_arrays(cube()))
    first, second = mesh_arrays(torus(30, 20)), mesh_arrays(torus(12, 8))
    renderer.stage(first)
    renderer.advance(0.0)
    renderer.advance(0.0)
    renderer.stage(second, make_preview(PreviewRequest((second,))))
    assert len(released) >= 2                   # what the first upload had made: freed
    assert all(obj.mglo is None or type(obj.mglo).__name__ == "InvalidObject"
               for obj in released)
    while not renderer.advance(0.0):
        assert renderer.arrays is not first
    assert renderer.arrays is second and renderer.preview is not None


def test_a_failed_upload_leaves_the_old_mesh_drawn(
        offscreen: Offscreen, monkeypatch: pytest.MonkeyPatch) -> None:
    renderer = offscreen.renderer
    old = mesh_arrays(cube())
    renderer.set_mesh(old)

    def broken(*args, **kwargs):
        raise RuntimeError("no room")
        yield  # (a generator, as the real one)

    monkeypatch.setattr(uploads, "table_steps", broken)
    with pytest.raises(RuntimeError, match="no room"):
        renderer.set_mesh(mesh_arrays(torus(6, 4)))
    assert renderer.arrays is old and not renderer.uploading
