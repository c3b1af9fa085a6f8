"""Run one user script against a fresh copy of the base scene.

:func:`execute` is the whole life of one run: read, compile (syntax errors
stop here), bind a copy of the base scene and a fresh run context (the run's
parameters and folder, and what its commands report), seed the random generators, ``exec``
the script in a fresh namespace with the thesis commands in it, record a
:class:`StepRecord` after every modeling command, and report what happened. It
runs in whatever thread calls it; the session calls it from a worker thread.
"""

from __future__ import annotations

import builtins
import ctypes
import os
import random
import sys
import threading
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from types import CodeType, ModuleType
from typing import NoReturn

import numpy as np

import livemod.dlfl as dlfl
from livemod.dlfl.io import load_mesh
from livemod.dlfl.run_context import RunContext, use_run
from livemod.dlfl.scene import Scene, Selection, use_scene

from .errors import Cancelled, cancelled_error, exception_error, is_user_file, syntax_error
from .instrument import CANCEL_FLAG, STOP_FUNCTION, compile_script, read_script
from .process import ProcessState
from .recording import RunControl, StepRecord, StepRecorder
from .results import ScriptError


@dataclass
class RunOutcome:
    """What :func:`execute` returns (mutable, worker-side; see RunResult for snapshots).

    Attributes:
        status: ``"ok"``, ``"error"`` or ``"cancelled"``.
        scene: the run's scene as the script left it.
        run: the run's context: its parameters and folder, and what the
            commands told it (declarations, files, picks).
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
    run: RunContext = field(default_factory=RunContext)

    @property
    def files_read(self) -> tuple[str, ...]:
        """The mesh files the script loaded and did not also save, in order (to be
        watched: a run that rewrites its own input must not start the next one)."""
        written = set(self.run.files_written)
        return tuple(dict.fromkeys(p for p in self.run.files_read if p not in written))

    @property
    def declarations(self) -> dict:
        """``name -> ParamSpec`` the script declared with ``param()``, in order."""
        return dict(self.run.declarations)


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


# Threads running a script's ``exec`` now, each with the run it runs (a token:
# its RunControl), the process it runs in and the script (see
# interrupt_user_code and _exit_guard): the forced interrupt is sent, and a
# thread leaves, under the lock, so that none is sent once the run has left the
# user's code.
_INTERRUPT_LOCK = threading.Lock()
_IN_USER_CODE: dict[int, tuple[object, int, str]] = {}


def _enter_user_code(token: object = None, script: str = "") -> None:
    """The calling thread runs the user's code of the run ``token`` of ``script``
    from now on (it may be interrupted, and the script's ``os._exit`` ends the run)."""
    with _INTERRUPT_LOCK:
        _IN_USER_CODE[threading.get_ident()] = (token, os.getpid(), script)


def _leave_user_code() -> None:
    """No forced interrupt is sent to the calling thread from now on. One sent
    before is raised by this call at the latest (CPython raises it at the first
    check after the lock is taken), so in the caller's ``finally``, never in
    the cleanup after it. Idempotent."""
    with _INTERRUPT_LOCK:
        _IN_USER_CODE.pop(threading.get_ident(), None)


class ProcessExit(SystemExit):  # noqa: N818  (named for what the script did)
    """``os._exit(code)`` called by a script's run: it ends the run, as
    ``sys.exit(code)`` would, never livemod (which would end with no word, and
    with a ``--watch`` or a window that the script does not own)."""

    def __str__(self) -> str:
        return f"os._exit({self.code}) ends the run here, not livemod"


_PROCESS_EXIT = os._exit


def _exit_guard(status: int) -> NoReturn:
    """``os._exit`` while livemod runs scripts: raises :class:`ProcessExit` when
    the script's own code (the script or a file in its folder) calls it in a
    run; ends the process otherwise: from another thread, from a child the
    script forked (whose entry is its parent's), from a library, or from
    livemod's own code on the run's thread (a signal handler of ``batch``)."""
    entry = _IN_USER_CODE.get(threading.get_ident())
    if entry is not None and entry[1] == os.getpid():
        try:
            caller = sys._getframe(1).f_code.co_filename
        except ValueError:  # called from C with no Python frame above: not the script
            caller = ""
        if is_user_file(caller, entry[2]):
            raise ProcessExit(status)
    _PROCESS_EXIT(status)


def capture_process() -> ProcessState:
    """The process state as it is now (see :mod:`livemod.runner.process`), with
    ``os._exit`` guarded first (see :func:`_exit_guard`; the guard stays for the
    life of the process), so that giving the state back keeps the guard."""
    os._exit = _exit_guard
    return ProcessState()


# held while a run takes or gives back the process state (see RunLease)
_STATE_LOCK = threading.Lock()


class RunLease:
    """One run's hold on the process state: :meth:`enter` pictures the process's
    settings (a live session's library is pictured once, for all its runs) and
    puts the script's folder first on ``sys.path``; :meth:`release` gives the
    process back as the run found it. A run that will not stop
    is abandoned with :meth:`revoke`, from another thread: the state is given
    back on its behalf, and the run, should it ever get to its own
    :meth:`release`, touches nothing any more. While such a run lives on, and
    once after it ended, the runs after it restore the state as they start,
    too (it may have changed it since).

    Args:
        state: the state every run of a session starts from; None takes one
            at :meth:`enter` and closes it at :meth:`release` (a single run).
    """

    def __init__(self, state: ProcessState | None = None) -> None:
        self.state = state
        self._own = state is None
        self._host: _HostState | None = None
        self._held = False
        self._revoked = False
        self._done = False  # released, or refused at enter: the run acts no more

    @property
    def files(self) -> list[str]:
        """Files of the local modules the run imported (after :meth:`release`)."""
        return self._host.files if self._host is not None else []

    def enter(self, script: str) -> bool:
        """Take the process for a run of ``script``; False when revoked already."""
        with _STATE_LOCK:
            if self._revoked:
                self._finish()
                return False
            if self.state is None:
                self.state = capture_process()
            elif self.state.abandoned or self.state.dirty:
                self.state.restore()  # what an abandoned run may have changed since
                self.state.dirty = False
            else:
                self.state.retake()  # the host's own changes since the last run stand
            self._host = _HostState(script, self.state.local_modules(
                os.path.dirname(script), lambda: _local_modules(script)))
            self._host.enter()
            self._held = True
            return True

    def release(self) -> None:
        """Give the process state back (idempotent: a late forced interrupt may
        cut it short, and it is called again)."""
        with _STATE_LOCK:
            self._give_back()
            self._finish()

    def revoke(self) -> None:
        """Give the process state back now, on behalf of a run that does not stop;
        from then on the run's own :meth:`enter` and :meth:`release` do nothing."""
        with _STATE_LOCK:
            if not self._revoked and not self._done and self.state is not None:
                self.state.abandoned += 1
            self._revoked = True
            self._give_back()

    def _give_back(self) -> None:
        if not self._held:
            return
        assert self._host is not None and self.state is not None
        self._host.leave()
        self.state.restore()
        self._held = False
        if self._own:
            self.state.close()

    def _finish(self) -> None:
        """The run acts no more: an abandoned one stops counting as one that may,
        and what it did since it was abandoned is undone as the next run starts."""
        if not self._done and self._revoked and self.state is not None:
            self.state.abandoned -= 1
            self.state.dirty = True
        self._done = True


def _local_modules(script: str) -> dict[str, ModuleType]:
    """The modules in ``sys.modules`` whose file is the user's, in the script's
    folder, by name. Every run looks at every module twice, so the folder's
    prefix is tested first (is_user_file has the last word)."""
    prefix = os.path.dirname(script) + os.sep
    found = {}
    for name, module in list(sys.modules.items()):
        file = _module_file(module)
        if file is not None and file.startswith(prefix) and is_user_file(file, script):
            found[name] = module
    return found


def _module_file(module: object) -> str | None:
    """The module's ``__file__``, absolute; read from its ``__dict__`` so that no
    code of the module runs (a module ``__getattr__``)."""
    file = getattr(module, "__dict__", _NO_DICT).get("__file__")
    if not isinstance(file, str):
        return None
    if file.startswith(os.sep) or os.path.isabs(file):  # the first test is the cheap one
        return file
    return os.path.abspath(file)


_NO_DICT: dict = {}


class _HostState:
    """The script's own modules in ``sys.modules``, and its folder on the path.

    :meth:`enter` puts the script's folder first on ``sys.path`` (also when it is
    on it already but later, where a same-named module in an earlier folder would
    shadow the script's own helper) and takes every module of the script's
    folder out of ``sys.modules``, whoever imported it (the host, say, or a run
    abandoned earlier): the script imports its helpers afresh from disk in every
    run, which is how edited helpers take effect. :meth:`leave` removes the
    modules the run imported and puts the host's back; the folder leaves the
    path as the process state is given back. It is idempotent, so that it can
    be completed when a late forced interrupt cut it short.

    Args:
        script: the script's absolute path.
        host_modules: the modules of its folder the host imported, by name.
    """

    def __init__(self, script: str, host_modules: dict[str, ModuleType]) -> None:
        self.script = script
        self.host_modules = host_modules
        self.run_modules: dict[str, ModuleType] | None = None  # set by leave()

    def enter(self) -> None:
        """Take the folder's modules out and put the folder first on the path."""
        for name in _local_modules(self.script):
            sys.modules.pop(name, None)
        sys.path.insert(0, os.path.dirname(self.script))

    def leave(self) -> None:
        """Undo :meth:`enter` for ``sys.modules``: each part checks whether it is done."""
        if self.run_modules is None:
            run = _local_modules(self.script)
            self.run_modules = {name: module for name, module in run.items()
                                if self.host_modules.get(name) is not module}
        self._remove_run_modules()
        sys.modules.update(self.host_modules)

    @property
    def files(self) -> list[str]:
        """Files of the local modules the run imported (after :meth:`leave`)."""
        modules = self.run_modules or {}
        return sorted({file for m in modules.values() if (file := _module_file(m))})

    def _remove_run_modules(self) -> None:
        for name, module in (self.run_modules or {}).items():
            if sys.modules.get(name) is module:  # not the host's, put back before
                del sys.modules[name]


def base_scene(mesh_path: str | None) -> Scene:
    """An empty scene, or one holding the mesh read from ``mesh_path``."""
    scene = Scene()
    if mesh_path is not None:
        scene.add(load_mesh(os.fspath(mesh_path)), os.path.basename(mesh_path))
    return scene


def prepare_scene(base: Scene | None, selection: Selection | None) -> Scene:
    """A private copy of ``base`` with the caller's selection."""
    scene = base.copy() if base is not None else Scene()
    if selection is not None:
        scene.selection = selection
    return scene


def execute(
    path: str | os.PathLike[str], *, source: str | None = None, base: Scene | None = None,
    seed: int | None = 0, parameters: dict | None = None,
    selection: Selection | None = None, control: RunControl | None = None,
    lease: RunLease | None = None,
) -> RunOutcome:
    """Run the script at ``path`` once, in the calling thread.

    The process is given back as the run found it (see :class:`RunLease`):
    working directory, standard streams, warnings filters, livemod's library
    and the rest :mod:`livemod.runner.process` lists. One run at a time per
    process (a live session's abandoned runs excepted: they hold nothing).

    Args:
        path: the script (its folder goes on ``sys.path`` during the run).
        source: the text to run; read from ``path`` when None.
        base: the scene the run starts from (copied, never changed); empty if None.
        seed: seeds ``random`` and ``numpy.random`` first; None leaves them alone.
        parameters: globals for the script, also the run context's ``parameters``
            (what ``param()`` returns).
        selection: what ``faces(True)`` and friends return.
        control: lets other threads cancel or pause the run.
        lease: the run's hold on the process (a session's, to start from its
            state and to be revoked); None: the process as it is now.

    Returns:
        A :class:`RunOutcome`; script errors are reported in it, never raised.

    Raises:
        OSError: ``path`` cannot be read (only when ``source`` is None).
    """
    script = os.path.abspath(os.fspath(path))
    started = time.perf_counter()
    scene = prepare_scene(base, selection)
    run = RunContext(directory=os.path.dirname(script), parameters=parameters)
    try:
        if source is None:
            source = read_script(script)
        code = compile_script(source, script)
    except SyntaxError as exc:
        return RunOutcome("error", scene, (), syntax_error(exc, script), time.perf_counter() - started,
                          source=source or "", run=run)
    recorder = StepRecorder(script, scene, control, run)
    recorder.install()
    try:
        status, error, modules = _exec(code, parameters, recorder, seed, control,
                                       lease or RunLease())
    finally:  # also for a Ctrl-C: the hook and the frames it caches must not outlive the run
        recorder.release()
    return RunOutcome(status, scene, recorder.steps, error,
                      time.perf_counter() - started, tuple(modules), source, run)


def _exec(code: CodeType, parameters: dict | None, recorder: StepRecorder, seed: int | None,
          control: RunControl | None, lease: RunLease,
          ) -> tuple[str, ScriptError | None, list[str]]:
    """``exec`` with the scene and the run context bound; returns ``(status, error, local module files)``.

    The script's namespace is made once the process state is taken (so that it
    holds the library's own functions). The state is given back in every case,
    also when a forced interrupt sent just before the script ended lands in the
    giving back (the run is then cancelled, as it was asked to be). A lease
    revoked before the run began runs nothing: the run is cancelled.
    """
    script = recorder.script
    if not lease.enter(script):
        return "cancelled", _cancelled(script, recorder), []
    status, error = "cancelled", None
    try:
        namespace = script_namespace(script, parameters)
        if control is not None:
            control.attach(namespace, recorder)
        token = control if control is not None else object()
        status, error = _run_code(code, namespace, recorder, seed, token)
    finally:
        try:
            _leave_user_code()  # where a late interrupt lands (one only: see interrupt_user_code)
            lease.release()
        except Cancelled:
            _leave_user_code()
            lease.release()
            status, error = "cancelled", _cancelled(script, recorder)
        except BaseException:  # Ctrl-C: the process is given back all the same
            _leave_user_code()
            lease.release()
            raise
    return status, error, lease.files


def _cancelled(script: str, recorder: StepRecorder) -> ScriptError:
    """The error of a cancelled run, at the line of its last step."""
    steps = recorder.steps
    return cancelled_error(script, steps[-1].line if steps else None)


def _run_code(code: CodeType, namespace: dict, recorder: StepRecorder, seed: int | None,
              token: object) -> tuple[str, ScriptError | None]:
    """``exec`` the script in ``namespace``; ``(status, error)``, errors caught."""
    script = recorder.script
    try:
        with use_scene(recorder.scene), use_run(recorder.run):
            try:
                _enter_user_code(token, script)
                seed_generators(seed)
                exec(code, namespace)  # noqa: S102  (running the user's script is the point)
            finally:  # first thing: a late interrupt lands here, not in what follows
                _leave_user_code()
    except Cancelled:
        return "cancelled", _cancelled(script, recorder)
    except SystemExit as exc:
        if exc.code not in (None, 0):
            return "error", exception_error(exc, script)
    except BaseException as exc:  # a script's own BaseException is its error, too
        if _is_ctrl_c(exc):
            raise
        return "error", exception_error(exc, script)
    return "ok", None


def _is_ctrl_c(exc: BaseException) -> bool:
    """True for a KeyboardInterrupt in the main thread, which is where Python puts
    Ctrl-C: ``livemod run`` must stop then. In a worker thread no signal can raise
    one, so there it is the script's own ``raise KeyboardInterrupt``."""
    return (isinstance(exc, KeyboardInterrupt)
            and threading.current_thread() is threading.main_thread())


def interrupt_user_code(thread: threading.Thread, script: str,
                        control: RunControl | None = None) -> bool:
    """Last resort for a cancelled run that does not stop: raise :class:`Cancelled`
    in ``thread`` if it is executing the user's own code right now.

    The compiled-in checks cover the script itself; this covers loops in the
    script's local modules. Library frames are never interrupted (a library
    operation ends at its next step instead), so the exception is only sent when
    the innermost frame belongs to the script or a file in its folder, and only
    while ``thread`` is inside a run's ``exec`` (never once the run has left it:
    see :func:`_leave_user_code`), of the run ``control`` controls when given:
    an exception meant for one run never reaches another.

    Returns:
        True when the exception was sent.
    """
    ident = thread.ident
    if ident is None:
        return False
    # under the lock the thread leaves by: once it has left, nothing is sent, and
    # an exception sent before is raised in its exec's ``finally`` as it leaves
    with _INTERRUPT_LOCK:
        entry = _IN_USER_CODE.get(ident)
        if entry is None or (control is not None and entry[0] is not control):
            return False
        frame = sys._current_frames().get(ident)
        if frame is None or not is_user_file(frame.f_code.co_filename, script):
            return False
        sent = ctypes.pythonapi.PyThreadState_SetAsyncExc(
            ctypes.c_ulong(ident), ctypes.py_object(Cancelled))
    return bool(sent == 1)
