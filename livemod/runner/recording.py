"""The step hook: what the runner notes after every modeling command.

It runs once per command, so it does as little as it can: it appends the raw
facts of the step (label, the script frame's instruction offset, ``V``/``E``/``F``
and the clock) to the run's :class:`~livemod.dlfl.scene.StepLog`, and a
:class:`StepList` turns them into :class:`StepRecord` objects when they are
read. Everything it reads is bound to closure variables, and the script's frame
is cached by the identity of the frame that called the command (see
:func:`script_frame`). In runs that never pause, the modeling-command wrapper
reads that cache as well and records the steps of a cached caller itself: the
hook then runs only when the caller changes, and on every step once cancelled.

:class:`RunControl` lives here too: the hook reads its cancel flag every step.
"""

from __future__ import annotations

import bisect
import dataclasses
import inspect
import sys
import time
from collections.abc import Callable, Sequence
from types import CodeType, FrameType

from livemod.dlfl.scene import NO_MESH, NO_STEP_LOG, STEP_HOOK_CALLER_DEPTH, Scene, StepLog

from .errors import Cancelled
from .instrument import CANCEL_FLAG
from .playback import Playback
from .results import STEP_FIELDS, StepList, StepRecord

PauseCallback = Callable[[int, Sequence[StepRecord], Scene], None]

_UNCACHED = object()  # a caller no frame is: the next step looks afresh
# code flags of generators and coroutines, whose frames change callers when resumed
_RESUMABLE = inspect.CO_GENERATOR | inspect.CO_COROUTINE | inspect.CO_ASYNC_GENERATOR


def script_frame(caller: FrameType | None, script: str,
                 ) -> tuple[object, FrameType | _Nowhere, CodeType | None]:
    """The innermost frame running ``script`` at or above ``caller`` (the frame
    that called the command), as ``(cache key, frame, its code)``.

    The key is ``caller`` itself when the answer holds for as long as that frame
    object runs: a frame's callers never change, unless a generator or coroutine
    lies between it and the script (then the key matches no frame). When the
    command was not called from the script at all, the frame is a stand-in
    whose ``f_lasti`` is -1 and the code is None.
    """
    frame, cacheable = caller, True
    while frame is not None and frame.f_code.co_filename != script:
        cacheable = cacheable and not frame.f_code.co_flags & _RESUMABLE
        frame = frame.f_back
    key = caller if cacheable else _UNCACHED
    if frame is None:
        return key, _NOWHERE, None
    return key, frame, frame.f_code


class RunControl:
    """Steers one run from other threads: cancel it, and pause it in playback.

    Args:
        playback: the session's playback state, or None for runs that never pause.
        on_pause: called in the worker with ``(step index, steps, scene)`` just
            before the run blocks at a step.
    """

    def __init__(self, playback: Playback | None = None,
                 on_pause: PauseCallback | None = None) -> None:
        self.playback = playback
        self.on_pause = on_pause
        self.paused_at: int | None = None
        # seconds the run has spent paused (the pause's snapshot, then the wait): the
        # run's working time is its wall time less this
        self.waited = 0.0
        self.finished = False
        self.cancel_requested = False  # a plain bool: the step hook reads it every step
        self._namespace: dict | None = None
        self._steps: Callable[[], int] = lambda: 0
        self._to_hook: Callable[[], None] = lambda: None  # see attach

    @property
    def cancelled(self) -> bool:
        """True once a newer run (or closing) asked this run to stop."""
        return self.cancel_requested

    @property
    def step_count(self) -> int:
        """Steps the run has finished so far."""
        return self._steps()

    def cancel(self) -> None:
        """Ask the run to stop at its next step or next loop iteration of the script."""
        self.cancel_requested = True
        # after the flag: a step that finds the scene's log gone finds the flag set
        self._to_hook()
        if self._namespace is not None:
            self._namespace[CANCEL_FLAG] = True  # read by the checks compile_script adds
        if self.playback is not None:
            self.playback.wake()

    def attach(self, namespace: dict, recorder: StepRecorder) -> None:
        """Give the control the run's globals (so :meth:`cancel` can flag them) and
        its recorder (to count steps, and to send every step to the hook, which
        checks the cancel flag, once cancelled)."""
        self._namespace = namespace
        self._steps = recorder.step_count
        self._to_hook = recorder.every_step_to_hook
        namespace[CANCEL_FLAG] = self.cancel_requested
        # read the flag again: a cancel() before _to_hook was set missed the hook, and
        # one between the read above and its write had its True overwritten
        if self.cancel_requested:
            namespace[CANCEL_FLAG] = True
            recorder.every_step_to_hook()


class _Nowhere:
    """Stands in for the script frame when there is none (one test less per step)."""

    def __init__(self) -> None:
        self.f_lasti = -1


_NOWHERE = _Nowhere()


