"""PLY binary bodies (either byte order): one ``np.frombuffer`` per element whose
rows share a layout, a row-by-row walk otherwise (see :mod:`.ply`)."""

from __future__ import annotations

import struct
from array import array

import numpy as np

from ._ply_layout import (
    _STRUCT_CODES,
    _Element,
    _empty_table,
    _ends_inside,
    _item_offsets,
    _list_count,
    _list_indices,
    _Property,
    _Table,
    _too_many_rows,
)
from .source import file_error


class _BinaryBody:
    """Reads the elements of a binary body one after the other.

    An element whose rows all have the list counts of its first row (every
    element without lists, and the faces of a mesh of one polygon size) is one
    ``np.frombuffer`` with a structured dtype; any other goes row by row.
    """

    def __init__(self, data: bytes, start: int, order: str, label: str) -> None:
        self.data, self.pos, self.order, self.label = data, start, order, label

    def element(self, element: _Element, wanted: set[int]) -> _Table:
        """The wanted columns of ``element``'s rows, which start at ``self.pos``."""
        if element.count == 0 or not element.properties:
            return _empty_table(element, wanted)
        self._check_room(element)
        _, first_counts, first_end = self._walk(element, 1)
        dtype = self._row_dtype(element, first_counts[0].tolist())
        if element.count <= (len(self.data) - self.pos) // dtype.itemsize:
            rows = np.frombuffer(self.data, dtype, count=element.count, offset=self.pos)
            if all((rows[f"n{i}"] == rows[f"n{i}"][0]).all() for i in _list_indices(element)):
                self.pos += element.count * dtype.itemsize
                return _rows_table(rows, element, wanted)
        starts, counts, end = self._walk(element, element.count)
        self.pos = end
        return self._walked_table(element, starts, counts, wanted)

    def _check_room(self, element: _Element) -> None:
        """Refuse, before reading, a row count the rest of the file cannot hold."""
        sizes = [np.dtype(p.count_code or p.code).itemsize for p in element.properties]
        left = len(self.data) - self.pos
        room = left // sum(sizes)
        if element.count <= room:
            return
        if not _list_indices(element):  # rows of one size: we know where it ends
            raise _ends_inside(self.label, element, room + 1, None)
        raise _too_many_rows(self.label, element, left, "bytes")

    def _row_dtype(self, element: _Element, counts: list[int]) -> np.dtype:
        """A row as a structured dtype: ``p{i}`` value (or items), ``n{i}`` list count."""
        fields: list[tuple[str, str] | tuple[str, str, tuple[int]]] = []
        list_counts = iter(counts)
        for i, prop in enumerate(element.properties):
            if prop.count_code is None:
                fields.append((f"p{i}", self.order + prop.code))
            else:
                fields.append((f"n{i}", self.order + prop.count_code))
                fields.append((f"p{i}", self.order + prop.code, (next(list_counts),)))
        return np.dtype(fields)

    def _walk(self, element: _Element, rows: int) -> tuple[np.ndarray, np.ndarray, int]:
        """Walk ``rows`` rows from ``self.pos`` (which stays).

        Returns:
            ``(starts, counts, end)``: ``(rows, P)`` int64 byte offset of every
            property, ``(rows, L)`` int64 count of every list, the end offset.
        """
        data, end, pos = self.data, len(self.data), self.pos
        steps = [(np.dtype(p.count_code or p.code).itemsize,
                  struct.Struct(self.order + _STRUCT_CODES[p.count_code]) if p.count_code else None,
                  np.dtype(p.code).itemsize, p) for p in element.properties]
        starts, counts = array("q"), array("q")
        for row in range(rows):
            for size, count_struct, item_size, prop in steps:
                starts.append(pos)
                if count_struct is not None and pos + size <= end:
                    count = count_struct.unpack_from(data, pos)[0]
                    if count < 0:
                        self._check_count(count, element, row, prop)
                    counts.append(count)
                    pos += count * item_size
                pos += size
            if pos > end:
                raise _ends_inside(self.label, element, row + 1, None)
        shape = (rows, -1)
        return np.array(starts, np.int64).reshape(shape), np.array(counts, np.int64).reshape(shape), pos

    def _check_count(self, count: int, element: _Element, row: int, prop: _Property) -> None:
        """Refuse a list count that :func:`._ply_layout._list_count` refuses."""
        try:
            _list_count(count, prop)
        except ValueError as problem:
            raise file_error(self.label, None, f"{element.name} {row}: {problem}") from None

    def line_of_row(self, index: int, row: int) -> int | None:
        """A binary file has no lines: None (messages name the row)."""
        return None

    def _walked_table(self, element: _Element, starts: np.ndarray, counts: np.ndarray,
                      wanted: set[int]) -> _Table:
        """The wanted columns, gathered from the offsets :meth:`_walk` found."""
        table = _Table()
        list_column = {i: k for k, i in enumerate(_list_indices(element))}
        for i in wanted:
            prop = element.properties[i]
            item = np.dtype(self.order + prop.code)
            if prop.count_code is None:
                table.scalars[i] = _values_at(self.data, starts[:, i], item)
                continue
            row_counts = counts[:, list_column[i]]
            first = starts[:, i] + np.dtype(prop.count_code).itemsize
            offsets = _item_offsets(first, row_counts, item.itemsize)
            table.lists[i] = (row_counts, _values_at(self.data, offsets, item))
        return table


def _rows_table(rows: np.ndarray, element: _Element, wanted: set[int]) -> _Table:
    """The wanted columns of rows read as one structured array (lists of one length)."""
    table = _Table()
    for i in wanted:
        if element.properties[i].count_code is None:
            table.scalars[i] = rows[f"p{i}"]
        else:
            items = rows[f"p{i}"]
            counts = np.full(len(rows), items.shape[1], dtype=np.int64)
            table.lists[i] = (counts, items.reshape(-1))
    return table


def _values_at(data: bytes, offsets: np.ndarray, dtype: np.dtype) -> np.ndarray:
    """``(N,)`` values of ``dtype`` at byte ``offsets`` of ``data``, at any alignment.

    One zero-copy view of ``data`` per alignment, gathered from, instead of an
    index for every byte of every value.
    """
    size = dtype.itemsize
    values = np.empty(len(offsets), dtype=dtype)
    remainder = offsets % size
    for shift in range(size):
        chosen = remainder == shift
        if chosen.any():
            view = np.frombuffer(data, dtype, count=(len(data) - shift) // size, offset=shift)
            values[chosen] = view[offsets[chosen] // size]
    return values
