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
