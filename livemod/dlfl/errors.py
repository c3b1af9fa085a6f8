"""Errors raised by the DLFL library.

Every error a :mod:`livemod.dlfl` function raises for bad input is a
:class:`DLFLError`; its subclasses say what kind of failure it was, so callers
can branch on the type instead of the message::

    DLFLError (ValueError)
    ├── UnknownIdError (also LookupError)   an id that never existed or was deleted
    ├── InvalidArgumentError                 a value of the wrong type, range or kind
    ├── NonManifoldError                     input that cannot be made an oriented 2-manifold
    ├── BudgetExceededError                  the result would pass the face budget
    ├── FileFormatError                      a file that cannot be read (file and line)
    ├── GeometryError                        a geometric impossibility (a collapsed face,
    │                                        an inverted crust, an overflowing coordinate)
    └── InvalidMeshError                     a mesh that breaks the DLFL's invariants (a bug
                                             in what built it: validate's verdict)

An operation that raises leaves the mesh exactly as it was.
"""

from __future__ import annotations

import difflib
from collections.abc import Iterable


class DLFLError(ValueError):
    """A DLFL operation was given input it cannot act on.

    Raised by every public function of :mod:`livemod.dlfl` for a wrong id, a wrong
    kind of id, an ambiguous corner, a malformed file or any other bad argument.
    The message names the offending value and, for files, the file and line.
    An operation that raises leaves the mesh exactly as it was.
    """


class UnknownIdError(DLFLError, LookupError):
    """An element id that the mesh never had, or that an operation deleted."""


class InvalidArgumentError(DLFLError):
    """An argument of the wrong type, out of range, or of the wrong kind of element."""


class NonManifoldError(DLFLError):
    """Input that cannot be made into an oriented 2-manifold (an unpairable soup, a
    bow-tie vertex, an edge shared by three faces)."""


class BudgetExceededError(DLFLError):
    """The operation's result would pass the face budget; nothing was allocated.

    Attributes:
        needed: the number of faces the result would have.
        budget: the budget in force.
    """

    def __init__(self, message: str, *, needed: int = 0, budget: int = 0) -> None:
        super().__init__(message)
        self.needed = needed
        self.budget = budget


class FileFormatError(DLFLError):
    """A file that cannot be read as its format says.

    The message starts with ``file:line:`` where the line is known.

    Attributes:
        path: the file (or the label of the stream) that was read, or None.
        line: the 1-based line (or record) where reading failed, or None.
    """

    def __init__(self, message: str, *, path: str | None = None,
                 line: int | None = None) -> None:
        super().__init__(message)
        self.path = path
        self.line = line


class GeometryError(DLFLError):
    """The geometry makes the operation impossible: a face with no normal, a crust
    that turns inside out, a coordinate that overflows.

    Attributes:
        reason: what failed, said without element ids, or None. Set where the
            ids would mislead: an extrusion rehearsed on a scratch mesh reports
            the reason against the face it was given.
    """

    def __init__(self, message: str, *, reason: str | None = None) -> None:
        super().__init__(message)
        self.reason = reason


class InvalidMeshError(DLFLError):
    """A mesh that breaks an invariant of the DLFL: a corner ring that does not
    close, an edge without two sides, a dangling id.

    :func:`~livemod.dlfl.validate.validate` raises it, and so does an operation
    that finds its own intermediate mesh broken. Bad input never causes it (input
    gets one of the other subclasses first): it reports a bug in whatever built the
    mesh, to be fixed there rather than handled.
    """


class DLFLRepairWarning(UserWarning):
    """A loader repaired its input (for example re-oriented a component)."""


class DLFLSkippedLinesWarning(UserWarning):
    """A reader skipped lines it did not understand; the mesh was read without them.

    The message is ``file: ignored N line(s) not understood: line K 'text'`` (and
    how many more). Also in ``mesh.notes``.

    Attributes:
        path: the file (or the label of the stream) that was read.
        count: how many lines were skipped.
        first_line: the 1-based number of the first of them.
        first_text: that line's text, cut at 40 characters.
    """

    def __init__(self, message: str, *, path: str = "", count: int = 0, first_line: int = 0,
                 first_text: str = "") -> None:
        super().__init__(message)
        self.path = path
        self.count = count
        self.first_line = first_line
        self.first_text = first_text


def close_match(name: object, valid: Iterable[str]) -> str | None:
    """The one of ``valid`` that ``name`` most likely misspells (compared in lower
    case, ``_`` as ``-``), or None when none is close or ``name`` is no string."""
    if not isinstance(name, str):
        return None
    names = list(valid)
    key = name.strip().lower().replace("_", "-")
    folded = {n.lower().replace("_", "-"): n for n in names}
    close = difflib.get_close_matches(key, list(folded), n=1, cutoff=0.6)
    return folded[close[0]] if close else None


def shown(value: object) -> str:
    """``repr(value)`` for a message, at most 80 characters: a huge int or a long
    list would otherwise fill the screen, or (past 4,300 digits) fail to print."""
    if isinstance(value, int) and value.bit_length() > 200:
        # str() of over 4,300 digits raises ValueError (sys.set_int_max_str_digits)
        digits = f"{len(str(value)):,}" if value.bit_length() < 14_000 else "over 4,000"
        return f"an integer of {digits} digits"
    try:
        text = repr(value)
    except ValueError:  # a number too long to print, inside a container
        return f"a {type(value).__name__} holding a number too long to print"
    return text if len(text) <= 80 else text[:77] + "..."


def did_you_mean(name: object, valid: Iterable[str]) -> str:
    """``"; did you mean 'x'?"`` for the one of ``valid`` that ``name`` most likely
    misspells (see :func:`close_match`), or ``""`` when none is close."""
    guess = close_match(name, valid)
    return f"; did you mean {guess!r}?" if guess is not None else ""


def unknown_name(what: str, name: object, valid: Iterable[str], listed: str | None) -> str:
    """The message for a ``name`` that is none of ``valid``: what it is not, the
    likely intended name, and the valid ones once, e.g. ``unknown subdivision scheme
    'catmul-clark'; did you mean 'catmull-clark'? valid schemes: ...``.

    Args:
        what: the message's start, e.g. ``"unknown subdivision scheme"``.
        name: what was given.
        valid: every valid name, in the order to list them.
        listed: how the list is introduced, e.g. ``"valid schemes"``; None lists
            none (``what`` names them already).
    """
    names = list(valid)
    hint = did_you_mean(name, names)
    message = f"{what} {shown(name)}{hint}"
    if listed is not None:
        message += f"{'' if hint else ';'} {listed}: {', '.join(names)}"
    return message
