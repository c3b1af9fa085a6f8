"""The live window: a moderngl-window ``WindowConfig`` over a runner ``LiveSession``.

The session runs the script in its own threads and posts immutable results to a
queue; :meth:`LiveViewer.on_render` drains that queue without blocking and does
all GL work on the main thread. :func:`create_viewer` builds the window with
explicit arguments (moderngl-window would otherwise parse ``sys.argv``), and
:func:`run_frames` is the main loop, also used by tests on the headless backend.
"""

from __future__ import annotations

import logging
import os
import queue
import re
import sys
import time
import traceback
import warnings
from collections import deque
from collections.abc import Callable
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any, ClassVar

import moderngl_window as mglw
import numpy as np

from livemod.dlfl.scene import Selection

from .camera import Camera, bounds_changed_a_lot
from .controls import (
    PICK_MODES,
    action_for,
    missing_lines,
    section_text,
    selection_python,
    split_picks,
    toggle_pick,
    unpicked_lines,
)
from .geometry import sample_points
from .hud import hud_quads
from .imagefiles import save_new_png
from .measure import WholeMeshMeasurer, measure_lines
from .objects_panel import (
    ObjectPanel,
    kept_hidden,
    next_alone,
    result_rows,
    visible_objects,
)
from .params_panel import Hit, ParameterPanel
from .renderer import (
    DARK_BACKGROUND,
    LIGHT_BACKGROUND,
    Renderer,
    Style,
    read_image,
    release_framebuffer,
)
from .text import MARGIN
from .timeline import Timeline, shown_step

# an unchanged picture is put on the screen again this often (repaints a window that
# was covered), and an idle glfw loop waits this long for input between frames
REPRESENT = 0.5
IDLE_WAIT = 0.01

# the HUD's time of a run at work goes up in these steps (each one draws the frame
# again: a million faces take half a second a frame on software GL)
RUNNING_TICK = 0.5

# a held step key steps again after REPEAT_DELAY s, then every REPEAT_INTERVAL s
REPEAT_DELAY = 0.4
REPEAT_INTERVAL = 0.1
REPEATING = frozenset({"step_forward", "step_back"})

SCRIPT_SUFFIXES = (".py",)
PARAMETER_DEBOUNCE = 0.15  # seconds a dragged slider rests before the script re-runs


@dataclass
class ViewOptions:
    """How to open the window.

    Attributes:
        script: the script to watch and run.
        mesh_path: mesh every run starts from (``--mesh``), or None.
        seed: the seed of random and numpy.random at the start of every run
            (``--seed``; None leaves them unseeded).
        backend: moderngl-window window class: "glfw" (default) or "headless".
        size: window size in pixels.
        samples: MSAA samples of the window framebuffer.
        vsync: wait for the display between frames.
        session_factory: ``(script, mesh_path) -> session``; the runner's
            ``LiveSession`` when None.
        echo: where selections and errors are echoed (stdout when None).
        poll: poll the file system instead of waiting for change events (network
            drives, WSL, containers).
        parameters: script parameter values the first run starts with (``--set``).
        selection: what ``faces(True)`` and the like return from the first run on
            (``--select``), until a pick changes it.
        output: where the runner writes the result after every successful run
            (``-o``; the format from the suffix), or None.
        all_objects: write every object of the scene, joined, not only the current.
    """

    script: str
    mesh_path: str | None = None
    seed: int | None = 0
    backend: str = "glfw"
    size: tuple[int, int] = (1280, 800)
    samples: int = 4
    vsync: bool = True
    session_factory: Callable[[str, str | None], Any] | None = None
    echo: Any = None
    poll: bool = False
    parameters: dict[str, Any] | None = None
    selection: Selection | None = None
    output: str | None = None
    all_objects: bool = False


@dataclass
class HeldKey:
    """A step key held down: what it runs, and when it runs again."""

    key: Any
    name: str
    shift: bool
    ctrl: bool
    due: float


def _default_factory(options: ViewOptions) -> Callable[[str, str | None], Any]:
    """The runner's ``LiveSession`` (imported only when a window opens)."""
    from livemod.runner import LiveSession

    def create(script: str, mesh_path: str | None) -> Any:
        return LiveSession(script, mesh_path=mesh_path, poll=options.poll, seed=options.seed,
                           parameters=options.parameters, output=options.output,
                           all_objects=options.all_objects)

    return create


def _key_names(keys: Any) -> dict[Any, str]:
    """Map a backend's key codes to moderngl-window key names."""
    names: dict[Any, str] = {}
    for name in dir(keys):
        if name.isupper() and not name.startswith("ACTION"):
            code = getattr(keys, name)
            if code != "undefined":
                names.setdefault(code, name)
    return names


