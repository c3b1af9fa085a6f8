"""What every ``livemod`` subcommand shares: exit codes, one-line messages, and the
checks of the files a command reads and writes, made before anything runs.

Exit codes (``livemod --help`` and the guide's command line section say the same):

- 0: done.
- 1: the script, a file or a variant failed: a script error, an input that is
  missing, unreadable or malformed, an output that cannot be written, no GL.
- 2: the command line is wrong: argparse's own errors and what is checked against
  the arguments after parsing (:class:`UsageError`), e.g. an output suffix no
  writer takes or a parameter the script does not declare.
- 130: interrupted (Ctrl-C); 141: the reader of the output went away.

Every message is one line on standard error, ``livemod: error: <what>: <why>``
(``warning`` and ``note`` likewise), naming the file, never an ``[Errno N]``.
This module imports neither the runner nor the viewer (both use it).
"""

from __future__ import annotations

import argparse
import contextlib
import errno
import os
import sys
import tempfile
from collections.abc import Iterable, Iterator
from typing import TextIO

from livemod.dlfl.errors import did_you_mean
from livemod.dlfl.io.source import show_path

DONE, FAILED, USAGE, INTERRUPTED, READER_LEFT = 0, 1, 2, 130, 141

EXIT_CODES_HELP = ("exit codes: 0 done; 1 the script, a file or a variant failed; 2 the "
                   "command line is wrong; 130 interrupted (Ctrl-C); 141 the reader of the "
                   "output left (| head)")


class Parser(argparse.ArgumentParser):
    """argparse's parser, whose invalid choice (a subcommand, ``--background``) also
    says which choice was likely meant: ``invalid choice: 'rn'; did you mean
    'run'? (choose from ...)``. Subcommands' parsers are of this class too."""

    def _check_value(self, action: argparse.Action, value: object) -> None:
        choices = action.choices
        if choices is None or value in choices:
            return
        names = [str(choice) for choice in choices]
        hint = did_you_mean(value, names)
        listed = ", ".join(map(repr, names))
        raise argparse.ArgumentError(action, f"invalid choice: {value!r}{hint} "
                                             f"(choose from {listed})")


class UsageError(ValueError):
    """The command line asks for what cannot be done (exit 2); the text says why."""


@contextlib.contextmanager
def usage_errors() -> Iterator[None]:
    """A block whose ValueErrors (a :class:`~livemod.dlfl.errors.DLFLError` too) are
    the command line's fault: each is re-raised as a :class:`UsageError`."""
    try:
        yield
    except UsageError:
        raise
    except ValueError as exc:
        raise UsageError(str(exc)) from None


def describe(exc: BaseException) -> str:
    """``exc`` as the ``<what>: <why>`` of one message: an OSError as the file it
    names and the system's words for what failed (no ``[Errno N]``); anything else
    (a DLFLError names its file and line itself) as its text."""
    if isinstance(exc, OSError) and exc.strerror:
        if exc.filename is None:  # the message already names the file (atomic writes)
            return exc.strerror
        return f"{show_path(os.fsdecode(exc.filename))}: {exc.strerror}"
    return str(exc) or type(exc).__name__


def error(text: str, stream: TextIO | None = None) -> None:
    """Print ``livemod: error: text`` on ``stream`` (default: standard error)."""
    _say("error", text, stream)


def warning(text: str, stream: TextIO | None = None) -> None:
    """Print ``livemod: warning: text`` on ``stream`` (default: standard error)."""
    _say("warning", text, stream)


def note(text: str, stream: TextIO | None = None) -> None:
    """Print ``livemod: note: text`` on ``stream`` (default: standard error)."""
    _say("note", text, stream)


def _say(kind: str, text: str, stream: TextIO | None) -> None:
    print(f"livemod: {kind}: {text}", file=stream or sys.stderr, flush=True)


def check_readable(path: str | os.PathLike[str]) -> None:
    """Check that ``path`` is a file this process can open for reading.

    Raises:
        OSError: it cannot be read; the message is ``cannot read PATH: why``.
    """
    name = os.fspath(path)
    try:
        if os.path.isdir(name):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR))
        with open(name, "rb"):
            pass
    except OSError as exc:
        raise type(exc)(exc.errno, f"cannot read {show_path(name)}: {exc.strerror}") from None


def check_writable(paths: Iterable[str | os.PathLike[str]]) -> None:
    """Check, before a long run, that each of ``paths`` can be written as livemod
    writes outputs: atomically, its folder made if missing. So the folder, or the
    nearest part of it that exists, must be a folder that takes a new file (tried
    with an unnamed temporary file: it catches what permission bits do not, such
    as a read-only disk or ``/proc``), and the path must not be a folder.

    Raises:
        OSError: the first path that cannot be written; the message is
            ``cannot write PATH: why``.
    """
    tried: set[str] = set()
    for path in paths:
        name = os.fspath(path)
        target = os.path.realpath(os.path.abspath(name))  # atomic writes follow links
        try:
            if os.path.isdir(target):
                raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR))
            folder = _existing_part(os.path.dirname(target))
            if folder not in tried:
                _try_a_file_in(folder)
                tried.add(folder)
        except OSError as exc:
            raise type(exc)(exc.errno, f"cannot write {show_path(name)}: {exc.strerror}") from None


def _existing_part(folder: str) -> str:
    """The nearest of ``folder`` and its parents that exists (``/`` always does)."""
    while not os.path.exists(folder):
        folder = os.path.dirname(folder)
    return folder


def _try_a_file_in(folder: str) -> None:
    """Create and drop a temporary file in ``folder`` (unnamed where the system
    allows: a watcher of the folder sees nothing).

    Raises:
        OSError: ``folder`` is a file, or takes no new file (the system's reason).
    """
    if not os.path.isdir(folder):
        raise NotADirectoryError(errno.ENOTDIR, f"{show_path(folder)} is a file, not a folder")
    with tempfile.TemporaryFile(dir=folder):
        pass
