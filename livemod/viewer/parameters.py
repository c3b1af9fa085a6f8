"""The script's parameters as the window edits them (GL-free).

:class:`Parameters` turns clicks and drags on the
:class:`~livemod.viewer.params_panel.ParameterPanel` into values, shows a value
at once and sends it to the session (:class:`~livemod.viewer.session.ParameterInputs`)
once it has rested :data:`PARAMETER_DEBOUNCE` seconds, so that a dragged slider
re-runs the script once per value it settles on, not once per pixel.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from .params_panel import Hit, ParameterPanel
from .runs import RunTracker
from .session import ParameterInputs

if TYPE_CHECKING:
    from livemod.runner.results import RunResult

PARAMETER_DEBOUNCE = 0.15  # seconds a dragged slider rests before the script re-runs


class Parameters:
    """The parameters panel's values, the slider being dragged, and the edits not
    sent to the session yet.

    Args:
        runs: told when a run is due.
        session: gives the session the values go to (the window's current one).
        echo: prints a line in the terminal.

    Attributes:
        panel: what the panel shows (its layout and hit tests).
        runs_asked: how often the panel re-ran the script (for tests).
        dragged: the slider being dragged, or None.
    """

    def __init__(self, runs: RunTracker, session: Callable[[], ParameterInputs],
                 echo: Callable[[str], None]) -> None:
        self._runs = runs
        self._session = session
        self._echo = echo
        self.forget()

    def forget(self, keep_panel: bool = False) -> None:
        """Drop the edits in flight and the drag; with ``keep_panel`` the panel keeps
        showing what it shows (a new mesh for the same script), else it starts
        empty (another script declares its own)."""
        if not keep_panel:
            self.panel = ParameterPanel()
            self.runs_asked = 0
        self.dragged: Hit | None = None
        self._pending: dict[str, Any] = {}  # values not yet sent to the session
        self._pending_at = 0.0

    def sync(self, result: RunResult) -> None:
        """Show the result's declarations with the session's values and any edit in
        flight (a run that failed before declaring any keeps the controls the user
        was using)."""
        specs = tuple(result.parameters)
        if not specs and result.error is not None:
            return
        self.panel.sync(specs, self.values())

    def values(self) -> dict[str, Any]:
        """The values the session's next run gets, with any edit not sent yet."""
        values = dict(self._session().parameters or {})
        values.update(self._pending)
        return values

    def python_lines(self) -> list[str]:
        """The values shown as ``name = param(...)`` lines to paste into the script."""
        return self.panel.python_lines()

    def copy(self, clipboard: Callable[[str], None] | None = None) -> None:
        """``Ctrl+C``: the :meth:`python_lines` to ``clipboard`` (the window's, when
        it has one), as one text ending in a newline, and to the echo a line each."""
        lines = self.python_lines()
        if not lines:
            self._echo("the script declares no parameters")
            return
        if clipboard is not None:
            clipboard("\n".join(lines) + "\n")
        for line in lines:
            self._echo(line)

    # -- input ---------------------------------------------------------------------

    def press(self, hit: Hit, px: float, size: tuple[int, int]) -> None:
        """A click on the panel at framebuffer x ``px``: reset, start a slider drag,
        toggle or cycle a choice."""
        if hit.part == "reset_all":
            self.reset(None)
        elif hit.part == "reset":
            self.reset([self.panel.specs[hit.row].name])
        elif hit.part == "slider":
            self.dragged = hit
            self.drag_to(px, size)
        elif hit.part in ("toggle", "prev", "next"):
            self.set(self.panel.specs[hit.row].name, self.panel.value_after(hit, px, size))
            self.flush(force=True)

    def drag_to(self, px: float, size: tuple[int, int]) -> None:
        """Move the dragged slider to framebuffer x ``px``."""
        hit = self.dragged
        if hit is not None and hit.row < len(self.panel.specs):
            self.set(self.panel.specs[hit.row].name, self.panel.value_after(hit, px, size))

    def let_go(self) -> None:
        """The slider was let go: its value has settled, so it is sent now."""
        self.dragged = None
        self.flush(force=True)

    def set(self, name: str, value: Any) -> None:
        """Show ``value`` for parameter ``name`` now; the script re-runs with it once
        the value has rested :data:`PARAMETER_DEBOUNCE` seconds (latest wins)."""
        if self.panel.values.get(name) == value and name not in self._pending:
            return
        self.panel.values[name] = value
        self._pending[name] = value
        self._pending_at = time.perf_counter()

    def flush(self, force: bool = False) -> None:
        """Send settled values to the session (never blocks: it only queues a run)."""
        if not self._pending:
            return
        if not force and time.perf_counter() - self._pending_at < PARAMETER_DEBOUNCE:
            return
        values, self._pending = self._pending, {}
        try:
            self._session().set_parameters(values)
        except Exception as exc:  # e.g. the declaration changed under the slider
            self._echo(f"parameters: {exc}")
            return
        self.runs_asked += 1
        self._runs.expect()

    def reset(self, names: list[str] | None) -> None:
        """Back to the defaults: the parameters ``names``, or all of them (None)."""
        for spec in self.panel.specs:
            if names is None or spec.name in names:
                self.panel.values[spec.name] = spec.default
                self._pending.pop(spec.name, None)
        self._session().reset_parameters(names)
        self.runs_asked += 1
        self._runs.expect()
