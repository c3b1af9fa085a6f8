"""Pictures of meshes in notebooks, drawn by a renderer found outside the library.

IPython asks an object it displays for a PNG through its ``_repr_png_`` method;
:class:`~livemod.dlfl.mesh.Mesh` and :class:`~livemod.dlfl.scene.Scene` answer
with :func:`picture_png`. The library draws nothing itself (it depends on numpy
only, and imports nothing of GL): a renderer registers here with
:func:`register_picture_renderer`. livemod's viewer registers its headless one
when :data:`RENDERER_MODULE` is imported, and :func:`picture_png` imports that
module by name the first time a picture is asked for. Without it (moderngl not
installed), or when it cannot draw (no offscreen GL), the answer is None and
IPython shows the text repr.
"""

from __future__ import annotations

import contextlib
import importlib
from collections.abc import Callable

PictureRenderer = Callable[[object], "bytes | None"]

# the module that registers livemod's own renderer when imported (only by name:
# the library does not depend on it)
RENDERER_MODULE = "livemod.viewer.pictures"

_registered: dict[str, PictureRenderer | None] = {}


def register_picture_renderer(render: PictureRenderer | None) -> None:
    """Make ``render`` the renderer of :func:`picture_png` (None: none).

    ``render(model)`` takes a mesh, a scene or a run's result and returns PNG
    bytes, or None when it cannot draw.
    """
    _registered["png"] = render


def picture_png(model: object) -> bytes | None:
    """PNG bytes of ``model`` from the registered renderer, imported from
    :data:`RENDERER_MODULE` the first time; None when there is none."""
    if "png" not in _registered:
        with contextlib.suppress(ImportError):  # no moderngl: no pictures
            importlib.import_module(RENDERER_MODULE)  # registers itself
        _registered.setdefault("png", None)  # looked once, for good or ill
    render = _registered["png"]
    return None if render is None else render(model)
