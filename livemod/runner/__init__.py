"""livemod.runner: run user scripts headless or live, with steps and playback.

Never imports moderngl (or anything GL): the viewer drives a
:class:`LiveSession` and drains its ``results`` queue on its own thread.
"""

from __future__ import annotations

from livemod.dlfl.arrays import MeshArrays

from .errors import Cancelled
from .execute import RunControl, RunOutcome, execute
from .headless import run_outcome, run_script
from .playback import Playback
from .preview import preview_arrays
from .results import RunResult, ScriptError, StepRecord
from .session import LiveSession
from .watch import FileWatcher, ManualNotifier, WatchdogNotifier

__all__ = [
    "Cancelled", "FileWatcher", "LiveSession", "ManualNotifier", "MeshArrays", "Playback",
    "RunControl", "RunOutcome", "RunResult", "ScriptError", "StepRecord", "WatchdogNotifier",
    "execute", "preview_arrays", "run_outcome", "run_script",
]
