"""Films of a script's build: one frame per modeling step, as the window plays them.

:func:`render_film` draws the shots of :func:`~livemod.runner.stepshots.shoot_steps`
into an offscreen target: one framing holds for the whole film (the build grows in
place instead of jumping), the camera optionally turns a little each frame, and
each frame can carry the step's caption as the HUD words it (``step k/N: label
(line L)``). ``livemod render SCRIPT --steps`` writes such a film; :func:`film`
gives one to show in a notebook.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from livemod.runner.stepshots import StepShots, shoot_steps

from .camera import Camera
from .geometry import sample_points
from .headless import Offscreen
from .hud import step_line
from .pictures import GL_LOCK, Animation, View, kept_target
from .renderer import Style
from .text import MARGIN, PADDING, PANEL, TEXT, box_quad, glyph_atlas, layout_text, text_width

if TYPE_CHECKING:
    from livemod.runner.recording import StepRecord

FIT_POINTS = 200_000  # points the framing of a whole film looks at, at most


class _Shown(NamedTuple):
    """What :func:`~livemod.viewer.hud.step_line` reads of a paused result."""

    steps: Sequence[StepRecord]
    step_index: int | None


def film_cameras(shots: StepShots, view: View, turn: float = 0.0) -> list[Camera]:
    """A camera per shot: at ``view``'s elevation, starting at its yaw and turning
    ``turn`` degrees a frame, at one distance that frames every shot at its yaw
    (with ``view``'s margin and zoom; orthographic when it says so)."""
    count = max(len(shots.shots), 1)
    parts = [part.positions for shot in shots.shots for part in (shot.arrays, shot.others)
             if part is not None]
    yaws = view.yaw + turn * np.arange(count)
    camera = Camera(yaw=view.yaw, pitch=view.elevation, ortho=view.ortho)
    if parts:
        points = np.concatenate([sample_points(p, max(FIT_POINTS // len(parts), 1))
                                 for p in parts])
        camera.fit_points(points, view.size[0] / view.size[1], yaws,
                          margin=view.orbit().framing.distance_factor)
    cameras = []
    for yaw in yaws:
        turned = camera.copy()
        turned.yaw = float(yaw) % 360.0
        cameras.append(turned)
    return cameras


def caption_quads(text: str, size: tuple[int, int]) -> np.ndarray:
    """Overlay quads of one line of ``text`` in a panel at the bottom left of a
    ``size`` (width, height) frame (see :mod:`livemod.viewer.text`)."""
    atlas = glyph_atlas()
    height = atlas.line_height + 2 * PADDING
    top = size[1] - MARGIN - height
    panel = box_quad(atlas, MARGIN, top, text_width(atlas, text) + 2 * PADDING, height, PANEL)
    return np.concatenate([panel, layout_text(atlas, [text], (MARGIN + PADDING,
                                                              top + PADDING), TEXT)])


def shot_captions(shots: StepShots) -> list[str]:
    """Each shot's caption, as the HUD words a paused step: ``step k/N: label (line L)``
    (``k`` counting from 1, ``N`` the run's steps)."""
    steps = shots.outcome.steps
    return [step_line(_Shown(steps, shot.index), len(steps)) for shot in shots.shots]


def render_film(offscreen: Offscreen, shots: StepShots, view: View, *, turn: float = 0.0,
                captions: bool = True,
                progress: Callable[[int, int], None] | None = None) -> list[np.ndarray]:
    """A frame (``(H, W, 3)`` uint8, or RGBA for a transparent background) per shot,
    drawn into ``offscreen`` (its size, not ``view.size``, is the frames'), with the
    step's caption when ``captions``; ``progress(done, total)`` after each."""
    view = dataclasses.replace(view, size=offscreen.size)
    style = view.style or Style()
    frames = []
    cameras = film_cameras(shots, view, turn)
    for done, (shot, camera, caption) in enumerate(zip(shots.shots, cameras,
                                                       shot_captions(shots), strict=True),
                                                   start=1):
        offscreen.activate()
        offscreen.renderer.set_mesh(shot.arrays, None, shot.others)
        overlay = caption_quads(caption, offscreen.size) if captions else None
        frames.append(offscreen.render(camera, style, overlay))
        if progress is not None:
            progress(done, len(shots.shots))
    offscreen.renderer.set_mesh(None)  # the last shot is not kept on the GPU
    return frames


def film(script: str | os.PathLike[str], *, turn: float = 0.0, captions: bool = True,
         size: tuple[int, int] = (360, 360), fps: float = 4.0, elevation: float = 20.0,
         yaw: float = 30.0, style: Style | None = None, parameters: dict | None = None,
         mesh_path: str | None = None, seed: int | None = 0) -> Animation:
    """A film of ``script``'s build, a frame per step, to show in a notebook or save
    (``livemod render SCRIPT --steps`` in Python): run headless with ``parameters``
    (``--set``), ``mesh_path`` (``--mesh``) and ``seed``.

    Raises:
        ScriptFailedError: the script failed (the message names file and line).
        InvalidArgumentError: it took no step, or ``parameters`` names one the
            run did not declare.
        OSError: the script or ``mesh_path`` cannot be read.
        ValueError, NoOffscreenGL: see :func:`~livemod.viewer.pictures.render_model`.
    """
    shots = script_shots(script, mesh_path=mesh_path, seed=seed, parameters=parameters)
    with GL_LOCK:
        frames = render_film(kept_target(size, 0), shots, View(size, elevation, yaw, style),
                             turn=turn, captions=captions)
    return Animation(tuple(frames), fps)


def script_shots(script: str | os.PathLike[str], **run: Any) -> StepShots:
    """:func:`~livemod.runner.stepshots.shoot_steps` of ``script`` (``run``: its
    keyword arguments), refusing a run that failed or took no step shot.

    Raises:
        ScriptFailedError: the script failed (naming file and line).
        InvalidArgumentError: no step asked for was taken (naming the steps it
            took), or a parameter the run did not declare.
    """
    from livemod.dlfl.errors import InvalidArgumentError
    from livemod.runner.headless import check_outcome

    shots = shoot_steps(script, **run)
    check_outcome(shots.outcome, run.get("parameters"))
    if not shots.shots:
        taken = len(shots.outcome.steps)
        have = f"steps 0 to {taken - 1}" if taken else "no steps"
        asked = run.get("which")
        missing = "nothing to film" if asked is None else \
            f"no step {', '.join(str(k) for k in sorted(asked))}"
        raise InvalidArgumentError(f"{os.fspath(script)} has {have}; {missing}")
    return shots
