"""The face budget: one limit on the size of the mesh any operation builds.

Every operation whose growth depends on its arguments or on the mesh's size
(subdivision schemes and their levels, extrusions and handles with their
segments, ``createFace`` with its points, crust, wireframe, columns, sponge,
sierpinsky, truncation, hulls, ...) computes the size of its result from
counts first, exactly or as a safe upper bound, and refuses with
:class:`~livemod.dlfl.errors.BudgetExceededError` before it allocates anything
when that size passes the budget. The mesh is unchanged then.

The budget counts faces: a result may hold at most ``budget`` faces and
``CORNERS_PER_FACE * budget`` corners (what that many quads hold), so a mesh of
a few huge faces is bounded too. Memory follows: a built mesh takes about 76
bytes per corner, and the bulk operations peak at a few times that while they
build, so the default of 20,000,000 faces (80,000,000 corners) keeps a result
at the budget within about 6 GB and a refused operation costs nothing.

Where the budget comes from, first found first:

* ``max_faces=`` on a library call (:func:`face_budget`);
* ``Scene.face_budget`` for the thesis commands, which pass it on (a script
  sets it with ``current_scene().face_budget = N``);
* the session's default: :func:`set_default_face_budget`, else the environment
  variable ``LIVEMOD_FACE_BUDGET`` (what ``livemod run/view/batch --face-budget
  N`` sets, so the processes a batch starts share it), else
  :data:`DEFAULT_FACE_BUDGET`.

Operators that add a fixed handful of elements (``createVertex``,
``insertEdge``, ``trisectEdge``, ``connectEdges``) are not checked: reaching
the budget through them takes millions of calls.
"""

from __future__ import annotations

import os
from typing import Protocol

from .errors import BudgetExceededError, InvalidArgumentError

__all__ = [
    "CORNERS_PER_FACE", "DEFAULT_FACE_BUDGET", "ENVIRONMENT_VARIABLE", "check_growth",
    "check_size", "default_face_budget", "face_budget", "fits", "repeated",
    "set_default_face_budget",
]

DEFAULT_FACE_BUDGET = 20_000_000
"""The face budget when nothing else sets one."""

CORNERS_PER_FACE = 4
"""A result may hold this many corners per face of the budget (quads)."""

ENVIRONMENT_VARIABLE = "LIVEMOD_FACE_BUDGET"
"""The environment variable that sets the session's default budget."""

# counts past this are reported as "more than" it: levels=10**6 must not build
# a number of a million digits (nor print one)
SATURATED = 10**18

_session_default: int | None = None


class Counted(Protocol):
    """What :func:`check_growth` reads of a mesh."""

    @property
    def num_faces(self) -> int: ...

    @property
    def num_corners(self) -> int: ...


def set_default_face_budget(faces: int | None) -> None:
    """Set the budget of every operation not given one (None: back to the
    environment variable or :data:`DEFAULT_FACE_BUDGET`).

    Raises:
        InvalidArgumentError: ``faces`` is not a whole number >= 1.
    """
    global _session_default
    _session_default = None if faces is None else _whole_budget(faces, "the face budget")


def default_face_budget() -> int:
    """The session's budget: :func:`set_default_face_budget`'s, else
    ``LIVEMOD_FACE_BUDGET``'s, else :data:`DEFAULT_FACE_BUDGET`.

    Raises:
        InvalidArgumentError: ``LIVEMOD_FACE_BUDGET`` holds no whole number >= 1.
    """
    if _session_default is not None:
        return _session_default
    text = _environment_value()
    if text is None or not text.strip():
        return DEFAULT_FACE_BUDGET
    try:
        value = int(text)
    except ValueError:
        value = 0
    if value < 1:
        raise InvalidArgumentError(f"{ENVIRONMENT_VARIABLE} must be a whole number of faces "
                                   f">= 1, got {text!r}")
    return value


# os.environ keeps its variables in a dict of encoded names and values. Every
# operation that can grow reads the variable, and os.environ.get costs three
# Python calls and, when it is unset (the usual case), two exceptions: about as
# much as a chained extrusion's checks together. The dict answers in one lookup;
# where an interpreter has no such dict, the mapping is asked.
_ENVIRON_DATA = getattr(os.environ, "_data", None)
_ENVIRON_KEY = os.environ.encodekey(ENVIRONMENT_VARIABLE)


