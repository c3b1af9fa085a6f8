"""PLY headers: the types, elements and properties a header declares, how to
parse it, and the helpers both body readers share (see :mod:`.ply`)."""

from __future__ import annotations

import re
from dataclasses import dataclass, field

import numpy as np

from ..errors import FileFormatError
from .source import file_error, show_token

# PLY type names -> numpy type codes (byte order added per file)
_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1",
    "short": "i2", "int16": "i2", "ushort": "u2", "uint16": "u2",
    "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}
_STRUCT_CODES = {"i1": "b", "u1": "B", "i2": "h", "u2": "H", "i4": "i", "u4": "I"}
_ENCODINGS = {"ascii": "ascii", "binary_little_endian": "<", "binary_big_endian": ">"}


@dataclass(frozen=True)
class _Property:
    """One ``property`` line: numpy codes without byte order (``"f4"``)."""

    name: str
    code: str  # the value's type, or a list's item type
    count_code: str | None = None  # a list's count type; None for a scalar


@dataclass
class _Element:
    name: str
    count: int
    properties: list[_Property] = field(default_factory=list)
    line: int | None = None  # its header line


@dataclass
class _Header:
    encoding: str = ""  # "ascii", "<" or ">"; "" until the format line
    elements: list[_Element] = field(default_factory=list)
    body_start: int = 0  # offset of the first byte after end_header's line
    body_line: int = 0  # the body's first line


@dataclass
class _Table:
    """The wanted properties of an element, by property index.

    ``scalars[i]`` is the ``(n,)`` column of scalar property ``i``; ``lists[i]``
    is ``((n,) int64 counts, (sum counts,) items)`` of list property ``i``.
    """

    scalars: dict[int, np.ndarray] = field(default_factory=dict)
    lists: dict[int, tuple[np.ndarray, np.ndarray]] = field(default_factory=dict)



# ---------------------------------------------------------------------- header


def _parse_header(data: bytes, label: str) -> _Header:
    """The header's format and elements, and where the body starts.

    Raises:
        FileFormatError: ``label:line: header: ...`` for a line that is not understood.
    """
    first, pos = _next_line(data, 0)
    if first.strip() != b"ply":
        raise file_error(label, 1, "not a PLY file (the first line is not 'ply')")
    header = _Header()
    number = 1
    while pos < len(data):
        line, pos = _next_line(data, pos)
        number += 1
        words = line.decode("utf-8", "replace").split()
        try:
            if words == ["end_header"]:
                if not header.encoding:
                    raise _HeaderProblem("no format line")
                header.body_start, header.body_line = pos, number + 1
                return header
            _header_line(words, header, number)
        except _HeaderProblem as problem:
            raise file_error(label, number, f"header: {problem}") from None
    raise file_error(label, number, "header: no end_header line")


class _HeaderProblem(Exception):
    """What is wrong with a header line (:func:`_parse_header` adds file and line)."""


def _next_line(data: bytes, pos: int) -> tuple[bytes, int]:
    """The line starting at ``pos`` (without its line end) and the next line's start.

    Lines end as in Python's universal newlines (``\\n``, ``\\r\\n`` or a lone
    ``\\r``); the ``\\r`` of a ``\\r\\n`` stays on the line, where it is a blank.
    """
    end = data.find(b"\n", pos)
    end = len(data) if end < 0 else end
    lone = data.find(b"\r", pos, end - 1)
    if lone >= 0:
        return data[pos:lone], lone + 1
    return data[pos:end], end + 1


def _header_line(words: list[str], header: _Header, line: int) -> None:
    """Add what header line ``line`` (``words``) says to ``header``."""
    keyword = words[0] if words else "comment"
    if keyword in ("comment", "obj_info"):
        return
    if keyword == "format":
        if header.encoding:
            raise _HeaderProblem("a second format line")
        header.encoding = _encoding(words)
    elif keyword == "element":
        header.elements.append(_element(words, header, line))
    elif keyword == "property":
        if not header.elements:
            raise _HeaderProblem("a property line before any element line")
        header.elements[-1].properties.append(_property(words))
    else:
        raise _HeaderProblem(f"unknown line {_shown(words)}")


def _shown(words: list[str]) -> str:
    return show_token(" ".join(words).encode())


def _encoding(words: list[str]) -> str:
    if len(words) != 3 or words[1] not in _ENCODINGS or words[2] != "1.0":
        raise _HeaderProblem(f"unsupported format {_shown(words[1:])}")
    return _ENCODINGS[words[1]]


def _element(words: list[str], header: _Header, line: int) -> _Element:
    if len(words) != 3 or not re.fullmatch("[0-9]{1,30}", words[2]):
        raise _HeaderProblem(f"bad element line {_shown(words)}")
    name = words[1]
    if name in ("vertex", "face") and any(e.name == name for e in header.elements):
        raise _HeaderProblem(f"a second element '{name}'")
    return _Element(name, int(words[2]), line=line)


def _property(words: list[str]) -> _Property:
    is_list = len(words) > 1 and words[1] == "list"
    if len(words) != (5 if is_list else 3):
        raise _HeaderProblem(f"bad property line {_shown(words)}")
    types = words[2:4] if is_list else words[1:2]
    for type_name in types:
        if type_name not in _TYPES:
            raise _HeaderProblem(f"unknown property type {show_token(type_name.encode())}")
    if not is_list:
        return _Property(words[2], _TYPES[words[1]])
    if _TYPES[words[2]] not in _STRUCT_CODES:
        raise _HeaderProblem(f"list count type '{words[2]}' is not an integer type")
    return _Property(words[4], _TYPES[words[3]], _TYPES[words[2]])


# ---------------------------------------------------------------------- shared by the bodies


def _list_indices(element: _Element) -> list[int]:
    return [i for i, p in enumerate(element.properties) if p.count_code is not None]


def _item_offsets(first: np.ndarray, counts: np.ndarray, stride: int) -> np.ndarray:
    """``(sum counts,)`` position of every list item: row ``r``'s items start at
    ``first[r]`` and are ``stride`` apart."""
    before = np.cumsum(counts) - counts
    total = int(counts.sum())
    return np.repeat(first - before * stride, counts) + np.arange(total, dtype=np.int64) * stride


def _empty_table(element: _Element, wanted: set[int]) -> _Table:
    """The wanted columns of an element without rows (or without properties)."""
    table = _Table()
    for i in wanted:
        if element.properties[i].count_code is None:
            table.scalars[i] = np.zeros(0)
        else:
            table.lists[i] = (np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64))
    return table


def _ends_inside(label: str, element: _Element, row: int, line: int | None) -> FileFormatError:
    """The file ends inside row ``row`` (1-based) of ``element``, at ``line`` (the
    last line of an ASCII body; None in a binary one)."""
    return file_error(label, line, f"the file ends inside element '{element.name}' "
                      f"(row {row} of {element.count})")


def _too_many_rows(label: str, element: _Element, left: int, unit: str) -> FileFormatError:
    """``element`` declares more rows than ``left`` units can hold (its header line)."""
    return file_error(label, element.line, f"element '{element.name}' has {element.count} "
                      f"rows, more than the {left} {unit} left in the file can hold")


def _list_count(count: float, prop: _Property) -> int:
    """A list's count as an int.

    Raises:
        ValueError: a negative or fractional count (the caller adds file and line).
    """
    if not float(count).is_integer():
        raise ValueError(f"list '{prop.name}' has count {count}, not a whole number")
    if count < 0:
        raise ValueError(f"list '{prop.name}' has a negative count ({int(count)})")
    return int(count)
