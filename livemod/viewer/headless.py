"""Offscreen rendering over a standalone EGL context: frames, turntables, files.

Uses the same :class:`Renderer` as the window. On a machine with no GPU, EGL gives
Mesa's llvmpipe; its output is bit-identical across runs.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import moderngl
import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.scene import Selection

from .camera import Camera
from .geometry import sample_points
from .imagefiles import check_output, write_images
from .renderer import Renderer, Style, read_image

if TYPE_CHECKING:
    from livemod.runner.preview import Preview


class NoOffscreenGL(RuntimeError):
    """No standalone GL context could be made (no EGL library, or no GL 3.3)."""


def create_context() -> moderngl.Context:
    """A standalone GL 3.3+ context over EGL (no display needed).

    Raises:
        NoOffscreenGL: EGL or a GL 3.3 driver is missing (the message says what
            to install).
    """
    options: dict = {"backend": "egl", "require": 330}
    try:
        return moderngl.create_standalone_context(**options)
    except Exception as exc:  # moderngl/glcontext raise plain Exceptions here
        raise NoOffscreenGL(
            f"no offscreen GL 3.3 context over EGL ({exc}); headless rendering needs Mesa's "
            f"EGL, e.g. apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri") from exc


class Offscreen:
    """An offscreen target of ``size`` with its own context and renderer.

    Colour is rendered with ``samples``-fold MSAA and resolved into a plain
    framebuffer that :meth:`render` returns as an image. :meth:`render` makes the
    context current first (:meth:`activate`): GL calls go to the context made
    last, and another Offscreen made in the meantime (even one since released)
    would otherwise get them. Code that calls :attr:`renderer` directly calls
    :meth:`activate` first.

    Raises:
        ValueError: a size or MSAA level this GL cannot make (nothing is left open).
        NoOffscreenGL: no context could be made.
    """

    def __init__(self, size: tuple[int, int], samples: int = 4,
                 ctx: moderngl.Context | None = None) -> None:
        self.ctx = ctx if ctx is not None else create_context()
        self.size = (int(size[0]), int(size[1]))
        try:
            _check_target(self.ctx, self.size, samples)
        except ValueError:
            if ctx is None:  # made here: a refused Offscreen leaves no context behind
                self.ctx.release()
            raise
        self.renderer = Renderer(self.ctx)
        self.resolved = self.ctx.framebuffer([self.ctx.renderbuffer(self.size, 4)],
                                             self.ctx.depth_renderbuffer(self.size))
        self.samples = samples
        self.target = self.resolved
        if samples > 0:
            self.target = self.ctx.framebuffer(
                [self.ctx.renderbuffer(self.size, 4, samples=samples)],
                self.ctx.depth_renderbuffer(self.size, samples=samples))

    def render(self, camera: Camera, style: Style, overlay: np.ndarray | None = None,
               ) -> np.ndarray:
        """Draw one frame; returns ``(H, W, 3)`` uint8 RGB, row 0 at the top, or
        ``(H, W, 4)`` RGBA when ``style.background`` is not opaque (a transparent
        background: alpha 0 where nothing is drawn)."""
        self.activate()
        self.renderer.draw(self.target, camera, style)
        if self.samples > 0:
            self.ctx.copy_framebuffer(self.resolved, self.target)
        if overlay is not None:
            self.renderer.draw_overlay(self.resolved, overlay)
        return read_image(self.resolved, style)

    def activate(self) -> None:
        """Make this target's context the one GL calls go to."""
        # moderngl makes a context current only by entering it; leaving it would
        # leave none current, so it is entered and not left
        self.ctx.__enter__()

    def release(self) -> None:
        """Free the context and everything in it."""
        self.ctx.release()


def _check_target(ctx: moderngl.Context, size: tuple[int, int], samples: int) -> None:
    """Raises ValueError when this GL cannot make a ``size`` target with ``samples``."""
    largest = int(ctx.info.get("GL_MAX_RENDERBUFFER_SIZE", 0) or 0)
    if largest and max(size) > largest:
        raise ValueError(f"{size[0]}x{size[1]} is larger than this GL's largest image, "
                         f"{largest}x{largest}")
    most = int(ctx.max_samples)
    if samples < 0 or (samples and (samples & (samples - 1) or samples > most)):
        levels = ", ".join(str(n) for n in (0, 2, 4, 8, 16, 32) if n <= most)
        raise ValueError(f"--samples {samples}: this GL takes {levels}")


