"""param(): declarations, values, checks and the Python they bake into."""

from __future__ import annotations

import pytest

from livemod.dlfl import RunContext, use_run
from livemod.dlfl.commands.params import param
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.params import make_spec


def run_with(values: dict) -> RunContext:
    return RunContext(parameters=values)


def test_default_is_returned_and_declaration_recorded() -> None:
    with use_run(run_with({})) as run:
        assert param("thickness", 0.1, min=0.01, max=0.5, doc="rod radius") == 0.1
    spec = run.declarations["thickness"]
    assert (spec.kind, spec.min, spec.max, spec.doc) == ("float", 0.01, 0.5, "rod radius")


def test_given_values_are_checked_and_converted() -> None:
    with use_run(run_with({"n": "12", "on": "false", "scheme": "loop", "r": 2})):
        assert param("n", 4, min=1, max=20) == 12
        assert param("on", True) is False
        assert param("scheme", "doo-sabin", choices=["doo-sabin", "loop"]) == "loop"
        assert param("r", 1.0) == 2.0


@pytest.mark.parametrize(
    ("values", "declare", "message"),
    [
        ({"n": 30}, lambda: param("n", 4, min=1, max=20), "above its maximum 20"),
        ({"n": "four"}, lambda: param("n", 4), "is an integer; got 'four'"),
        ({"s": "x"}, lambda: param("s", "a", choices=["a", "b"]), "must be one of 'a', 'b'"),
        ({"b": "maybe"}, lambda: param("b", False), "use true or false"),
        ({}, lambda: param("bad name", 1), "must be a Python identifier"),
        ({}, lambda: param("x", 5, min=0, max=1), "above its maximum 1"),
        ({}, lambda: param("x", "s", min=0), "need a numeric default"),
        ({}, lambda: param("x", [1]), "must be a number, a bool or a string"),
    ],
)
def test_bad_values_and_declarations_are_clear_errors(values, declare, message) -> None:
    with use_run(run_with(values)), pytest.raises(InvalidArgumentError, match=message):
        declare()


def test_conflicting_redeclaration_is_refused_but_repeats_are_fine() -> None:
    with use_run(run_with({})):
        assert param("k", 2, min=0) == 2
        assert param("k", 2, min=0) == 2
        with pytest.raises(InvalidArgumentError, match="declared twice"):
            param("k", 3)


def test_as_python_bakes_the_value_into_a_declaration() -> None:
    spec = make_spec("t", 0.1, min=0.0, max=1.0, doc="thickness")
    assert spec.as_python(0.25) == "param('t', 0.25, min=0.0, max=1.0, doc='thickness')"
    choice = make_spec("scheme", "loop", choices=["loop", "sqrt3"])
    assert choice.as_python("sqrt3") == "param('scheme', 'sqrt3', choices=['loop', 'sqrt3'])"


def test_param_is_a_thesis_namespace_command() -> None:
    import livemod.dlfl as dlfl

    assert "param" in dlfl.__all__
