"""livemod.runner: run user scripts headless or live, with steps and playback.

Never imports moderngl (or anything GL): the viewer drives a
:class:`LiveSession` and drains its ``results`` queue on its own thread.

What the queue carries (all frozen, numpy arrays read-only and private):

* ``status="ok"``: the script ended; ``arrays`` is its current object,
  ``step_index`` None. A second result with the same ``run_id`` follows with
  ``preview`` filled once the smoothed preview is computed.
* ``status="paused"``: playback stopped after step ``step_index`` (0-based);
  ``steps`` holds the steps so far.
* ``status="error"`` / ``"cancelled"`` (the latter only for
  :meth:`LiveSession.cancel`): ``error`` says where; ``arrays`` is the last good
  mesh with ``stale=True`` (None if there was none), ``partial`` the mesh as the
  failed run left it, ``steps`` the steps that finished.

Only the newest run posts; a run superseded by a save posts nothing. Between a
save and its first result, :attr:`LiveSession.activity` (a :class:`RunActivity`)
says the newest run is at work and for how long. Going back
shows a cached snapshot when one is in the budget, else the script is replayed
to that step (same text, same seed). Playback is one state machine (running,
playing, paused, finished; see :mod:`livemod.runner.playback` and
docs/playback.md); :attr:`LiveSession.playback` shows where it is.
"""

from __future__ import annotations

from livemod.dlfl.arrays import MeshArrays

from .errors import Cancelled, ScriptFailedError
from .execute import RunControl, RunOutcome, execute
from .headless import run_outcome, run_script
from .playback import Playback, PlaybackState, PlaybackView
from .preview import preview_arrays
from .recording import StepRecord
from .results import RunResult, RunStatus, ScriptError
from .session import LiveSession, RunActivity
from .watch import FileWatcher, ManualNotifier, WatchdogNotifier

__all__ = [
    "Cancelled", "FileWatcher", "LiveSession", "ManualNotifier", "MeshArrays", "Playback",
    "PlaybackState", "PlaybackView", "RunActivity", "RunControl", "RunOutcome", "RunResult",
    "RunStatus", "ScriptError", "ScriptFailedError", "StepRecord", "WatchdogNotifier",
    "execute", "preview_arrays", "run_outcome", "run_script",
]
