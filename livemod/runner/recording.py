"""Step recording: the step record, and the hook that writes it after every command.

The runner owns everything of a step's record. The library's commands only
announce that a step happened, by calling the run's ``step_hook`` with a label
(see :mod:`livemod.dlfl.run_context`); :class:`StepRecorder` is the hook the
runner installs. It runs once per command, so it does as little as it can: it
appends the raw facts of the step to the run's :class:`StepLog` (the layout is
written down there, and only here is it written or read), and a
:class:`StepList` turns them into :class:`StepRecord` objects when they are
read. Everything the hook reads is bound to closure variables, and the script's
frame is cached by the identity of the frame that called the command (see
:func:`script_frame`). In runs that never pause the run's hook is the
recorder's lean one, which records the steps of a cached caller and nothing
else; every other step (a new caller, a run that may pause, any step once the
run is cancelled) goes to the full one.

:class:`RunControl` lives here too: the full hook reads its cancel flag every step.
"""

from __future__ import annotations

import bisect
import dataclasses
import functools
import inspect
import operator
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from types import CodeType, FrameType
from typing import Any, overload

from livemod.dlfl.run_context import STEP_HOOK_CALLER_DEPTH, RunContext, StepHook
from livemod.dlfl.scene import Scene

from .errors import Cancelled
from .instrument import CANCEL_FLAG
from .playback import Playback


@dataclass(frozen=True)
class StepRecord:
    """One finished modeling step of a run.

    Attributes:
        index: 0-based position of the step in the run.
        label: the command name, or the label given to ``step()``.
        line: the script line that issued the command (None when the command
            was not called from the script's own code, e.g. from a bare thread).
        counts: ``(V, E, F)`` of the current object after the step.
        elapsed: seconds since the run started, taken when the step finished.
    """

    index: int
    label: str
    line: int | None
    counts: tuple[int, int, int]
    elapsed: float


# a step in a StepLog is this many facts: its label, the f_lasti of the script's
# frame, V, E and F of the current mesh (Mesh.counts(); NO_COUNTS without one) and
# time.perf_counter(); its code is the log's code at the time. The counts are
# facts of their own, not one tuple: a tuple kept per step is a container the
# garbage collector walks, and costs the run more than unpacking it
STEP_FIELDS = 6
NO_COUNTS = (0, 0, 0)


class StepLog:
    """The raw facts of a run's steps: ``facts``, :data:`STEP_FIELDS` items a step.

    The recorder's hooks append to it; :class:`StepList` reads it. The steps of
    a caller the hook has seen are recorded at the ``f_lasti`` of :attr:`frame`,
    which the hook found to be the script's frame for :attr:`caller`.

    Attributes:
        facts: the flat list of facts (a plain list: CPython specializes
            ``facts.extend`` only for exactly that type).
        caller: the frame whose commands are recorded at :attr:`frame`, or any
            object that is no frame (then none is).
        frame: has the ``f_lasti`` to record (usually the script's frame).
        code: the code steps recorded now ran (None: not the script's).
    """

    __slots__ = ("facts", "caller", "frame", "code", "_codes")

    def __init__(self) -> None:
        self.facts: list = []
        self.caller: object = None
        self.frame: Any = None
        self.code: Any = None
        # (first step, code) each time the code changes: a step's facts leave it
        # out, since it changes only when the hook follows another caller
        self._codes: list[tuple[int, Any]] = [(0, None)]

    def __len__(self) -> int:
        """Steps recorded."""
        return len(self.facts) // STEP_FIELDS

    def follow(self, caller: object, frame: Any, code: Any) -> None:
        """From now on, record the steps of the commands ``caller`` calls at
        ``frame``'s ``f_lasti`` in ``code``."""
        if code is not self.code:
            self._codes.append((len(self), code))
        self.caller, self.frame, self.code = caller, frame, code

    def code_of(self, step: int) -> Any:
        """The code step ``step`` (0-based) was recorded with."""
        return self._codes[bisect.bisect_right(self._codes, step, key=_first) - 1][1]

    def record(self, k: int, started: float) -> StepRecord:
        """The record of step ``k`` (0-based), its ``elapsed`` counted from ``started``."""
        at = k * STEP_FIELDS
        label, lasti, v, e, f, clock = self.facts[at:at + STEP_FIELDS]
        return StepRecord(k, label, code_line(self.code_of(k), lasti), (v, e, f), clock - started)


