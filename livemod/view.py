"""Seeing models from Python: in a notebook, or in a session without a script file.

* :func:`show` opens the live window on a mesh, a scene or a run's result built in
  Python (as ``trimesh.Trimesh.show()`` does): orbit, pick, measure, cut it open as
  in ``livemod view``. It blocks until the window is closed, or with
  ``block=False`` returns at once with a handle to update or close the window.
* :func:`picture` (a still), :func:`turntable` (an animation around the up axis)
  and :func:`film` (a frame per modeling step of a script) return objects a
  notebook shows inline, as PNG and animated PNG, and that ``save(path)`` to a
  file as ``livemod render`` writes it. A bare :class:`~livemod.dlfl.Mesh`, a
  :class:`~livemod.dlfl.Scene` or a run's result shows as a picture by itself.

The window opens in a process of its own (a fresh interpreter, so no user module is
imported again): GL windows need their process's main thread, which a notebook's
kernel or a Python prompt keeps for itself, and a window's GLX context does not mix
with the EGL contexts of the pictures in one process. Models reach it pickled, as
immutable render snapshots.
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
import pickle
import queue
import subprocess
import sys
import threading
from collections.abc import Callable
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.scene import Scene, Selection
from livemod.runner.playback import DEFAULT_RATE, MAX_RATE, MIN_RATE, PlaybackState, PlaybackView
from livemod.runner.results import RunResult, freeze_arrays, object_fields, snapshot_scene
from livemod.viewer.film import film
from livemod.viewer.pictures import Animation, Picture, picture, turntable

if TYPE_CHECKING:
    from livemod.viewer.session import Session

__all__ = ["Animation", "Picture", "ShownWindow", "WindowUnavailable", "film", "open_windows",
           "picture", "show", "turntable"]

WINDOW_SIZE = (1280, 800)
OPENED = "opened"  # the window process's line on its stdout once the window is up


class WindowUnavailable(OSError):
    """No window could be opened (no display, no GL); the message says why."""


def show(model: object, *, block: bool = True, size: tuple[int, int] = WINDOW_SIZE,
         title: str | None = None) -> ShownWindow:
    """Open the live window on ``model``: a Mesh, a MeshArrays, a Scene (its current
    object, and the others in the objects panel) or a run's RunResult.

    With ``block`` (the default) it returns when the window is closed; else as soon
    as the window is up, with a :class:`ShownWindow` to :meth:`~ShownWindow.update`
    it with another model, :meth:`~ShownWindow.wait` for it or
    :meth:`~ShownWindow.close` it. Ctrl-C while blocked closes the window. What is
    picked in it is echoed on standard error, as Python (``faces(True) == (12,)``).

    Raises:
        InvalidArgumentError: ``model`` is none of those.
        WindowUnavailable: no window could be opened (the message says why: no
            display, say); nothing is left running.
    """
    name = title or type(model).__name__.lower()
    first = shown_result(model, name)
    window = ShownWindow(name)
    window.open(first, size)
    if block:
        try:
            window.wait()
        except KeyboardInterrupt:
            window.close()
    return window


def shown_result(model: object, name: str, run_id: int = 1) -> RunResult:
    """``model`` as the finished result of a run of no steps, named ``name``, that
    the window shows (a RunResult as it is).

    Raises:
        InvalidArgumentError: ``model`` is not a Mesh, MeshArrays, Scene or RunResult.
    """
    if isinstance(model, RunResult):
        return dataclasses.replace(model, run_id=run_id)
    if isinstance(model, MeshArrays):
        return RunResult.finished(run_id, name, (), freeze_arrays(model), 0.0)
    if isinstance(model, Mesh):
        scene = Scene()
        scene.add(model, name)  # (not changed: the snapshot copies it)
        model = scene
    if isinstance(model, Scene):
        return RunResult.finished(run_id, name, (), snapshot_scene(model), 0.0,
                                  **object_fields(model))
    raise InvalidArgumentError(f"show takes a Mesh, MeshArrays, Scene or RunResult, not "
                               f"{type(model).__name__}")


_OPEN: list[ShownWindow] = []


def open_windows() -> list[ShownWindow]:
    """The windows :func:`show` opened that are still open."""
    _OPEN[:] = [window for window in _OPEN if window.is_open]
    return list(_OPEN)


class ShownWindow:
    """A live window :func:`show` opened, in its own process."""

    def __init__(self, name: str) -> None:
        self.name = name
        self._process: subprocess.Popen[bytes] | None = None
        self._runs = 1

    def open(self, first: RunResult, size: tuple[int, int]) -> None:
        """Start the window's process on ``first`` and wait until the window is up.

        Raises:
            WindowUnavailable: it could not open one (the process has ended).
        """
        code = "from livemod.view import serve_window; serve_window()"
        self._process = subprocess.Popen([sys.executable, "-c", code], stdin=subprocess.PIPE,
                                         stdout=subprocess.PIPE)
        with contextlib.suppress(BrokenPipeError):  # it ended at once: said below
            self._send((self.name, size, first))
        said = self._stdout.readline().decode("utf-8", "replace").strip()
        if said != OPENED:
            self.wait()
            raise WindowUnavailable(said or f"the window's process ended with exit code "
                                            f"{self._process.returncode}")
        _OPEN.append(self)

    @property
    def is_open(self) -> bool:
        """True until the window is closed (by its user or :meth:`close`)."""
        return self._process is not None and self._process.poll() is None

    def update(self, model: object) -> None:
        """Show ``model`` instead (as a new run: the camera stays where it is).

        Raises:
            InvalidArgumentError: ``model`` is not a model :func:`show` takes.
            WindowUnavailable: the window was closed.
        """
        self._runs += 1
        result = shown_result(model, self.name, self._runs)
        try:
            self._send(result)
        except (BrokenPipeError, ValueError):  # its process has gone
            raise WindowUnavailable(f"the window of {self.name} was closed") from None

    def wait(self, timeout: float | None = None) -> bool:
        """Wait until the window is closed (at most ``timeout`` seconds); True when it is."""
        process = self._process
        if process is None:
            return True
        try:
            process.wait(timeout)
        except subprocess.TimeoutExpired:
            return False
        for pipe in (process.stdin, process.stdout):  # (the process has ended)
            if pipe is not None:
                with contextlib.suppress(OSError):  # a flush into a closed pipe
                    pipe.close()
        return True

    def close(self, timeout: float = 10.0) -> None:
        """Close the window (its process ends; ended at once after ``timeout`` s)."""
        process = self._process
        if process is None or process.poll() is not None:
            return
        with contextlib.suppress(BrokenPipeError, ValueError):  # gone meanwhile
            self._send(None)
        if not self.wait(timeout):
            process.kill()
            self.wait()

    @property
    def _stdout(self) -> IO[bytes]:
        assert self._process is not None and self._process.stdout is not None
        return self._process.stdout

    def _send(self, message: object) -> None:
        assert self._process is not None and self._process.stdin is not None
        pickle.dump(message, self._process.stdin, protocol=pickle.HIGHEST_PROTOCOL)
        self._process.stdin.flush()


# -- the window's process ---------------------------------------------------------------


class ShownSession:
    """The window's session for models posted from Python: nothing runs, each model
    arrives as a finished result of no steps, and the step keys have nothing to show.

    Attributes:
        results: the results the window takes (see :class:`~livemod.viewer.session.Session`).
    """

    def __init__(self, first: RunResult) -> None:
        self.results: queue.Queue[RunResult] = queue.Queue()
        self.latest = first
        self.selection = Selection()
        self._rate = DEFAULT_RATE

    def post(self, result: RunResult) -> None:
        """Show ``result`` next."""
        self.latest = result
        self.results.put(result)

    def start(self) -> None:
        self.post(self.latest)

    def close(self) -> None:
        return

    def reload(self) -> None:
        self.post(self.latest)

    @property
    def activity(self) -> None:
        return None

    @property
    def empty_script(self) -> None:
        return None

    @property
    def background_runs(self) -> tuple[int, ...]:
        return ()  # it runs no script

    @property
    def playback(self) -> PlaybackView:
        return PlaybackView(PlaybackState.FINISHED, None, self._rate)

    @property
    def play_rate(self) -> float:
        return self._rate

    def faster(self) -> float:
        self._rate = min(self._rate * 2.0, MAX_RATE)
        return self._rate

    def slower(self) -> float:
        self._rate = max(self._rate / 2.0, MIN_RATE)
        return self._rate

    def toggle_play(self) -> bool:
        return False

    def play(self, rate: float | None = None) -> bool:
        return False

    def pause(self) -> bool:
        return False

    def resume(self) -> bool:
        return False

    def run_to_end(self) -> bool:
        return False

    def step_forward(self) -> bool:
        return False

    def step_back(self) -> bool:
        return False

    def goto_step(self, k: int) -> bool:
        return False

    def cancel(self) -> bool:
        return False

    @property
    def parameters(self) -> dict[str, Any]:
        return {}

    def set_parameters(self, values: dict[str, Any]) -> None:
        if values:
            raise InvalidArgumentError(f"a model shown from Python has no parameters, "
                                       f"not {', '.join(values)}")

    def reset_parameters(self, names: list[str] | None = None) -> None:
        return

    def set_selection(self, selection: Selection | None) -> None:
        self.selection = selection or Selection()


def serve_window() -> None:
    """The window's process (see :class:`ShownWindow`): read ``(name, size, first
    result)`` from stdin, open the window, say :data:`OPENED` (or why not) on stdout,
    show each result read after it, and close at a None, at the end of stdin or when
    the window is closed. Echoes go to stderr."""
    from livemod.viewer.window import (
        ViewOptions,
        WindowUnavailable,
        close_viewer,
        create_viewer,
        run_frames,
    )

    source = sys.stdin.buffer
    name, size, first = pickle.load(source)
    session = ShownSession(first)
    options = ViewOptions(name, size=size, session_factory=window_sessions(session, name),
                          echo=sys.stderr)
    try:
        viewer = create_viewer(options)
    except WindowUnavailable as exc:
        print(str(exc), flush=True)
        return
    print(OPENED, flush=True)
    # nobody reads stdout from now on: what is printed goes where the echoes go
    os.dup2(sys.stderr.fileno(), sys.stdout.fileno())
    closing = threading.Event()
    threading.Thread(target=_read_models, args=(source, session, closing), daemon=True).start()
    try:
        run_frames(viewer, until=lambda _viewer: closing.is_set())
    except KeyboardInterrupt:  # Ctrl-C at the prompt reaches the whole process group
        pass
    finally:
        close_viewer(viewer)


def window_sessions(shown: ShownSession, name: str) -> Callable[[str, str | None], Session]:
    """The window's session factory: ``shown``, showing a mesh file dropped on the
    window when one is; a dropped script runs live, as in ``livemod view``."""
    placeholder = str(Path(name).resolve())  # the window's "script"

    def create(script: str, mesh_path: str | None) -> Session:
        if script != placeholder:
            from livemod.viewer.window import ViewOptions, live_sessions

            return live_sessions(ViewOptions(script))(script, mesh_path)
        if mesh_path is not None:
            from livemod.dlfl.errors import DLFLError
            from livemod.dlfl.io import load_mesh

            try:
                shown.latest = shown_result(load_mesh(mesh_path), Path(mesh_path).name)
            except (OSError, DLFLError) as exc:  # the model shown stays
                print(f"livemod: error: {exc}", file=sys.stderr, flush=True)
        return shown

    return create


def _read_models(source: IO[bytes], session: ShownSession, closing: threading.Event) -> None:
    """Post each result read from ``source`` until a None or its end, then set ``closing``."""
    try:
        while (result := pickle.load(source)) is not None:
            session.post(result)
    except (EOFError, OSError, pickle.UnpicklingError):
        pass
    closing.set()
