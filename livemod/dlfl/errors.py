"""Errors raised by the DLFL library."""

from __future__ import annotations


class DLFLError(ValueError):
    """A DLFL operation was given input it cannot act on.

    Raised by every public function of :mod:`livemod.dlfl` for a wrong id, a wrong
    kind of id, an ambiguous corner, a malformed file or any other bad argument.
    The message names the offending value and, for files, the file and line.
    An operation that raises leaves the mesh exactly as it was.
    """


class DLFLRepairWarning(UserWarning):
    """A loader repaired its input (for example re-oriented a component)."""
