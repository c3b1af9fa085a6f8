"""Argument checks shared by the operations, so one mistake reads the same everywhere.

The checks raise :class:`InvalidArgumentError` naming the argument and showing the value.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable
from math import isfinite
from typing import Any, TypeGuard

import numpy as np

from .errors import InvalidArgumentError, UnknownIdError, shown

# ids are int64 in the element tables and their dense snapshots: an integer
# outside this range names no element (and numpy could not even hold it)
ID_RANGE = range(-2**63, 2**63)


def finite_number(value: object, name: str) -> float:
    """``value`` as a float.

    Python and numpy ints and floats are numbers; bools and strings are not.

    Raises:
        InvalidArgumentError: ``value`` is not a number, or is NaN or infinite
            (an int beyond the float range too); the message names ``name`` and
            shows the value.
    """
    kind = type(value)
    # float and int first: the ABC check costs more than the rest of this
    if kind is not float and kind is not int and (
            isinstance(value, bool) or not isinstance(value, numbers.Real)):
        raise InvalidArgumentError(f"{name} must be a number, got {shown(value)}")
    try:
        number = float(value)  # type: ignore[arg-type]
    except OverflowError:  # an int beyond the float range, 10**400
        number = math.inf
    if not math.isfinite(number):
        raise InvalidArgumentError(f"{name} must be finite, got {shown(value)}")
    return number


def finite_vector(value: object, name: str, *, repeat_scalar: bool = False) -> np.ndarray:
    """``(3,)`` float64 from three finite numbers (with ``repeat_scalar``, one
    number stands for all three).

    Raises:
        InvalidArgumentError: anything else, naming ``name`` (numpy's own ValueError for
            strings or ragged rows would not say which argument was wrong).
    """
    try:
        arr = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError, OverflowError):  # OverflowError: 10**400
        raise InvalidArgumentError(f"{name} must be three finite numbers, got "
                                   f"{shown(value)}") from None
    if repeat_scalar and arr.shape == ():
        arr = np.full(3, float(arr))
    if arr.shape != (3,) or not np.isfinite(arr).all():
        raise InvalidArgumentError(f"{name} must be three finite numbers, got {shown(value)}")
    return arr


def as_point(position: Any) -> tuple[float, float, float]:
    """``position`` (three finite numbers: a tuple, a list, a ``(3,)`` array) as
    three floats.

    Raises:
        InvalidArgumentError: not three numbers, or one of them is NaN or infinite.
    """
    kind = type(position)
    # a string unpacks into digits ("123" -> 1, 2, 3; b"123" -> 49, 50, 51): refuse
    # it, testing the common tuple and list first to keep create_vertex fast
    if kind is not tuple and kind is not list and isinstance(position, (str, bytes, bytearray)):
        raise InvalidArgumentError(
            f"expected a position (x, y, z) of three numbers, got {shown(position)}")
    try:
        x, y, z = (float(v) for v in position)
    except (TypeError, ValueError, OverflowError):  # OverflowError: an int like 10**400
        raise InvalidArgumentError(
            f"expected a position (x, y, z) of three numbers, got {shown(position)}"
        ) from None
    if not (isfinite(x) and isfinite(y) and isfinite(z)):
        raise InvalidArgumentError(f"expected a position (x, y, z) of three finite numbers, got "
                                   f"{shown(position)}")
    return x, y, z


def rgb(value: object, name: str = "colour") -> tuple[float, float, float]:
    """``value`` as a colour: three numbers ``(r, g, b)``, each in ``[0, 1]``.

    Raises:
        InvalidArgumentError: not three numbers, or one outside ``[0, 1]`` (the
            message suggests dividing 0-255 values by 255).
    """
    wanted = f"{name} must be three numbers (r, g, b) in [0, 1], got {shown(value)}"
    if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
        raise InvalidArgumentError(wanted)
    parts = list(value)
    if len(parts) != 3:
        raise InvalidArgumentError(wanted)
    red, green, blue = (finite_number(v, name) for v in parts)
    if not all(0.0 <= v <= 1.0 for v in (red, green, blue)):
        raise InvalidArgumentError(f"{wanted} (divide 0-255 values by 255)")
    return red, green, blue


def is_id(value: object) -> TypeGuard[numbers.Integral]:
    """True for a Python or numpy integer (an id); bools are not ids."""
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def id_list(values: object, name: str) -> list[int]:
    """``values``, an iterable of element ids, as a list of ints.

    Python and numpy integers are ids; bools, floats and strings are not (a
    float would otherwise be truncated to some other element's id).

    Raises:
        InvalidArgumentError: ``values`` is not iterable, or holds something that
            is not an integer; the message names ``name`` and shows the value.
        UnknownIdError: an integer outside the int64 range of ids, which no
            element has (and no id array could hold).
    """
    if isinstance(values, str | bytes) or not isinstance(values, Iterable):
        raise InvalidArgumentError(f"{name} must be a list of ids, got {shown(values)}")
    ids = list(values)
    for value in ids:
        if isinstance(value, bool) or not isinstance(value, numbers.Integral):
            raise InvalidArgumentError(f"{name} must hold ids (integers), got {shown(value)}")
    out = [int(value) for value in ids]
    for value in out:
        if value not in ID_RANGE:
            raise UnknownIdError(f"{name}: no element has the id {shown(value)} (ids lie "
                                 "below 2**63)")
    return out


def flag(value: object, name: str) -> bool:
    """``value`` as a bool, for an on/off option.

    True, False, numpy bools and the integers 0 and 1 (TopMod's C++ took ints)
    are flags; anything else is refused, or a string such as ``"no"`` or
    ``"False"`` would silently mean True.

    Raises:
        InvalidArgumentError: ``value`` is not one of those; the message names ``name``.
    """
    if value is True or value is False:
        return value
    if isinstance(value, np.bool_ | numbers.Integral) and value in (0, 1):
        return bool(value)
    raise InvalidArgumentError(f"{name} must be True or False, got {shown(value)}")


def positive_number(value: object, name: str) -> float:
    """``value`` as a float greater than 0.

    Raises:
        InvalidArgumentError: not a finite number (see :func:`finite_number`), or not > 0.
    """
    number = finite_number(value, name)
    if number <= 0:
        raise InvalidArgumentError(f"{name} must be a positive number, got {shown(value)}")
    return number


# ids and corner links are int32 in the element tables: no mesh holds more of a kind
MAX_ELEMENTS = 2**31 - 1


def whole_count(value: object, name: str, *, least: int = 1, each: int = 1) -> int:
    """``value`` as an int of at least ``least``, for an operation that makes at
    least ``each`` new corners per unit of it (0: the caller checks the face
    budget first, then calls again with its ``each``).

    Raises:
        InvalidArgumentError: not an integer (bools are not), below ``least``, or so
            large that ``value * each`` corners would not fit in a mesh (a count
            like ``10**30`` would otherwise run until memory ran out).
    """
    # a plain int first: the ABC check costs more than the rest (chained extrusions)
    if type(value) is not int and (isinstance(value, bool)
                                   or not isinstance(value, numbers.Integral)):
        raise InvalidArgumentError(f"{name} must be an integer >= {least}, got {shown(value)}")
    count = int(value)
    if count < least:
        raise InvalidArgumentError(f"{name} must be an integer >= {least}, got {shown(count)}")
    if count * each > MAX_ELEMENTS:
        made = count * each
        raise InvalidArgumentError(f"{name}={shown(count)} would make at least "
                                   f"{f'{made:,}' if made.bit_length() <= 200 else shown(made)} "
                                   f"corners, more than a mesh can hold ({MAX_ELEMENTS:,})")
    return count


def first_not_finite(rows: np.ndarray) -> int | None:
    """Index of the first row of ``rows`` ``(N, 3)`` with a NaN or infinite
    coordinate (the one an overflow message names), or None when all are finite."""
    if np.isfinite(rows).all():
        return None
    return int(np.flatnonzero(~np.isfinite(rows).all(axis=1))[0])
