"""LiveSession: watch a script, re-run it in a worker thread, step through it.

Threads (none of them the caller's):

* the watcher's debounce thread calls :meth:`LiveSession._files_changed`;
* the supervisor thread takes run requests, cancels the running run, waits a
  short grace for it to stop and starts the next one (latest wins: queued
  requests coalesce). A run that does not stop in the grace (blocked in a call
  no interrupt reaches, or swallowing the interrupt) is abandoned: its results
  are never posted, the process state is given back on its behalf, and its
  thread is left to end in the background (:attr:`LiveSession.background_runs`);
* one worker thread per run executes the script and posts results;
* the preview thread smooths finished meshes.

The caller only sets state and enqueues requests, so no public method blocks.
Results go to :attr:`LiveSession.results`; only the newest run's results are
posted (a superseded run's are dropped). :attr:`LiveSession.activity` says,
when polled, whether the newest run is working now and for how long, so the
caller can show a run a save started before its first result arrives.
"""

from __future__ import annotations

import dataclasses
import hashlib
import logging
import os
import queue
import threading
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.errors import DLFLError
from livemod.dlfl.io import scene_objects
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.params import ParamSpec
from livemod.dlfl.run_context import RunContext
from livemod.dlfl.scene import Scene, Selection

from .declarations import check_values, fitting_values, literal_declarations
from .errors import Cancelled, cancelled_error, exception_error, syntax_error
from .execute import RunControl, RunLease, RunOutcome, base_scene, capture_process, execute
from .instrument import decode_script
from .playback import Action, Playback, PlaybackView, RunPosition, Show
from .preview import PreviewWorker, preview_arrays
from .process import ProcessState
from .recording import StepRecord
from .results import (
    RunResult,
    RunStatus,
    ScriptError,
    current_mesh,
    object_fields,
    parameter_items,
    save_result,
    snapshot_scene,
)
from .snapshots import DEFAULT_BUDGET, SnapshotCache
from .stopping import GRACE, CancelReason, RunStopper
from .stopping import Run as _Run
from .watch import FileWatcher, Notifier

_LOG = logging.getLogger("livemod.session")
_WAKE = object()  # queued by cancel(): the supervisor minds the cancelled run


@dataclass
class _Request:
    """A run to start: the script and the text to run (None: read it)."""

    script: str
    source: str | None


@dataclass(frozen=True)
class RunActivity:
    """The newest run while it works on the script (see :attr:`LiveSession.activity`).

    Attributes:
        run_id: the run's id, as its results will carry.
        script: the script it runs.
        working: seconds it has worked so far (its pauses left out, as in the
            ``elapsed`` of its results).
    """

    run_id: int
    script: str
    working: float