@dataclass(frozen=True)
class Framing:
    """How a render frames what it draws.

    Attributes:
        margin: the empty border at each side, as a share of the frame, where the
            view is tightest (0 to below 0.5: 0.1 leaves a tenth of the height
            above and below a tall mesh); None: a thin border (a camera 6% farther
            than the tightest fit).
        zoom: how much larger than that the mesh is drawn (2: twice; what then
            falls outside the frame is cut).
        refit: frame each turntable frame at its own yaw, so that the mesh fills
            every frame (its size changes as it turns); else one framing holds
            for the whole orbit.
    """

    margin: float | None = None
    zoom: float = 1.0
    refit: bool = False

    @property
    def distance_factor(self) -> float:
        """The camera's distance over the tightest fit's."""
        farther = 1.06 if self.margin is None else 1.0 / (1.0 - 2.0 * self.margin)
        return farther / self.zoom


def framed_camera(arrays: MeshArrays | None, elevation: float = 25.0, yaw: float = 30.0,
                  ortho: bool = False, aspect: float = 1.0, frames: int = 1,
                  framing: Framing | None = None) -> Camera:
    """A camera at ``yaw``/``elevation`` framing ``arrays`` as ``framing`` says (by
    default: tightly, with a thin border) at every one of the ``frames`` turntable
    yaws (so the framing holds over the whole orbit)."""
    positions = np.zeros((0, 3)) if arrays is None else arrays.positions
    return camera_framing(positions, elevation, yaw, ortho, aspect, frames, framing)


def camera_framing(positions: np.ndarray, elevation: float = 25.0, yaw: float = 30.0,
                   ortho: bool = False, aspect: float = 1.0, frames: int = 1,
                   framing: Framing | None = None) -> Camera:
    """:func:`framed_camera` for ``(n, 3)`` ``positions`` (none: the default view)."""
    camera = Camera(yaw=yaw, pitch=elevation, ortho=ortho)
    if len(positions):
        yaws = yaw + 360.0 * np.arange(max(frames, 1)) / max(frames, 1)
        factor = (framing or Framing()).distance_factor
        camera.fit_points(sample_points(positions), aspect, yaws, margin=factor)
    return camera


def turntable_cameras(camera: Camera, frames: int) -> Iterator[Camera]:
    """``frames`` copies of ``camera`` evenly spaced around the up axis (no repeat of 360)."""
    for index in range(frames):
        turned = camera.copy()
        turned.yaw = (camera.yaw + 360.0 * index / frames) % 360.0
        yield turned


def render_turntable(offscreen: Offscreen, camera: Camera, style: Style, frames: int,
                     progress: Callable[[int, int], None] | None = None) -> list[np.ndarray]:
    """Render ``frames`` turntable images (each ``(H, W, 3)`` uint8)."""
    return render_views(offscreen, list(turntable_cameras(camera, frames)), style, progress)


def render_views(offscreen: Offscreen, cameras: list[Camera], style: Style,
                 progress: Callable[[int, int], None] | None = None) -> list[np.ndarray]:
    """One image (``(H, W, 3)`` uint8) from each camera, ``progress(done, total)``
    called after each."""
    images = []
    for index, camera in enumerate(cameras):
        images.append(offscreen.render(camera, style))
        if progress is not None:
            progress(index + 1, len(cameras))
    return images


