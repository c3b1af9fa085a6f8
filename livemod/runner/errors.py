"""Turn what a script raised into a :class:`ScriptError` a person can act on, and
the runner's own exceptions."""

from __future__ import annotations

import builtins
import difflib
import os
import traceback
from types import TracebackType

import livemod
from livemod.dlfl.errors import DLFLError

from .results import ScriptError

_LIBRARY_DIR = os.path.dirname(os.path.abspath(livemod.__file__)) + os.sep


class Cancelled(BaseException):  # noqa: N818  (a signal, not an error)
    """Raised inside a run to stop it (a BaseException so ``except Exception``
    in a script does not swallow it)."""


class ScriptFailedError(DLFLError):
    """A headless run of the user's script failed: ``livemod render``, a film, a
    batch's parameters found by running it.

    The message is ``FILE:LINE: TypeName: text``, as the window's error panel says
    it, unless the raiser words it for its context.

    Attributes:
        error: the run's :class:`ScriptError` (file, line, message, short traceback).
    """

    def __init__(self, error: ScriptError, message: str | None = None) -> None:
        super().__init__(str(error) if message is None else message)
        self.error = error


def syntax_error(exc: SyntaxError, path: str) -> ScriptError:
    """A ``"syntax"`` error for a script that did not compile."""
    lines = traceback.format_exception_only(type(exc), exc)
    return ScriptError(
        kind="syntax",
        file=exc.filename or path,
        line=exc.lineno,
        message=f"SyntaxError: {exc.msg}",
        traceback="".join(lines),
    )


def cancelled_error(path: str, line: int | None = None) -> ScriptError:
    """A ``"cancelled"`` error (the run was superseded or stopped)."""
    return ScriptError("cancelled", path, line, "cancelled", "")


def exception_error(exc: BaseException, path: str) -> ScriptError:
    """An ``"exception"`` error pointing at the deepest frame of the user's code.

    Frames of the livemod package (the library and the runner) and of code outside
    the script's folder are trimmed; the script's and its local modules' remain.
    """
    frames = _user_frames(exc.__traceback__, path)
    file, line = (frames[-1].filename, frames[-1].lineno) if frames else (path, None)
    suggestion = _suggestion(exc)
    hint = f". Did you mean: '{suggestion}'?" if suggestion else ""
    message = _one_line(exc) + hint
    text = "Traceback (most recent call last):\n"
    text += "".join(traceback.format_list(frames)) + _described(exc, hint)
    return ScriptError("exception", file, line, message, text)


def _one_line(exc: BaseException) -> str:
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0]}" if text else type(exc).__name__


def _described(exc: BaseException, hint: str) -> str:
    """The last lines of a traceback: type, whole text and ``hint``, then the
    exception's notes (``add_note``), each on its own line."""
    body = str(exc)
    lines = [(f"{type(exc).__name__}: {body}" if body else type(exc).__name__) + hint]
    notes = getattr(exc, "__notes__", None)
    if isinstance(notes, list | tuple):
        lines += [str(note) for note in notes]
    return "\n".join(lines) + "\n"


def _suggestion(exc: BaseException) -> str | None:
    """The name a misspelt name or attribute was most likely meant to be, as
    Python's own traceback offers it ("Did you mean: 'extrude'?"), or None.

    CPython 3.11 computes that only when it prints a traceback itself, so the
    runner, which formats its own, looks the name up the same way: among the
    raising frame's names and the builtins, or the object's attributes.
    """
    name = getattr(exc, "name", None)
    if not isinstance(name, str) or not isinstance(exc, NameError | AttributeError):
        return None
    if isinstance(exc, AttributeError):
        try:
            candidates = dir(exc.obj)
        except Exception:  # an object whose __dir__ fails offers no suggestion
            return None
    else:
        candidates = _frame_names(exc.__traceback__)
    close = difflib.get_close_matches(name, [c for c in candidates if c != name], n=1)
    return close[0] if close else None


def _frame_names(tb: TracebackType | None) -> list[str]:
    """Local, global and builtin names of the frame ``tb`` ends in."""
    if tb is None:
        return list(vars(builtins))
    while tb.tb_next is not None:
        tb = tb.tb_next
    frame = tb.tb_frame
    return [*frame.f_locals, *frame.f_globals, *vars(builtins)]


# folders of installed packages: a project often keeps its virtual environment
# (".venv/lib/python3.11/site-packages") inside the script's folder
_PACKAGE_FOLDERS = frozenset({"site-packages", "dist-packages"})


def is_user_file(filename: str, script: str) -> bool:
    """True for the script and for files in its folder (or below) that are the
    user's: not livemod itself, nor a package installed there."""
    if filename == script:
        return True
    folder = os.path.dirname(script) + os.sep
    if not filename.startswith(folder) or filename.startswith(_LIBRARY_DIR):
        return False
    below = filename[len(folder):].split(os.sep)
    return _PACKAGE_FOLDERS.isdisjoint(below)


def _user_frames(tb: TracebackType | None, script: str) -> traceback.StackSummary:
    kept = [
        (frame, lineno)
        for frame, lineno in traceback.walk_tb(tb)
        if is_user_file(frame.f_code.co_filename, script)
    ]
    return traceback.StackSummary.extract(iter(kept), lookup_lines=True)