class LiveSession:
    """Runs a script on every save and lets the caller step through its runs.

    Args:
        script: path of the user script.
        mesh_path: mesh every run starts from (``--mesh``); empty scene if None.
        seed: seed of ``random``/``numpy.random`` at each run start (None: unseeded).
        debounce: seconds of quiet after the last file event before a run.
        poll: poll the file system instead of waiting for events.
        preview: compute the patch-smoothed preview of finished and paused meshes
            (True: :func:`preview_arrays`; or a function ``Mesh -> MeshArrays | None``).
        notifier: the file-event source (tests inject a ManualNotifier).
        output: save the mesh here after every successful run (``run --watch -o``).
        all_objects: save every object of the scene joined, not just the current one.
        parameters: initial script parameters (globals, and what ``param()`` returns).
        base: a scene every run starts from (copied per run), instead of ``mesh_path``.
        snapshot_budget: bytes of paused snapshots kept for stepping back without a
            replay.

    Attributes:
        results: :class:`RunResult` snapshots; drain with ``get_nowait()``.
        activity: the run at work now, or None (see :class:`RunActivity`); poll it.
        background_runs: ids of abandoned runs still working; poll it.
        empty_script: the script's path while a save left it empty (and ran
            nothing), or None; poll it.
    """

    def __init__(self, script: str | os.PathLike[str], *, mesh_path: str | None = None,
                 seed: int | None = 0, debounce: float = 0.15, poll: bool = False,
                 preview: bool | Callable[[Mesh], MeshArrays | None] = True, notifier: Notifier | None = None,
                 output: str | None = None, parameters: dict | None = None,
                 all_objects: bool = False,
                 base: Scene | None = None, snapshot_budget: int = DEFAULT_BUDGET) -> None:
        self.script = os.path.abspath(os.fspath(script))
        self.results: queue.Queue[RunResult] = queue.Queue()
        self.mesh_path = mesh_path
        self.seed = seed
        # both resolved now: a run's os.chdir must not move them
        self._mesh_absolute = None if mesh_path is None else os.path.abspath(mesh_path)
        self.output = None if output is None else os.path.abspath(output)
        self.all_objects = all_objects
        self._parameters = dict(parameters or {})
        self._declarations: dict[str, ParamSpec] = {}  # of the newest script text
        self._selection: Selection | None = None
        self._playback = Playback()
        self._snapshots = SnapshotCache(snapshot_budget)
        self._lock = threading.RLock()
        self._requests: queue.Queue[_Request | object | None] = queue.Queue()
        self._run_id = 0
        self._current: _Run | None = None
        self._stopper = RunStopper(self._lock, self._before_abandoning)
        self._process: ProcessState | None = None  # shared by the runs (see start)
        self._save_lock = threading.Lock()  # one output save at a time, the newest last
        self._last_good: RunResult | None = None
        self._last_posted: RunResult | None = None
        # the newest run's end (ok, error, cancelled), posted or not: see _post_locked
        self._final: RunResult | None = None
        self._source: str | None = None
        self._seen: dict[str, bytes] = {}
        self._empty_script: str | None = None  # see empty_script
        self._base: Scene | None = base.copy() if base is not None else None
        self._base_version = 0  # counts changes of the --mesh file (see _base_scene)
        self._closed = False
        # set once closing has stopped (or abandoned) the last run: no run of the
        # session holds the process state any more (see close)
        self._let_go = threading.Event()
        self._watcher = FileWatcher(self._files_changed, debounce=debounce,
                                    notifier=notifier, poll=poll)
        self._previews = _preview_worker(preview, self._post_preview, self._is_latest)
        self._supervisor = threading.Thread(target=self._supervise, name="livemod-session",
                                            daemon=True)

    # -- life cycle ------------------------------------------------------------

    def start(self) -> None:
        """Start watching and run the script once."""
        # the library every run gets; each run pictures the process's settings anew
        self._process = capture_process()
        self._watcher.start()
        self._watcher.set_files(self._own_files())
        self._supervisor.start()
        self.reload()

    def close(self) -> None:
        """Stop watching and cancel the run; the other threads wind down in the
        background.

        Returns once the run has stopped or been abandoned (within
        :data:`~livemod.runner.stopping.GRACE` seconds and a little more), so that
        no run of the session gives the process state back after it: a late
        give-back would undo what the host changed since (its directory, the
        streams a test or a notebook put in place)."""
        with self._lock:
            self._closed = True
            started = self._supervisor.ident is not None
        self._requests.put(None)
        if not started:
            if self._previews is not None:
                self._previews.close()  # the supervisor would have closed it
        elif threading.current_thread() is not self._supervisor:
            self._let_go.wait(GRACE + 1.0)

    def join(self, timeout: float = 10.0) -> bool:
        """Wait (up to ``timeout`` s) for the session's threads after :meth:`close`."""
        if self._supervisor.ident is None:
            return True
        self._supervisor.join(timeout)
        return not self._supervisor.is_alive()

    def reload(self) -> None:
        """Re-run the script now, even if its content did not change."""
        self._request(None)

    def open(self, script: str | os.PathLike[str]) -> None:
        """Switch to another script: its first run starts at once; stale state is
        dropped (the old script's text, declarations, parameter values and
        snapshots, and any result of its runs still to come)."""
        with self._lock:
            self.script = os.path.abspath(os.fspath(script))
            self._last_good, self._final, self._seen = None, None, {}
            # a replay asked before the first run reads the new script from disk
            self._source, self._declarations, self._parameters = None, {}, {}
            self._snapshots.reset(-1)  # no run has that id
            self._empty_script = None
            self._playback.apply(Action.OPEN)  # a new script starts unpaused
            self._watcher.set_files(self._own_files())
        self.reload()

    # -- inputs of the next run ---------------------------------------------------

    def set_selection(self, selection: Selection | None) -> None:
        """What ``faces(True)`` and friends return from the next run on (no re-run)."""
        with self._lock:
            self._selection = selection

    def set_parameters(self, values: dict) -> None:
        """Update script parameters (globals, and what ``param()`` returns) and re-run.

        The values are kept for later runs (saves of the script included) while
        their declarations still fit them.

        Raises:
            DLFLError: once the script's declarations are known, a name it does
                not declare or a value that does not fit (nothing is changed).
        """
        with self._lock:
            if self._declarations:
                values = check_values(self._declarations, values)
            self._parameters.update(values)
        self._request(self._source)

    def reset_parameters(self, names: list[str] | None = None) -> None:
        """Forget the given values (all when ``names`` is None) and re-run with defaults."""
        with self._lock:
            for name in list(self._parameters) if names is None else names:
                self._parameters.pop(name, None)
        self._request(self._source)

    @property
    def parameters(self) -> dict:
        """The values the next run gets, by name."""
        with self._lock:
            return dict(self._parameters)

    @property
    def declarations(self) -> dict[str, ParamSpec]:
        """``name -> ParamSpec`` of the script as last run (empty before the first run)."""
        with self._lock:
            return dict(self._declarations)

    # -- playback -------------------------------------------------------------------
    # Every method here is one action of the playback's state machine (see
    # livemod/runner/playback.py for its states and transition table). Each
    # returns True when a result is on its way (or was posted), False when it
    # changed nothing on screen (at the first step already, at the end already).

    @property
    def playback(self) -> PlaybackView:
        """The playback's state, the step it shows (or goes to) and the play rate."""
        return self._playback.view

    @property
    def play_rate(self) -> float:
        """Steps per second while playing (the user's choice; 2 to begin with).

        Raises:
            ValueError: set to a number that is not positive and finite.
        """
        return self._playback.rate

    @play_rate.setter
    def play_rate(self, rate: float) -> None:
        self._playback.rate = rate

    def faster(self) -> float:
        """Double the play rate, up to 64 steps a second; the new rate."""
        return self._playback.scale_rate(2.0)

    def slower(self) -> float:
        """Halve the play rate, down to a step every 4 seconds; the new rate."""
        return self._playback.scale_rate(0.5)

    def play(self, rate: float | None = None) -> bool:
        """Advance :attr:`play_rate` steps a second (``rate``, when given, becomes
        it): from the step shown, or from the first step when the run has ended
        (the script is replayed to it).

        Raises:
            ValueError: ``rate`` is not positive.
        """
        if rate is not None:
            self._playback.rate = rate
        return self._act(Action.PLAY)

    def pause(self) -> bool:
        """Hold the run at the step shown (a running run at its next step); later
        runs (a save, a parameter change) hold at the same step."""
        return self._act(Action.PAUSE)

    def toggle_play(self) -> bool:
        """Pause while playing, else play (the Space key)."""
        return self._act(Action.TOGGLE)

    def resume(self) -> bool:
        """Go on from a pause: playing again if a play was paused, else to the end."""
        return self._act(Action.RESUME)

    def run_to_end(self) -> bool:
        """Show the end: the run goes on without pausing, as later runs do; an
        ended run's last result is shown again."""
        return self._act(Action.END)

    def step_forward(self) -> bool:
        """Show the next step (a running run stops at its next step)."""
        return self._act(Action.STEP_FORWARD)

    def step_back(self) -> bool:
        """Show the previous step (from the snapshot cache, or by replaying to it)."""
        return self._act(Action.STEP_BACK)

    def goto_step(self, k: int) -> bool:
        """Show the mesh right after step ``k`` (0-based).

        A step the live run has not reached yet is run to; one behind it is shown
        from the snapshot cache, or else the script is replayed to it (same seed,
        same text, so the same mesh). Past the last step of an ended run is its end.
        """
        return self._act(Action.GOTO, int(k))

    def cancel(self) -> bool:
        """Stop the running run; a ``"cancelled"`` result keeps the last good mesh
        (also for a run that does not stop: it is abandoned after a short grace)."""
        with self._lock:
            run = self._current
            if self._act(Action.CANCEL):
                assert run is not None  # a live run, by the transition
                run.cancel_reason = CancelReason.USER
                run.cancelled_at = time.perf_counter()
                run.control.cancel()
                self._requests.put(_WAKE)  # the supervisor minds it from now on
                return True
            return False

    def _act(self, action: Action, k: int = 0) -> bool:
        """Apply ``action`` to the playback and do what showing its step takes."""
        with self._lock:
            show = self._playback.apply(action, self._run_position(), k)
            if show is Show.CACHED:
                cached = self._snapshots.get(self._playback.mode.step or 0)
                assert cached is not None  # the position said it was there
                self._post_locked(cached)
            elif show is Show.FINAL:
                assert self._final is not None  # the position said it was there
                self._post_locked(self._final)
            elif show is Show.REPLAY:
                self._request(self._source)
            return show is not Show.NOTHING

    def _run_position(self) -> RunPosition:
        """Where the newest run is, for the playback (caller holds the lock)."""
        run, final = self._current, self._final
        if final is not None and not self._is_newest(final):
            final = None
        if run is None or final is not None or run.stopped or self._closed:
            return RunPosition(final=final is not None,
                               done=len(final.steps) if final is not None else 0,
                               cached=self._snapshots.indexes())
        return RunPosition(live=True, held=run.control.paused_at,
                           done=run.control.step_count, cached=self._snapshots.indexes())

    @property
    def activity(self) -> RunActivity | None:
        """The newest run while it works: started (by a save, a key, anything) and
        neither paused at a step nor ended; None otherwise. Only the newest run is
        ever reported, so a superseded run cannot stand for a newer one."""
        with self._lock:
            run = self._current
            if (run is None or run.stopped or self._closed
                    or run.control.paused_at is not None):
                return None
            return RunActivity(run.run_id, run.script, run.working())

    @property
    def background_runs(self) -> tuple[int, ...]:
        """Ids of the runs that did not stop when asked and still work in the
        background, oldest first (empty almost always).

        Such a run is blocked in a call no interrupt reaches (``time.sleep``, a
        wait, a read, one long library or numpy operation) or swallows the
        interrupt. It was abandoned after a grace of
        :data:`~livemod.runner.stopping.GRACE` seconds: what it does is never
        shown nor saved, and the runs after it start at once. Its thread ends
        when its call returns (or with the process), and it leaves this tuple
        then. The window and ``run --watch`` say so meanwhile.
        """
        return self._stopper.background

    @property
    def empty_script(self) -> str | None:
        """The script's path while a save left it empty and was ignored; else None.

        Empty is no bytes or whitespace only. Such a save runs nothing: an editor
        that truncates the file and then writes it would otherwise show an empty
        scene for the gap, so the last result stays shown. When the script is
        still empty once the debounce has passed, this tells the caller, so the
        window can say so (e.g. "model.py is empty: showing the last result").
        It goes back to None when the script has content again (run or not:
        the same text back runs nothing either) or when a run starts.
        """
        with self._lock:
            return self._empty_script

    # -- triggering runs ---------------------------------------------------------------

    def _request(self, source: str | None) -> None:
        """Queue a run of the current script (``source`` None: read it from disk).

        The current run, unless it has finished, is superseded at once: what it
        posts from now on is dropped, also before the supervisor gets to stopping
        it (a run that ends in that moment would otherwise show, and then the
        new run's result)."""
        with self._lock:
            if self._closed:
                return
            self._requests.put(_Request(self.script, source))
            run = self._current
            if run is not None and not run.control.finished:
                run.cancel_reason = run.cancel_reason or CancelReason.SUPERSEDED

    def _files_changed(self) -> None:
        """Watcher callback: queue a run when a watched file's content changed."""
        with self._lock:
            files, script = sorted(self._watcher.files), self.script
        source = _read_bytes(script)  # read once: for its digest and for emptiness
        if source is None:
            return  # the script vanished (or is being replaced): wait for it to return
        digests = {path: _digest(path) for path in files if path != script}
        digests[script] = _hash(source)
        emptied = _is_blank(source)
        with self._lock:
            if script == self.script:
                # an editor truncated it and has not written it yet, or the user
                # emptied it: keep the last result, and say why (empty_script)
                self._empty_script = script if emptied else None
        if emptied:
            return
        with self._lock:
            changed = [p for p, d in digests.items() if p in self._seen and self._seen[p] != d]
            # no run has read the script yet (it did not exist): its first save runs it
            appeared = script not in self._seen
            self._seen.update({p: d for p, d in digests.items() if d is not None})
            if self._mesh_file() in changed:
                self._base = None  # the next run reads the new --mesh
                self._base_version += 1
        if changed or appeared:
            self._request(None)

    def _supervise(self) -> None:
        """Supervisor thread: start each requested run after stopping the previous one."""
        while True:
            request = self._next_request()
            self._stop_current(CancelReason.SUPERSEDED)
            if request is None:
                self._let_go.set()
                break
            self._start_run(request)
        self._watcher.close()
        if self._previews is not None:
            self._previews.close()
        if self._process is not None:
            self._process.close()  # no run holds it now: the last one gave it back

    def _next_request(self) -> _Request | None:
        """The newest queued request (older ones coalesce); None means close. While
        it waits it minds the runs asked to stop (see :meth:`RunStopper.mind`)."""
        while True:
            with self._lock:
                current = self._current
            request = self._take(self._stopper.mind_interval(current))
            if request is not _WAKE:
                return request  # type: ignore[return-value]
            self._stopper.mind(current)

    def _take(self, timeout: float | None) -> _Request | object | None:
        """The newest queued item (a close wins), or ``_WAKE`` when only wake-ups
        came, or nothing within ``timeout`` seconds."""
        try:
            newest = self._requests.get(timeout=timeout)
        except queue.Empty:
            return _WAKE
        while newest is not None:
            try:
                item = self._requests.get_nowait()
            except queue.Empty:
                break
            if item is not _WAKE:
                newest = item
        return newest

    def _stop_current(self, reason: CancelReason) -> None:
        """Cancel the running run; wait until its thread is done with the script,
        or abandon it (see :class:`RunStopper`)."""
        if self._current is not None:
            self._stopper.stop(self._current, reason)

    def _before_abandoning(self, run: _Run) -> None:
        """A run the user cancelled says so now, as it is abandoned (under the lock)."""
        if run.cancel_reason is CancelReason.USER:
            self._post_locked(self._cancelled_result(run))

    def _start_run(self, request: _Request) -> None:
        with self._lock:
            if request.script != self.script:
                return  # queued before open() switched scripts
            self._run_id += 1
            run = _Run(self._run_id, request.script, RunControl(self._playback),
                       RunLease(self._process), started=time.perf_counter())
            run.control.on_pause = lambda index, steps, scene, context: self._post_paused(
                run, index, steps, scene, context)
            run.thread = threading.Thread(target=self._run_body, args=(run, request.source),
                                          name=f"livemod-run-{run.run_id}", daemon=True)
            self._current = run
            self._snapshots.reset(run.run_id)
            self._empty_script = None
            self._playback.apply(Action.NEW_RUN)
        run.thread.start()

    # -- the worker ------------------------------------------------------------------

    def _run_body(self, run: _Run, source: str | None) -> None:
        """Worker thread: run the script once and publish what came out."""
        try:
            self._run_script(run, source)
        except Exception as exc:  # livemod's fault, past the script: still say it ended
            _LOG.exception("run %d of %s failed after the script", run.run_id, run.script)
            self._publish_failure(run, exc, time.perf_counter() - run.started, run.script)
        finally:
            self._stopper.ended(run)  # after the publishing: the caller sees no gap between

    def _run_script(self, run: _Run, source: str | None) -> None:
        """Run the script once (in the worker) and publish what came out."""
        with self._lock:
            parameters, selection = dict(self._parameters), self._selection
        inputs = self._inputs(run, source)
        if inputs is None:
            return
        source, base = inputs
        with self._lock:
            parameters = self._fit_parameters(run.script, source, parameters)
        try:
            outcome = execute(run.script, source=source, base=base, seed=self.seed,
                              parameters=parameters, selection=selection, control=run.control,
                              lease=run.lease)
        except Cancelled:  # a forced interrupt that arrived after the script ended
            run.control.finished = True
            self._publish_cancelled(run)
            return
        run.control.finished = True
        if not run.abandoned:  # (an abandoned run read old files: nothing to watch)
            self._watch_files(run.script, outcome.modules + outcome.files_read)
        self._publish(run, outcome, parameter_items(parameters))

    def _inputs(self, run: _Run, source: str | None) -> tuple[str, Scene | None] | None:
        """The text to run (read now when ``source`` is None) and the base scene; None
        when either cannot be had (that failure is published, naming its file)."""
        started = time.perf_counter()
        try:
            if source is None:
                source, digest = _read_script(run.script)
                with self._lock:
                    self._seen[run.script] = digest
        except Exception as exc:
            self._publish_failure(run, exc, time.perf_counter() - started, run.script)
            return None
        with self._lock:
            self._source = source
        try:
            base = self._base_scene()
        except Exception as exc:
            mesh_file = self._mesh_file() or run.script
            self._publish_failure(run, exc, time.perf_counter() - started, mesh_file)
            return None
        return source, base

    def _specs(self, context: RunContext) -> tuple[ParamSpec, ...]:
        """The declarations to show with a result: the script's, as known in full
        (a failed or paused run may not have reached every ``param()``)."""
        with self._lock:
            known = tuple(self._declarations.values())
        return known or tuple(context.declarations.values())

    def _fit_parameters(self, script: str, source: str, parameters: dict) -> dict:
        """The values that still fit the declarations of ``source`` (caller holds the
        lock); the ones that no longer fit are forgotten for good."""
        try:
            specs = literal_declarations(source, script)
        except DLFLError:
            specs = None  # the run reports the syntax or declaration error
        if specs is None:
            return parameters
        kept = fitting_values(specs, parameters, self._declarations)
        for name in set(parameters) - set(kept):
            if self._parameters.get(name) == parameters[name]:
                del self._parameters[name]
        self._declarations = specs
        return kept

    def _own_files(self) -> list[str]:
        """The files watched from the start: the script and the ``--mesh`` file."""
        mesh_file = self._mesh_file()
        return [self.script] if mesh_file is None else [self.script, mesh_file]

    def _mesh_file(self) -> str | None:
        return self._mesh_absolute

    def _base_scene(self) -> Scene | None:
        """The ``--mesh`` scene, loaded in the worker (never on the caller's thread)
        once, and again after the file changed."""
        mesh_file = self._mesh_file()
        with self._lock:
            base, version = self._base, self._base_version
            if mesh_file is None or base is not None:
                return base
            digest = _digest(mesh_file)  # first: a file that fails to load is watched too
            if digest is not None:
                self._seen[mesh_file] = digest
        base = base_scene(mesh_file)
        with self._lock:
            # a change seen while loading may have come too late for this load: keep
            # nothing, so that the run the change asked for loads the file again
            if version == self._base_version:
                self._base = base
        return base

    def _watch_files(self, script: str, paths: tuple[str, ...]) -> None:
        """Watch the local modules and mesh files a run read, remembering their
        content now (the session's own ``output`` is never watched: it changes
        because a run ended)."""
        paths = tuple(p for p in paths if p != self.output)
        with self._lock:
            if script != self.script:
                return
            for path in paths:
                digest = _digest(path)
                if path not in self._seen and digest is not None:
                    self._seen[path] = digest
            try:
                self._watcher.set_files(self._watcher.files | set(paths))
            except OSError as exc:  # e.g. inotify's watch limit: the run's result still counts
                _LOG.warning("cannot watch the folders of %s: %s; saves there will not "
                             "re-run the script", ", ".join(paths), exc)

    def _publish(self, run: _Run, outcome: RunOutcome, values: tuple) -> None:
        """Worker, at the end of a run: save ``output`` and post the result (a
        superseded or abandoned run, even one that ended, posts and saves nothing:
        it ran older inputs)."""
        with self._lock:
            if run.superseded:
                return
            if outcome.status == "ok" and run.script == self.script:
                # as the run computed them (a param() may compute its arguments)
                self._declarations = outcome.declarations
        save_error = None
        if outcome.status == "ok":
            with self._save_lock:  # a newer run's save waits for this one, so it comes last
                if run.superseded:
                    return
                save_error = self._save_output(outcome)
        if outcome.status == "ok" and save_error is None:
            self._publish_ok(run, outcome, values)
            return
        error = save_error or outcome.error
        status = RunStatus.ERROR if save_error is not None else RunStatus(outcome.status)
        with self._lock:
            last = self._last_good
        result = RunResult.failed(
            run.run_id, run.script, status, outcome.steps, error, _working(run, outcome),
            last_good=last, parameters=self._specs(outcome.run),
            partial=snapshot_scene(outcome.scene), values=values)
        with self._lock:
            self._post_locked(result)

    def _publish_ok(self, run: _Run, outcome: RunOutcome, values: tuple) -> None:
        """Post a finished run's result (it becomes the last good one) and ask for
        its preview."""
        result = RunResult.finished(
            run.run_id, run.script, outcome.steps, snapshot_scene(outcome.scene),
            _working(run, outcome), parameters=self._specs(outcome.run), values=values,
            **object_fields(outcome.scene, outcome.run))
        with self._lock:
            if self._is_newest(result):
                self._last_good = result
            self._post_locked(result)
        mesh = current_mesh(outcome.scene)
        if self._previews is not None and mesh is not None:
            self._previews.request(result, mesh)

    def _publish_cancelled(self, run: _Run) -> None:
        """A run the user cancelled whose forced interrupt came after its script had
        ended (so execute had no outcome to give): it still says it was cancelled."""
        if run.cancel_reason is not CancelReason.USER:
            return  # superseded: the newer run's result is what shows
        with self._lock:
            self._post_locked(self._cancelled_result(run))

    def _cancelled_result(self, run: _Run) -> RunResult:
        """The ``"cancelled"`` result of a run the user stopped, over the last good
        mesh (caller holds the lock)."""
        return RunResult.failed(run.run_id, run.script, RunStatus.CANCELLED, (),
                                cancelled_error(run.script), run.working(),
                                last_good=self._last_good)

    def _publish_failure(self, run: _Run, exc: Exception, elapsed: float, file: str) -> None:
        """A run that could not start (script unreadable or not text, ``--mesh``
        unloadable); the error points at ``file``, the one that failed."""
        run.control.finished = True
        with self._lock:
            last = self._last_good
        if isinstance(exc, SyntaxError):  # bytes that are not text: as Python reports it
            error = syntax_error(exc, run.script)
        else:
            error = dataclasses.replace(exception_error(exc, file), file=file)
        self._post(RunResult.failed(run.run_id, run.script, RunStatus.ERROR, (), error, elapsed,
                                    last_good=last, parameters=last.parameters if last else ()))

    def _save_output(self, outcome: RunOutcome) -> ScriptError | None:
        """Write the mesh to ``output`` (``run --watch -o``); an error if that fails."""
        if self.output is None:
            return None
        objects = scene_objects(outcome.scene, self.all_objects)
        if not objects:
            return None
        try:
            save_result(objects, self.output)
        except Exception as exc:
            error = exception_error(exc, self.script)
            return dataclasses.replace(error, file=self.output)
        return None

    def _post_paused(self, run: _Run, index: int, steps: Sequence[StepRecord],
                     scene: Scene, context: RunContext) -> None:
        """Worker, at a pause: post the mesh as it is after step ``index``."""
        result = RunResult.paused(
            run.run_id, run.script, steps, index, snapshot_scene(scene),
            steps[-1].elapsed if steps else 0.0, parameters=self._specs(context),
            values=parameter_items(context.parameters), **object_fields(scene, context))
        with self._lock:
            self._snapshots.put(result)
            if not self._is_newest(result) or not self._playback.arrived(index):
                return  # e.g. the caller is looking at an earlier, cached step
            self._post_locked(result)
        mesh = current_mesh(scene)
        if self._previews is not None and mesh is not None:
            self._previews.request(result, mesh.copy())  # the live mesh changes on resume

    # -- posting ---------------------------------------------------------------------

    def _is_newest(self, result: RunResult) -> bool:
        """True while ``result`` belongs to the newest run of the open script and
        that run was not superseded, nor the session closed (caller holds the lock)."""
        run = self._current
        return (run is not None and result.run_id == run.run_id
                and result.script == self.script and not run.superseded
                and not self._closed)

    def _post(self, result: RunResult) -> None:
        """Publish ``result`` if it is still the newest (see :meth:`_is_newest`)."""
        with self._lock:
            self._post_locked(result)

    def _is_latest(self, result: RunResult) -> bool:
        """Whether ``result`` is still worth a preview: the last one posted, or the
        newest run's end kept unposted (it is posted on :meth:`run_to_end`)."""
        with self._lock:
            return (self._last_posted is result or self._final is result) and self._is_newest(result)

    def _post_preview(self, result: RunResult, preview: MeshArrays) -> None:
        """Preview thread: post ``result`` again with its preview, if still shown
        (and keep it with its preview, if it is the end kept unposted)."""
        with self._lock:
            if not self._is_newest(result):
                return
            with_preview = dataclasses.replace(result, preview=preview)
            if self._final is result:
                self._final = with_preview
            if self._last_posted is result:
                self._snapshots.put(with_preview)
                self._last_posted = with_preview
                self.results.put(with_preview)

    def _post_locked(self, result: RunResult) -> None:
        """Publish ``result`` (e.g. again, from the snapshot cache) if it is still
        the newest (caller holds the lock). A run's end goes to the playback
        first, which keeps it unposted while the caller looks at an earlier step."""
        if not self._is_newest(result):
            return
        if result.status is not RunStatus.PAUSED:
            self._final = result
            if self._playback.apply(Action.RUN_ENDED, k=len(result.steps)) is Show.NOTHING:
                return
        self._last_posted = result
        self.results.put(result)


