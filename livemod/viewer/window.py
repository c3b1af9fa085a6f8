"""The live window: a moderngl-window ``WindowConfig`` over a runner session.

The window is a composition. The session (:class:`~livemod.viewer.session.Session`)
runs the script in its own threads and posts immutable results to a queue;
:meth:`LiveViewer.on_render` drains that queue without blocking, and does all GL
work on the main thread. What the window knows and does is kept by one object
each: :class:`~livemod.viewer.script_session.ScriptSession` (the script and its
session, and the results taken), :class:`~livemod.viewer.runs.RunTracker` (the
runs), :class:`~livemod.viewer.painter.FramePainter` (each frame: its picture,
quick or whole, kept or drawn, and the overlay over it), and the controllers
:class:`~livemod.viewer.stepping.Stepping`, :class:`~livemod.viewer.parameters.Parameters`,
:class:`~livemod.viewer.objects.SceneObjects`, :class:`~livemod.viewer.picking.Picking`,
:class:`~livemod.viewer.section.SectionPlane` and :class:`~livemod.viewer.look.Look`.
A key runs its action from the table of :mod:`livemod.viewer.actions`; the HUD and
the overlay's cache key derive from one :class:`~livemod.viewer.view_state.ViewState`.
:func:`create_viewer` builds the window with explicit arguments (moderngl-window
would otherwise parse ``sys.argv``), and :func:`run_frames` is the main loop, also
used by tests on the headless backend.
"""

from __future__ import annotations

import logging
import os
import re
import sys
import warnings
from collections.abc import Callable
from dataclasses import dataclass, replace
from functools import partial
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, TextIO

import moderngl_window as mglw
import numpy as np

from livemod.dlfl.scene import Selection

from .actions import check_bindings, window_actions
from .camera import Camera
from .controls import action_for
from .display import MeshDisplay
from .frames import Frames
from .imagefiles import save_numbered_png
from .look import Look
from .measure import WholeMeshMeasurer
from .objects import SceneObjects
from .overlay import Overlay
from .painter import FramePainter
from .parameters import Parameters
from .picking import Picking
from .pointer import Buttons, Pointer
from .renderer import Renderer, Style, render_offscreen
from .runs import RunTracker
from .script_session import ScriptSession, SessionFactory
from .section import SectionPlane
from .session import Session
from .smoothing import PreviewControl
from .stepping import Stepping
from .view_state import ViewState

if TYPE_CHECKING:
    from livemod.runner.results import RunResult

IDLE_WAIT = 0.01  # seconds an idle glfw loop waits for input between frames


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
        echo: where run summaries, selections and errors are echoed (stdout when None).
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
    session_factory: SessionFactory | None = None
    echo: TextIO | None = None
    poll: bool = False
    parameters: dict[str, Any] | None = None
    selection: Selection | None = None
    output: str | None = None
    all_objects: bool = False


