"""What a run hands back: errors and immutable result snapshots (the step
records are :mod:`livemod.runner.recording`'s).

Everything here is frozen and holds read-only numpy copies, so a result can
cross from the worker thread to the caller's thread (or to another process)
without sharing anything mutable with the run that made it.
"""

from __future__ import annotations

import dataclasses
import enum
import os
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from livemod.dlfl.arrays import MeshArrays, concatenate_arrays, mesh_arrays
from livemod.dlfl.errors import DLFLError
from livemod.dlfl.io import save_objects
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.run_context import RunContext
from livemod.dlfl.scene import SELECTION_READERS, Scene

if TYPE_CHECKING:
    from .recording import StepRecord


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

    def trace_lines(self) -> list[str]:
        """The traceback's lines without the one that repeats :attr:`message`
        (shown on its own line, after them) and without blank ones."""
        said = self.message.strip()
        return [line for line in self.traceback.splitlines()
                if line.strip() and line.strip() != said]


class RunStatus(enum.StrEnum):
    """How a run ended, or that it is paused; the values are what the HUD, the
    terminal and ``batch``'s table show (and compare equal to those strings)."""

    OK = "ok"  # the script ended
    ERROR = "error"  # the script raised, did not compile, or could not be read or saved
    CANCELLED = "cancelled"  # the user cancelled it (LiveSession.cancel)
    PAUSED = "paused"  # playback holds it after a step


@dataclass(frozen=True)
class RunResult:
    """An immutable snapshot of one run, posted to :attr:`LiveSession.results`.

    Attributes:
        run_id: increases with every run of a session; a higher id supersedes.
        script: absolute path of the script.
        status: a :class:`RunStatus`: ``"ok"`` (the script ended), ``"error"``,
            ``"cancelled"`` or ``"paused"`` (playback stopped after step ``step_index``).
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
        others: the scene's other objects (all but the current one) as one
            render snapshot, drawn beside ``arrays`` (ids may repeat between
            objects; see :func:`livemod.dlfl.arrays.concatenate_arrays`); None
            when the scene holds one object or none.
        other_objects: the same objects one by one, as ``(object id, name,
            render snapshot)`` in object order (the viewer shows or hides each);
            empty when ``others`` is None.
        current_object: ``(object id, name)`` of the object ``arrays`` shows, or
            None when the scene is empty (or the result has no mesh of its own).
        unselected: the selection fields (``"faces"``, ``"edges"``, ``"vertices"``,
            ``"corners"``) the run asked for with ``faces(True)`` and the like
            while nothing of that kind was selected, in that order.

    Build one with :meth:`finished`, :meth:`paused` or :meth:`failed`.
    """

    run_id: int
    script: str
    status: RunStatus
    steps: Sequence[StepRecord]
    step_index: int | None
    arrays: MeshArrays | None
    preview: MeshArrays | None
    error: ScriptError | None
    elapsed: float
    stale: bool
    parameters: tuple = ()
    partial: MeshArrays | None = None
    values: tuple = ()
    others: MeshArrays | None = None
    other_objects: tuple = ()
    current_object: tuple[int, str] | None = None
    unselected: tuple[str, ...] = ()

    @classmethod
    def finished(cls, run_id: int, script: str, steps: Sequence[StepRecord],
                 arrays: MeshArrays | None, elapsed: float, *, parameters: tuple = (),
                 values: tuple = (), **objects: Any) -> RunResult:
        """A run whose script ended (``"ok"``); ``objects`` are the fields
        :func:`object_fields` gives."""
        return cls(run_id, script, RunStatus.OK, steps, None, arrays, None, None, elapsed,
                   False, parameters, values=values, **objects)

    @classmethod
    def paused(cls, run_id: int, script: str, steps: Sequence[StepRecord], index: int,
               arrays: MeshArrays | None, elapsed: float, *, parameters: tuple = (),
               values: tuple = (), **objects: Any) -> RunResult:
        """A run held by playback after step ``index`` (``"paused"``)."""
        return cls(run_id, script, RunStatus.PAUSED, steps, index, arrays, None, None,
                   elapsed, False, parameters, values=values, **objects)

    @classmethod
    def failed(cls, run_id: int, script: str, status: RunStatus, steps: Sequence[StepRecord],
               error: ScriptError | None, elapsed: float, *, last_good: RunResult | None,
               parameters: tuple = (), partial: MeshArrays | None = None,
               values: tuple = ()) -> RunResult:
        """A run that did not end well (``"error"`` or ``"cancelled"``): it shows
        ``last_good``'s mesh and objects, marked stale (nothing when None)."""
        result = cls(run_id, script, status, steps, None, None, None, error, elapsed, False,
                     parameters, partial, values)
        if last_good is None:
            return result
        return dataclasses.replace(
            result, arrays=last_good.arrays, preview=last_good.preview, stale=True,
            others=last_good.others, other_objects=last_good.other_objects,
            current_object=last_good.current_object)

    def _repr_png_(self) -> bytes | None:
        """A picture of the run's mesh and other objects for Jupyter (see
        :mod:`livemod.dlfl.display`)."""
        from livemod.dlfl.display import picture_png

        return picture_png(self)