def _first(item: tuple[int, Any]) -> int:
    """The first step of a ``(first step, code)`` pair."""
    return item[0]


class StepList(Sequence[StepRecord]):
    """The steps of a run: an immutable sequence of :class:`StepRecord`.

    The runner's step hook only appends the raw facts of each step to a
    :class:`StepLog`; a record is built, and the script line looked up from the
    code and instruction offset, when the step is read. A run of thousands of
    commands thus pays for the records someone looks at. The log may grow on (a
    paused run goes on); this view keeps its first ``count`` steps.

    It compares equal to a tuple of the same records and pickles as one.
    """

    __slots__ = ("_log", "_count", "_started")

    def __init__(self, log: StepLog, count: int, started: float) -> None:
        self._log = log
        self._count = count
        self._started = started

    def __len__(self) -> int:
        return self._count

    @overload
    def __getitem__(self, index: int) -> StepRecord: ...

    @overload
    def __getitem__(self, index: slice) -> tuple[StepRecord, ...]: ...

    def __getitem__(self, index: int | slice) -> StepRecord | tuple[StepRecord, ...]:
        """The record of step ``index`` (negative counts from the end), or a tuple
        of records for a slice.

        Raises:
            IndexError: no such step.
        """
        if isinstance(index, slice):
            return tuple(self._record(k) for k in range(*index.indices(self._count)))
        k = operator.index(index)
        k += self._count if k < 0 else 0
        if not 0 <= k < self._count:
            raise IndexError(f"step {index} of {self._count}")
        return self._record(k)

    def __iter__(self) -> Iterator[StepRecord]:
        return (self._record(k) for k in range(self._count))

    def __eq__(self, other: object) -> bool:
        if isinstance(other, StepList | tuple):
            return len(self) == len(other) and tuple(self) == tuple(other)
        return NotImplemented

    def __hash__(self) -> int:
        return hash(tuple(self))

    def __reduce__(self) -> tuple:
        return tuple, (tuple(self),)

    def __repr__(self) -> str:
        return f"StepList({list(self)!r})"

    def _record(self, k: int) -> StepRecord:
        return self._log.record(k, self._started)


def code_line(code: CodeType | None, lasti: int) -> int | None:
    """The source line of byte offset ``lasti`` in ``code`` (what ``frame.f_lineno``
    says for a frame of ``code`` at ``f_lasti == lasti``); None without code."""
    if code is None:
        return None
    if lasti < 0:
        return code.co_firstlineno
    starts, lines = _line_table(code)
    return lines[bisect.bisect_right(starts, lasti) - 1]


@functools.lru_cache(maxsize=64)
def _line_table(code: CodeType) -> tuple[list[int], list[int | None]]:
    """Start offsets of ``code``'s line ranges, and their lines (for bisection)."""
    ranges = list(code.co_lines())
    return [start for start, _, _ in ranges], [line for _, _, line in ranges]


PauseCallback = Callable[[int, Sequence[StepRecord], Scene, RunContext], None]

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
        on_pause: called in the worker with ``(step index, steps, scene, run
            context)`` just before the run blocks at a step.
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
        # after the flag: a step that goes to the full hook finds the flag set
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

    def detach(self) -> None:
        """The run has ended: let go of its globals, its recorder and the pause
        callback, keeping the step count. Each refers back to the control (a
        cycle), and would keep the run's scene until the garbage collector runs.
        Safe while another thread calls :meth:`cancel`."""
        steps = self._steps()
        self._steps = lambda: steps
        self._to_hook = lambda: None
        self._namespace = {}  # not None: a cancel() under way may read it twice
        self.on_pause = None


class _Nowhere:
    """Stands in for the script frame when there is none (one test less per step)."""

    def __init__(self) -> None:
        self.f_lasti = -1


_NOWHERE = _Nowhere()


