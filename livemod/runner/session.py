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

The session is a composition, all of it guarded by one lock (the session's):
:class:`~livemod.runner.inputs.RunInputs` holds what the next run gets and
decides when a save asks for one; :class:`~livemod.runner.supervisor.RunSupervisor`
starts and stops the runs; :class:`RunWorker` runs the script in a run's thread
and turns what came out into results; :class:`~livemod.runner.posting.ResultPosting`
decides which results reach the caller, as the playback shows them.
"""

from __future__ import annotations

import dataclasses
import logging
import os
import threading
import time
from collections.abc import Callable, Sequence

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.io import scene_objects
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.params import ParamSpec
from livemod.dlfl.run_context import RunContext
from livemod.dlfl.scene import Scene, Selection

from .errors import Cancelled, exception_error, syntax_error
from .execute import RunOutcome, base_scene, capture_process, execute
from .inputs import RunInputs
from .playback import Action, Playback, PlaybackView
from .posting import ResultPosting
from .preview import PreviewWorker, preview_arrays
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
from .stopping import CancelReason
from .stopping import Run as _Run
from .supervisor import RunActivity, RunSupervisor
from .watch import FileWatcher, Notifier

_LOG = logging.getLogger("livemod.session")


class RunWorker:
    """Runs the script once in a run's thread and publishes what came out.

    It reads the run's inputs (the script's text, the ``--mesh`` scene, the
    parameters that still fit), executes the script, saves the ``output`` of a
    run that ended well, turns the outcome into a :class:`RunResult` and hands it
    to the posting, asking for the preview of a mesh it posted. It is the
    :class:`~livemod.runner.supervisor.RunWork` of the session's supervisor.

    Args:
        lock: the session's lock.
        inputs: the session's run inputs.
        posting: where results go.
        seed: seed of ``random``/``numpy.random`` at each run start (None: unseeded).
        output: absolute path to save the mesh to after every good run, or None.
        all_objects: save every object of the scene joined, not just the current one.
        preview: compute the preview of finished and paused meshes (see
            :class:`LiveSession`).
    """

    def __init__(self, lock: threading.RLock, inputs: RunInputs, posting: ResultPosting, *,
                 seed: int | None, output: str | None, all_objects: bool,
                 preview: bool | Callable[[Mesh], MeshArrays | None]) -> None:
        self._lock = lock
        self._inputs = inputs
        self._posting = posting
        self._seed = seed
        self._output = output
        self._all_objects = all_objects
        self._save_lock = threading.Lock()  # one output save at a time, the newest last
        self._previews = _preview_worker(preview, posting.post_preview, posting.is_latest)

    def close(self) -> None:
        """Stop the preview thread (the session winds down)."""
        if self._previews is not None:
            self._previews.close()

    def run(self, run: _Run, source: str | None) -> None:
        """Worker thread: run the script once and publish what came out."""
        try:
            self._run_script(run, source)
        except Exception as exc:  # livemod's fault, past the script: still say it ended
            _LOG.exception("run %d of %s failed after the script", run.run_id, run.script)
            self._publish_failure(run, exc, time.perf_counter() - run.started, run.script)

    def _run_script(self, run: _Run, source: str | None) -> None:
        """Run the script once (in the worker) and publish what came out."""
        with self._lock:
            parameters, selection = dict(self._inputs.parameters), self._inputs.selection
        inputs = self._start_from(run, source)
        if inputs is None:
            return
        source, base = inputs
        with self._lock:
            parameters = self._inputs.fit_parameters(run.script, source, parameters)
        try:
            outcome = execute(run.script, source=source, base=base, seed=self._seed,
                              parameters=parameters, selection=selection, control=run.control,
                              lease=run.lease)
        except Cancelled:  # a forced interrupt that arrived after the script ended
            run.control.finished = True
            self.publish_cancelled(run)
            return
        run.control.finished = True
        if not run.abandoned:  # (an abandoned run read old files: nothing to watch)
            self._inputs.watch_files(run.script, outcome.modules + outcome.files_read)
        self._publish(run, outcome, parameter_items(parameters))

    def _start_from(self, run: _Run, source: str | None) -> tuple[str, Scene | None] | None:
        """The text to run (read now when ``source`` is None) and the base scene; None
        when either cannot be had (that failure is published, naming its file)."""
        started = time.perf_counter()
        try:
            source = self._inputs.text(run.script, source)
        except Exception as exc:
            self._publish_failure(run, exc, time.perf_counter() - started, run.script)
            return None
        try:
            base = self._inputs.base_scene(base_scene)
        except Exception as exc:
            mesh_file = self._inputs.mesh_file or run.script
            self._publish_failure(run, exc, time.perf_counter() - started, mesh_file)
            return None
        return source, base

    def _publish(self, run: _Run, outcome: RunOutcome, values: tuple) -> None:
        """Worker, at the end of a run: save ``output`` and post the result (a
        superseded or abandoned run, even one that ended, posts and saves nothing:
        it ran older inputs)."""
        with self._lock:
            if run.superseded:
                return
            if outcome.status == "ok":
                self._inputs.ran(run.script, outcome.declarations)
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
            last = self._posting.last_good
        result = RunResult.failed(
            run.run_id, run.script, status, outcome.steps, error, _working(run, outcome),
            last_good=last, parameters=self._inputs.specs(outcome.run),
            partial=snapshot_scene(outcome.scene), values=values)
        self._posting.post(result)

    def _publish_ok(self, run: _Run, outcome: RunOutcome, values: tuple) -> None:
        """Post a finished run's result (it becomes the last good one) and ask for
        its preview."""
        result = RunResult.finished(
            run.run_id, run.script, outcome.steps, snapshot_scene(outcome.scene),
            _working(run, outcome), parameters=self._inputs.specs(outcome.run), values=values,
            **object_fields(outcome.scene, outcome.run))
        self._posting.post_good(result)
        mesh = current_mesh(outcome.scene)
        if self._previews is not None and mesh is not None:
            self._previews.request(result, mesh)

    def publish_cancelled(self, run: _Run) -> None:
        """A run the user cancelled says so, over the last good mesh: as it is
        abandoned, or when its forced interrupt came after its script had ended
        (so execute had no outcome to give). A superseded run posts nothing: the
        newer run's result is what shows."""
        if run.cancel_reason is not CancelReason.USER:
            return
        with self._lock:
            self._posting.post_locked(self._posting.cancelled_result(run))

    def _publish_failure(self, run: _Run, exc: Exception, elapsed: float, file: str) -> None:
        """A run that could not start (script unreadable or not text, ``--mesh``
        unloadable); the error points at ``file``, the one that failed."""
        run.control.finished = True
        with self._lock:
            last = self._posting.last_good
        if isinstance(exc, SyntaxError):  # bytes that are not text: as Python reports it
            error = syntax_error(exc, run.script)
        else:
            error = dataclasses.replace(exception_error(exc, file), file=file)
        self._posting.post(RunResult.failed(
            run.run_id, run.script, RunStatus.ERROR, (), error, elapsed,
            last_good=last, parameters=last.parameters if last else ()))

    def _save_output(self, outcome: RunOutcome) -> ScriptError | None:
        """Write the mesh to ``output`` (``run --watch -o``); an error if that fails."""
        if self._output is None:
            return None
        objects = scene_objects(outcome.scene, self._all_objects)
        if not objects:
            return None
        try:
            save_result(objects, self._output)
        except Exception as exc:
            error = exception_error(exc, self._inputs.script)
            return dataclasses.replace(error, file=self._output)
        return None

    def paused(self, run: _Run, index: int, steps: Sequence[StepRecord],
               scene: Scene, context: RunContext) -> None:
        """Worker, at a pause: post the mesh as it is after step ``index``."""
        result = RunResult.paused(
            run.run_id, run.script, steps, index, snapshot_scene(scene),
            steps[-1].elapsed if steps else 0.0, parameters=self._inputs.specs(context),
            values=parameter_items(context.parameters), **object_fields(scene, context))
        if not self._posting.post_step(result, index):
            return
        mesh = current_mesh(scene)
        if self._previews is not None and mesh is not None:
            self._previews.request(result, mesh.copy())  # the live mesh changes on resume


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
        self.mesh_path = mesh_path
        self.seed = seed
        # both resolved now: a run's os.chdir must not move them
        mesh_file = None if mesh_path is None else os.path.abspath(mesh_path)
        self.output = None if output is None else os.path.abspath(output)
        self.all_objects = all_objects
        self._lock = threading.RLock()  # the one lock of every part below
        self._playback = Playback()
        self._snapshots = SnapshotCache(snapshot_budget)
        watcher = FileWatcher(self._files_changed, debounce=debounce, notifier=notifier,
                              poll=poll)
        self._inputs = RunInputs(self._lock, os.path.abspath(os.fspath(script)),
                                 mesh_file=mesh_file, base=base, parameters=parameters,
                                 output=self.output, watcher=watcher)
        self._runs = RunSupervisor(self._lock, self._inputs, self._playback, self._snapshots)
        self._posting = ResultPosting(self._lock, self._runs, self._inputs, self._playback,
                                      self._snapshots)
        self.results = self._posting.results
        self._worker = RunWorker(self._lock, self._inputs, self._posting, seed=seed,
                                 output=self.output, all_objects=all_objects, preview=preview)

    @property
    def script(self) -> str:
        """Absolute path of the open script (see :meth:`open`)."""
        return self._inputs.script

    # -- life cycle ------------------------------------------------------------

    def start(self) -> None:
        """Start watching and run the script once."""
        # the library every run gets; each run pictures the process's settings anew
        process = capture_process()
        self._inputs.start_watching()
        self._runs.start(self._worker, process)
        self.reload()

    def close(self) -> None:
        """Stop watching and cancel the run; the other threads wind down in the
        background.

        Returns once the run has stopped or been abandoned (within
        :data:`~livemod.runner.stopping.GRACE` seconds and a little more), so that
        no run of the session gives the process state back after it: a late
        give-back would undo what the host changed since (its directory, the
        streams a test or a notebook put in place)."""
        if not self._runs.close():
            self._worker.close()  # the supervisor would have closed it

    def join(self, timeout: float = 10.0) -> bool:
        """Wait (up to ``timeout`` s) for the session's threads after :meth:`close`."""
        return self._runs.join(timeout)

    def reload(self) -> None:
        """Re-run the script now, even if its content did not change."""
        self._runs.request(None)

    def open(self, script: str | os.PathLike[str]) -> None:
        """Switch to another script: its first run starts at once; stale state is
        dropped (the old script's text, declarations, parameter values and
        snapshots, and any result of its runs still to come)."""
        with self._lock:
            self._posting.forget()
            self._snapshots.reset(-1)  # no run has that id
            self._playback.apply(Action.OPEN)  # a new script starts unpaused
            self._inputs.switch(os.path.abspath(os.fspath(script)))
        self.reload()

    # -- inputs of the next run ---------------------------------------------------

    def set_selection(self, selection: Selection | None) -> None:
        """What ``faces(True)`` and friends return from the next run on (no re-run)."""
        with self._lock:
            self._inputs.selection = selection

    def set_parameters(self, values: dict) -> None:
        """Update script parameters (globals, and what ``param()`` returns) and re-run.

        The values are kept for later runs (saves of the script included) while
        their declarations still fit them.

        Raises:
            DLFLError: once the script's declarations are known, a name it does
                not declare or a value that does not fit (nothing is changed).
        """
        self._inputs.update_parameters(values)
        self._runs.request(self._inputs.source)

    def reset_parameters(self, names: list[str] | None = None) -> None:
        """Forget the given values (all when ``names`` is None) and re-run with defaults."""
        self._inputs.forget_parameters(names)
        self._runs.request(self._inputs.source)

    @property
    def parameters(self) -> dict:
        """The values the next run gets, by name."""
        with self._lock:
            return dict(self._inputs.parameters)

    @property
    def declarations(self) -> dict[str, ParamSpec]:
        """``name -> ParamSpec`` of the script as last run (empty before the first run)."""
        with self._lock:
            return dict(self._inputs.declarations)

    def _files_changed(self) -> None:
        """Watcher callback: queue a run when a watched file's content changed."""
        if self._inputs.files_changed():
            self._runs.request(None)

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
        return self._posting.act(Action.PLAY)

    def pause(self) -> bool:
        """Hold the run at the step shown (a running run at its next step); later
        runs (a save, a parameter change) hold at the same step."""
        return self._posting.act(Action.PAUSE)

    def toggle_play(self) -> bool:
        """Pause while playing, else play (the Space key)."""
        return self._posting.act(Action.TOGGLE)

    def resume(self) -> bool:
        """Go on from a pause: playing again if a play was paused, else to the end."""
        return self._posting.act(Action.RESUME)

    def run_to_end(self) -> bool:
        """Show the end: the run goes on without pausing, as later runs do; an
        ended run's last result is shown again."""
        return self._posting.act(Action.END)

    def step_forward(self) -> bool:
        """Show the next step (a running run stops at its next step)."""
        return self._posting.act(Action.STEP_FORWARD)

    def step_back(self) -> bool:
        """Show the previous step (from the snapshot cache, or by replaying to it)."""
        return self._posting.act(Action.STEP_BACK)

    def goto_step(self, k: int) -> bool:
        """Show the mesh right after step ``k`` (0-based).

        A step the live run has not reached yet is run to; one behind it is shown
        from the snapshot cache, or else the script is replayed to it (same seed,
        same text, so the same mesh). Past the last step of an ended run is its end.
        """
        return self._posting.act(Action.GOTO, int(k))

    def cancel(self) -> bool:
        """Stop the running run; a ``"cancelled"`` result keeps the last good mesh
        (also for a run that does not stop: it is abandoned after a short grace)."""
        with self._lock:
            run = self._runs.current
            if self._posting.act(Action.CANCEL):
                assert run is not None  # a live run, by the transition
                self._runs.cancel(run)
                return True
            return False

    @property
    def activity(self) -> RunActivity | None:
        """The newest run while it works: started (by a save, a key, anything) and
        neither paused at a step nor ended; None otherwise. Only the newest run is
        ever reported, so a superseded run cannot stand for a newer one."""
        return self._runs.activity

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
        return self._runs.background

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
            return self._inputs.empty_script


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