def live_sessions(options: ViewOptions) -> SessionFactory:
    """The window's sessions as ``livemod view`` makes them: the runner's
    ``LiveSession`` (imported only when a window opens) with ``options``' poll,
    seed, parameters and output, and no preview of its own."""
    from livemod.runner import LiveSession

    def create(script: str, mesh_path: str | None) -> Session:
        # (no preview of the session's own: the window asks for its own, of every
        # object drawn, at the density shown; see PreviewControl)
        return LiveSession(script, mesh_path=mesh_path, poll=options.poll, seed=options.seed,
                           parameters=options.parameters, output=options.output,
                           all_objects=options.all_objects, preview=False)

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
    """The live viewer window; configure through :func:`create_viewer`.

    Attributes:
        scripts: the script shown and its session (:attr:`session`).
        runs: what the window knows of the session's runs.
        look, stepping, parameters, objects, picking, section: the controllers.
        display: the mesh on screen.
        overlay, pointer: the panels over the scene, and the mouse.
        actions: action name -> what it does (every key binding's action is in it).
        painter: the frames: quick or whole pictures, the kept frame, the frame rate.
        screenshots: the screenshots written, in order.
        clipboard: puts text on the window's clipboard (None: the backend has none).
    """

    gl_version = (3, 3)
    title = "livemod"
    aspect_ratio = None  # type: ignore[assignment]  # follow the window's shape
    resizable = True
    clear_color = None  # type: ignore[assignment]  # the renderer clears
    log_level = logging.WARNING
    options: ClassVar[ViewOptions]

    def __init__(self, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.wnd.exit_key = None  # Esc clears the selection instead
        self.clipboard = glfw_clipboard(self)
        self.renderer = Renderer(self.ctx)
        self.camera = Camera()
        self.whole = WholeMeshMeasurer()  # genus and volume of the mesh shown, off-thread
        self._compose()
        self.renderer.set_selection(self.picking.selection)
        self.screenshots: list[Path] = []
        self._key_names = _key_names(self.wnd.keys)
        self._start_session()
        install_glfw_drop(self)

    def _compose(self) -> None:
        """Make the controllers and the action table (checked: every key binding has
        its handler)."""
        self.runs = RunTracker()
        options, echo = self.options, self._echo
        self.scripts = ScriptSession(options.script, options.mesh_path,
                                     options.session_factory or live_sessions(options),
                                     self.runs, echo, options.output)
        session = self.scripts.live
        self.look = Look()
        self.stepping = Stepping(self.runs, session, echo)
        self.parameters = Parameters(self.runs, session, echo)
        self.picking = Picking(session, echo, self.options.selection)
        self.objects = SceneObjects(self.runs, self.look, echo,
                                    lambda others: self.display.show_others(others))
        self.section = SectionPlane(self.look, lambda: self.renderer.bounds, echo)
        self.overlay = Overlay(self.look, self.runs, self.parameters, self.objects)
        self.display = MeshDisplay(self.renderer, self.camera, self.whole, self.picking,
                                   self.objects, self.look, lambda: self.screen_size, echo)
        self.smoothing = PreviewControl(
            self.renderer, self.look, self.camera, lambda: self.display.content,
            lambda: self.screen_size[0] / max(self.screen_size[1], 1), echo)
        self.painter = FramePainter(self.ctx, self.renderer, self.camera, self.overlay)
        self.pointer = Pointer(self.overlay, self.parameters, self.objects, self.stepping,
                               self.camera, self._framebuffer)
        self.actions = window_actions(self)
        check_bindings(self.actions)

    # -- what the tests and the keys read --------------------------------------------

    @property
    def result(self) -> RunResult | None:
        """The result shown."""
        return self.runs.result

    @property
    def waiting(self) -> bool:
        """The window asked for a result that has not come yet."""
        return self.runs.waiting

    @property
    def frames(self) -> Frames:
        """The kept frame and the frame rate (the painter's)."""
        return self.painter.frames

    @property
    def selection(self) -> Selection:
        """The picks: what the next run's ``faces(True)`` and the like return."""
        return self.picking.selection

    @property
    def session(self) -> Session | None:
        """The session of the script shown (None once closed)."""
        return self.scripts.session

    @property
    def script(self) -> str:
        """The absolute path of the script shown."""
        return self.scripts.script

    @property
    def style(self) -> Style:
        """What the renderer draws."""
        return self.look.style

    @property
    def screen_size(self) -> tuple[int, int]:
        """The window's framebuffer size in pixels now. Not ``wnd.fbo.size``: moderngl's
        screen framebuffer keeps the size the window opened with, so after a resize
        the frame would be drawn (and picked, and laid out) at the old size."""
        width, height = self.wnd.buffer_size
        return int(width), int(height)

    # -- the session --------------------------------------------------------------------

    def _start_session(self, parameters: dict[str, Any] | None = None) -> None:
        """Start the session of the script shown, its first run with ``parameters``
        (over ``--set``'s) when given."""
        self.scripts.start(self.picking.selection, parameters)
        self.wnd.title = f"livemod - {Path(self.scripts.script).name}"

    def _apply(self, result: RunResult) -> None:
        """Show ``result``: its objects, steps and parameters, then its mesh."""
        self.objects.sync(result)
        self.runs.take(result)
        self.parameters.sync(result)
        self.display.show(result)

    def _echo(self, line: str) -> None:
        stream = self.options.echo if self.options.echo is not None else sys.stdout
        print(line, file=stream, flush=True)

    # -- frames ---------------------------------------------------------------------------

    def on_render(self, time_now: float, frame_time: float) -> None:
        """Draw a frame (moderngl-window's callback): take the runner's newest
        result, upload it, draw or copy the kept frame, then the HUD and panels."""
        self.frames.begin_turn()
        self.parameters.flush()
        self.stepping.flush_scrub()
        self.scripts.take_results(self._apply)
        self.display.advance()
        self.smoothing.update()
        self.stepping.repeat_held()
        self.runs.poll(self.scripts.live())
        self.painter.follow_view(self.look.style)
        self.painter.paint(self.wnd.fbo, self.view_state(),
                           idle_ok=self.wnd.name in ("glfw", "headless"))

    def view_state(self) -> ViewState:
        """What the overlay shows now (the panels laid out for the window's size)."""
        size, runs, result = self.screen_size, self.runs, self.runs.result
        playback = self.stepping.view
        self.overlay.lay_out(size)
        selection, missing = self.picking.hud_lines(
            self.renderer.arrays, () if result is None else result.unselected)
        return ViewState(
            script=self.script, result=result, waiting=runs.waiting, working=runs.working(),
            running_run=None if runs.activity is None else runs.activity.run_id,
            background=runs.background,
            good_run=runs.good_run, total_steps=runs.total_steps, arrays=self.renderer.arrays,
            partial=self.display.show_partial, nonfinite=self.renderer.nonfinite,
            viewer_error=runs.viewer_error, empty_script=runs.empty_script,
            whole=self.whole.facts(), fps=self.frames.fps, pick_mode=self.picking.mode,
            selection=tuple(selection), missing=tuple(missing),
            measures=tuple(self.picking.measures), others=self.renderer.others,
            others_note=self.objects.note(), current_hidden=not self.look.style.current,
            style=self.look.style, preview=self.smoothing.hud_line(), quick=self.painter.quick,
            ortho=self.camera.ortho, playback=playback.state,
            rate=playback.rate, hud=self.look.show_hud, help=self.look.show_help,
            panels=self.overlay.state(), size=size, bottom=self.overlay.error_room(size))

    def capture(self, transparent: bool = False) -> np.ndarray:
        """Render the scene (no HUD) offscreen at the window's size: ``(H, W, 3)``
        uint8, or ``(H, W, 4)`` with alpha 0 where nothing is drawn when
        ``transparent``."""
        style = self.look.style
        if transparent:
            style = replace(style, background=(*style.background[:3], 0.0))
        try:
            return render_offscreen(self.renderer, self.camera, style, self.screen_size)
        finally:
            self.wnd.use()

    def save_screenshot(self, transparent: bool = False) -> Path:
        """Write :meth:`capture` to ``<script>_NNN.png`` in the working directory and
        return its path. NNN starts at the count of this window's screenshots and
        goes up past every name taken (see :func:`~.imagefiles.save_numbered_png`),
        so a file that another process writes meanwhile is never written over."""
        path = save_numbered_png(Path(self.script).stem, len(self.screenshots),
                                 self.capture(transparent))
        self.screenshots.append(path)
        self._echo(f"screenshot: {path}")
        return path

    def release_gl(self) -> None:
        """Free the GL objects the window made (the kept frame, and the renderer's:
        see :meth:`Renderer.release`); calling it again does nothing. Nothing may be
        drawn after it. :func:`close_viewer` calls it before destroying the window."""
        self.ctx.__enter__()  # (GL calls go to the context made current last)
        self.frames.release()
        self.renderer.release()

    def on_close(self) -> None:
        """The window closes: stop the session's threads and the window's own
        (moderngl-window's callback)."""
        self._close_session()
        self.close_workers()

    def close_workers(self) -> None:
        """Stop the threads that prepare meshes and previews (again: nothing)."""
        self.display.close()
        self.smoothing.close()

    # -- keys ---------------------------------------------------------------------------

    def on_key_event(self, key: Any, action: Any, modifiers: Any) -> None:
        """A key press runs its binding (see ``H`` and docs/viewer.md); a step key
        held down steps on (see :meth:`Stepping.repeat_held`). The toolkit's own
        repeats do nothing: glfw's come at the system's rate, pyglet sends none, and
        the frame loop's timer repeats at one rate in every backend."""
        keys = self.wnd.keys
        if action == keys.ACTION_RELEASE:
            self.stepping.release(key)
        elif action == keys.ACTION_PRESS:
            name = self._key_names.get(key)
            done = None if name is None else self.handle_key(
                name, shift=bool(modifiers.shift), ctrl=bool(modifiers.ctrl))
            self.stepping.hold(key, done)

    def handle_key(self, name: str, shift: bool = False, ctrl: bool = False) -> str | None:
        """Run the action bound to key ``name``; returns the action (None if unbound)."""
        action = action_for(name, shift, ctrl)
        if action is not None:
            self.actions[action]()
        return action

    # -- mouse ----------------------------------------------------------------------------

    def on_mouse_press_event(self, x: int, y: int, button: int) -> None:
        """A press on a panel, the object list or the timeline acts there; on the
        model it starts a click (pick) or a drag (orbit, pan)."""
        self.pointer.press(x, y)

    def on_mouse_position_event(self, x: int, y: int, dx: int, dy: int) -> None:
        self.pointer.move(x, y)

    def on_mouse_drag_event(self, x: int, y: int, dx: int, dy: int) -> None:
        states, shift = self.wnd.mouse_states, bool(self.wnd.modifiers.shift)
        self.pointer.drag(x, y, dx, dy, Buttons(states.left, states.right, states.middle, shift))

    def on_mouse_release_event(self, x: int, y: int, button: int) -> None:
        """End a drag, or pick on a left click that did not move (shift adds)."""
        if self.pointer.release() and button == self.wnd.mouse.left:
            self.click(x, y, add=bool(self.wnd.modifiers.shift))

    def on_mouse_scroll_event(self, x_offset: float, y_offset: float) -> None:
        self.pointer.scroll(y_offset)

    def _framebuffer(self) -> tuple[tuple[int, int], float]:
        """The framebuffer's size, and its pixels per window point."""
        size = self.screen_size
        return size, size[0] / max(self.wnd.size[0], 1)

    def click(self, x: float, y: float, add: bool = False) -> None:
        """Pick at window point ``(x, y)`` in the current mode and update the selection.

        A click on the background without ``add`` clears the selection.
        """
        size, ratio = self._framebuffer()
        hit = self.renderer.pick(self.camera, size, int(x * ratio), int(y * ratio),
                                 self.picking.mode, radius=int(6 * ratio))
        self.wnd.use()
        selection = self.picking.clicked(None if hit is None else hit.element_id, add)
        if selection is not None:
            self.set_selection(selection)

    def set_selection(self, selection: Selection) -> None:
        """Show ``selection``, send it to the session and echo it as Python."""
        self.picking.select(selection, self.renderer.arrays)
        self.renderer.set_selection(selection)

    # -- files ------------------------------------------------------------------------------

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
        kept = self.parameters.values()  # (asked of the session: before it closes)
        had_selection = not self.picking.selection.is_empty()
        self._close_session()
        is_script = self.scripts.retarget(path)
        self._forget_the_run(keep_parameters=not is_script)
        self._start_session(None if is_script else kept)
        self._echo(f"opened {Path(path).resolve()}")
        if not is_script:
            note = "; the selection was cleared (its ids were the old mesh's)" \
                if had_selection else ""
            self._echo(f"the script runs on the new mesh with its parameter values kept{note}")

    def _forget_the_run(self, keep_parameters: bool = False) -> None:
        """Drop what the window kept of the runs of the session just closed: the
        next script's ids, steps and parameters are its own, and a key held, a
        scrub, E or a viewer error of the old one must not carry over to it. With
        ``keep_parameters`` (a new mesh for the same script) the parameter panel
        stays as it is, but for edits in flight, which the caller passes on."""
        self.picking.forget()
        self.renderer.set_selection(self.picking.selection)
        self.objects.forget()
        self.display.forget()  # (fit the new script's first result)
        self.runs.forget()
        self.stepping.forget()
        self.pointer.forget()
        self.parameters.forget(keep_panel=keep_parameters)

    def _close_session(self) -> None:
        self.whole.close()
        self.scripts.close()


def _glfw_window(viewer: LiveViewer) -> Any | None:
    """The glfw handle of ``viewer``'s window, or None for another backend."""
    handle = getattr(viewer.wnd, "_window", None)
    return handle if viewer.options.backend == "glfw" else None


def glfw_clipboard(viewer: LiveViewer) -> Callable[[str], None] | None:
    """What puts text on the clipboard of ``viewer``'s glfw window (moderngl-window
    has no clipboard of its own), or None for another backend."""
    handle = _glfw_window(viewer)
    if handle is None:
        return None
    import glfw

    return partial(glfw.set_clipboard_string, handle)


def install_glfw_drop(viewer: LiveViewer) -> None:
    """Open files dropped on ``viewer``'s window: moderngl-window's glfw backend
    does not forward drops, so glfw is hooked directly (other backends do)."""
    handle = _glfw_window(viewer)
    if handle is None:
        return
    import glfw

    def dropped(_window: Any, paths: list[str]) -> None:
        if paths:
            viewer.open_path(paths[0])

    callback: Any = dropped
    glfw.set_drop_callback(handle, callback)


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
    if viewer.frames.presented:
        window.swap_buffers()
    elif window.name == "glfw":
        import glfw  # the window's own backend: already loaded

        glfw.wait_events_timeout(IDLE_WAIT)


def close_viewer(viewer: LiveViewer) -> None:
    """Stop the session, free the window's GL objects and destroy the window."""
    viewer._close_session()
    viewer.close_workers()
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