class StepRecorder:
    """Records steps, pauses and cancels a run; :attr:`hook` is the scene's ``step_hook``.

    :meth:`install` also gives the scene the recorder's :class:`StepLog`, so
    that the modeling-command wrapper records the steps of callers the hook has
    seen itself, for runs that never pause; a cancel takes it away again.

    Attributes:
        hook: the step hook; call it only from the modeling-command wrapper or
            :meth:`Scene.record_step` (it finds the script's line from there).
        started: ``perf_counter()`` when the run started (steps' ``elapsed`` is from it).
    """

    def __init__(self, script: str, scene: Scene, control: RunControl | None) -> None:
        self.script = script
        self.scene = scene
        self.control = control
        self.started = time.perf_counter()
        self._log = StepLog()
        # (step index, seconds paused up to and including the pause after it), in order
        self._pauses: list[tuple[int, float]] = []
        self.hook: Callable[[str], None] = self._make_hook()

    def install(self) -> None:
        """Make the scene record its steps here: its ``step_hook``, and its
        ``step_log`` unless the run may pause (the wrapper does not pause)."""
        self.scene.step_hook = self.hook
        if self.control is None or self.control.playback is None:
            self.scene.step_log = self._log

    def every_step_to_hook(self) -> None:
        """Take the log away from the scene: from the next step on, the hook records
        every step (and so checks the cancel flag). Safe from any thread."""
        self.scene.step_log = NO_STEP_LOG

    def step_count(self) -> int:
        """Steps recorded so far."""
        return len(self._log.facts) // STEP_FIELDS

    @property
    def steps(self) -> StepList:
        """The steps recorded so far (a view that later steps do not change)."""
        if self._pauses:  # their elapsed leaves the pauses out
            return _PausedStepList(self._log, self.step_count(), self.started, self._pauses)
        return StepList(self._log, self.step_count(), self.started)

    def release(self) -> None:
        """End the recording: uninstalls the hook and the log, and drops the
        frames they cache, which keep their locals alive."""
        self.scene.step_hook = None
        self.scene.step_log = NO_STEP_LOG
        self.hook = _ended
        self._log.follow(_UNCACHED, _NOWHERE, self._log.code)

    def _make_hook(self) -> Callable[[str], None]:
        log, scene, objects, clock = self._log, self.scene, self.scene.objects, time.perf_counter
        facts = log.facts
        extend = facts.extend
        control, script, getframe = self.control or RunControl(), self.script, sys._getframe
        playback, step_done = control.playback, self._step_done
        log.follow(_UNCACHED, _NOWHERE, None)

        def hook(label: str) -> None:
            if control.cancel_requested:
                raise Cancelled
            try:
                here: FrameType | None = getframe(STEP_HOOK_CALLER_DEPTH)
            except ValueError:  # called from near the bottom of a thread's stack
                here = None
            if here is not log.caller:  # the cache the command wrapper reads, too
                log.follow(*script_frame(here, script))
            try:
                m = objects[scene.current].mesh  # type: ignore[index]
            except KeyError:  # no current object
                m = NO_MESH
            # Mesh.counts() inlined, its subtractions left to StepList: this is per step
            extend((label, log.frame.f_lasti, m._v.n, len(m._v.free), m._e.n,
                    len(m._e.free), m._f.n, len(m._f.free), clock()))
            if playback is not None and len(facts) // STEP_FIELDS > playback.hold_from:
                step_done(control, playback)

        return hook

    def _step_done(self, control: RunControl, playback: Playback) -> None:
        """Pause after the step just recorded if playback says so.

        Raises:
            Cancelled: the run was cancelled while paused.
        """
        index = self.step_count() - 1
        if not playback.should_pause(index):
            return
        control.paused_at = index
        paused = time.perf_counter()
        if control.on_pause is not None:
            control.on_pause(index, self.steps, self.scene)
        playback.wait(index, lambda: control.cancel_requested)
        # the snapshot and the wait are the viewer's time, not the script's
        spent = time.perf_counter() - paused
        control.waited += spent
        self._pauses.append((index, spent + (self._pauses[-1][1] if self._pauses else 0.0)))
        control.paused_at = None
        if control.cancel_requested:
            raise Cancelled


class _PausedStepList(StepList):
    """The steps of a run that paused: each step's ``elapsed`` is the run's working
    time, without the pauses before it (a paused run waits on the viewer).

    ``pauses`` is the recorder's list; it only grows by pauses after the last step
    of this view, which change none of its steps.
    """

    __slots__ = ("_pauses",)

    def __init__(self, log: StepLog, count: int, started: float,
                 pauses: list[tuple[int, float]]) -> None:
        super().__init__(log, count, started)
        self._pauses = pauses

    def _record(self, k: int) -> StepRecord:
        record = super()._record(k)
        before = bisect.bisect_left(self._pauses, k, key=lambda pause: pause[0])
        if before == 0:
            return record
        return dataclasses.replace(record, elapsed=record.elapsed - self._pauses[before - 1][1])


def _ended(label: str) -> None:
    """The hook of a finished recording: steps after the end are not recorded."""
