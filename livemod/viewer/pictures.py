"""Pictures of models in memory: what a notebook shows and a snapshot test compares.

A *model* is a :class:`~livemod.dlfl.mesh.Mesh`, a
:class:`~livemod.dlfl.arrays.MeshArrays`, a :class:`~livemod.dlfl.scene.Scene` (its
current object and the others beside it, as ``livemod render`` draws a script's
scene) or a run's :class:`~livemod.runner.results.RunResult` (its mesh, or the mesh a
failed run left, and its other objects). Models are drawn headless by the renderer
of ``livemod render`` (:mod:`.headless`), framed and lit as it frames them, into
offscreen targets kept for the rest of the process, one per size and MSAA level:
making a GL context is the slow part of a first picture.

Importing this module registers :func:`png_of` as the picture renderer of
:mod:`livemod.dlfl.display`, so that meshes, scenes and results show as pictures in
Jupyter.
"""

from __future__ import annotations

import atexit
import io
import threading
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from livemod.dlfl.arrays import MeshArrays, concatenate_arrays, mesh_arrays
from livemod.dlfl.display import register_picture_renderer
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.scene import Scene

# GL at import: where moderngl is missing, the import fails and the library's
# lookup (livemod.dlfl.display) finds no renderer
from .headless import Drawn, Framing, NoOffscreenGL, Offscreen, Orbit, render_frames
from .renderer import Style

PICTURE_SIZE = (480, 360)  # a notebook picture's (width, height) in pixels
TURNTABLE_SIZE = (320, 320)
TURNTABLE_FRAMES = 36


@dataclass(frozen=True)
class ModelParts:
    """What a picture of a model draws.

    Attributes:
        arrays: the current object (None: none, or it has no vertices).
        others: the other objects joined, drawn beside it (None: none).
    """

    arrays: MeshArrays | None
    others: MeshArrays | None

    @property
    def empty(self) -> bool:
        """True when there is nothing to draw."""
        return self.arrays is None and self.others is None

    def joined(self) -> MeshArrays | None:
        """Every object drawn as one snapshot (None when nothing is drawn)."""
        parts = [part for part in (self.arrays, self.others) if part is not None]
        if len(parts) < 2:
            return parts[0] if parts else None
        return concatenate_arrays(parts)


def model_parts(model: object) -> ModelParts:
    """The :class:`ModelParts` of a mesh, a MeshArrays, a scene or a run's result.

    Raises:
        InvalidArgumentError: ``model`` is none of those.
    """
    from livemod.runner.results import RunResult, snapshot_others, snapshot_scene

    if isinstance(model, Mesh):
        return ModelParts(_drawn(mesh_arrays(model)), None)
    if isinstance(model, MeshArrays):
        return ModelParts(_drawn(model), None)
    if isinstance(model, Scene):
        return ModelParts(_drawn(snapshot_scene(model)), snapshot_others(model))
    if isinstance(model, RunResult):
        mesh = model.arrays if model.arrays is not None else model.partial
        return ModelParts(_drawn(mesh), model.others)
    raise InvalidArgumentError(f"a picture is of a Mesh, MeshArrays, Scene or RunResult, "
                               f"not {type(model).__name__}")


def _drawn(arrays: MeshArrays | None) -> MeshArrays | None:
    """``arrays``, or None when it has no vertices (nothing to draw or frame)."""
    return arrays if arrays is not None and len(arrays.positions) else None


@dataclass(frozen=True)
class View:
    """Where a picture is taken from and what it draws.

    Attributes:
        size: ``(width, height)`` in pixels.
        elevation, yaw: the camera's degrees above the horizon and around the up
            axis (``livemod render``'s ``--elevation`` and ``--yaw``).
        style: what is drawn (None: ``livemod render``'s default).
        ortho: an orthographic projection (``--ortho``).
        framing: the border and zoom (``--margin``, ``--zoom``; None: the default).
    """

    size: tuple[int, int] = PICTURE_SIZE
    elevation: float = 25.0
    yaw: float = 30.0
    style: Style | None = None
    ortho: bool = False
    framing: Framing | None = None

    def orbit(self, frames: int = 1) -> Orbit:
        """The :class:`~.headless.Orbit` of ``frames`` turntable views from here."""
        return Orbit(frames, self.elevation, self.yaw, self.ortho, self.framing or Framing())


def render_model(model: object, view: View | None = None, frames: int = 1,
                 ) -> list[np.ndarray]:
    """``frames`` turntable images of ``model`` (a model or its :class:`ModelParts`;
    one frame: a still from ``view``, by default a :class:`View`), each
    ``(H, W, 3)`` uint8 (``(H, W, 4)`` for a transparent background), framed for
    the whole turn as ``livemod render --turntable`` frames it. A still is drawn
    with 4x MSAA, a turntable without (as ``livemod render`` does).

    Raises:
        InvalidArgumentError: ``model`` is not a model (see :func:`model_parts`).
        ValueError: a size this GL cannot make.
        NoOffscreenGL: no offscreen GL context could be made.
    """
    parts = model if isinstance(model, ModelParts) else model_parts(model)
    view = view or View()
    with GL_LOCK:
        target = kept_target(view.size, 4 if frames == 1 else 0)
        try:
            return render_frames(target, Drawn(parts.arrays, others=parts.others),
                                 view.orbit(frames), view.style or Style())
        finally:  # the model is not kept alive on the GPU between pictures
            target.activate()
            target.renderer.set_mesh(None)


