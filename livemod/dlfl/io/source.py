"""Where a reader's bytes come from: a path or the contents themselves."""

from __future__ import annotations

import os


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
    """``data`` with classic Mac OS line ends (a lone ``\\r``) turned into ``\\n``.

    Only a file holding no ``\\n`` at all is rewritten: the line readers split at
    ``\\n`` and take ``\\r`` for a blank, so such a file would read as one line
    (its first ``v`` and nothing else). The test stops at the first ``\\n`` of an
    ordinary file, so LF and CRLF files cost nothing.
    """
    if b"\n" not in data and b"\r" in data:
        return data.replace(b"\r", b"\n")
    return data
