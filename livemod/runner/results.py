"""What a run hands back: step records, errors and immutable result snapshots.

Everything here is frozen and holds read-only numpy copies, so a result can
cross from the worker thread to the caller's thread (or to another process)
without sharing anything mutable with the run that made it.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from livemod.dlfl.arrays import MeshArrays, mesh_arrays
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.scene import Scene


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


@dataclass(frozen=True)
class ScriptError:
    """Why a run did not finish.

    Attributes:
        kind: ``"syntax"`` (nothing ran), ``"exception"`` or ``"cancelled"``.
        file: the file the error points at (the script, or a local helper module).
        line: line in ``file``, None when unknown.
        message: ``"TypeName: text"``, one line.
        traceback: a short traceback with the library's and the runner's frames
            trimmed away.
    """

    kind: str
    file: str
    line: int | None
    message: str
    traceback: str

    def __str__(self) -> str:
        where = f"{self.file}:{self.line}" if self.line is not None else self.file
        return f"{where}: {self.message}"


@dataclass(frozen=True)
class RunResult:
    """An immutable snapshot of one run, posted to :attr:`LiveSession.results`.

    Attributes:
        run_id: increases with every run of a session; a higher id supersedes.
        script: absolute path of the script.
        status: ``"ok"`` (the script ended), ``"error"``, ``"cancelled"`` or
            ``"paused"`` (playback stopped after step ``step_index``).
        steps: the steps that finished, in order.
        step_index: the step the arrays show when paused; None at the end.
        arrays: render snapshot of the current object. For ``"error"`` and
            ``"cancelled"`` it is the last good result's (``stale`` is True).
        preview: the patch-smoothed preview, or None (it is posted in a second
            result with the same ``run_id`` once computed).
        error: set for ``"error"`` and ``"cancelled"``.
        elapsed: seconds the run took until this snapshot.
        stale: True when ``arrays`` come from an earlier run.
        parameters: the parameters the script declared with ``param()``, as
            ``ParamSpec`` objects in the order of the script (for the viewer's
            controls); empty when the script declares none.
        partial: for errors, the mesh as the failed run left it (None otherwise).
        values: the values the run was given, as sorted ``(name, value)`` pairs.
    """

    run_id: int
    script: str
    status: str
    steps: tuple[StepRecord, ...]
    step_index: int | None
    arrays: MeshArrays | None
    preview: MeshArrays | None
    error: ScriptError | None
    elapsed: float
    stale: bool
    parameters: tuple = ()
    partial: MeshArrays | None = None
    values: tuple = ()


def freeze_arrays(arrays: MeshArrays) -> MeshArrays:
    """A copy of ``arrays`` whose numpy arrays are private and read-only."""
    copies = {}
    for field in dataclasses.fields(arrays):
        arr = np.array(getattr(arrays, field.name), copy=True)
        arr.flags.writeable = False
        copies[field.name] = arr
    return MeshArrays(**copies)


def snapshot_mesh(mesh: Mesh) -> MeshArrays:
    """Read-only render arrays of ``mesh``, sharing no memory with it."""
    return freeze_arrays(mesh_arrays(mesh))


def current_mesh(scene: Scene) -> Mesh | None:
    """The scene's current mesh without creating an empty object (unlike ``scene.mesh``)."""
    if scene.current is None or scene.current not in scene.objects:
        return None
    return scene.objects[scene.current].mesh


def snapshot_scene(scene: Scene) -> MeshArrays | None:
    """Render arrays of the scene's current object, None for an empty scene."""
    mesh = current_mesh(scene)
    return None if mesh is None else snapshot_mesh(mesh)


def parameter_items(parameters: dict | None) -> tuple:
    """``parameters`` as a hashable, sorted tuple of ``(name, value)`` pairs."""
    return tuple(sorted((parameters or {}).items()))