@dataclass(frozen=True, eq=False)
class Picture:
    """One rendered picture; Jupyter shows it as a PNG.

    Attributes:
        image: ``(H, W, 3)`` uint8 RGB (``(H, W, 4)`` RGBA), row 0 at the top.
    """

    image: np.ndarray

    def _repr_png_(self) -> bytes:
        return png_bytes([self.image])

    def save(self, path: str | Path) -> Path:
        """Write the picture to ``path`` (.png, .gif or .webp), atomically."""
        from .imagefiles import write_images

        return write_images(str(path), [self.image])[0]


@dataclass(frozen=True, eq=False)
class Animation:
    """Frames played in a loop; Jupyter shows them as an animated PNG.

    Attributes:
        frames: each ``(H, W, 3)`` uint8 (or RGBA), all one size.
        fps: frames per second.
    """

    frames: tuple[np.ndarray, ...]
    fps: float = 25.0

    def _repr_png_(self) -> bytes:
        return png_bytes(self.frames, self.fps)

    def save(self, path: str | Path) -> list[Path]:
        """Write the frames where ``livemod render -o path`` would (a .gif, .webp or
        .mp4, a folder, or a PNG pattern), atomically; the paths written."""
        from .imagefiles import write_images

        return write_images(str(path), self.frames, self.fps)


def picture(model: object | ModelParts, *, size: tuple[int, int] = PICTURE_SIZE, elevation: float = 25.0,
            yaw: float = 30.0, style: Style | None = None) -> Picture:
    """A picture of ``model`` as ``livemod render`` draws it (see :func:`render_model`)."""
    return Picture(render_model(model, View(size, elevation, yaw, style))[0])


def turntable(model: object, *, frames: int = TURNTABLE_FRAMES,
              size: tuple[int, int] = TURNTABLE_SIZE, fps: float = 25.0,
              elevation: float = 20.0, yaw: float = 30.0,
              style: Style | None = None) -> Animation:
    """A turntable of ``model``: ``frames`` views evenly spaced around the up axis,
    as ``livemod render --turntable`` draws them, to show inline or save.

    Raises:
        InvalidArgumentError: ``model`` is not a model, or ``frames`` is below 1.
        ValueError, NoOffscreenGL: see :func:`render_model`.
    """
    if frames < 1:
        raise InvalidArgumentError(f"a turntable needs at least one frame, not {frames}")
    images = render_model(model, View(size, elevation, yaw, style), frames)
    return Animation(tuple(images), fps)


def png_bytes(images: tuple[np.ndarray, ...] | list[np.ndarray], fps: float = 25.0) -> bytes:
    """``images`` as one PNG: a still for one image, an animated PNG (looping at
    ``fps``) for several."""
    from PIL import Image

    data = io.BytesIO()
    first, *rest = (Image.fromarray(image) for image in images)
    if rest:
        first.save(data, format="PNG", save_all=True, append_images=rest, loop=0,
                   duration=round(1000.0 / fps))
    else:
        first.save(data, format="PNG")
    return data.getvalue()


def png_of(model: object) -> bytes | None:
    """The PNG of :func:`picture` (the hook :mod:`livemod.dlfl.display` calls); None
    when there is nothing to draw, or no offscreen GL (said once, as a warning)."""
    parts = model_parts(model)
    if parts.empty:
        return None
    try:
        return picture(parts)._repr_png_()
    except NoOffscreenGL as exc:
        if not _NO_GL_SAID:
            _NO_GL_SAID.append(True)
            warnings.warn(f"livemod draws no pictures here: {exc}", RuntimeWarning,
                          stacklevel=2)
        return None


_NO_GL_SAID: list[bool] = []


# -- the offscreen targets kept for the process --------------------------------------

GL_LOCK = threading.RLock()  # GL calls go to one current context at a time
_TARGETS: dict[tuple[tuple[int, int], int], Offscreen] = {}


def kept_target(size: tuple[int, int], samples: int) -> Offscreen:
    """The kept target of ``size`` and ``samples`` (made on first use, with a GL
    context of its own: renderers bind their buffers to the context's shared
    binding points, so two in one context would draw with each other's), for
    drawing pictures in memory. The caller holds :data:`GL_LOCK` while it draws.

    Raises:
        ValueError: a size or MSAA level this GL cannot make.
        NoOffscreenGL: no offscreen GL context could be made.
    """
    key = ((int(size[0]), int(size[1])), samples)
    if key not in _TARGETS:
        _TARGETS[key] = Offscreen(key[0], samples)
    return _TARGETS[key]


@atexit.register
def release_targets() -> None:
    """Free the kept targets and their GL contexts (done at exit)."""
    with GL_LOCK:
        for target in _TARGETS.values():
            target.release()
        _TARGETS.clear()


register_picture_renderer(png_of)