def freeze_arrays(arrays: MeshArrays, copy: bool = True) -> MeshArrays:
    """A copy of ``arrays`` whose numpy arrays are private and read-only.

    ``copy=False`` is for arrays nothing else holds (fresh from
    :func:`concatenate_arrays`): they are made read-only without a second copy.
    """
    copies = {}
    for field in dataclasses.fields(arrays):
        value = getattr(arrays, field.name)
        if value is not None:  # face_colors is None for a mesh without colours
            arr = np.array(value, copy=copy)
            arr.flags.writeable = False
            copies[field.name] = arr
    return dataclasses.replace(arrays, **copies)


def snapshot_mesh(mesh: Mesh) -> MeshArrays:
    """Read-only render arrays of ``mesh``, sharing no memory with it."""
    return freeze_arrays(mesh_arrays(mesh), copy=False)  # mesh_arrays copies already


def current_mesh(scene: Scene) -> Mesh | None:
    """The scene's current mesh without creating an empty object (unlike ``scene.mesh``)."""
    if scene.current is None or scene.current not in scene.objects:
        return None
    return scene.objects[scene.current].mesh


def result_mesh(scene: Scene, all_objects: bool = False) -> Mesh | None:
    """The mesh a run's output holds: the current object's, or with ``all_objects``
    every object of the scene joined into one mesh (each a component); None for
    an empty scene."""
    if not all_objects or len(scene.objects) <= 1:
        return current_mesh(scene)
    from livemod.dlfl.build import join_meshes

    return join_meshes([obj.mesh for obj in scene.objects.values()])


def save_result(objects: Sequence[tuple[str, Mesh]], path: str,
                format: str | None = None) -> None:  # noqa: A002
    """Write a run's objects (see :func:`~livemod.dlfl.io.scene_objects`) to ``path`` as
    :func:`~livemod.dlfl.io.save_objects` does (format by suffix unless
    ``format``, atomically: glTF and 3MF keep the objects apart, other formats
    join several into one mesh), making its folder if missing, as ``run -o``,
    ``run --watch -o`` and batch outputs do.

    Raises:
        OSError, DLFLError: the file cannot be written, its suffix is unknown, or
            there is no object.
    """
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    save_objects(objects, path, format=format)


def save_problem(objects: Sequence[tuple[str, Mesh]], path: str) -> str | None:
    """:func:`save_result` for a command line: write ``objects`` (none: the
    script left no mesh) to ``path`` and return what went wrong as one message
    (no ``[Errno N]``), or None when it was written."""
    from livemod.commandline import describe

    if not objects:  # whatever waits for the file must not take an old one
        return f"the script left no mesh; {path} was not written"
    try:
        save_result(objects, path)
    except OSError as exc:
        return describe(exc)
    except DLFLError as exc:  # a writer's refusal
        return f"cannot write {path}: {exc}"
    return None


def snapshot_scene(scene: Scene) -> MeshArrays | None:
    """Render arrays of the scene's current object, None for an empty scene."""
    mesh = current_mesh(scene)
    return None if mesh is None else snapshot_mesh(mesh)


def snapshot_others(scene: Scene) -> MeshArrays | None:
    """Render arrays of every object but the current one, joined in object order;
    None when there are none (or they are all empty)."""
    return join_others(snapshot_other_objects(scene))


def snapshot_other_objects(scene: Scene) -> tuple[tuple[int, str, MeshArrays], ...]:
    """``(object id, name, read-only render arrays)`` of every object but the current
    one that has vertices, in object order."""
    parts = ((oid, obj.name, mesh_arrays(obj.mesh)) for oid, obj in scene.objects.items()
             if oid != scene.current)
    return tuple((oid, name, freeze_arrays(arrays, copy=False))
                 for oid, name, arrays in parts if len(arrays.positions))


def join_others(objects: Sequence[tuple[int, str, MeshArrays]]) -> MeshArrays | None:
    """The render arrays of ``objects`` (as :func:`snapshot_other_objects` gives
    them) joined into one, read-only; None when there are none."""
    if not objects:
        return None
    if len(objects) == 1:  # already read-only: no second copy of a lone object
        return objects[0][2]
    return freeze_arrays(concatenate_arrays([arrays for _, _, arrays in objects]), copy=False)


def object_fields(scene: Scene, run: RunContext | None = None) -> dict[str, Any]:
    """The ``others``, ``other_objects``, ``current_object`` and ``unselected``
    fields of a :class:`RunResult` of ``scene``, left by ``run`` (None: a run
    that found every selection it asked for)."""
    objects = snapshot_other_objects(scene)
    current = scene.current
    # a script may set ``current`` to an id it never made (or killed)
    named = (current, scene.objects[current].name) if current in scene.objects else None
    asked = run.unselected_reads if run is not None else ()
    unselected = tuple(name for name in SELECTION_READERS if name in asked)
    return {"others": join_others(objects), "other_objects": objects, "current_object": named,
            "unselected": unselected}


def parameter_items(parameters: dict | None) -> tuple:
    """``parameters`` as a hashable, sorted tuple of ``(name, value)`` pairs."""
    return tuple(sorted((parameters or {}).items()))
