"""The scene after each modeling step of one headless run (for films of the build).

The window's step playback pauses a run after a step and posts a snapshot of the
scene there; this does the same for every step (or the steps asked for) of a run
in the calling thread, without waiting: a :class:`~.playback.Playback` that holds
every step and lets it go at once drives the step recorder's pauses, and each pause
keeps a read-only snapshot, as the session's paused results do.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Collection
from dataclasses import dataclass

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.scene import Scene, Selection

from .execute import RunOutcome, base_scene, execute
from .playback import Playback
from .recording import RunControl, StepRecord
from .results import snapshot_others, snapshot_scene


@dataclass(frozen=True)
class StepShot:
    """The scene as step ``index`` left it.

    Attributes:
        index: the step (0-based, as ``livemod run --steps`` numbers them).
        arrays: the current object (None: the scene had none).
        others: the other objects joined (None: none).
    """

    index: int
    arrays: MeshArrays | None
    others: MeshArrays | None


@dataclass(frozen=True)
class StepShots:
    """A run and the shots of its steps.

    Attributes:
        outcome: the run's outcome; ``outcome.steps`` names every step taken.
        shots: the shots of the steps asked for that the run reached, in order.
    """

    outcome: RunOutcome
    shots: tuple[StepShot, ...]

    @property
    def steps(self) -> tuple[StepRecord, ...]:
        """The records of the shot steps, in the shots' order."""
        return tuple(self.outcome.steps[shot.index] for shot in self.shots)


class _EveryStep(Playback):
    """Playback that pauses a run after every step and lets it go on at once."""

    def __init__(self) -> None:
        super().__init__()
        self.hold_from = 0

    def wait(self, index: int, cancelled: Callable[[], bool]) -> None:
        return


def shoot_steps(path: str | os.PathLike[str], *, which: Collection[int] | None = None,
                mesh_path: str | None = None, seed: int | None = 0,
                parameters: dict | None = None,
                selection: Selection | None = None) -> StepShots:
    """Run the script once in the calling thread, keeping a snapshot of the scene
    after every step (``which`` None) or after the steps in ``which``.

    The run goes on to its end either way (so ``outcome.steps`` counts them all).
    Script errors are in ``outcome.error``, never raised; the shots taken before
    it are kept.

    Raises:
        OSError: the script or ``mesh_path`` cannot be read.
        DLFLError: ``mesh_path`` is not a mesh its reader takes.
    """
    wanted = None if which is None else frozenset(which)
    shots: list[StepShot] = []

    def keep(index: int, steps: object, scene: Scene, run: object) -> None:
        if wanted is None or index in wanted:
            shots.append(StepShot(index, snapshot_scene(scene), snapshot_others(scene)))

    control = RunControl(_EveryStep(), on_pause=keep)
    base = base_scene(mesh_path) if mesh_path is not None else None
    outcome = execute(path, base=base, seed=seed, parameters=parameters,
                      selection=selection, control=control)
    return StepShots(outcome, tuple(shots))
