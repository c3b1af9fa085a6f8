"""Where a reader's bytes come from: a path or the contents themselves."""

from __future__ import annotations

import os

import numpy as np

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


def show_token(token: bytes) -> str:
    """A token from a file as it should appear in an error message (quoted, cut at 40)."""
    text = token.decode("utf-8", "replace")
    return repr(text if len(text) <= 40 else text[:40] + "...")


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
