"""Argument checks shared by the operations, so one mistake reads the same everywhere."""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from typing import TypeGuard

import numpy as np

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


def finite_vector(value: object, name: str, *, repeat_scalar: bool = False) -> np.ndarray:
    """``(3,)`` float64 from three finite numbers (with ``repeat_scalar``, one
    number stands for all three).

    Raises:
        DLFLError: anything else, naming ``name`` (numpy's own ValueError for
            strings or ragged rows would not say which argument was wrong).
    """
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        raise DLFLError(f"{name} must be three finite numbers, got {value!r}") from None
    if repeat_scalar and arr.shape == ():
        arr = np.full(3, float(arr))
    if arr.shape != (3,) or not np.isfinite(arr).all():
        raise DLFLError(f"{name} must be three finite numbers, got {value!r}")
    return arr


def is_id(value: object) -> TypeGuard[numbers.Integral]:
    """True for a Python or numpy integer (an id); bools are not ids."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def id_list(values: object, name: str) -> list[int]:
    """``values``, an iterable of element ids, as a list of ints.

    Python and numpy integers are ids; bools, floats and strings are not (a
    float would otherwise be truncated to some other element's id).

    Raises:
        DLFLError: ``values`` is not iterable, or holds something that is not an
            integer; the message names ``name`` and shows the value.
    """
    if isinstance(values, str | bytes) or not isinstance(values, Iterable):
        raise DLFLError(f"{name} must be a list of ids, got {values!r}")
    ids = list(values)
    for value in ids:
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise DLFLError(f"{name} must hold ids (integers), got {value!r}")
    return [int(value) for value in ids]


def flag(value: object, name: str) -> bool:
    """``value`` as a bool, for an on/off option.

    True, False, numpy bools and the integers 0 and 1 (TopMod's C++ took ints)
    are flags; anything else is refused, or a string such as ``"no"`` or
    ``"False"`` would silently mean True.

    Raises:
        DLFLError: ``value`` is not one of those; the message names ``name``.
    """
    if value is True or value is False:
        return value
    if isinstance(value, np.bool_ | numbers.Integral) and value in (0, 1):
        return bool(value)
    raise DLFLError(f"{name} must be True or False, got {value!r}")


def positive_number(value: object, name: str) -> float:
    """``value`` as a float greater than 0.

    Raises:
        DLFLError: not a finite number (see :func:`finite_number`), or not > 0.
    """
    number = finite_number(value, name)
    if number <= 0:
        raise DLFLError(f"{name} must be a positive number, got {value!r}")
    return number


# ids and corner links are int32 in the element tables: no mesh holds more of a kind
MAX_ELEMENTS = 2**31 - 1


def whole_count(value: object, name: str, *, least: int = 1, each: int = 1) -> int:
    """``value`` as an int of at least ``least``, for an operation that makes at
    least ``each`` new corners per unit of it.

    Raises:
        DLFLError: not an integer (bools are not), below ``least``, or so large
            that ``value * each`` corners would not fit in a mesh (a count like
            ``10**30`` would otherwise run until memory ran out).
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise DLFLError(f"{name} must be an integer >= {least}, got {value!r}")
    count = int(value)
    if count < least:
        raise DLFLError(f"{name} must be an integer >= {least}, got {count}")
    if count * each > MAX_ELEMENTS:
        raise DLFLError(f"{name}={count} would make at least {count * each:,} corners, more "
                        f"than a mesh can hold ({MAX_ELEMENTS:,})")
    return count


def first_not_finite(rows: np.ndarray) -> int | None:
    """Index of the first row of ``rows`` ``(N, 3)`` with a NaN or infinite
    coordinate (the one an overflow message names), or None when all are finite."""
    if np.isfinite(rows).all():
        return None
    return int(np.flatnonzero(~np.isfinite(rows).all(axis=1))[0])