class StepRecorder:
    """Records steps, pauses and cancels a run: the step hook of its run context.

    Args:
        script: the script's absolute path (the frame whose line a step records).
        scene: the run's scene (a step records its current object's counts).
        control: steers the run; None for one that never pauses nor is cancelled.
        run: the run context the hook goes into (a fresh one when None).

    Attributes:
        hook: the full step hook: it checks the cancel flag, finds the script's
            frame of a new caller, records, and pauses. Call it only from the
            modeling-command wrapper or ``announce_step`` (it finds the
            script's line from there).
        run: the run context :meth:`install` gives the hook.
        started: ``perf_counter()`` when the run started (steps' ``elapsed`` is from it).
    """

    def __init__(self, script: str, scene: Scene, control: RunControl | None,
                 run: RunContext | None = None) -> None:
        self.script = script
        self.scene = scene
        self.control = control
        self.run = run if run is not None else RunContext()
        self.started = time.perf_counter()
        self._log = StepLog()
        # (step index, seconds paused up to and including the pause after it), in order
        self._pauses: list[tuple[int, float]] = []
        self._swapping = threading.Lock()  # a cancel's swap never outlives release()
        self.hook, self._lean = self._make_hooks()

    def install(self) -> None:
        """Make the run context record its steps here: with the lean hook for a
        run that may not pause (the lean hook does not pause), else with the full one."""
        may_pause = self.control is not None and self.control.playback is not None
        self.run.step_hook = self.hook if may_pause else self._lean

    def every_step_to_hook(self) -> None:
        """Give every step from the next on to the full hook (which checks the
        cancel flag). Safe from any thread; nothing once released."""
        with self._swapping:
            if self.run.step_hook is not None:
                self.run.step_hook = self.hook

    def step_count(self) -> int:
        """Steps recorded so far."""
        return len(self._log)

    @property
    def steps(self) -> StepList:
        """The steps recorded so far (a view that later steps do not change)."""
        if self._pauses:  # their elapsed leaves the pauses out
            return _PausedStepList(self._log, self.step_count(), self.started, self._pauses)
        return StepList(self._log, self.step_count(), self.started)

    def release(self) -> None:
        """End the recording: uninstalls the hook and drops the frames the log
        caches, which keep their locals alive."""
        with self._swapping:
            self.run.step_hook = None
        self.hook = self._lean = _ended
        self._log.follow(_UNCACHED, _NOWHERE, self._log.code)

    def _make_hooks(self) -> tuple[Callable[..., None], StepHook]:
        """The full hook and the lean one. The lean one records the step of a
        caller the full one has seen, and gives any other step to it."""
        log, scene, objects, clock = self._log, self.scene, self.scene.objects, time.perf_counter
        facts = log.facts
        extend = facts.extend
        control, script, getframe = self.control or RunControl(), self.script, sys._getframe
        playback, step_done = control.playback, self._step_done
        log.follow(_UNCACHED, _NOWHERE, None)

        def hook(label: str, depth: int = STEP_HOOK_CALLER_DEPTH) -> None:
            if control.cancel_requested:
                raise Cancelled
            try:
                here: FrameType | None = getframe(depth)
            except ValueError:  # called from near the bottom of a thread's stack
                here = None
            if here is not log.caller:
                log.follow(*script_frame(here, script))
            try:
                v, e, f = objects[scene.current].mesh.counts()  # type: ignore[index]
            except KeyError:  # no current object
                v, e, f = NO_COUNTS
            extend((label, log.frame.f_lasti, v, e, f, clock()))  # the layout: STEP_FIELDS
            if playback is not None and len(facts) // STEP_FIELDS > playback.hold_from:
                step_done(control, playback)

        def lean(label: str) -> None:
            try:
                if getframe(STEP_HOOK_CALLER_DEPTH) is log.caller:
                    try:
                        v, e, f = objects[scene.current].mesh.counts()  # type: ignore[index]
                    except KeyError:
                        v, e, f = NO_COUNTS
                    extend((label, log.frame.f_lasti, v, e, f, clock()))  # as hook does
                    return
            except ValueError:  # no Python caller (the bottom of a thread's stack)
                pass
            hook(label, STEP_HOOK_CALLER_DEPTH + 1)

        return hook, lean

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
            control.on_pause(index, self.steps, self.scene, self.run)
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