def render_arrays(arrays: MeshArrays | None, out: str, *, size: tuple[int, int] = (800, 600),
                  turntable: int = 0, elevation: float = 25.0, yaw: float = 30.0,
                  style: Style | None = None,
                  preview: Preview | MeshArrays | None = None,
                  selection: Selection | None = None,
                  progress: Callable[[int, int], None] | None = None,
                  ortho: bool = False, samples: int | None = None,
                  offscreen: Offscreen | None = None,
                  others: MeshArrays | None = None, fps: float = 25.0,
                  framing: Framing | None = None) -> list[Path]:
    """Render ``arrays`` to ``out`` (one frame, or a ``turntable`` of that many frames).

    ``framing`` sets the border, the zoom and whether each turntable frame is
    framed at its own angle (see :class:`Framing`); by default one framing,
    computed for all the turntable's angles, holds at every one. ``samples`` is the MSAA level: by default 4 for one frame and 0 for a
    turntable (edges are anti-aliased in the shader; MSAA triples software GL's cost).
    With ``offscreen`` (made beforehand, so a bad size or GL fails before a long
    run), it is drawn into and left to the caller to release; ``size`` and
    ``samples`` are then its own. ``others`` (the scene's other objects) are drawn
    beside ``arrays`` and framed with it. The camera looks from ``elevation`` degrees
    above the horizon and ``yaw`` degrees around the up axis (0: from +z), where a
    turntable starts. ``fps`` is the frame rate of a GIF,
    WebP or MP4 ``out`` (see :func:`~livemod.viewer.imagefiles.write_images`).

    Raises:
        ValueError: a size or MSAA level this GL cannot make, or an ``out`` that
            cannot take these frames (see :func:`~livemod.viewer.imagefiles.check_output`;
            checked before rendering).
        NoOffscreenGL: no offscreen GL context could be made.
    """
    drawn = Drawn(arrays, preview, others, selection)
    orbit = Orbit(max(turntable, 1), elevation, yaw, ortho, framing or Framing())
    style = style if style is not None else Style()
    # before any GL: a name that cannot take these frames costs no context
    check_output(out, max(turntable, 1), offscreen.size if offscreen is not None else size,
                 transparent=style.background[3] < 1.0, fps=fps)
    if offscreen is not None:
        return _render_into(offscreen, drawn, out, orbit, style, progress, fps)
    if samples is None:
        samples = 0 if turntable > 1 else 4
    offscreen = Offscreen(size, samples=samples)
    try:
        return _render_into(offscreen, drawn, out, orbit, style, progress, fps)
    finally:
        offscreen.release()


@dataclass(frozen=True)
class Drawn:
    """What :func:`render_arrays` draws: the mesh, its preview, the other objects."""

    arrays: MeshArrays | None
    preview: Preview | MeshArrays | None = None
    others: MeshArrays | None = None
    selection: Selection | None = None


@dataclass(frozen=True)
class Orbit:
    """Where :func:`render_arrays` looks from: ``frames`` turntable views starting at
    ``yaw`` degrees, ``elevation`` degrees above the horizon, orthographic or not,
    framed as ``framing`` says."""

    frames: int = 1
    elevation: float = 25.0
    yaw: float = 30.0
    ortho: bool = False
    framing: Framing = Framing()

    def cameras(self, positions: np.ndarray, aspect: float) -> list[Camera]:
        """The camera of each frame, framing ``(n, 3)`` ``positions``."""
        shared = camera_framing(positions, self.elevation, self.yaw, self.ortho, aspect,
                                self.frames, self.framing)
        turned = list(turntable_cameras(shared, self.frames))
        if not self.framing.refit:
            return turned
        return [camera_framing(positions, self.elevation, camera.yaw, self.ortho, aspect,
                               1, self.framing) for camera in turned]


def _render_into(offscreen: Offscreen, drawn: Drawn, out: str, orbit: Orbit,
                 style: Style, progress: Callable[[int, int], None] | None,
                 fps: float) -> list[Path]:
    """:func:`render_arrays` into an existing target (which stays open), its output
    name already checked."""
    return write_images(out, render_frames(offscreen, drawn, orbit, style, progress), fps)


def render_frames(offscreen: Offscreen, drawn: Drawn, orbit: Orbit, style: Style,
                  progress: Callable[[int, int], None] | None = None) -> list[np.ndarray]:
    """The images (each ``(H, W, 3)`` uint8, or RGBA for a transparent background)
    of ``drawn`` seen along ``orbit``, drawn into ``offscreen`` (which stays open,
    ``drawn`` uploaded to it); ``progress(done, total)`` after each."""
    size = offscreen.size
    offscreen.activate()
    offscreen.renderer.set_mesh(drawn.arrays, drawn.preview, drawn.others)
    if drawn.selection is not None:
        offscreen.renderer.set_selection(drawn.selection)
    # framed as the window fits: the mesh and the other objects together
    cameras = orbit.cameras(offscreen.renderer.drawn_positions(), size[0] / size[1])
    return render_views(offscreen, cameras, style, progress)
