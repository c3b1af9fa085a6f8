"""Run one user script against a fresh copy of the base scene.

:func:`execute` is the whole life of one run: read, compile (syntax errors
stop here), bind a copy of the base scene, seed the random generators, ``exec``
the script in a fresh namespace with the thesis commands in it, record a
:class:`StepRecord` after every modeling command, and report what happened. It
runs in whatever thread calls it; the session calls it from a worker thread.
"""

from __future__ import annotations

import builtins
import contextlib
import ctypes
import os
import random
import sys
import threading
import time
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from types import CodeType

import numpy as np

import livemod.dlfl as dlfl
from livemod.dlfl.io import load_mesh
from livemod.dlfl.scene import Scene, Selection, use_scene

from .errors import Cancelled, cancelled_error, exception_error, is_user_file, syntax_error
from .instrument import CANCEL_FLAG, STOP_FUNCTION, compile_script, read_script
from .recording import RunControl, StepRecorder
from .results import ScriptError, StepRecord


@dataclass
class RunOutcome:
    """What :func:`execute` returns (mutable, worker-side; see RunResult for snapshots).

    Attributes:
        status: ``"ok"``, ``"error"`` or ``"cancelled"``.
        scene: the run's scene as the script left it.
        steps: the steps that finished.
        error: the error for ``"error"``/``"cancelled"``.
        elapsed: seconds from the start of compilation to the end.
        modules: files of local modules the script imported (to be watched).
        source: the text that ran.
    """

    status: str
    scene: Scene
    steps: Sequence[StepRecord]
    error: ScriptError | None
    elapsed: float
    modules: tuple[str, ...] = ()
    source: str = ""

    @property
    def files_read(self) -> tuple[str, ...]:
        """The mesh files the script loaded and did not also save, in order (to be
        watched: a run that rewrites its own input must not start the next one)."""
        written = set(self.scene.files_written)
        return tuple(dict.fromkeys(p for p in self.scene.files_read if p not in written))

    @property
    def declarations(self) -> dict:
        """``name -> ParamSpec`` the script declared with ``param()``, in order."""
        return dict(self.scene.declarations)


def _raise_cancelled() -> None:
    raise Cancelled


def script_namespace(path: str, parameters: dict | None) -> dict:
    """Fresh globals: the thesis commands, ``__file__``, and the parameters."""
    namespace: dict = {name: getattr(dlfl, name) for name in dlfl.__all__}
    namespace.update(
        __name__="__main__", __file__=path, __builtins__=builtins, __doc__=None,
        __package__=None,
    )
    namespace[STOP_FUNCTION] = _raise_cancelled
    namespace[CANCEL_FLAG] = False
    namespace.update(parameters or {})
    return namespace


def seed_generators(seed: int | None) -> None:
    """Seed ``random`` and ``numpy.random`` (None leaves them alone)."""
    if seed is not None:
        random.seed(seed)
        np.random.seed(seed % 2**32)


@contextlib.contextmanager
def script_folder_on_path(path: str) -> Iterator[None]:
    """Put the script's folder first on ``sys.path`` for the duration of the run,
    also when it is on it already but later, where a same-named module in an
    earlier folder would shadow the script's own helper."""
    folder = os.path.dirname(path)
    sys.path.insert(0, folder)
    try:
        yield
    finally:
        with contextlib.suppress(ValueError):  # the script may have taken it out
            sys.path.remove(folder)  # the first: ours, unless the script added another


@contextlib.contextmanager
def local_modules(path: str, found: list[str]) -> Iterator[None]:
    """Collect (into ``found``) and purge the local modules a run imports.

    Modules first imported during the run whose file lies in the script's folder
    are removed from ``sys.modules`` afterwards, so the next run imports them
    again from disk (that is how edited helpers take effect).
    """
    before = set(sys.modules)
    try:
        yield
    finally:
        for name in set(sys.modules) - before:
            file = getattr(sys.modules.get(name), "__file__", None)
            if file and is_user_file(os.path.abspath(file), path):
                found.append(os.path.abspath(file))
                sys.modules.pop(name, None)


def base_scene(mesh_path: str | None) -> Scene:
    """An empty scene, or one holding the mesh read from ``mesh_path``."""
    scene = Scene()
    if mesh_path is not None:
        scene.add(load_mesh(os.fspath(mesh_path)), os.path.basename(mesh_path))
    return scene


