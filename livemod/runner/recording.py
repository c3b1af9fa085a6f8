"""The step hook: what the runner notes after every modeling command.

It runs once per command, so it does as little as it can: it appends the raw
facts of the step (label, the script frame's code and instruction offset,
``V``/``E``/``F`` and the clock) to one flat list, and a :class:`StepList`
turns them into :class:`StepRecord` objects when they are read. Everything it
reads is bound to closure variables, and the script's frame is cached by the
identity of the frame that called the command (see :func:`script_frame`).

:class:`RunControl` lives here too: the hook reads its cancel flag every step.
"""

from __future__ import annotations

import inspect
import sys
import time
from collections.abc import Callable, Sequence
from types import CodeType, FrameType

from livemod.dlfl.mesh import Mesh
from livemod.dlfl.scene import STEP_HOOK_CALLER_DEPTH, Scene

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
        self.finished = False
        self.cancel_requested = False  # a plain bool: the step hook reads it every step
        self._namespace: dict | None = None
        self._steps: Callable[[], int] = lambda: 0

    @property
    def cancelled(self) -> bool:
        return self.cancel_requested

    @property
    def step_count(self) -> int:
        """Steps the run has finished so far."""
        return self._steps()

    def cancel(self) -> None:
        """Ask the run to stop at its next step or next loop iteration of the script."""
        self.cancel_requested = True
        if self._namespace is not None:
            self._namespace[CANCEL_FLAG] = True  # read by the checks compile_script adds
        if self.playback is not None:
            self.playback.wake()

    def attach(self, namespace: dict, recorder: StepRecorder) -> None:
        """Give the control the run's globals (so :meth:`cancel` can flag them) and
        its recorder (to count steps)."""
        self._namespace = namespace
        self._steps = recorder.step_count
        namespace[CANCEL_FLAG] = self.cancel_requested


class _Nowhere:
    """Stands in for the script frame when there is none (one test less per step)."""

    def __init__(self) -> None:
        self.f_lasti = -1


_NOWHERE = _Nowhere()
_EMPTY = Mesh()  # counted when the scene has no current object


class StepRecorder:
    """Records steps, pauses and cancels a run; :attr:`hook` is the scene's ``step_hook``.

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
        self._flat: list = []  # STEP_FIELDS items per step, see StepList
        self.hook: Callable[[str], None] = self._make_hook()

    def step_count(self) -> int:
        """Steps recorded so far."""
        return len(self._flat) // STEP_FIELDS

    @property
    def steps(self) -> StepList:
        """The steps recorded so far (a view that later steps do not change)."""
        return StepList(self._flat, self.step_count(), self.started)

    def release(self) -> None:
        """End the recording (call it once the hook is uninstalled): drops the hook,
        and with it the frames it caches, which keep their locals alive."""
        self.hook = _ended

    def _make_hook(self) -> Callable[[str], None]:
        extend, scene, objects, clock = self._flat.extend, self.scene, self.scene.objects, time.perf_counter
        control, script, getframe = self.control or RunControl(), self.script, sys._getframe
        playback, step_done = control.playback, self._step_done
        caller: object = _UNCACHED
        frame: FrameType | _Nowhere = _NOWHERE
        code: CodeType | None = None

        def hook(label: str) -> None:
            nonlocal caller, frame, code
            if control.cancel_requested:
                raise Cancelled
            try:
                here: FrameType | None = getframe(STEP_HOOK_CALLER_DEPTH)
            except ValueError:  # called from near the bottom of a thread's stack
                here = None
            if here is not caller:
                caller, frame, code = script_frame(here, script)
            try:
                m = objects[scene.current].mesh  # type: ignore[index]
            except KeyError:  # no current object
                m = _EMPTY
            # Mesh.counts() inlined, its subtractions left to StepList: this is per step
            extend((label, code, frame.f_lasti, m._v.n, len(m._v.free), m._e.n,
                    len(m._e.free), m._f.n, len(m._f.free), clock()))
            if playback is not None and playback.mode == "step":
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
        if control.on_pause is not None:
            control.on_pause(index, self.steps, self.scene)
        playback.wait(index, lambda: control.cancel_requested)
        control.paused_at = None
        if control.cancel_requested:
            raise Cancelled


def _ended(label: str) -> None:
    """The hook of a finished recording: steps after the end are not recorded."""
