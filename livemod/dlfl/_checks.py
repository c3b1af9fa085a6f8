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
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise DLFLError(f"{name} must be a number, got {value!r}")
    number = float(value)
    if not math.isfinite(number):
        raise DLFLError(f"{name} must be finite, got {value!r}")
    return number