def _working(run: _Run, outcome: RunOutcome) -> float:
    """The run's working time: its wall time less the time it spent paused."""
    return max(outcome.elapsed - run.control.waited, 0.0)


def _preview_worker(preview: bool | Callable[[Mesh], MeshArrays | None],
                    post: Callable[[RunResult, MeshArrays], None],
                    is_current: Callable[[RunResult], bool]) -> PreviewWorker | None:
    if preview is False:
        return None
    compute = preview_arrays if preview is True else preview
    return PreviewWorker(post, is_current, compute)


def _read_script(path: str) -> tuple[str, bytes]:
    """The script's text and the digest of its bytes (what a watched save is
    compared with). Raises OSError, or SyntaxError for bytes that are not text."""
    with open(path, "rb") as handle:
        data = handle.read()
    return decode_script(data, path), _hash(data)


def _hash(data: bytes) -> bytes:
    return hashlib.blake2b(data, digest_size=16).digest()


def _is_blank(data: bytes) -> bool:
    """True when a script's bytes are nothing but whitespace (and a UTF-8 BOM):
    an editor between truncating and writing, or a user who emptied it."""
    return not data.removeprefix(b"\xef\xbb\xbf").strip()


def _read_bytes(path: str) -> bytes | None:
    """The file's bytes, None when it cannot be read (e.g. mid-rename)."""
    try:
        with open(path, "rb") as handle:
            return handle.read()
    except OSError:
        return None


def _digest(path: str) -> bytes | None:
    """Hash of the file's bytes, None when it cannot be read (e.g. mid-rename)."""
    data = _read_bytes(path)
    return None if data is None else _hash(data)