class LiveViewer(mglw.WindowConfig):
    """The live viewer window; configure through :func:`create_viewer`."""

    gl_version = (3, 3)
    title = "livemod"
    aspect_ratio = None  # type: ignore[assignment]  # follow the window's shape
    resizable = True
    clear_color = None  # type: ignore[assignment]  # the renderer clears
    log_level = logging.WARNING
    options: ClassVar[ViewOptions]
    _param_drag: Hit | None  # the slider being dragged on the parameters panel
    _pending: dict[str, Any]

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.wnd.exit_key = None  # Esc clears the selection instead
        self.renderer = Renderer(self.ctx)
        self.camera = Camera()
        self.style = Style()
        self.pick_mode = "face"
        self.selection = self.options.selection or Selection()
        self.renderer.set_selection(self.selection)
        self.measures: list[str] = []  # the HUD's measurements of the picked elements
        self.show_help = False
        self.show_hud = True
        self.playing = False
        self.waiting = True
        self.result: Any = None
        self.activity: Any = None  # the session's run at work, newer than the result shown
        self.empty_script: str | None = None  # the session's: a save left the script empty
        self.whole = WholeMeshMeasurer()  # genus and volume of the mesh shown, off-thread
        self.total_steps = 0
        self.objects = ObjectPanel()  # the object list (L) and the hidden objects' ids
        self.show_partial = False  # E: a failed run's own mesh instead of the last good one
        self.viewer_error: str | None = None  # the last result the window failed to show
        self.timeline = Timeline()
        self._scrubbing = False  # the timeline is being dragged
        self._scrub_step: int | None = None  # the step to go to once the pointer rests
        self._scrub_time = 0.0  # when the pointer last moved it
        self.show_objects = False
        # the times of the last frames drawn (see _count_fps), and whether this
        # loop turn drew one
        self.frame_times: deque[float] = deque(maxlen=120)
        self._drew = False
        self.screenshots: list[Path] = []
        self._fit_bounds: np.ndarray | None = None
        self._press: tuple[int, int, int] | None = None
        self._moved = False
        self._pointer: tuple[float, float] = (-1.0, -1.0)  # window point of the mouse
        self._key_names = _key_names(self.wnd.keys)
        self.held: HeldKey | None = None  # the step key held down, repeating
        self._clock = time.perf_counter  # of the key repeat (tests step it by hand)
        self._last_frame = time.perf_counter()
        self._fps_shown, self._fps_time = 0.0, 0.0
        self._overlay_cache: tuple[tuple, np.ndarray] | None = None
        self._picks_cache: tuple[Selection, Any, dict[str, list[str]]] | None = None
        # the last frame drawn and its _frame_key: a frame that would look the same is
        # copied from it (an idle window then costs a copy a frame, not a draw)
        self._frame: tuple[tuple, Any] | None = None
        self.keep_frames = True
        # whether the last on_render put a picture on the screen (else the loop waits
        # for events instead of swapping), and when it last did
        self.presented = True
        self._presented_at = 0.0
        self._init_parameters()
        self.script = str(Path(self.options.script).resolve())
        self.mesh_path = self.options.mesh_path
        self.session = self._start_session()
        self._install_drop_callback()

    # -- session ---------------------------------------------------------------

    def _start_session(self, parameters: dict[str, Any] | None = None) -> Any:
        """Make and start the session of :attr:`script` on :attr:`mesh_path`, its
        first run with ``parameters`` (over ``--set``'s) when given."""
        factory = self.options.session_factory or _default_factory(self.options)
        session = factory(self.script, self.mesh_path)
        if not self.selection.is_empty():
            session.set_selection(self.selection)
        if parameters:
            # (queued before start: the first run and this request are one run)
            session.set_parameters(parameters)
        session.start()
        self.waiting = True
        self.wnd.title = f"livemod - {Path(self.script).name}"
        return session

    def _drain_results(self) -> None:
        """Apply the newest result in the session's queue (never blocks)."""
        latest = None
        while True:
            try:
                latest = self.session.results.get_nowait()
            except queue.Empty:
                break
        if latest is not None:
            try:
                self._apply(latest)
            except Exception as exc:  # a bug of the viewer's own: keep the window alive
                self._viewer_failed(latest, exc)

    def _run_activity(self) -> Any:
        """The session's run at work (one a save started too), or None. A run whose
        end is already shown, or one older than the result shown, is at work no
        more: its result arrived before the session marked it ended."""
        activity = getattr(self.session, "activity", None) if self.session is not None else None
        shown = self.result
        if activity is None or shown is None or activity.run_id > shown.run_id:
            return activity
        if activity.run_id == shown.run_id and shown.status == "paused":
            return activity  # a paused run that goes on
        return None

    def _working(self) -> float | None:
        """Seconds the run at work has worked, in :data:`RUNNING_TICK` steps (None
        when no run works)."""
        if self.activity is None:
            return None
        return RUNNING_TICK * int(self.activity.working / RUNNING_TICK)

    def _viewer_failed(self, result: Any, exc: Exception) -> None:
        """Say that ``result`` could not be shown (the HUD and the terminal, with the
        traceback) and keep drawing what was shown before."""
        self.viewer_error = f"the viewer could not show run {result.run_id}: " \
                            f"{type(exc).__name__}: {exc}"
        self.waiting = False
        self._echo(self.viewer_error)
        traceback.print_exception(exc, file=sys.stderr)

    def _apply(self, result: Any) -> None:
        self.viewer_error = None
        first_error = result.error is not None and (
            self.result is None or self.result.error != result.error)
        self._sync_objects(result)
        if self.playing and _run_ended(self.result, result):
            self.playing = False  # played to the end (or failed): Space plays again
        self.result = result
        self.waiting = False
        self._sync_parameters(result)
        self._count_steps(result)
        arrays = self._drawn_arrays(result)
        if arrays is not None and arrays is not self.renderer.arrays:
            self._show_mesh(result, arrays)
        elif result.arrays is None and result.error is None:
            self.renderer.set_mesh(None)  # the script ended with no mesh: show none
            self.measures = []
            self.whole.measure(None)
        elif result.preview is not None and result.preview is not self.renderer.preview:
            self.renderer.set_preview(result.preview)
        if first_error:
            self._echo(f"error: {result.error.file}:{result.error.line}: "
                       f"{result.error.message}")

    def _count_steps(self, result: Any) -> None:
        """Take the step count of a run that ended, and echo an ``-o`` write."""
        if result.status in ("ok", "error"):
            # a failed run's steps are what the step keys and the timeline go
            # through; a syntax error has none, so the timeline goes with it
            self.total_steps = len(result.steps)
        if result.status == "ok" and self.options.output is not None:
            self._echo(  # the session wrote it before posting
                f"run {result.run_id}: wrote {self.options.output}")

    def _upload(self, arrays: Any, preview: Any, others: Any) -> None:
        self.renderer.set_mesh(arrays, preview, others)
        self.renderer.set_selection(self.selection)
        self.measures = measure_lines(self.selection, arrays)
        self.whole.measure(arrays)
        bounds = self.renderer.bounds
        if bounds is not None and len(arrays.positions) and bounds_changed_a_lot(
                self._fit_bounds, bounds):
            self._do_fit()
            self._fit_bounds = bounds

    def _show_mesh(self, result: Any, arrays: Any) -> None:
        """Upload ``arrays`` (``result``'s own mesh, or its failed run's) with the
        result's preview when it is the preview of those arrays, and its others."""
        preview = result.preview if arrays is result.arrays else None
        self._upload(arrays, preview, self._visible_others(result))

    def _drawn_arrays(self, result: Any) -> Any:
        """The mesh to show of ``result``: the failed run's own (E), or the last good one."""
        if self.show_partial and result.error is not None and result.partial is not None:
            return result.partial
        return result.arrays

    def _do_toggle_partial(self) -> None:
        result = self.result
        if result is None or result.error is None or result.partial is None:
            self._echo("no failed run to show: E shows the mesh a failed run left")
            return
        self.show_partial = not self.show_partial
        self._show_mesh(result, self._drawn_arrays(result))
        self._echo("showing the mesh as the failed run left it" if self.show_partial
                   else "showing the last good mesh")

    @property
    def hidden_others(self) -> frozenset[int]:
        """Ids of the other objects not drawn (unticked in the object list, or not
        the one ``Tab`` shows alone)."""
        return self.objects.hidden

    def _other_ids(self, result: Any = None) -> list[int]:
        result = self.result if result is None else result
        return [oid for oid, _, _ in result.other_objects] if result is not None else []

    def _sync_objects(self, result: Any) -> None:
        """List ``result``'s objects, keeping hidden the ones still there."""
        before = frozenset(self._other_ids()) - self.objects.hidden
        hidden = kept_hidden(self.objects.hidden, before, self._other_ids(result))
        self.objects.sync(result_rows(result), hidden)

    def _visible_others(self, result: Any) -> Any:
        """The other objects to draw, joined: all of them (the result's own join),
        or those not hidden; None when none is shown."""
        if not self.objects.hidden:
            return result.others
        from livemod.runner.results import join_others

        return join_others(visible_objects(result.other_objects, self.objects.hidden))

    def set_hidden_others(self, hidden: frozenset[int]) -> None:
        """Draw the other objects whose ids are not in ``hidden`` (and the others at
        all: choosing what to show means showing it)."""
        self.objects.hidden = frozenset(hidden)
        self.style = replace(self.style, others=True)
        if self.result is not None:
            self.renderer.set_others(self._visible_others(self.result))

    def _others_note(self) -> str:
        """Which other objects are drawn, for the HUD and the echo ("" for all)."""
        objects = self.result.other_objects if self.result is not None else ()
        shown = visible_objects(objects, self.objects.hidden)
        if len(shown) == len(objects):
            return ""
        if len(shown) == 1:
            oid, name, _ = shown[0]
            named = f" {name!r}" if name else ""
            return f"object {oid}{named} alone (of {len(objects)}; Tab: next)"
        return f"{len(shown)} of {len(objects)} shown (L: list)"

    def _echo_others(self) -> None:
        """Say which other objects are drawn now."""
        self._echo(f"other objects: {self._others_note() or 'all ' + str(len(self._other_ids()))}")

    def _echo(self, line: str) -> None:
        stream = self.options.echo if self.options.echo is not None else sys.stdout
        print(line, file=stream, flush=True)

    # -- frames ----------------------------------------------------------------

    def on_render(self, time_now: float, frame_time: float) -> None:
        """Draw a frame (moderngl-window's callback): take the runner's newest
        result, upload it, draw or copy the kept frame, then the HUD and panels."""
        now = time.perf_counter()
        if self._drew:  # the turn before drew a picture: its whole turn is a frame time
            self.frame_times.append(now - self._last_frame)
        self._drew, self._last_frame = False, now
        self._flush_parameters()
        self._flush_scrub()
        self._drain_results()
        self._repeat_held_key()
        self.activity = self._run_activity()
        self.empty_script = getattr(self.session, "empty_script", None)
        self._count_fps()
        screen = self.wnd.fbo
        if self.keep_frames:
            self._show_kept_frame(screen)
        else:
            self._draw_frame(screen)
            self.presented = True

    def _count_fps(self) -> None:
        """Update the HUD's frame rate twice a second: frames drawn per second of
        the loop turns that drew them (each from the start of its turn to the
        start of the next: results taken, the draw, the swap). Turns that drew
        nothing (an unchanged picture copied, or a wait for input) do not count,
        so an idle window keeps the rate of its last drawn frames."""
        now = time.perf_counter()
        if now - self._fps_time > 0.5 and self.frame_times:
            self._fps_shown = round(len(self.frame_times) / max(sum(self.frame_times), 1e-9))
            self._fps_time = now

    def _show_kept_frame(self, screen: Any) -> None:
        """Copy the kept frame to ``screen``, drawing it again first if the picture
        would differ (see :meth:`_frame_key`). An unchanged picture is not copied at
        all (:attr:`presented` False: the loop need not swap) but every
        ``REPRESENT`` seconds, which repaints a window that was covered."""
        key, now, kept = self._frame_key(screen), time.perf_counter(), self._frame
        changed = kept is None or kept[0] != key
        # other backends take their input events while swapping: they swap every frame
        idle_ok = self.wnd.name in ("glfw", "headless")
        self.presented = changed or not idle_ok or now - self._presented_at > REPRESENT
        if not self.presented:
            return
        self._presented_at = now
        if changed:
            target = self._frame_target(screen)
            fresh = kept is None or target is not kept[1]  # a new framebuffer
            self._frame = (key, target)
            self._draw_frame(target)
        else:
            assert kept is not None
            target, fresh = kept[1], False
        if fresh:
            self.ctx.error  # noqa: B018  (reading it clears an older error)
        self.ctx.copy_framebuffer(screen, target)
        screen.use()
        if fresh and self.ctx.error != "GL_NO_ERROR":
            # a screen whose MSAA moderngl misreports refuses the copy: draw each frame
            self.keep_frames = False
            self._draw_frame(screen)

    def _draw_frame(self, fbo: Any) -> None:
        """Draw the scene and the overlay into ``fbo`` (the screen or the kept
        frame, both of :attr:`screen_size`)."""
        size = self.screen_size
        self._drew = True
        self.renderer.draw(fbo, self.camera, self.style, size)
        if self.show_hud or self.show_help:
            self.renderer.draw_overlay(fbo, self._overlay_quads(size), size)

    def _frame_key(self, screen: Any) -> tuple:
        """Everything the picture depends on: a frame with the same key is the same
        picture, so it is copied from the last one instead of drawn again."""
        camera = self.camera
        view = (tuple(camera.target.tolist()), camera.distance, camera.yaw, camera.pitch,
                camera.fov, camera.ortho)
        # the frame rate alone does not redraw: a million faces take half a second a
        # frame on software GL, and an idle window would be drawing all the time
        size = self.screen_size
        overlay = (self._overlay_key(size, with_fps=False)
                   if self.show_hud or self.show_help else None)
        return (self.renderer.version, view, self.style, overlay, size, screen.samples)

    def _frame_target(self, screen: Any) -> Any:
        """A framebuffer like ``screen`` (size, MSAA) to keep the last frame in; the
        old one is released when the size changed."""
        old, size = None if self._frame is None else self._frame[1], self.screen_size
        if old is not None and old.size == size and old.samples == screen.samples:
            return old
        if old is not None:
            release_framebuffer(old)
        return self.ctx.framebuffer(
            [self.ctx.renderbuffer(size, 4, samples=screen.samples)],
            self.ctx.depth_renderbuffer(size, samples=screen.samples))

    def _panel_shown(self) -> bool:
        return self.show_hud and not self.show_help

    def _overlay_quads(self, size: tuple[int, int]) -> np.ndarray:
        """HUD quads, laid out again only when something shown changed (the FPS
        figure changes twice a second), to keep frames cheap while a script runs."""
        key = self._overlay_key(size)
        if self._overlay_cache is None or self._overlay_cache[0] != key:
            parts = [hud_quads(self._hud_info(), size)]
            if self._panel_shown():  # the parameters' tooltip is drawn over the list
                parts.insert(0, self.params.quads(size))
            if self._objects_shown():
                self.objects.top = self.params.bottom(size) + (
                    MARGIN if self.params.specs else 0)
                parts.insert(0, self.objects.quads(size))
            if self._timeline_shown():
                parts.insert(0, self.timeline.quads(size, shown_step(self.result, self._steps()),
                                                    self._steps()))
            self._overlay_cache = (key, np.concatenate(parts))
        return self._overlay_cache[1]

    def _overlay_key(self, size: tuple[int, int], with_fps: bool = True) -> tuple:
        """Everything the HUD and the panels show (but the frame rate, when not
        ``with_fps``)."""
        return (id(self.result), self.waiting, self._working(), self.total_steps,
                self.whole.facts(),
                self._fps_shown if with_fps else None, self.pick_mode, self.selection,
                self.style,
                self.camera.ortho, self.playing, self.show_hud, self.show_help, size,
                self.params.state(), self.objects.state(), self._objects_shown(),
                self.show_partial, self.viewer_error, self.renderer.nonfinite,
                self.empty_script)

    def _objects_shown(self) -> bool:
        # one object is listed too: its checkbox hides it
        return self.show_objects and self._panel_shown() and bool(self.objects.rows)

    def _hud_info(self) -> dict[str, Any]:
        return {"script": self.script, "result": self.result, "waiting": self.waiting,
                "working": self._working(),
                "arrays": self.renderer.arrays, "partial": self.show_partial,
                "nonfinite": self.renderer.nonfinite,
                "viewer_error": self.viewer_error, "empty_script": self.empty_script,
                "total_steps": self.total_steps,
                "whole": self.whole.facts(), "fps": self._fps_shown,
                "pick_mode": self.pick_mode, **self._pick_lines(),
                "measures": self.measures,
                "others": self.renderer.others, "others_note": self._others_note(),
                "current_hidden": not self.style.current,
                "style": self.style, "ortho": self.camera.ortho, "playing": self.playing,
                "hud": self.show_hud, "help": self.show_help,
                # the error panel stands above the timeline
                "bottom": self.timeline.frame(self.screen_size)[3] + MARGIN
                if self._timeline_shown() else 0.0}

    def _pick_lines(self) -> dict[str, list[str]]:
        """The HUD's ``selection`` lines (the picks the mesh shown holds, as the next
        run's ``faces(True)`` and the like see them) and its ``missing`` notes: picks
        it lacks (kept, as stepping back to before they were made must not lose
        them), and selections the run asked for with nothing picked."""
        arrays, selection = self.renderer.arrays, self.selection
        unpicked = unpicked_lines(getattr(self.result, "unselected", ()), selection)
        if selection.is_empty():
            return {"selection": [], "missing": unpicked}
        cache = self._picks_cache  # (the arrays held, not their id: ids are reused)
        if cache is None or cache[0] != selection or cache[1] is not arrays:
            present, missing = split_picks(selection, arrays)
            # all missing: no `faces(True) == ()` line (that says a pick was cleared)
            shown = selection_python(present, arrays) if not present.is_empty() else []
            cache = (selection, arrays, {"selection": shown,
                                         "missing": missing_lines(missing)})
            self._picks_cache = cache
        return {**cache[2], "missing": cache[2]["missing"] + unpicked}

    def capture(self, transparent: bool = False) -> np.ndarray:
        """Render the scene (no HUD) offscreen at the window's size: ``(H, W, 3)``
        uint8, or ``(H, W, 4)`` with alpha 0 where nothing is drawn when
        ``transparent``."""
        size = self.screen_size
        style = self.style
        if transparent:
            style = replace(style, background=(*style.background[:3], 0.0))
        fbo = self.ctx.framebuffer([self.ctx.renderbuffer(size, 4)],
                                   self.ctx.depth_renderbuffer(size))
        try:
            self.renderer.draw(fbo, self.camera, style)
            return read_image(fbo, style)
        finally:
            release_framebuffer(fbo)
            self.wnd.use()

    def save_screenshot(self, transparent: bool = False) -> Path:
        """Write :meth:`capture` to ``<script>_NNN.png`` in the working directory and
        return its path. NNN starts at the count of this window's screenshots and
        goes up past every name taken; the name is taken in the same step as the
        file is made (see :func:`~.imagefiles.save_new_png`), so a file that another
        process writes meanwhile is never written over."""
        image = self.capture(transparent)
        stem = Path(self.script).stem
        index = len(self.screenshots)
        while True:
            path = Path(f"{stem}_{index:03d}.png")
            try:
                save_new_png(path, image)
                break
            except FileExistsError:
                index += 1
        self.screenshots.append(path)
        self._echo(f"screenshot: {path}")
        return path

    def release_gl(self) -> None:
        """Free the GL objects the window made (the kept frame, and the renderer's:
        see :meth:`Renderer.release`); calling it again does nothing. Nothing may be
        drawn after it. :func:`close_viewer` calls it before destroying the window."""
        self.ctx.__enter__()  # (GL calls go to the context made current last)
        if self._frame is not None:
            release_framebuffer(self._frame[1])
            self._frame = None
        self.renderer.release()

    def on_close(self) -> None:
        """The window closes: stop the session's threads (moderngl-window's callback)."""
        self._close_session()

    # -- keys ------------------------------------------------------------------

    def on_key_event(self, key: Any, action: Any, modifiers: Any) -> None:
        """A key press runs its binding (see ``H`` and docs/viewer.md); a step key
        held down steps on (see :meth:`_repeat_held_key`). The toolkit's own repeats
        do nothing: glfw's come at the system's rate, pyglet sends none, and the
        frame loop's timer repeats at one rate in every backend."""
        keys = self.wnd.keys
        if action == keys.ACTION_RELEASE:
            if self.held is not None and self.held.key == key:
                self.held = None
            return
        if action != keys.ACTION_PRESS:
            return
        self.held = None  # another key ends a repeat, as a keyboard's does
        name = self._key_names.get(key)
        if name is None:
            return
        shift, ctrl = bool(modifiers.shift), bool(modifiers.ctrl)
        # held only when it went somewhere (else it said why not, once)
        if self.handle_key(name, shift=shift, ctrl=ctrl) in REPEATING and self.waiting:
            self.held = HeldKey(key, name, shift, ctrl, self._clock() + REPEAT_DELAY)

    def _repeat_held_key(self) -> None:
        """Step again while a step key is held, once the step before has arrived (a
        step that replays the script must not pile up behind the key); at the
        first or last step the repeat ends."""
        held = self.held
        if held is None or self.waiting:
            return
        now = self._clock()
        if now < held.due:
            return
        self.handle_key(held.name, shift=held.shift, ctrl=held.ctrl)
        if self.waiting:
            held.due = now + REPEAT_INTERVAL
        else:
            self.held = None  # nowhere to go: it said so once

    def handle_key(self, name: str, shift: bool = False, ctrl: bool = False) -> str | None:
        """Run the action bound to key ``name``; returns the action (None if unbound)."""
        action = action_for(name, shift, ctrl)
        if action is None:
            return None
        handler = getattr(self, f"_do_{action}", None)
        if handler is not None:
            handler()
        elif action.startswith("pick_"):
            self.pick_mode = action.removeprefix("pick_")
        elif action.startswith("view_"):
            self.camera.preset(action.removeprefix("view_"))
        elif action.startswith("labels_"):
            self._toggle_labels(action.removeprefix("labels_"))
        else:
            self._toggle_style(action.removeprefix("toggle_"))
        return action

    def _toggle_style(self, field_name: str) -> None:
        flipped: dict[str, Any] = {field_name: not getattr(self.style, field_name)}
        self.style = replace(self.style, **flipped)

    def _toggle_labels(self, kind: str) -> None:
        if kind == "selected":
            self.style = replace(self.style,
                                 labels_selected_only=not self.style.labels_selected_only)
            return
        self.style = replace(self.style, labels=self.style.labels ^ {kind})

    def _do_help(self) -> None:
        self.show_help = not self.show_help

    def _do_toggle_hud(self) -> None:
        self.show_hud = not self.show_hud

    def _do_toggle_background(self) -> None:
        light = self.style.background == DARK_BACKGROUND
        self.style = replace(self.style,
                             background=LIGHT_BACKGROUND if light else DARK_BACKGROUND)

    def _do_toggle_ortho(self) -> None:
        self.camera.ortho = not self.camera.ortho

    def _do_fit(self) -> None:
        positions = self.renderer.drawn_positions()
        if len(positions):
            width, height = self.screen_size
            self.camera.fit_points(sample_points(positions), width / max(height, 1))

    def _do_play_pause(self) -> None:
        self.playing = not self.playing
        if self.playing:
            self.session.play(2.0)
        else:
            self.session.pause()
        self.waiting = self.playing

    def _ended(self) -> bool:
        """The result shown is of a run that ended (not a paused or cached step) and
        the window asked for nothing since: no step lies ahead of it."""
        result = self.result
        return (not self.waiting and result is not None and result.status != "paused"
                and result.step_index is None)

    def _do_step_forward(self) -> None:
        self.playing = False
        self.session.step_forward()  # (a run a save started pauses at its next step)
        # at the end the session posts nothing: say so, not `running` until the next save
        if self._ended():
            self._echo("no steps" if shown_step(self.result, self._steps()) is None
                       else "at the last step (Left, Home or the timeline go back)")
        else:
            self.waiting = True

    def _do_step_back(self) -> None:
        self.playing = False
        shown = shown_step(self.result, self._steps())
        self.session.step_back()
        if self.waiting or (shown is not None and shown > 0):
            self.waiting = True
        else:  # the session has no step before this one and posts nothing
            self._echo("no steps" if shown is None else "at the first step")

    def _do_run_to_end(self) -> None:
        self.playing = False
        self.session.run_to_end()
        if self._ended():
            self._echo("already at the end")
        else:
            self.waiting = True

    def _do_reload(self) -> None:
        self.session.reload()
        self.waiting = True

    def _do_cycle_others(self) -> None:
        ids = self._other_ids()
        if not ids:
            self._echo("the scene has no other objects")
            return
        self.set_hidden_others(next_alone(ids, self.objects.hidden))
        self._echo_others()

    def _do_toggle_object_list(self) -> None:
        self.show_objects = not self.show_objects
        if self.show_objects and not self.objects.rows:
            self._echo("the scene has no objects to list")

    def _do_cycle_section(self) -> None:
        axis = 0 if self.style.section is None else self.style.section[0] + 1
        bounds = self.renderer.bounds
        if axis > 2 or bounds is None:
            self.style = replace(self.style, section=None)
            self._echo("section: off")
            return
        self.style = replace(self.style, section=(axis, float(bounds[:, axis].mean())))
        self._echo(f"section: {section_text(self.style.section)}")

    def _do_section_back(self) -> None:
        self._move_section(-1)

    def _do_section_forward(self) -> None:
        self._move_section(1)

    def _move_section(self, direction: int) -> None:
        """Move the section plane by 1/20 of what is drawn, along its axis."""
        bounds, section = self.renderer.bounds, self.style.section
        if section is None or bounds is None:
            self._echo("no section to move: C cuts the meshes")
            return
        axis, at = section
        low, high = float(bounds[0, axis]), float(bounds[1, axis])
        step = (high - low) / 20 or 1.0
        at = min(max(at + direction * step, low - step), high + step)
        self.style = replace(self.style, section=(axis, at))
        self._echo(f"section: {section_text(self.style.section)}")

    def _do_screenshot(self) -> None:
        self.save_screenshot()

    def _do_screenshot_transparent(self) -> None:
        self.save_screenshot(transparent=True)

    def _do_next_pick_mode(self) -> None:
        self.pick_mode = PICK_MODES[(PICK_MODES.index(self.pick_mode) + 1) % len(PICK_MODES)]

    def _do_clear_selection(self) -> None:
        self.set_selection(Selection())

    def _do_copy_parameters(self) -> None:
        lines = self.params.python_lines()
        if not lines:
            self._echo("the script declares no parameters")
            return
        handle = getattr(self.wnd, "_window", None)
        if self.options.backend == "glfw" and handle is not None:
            import glfw

            glfw.set_clipboard_string(handle, "\n".join(lines) + "\n")
        for line in lines:
            self._echo(line)

    def _do_quit(self) -> None:
        self.wnd.close()

    # -- mouse -----------------------------------------------------------------

    def on_mouse_press_event(self, x: int, y: int, button: int) -> None:
        """A press on a panel, the object list or the timeline acts there; on the
        model it starts a click (pick) or a drag (orbit, pan)."""
        hit = self._panel_hit(x, y)
        if hit is not None:
            self._press_panel(hit, x * self._pixel_ratio())
            return
        hit = self._objects_hit(x, y)
        if hit is not None:
            self._press_objects(hit)
            return
        if self._timeline_hit(x, y):
            self._scrub_to(x * self._pixel_ratio())
            return
        self._press = (x, y, button)
        self._moved = False

    def on_mouse_position_event(self, x: int, y: int, dx: int, dy: int) -> None:
        """The pointer moved without a button: highlight the row under it."""
        self._pointer = (x, y)
        hit = self._panel_hit(x, y)
        self.params.hover = hit.row if hit is not None and hit.row >= 0 else None
        self.objects.point_at(self._objects_hit(x, y))

    def on_mouse_drag_event(self, x: int, y: int, dx: int, dy: int) -> None:
        """Drag a slider or the timeline, else orbit (left) or pan (shift-left,
        right, middle)."""
        self._pointer = (x, y)
        if self._param_drag is not None:
            self._drag_slider(x * self._pixel_ratio())
            return
        if self._scrubbing:
            self._scrub_to(x * self._pixel_ratio())
            return
        if self._press is not None and abs(x - self._press[0]) + abs(y - self._press[1]) > 3:
            self._moved = True
        states = self.wnd.mouse_states
        if states.left and not self.wnd.modifiers.shift:
            self.camera.orbit(dx * 0.4, dy * 0.4)
        elif states.left or states.right or states.middle:
            self.camera.pan(dx * self._pixel_ratio(), dy * self._pixel_ratio(),
                            self.screen_size[1])

    def on_mouse_release_event(self, x: int, y: int, button: int) -> None:
        """End a drag (a slider's value is sent now), or pick on a left click that
        did not move (shift adds to the selection)."""
        if self._param_drag is not None:
            self._param_drag = None
            self._flush_parameters(force=True)  # the value has settled
            return
        if self._scrubbing:
            self._scrubbing = False
            self._flush_scrub(force=True)
            return
        clicked = self._press is not None and not self._moved
        self._press = None
        if clicked and button == self.wnd.mouse.left:
            self.click(x, y, add=bool(self.wnd.modifiers.shift))

    def on_mouse_scroll_event(self, x_offset: float, y_offset: float) -> None:
        """The wheel scrolls the object list under the pointer, else zooms."""
        if y_offset and self._objects_hit(*self._pointer) is not None:
            rows = max(1, round(abs(y_offset)))
            self.objects.scroll(-rows if y_offset > 0 else rows, self.screen_size)
            return
        self.camera.zoom(y_offset)

    def _pixel_ratio(self) -> float:
        return self.screen_size[0] / max(self.wnd.size[0], 1)

    @property
    def screen_size(self) -> tuple[int, int]:
        """The window's framebuffer size in pixels now. Not ``wnd.fbo.size``: moderngl's
        screen framebuffer keeps the size the window opened with, so after a resize
        the frame would be drawn (and picked, and laid out) at the old size."""
        width, height = self.wnd.buffer_size
        return int(width), int(height)

    def click(self, x: float, y: float, add: bool = False) -> None:
        """Pick at window point ``(x, y)`` in the current mode and update the selection.

        A click on the background without ``add`` clears the selection.
        """
        ratio = self._pixel_ratio()
        px, py = int(x * ratio), int(y * ratio)
        hit = self.renderer.pick(self.camera, self.screen_size, px, py, self.pick_mode,
                                 radius=int(6 * ratio))
        self.wnd.use()
        if hit is None:
            if not add:
                self.set_selection(Selection())
            return
        self.set_selection(toggle_pick(self.selection, self.pick_mode, hit.element_id, add))

    def set_selection(self, selection: Selection) -> None:
        """Show ``selection``, send it to the session and echo it as Python."""
        self.selection = selection
        self.renderer.set_selection(selection)
        self.session.set_selection(selection)
        self.measures = measure_lines(selection, self.renderer.arrays)
        for line in (*selection_python(selection, self.renderer.arrays), *self.measures):
            self._echo(line)

    # -- parameters --------------------------------------------------------------

    def _init_parameters(self) -> None:
        self.params = ParameterPanel()
        self.parameter_runs = 0  # how often the panel re-ran the script (for tests)
        self._param_drag = None
        self._pending = {}  # slider values not yet sent to the session
        self._pending_at = 0.0

    def _sync_parameters(self, result: Any) -> None:
        """Show the result's declarations with the session's values and any edit in flight."""
        specs = tuple(getattr(result, "parameters", ()) or ())
        if not specs and result.error is not None:
            return  # a run that failed early: keep the controls the user was using
        values = dict(getattr(self.session, "parameters", {}) or {})
        values.update(self._pending)
        self.params.sync(specs, values)

    def _panel_hit(self, x: float, y: float) -> Hit | None:
        if not self._panel_shown():
            return None
        ratio = self._pixel_ratio()
        return self.params.hit(x * ratio, y * ratio, self.screen_size)

    # -- the step timeline -----------------------------------------------------------

    def _steps(self) -> int:
        """Steps the timeline spans: the last complete run's, or more while one runs."""
        shown = len(self.result.steps) if self.result is not None else 0
        return max(self.total_steps, shown)

    def _timeline_shown(self) -> bool:
        return self._panel_shown() and self._steps() > 1

    def _timeline_hit(self, x: float, y: float) -> bool:
        ratio = self._pixel_ratio()
        return self._timeline_shown() and self.timeline.hit(x * ratio, y * ratio,
                                                            self.screen_size)

    def _scrub_to(self, px: float) -> None:
        """Drag the timeline to ``px``: its step is gone to once the pointer rests or
        is let go (a drag over steps not in the snapshot cache would replay the
        script for each)."""
        self._scrubbing = True
        self._scrub_step = self.timeline.step_at(px, self.screen_size, self._steps())
        self._scrub_time = time.perf_counter()

    def _flush_scrub(self, force: bool = False) -> None:
        step = self._scrub_step
        resting = time.perf_counter() - self._scrub_time >= PARAMETER_DEBOUNCE / 3
        if step is None or not (force or resting):
            return
        self._scrub_step = None
        if step != shown_step(self.result, self._steps()) or self.waiting:
            self._goto_step(step)

    def _do_first_step(self) -> None:
        if not self.waiting and shown_step(self.result, self._steps()) is None:
            self._echo("no steps")  # (a syntax error: replaying it would fail again)
            return
        self._goto_step(0)

    def _goto_step(self, k: int) -> None:
        """Stop playing and show the mesh right after step ``k`` (0-based)."""
        self.playing = False
        self.session.goto_step(k)
        self.waiting = True

    def _objects_hit(self, x: float, y: float) -> Hit | None:
        if not self._objects_shown():
            return None
        ratio = self._pixel_ratio()
        return self.objects.hit(x * ratio, y * ratio, self.screen_size)

    def _press_objects(self, hit: Hit) -> None:
        """A click on the object list: tick or untick an object, or all (the current
        one too) / none (of the others)."""
        ids = frozenset(self._other_ids())
        if hit.part == "current":
            self.set_current_shown(self.objects.current_hidden)
            self._echo(f"current object: {'hidden' if self.objects.current_hidden else 'shown'}")
            return
        if hit.part in ("all", "none"):
            if hit.part == "all":
                self.set_current_shown(True)
            self.set_hidden_others(frozenset() if hit.part == "all" else ids)
        elif hit.part == "toggle":
            self.set_hidden_others(self.objects.hidden ^ {self.objects.rows[hit.row].oid})
        else:
            return
        self._echo_others()

    def set_current_shown(self, shown: bool) -> None:
        """Draw the current object or not (not drawn, it is not picked or labelled);
        it stays so across runs, whichever object the script leaves current."""
        self.objects.current_hidden = not shown
        self.style = replace(self.style, current=shown)

    def _press_panel(self, hit: Hit, px: float) -> None:
        """A click on the panel: reset, start a slider drag, toggle or cycle a choice."""
        if hit.part == "reset_all":
            self._reset_parameters(None)
        elif hit.part == "reset":
            self._reset_parameters([self.params.specs[hit.row].name])
        elif hit.part == "slider":
            self._param_drag = hit
            self._drag_slider(px)
        elif hit.part in ("toggle", "prev", "next"):
            self.set_parameter(self.params.specs[hit.row].name,
                               self.params.value_after(hit, px, self.screen_size))
            self._flush_parameters(force=True)

    def _drag_slider(self, px: float) -> None:
        hit = self._param_drag
        if hit is not None and hit.row < len(self.params.specs):
            self.set_parameter(self.params.specs[hit.row].name,
                               self.params.value_after(hit, px, self.screen_size))

    def set_parameter(self, name: str, value: Any) -> None:
        """Show ``value`` for parameter ``name`` now; the script re-runs with it once
        the value has rested :data:`PARAMETER_DEBOUNCE` seconds (latest wins)."""
        if self.params.values.get(name) == value and name not in self._pending:
            return
        self.params.values[name] = value
        self._pending[name] = value
        self._pending_at = time.perf_counter()

    def _flush_parameters(self, force: bool = False) -> None:
        """Send settled slider values to the session (never blocks: it only queues a run)."""
        if not self._pending or self.session is None:
            return
        if not force and time.perf_counter() - self._pending_at < PARAMETER_DEBOUNCE:
            return
        values, self._pending = self._pending, {}
        try:
            self.session.set_parameters(values)
        except Exception as exc:  # e.g. the declaration changed under the slider
            self._echo(f"parameters: {exc}")
            return
        self.parameter_runs += 1
        self.waiting = True

    def _reset_parameters(self, names: list[str] | None) -> None:
        """Back to the defaults: one parameter, or all of them (None)."""
        for spec in self.params.specs:
            if names is None or spec.name in names:
                self.params.values[spec.name] = spec.default
                self._pending.pop(spec.name, None)
        self.session.reset_parameters(names)
        self.parameter_runs += 1
        self.waiting = True

    # -- files -----------------------------------------------------------------

    def _install_drop_callback(self) -> None:
        """moderngl-window's glfw backend does not forward drops; hook glfw directly."""
        handle = getattr(self.wnd, "_window", None)
        if self.options.backend != "glfw" or handle is None:
            return
        import glfw

        def dropped(_window: Any, paths: list[str]) -> None:
            if paths:
                self.open_path(paths[0])

        callback: Any = dropped
        glfw.set_drop_callback(handle, callback)

    def on_files_dropped_event(self, x: int, y: int, paths: list[Any]) -> None:
        """A file dropped on the window is opened (the first of several)."""
        if paths:
            self.open_path(str(paths[0]))

    def open_path(self, path: str) -> None:
        """Open a script (``.py``: it replaces the watched one) or a mesh (the new base).

        A new script starts afresh (see :meth:`_forget_the_run`). A mesh is new input
        to the same script, so the script's parameter values are kept (the ones set
        on the panel, one still being dragged, and ``--set``'s); the selection is
        cleared all the same, as its ids are the old mesh's, which the new one
        does not share."""
        resolved = str(Path(path).resolve())
        is_script = Path(path).suffix.lower() in SCRIPT_SUFFIXES
        kept: dict[str, Any] = {}
        if is_script:
            self.script = resolved
        else:
            self.mesh_path = resolved
            kept = self._parameter_values()
        had_selection = not self.selection.is_empty()
        self._close_session()
        self._forget_the_run(keep_parameters=not is_script)
        self.session = self._start_session(kept)
        self._echo(f"opened {resolved}")
        if not is_script:
            note = "; the selection was cleared (its ids were the old mesh's)" \
                if had_selection else ""
            self._echo(f"the script runs on the new mesh with its parameter values kept{note}")

    def _parameter_values(self) -> dict[str, Any]:
        """The values the session's next run gets, with any slider edit not sent yet."""
        values = dict(getattr(self.session, "parameters", {}) or {})
        values.update(self._pending)
        return values

    def _forget_the_run(self, keep_parameters: bool = False) -> None:
        """Drop what the window kept of the runs of the session just closed: the
        next script's ids, steps and parameters are its own, and a key held, a
        scrub, E or a viewer error of the old one must not carry over to it. With
        ``keep_parameters`` (a new mesh for the same script) the parameter panel
        stays as it is, but for edits in flight, which the caller passes on."""
        self.selection = Selection()
        self.renderer.set_selection(self.selection)
        self.measures = []
        self.objects.sync((), frozenset())  # another script's objects share no ids
        self.set_current_shown(True)
        self._fit_bounds = None  # fit the new script's first result
        self.result, self.activity, self.viewer_error = None, None, None
        self.total_steps = 0
        self.show_partial = self.playing = self._scrubbing = False
        self.held, self._scrub_step, self._press = None, None, None
        if keep_parameters:
            self._pending, self._param_drag = {}, None
        else:
            self._init_parameters()  # the new script declares its own

    def _close_session(self) -> None:
        self.whole.close()
        session, self.session = self.session, None
        if session is not None:
            session.close()