def _environment_value() -> str | None:
    """The value of :data:`ENVIRONMENT_VARIABLE` in ``os.environ``, or None."""
    data = getattr(os.environ, "_data", None)
    if data is not _ENVIRON_DATA or data is None:  # replaced, or it keeps no such dict
        return os.environ.get(ENVIRONMENT_VARIABLE)
    raw = data.get(_ENVIRON_KEY)
    return None if raw is None else os.environ.decodevalue(raw)


def face_budget(max_faces: object = None) -> int:
    """The budget in force: ``max_faces``, or the session's default when None.

    Raises:
        InvalidArgumentError: ``max_faces`` is not None nor a whole number >= 1.
    """
    if max_faces is None:
        return default_face_budget()
    return _whole_budget(max_faces, "max_faces")


def _whole_budget(value: object, name: str) -> int:
    if isinstance(value, bool) or not hasattr(value, "__index__"):
        raise InvalidArgumentError(f"{name} must be a whole number of faces >= 1, "
                                   f"got {value!r}")
    number = value.__index__()
    if number < 1:
        raise InvalidArgumentError(f"{name} must be a whole number of faces >= 1, "
                                   f"got {number}")
    return number


def check_size(operation: str, faces: int, corners: int = 0, *,
               max_faces: object = None) -> None:
    """Refuse a result of ``faces`` faces and ``corners`` corners over the budget.

    Args:
        operation: what would build it, for the message (``"catmull-clark"``).
        faces, corners: the size of the result (exact or an upper bound), from
            counts; any size of int (:func:`repeated` keeps them printable).
        max_faces: the caller's budget, or None for the session's.

    Raises:
        BudgetExceededError: over the budget; ``needed`` is the smallest budget
            that would allow it (at most :data:`SATURATED`).
        InvalidArgumentError: a bad ``max_faces``.
    """
    # the common path, a result within the budget, is a few comparisons: every
    # extrusion of a chain passes here
    budget = default_face_budget() if max_faces is None else face_budget(max_faces)
    quads = -(-corners // CORNERS_PER_FACE)
    needed = faces if faces >= quads else quads
    if needed <= budget:
        return
    if faces >= needed:
        what = f"{_count(faces)} faces, more than the budget of {budget:,} faces"
    else:
        what = (f"{_count(corners)} corners, more than the budget of {budget:,} faces "
                f"allows ({CORNERS_PER_FACE} corners a face: {budget * CORNERS_PER_FACE:,})")
    raise BudgetExceededError(
        f"{operation} would produce {what}; nothing was changed. To allow it, raise "
        f"the budget: max_faces=N on the call, current_scene().face_budget = N in a "
        f"script, livemod run/view/batch --face-budget N, or {ENVIRONMENT_VARIABLE}=N",
        needed=min(needed, SATURATED), budget=budget)


def fits(faces: int, corners: int = 0, *, max_faces: object = None) -> bool:
    """Whether a result of ``faces`` faces and ``corners`` corners is within the
    budget (see :func:`check_size`).

    Raises:
        InvalidArgumentError: a bad ``max_faces``.
    """
    return _needed(faces, corners) <= face_budget(max_faces)


def _needed(faces: int, corners: int) -> int:
    """The smallest budget that allows ``faces`` faces and ``corners`` corners."""
    return max(faces, -(-corners // CORNERS_PER_FACE))


def check_growth(mesh: Counted, operation: str, *, faces: int, corners: int,
                 max_faces: object = None) -> None:
    """:func:`check_size` for an operation that adds ``faces`` and ``corners``
    (upper bounds) to ``mesh``, whose elements it keeps.

    Raises:
        BudgetExceededError, InvalidArgumentError: see :func:`check_size`.
    """
    check_size(operation, mesh.num_faces + faces, mesh.num_corners + corners,
               max_faces=max_faces)


def repeated(count: int, factor: int, times: int) -> int:
    """``count * factor**times`` for counts ``>= 0``, or :data:`SATURATED` when
    that is more: the size after ``times`` levels that each multiply it, without
    building a number of ``times`` digits."""
    if count == 0 or factor == 1:
        return count
    size = count
    for _ in range(times):  # factor >= 2: saturates within 60 turns
        size *= factor
        if size >= SATURATED:
            return SATURATED
    return size


def _count(number: int) -> str:
    """``number`` with thousands separators, or "more than 10^18" past that."""
    if number >= SATURATED:
        return "more than 10^18"
    return f"{number:,}"
