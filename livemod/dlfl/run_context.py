"""The run context: what a run of a script gives the commands, and learns from them.

Thesis commands act on two things. The *scene* (:mod:`livemod.dlfl.scene`) is
what the script models: its objects, the current object, the selection and the
face budget. The *run context* is the run that does the modeling: where its
relative file names start, the values given to its ``param()`` calls, and what
it is told by the commands (its steps, the files it read and wrote, its
declarations, the picks it asked for). Both are context variables, so each run
of the runner binds its own (:func:`use_run`, as :func:`~livemod.dlfl.scene.use_scene`
binds the scene), while a plain ``python script.py`` uses one process-wide
default context that records nothing of its steps.

Which is which, field by field (a field is the run's when two runs of the same
scene may differ in it, or when a copy of the scene, taken for a snapshot or a
later run, must not carry it):

* ``step_hook`` and ``command_depth``: the run's. Steps are told to whoever
  watches this run (the runner's recorder); the depth counts the modeling
  commands the running code is inside of. The layout of a step's record is the
  runner's alone (:mod:`livemod.runner.recording`): a command only says that a
  step with this label happened, through :func:`announce_step`.
* ``directory`` and ``parameters``: the run's inputs. The same scene runs from
  another folder, or with other values in a sweep.
* ``declarations``, ``files_read``, ``files_written``, ``missing_picks`` and
  ``unselected_reads``: what this run did. The next run starts with none, and a
  copied scene has done nothing.
* The selection stays the scene's: the viewer picks ids of the scene's meshes,
  and a copy of the scene keeps them. What a run's ``faces(True)`` found of it
  is the run's (``missing_picks``, ``unselected_reads``).
* The face budget stays the scene's: it limits the meshes the scene holds.
"""

from __future__ import annotations

import contextlib
import contextvars
from collections.abc import Callable
from typing import Any

from .scene import Selection, binding

StepHook = Callable[[str], None]

# Frames from a step hook up to the code that called the modeling command: the
# modeling-command wrapper calls the hook itself (``sys._getframe(STEP_HOOK_CALLER_DEPTH)``
# in the hook is the command's caller). Steps announced by :func:`announce_step`
# reach the hook one frame deeper.
STEP_HOOK_CALLER_DEPTH = 2


class RunContext:
    """One run of a script, as the commands see it.

    Args:
        directory: see the attribute.
        parameters: see the attribute (copied).
        step_hook: see the attribute.

    Attributes:
        step_hook: called with a step's label after every outermost modeling
            command (and by :func:`announce_step`); None records no steps. The
            modeling-command wrapper calls it directly (see
            ``STEP_HOOK_CALLER_DEPTH``). The runner installs its recorder here,
            and may swap it for another while the run goes on (any thread).
        command_depth: how many modeling commands the running code is inside
            of; steps are announced only at depth 0.
        directory: the folder relative file names in ``load``/``save`` refer to
            (the runner sets the script's folder); None for the working directory.
        parameters: values for ``param()`` declarations, by name (set by the runner).
        declarations: the :class:`~livemod.dlfl.params.ParamSpec` of every
            ``param()`` call of the run, by name, in call order.
        files_read, files_written: absolute paths of the mesh files ``load`` read
            (or tried to) and ``save`` wrote, in order; a live session re-runs the
            script when one it read changes.
        missing_picks: the ids of the scene's selection that ``faces(True)`` and
            the like left out because the current mesh had no such element then
            (a pick from an older result, or a mistyped ``--select``).
        unselected_reads: the selection fields (``"faces"``, ``"edges"``,
            ``"vertices"``, ``"corners"``) a ``faces(True)`` or the like asked for
            while nothing of that kind was selected (a headless run's note says so).
    """

    __slots__ = ("step_hook", "command_depth", "directory", "parameters", "declarations",
                 "files_read", "files_written", "missing_picks", "unselected_reads")

    def __init__(self, *, directory: str | None = None, parameters: dict | None = None,
                 step_hook: StepHook | None = None) -> None:
        self.step_hook = step_hook
        self.command_depth = 0
        self.directory = directory
        self.parameters: dict[str, object] = dict(parameters or {})
        self.declarations: dict[str, Any] = {}
        self.files_read: list[str] = []
        self.files_written: list[str] = []
        self.missing_picks = Selection()
        self.unselected_reads: set[str] = set()


def announce_step(label: str) -> None:
    """Tell the run that a step ``label`` happened (``step()`` and ``load`` do; the
    modeling-command wrapper does the same for each command). Nothing happens
    inside another modeling command (the outer one is the step) or when no one
    records the run's steps."""
    run = RUN.get(STANDALONE_RUN)
    hook = run.step_hook
    if hook is not None and not run.command_depth:
        hook(label)


# the process-wide run context, current where no run is bound (a plain script)
STANDALONE_RUN = RunContext()
# the context variable behind current_run(); read as ``RUN.get(STANDALONE_RUN)``
# where a Python call per read counts (the wrapper of every modeling command)
RUN: contextvars.ContextVar[RunContext] = contextvars.ContextVar("livemod_run")


def current_run() -> RunContext:
    """The run the thesis commands report to: the one bound by :func:`use_run`, or
    the process-wide :data:`STANDALONE_RUN`."""
    return RUN.get(STANDALONE_RUN)


def use_run(run: RunContext) -> contextlib.AbstractContextManager[RunContext]:
    """Bind ``run`` as the current run context for the calling context (thread)."""
    return binding(RUN, run)
