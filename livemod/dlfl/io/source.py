"""Where a reader's bytes come from: a path or the contents themselves."""

from __future__ import annotations

import os
import shlex
import warnings

import numpy as np

from ..errors import DLFLSkippedLinesWarning, FileFormatError
from ..mesh import Mesh
from ._lines import byte_offsets


def read_source(
    source: str | os.PathLike[str] | bytes, name: str | None, default: str
) -> tuple[bytes, str]:
    """The bytes to parse and the name to use in messages.

    Args:
        source: a path (``str`` or path-like), or the file contents as bytes.
        name: the name for messages; default the path, or ``default`` for bytes.
        default: the name used for in-memory contents without ``name``.

    Raises:
        OSError: the path cannot be read.
    """
    if isinstance(source, (bytes, bytearray, memoryview)):
        return bytes(source), name or default
    path = os.fspath(source)
    with open(path, "rb") as handle:
        data = handle.read()
    return data, name or path


def show_path(path: str | os.PathLike[str]) -> str:
    """A file name as every livemod message shows it: as it is where a shell would
    take it so (``model.obj``, ``out/a-1.stl``), else in single quotes
    (``'my model.obj'``, ``''``), so that it can be pasted into a command. A
    stream's label (``<obj>``) is shown as it is."""
    name = os.fspath(path)
    if name.startswith("<") and name.endswith(">") and len(name) > 2:
        return name
    return shlex.quote(name)


def file_error(label: str, line: int | None, what: str) -> FileFormatError:
    """The error for a file that cannot be read as its format says.

    Args:
        label: the file's name (or a stream's label such as ``<obj>``).
        line: the 1-based line where reading failed; None where the format has
            no lines (binary files) or the problem is the whole file's.
        what: what is wrong.

    Returns:
        ``FileFormatError("label:line: what", path=label, line=line)`` (the
        name shown by :func:`show_path`; ``label: what`` without a line).
    """
    where = show_path(label) if line is None else f"{show_path(label)}:{line}"
    return FileFormatError(f"{where}: {what}", path=label, line=line)


def report_skipped(mesh: Mesh, label: str, lines: list[int], first_text: bytes) -> None:
    """Tell that a reader skipped ``lines`` (1-based, ascending, not empty) of the
    file ``label``, the first reading ``first_text``: a note in ``mesh.notes`` and
    a :class:`DLFLSkippedLinesWarning` (the command line prints it as a note)."""
    count, text = len(lines), _cut(first_text.strip())
    more = f" and {count - 1} more" if count > 1 else ""
    message = (f"{show_path(label)}: ignored {count} line{'s' if count > 1 else ''} not "
               f"understood: line {lines[0]} {text!r}{more}")
    mesh.notes.append(message)
    warnings.warn(DLFLSkippedLinesWarning(message, path=label, count=count, first_line=lines[0],
                                          first_text=text), stacklevel=3)


def show_token(token: bytes) -> str:
    """A token from a file as it should appear in an error message (quoted, cut at 40)."""
    return repr(_cut(token))


def _cut(token: bytes) -> str:
    """``token`` as text, cut at 40 characters (``...`` added)."""
    text = token.decode("utf-8", "replace")
    return text if len(text) <= 40 else text[:40] + "..."


def lf_line_ends(data: bytes) -> bytes:
    """``data`` with every lone ``\\r`` (one not followed by ``\\n``) turned into ``\\n``.

    The line readers split at ``\\n`` and take ``\\r`` for a blank, so this gives
    them Python's universal newlines: ``\\r\\n``, ``\\n`` and a lone ``\\r`` (classic
    Mac OS, or one stray line end in an LF file) each end one line. Otherwise a
    lone ``\\r`` would join two lines into one. Both have the same length, so
    byte offsets stay those of ``data``.

    Cost: an LF file pays one memchr for ``\\r``; a CRLF file one blocked search
    for ``\\r`` and a look at the byte after each; only a file that holds a lone
    ``\\r`` is copied.
    """
    if b"\r" not in data:
        return data
    if b"\n" not in data:
        return data.replace(b"\r", b"\n")
    buf = np.frombuffer(data, dtype=np.uint8)
    returns = byte_offsets(buf, 13)
    following = buf[np.minimum(returns + 1, len(buf) - 1)]
    lone = returns[(following != 10) | (returns == len(buf) - 1)]
    if len(lone) == 0:
        return data
    fixed = bytearray(data)
    np.frombuffer(fixed, dtype=np.uint8)[lone] = 10
    return bytes(fixed)


def file_stem(path: str) -> str:
    """The name of the file ``path`` without its extension (``"mesh"`` for a name
    that is all extension), after which a writer names the files it puts beside it."""
    return os.path.splitext(os.path.basename(path))[0] or "mesh"


def companion_path(path: str, suffix: str) -> str:
    """The file of ``path``'s stem and ``suffix`` (e.g. ``".mtl"``) beside ``path``:
    where a writer puts a file its output names (a material library, a buffer)."""
    return os.path.join(os.path.dirname(path), file_stem(path) + suffix)
