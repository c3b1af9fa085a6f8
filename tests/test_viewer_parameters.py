"""The parameters controller (GL-free): values shown at once, sent once settled."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from livemod.dlfl.errors import DLFLError
from livemod.dlfl.params import make_spec
from livemod.viewer.parameters import Parameters
from livemod.viewer.params_panel import Hit
from livemod.viewer.runs import RunTracker

SPECS = (make_spec("sides", 4, min=3, max=12), make_spec("apex", False),
         make_spec("kind", "flat", choices=["flat", "star"]))
SIZE = (800, 600)


class FakeInputs:
    """A session's parameter inputs: records what it is sent."""

    def __init__(self) -> None:
        self.parameters: dict = {"sides": 5}
        self.sent: list = []

    def set_parameters(self, values: dict) -> None:
        if values.get("sides") == 99:
            raise DLFLError("parameter 'sides' must be at most 12, got 99")
        self.sent.append(values)
        self.parameters.update(values)

    def reset_parameters(self, names: list[str] | None = None) -> None:
        self.sent.append(("reset", names))


@pytest.fixture
def control() -> tuple[Parameters, FakeInputs, list[str]]:
    session, said = FakeInputs(), []
    parameters = Parameters(RunTracker(), lambda: session, said.append)
    parameters.sync(SimpleNamespace(parameters=SPECS, error=None))
    return parameters, session, said


def test_the_panel_shows_the_sessions_values_over_the_defaults(control) -> None:
    parameters, _, _ = control
    assert parameters.panel.values == {"sides": 5, "apex": False, "kind": "flat"}
    assert parameters.python_lines()[0] == "sides = param('sides', 5, min=3, max=12)"
    failed = SimpleNamespace(parameters=(), error=object())  # failed before any param()
    parameters.sync(failed)
    assert parameters.panel.specs == SPECS


def test_a_value_is_shown_at_once_and_sent_once_settled(control) -> None:
    parameters, session, _ = control
    parameters.set("sides", 7)
    parameters.set("sides", 8)
    assert parameters.panel.values["sides"] == 8 and parameters.values()["sides"] == 8
    parameters.flush()  # not rested yet
    assert session.sent == [] and not parameters._runs.waiting
    parameters.flush(force=True)
    assert session.sent == [{"sides": 8}] and parameters.runs_asked == 1
    assert parameters._runs.waiting
    parameters.set("sides", 8)  # the value it has: nothing to send
    parameters.flush(force=True)
    assert session.sent == [{"sides": 8}]


def test_a_value_the_session_refuses_is_said_and_runs_nothing(control) -> None:
    parameters, session, said = control
    parameters.set("sides", 99)
    parameters.flush(force=True)
    assert said == ["parameters: parameter 'sides' must be at most 12, got 99"]
    assert session.sent == [] and parameters.runs_asked == 0


def test_clicks_toggle_cycle_and_reset(control) -> None:
    parameters, session, _ = control
    parameters.press(Hit(1, "toggle"), 0.0, SIZE)
    parameters.press(Hit(2, "next"), 0.0, SIZE)
    assert session.sent == [{"apex": True}, {"kind": "star"}]  # each sent at once
    parameters.press(Hit(1, "reset"), 0.0, SIZE)
    assert parameters.panel.values["apex"] is False
    parameters.press(Hit(-1, "reset_all"), 0.0, SIZE)
    assert session.sent[2:] == [("reset", ["apex"]), ("reset", None)]
    assert parameters.panel.values == {"sides": 4, "apex": False, "kind": "flat"}
    assert parameters.runs_asked == 4


def test_a_dragged_slider_sends_its_value_when_let_go(control) -> None:
    parameters, session, _ = control
    parameters.press(Hit(0, "slider"), 0.0, SIZE)  # the left end: the min
    assert parameters.dragged == Hit(0, "slider") and parameters.panel.values["sides"] == 3
    parameters.drag_to(10_000.0, SIZE)  # past the right end: the max
    assert parameters.panel.values["sides"] == 12 and session.sent == []
    parameters.let_go()
    assert parameters.dragged is None and session.sent == [{"sides": 12}]


def test_forgetting_keeps_the_panel_only_for_the_same_script(control) -> None:
    parameters, session, _ = control
    parameters.set("sides", 9)
    parameters.forget(keep_panel=True)  # a new mesh: the panel stays, the edit is dropped
    assert parameters.panel.values["sides"] == 9 and parameters.values() == {"sides": 5}
    parameters.forget()  # another script
    assert parameters.panel.specs == () and parameters.runs_asked == 0


def test_copy_puts_the_param_lines_on_the_clipboard_and_echoes_them(control) -> None:
    parameters, _, said = control
    parameters.set("sides", 7)
    copied: list[str] = []
    parameters.copy(copied.append)
    lines = parameters.python_lines()
    assert lines[0] == "sides = param('sides', 7, min=3, max=12)" and len(lines) == 3
    assert copied == ["\n".join(lines) + "\n"] and said[-3:] == lines
    parameters.copy()  # a window without a clipboard: the echo only
    assert said[-3:] == lines and len(said) == 6 and len(copied) == 1


def test_copy_says_when_the_script_declares_no_parameters(control) -> None:
    parameters, _, said = control
    parameters.sync(SimpleNamespace(parameters=(), error=None))  # a script with none
    copied: list[str] = []
    parameters.copy(copied.append)
    assert copied == [] and said == ["the script declares no parameters"]
