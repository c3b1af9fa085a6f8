"""Synchronous, headless runs (``livemod run``, batch variants, tests)."""

from __future__ import annotations

import dataclasses
import os

from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.run_context import RunContext
from livemod.dlfl.scene import SELECTION_READERS, Selection

from .errors import ScriptFailedError
from .execute import RunOutcome, base_scene, execute
from .results import RunResult, RunStatus, object_fields, parameter_items, snapshot_scene


def run_outcome(path: str | os.PathLike[str], *, mesh_path: str | None = None,
                seed: int | None = 0, parameters: dict | None = None,
                selection: Selection | None = None) -> RunOutcome:
    """Run the script once in the calling thread and return the live outcome
    (its scene holds the real mesh, e.g. to save it).

    Raises:
        OSError: the script or ``mesh_path`` cannot be read.
        DLFLError: ``mesh_path`` is not a mesh its reader takes.
    """
    base = base_scene(mesh_path) if mesh_path is not None else None
    return execute(path, base=base, seed=seed, parameters=parameters, selection=selection)


def missing_picks_note(run: RunContext) -> str | None:
    """One line naming the selected ids a run's ``faces(True)`` and the like left out
    (the mesh had no such element then), for ``livemod: warning: ...``; None when
    there were none."""
    missing = run.missing_picks
    named = [f"{field.name} {', '.join(map(str, ids))}" for field in dataclasses.fields(missing)
             if (ids := getattr(missing, field.name))]
    if not named:
        return None
    return (f"the mesh had no {'; no '.join(named)} when the script asked for "
            f"the selection; those picks were left out")


def unselected_note(run: RunContext) -> str | None:
    """One line for ``livemod: note: ...`` when the script asked for a selection
    (``faces(True)`` and the like) that had nothing in it, as a headless run
    without ``--select`` has: a rind of no faces is a closed double shell, not the
    crust with an opening its author picked in the window. None otherwise."""
    asked = [kind for name, kind in SELECTION_READERS.items() if name in run.unselected_reads]
    if not asked:
        return None
    calls = " and ".join(f"{kind}(True)" for kind in asked)
    example = " ".join(f"--select {kind}=ID,..." for kind in asked)
    return (f"{calls} found nothing selected, so the script got none; give "
            f"{example}, or pick in `livemod view`")


def report_selection(run: RunContext) -> None:
    """Print, on stderr, the warning of :func:`missing_picks_note` and the note of
    :func:`unselected_note` for a headless run (each when it has one)."""
    from livemod.commandline import note, warning

    left_out, unselected = missing_picks_note(run), unselected_note(run)
    if left_out is not None:
        warning(left_out)
    if unselected is not None:
        note(unselected)


def check_outcome(outcome: RunOutcome, values: dict | None = None) -> None:
    """Return when a headless run went well, else raise why it is not to be shown
    or written.

    Raises:
        ScriptFailedError: the script failed (``FILE:LINE: message``).
        InvalidArgumentError: ``values`` (``--set``) names a parameter the run did
            not declare (a script whose declarations are computed is checked only
            as it runs).
    """
    from .declarations import undeclared

    if outcome.error is not None:
        raise ScriptFailedError(outcome.error)
    problem = undeclared(outcome.declarations, values or {}, ran=True)
    if problem is not None:
        raise InvalidArgumentError(problem)


def result_of(outcome: RunOutcome, script: str, parameters: dict | None,
              run_id: int = 1) -> RunResult:
    """The immutable :class:`RunResult` of a headless outcome."""
    script = os.path.abspath(script)
    arrays, values = snapshot_scene(outcome.scene), parameter_items(parameters)
    specs = tuple(outcome.declarations.values())
    if outcome.status == RunStatus.OK:
        return RunResult.finished(run_id, script, outcome.steps, arrays, outcome.elapsed,
                                  parameters=specs, values=values,
                                  **object_fields(outcome.scene, outcome.run))
    return RunResult.failed(run_id, script, RunStatus(outcome.status), outcome.steps,
                            outcome.error, outcome.elapsed, last_good=None,
                            parameters=specs, partial=arrays, values=values)


def run_script(path: str | os.PathLike[str], *, mesh_path: str | None = None,
               seed: int | None = 0, parameters: dict | None = None,
               selection: Selection | None = None) -> RunResult:
    """Run the script once, synchronously, and return its :class:`RunResult`.

    Script errors are in ``result.error`` (status ``"error"``), never raised;
    ``arrays`` is None then and ``partial`` holds the mesh as the script left it.

    Raises:
        OSError: the script or ``mesh_path`` cannot be read.
    """
    outcome = run_outcome(path, mesh_path=mesh_path, seed=seed, parameters=parameters,
                          selection=selection)
    return result_of(outcome, os.fspath(path), parameters)
