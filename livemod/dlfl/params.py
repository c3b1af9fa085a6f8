"""Script parameters: declared once with ``param()``, set from sliders or the command line.

A script writes ``t = param("thickness", 0.1, min=0.01, max=0.5, doc="rod radius")``.
The call returns the value the runner was given for ``thickness`` (from ``--set``,
a batch sweep or a slider), or the default, and records the declaration in the
scene so the viewer can draw a control and ``livemod batch`` can check a sweep
before anything runs.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ._checks import finite_number, positive_number, shown
from .errors import InvalidArgumentError

KINDS = ("bool", "int", "float", "choice", "str")


@dataclass(frozen=True)
class ParamSpec:
    """One declared parameter.

    Attributes:
        name: a Python identifier.
        default: the value used when none is given.
        kind: "bool", "int", "float", "choice" or "str", from the default and choices.
        min, max, step: numeric range and slider step (None when open).
        choices: the allowed values of a "choice" parameter.
        doc: one line shown on hover and in ``livemod params``.
    """

    name: str
    default: Any
    kind: str
    min: float | None = None
    max: float | None = None
    step: float | None = None
    choices: tuple[Any, ...] | None = None
    doc: str = ""

    def check(self, value: Any) -> Any:
        """``value`` converted to this parameter's kind and checked against its range.

        Strings (from the command line) are parsed. Raises DLFLError naming the
        parameter, the value and what was expected.
        """
        if isinstance(value, str) and self.kind != "str":
            value = self.parse(value)
        converted = self._convert(value)
        self._check_range(converted)
        return converted

    def parse(self, text: str) -> Any:
        """Parse a command-line string for this parameter.

        Raises:
            DLFLError: ``text`` is not of the parameter's kind, or not one of its
                choices; the message names the parameter and the text.
        """
        if self.kind == "bool":
            lowered = text.strip().lower()
            if lowered in ("1", "true", "yes", "on"):
                return True
            if lowered in ("0", "false", "no", "off"):
                return False
            raise InvalidArgumentError(
                f"parameter {self.name!r} is a bool; got {text!r} (use true or false)")
        if self.kind == "choice":
            for choice in self.choices or ():
                if str(choice) == text:
                    return choice
            return text
        try:
            return int(text) if self.kind == "int" else float(text)
        except ValueError:
            raise InvalidArgumentError(
                f"parameter {self.name!r} is {_article(self.kind)}; got {text!r}"
            ) from None

    def _convert(self, value: Any) -> Any:
        if self.kind == "bool":
            if isinstance(value, bool):
                return value
        elif self.kind == "int":
            if isinstance(value, int) and not isinstance(value, bool):
                return value
            if isinstance(value, float) and value.is_integer():
                return int(value)
        elif self.kind == "float":
            if isinstance(value, int | float) and not isinstance(value, bool) and math.isfinite(value):
                return float(value)
        elif self.kind == "choice":
            if value in (self.choices or ()):
                return value
            valid = ", ".join(repr(c) for c in self.choices or ())
            raise InvalidArgumentError(
                f"parameter {self.name!r} must be one of {valid}; got {value!r}")
        elif isinstance(value, str):
            return value
        raise InvalidArgumentError(
            f"parameter {self.name!r} is {_article(self.kind)}; got {value!r}")

    def _check_range(self, value: Any) -> None:
        if self.kind not in ("int", "float"):
            return
        if self.min is not None and value < self.min:
            raise InvalidArgumentError(
                f"parameter {self.name!r} = {value} is below its minimum {self.min}")
        if self.max is not None and value > self.max:
            raise InvalidArgumentError(
                f"parameter {self.name!r} = {value} is above its maximum {self.max}")

    def as_python(self, value: Any) -> str:
        """A ``param(...)`` call with ``value`` as its default, for baking into a script."""
        parts = [repr(self.name), repr(value)]
        for key in ("min", "max", "step"):
            if getattr(self, key) is not None:
                parts.append(f"{key}={getattr(self, key)!r}")
        if self.choices is not None:
            parts.append(f"choices={list(self.choices)!r}")
        if self.doc:
            parts.append(f"doc={self.doc!r}")
        return f"param({', '.join(parts)})"


def _article(kind: str) -> str:
    return {"int": "an integer", "float": "a number", "bool": "a bool",
            "choice": "a choice", "str": "a string"}[kind]


def make_spec(
    name: str, default: Any, min: float | None = None, max: float | None = None,  # noqa: A002  (param's own names)
    step: float | None = None, choices: Sequence[Any] | None = None, doc: str = "",
) -> ParamSpec:
    """Build and check a :class:`ParamSpec` from the arguments of ``param()``.

    Raises:
        DLFLError: a bad name, a default outside its range or choices, a range
            on a non-number, or min > max.
    """
    if not isinstance(name, str) or not name.isidentifier():
        raise InvalidArgumentError(f"a parameter name must be a Python identifier, got "
                                   f"{shown(name)}")
    kind = _kind_of(name, default, choices)
    if (min is not None or max is not None or step is not None) and kind not in ("int", "float"):
        raise InvalidArgumentError(f"parameter {name!r}: min, max and step need a numeric default")
    # numbers (kept as given), or the range checks would compare a value with a string
    for bound, label in ((min, "min"), (max, "max")):
        if bound is not None:
            finite_number(bound, f"parameter {name!r}: {label}")
    if step is not None:
        positive_number(step, f"parameter {name!r}: step")
    if min is not None and max is not None and min > max:
        raise InvalidArgumentError(f"parameter {name!r}: min {min} is above max {max}")
    spec = ParamSpec(name, default, kind, min, max, step,
                     tuple(choices) if choices is not None else None, str(doc))
    spec.check(default)
    return spec


def _kind_of(name: str, default: Any, choices: Sequence[Any] | None) -> str:
    if choices is not None:
        if isinstance(choices, str | bytes) or not isinstance(choices, Sequence) or not choices:
            raise InvalidArgumentError(f"parameter {name!r}: choices must be a non-empty list, "
                                       f"got {shown(choices)}")
        return "choice"
    if isinstance(default, bool):
        return "bool"
    if isinstance(default, int):
        return "int"
    if isinstance(default, float):
        return "float"
    if isinstance(default, str):
        return "str"
    raise InvalidArgumentError(
        f"parameter {name!r}: the default must be a number, a bool or a string, got {default!r}"
    )