def _run_ended(shown: Any, result: Any) -> bool:
    """``result`` is a run's end (ok, error, cancelled) newly arrived, not the
    re-post of ``shown`` with its preview."""
    if result.status == "paused":
        return False
    return shown is None or (shown.run_id, shown.status) != (result.run_id, result.status)


class WindowUnavailable(OSError):
    """No window could be opened (no display, no GL): ``livemod view`` says why."""


def _window_failure(exc: Exception, warned: list[str]) -> str:
    """The message for a window that did not open, with what the toolkit warned."""
    # glfw words its errors "(65550) b'X11: ...'"
    reason = "; ".join(re.sub(r"^\(\d+\) b['\"](.*)['\"]$", r"\1", text) for text in warned)
    reason = reason or str(exc)
    hint = ""
    if not (os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY")):
        hint = (" There is no display (DISPLAY and WAYLAND_DISPLAY are unset): run it"
                " in a desktop session or under xvfb-run, or work headless with"
                " `livemod run --watch` and `livemod render`.")
    return f"cannot open a window ({reason}).{hint}"


def create_viewer(options: ViewOptions) -> LiveViewer:
    """Open the window described by ``options`` (on the calling, main thread).

    Raises:
        WindowUnavailable: the window toolkit could not open a window.
    """
    attributes = {"options": options, "samples": options.samples, "vsync": options.vsync,
                  "window_size": options.size}
    config_cls = type("LiveViewerWindow", (LiveViewer,), attributes)
    args = ["--window", options.backend, "--size", f"{options.size[0]}x{options.size[1]}",
            "--samples", str(options.samples)]
    if options.backend == "headless":
        args += ["--backend", "egl"]
    with warnings.catch_warnings(record=True) as said:  # glfw warns the reason, then fails
        warnings.simplefilter("always")
        try:
            viewer = mglw.create_window_config_instance(config_cls, args=args)
        except (ValueError, RuntimeError) as exc:
            raise WindowUnavailable(_window_failure(exc, [str(w.message) for w in said])) from None
    assert isinstance(viewer, LiveViewer)
    viewer.timer.start()
    return viewer


def run_frames(viewer: LiveViewer, max_frames: int | None = None,
               until: Callable[[LiveViewer], bool] | None = None) -> int:
    """The main loop: render until the window closes, ``max_frames`` or ``until``.

    Returns the number of frames (turns of the loop; while the picture does not
    change, a glfw window waits up to ``IDLE_WAIT`` s for input in each instead of
    swapping). The caller closes with :func:`close_viewer`.
    """
    window = viewer.wnd
    frames = 0
    while not window.is_closing and (max_frames is None or frames < max_frames):
        if until is not None and until(viewer):
            break
        current, delta = viewer.timer.next_frame()
        window.use()
        window.render(current, delta)
        if not window.is_closing:  # (a closed window has no buffers to swap)
            _present_or_wait(viewer)
        frames += 1
    return frames


def _present_or_wait(viewer: LiveViewer) -> None:
    """Swap in the frame :meth:`LiveViewer.on_render` drew, or, when it drew none
    (nothing changed), let a glfw window sleep until an input event or
    :data:`IDLE_WAIT` instead of swapping the same picture again."""
    window = viewer.wnd
    if viewer.presented:
        window.swap_buffers()
    elif window.name == "glfw":
        import glfw  # the window's own backend: already loaded

        glfw.wait_events_timeout(IDLE_WAIT)


def close_viewer(viewer: LiveViewer) -> None:
    """Stop the session, free the window's GL objects and destroy the window."""
    viewer._close_session()
    viewer.release_gl()
    viewer.wnd.destroy()


def view(options: ViewOptions) -> int:
    """``livemod view``: open the window and run until it is closed."""
    viewer = create_viewer(options)
    try:
        run_frames(viewer)
    except KeyboardInterrupt:
        pass
    finally:
        close_viewer(viewer)
    return 0


