"""livemod.dlfl.display: meshes and scenes show as pictures in Jupyter, while the
library itself imports nothing of GL."""

from __future__ import annotations

import io
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from livemod.dlfl import Mesh, Scene, display
from livemod.dlfl.shapes import cube
from livemod.viewer.pictures import picture

ROOT = Path(__file__).resolve().parents[1]


def _python(code: str) -> str:
    """Run ``code`` in a fresh interpreter on this tree; its stdout."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          env=env, timeout=120, check=True)
    return done.stdout.strip()


def test_importing_the_library_and_making_meshes_imports_nothing_of_gl():
    loaded = _python(
        "import sys\n"
        "import livemod.dlfl\n"
        "from livemod.dlfl import *\n"
        "from livemod.dlfl.shapes import cube\n"
        "repr(cube())\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('moderngl', 'glcontext',"
        " 'moderngl_window', 'glfw') or m.startswith(('livemod.viewer', 'livemod.runner'))))\n")
    assert loaded == "[]"


def test_a_mesh_asks_the_viewer_for_its_picture_lazily():
    shown = _python(
        "import sys\n"
        "from livemod.dlfl.shapes import cube\n"
        "png = cube()._repr_png_()\n"
        "print(png[:8] == b'\\x89PNG\\r\\n\\x1a\\n', 'livemod.viewer.pictures' in sys.modules)\n")
    assert shown == "True True"


def test_without_moderngl_there_is_no_picture_and_no_error():
    shown = _python(
        "import sys\n"
        "sys.modules['moderngl'] = None  # as if it were not installed\n"
        "from livemod.dlfl.shapes import cube\n"
        "mesh = cube()\n"
        "print(mesh._repr_png_(), repr(mesh))\n")
    assert shown == "None <Mesh V=8 E=12 F=6>"


def test_the_picture_is_the_viewer_s_picture_of_the_mesh():
    mesh = cube()
    shown = np.asarray(Image.open(io.BytesIO(mesh._repr_png_())).convert("RGB"))
    assert np.array_equal(shown, picture(mesh).image)


def test_a_scene_and_a_registered_renderer(monkeypatch: pytest.MonkeyPatch):
    seen: list[object] = []
    monkeypatch.setattr(display, "_registered", {})
    display.register_picture_renderer(lambda model: seen.append(model) or b"png")
    scene = Scene()
    scene.add(cube(), "cube")
    assert scene._repr_png_() == b"png" and Mesh()._repr_png_() == b"png"
    assert seen[0] is scene and isinstance(seen[1], Mesh)
    display.register_picture_renderer(None)
    assert scene._repr_png_() is None


def test_a_renderer_module_that_cannot_be_imported_gives_no_picture(
        monkeypatch: pytest.MonkeyPatch):
    monkeypatch.setattr(display, "_registered", {})
    monkeypatch.setattr(display, "RENDERER_MODULE", "livemod.no_such_module")
    assert cube()._repr_png_() is None
    assert display._registered == {"png": None}  # looked once
