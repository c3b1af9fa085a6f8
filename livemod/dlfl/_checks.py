"""Argument checks shared by the operations, so one mistake reads the same everywhere."""

from __future__ import annotations

import math
import numbers

from .errors import DLFLError


def finite_number(value: object, name: str) -> float:
    """``value`` as a float.

    Python and numpy ints and floats are numbers; bools and strings are not.

    Raises:
        DLFLError: ``value`` is not a number, or is NaN or infinite; the message
            names ``name`` and shows the value.
    """
    kind = type(value)
    # float and int first: the ABC check costs more than the rest of this
    if kind is not float and kind is not int and (
            isinstance(value, bool) or not isinstance(value, numbers.Real)):
        raise DLFLError(f"{name} must be a number, got {value!r}")
    number = float(value)  # type: ignore[arg-type]
    if not math.isfinite(number):
        raise DLFLError(f"{name} must be finite, got {value!r}")
    return number
