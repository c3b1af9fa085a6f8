"""The window's smoothed preview (livemod.viewer.smoothing): asked for when shown,
of every object drawn, at the density the keys set, and what the HUD says."""

from __future__ import annotations

import io
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import pytest

from livemod.runner.preview import DEFAULT_TRIANGLE_BUDGET, GPU_TRIANGLE_BUDGET, Preview
from livemod.viewer.hud import hud_lines
from livemod.viewer.smoothing import triangle_budget
from livemod.viewer.window import LiveViewer, ViewOptions, close_viewer, create_viewer

from .viewer_support import frames_until, press_key

TWO_OBJECTS = "load('torus')\nload('cube')\n"   # the cube current, the torus beside it


@contextmanager
def opened(script: Path) -> Iterator[LiveViewer]:
    viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(160, 120),
                                       samples=0, vsync=False, echo=io.StringIO()))
    try:
        frames_until(viewer, lambda v: v.result is not None and v.renderer.arrays is not None)
        yield viewer
    finally:
        close_viewer(viewer)


def _preview(viewer: LiveViewer) -> Preview:
    shown = viewer.renderer.preview
    assert isinstance(shown, Preview)
    return shown


def _hud(viewer: LiveViewer) -> list[str]:
    return [line for line, _ in hud_lines(viewer.view_state())]


def _arrived(description: str):  # noqa: ANN202
    def done(viewer: LiveViewer) -> bool:
        shown = viewer.renderer.preview
        return isinstance(shown, Preview) and shown.description == description \
            and not viewer.smoothing.updating
    return done


def test_the_preview_is_asked_for_when_shown_and_covers_every_object(tmp_path: Path) -> None:
    script = tmp_path / "two.py"
    script.write_text(TWO_OBJECTS)
    with opened(script) as viewer:
        frames_until(viewer, lambda v: v.runs.result.others is not None)
        assert viewer.renderer.preview is None and viewer.smoothing.hud_line() == ""
        press_key(viewer, "P")
        frames_until(viewer, _arrived("patches, density 4"))
        made = _preview(viewer)
        # the cube's 24 corners first, then the torus's 8 x 6 x 4, 32 triangles each
        assert made.parts == (24 * 32, 192 * 32) and made.total == 216
        assert "preview: patches, density 4" in _hud(viewer)
        press_key(viewer, "TAB")                    # the torus alone... is the other one
        press_key(viewer, "A")                      # the others off: none beside the cube
        frames_until(viewer, lambda v: len(_preview(v).parts) == 1)
        assert _preview(viewer).total == 24


def test_the_density_and_mode_keys_ask_for_another_preview(tmp_path: Path) -> None:
    script = tmp_path / "cube.py"
    script.write_text("load('cube')\n")
    with opened(script) as viewer:
        press_key(viewer, "PAGE_UP")                # shows the preview too
        assert viewer.style.preview
        frames_until(viewer, _arrived("patches, density 5"))
        assert len(_preview(viewer).surface.triangles) == 24 * 2 * 25
        press_key(viewer, "PAGE_DOWN")
        press_key(viewer, "PAGE_DOWN")
        frames_until(viewer, _arrived("patches, density 3"))
        press_key(viewer, "P", shift=True)
        frames_until(viewer, _arrived("Catmull-Clark, 2 levels"))
        press_key(viewer, "P", shift=True)
        frames_until(viewer, _arrived("patches, density 3"))
        echoed = viewer.options.echo.getvalue()  # type: ignore[union-attr]
        assert "preview: patches, density 5" in echoed and "preview: catmull-clark" in echoed


def test_a_new_run_keeps_the_old_preview_until_its_own_comes(tmp_path: Path) -> None:
    script = tmp_path / "cube.py"
    script.write_text("load('cube')\n")
    with opened(script) as viewer:
        press_key(viewer, "P")
        frames_until(viewer, _arrived("patches, density 4"))
        old = _preview(viewer)
        script.write_text("load('tetrahedron')\n")
        viewer.session.reload()  # type: ignore[union-attr]
        frames_until(viewer, lambda v: v.renderer.arrays.counts == (4, 6, 4))
        assert viewer.renderer.preview is old or _preview(viewer).total == 12
        frames_until(viewer, lambda v: _preview(v).total == 12 and not v.smoothing.updating)
        assert "preview: patches, density 4" in _hud(viewer)


@pytest.mark.parametrize("name, budget", [
    ("llvmpipe (LLVM 15.0.6, 256 bits)", DEFAULT_TRIANGLE_BUDGET),
    ("softpipe", DEFAULT_TRIANGLE_BUDGET),
    ("NVIDIA GeForce RTX 3060/PCIe/SSE2", GPU_TRIANGLE_BUDGET),
])
def test_the_budget_follows_the_gl_renderer(name: str, budget: int) -> None:
    assert triangle_budget(name) == budget
