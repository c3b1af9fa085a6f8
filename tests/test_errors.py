"""Tests of livemod.dlfl.errors: the hierarchy callers branch on, and the fields
the subclasses carry."""

from __future__ import annotations

import pytest

import livemod.dlfl
from livemod.dlfl import Scene, commands, errors, use_scene
from livemod.dlfl.errors import (
    BudgetExceededError,
    DLFLError,
    FileFormatError,
    GeometryError,
    InvalidArgumentError,
    InvalidMeshError,
    NonManifoldError,
    UnknownIdError,
)
from livemod.dlfl.extrusion import resolve_kind


def test_every_error_is_a_dlfl_error_and_a_value_error():
    subclasses = {UnknownIdError, InvalidArgumentError, NonManifoldError,
                  BudgetExceededError, FileFormatError, GeometryError, InvalidMeshError}
    defined = {value for value in vars(errors).values()
               if isinstance(value, type) and issubclass(value, DLFLError)} - {DLFLError}
    assert defined == subclasses
    assert all(issubclass(error, ValueError) for error in subclasses)
    assert issubclass(UnknownIdError, LookupError)
    assert not any(issubclass(error, LookupError) for error in subclasses - {UnknownIdError})


def test_a_script_can_catch_every_error_by_its_documented_name():
    defined = {name for name, value in vars(errors).items()
               if isinstance(value, type) and issubclass(value, DLFLError)}
    assert set(livemod.dlfl.ERRORS) == defined
    assert all(getattr(livemod.dlfl, name) is getattr(errors, name) for name in defined)
    assert defined <= set(livemod.dlfl.__all__)


def test_the_subclasses_carry_their_fields():
    budget = BudgetExceededError("too many", needed=12, budget=10)
    assert (str(budget), budget.needed, budget.budget) == ("too many", 12, 10)
    file_error = FileFormatError("m.obj:3: bad", path="m.obj", line=3)
    assert (file_error.path, file_error.line) == ("m.obj", 3)
    assert FileFormatError("bad").path is None and FileFormatError("bad").line is None
    assert GeometryError("face 3 has no normal").reason is None
    assert GeometryError("face 3 has no normal", reason="a face has no normal").reason == (
        "a face has no normal")



# -- a misspelt name: the likely one, and the valid ones once ------------------------

def test_close_match_folds_case_and_underscores_and_needs_a_close_name():
    names = ["catmull-clark", "doo-sabin", "loop"]
    assert errors.close_match("Catmul_Clark", names) == "catmull-clark"
    assert errors.close_match("lop", names) == "loop"
    assert errors.close_match("zzz", names) is None
    assert errors.close_match(3, names) is None


def test_unknown_name_says_the_likely_name_and_lists_once():
    message = errors.unknown_name("unknown scheme", "lop", ["loop", "dual"], "valid schemes")
    assert message == "unknown scheme 'lop'; did you mean 'loop'? valid schemes: loop, dual"
    plain = errors.unknown_name("unknown scheme", "zz", ["loop", "dual"], "valid schemes")
    assert plain == "unknown scheme 'zz'; valid schemes: loop, dual"
    unlisted = errors.unknown_name("interp must be 'a' or 'b', got", "aa", ["a", "b"], None)
    assert unlisted == "interp must be 'a' or 'b', got 'aa'; did you mean 'a'?"


MISSPELT = [
    (lambda c: c.subdivide("catmul-clark"), "did you mean 'catmull-clark'?", "valid schemes"),
    (lambda c: c.extrude("cubicle", 0), "did you mean 'cubical'?", "valid types"),
    (lambda c: c.load("soccerbal"), "did you mean 'soccerball'?", "shapes"),
    (lambda c: c.addHandle("hermit", (0, 0), (1, 0), 4), "did you mean 'hermite'?", None),
]


@pytest.mark.parametrize(("call", "hint", "listed"), MISSPELT,
                         ids=["scheme", "extrusion", "shape", "handle"])
def test_a_misspelt_name_in_a_command_gets_the_likely_one(call, hint, listed):
    scene = Scene()
    with use_scene(scene):
        commands.load("cube")
        with pytest.raises(InvalidArgumentError) as caught:
            call(commands)
    message = str(caught.value)
    assert hint in message
    assert listed is None or message.count(f"{listed}:") == 1


def test_a_misspelt_library_extrusion_kind_gets_the_likely_one():
    with pytest.raises(InvalidArgumentError, match="did you mean 'doo-sabin'\\? valid kinds"):
        resolve_kind("do-sabin")