def prepare_scene(base: Scene | None, selection: Selection | None,
                  parameters: dict | None) -> Scene:
    """A private copy of ``base`` with the caller's selection and parameters."""
    scene = base.copy() if base is not None else Scene()
    if selection is not None:
        scene.selection = selection
    scene.parameters = dict(parameters or {})
    return scene


def execute(
    path: str | os.PathLike[str], *, source: str | None = None, base: Scene | None = None,
    seed: int | None = 0, parameters: dict | None = None,
    selection: Selection | None = None, control: RunControl | None = None,
) -> RunOutcome:
    """Run the script at ``path`` once, in the calling thread.

    Args:
        path: the script (its folder goes on ``sys.path`` during the run).
        source: the text to run; read from ``path`` when None.
        base: the scene the run starts from (copied, never changed); empty if None.
        seed: seeds ``random`` and ``numpy.random`` first; None leaves them alone.
        parameters: globals for the script, also put in ``scene.parameters``.
        selection: what ``faces(True)`` and friends return.
        control: lets other threads cancel or pause the run.

    Returns:
        A :class:`RunOutcome`; script errors are reported in it, never raised.

    Raises:
        OSError: ``path`` cannot be read (only when ``source`` is None).
    """
    script = os.path.abspath(os.fspath(path))
    started = time.perf_counter()
    scene = prepare_scene(base, selection, parameters)
    scene.directory = os.path.dirname(script)
    try:
        if source is None:
            source = read_script(script)
        code = compile_script(source, script)
    except SyntaxError as exc:
        return RunOutcome("error", scene, (), syntax_error(exc, script), time.perf_counter() - started,
                          source=source or "")
    recorder = StepRecorder(script, scene, control)
    recorder.install()
    namespace = script_namespace(script, parameters)
    if control is not None:
        control.attach(namespace, recorder)
    try:
        status, error, modules = _exec(code, namespace, script, scene, recorder, seed)
    finally:  # also for a Ctrl-C: the hook and the frames it caches must not outlive the run
        recorder.release()
    return RunOutcome(status, scene, recorder.steps, error,
                      time.perf_counter() - started, tuple(modules), source)


def _exec(code: CodeType, namespace: dict, script: str, scene: Scene,
          recorder: StepRecorder, seed: int | None,
          ) -> tuple[str, ScriptError | None, list[str]]:
    """``exec`` with the scene bound; returns ``(status, error, local module files)``."""
    modules: list[str] = []
    try:
        with use_scene(scene), script_folder_on_path(script), local_modules(script, modules):
            seed_generators(seed)
            exec(code, namespace)  # noqa: S102  (running the user's script is the point)
    except Cancelled:
        steps = recorder.steps
        line = steps[-1].line if steps else None
        return "cancelled", cancelled_error(script, line), modules
    except SystemExit as exc:
        if exc.code not in (None, 0):
            return "error", exception_error(exc, script), modules
    except BaseException as exc:  # a script's own BaseException is its error, too
        if _is_ctrl_c(exc):
            raise
        return "error", exception_error(exc, script), modules
    return "ok", None, modules


def _is_ctrl_c(exc: BaseException) -> bool:
    """True for a KeyboardInterrupt in the main thread, which is where Python puts
    Ctrl-C: ``livemod run`` must stop then. In a worker thread no signal can raise
    one, so there it is the script's own ``raise KeyboardInterrupt``."""
    return (isinstance(exc, KeyboardInterrupt)
            and threading.current_thread() is threading.main_thread())


def interrupt_user_code(thread: threading.Thread, script: str) -> bool:
    """Last resort for a cancelled run that does not stop: raise :class:`Cancelled`
    in ``thread`` if it is executing the user's own code right now.

    The compiled-in checks cover the script itself; this covers loops in the
    script's local modules. Library frames are never interrupted (a library
    operation ends at its next step instead), so the exception is only sent when
    the innermost frame belongs to the script or a file in its folder.

    Returns:
        True when the exception was sent.
    """
    ident = thread.ident
    if ident is None:
        return False
    frame = sys._current_frames().get(ident)
    if frame is None or not is_user_file(frame.f_code.co_filename, script):
        return False
    sent = ctypes.pythonapi.PyThreadState_SetAsyncExc(
        ctypes.c_ulong(ident), ctypes.py_object(Cancelled))
    return bool(sent == 1)
