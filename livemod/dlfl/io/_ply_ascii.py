"""PLY ASCII bodies: the line path (one row per line, the OBJ reader's vectorized
parsers) and the token path (any layout, and every error); see :mod:`.ply`."""

from __future__ import annotations

import contextlib
import functools
import itertools
from array import array
from dataclasses import dataclass

import numpy as np

from ..errors import FileFormatError
from ._lines import (
    byte_offsets,
    gather_lines,
    parse_index_lines,
    parse_number_lines,
    token_starts,
)
from ._parallel import map_in_order
from ._ply_layout import (
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
from .source import file_error, lf_line_ends, show_token

# ---------------------------------------------------------------------- ASCII body
#
# Two paths read an element and give the same table. The line path takes the
# layout every exporter writes, one row per line, and parses whole blocks of
# lines with the OBJ reader's vectorized parsers; it never raises, and where
# anything does not fit it declines. The token path reads any layout token by
# token, and is the one that names what is wrong.

# lines per parse: enough to amortise the call, few enough that its
# temporaries stay in the cache (as in the OBJ reader)
_LINES_PER_PASS = 1 << 16
# bytes per pass of the scan for tokens: a cache-sized slice of the body
_BYTES_PER_SCAN = 1 << 20
# below this body size the token path is quicker: the line path's fixed cost
# (tens of numpy calls per element, ~1 ms) outweighs its speed
_LINE_PATH_MIN_BYTES = 1 << 17


@dataclass(frozen=True)
class _Lines:
    """The lines of an ASCII body and the tokens (``body.split()``) on each.

    Attributes:
        buf: ``(B,)`` uint8 view of the body, ending with ``\\n``.
        starts, ends: ``(L,)`` int64 offset of every line and of its ``\\n``.
        ids: ``(N,)`` int64 the lines holding a token, in order (lines of
            blanks hold none: the token path does not see them either).
        first: ``(N,)`` int64 index in ``body.split()`` of each one's first token.
        widths: ``(N,)`` int64 how many tokens each one holds.
    """

    buf: np.ndarray
    starts: np.ndarray
    ends: np.ndarray
    ids: np.ndarray
    first: np.ndarray
    widths: np.ndarray


def _token_lines(body: bytes) -> _Lines:
    """The lines of ``body`` and the tokens on each (see :class:`_Lines`).

    The body is scanned in slices of whole lines, on a few threads: a token
    never spans a newline, so a line's first token is the tokens before it.
    """
    data = body if body.endswith(b"\n") else body + b"\n"
    buf = np.frombuffer(data, dtype=np.uint8)
    cuts = [0]
    while cuts[-1] < len(data):  # after the first newline past the next slice (or the end)
        cuts.append(data.find(b"\n", cuts[-1] + _BYTES_PER_SCAN) + 1 or len(data))
    parts = list(map_in_order(lambda cut: _scan_lines(buf, *cut), itertools.pairwise(cuts)))
    starts, ends, widths = (np.concatenate([part[i] for part in parts]) for i in range(3))
    ids = np.flatnonzero(widths)
    first = np.cumsum(widths) - widths
    return _Lines(buf, starts, ends, ids, first[ids], widths[ids])


def _scan_lines(buf: np.ndarray, start: int, end: int) -> tuple[np.ndarray, ...]:
    """``(starts, ends, widths)``: ``(L,)`` int64 line and ``\\n`` offsets and
    token counts of the whole lines ``buf[start:end]``."""
    part = buf[start:end]
    ends = np.flatnonzero(part == 10)
    starts = np.concatenate([[0], ends[:-1] + 1])
    tokens = token_starts(part)
    widths = np.diff(np.searchsorted(tokens, starts), append=len(tokens))
    return starts + start, ends + start, widths


@dataclass(frozen=True)
class _RowLayout:
    """Where the tokens of an element's row sit on a line holding just that row.

    A row whose list has ``n`` items is ``len(properties) + n`` tokens: the
    scalars before the list at their property index, the list count at
    ``at``, its items after it, then the scalars after the list, ``n`` later.
    """

    element: _Element
    wanted: set[int]
    at: int | None  # the element's one list property; None without a list
    integral: bool  # every property (list items too) of an integer type

    @classmethod
    def of(cls, element: _Element, wanted: set[int]) -> _RowLayout:
        """The layout of ``element`` (which has at most one list)."""
        lists = _list_indices(element)
        integral = all(p.code[0] in "iu" for p in element.properties)
        return cls(element, wanted, lists[0] if lists else None, integral)

    def column(self, i: int, n: int) -> int:
        """The token of scalar property ``i`` on a line whose list has ``n`` items."""
        return i + n if self.at is not None and i > self.at else i

    def needed(self, n: int) -> list[int]:
        """The tokens to convert on a line whose list has ``n`` items: the
        wanted scalars, the list count, and the items of a wanted list."""
        columns = [self.column(i, n) for i in self.wanted if i != self.at]
        if self.at is not None:
            columns.append(self.at)
            if self.at in self.wanted:
                columns += range(self.at + 1, self.at + 1 + n)
        return columns

    def empty_table(self, sizes: np.ndarray) -> _Table:
        """The table to fill for rows whose lists have ``sizes`` (``(n,)`` int64) items."""
        table = _Table()
        for i in self.wanted:
            if i == self.at:
                table.lists[i] = (sizes, np.empty(int(sizes.sum())))
            else:
                table.scalars[i] = np.empty(len(sizes))
        return table

    def fill(self, table: _Table, values: np.ndarray, rows: np.ndarray, n: int,
             offsets: np.ndarray) -> None:
        """Copy rows ``rows`` (``(k,)`` ascending int64, k > 0) of the element,
        whose lists have ``n`` items, from their ``(k, P + n)`` ``values`` into
        ``table``; ``offsets`` is each row's first item in the list's items."""
        for i, column in table.scalars.items():
            column[rows] = values[:, self.column(i, n)]
        if self.at is not None and self.at in table.lists:
            items, lists = table.lists[self.at][1], values[:, self.at + 1 : self.at + 1 + n]
            start = int(offsets[rows[0]])
            if rows[-1] - rows[0] + 1 == len(rows):  # consecutive rows: their items are too
                items[start : start + lists.size] = lists.ravel()
            else:
                items[offsets[rows][:, None] + np.arange(n)] = lists


# One group of rows parsed together: (picked, n, values), rows ``picked``
# ((k,) int64) whose lists have ``n`` items, and their (k, P + n) float64 numbers
_Piece = tuple[np.ndarray, int, np.ndarray]


class _AsciiBody:
    """Reads the elements of an ASCII body one after the other.

    The line path (:meth:`_line_table`) reads an element with at most one
    list whose rows are the next ``count`` lines holding tokens, one row each
    (lines of blanks are passed over, as they hold no token). It parses a few
    thousand lines at a time: an element of integer types first with
    :func:`._lines.parse_index_lines`, and the lines that does not take, or
    every line of any other element, with :func:`._lines.parse_number_lines`
    in groups of one length; the lines neither takes go through
    :func:`_number` and :meth:`_count` token by token, as in the token path.
    Where one of those refuses a needed token, or a list count is not what
    its line's length says, it declines, and the token path reads the element
    and names the problem.

    The token path (:meth:`_token_table`) splits the body into tokens once and
    converts only those of wanted properties and of list counts. An element
    whose rows all have the list counts of its first row is read as columns of
    equally spaced tokens; any other goes row by row.

    Both read from token ``self.t`` and leave it after the element.
    """

    def __init__(self, body: bytes, label: str, first_line: int = 1) -> None:
        self.body, self.t, self.label, self.first_line = body, 0, label, first_line
        self.element_tokens: list[int] = []  # the token each element read starts at
        self._elements: list[_Element] = []
        # float() takes "1_000" and non-ASCII digits: only then check every token
        self.careful = b"_" in body or not body.isascii()

    @functools.cached_property
    def tokens(self) -> list[bytes]:
        """``(T,)`` every token of the body (split only if the token path runs)."""
        return self.body.split()

    @functools.cached_property
    def lines(self) -> _Lines:
        """The body's lines and the tokens on each (scanned on first use)."""
        return _token_lines(self.body)

    def element(self, element: _Element, wanted: set[int]) -> _Table:
        """The wanted columns of ``element``'s rows, which start at token ``self.t``.

        Raises:
            FileFormatError: the rows run past the end of the body, or a list
                count or wanted number is malformed (``file:line: ...``).
        """
        self.element_tokens.append(self.t)
        self._elements.append(element)
        if element.count == 0 or not element.properties:
            return _empty_table(element, wanted)
        table = self._line_table(element, wanted)
        return self._token_table(element, wanted) if table is None else table

    # ------------------------------------------------------------ line path

    def _line_table(self, element: _Element, wanted: set[int]) -> _Table | None:
        """The wanted columns of ``element``'s rows read line by line, or None
        where the line path declines (see the class doc, and a body under
        :data:`_LINE_PATH_MIN_BYTES`); never raises."""
        if len(self.body) < _LINE_PATH_MIN_BYTES:
            return None
        found = self._row_lines(element)
        if found is None:
            return None
        ids, sizes = found
        layout = _RowLayout.of(element, wanted)
        table = layout.empty_table(sizes)
        offsets = np.cumsum(sizes) - sizes
        passes = [np.arange(k, min(k + _LINES_PER_PASS, len(ids)))
                  for k in range(0, len(ids), _LINES_PER_PASS)]
        # numpy lets go of the GIL in the parsers: passes on a few threads
        parsed = map_in_order(lambda rows: self._pass(layout, ids[rows], sizes[rows]), passes)
        for rows, pieces in zip(passes, parsed, strict=True):
            if pieces is None:
                return None  # the passes still running are finished, then dropped
            for picked, n, values in pieces:
                layout.fill(table, values, rows[picked], n, offsets)
        self.t += len(ids) * len(element.properties) + int(sizes.sum())
        return table

    def _row_lines(self, element: _Element) -> tuple[np.ndarray, np.ndarray] | None:
        """The lines of ``element``'s rows, if they are one row each.

        Returns:
            ``(ids, sizes)``: ``(n,)`` int64 the next ``n = count`` lines holding
            tokens, and the number of list items a row on each would have
            (zeros without a list); None when the element has several lists,
            token ``self.t`` does not start a line, fewer lines are left, or a
            line is too short for a row (without a list: not exactly as long).
        """
        lists, lines, count = _list_indices(element), self.lines, element.count
        j = int(np.searchsorted(lines.first, self.t))
        if len(lists) > 1 or j + count > len(lines.ids) or lines.first[j] != self.t:
            return None
        sizes = lines.widths[j : j + count] - len(element.properties)
        if (sizes < 0).any() or (not lists and (sizes != 0).any()):
            return None
        return lines.ids[j : j + count], sizes

    def _pass(self, layout: _RowLayout, ids: np.ndarray, sizes: np.ndarray) -> list[_Piece] | None:
        """The numbers on lines ``ids`` (``(k,)`` int64), rows whose lists have
        ``sizes`` items, as pieces (see :data:`_Piece`; ``picked`` indexes
        ``ids``, and only the :meth:`_RowLayout.needed` columns are meaningful).
        None where a needed token is refused or a list count is not its size."""
        if layout.at is None and not layout.wanted:  # nobody wants it: nothing to convert
            return []
        pieces: list[_Piece] = []
        rest = np.arange(len(ids))
        if layout.integral:
            pieces, rest = self._index_pieces(layout, ids, sizes)
        for n, group in _groups(sizes[rest]):
            values = self._number_values(layout, ids[rest[group]], n)
            if values is None:
                return None
            pieces.append((rest[group], n, values))
        if layout.at is not None and not all((v[:, layout.at] == n).all() for _, n, v in pieces):
            return None
        return pieces

    def _index_pieces(self, layout: _RowLayout, ids: np.ndarray, sizes: np.ndarray,
                      ) -> tuple[list[_Piece], np.ndarray]:
        """:meth:`_pass` for the lines of plain integers ``[-]d+`` (any length of
        list), and the ``(r,)`` int64 indices into ``ids`` of the other lines."""
        # "-0" would lose its sign, and "7/1" is a corner to the parser, not a number
        block, starts, odd = _padded_lines(self.lines, ids, b"-/")
        flat, counts, accepted = parse_index_lines(block, starts)
        accepted &= ~odd & (counts == len(layout.element.properties) + sizes)
        first = np.cumsum(counts) - counts
        taken = np.flatnonzero(accepted)
        pieces = []
        for n, group in _groups(sizes[taken]):
            columns = np.arange(len(layout.element.properties) + n)
            values = flat[first[taken[group], None] + columns].astype(np.float64)
            pieces.append((taken[group], n, values))
        return pieces, np.flatnonzero(~accepted)

    def _number_values(self, layout: _RowLayout, ids: np.ndarray, n: int) -> np.ndarray | None:
        """``(k, P + n)`` float64 numbers of lines ``ids`` (``(k,)`` int64), rows
        whose lists have ``n`` items (see :meth:`_pass`); None where a needed
        token is refused."""
        block, starts, odd = _padded_lines(self.lines, ids, b",")
        values, accepted = parse_number_lines(block, starts, len(layout.element.properties) + n)
        for k in np.flatnonzero(~accepted | odd).tolist():
            if not self._python_row(values[k], int(ids[k]), layout, n):
                return None
        return values

    def _python_row(self, out: np.ndarray, line: int, layout: _RowLayout, n: int) -> bool:
        """Convert the needed tokens of ``line`` into ``out`` (``(P + n,)``) as
        the token path would; False if it would refuse one of them."""
        lines = self.lines
        tokens = bytes(lines.buf[lines.starts[line] : lines.ends[line]]).split()
        try:
            for column in layout.needed(n):
                if column == layout.at:
                    prop = layout.element.properties[column]
                    count = _count_value(tokens[column], self.careful, prop)
                    out[column] = min(count, n + 1)  # other than n is all that counts
                else:
                    out[column] = _number(tokens[column], self.careful)
        except (ValueError, FileFormatError):
            return False
        return True

    # ------------------------------------------------------------ token path

    def _token_table(self, element: _Element, wanted: set[int]) -> _Table:
        """The wanted columns of ``element``'s rows (at least one row and one
        property) read from the tokens; raises as :meth:`element` says."""
        left = len(self.tokens) - self.t
        if element.count > left // len(element.properties):
            if not _list_indices(element):
                raise _ends_inside(self.label, element, left // len(element.properties) + 1,
                                   self._last_line())
            raise _too_many_rows(self.label, element, left, "numbers")
        starts, counts, end = self._walk(element, 1)
        width = end - self.t
        if element.count * width <= left and self._uniform(element, starts[0] - self.t, width):
            table = self._uniform_table(element, starts[0] - self.t, counts[0], width, wanted)
            self.t += element.count * width
            return table
        starts, counts, self.t = self._walk(element, element.count)
        return self._walked_table(element, starts, counts, wanted)

    def _column(self, element: _Element, first: int, width: int) -> np.ndarray:
        """``(n,)`` float64: the token ``first`` of every row, rows ``width`` apart."""
        stop = self.t + element.count * width
        try:
            return _numbers(self.tokens[self.t + first : stop : width], self.careful)
        except _NotANumber as bad:
            raise self._bad_number(element, self.t + first + bad.at * width) from None

    def _uniform(self, element: _Element, offsets: np.ndarray, width: int) -> bool:
        """Whether every row's list counts are the first row's.

        A token that is not a number says no too: the rows may just not be
        ``width`` tokens apart, and the row-by-row walk names the real problem.
        """
        for i in _list_indices(element):
            try:
                counts = self._column(element, int(offsets[i]), width)
            except FileFormatError:
                return False
            if not (counts == counts[0]).all():
                return False
        return True

    def _uniform_table(self, element: _Element, offsets: np.ndarray, first_counts: np.ndarray,
                       width: int, wanted: set[int]) -> _Table:
        """The wanted columns of rows ``width`` tokens wide (token offsets ``offsets``)."""
        table = _Table()
        list_column = {i: k for k, i in enumerate(_list_indices(element))}
        for i in wanted:
            at = int(offsets[i])
            if element.properties[i].count_code is None:
                table.scalars[i] = self._column(element, at, width)
                continue
            count = int(first_counts[list_column[i]])
            items = [self._column(element, at + 1 + k, width) for k in range(count)]
            flat = np.stack(items, axis=1).ravel() if items else np.zeros(0)
            table.lists[i] = (np.full(element.count, count, dtype=np.int64), flat)
        return table

    def _walk(self, element: _Element, rows: int) -> tuple[np.ndarray, np.ndarray, int]:
        """Walk ``rows`` rows from token ``self.t`` (which stays).

        Returns:
            ``(starts, counts, end)``: ``(rows, P)`` int64 token index of every
            property, ``(rows, L)`` int64 count of every list, the end index.
        """
        end, t = len(self.tokens), self.t
        starts, counts = array("q"), array("q")
        for row in range(rows):
            for prop in element.properties:
                starts.append(t)
                if prop.count_code is not None and t < end:
                    count = self._count(t, element, row, prop)
                    counts.append(count)
                    t += count
                t += 1
            if t > end:
                raise _ends_inside(self.label, element, row + 1, self._last_line())
        shape = (rows, -1)
        return np.array(starts, np.int64).reshape(shape), np.array(counts, np.int64).reshape(shape), t

    def _count(self, t: int, element: _Element, row: int, prop: _Property) -> int:
        """The list count at token ``t``, of row ``row``; refuses what is not a whole
        number of at least 0 (``3.0`` is taken, as a whole number)."""
        try:
            count = _count_value(self.tokens[t], self.careful, prop)
        except _NotANumber:
            raise file_error(self.label, self.token_line(t), f"{element.name} {row}: bad "
                             f"number {show_token(self.tokens[t])}") from None
        except ValueError as problem:
            raise file_error(self.label, self.token_line(t),
                             f"{element.name} {row}: {problem}") from None
        # more items than tokens left ends the file inside the element; capped so a
        # count past 2**63 is that error too, not an overflow of the count array
        return min(count, len(self.tokens) + 1)

    def _walked_table(self, element: _Element, starts: np.ndarray, counts: np.ndarray,
                      wanted: set[int]) -> _Table:
        """The wanted columns, gathered from the token indices :meth:`_walk` found."""
        table = _Table()
        list_column = {i: k for k, i in enumerate(_list_indices(element))}
        for i in wanted:
            if element.properties[i].count_code is None:
                table.scalars[i] = self._numbers_at(element, starts[:, i])
                continue
            row_counts = counts[:, list_column[i]]
            offsets = _item_offsets(starts[:, i] + 1, row_counts, 1)
            table.lists[i] = (row_counts, self._numbers_at(element, offsets))
        return table

    def _numbers_at(self, element: _Element, at: np.ndarray) -> np.ndarray:
        """``(N,)`` float64 of the tokens at ``at`` (``(N,)`` int64) of ``element``."""
        indices = at.tolist()
        try:
            return _numbers([self.tokens[k] for k in indices], self.careful)
        except _NotANumber as bad:
            raise self._bad_number(element, indices[bad.at]) from None

    def _bad_number(self, element: _Element, t: int) -> FileFormatError:
        return file_error(self.label, self.token_line(t), f"element '{element.name}': bad "
                          f"number {show_token(self.tokens[t])}")

    def token_line(self, t: int) -> int:
        """The 1-based file line of token ``t``."""
        return self.first_line + int(np.searchsorted(self._newlines, self._token_offsets[t]))

    def _last_line(self) -> int:
        """The file's last line (where a file cut short ends)."""
        ends_with_newline = self.body.endswith((b"\n", b"\r"))
        return self.first_line + len(self._newlines) - int(ends_with_newline)

    def line_of_row(self, index: int, row: int) -> int:
        """The line where row ``row`` of element ``index`` (as read, in order) starts
        (an error path: it walks the element's rows again)."""
        saved, self.t = self.t, self.element_tokens[index]
        try:
            starts, _, _ = self._walk(self._elements[index], row + 1)
        finally:
            self.t = saved
        return self.token_line(int(starts[row, 0]))

    @functools.cached_property
    def _newlines(self) -> np.ndarray:
        """``(L,)`` int64 offsets of the body's line ends (a lone ``\\r`` too)."""
        return byte_offsets(np.frombuffer(lf_line_ends(self.body), dtype=np.uint8), 10)

    @functools.cached_property
    def _token_offsets(self) -> np.ndarray:
        """``(T,)`` int64 offset in the body of every token of :attr:`tokens`."""
        return token_starts(np.frombuffer(self.body, dtype=np.uint8))


def _count_value(token: bytes, careful: bool, prop: _Property) -> int:
    """A list count token as an int.

    Raises:
        _NotANumber: the token is not a number.
        ValueError: a negative or fractional count.
    """
    if not careful:
        with contextlib.suppress(ValueError):
            count = int(token)  # the usual form, and cheaper than float()
            if count >= 0:
                return count
    return _list_count(_number(token, careful), prop)


class _NotANumber(ValueError):
    """Item ``at`` of a list of tokens is not a number."""

    def __init__(self, at: int) -> None:
        super().__init__(at)
        self.at = at


def _numbers(tokens: list[bytes], careful: bool) -> np.ndarray:
    """``(N,)`` float64 of number tokens; ``careful`` checks each (see :func:`_number`).

    Raises:
        _NotANumber: naming the first token that is not a number.
    """
    if not careful:
        try:
            return np.fromiter(map(float, tokens), dtype=np.float64, count=len(tokens))
        except ValueError:
            pass  # find the bad token, and say which it is
    values = np.empty(len(tokens))
    for k, token in enumerate(tokens):
        try:
            values[k] = _number(token, True)
        except _NotANumber:
            raise _NotANumber(k) from None
    return values


def _number(token: bytes, careful: bool) -> float:
    """``float(token)``; refuses what is not a number (with ``careful``, also
    underscores and non-ASCII bytes, which ``float`` would take).

    Raises:
        _NotANumber: the token is not a number.
    """
    try:
        if careful and (b"_" in token or not token.isascii()):
            raise ValueError(token)
        return float(token)
    except ValueError:
        raise _NotANumber(0) from None


def _groups(sizes: np.ndarray) -> list[tuple[int, np.ndarray]]:
    """``(n, rows)`` for each distinct value ``n`` of ``sizes`` (``(N,)`` int64):
    ``rows`` the ``(k,)`` int64 indices, ascending, where it occurs."""
    if len(sizes) == 0:
        return []
    if (sizes == sizes[0]).all():  # one polygon size, or no list: no sort
        return [(int(sizes[0]), np.arange(len(sizes)))]
    order = np.argsort(sizes, kind="stable")
    cuts = np.flatnonzero(np.diff(sizes[order])) + 1
    return [(int(sizes[rows[0]]), rows) for rows in np.split(order, cuts)]


def _padded_lines(lines: _Lines, ids: np.ndarray, odd: bytes,
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lines ``ids`` (``(K,)`` sorted int64, K > 0) copied into one buffer as
    :mod:`._lines` wants it: every line after a blank, the last byte ``\\n``.

    Returns:
        ``(block, starts, flagged)``: ``(S,)`` uint8, ``(K,)`` int64 line
        starts, and ``(K,)`` bool the lines holding a byte of ``odd`` (one a
        parser takes and the token path does not, such as a comma).
    """
    block = _line_bytes(lines, ids)
    lengths = lines.ends[ids] + 1 - lines.starts[ids]
    starts = np.cumsum(lengths) - lengths
    hits = np.zeros(len(block), dtype=bool)
    for byte in odd:
        hits |= block == byte
    flagged = np.zeros(len(ids), dtype=bool)
    flagged[np.searchsorted(starts, np.flatnonzero(hits), side="right") - 1] = True
    # a PLY line starts with its first number: give it the blank the parser needs
    return np.insert(block, starts, np.uint8(32)), starts + np.arange(len(ids)), flagged


def _line_bytes(lines: _Lines, ids: np.ndarray) -> np.ndarray:
    """``(S,)`` uint8 the bytes of lines ``ids`` (``(K,)`` sorted int64, K > 0),
    newlines included, one after the other (a view when they are consecutive)."""
    first, last = int(ids[0]), int(ids[-1])
    block = lines.buf[lines.starts[first] : lines.ends[last] + 1]
    if len(ids) == last - first + 1:
        return block
    lengths = lines.ends[first : last + 1] + 1 - lines.starts[first : last + 1]
    chosen = np.zeros(last - first + 1, dtype=bool)
    chosen[ids - first] = True
    if len(block) > 4 * int(lengths[chosen].sum()):  # a few among many: slice by slice
        return gather_lines(lines.buf, lines.starts, lines.ends, ids)[0]
    return block[np.repeat(chosen, lengths)]  # one mask beats a slice per line
