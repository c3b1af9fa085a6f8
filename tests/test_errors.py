"""Tests of livemod.dlfl.errors: the hierarchy callers branch on, and the fields
the subclasses carry."""

from __future__ import annotations

from livemod.dlfl import errors
from livemod.dlfl.errors import (
    BudgetExceededError,
    DLFLError,
    FileFormatError,
    GeometryError,
    InvalidArgumentError,
    NonManifoldError,
    UnknownIdError,
)


def test_every_error_is_a_dlfl_error_and_a_value_error():
    subclasses = {UnknownIdError, InvalidArgumentError, NonManifoldError,
                  BudgetExceededError, FileFormatError, GeometryError}
    defined = {value for value in vars(errors).values()
               if isinstance(value, type) and issubclass(value, DLFLError)} - {DLFLError}
    assert defined == subclasses
    assert all(issubclass(error, ValueError) for error in subclasses)
    assert issubclass(UnknownIdError, LookupError)
    assert not any(issubclass(error, LookupError) for error in subclasses - {UnknownIdError})


def test_the_subclasses_carry_their_fields():
    budget = BudgetExceededError("too many", needed=12, budget=10)
    assert (str(budget), budget.needed, budget.budget) == ("too many", 12, 10)
    file_error = FileFormatError("m.obj:3: bad", path="m.obj", line=3)
    assert (file_error.path, file_error.line) == ("m.obj", 3)
    assert FileFormatError("bad").path is None and FileFormatError("bad").line is None
    assert GeometryError("face 3 has no normal").reason is None
    assert GeometryError("face 3 has no normal", reason="a face has no normal").reason == (
        "a face has no normal")

