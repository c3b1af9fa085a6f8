"""The script the window shows, and the live session that runs it (GL-free).

:class:`ScriptSession` holds the script's path, the mesh every run starts from and
the session running them, made by a factory (the runner's
:class:`~livemod.runner.session.LiveSession`, or a test's fake: see
:class:`~livemod.viewer.session.Session`). It starts and closes the session, and
takes the results the session posts, without blocking: a summary line for each
run that ended, the newest result shown. Opening another file makes the window's
controllers forget the old runs, which is the window's to do;
:meth:`ScriptSession.retarget` says which of the two paths the file replaces.
"""

from __future__ import annotations

import sys
import traceback
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from livemod.dlfl.scene import Selection
from livemod.runner.results import RunStatus

from .runs import RunTracker
from .session import Session

if TYPE_CHECKING:
    from livemod.runner.results import RunResult

SCRIPT_SUFFIXES = (".py",)  # a file opened with one of these is a script, else a mesh

SessionFactory = Callable[[str, str | None], Session]


class ScriptSession:
    """The script shown and its session.

    Args:
        script: the script to watch and run (kept as an absolute path).
        mesh_path: the mesh every run starts from, or None.
        factory: ``(script, mesh_path) -> session``, not started.
        runs: what the window knows of the runs: told when a result is expected,
            and given each result taken.
        echo: where the summary lines go.
        output: the file the session writes after every successful run (``-o``),
            named in the summary; or None.

    Attributes:
        script: the script's absolute path.
        mesh_path: the mesh every run starts from, or None.
        session: the session running them; None while closed.
    """

    def __init__(self, script: str, mesh_path: str | None, factory: SessionFactory,
                 runs: RunTracker, echo: Callable[[str], None],
                 output: str | None = None) -> None:
        self.script = str(Path(script).resolve())
        self.mesh_path = mesh_path
        self.session: Session | None = None
        self._factory = factory
        self._runs = runs
        self._echo = echo
        self._output = output

    def live(self) -> Session:
        """The session the controllers drive (the current one: opening a file makes
        another). Precondition: it is open (see :meth:`start`)."""
        assert self.session is not None, "the session is closed"
        return self.session

    def start(self, selection: Selection, parameters: dict[str, Any] | None = None) -> None:
        """Make and start the session of :attr:`script` on :attr:`mesh_path`, whose
        runs get ``selection``, its first run with ``parameters`` (over ``--set``'s)
        when given; the window then waits for its first result. Precondition: the
        last one is closed (see :meth:`close`)."""
        assert self.session is None, "the session is open"
        session = self._factory(self.script, self.mesh_path)
        if not selection.is_empty():
            session.set_selection(selection)
        if parameters:
            # (queued before start: the first run and this request are one run)
            session.set_parameters(parameters)
        session.start()
        self._runs.expect()
        self.session = session

    def close(self) -> None:
        """Close the session (its threads wind down in the background); again:
        nothing."""
        session, self.session = self.session, None
        if session is not None:
            session.close()

    def retarget(self, path: str) -> bool:
        """Make ``path`` (made absolute) the script, when its suffix is one of
        :data:`SCRIPT_SUFFIXES` (returns True), else the mesh the runs start from
        (False). The session is not touched: close it before, start it after."""
        resolved = str(Path(path).resolve())
        is_script = Path(path).suffix.lower() in SCRIPT_SUFFIXES
        if is_script:
            self.script = resolved
        else:
            self.mesh_path = resolved
        return is_script

    def take_results(self, show: Callable[[RunResult], None]) -> None:
        """Say each run that ended, in the echo, and ``show`` the newest result
        posted, if any (never blocks). An exception ``show`` raises (a bug of the
        viewer's own) is told and printed, and the window goes on."""
        arrived = self._runs.arrived(self.live().results)
        for result in arrived:
            if self._runs.newly_ended(result):
                self._summarize(result)
        if not arrived:
            return
        try:
            show(arrived[-1])
        except Exception as exc:  # a bug of the viewer's own: keep the window alive
            self._echo(self._runs.failed_to_show(arrived[-1], exc))
            traceback.print_exception(exc, file=sys.stderr)

    def _summarize(self, result: RunResult) -> None:
        """One line per run, as ``livemod run --watch`` prints it, and the ``-o``
        file the session wrote before posting."""
        from livemod.runner.cli import run_summary

        self._echo(run_summary(result))
        if result.status == RunStatus.OK and self._output is not None:
            self._echo(f"run {result.run_id}: wrote {self._output}")
