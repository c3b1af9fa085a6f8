"""Vectorized tokenizing of text lines held in one uint8 buffer.

The readers split a file into lines once, copy the lines of one kind (``v``,
``f``, ...) into a buffer and parse all of them with whole-array numpy steps,
in two tiers: lines in the plain form (``[-]d+[.d+]`` numbers, bare indices)
take the cheapest path, the others a general tokenizer that also knows
exponents, signs, ``v/t/n`` corners and relative indices. Neither accepts
anything else; every line they do not accept is reported back, and the reader
parses it with plain Python, which is the reference behaviour and the one that
raises errors. So the fast paths never need to explain an error.

Buffers follow one convention: byte 0 is a separator (the blanked keyword of the
first line) and the last byte is ``\\n``, so every token has a separator on
both sides.
"""

from __future__ import annotations

import numpy as np

from ._numtext import decimal_to_float
from ._parallel import map_in_order

SEP, DIGIT, DOT, MINUS, SLASH, ODD, EXP, PLUS = range(8)
_INT_POW10 = np.array([10**k for k in range(19)], dtype=np.int64)


def _classes(separators: bytes, extra: dict[int, int]) -> np.ndarray:
    table = np.full(256, ODD, dtype=np.uint8)
    table[list(separators)] = SEP
    table[ord("0") : ord("9") + 1] = DIGIT
    table[ord("-")] = MINUS
    for byte, cls in extra.items():
        table[byte] = cls
    return table


_NUMBER_CLASSES = _classes(
    b" \t\r\n\v\f,", {ord("."): DOT, ord("e"): EXP, ord("E"): EXP, ord("+"): PLUS})
_INDEX_CLASSES = _classes(b" \t\r\n\v\f", {ord("/"): SLASH})


def token_starts(buf: np.ndarray) -> np.ndarray:
    """``(T,)`` int64 offset in ``buf`` (``(B,)`` uint8) of every token, tokens being
    what ``bytes.split()`` gives: runs of bytes other than space, ``\t``, ``\n``,
    ``\v``, ``\f`` and ``\r``."""
    blank = (buf - np.uint8(9)) < 5  # \t \n \v \f \r (arithmetic beats a lookup here)
    blank |= buf == 32
    # a token starts where a blank is followed by anything else, or at 0
    starts = np.flatnonzero(blank[:-1] > blank[1:]) + 1
    if len(buf) and not blank[0]:
        starts = np.concatenate([[0], starts])
    return starts


def split_lines(data: bytes) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split text into lines without copying.

    Args:
        data: the file contents; must end with ``b"\\n"``.

    Returns:
        ``(buf, starts, ends)``: ``(B,)`` uint8 read-only view of ``data``, and
        ``(L,)`` int64 start offsets and offsets of the closing ``\\n``.
    """
    buf = np.frombuffer(data, dtype=np.uint8)
    ends = _newlines(buf)
    starts = np.empty_like(ends)
    if len(ends):
        starts[0] = 0
        starts[1:] = ends[:-1] + 1
    return buf, starts, ends


# bytes per newline search: a comparison's bool temporary that stays in the
# cache (one over a 300 MB file cost 0.8 s, blocks of 1 MB on two threads 0.3 s)
_NEWLINE_BLOCK = 1 << 20


def _newlines(buf: np.ndarray) -> np.ndarray:
    """``(L,)`` int64 offsets of the ``\\n`` bytes of ``buf`` (``(B,)`` uint8), in order."""
    return byte_offsets(buf, 10)


def byte_offsets(buf: np.ndarray, byte: int) -> np.ndarray:
    """``(K,)`` int64 offsets of the bytes equal to ``byte`` in ``buf`` (``(B,)``
    uint8), in order; searched in cache-sized blocks on a few threads."""
    if len(buf) <= _NEWLINE_BLOCK:
        return np.flatnonzero(buf == byte)
    parts = map_in_order(lambda a: np.flatnonzero(buf[a : a + _NEWLINE_BLOCK] == byte) + a,
                         range(0, len(buf), _NEWLINE_BLOCK))
    return np.concatenate(list(parts))


def gather_lines(
    buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, lines: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Copy the chosen lines into one writable buffer.

    Args:
        buf: ``(B,)`` uint8 file bytes.
        starts, ends: ``(L,)`` line start and newline offsets.
        lines: ``(K,)`` sorted indices of the lines to take.

    Returns:
        ``(block, block_starts)``: ``(S,)`` uint8 copy of those lines (newlines
        included) and ``(K,)`` int64 start of each line in it.
    """
    if len(lines) == 0:
        return np.zeros(0, dtype=np.uint8), np.zeros(0, dtype=np.int64)
    lengths = ends[lines] + 1 - starts[lines]
    block_starts = np.zeros(len(lines), dtype=np.int64)
    np.cumsum(lengths[:-1], out=block_starts[1:])
    # consecutive lines are contiguous in the file: copy them as one slice
    breaks = np.flatnonzero(np.diff(lines) != 1) + 1
    first = np.concatenate([[0], breaks])
    last = np.concatenate([breaks - 1, [len(lines) - 1]])
    pieces = [
        buf[a : b + 1]
        for a, b in zip(starts[lines[first]].tolist(), ends[lines[last]].tolist(), strict=True)
    ]
    return np.concatenate(pieces), block_starts


def _runs(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Start and end (exclusive) of each run of True; ``mask[0]``/``mask[-1]`` False."""
    edges = np.flatnonzero(mask[1:] != mask[:-1]) + 1
    return edges[0::2], edges[1::2]


def _owner(starts: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """Index of the segment (line or token) each position falls in."""
    return np.searchsorted(starts, positions, side="right") - 1


_BLOCK = 1 << 20


def _scan_block(buf: np.ndarray, start: int, end: int) -> tuple[np.ndarray, ...]:
    """Positions in ``buf[start:end]`` of bytes other than digits, spaces and
    newlines, and the starts and ends of its digit runs (block of whole lines)."""
    block = buf[start:end]
    is_digit = (block - np.uint8(48)) < 10
    # spaces and newlines are most of the rest and never need a look
    special = ~is_digit
    special &= block != 32
    special &= block != 10
    run_starts, run_ends = _runs(is_digit)
    return np.flatnonzero(special) + start, run_starts + start, run_ends + start


def _run_values(buf: np.ndarray, other: np.ndarray, run_starts: np.ndarray,
                run_ends: np.ndarray) -> np.ndarray:
    """``(R,)`` int64 value of each digit run (saturating at 2**63 - 1).

    ``other`` lists every byte that is neither a digit, a space nor a newline;
    they are blanked for one ``numpy.fromstring`` call and then restored.
    """
    if len(run_starts) == 0:
        return np.zeros(0, dtype=np.int64)
    saved = buf[other]
    buf[other] = 32
    try:
        values = np.fromstring(buf.tobytes(), dtype=np.int64, sep=" ")
    finally:
        buf[other] = saved
    if len(values) == len(run_starts):
        return values
    # never expected; stay correct if numpy's parser ever disagrees on run count
    text = buf.tobytes()
    return np.array(
        [min(int(text[a:b]), 2**63 - 1)
         for a, b in zip(run_starts.tolist(), run_ends.tolist(), strict=True)],
        dtype=np.int64,
    )


def pass_starts(starts: np.ndarray, total: int, size: int) -> np.ndarray:
    """Where to cut records into passes of about ``size`` units each.

    Args:
        starts: ``(N,)`` sorted int64 offset of each record (a line's first
            byte, a face's first corner), the first one 0.
        total: the offset where the last record ends.
        size: the units a pass should hold.

    Returns:
        ``(P,)`` int64 ascending, distinct indices into ``starts`` of the records
        that begin a pass: record 0, then the first record starting at or after
        each multiple of ``size``. A record longer than ``size`` (a 2 MB line, a
        face of 100,000 corners) is a pass of its own, and no pass is empty,
        wherever the multiples fall (at the last record, or past its start).
    """
    at = np.searchsorted(starts, np.arange(0, total, size))
    return _distinct_sorted(at[at < len(starts)])


def _distinct_sorted(values: np.ndarray) -> np.ndarray:
    """The distinct values of a sorted array (``np.unique`` costs ~60 ms on its
    first call in a process, a tenth of a small file's load)."""
    if len(values) < 2:
        return values
    return values[np.concatenate([[True], values[1:] != values[:-1]])]


class _Scan:
    """Digit runs and the classes of the other bytes of a writable line buffer.

    Args:
        buf: ``(S,)`` uint8 lines (see module doc).
        starts: ``(L,)`` int64 line starts; the byte-level passes run over blocks
            of whole lines of about 1 MB, which stay in the CPU cache.
        classes: ``(256,)`` uint8 byte class table.
    """

    def __init__(self, buf: np.ndarray, starts: np.ndarray, classes: np.ndarray) -> None:
        self.buf = buf
        self.classes = classes
        cuts = starts[pass_starts(starts, len(buf), _BLOCK)]
        bounds = [*cuts.tolist(), len(buf)] if len(cuts) else [0, len(buf)]
        parts = [_scan_block(buf, a, b) for a, b in zip(bounds[:-1], bounds[1:], strict=True)]
        self.other, self.run_starts, self.run_ends = (
            np.concatenate([p[i] for p in parts]) if parts else np.zeros(0, np.int64)
            for i in range(3)
        )
        self.other_cls = classes[buf[self.other]]

    def cls(self, positions: np.ndarray) -> np.ndarray:
        """Class of the bytes at ``positions``; positions past either end read as
        the separator that ends the buffer there (``e`` two bytes before the end
        of a truncated file looks two bytes ahead)."""
        inside = np.clip(positions, 0, len(self.buf) - 1)
        return self.classes[self.buf[inside]]

    def positions(self, cls: int) -> np.ndarray:
        return self.other[self.other_cls == cls]

    def values(self) -> np.ndarray:
        return _run_values(self.buf, self.other, self.run_starts, self.run_ends)


def _lines_of(starts: np.ndarray, positions: np.ndarray) -> np.ndarray:
    """``(L,)`` bool: lines containing any of ``positions``."""
    flagged = np.zeros(len(starts), dtype=bool)
    flagged[_owner(starts, positions)] = True
    return flagged


def _per_line(starts: np.ndarray, token_starts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``(first token index, token count)`` of each line, both ``(L,)`` int64."""
    first = np.searchsorted(token_starts, starts)
    counts = np.diff(np.append(first, len(token_starts)))
    return first, counts


def _general_number_lines(buf: np.ndarray, starts: np.ndarray, want: int,
                          ) -> tuple[np.ndarray, np.ndarray]:
    """:func:`parse_number_lines` for any line: numbers with an exponent too
    (through ``float()`` one by one), with the same arguments and results."""
    num_lines = len(starts)
    scan = _Scan(buf, starts, _NUMBER_CLASSES)
    rs, re = scan.run_starts, scan.run_ends
    if num_lines == 0 or len(rs) == 0:
        return np.zeros((num_lines, want)), np.zeros(num_lines, dtype=bool)
    bad = [scan.positions(ODD), *_misplaced_signs(scan)]
    before = scan.cls(rs - 1)
    is_frac = before == DOT
    is_exp = (before == EXP) | ((before == MINUS) | (before == PLUS)) & (
        scan.cls(np.maximum(rs - 2, 0)) == EXP)
    after = scan.cls(re)
    is_int = ~is_frac & ~is_exp
    allowed = np.where(is_int, (after == SEP) | (after == DOT) | (after == EXP),
                       np.where(is_frac, (after == SEP) | (after == EXP), after == SEP))
    bad.append(rs[~allowed])
    rejected = _lines_of(starts, np.concatenate(bad))
    lead = np.flatnonzero(is_int)  # every number starts with its integer run
    if len(lead) == 0:  # only numbers like ".5": the caller parses every line
        return np.zeros((num_lines, want)), np.zeros(num_lines, dtype=bool)
    first, counts = _per_line(starts, rs[lead])
    rejected |= counts < want
    values = _numbers(scan, lead, is_frac)
    pick = np.minimum(first[:, None] + np.arange(want), len(lead) - 1)
    picked = values[pick]
    rejected |= ~np.isfinite(picked).all(axis=1)  # "1e999": let the caller name the line
    return picked, ~rejected


def _misplaced_signs(scan: _Scan) -> list[np.ndarray]:
    """Positions of ``-``, ``+``, ``.``, ``e`` not inside ``[-]d+[.d+][e[+-]d+]``."""
    minus, plus = scan.positions(MINUS), scan.positions(PLUS)
    dot, exp = scan.positions(DOT), scan.positions(EXP)
    before_minus = scan.cls(minus - 1)
    after_exp = scan.cls(exp + 1)
    signed = (after_exp == MINUS) | (after_exp == PLUS)
    return [
        minus[((before_minus != SEP) & (before_minus != EXP)) | (scan.cls(minus + 1) != DIGIT)],
        plus[(scan.cls(plus - 1) != EXP) | (scan.cls(plus + 1) != DIGIT)],
        dot[(scan.cls(dot - 1) != DIGIT) | (scan.cls(dot + 1) != DIGIT)],
        exp[(scan.cls(exp - 1) != DIGIT)
            | ~((after_exp == DIGIT) | signed & (scan.cls(exp + 2) == DIGIT))],
    ]


def _numbers(scan: _Scan, lead: np.ndarray, is_frac: np.ndarray) -> np.ndarray:
    """``(T,)`` float64 value of each number ``[-]int[.frac]`` led by run ``lead``."""
    rs, re = scan.run_starts, scan.run_ends
    run_values = scan.values()
    int_val, int_len = run_values[lead], (re - rs)[lead]
    nxt = np.minimum(lead + 1, len(rs) - 1)
    # the fraction belongs to this number only if just one '.' separates them
    has_frac = is_frac[nxt] & (nxt != lead) & (rs[nxt] == re[lead] + 1)
    frac_val = np.where(has_frac, run_values[nxt], 0)
    frac_len = np.where(has_frac, (re - rs)[nxt], 0)
    # below 10**18 a run value is exact (fromstring saturates at 2**63 - 1)
    fits = (int_val < 10**18) & (frac_val < 10**18) & (frac_len <= 22)
    fits &= (int_val == 0) | (int_len + frac_len <= 18)
    scale = _INT_POW10[np.minimum(frac_len, 18)]
    mantissa = np.where(fits, np.where(int_val == 0, 0, int_val * scale) + frac_val, 0)
    values, decided = decimal_to_float(mantissa, np.minimum(frac_len, 22))
    values = np.where(scan.buf[rs[lead] - 1] == ord("-"), -values, values)
    mantissa_end = np.where(has_frac, re[nxt], re[lead])
    has_exp = scan.cls(mantissa_end) == EXP  # rare: Python parses these numbers
    exp_run = np.minimum(lead + 1 + has_frac, len(rs) - 1)
    end = np.where(has_exp, re[exp_run], mantissa_end)
    for i in np.flatnonzero(~(fits & decided) | has_exp).tolist():
        start = rs[lead[i]] - int(scan.buf[rs[lead[i]] - 1] == ord("-"))
        values[i] = _python_float(scan.buf[start : end[i]].tobytes())
    return values


def _python_float(text: bytes) -> float:
    """``float(text)``; NaN for text that is not a number (its line is rejected)."""
    try:
        return float(text)
    except ValueError:
        return float("nan")


def _general_index_lines(buf: np.ndarray, starts: np.ndarray,
                         ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`parse_index_lines` for any line: signed indices and ``v/t/n``
    corners too, with the same arguments and results."""
    num_lines = len(starts)
    scan = _Scan(buf, starts, _INDEX_CLASSES)
    rs, re = scan.run_starts, scan.run_ends
    if num_lines == 0 or len(rs) == 0:
        return np.zeros(0, np.int64), np.zeros(num_lines, np.int64), np.zeros(num_lines, bool)
    bad = [scan.positions(ODD)]
    minus, slash = scan.positions(MINUS), scan.positions(SLASH)
    before_minus = scan.cls(minus - 1)
    bad.append(minus[((before_minus != SEP) & (before_minus != SLASH))
                     | (scan.cls(minus + 1) != DIGIT)])
    before_slash = scan.cls(slash - 1)
    bad.append(slash[(before_slash != DIGIT) & (before_slash != SLASH)])
    before = scan.cls(rs - 1)
    negative = before == MINUS
    lead = (before == SEP) | negative & (scan.cls(np.maximum(rs - 2, 0)) == SEP)
    after = scan.cls(re)
    bad.append(rs[lead & (((after != SEP) & (after != SLASH)) | (re - rs > 18))])
    rejected = _lines_of(starts, np.concatenate(bad))
    lead_runs = np.flatnonzero(lead)
    _, counts = _per_line(starts, rs[lead_runs])
    rejected |= counts == 0
    values = scan.values()[lead_runs]
    return np.where(negative[lead_runs], -values, values), counts, ~rejected


# ------------------------------------------------------------- plain lines
#
# Nearly every line of a large file is plain: numbers ``[-]d+[.d+]`` or bare
# indices between blanks. Those need no tokenizer: a number is one run of
# digits and points, with the point dropped one digit run, and one
# ``numpy.fromstring`` reads every mantissa of a block. Only the few bytes that
# are neither digits, points, spaces nor newlines are looked at one by one
# (their classes and neighbours). Lines that are not plain go to the general
# tokenizer above, in a block of their own.


class _PlainScan:
    """Number tokens of a block, and the bytes that may break the plain form.

    Args:
        buf: ``(S,)`` uint8 lines (see module doc).
        starts: ``(L,)`` int64 line starts.
        classes: ``(256,)`` byte class table (for the special bytes only).

    Attributes:
        is_digit, is_dot: ``(S,)`` bool, the digits and the points.
        ts, te: ``(T,)`` int64 start and end (exclusive) of every run of digits
            and points (a number without its sign).
        per_line: ``(L,)`` int64 tokens per line.
        special, special_cls: positions and classes of the bytes that are not
            digits, points, spaces or newlines.
        dots: positions of the points; ``has_point`` and ``point``: ``(T,)``
            whether a token has one and where its last one is.
        two_points: ``(T,)`` bool, tokens with more than one point.
    """

    def __init__(self, buf: np.ndarray, starts: np.ndarray, classes: np.ndarray) -> None:
        self.is_digit = (buf - np.uint8(48)) < 10
        self.is_dot = is_dot = buf == 46
        numeric = self.is_digit | is_dot
        self.ts, self.te = _runs(numeric)
        _, self.per_line = _per_line(starts, self.ts)
        self.special = _special_bytes(buf, numeric)
        self.special_cls = classes[buf[self.special]]
        self.dots = np.flatnonzero(is_dot)
        self.has_point, self.point, self.two_points = _points(self.dots, self.ts, self.te)

    def flagged(self, starts: np.ndarray, bad_bytes: list[np.ndarray],
                bad_tokens: np.ndarray) -> np.ndarray:
        """``(L,)`` bool: lines holding one of ``bad_bytes`` (positions) or a token
        flagged in ``bad_tokens`` (``(T,)`` bool)."""
        flagged = _lines_of(starts, np.concatenate(bad_bytes))
        flagged[_owner(starts, self.ts[bad_tokens])] = True
        return flagged


def _special_bytes(buf: np.ndarray, numeric: np.ndarray) -> np.ndarray:
    """Positions of the bytes of ``buf`` that are neither ``numeric`` (``(S,)``
    bool), blanks nor newlines: the only ones the plain paths look at."""
    odd = ~numeric
    odd &= buf != 32
    odd &= buf != 10
    return np.flatnonzero(odd)


def _points(dots: np.ndarray, ts: np.ndarray, te: np.ndarray,
            ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Which tokens ``[ts, te)`` hold one of the sorted ``dots``, where the last one
    is, and which hold two or more: three ``(T,)`` arrays."""
    if len(dots) == len(ts) and (dots > ts).all() and (dots < te).all():
        # a point in every token, as most writers give: no search needed
        return np.ones(len(ts), dtype=bool), dots, np.zeros(len(ts), dtype=bool)
    at = np.searchsorted(dots, te) - 1  # the last point before a token's end
    before = dots[np.maximum(at - 1, 0)] if len(dots) else ts
    point = dots[np.maximum(at, 0)] if len(dots) else ts
    has_point = (at >= 0) & (point > ts)
    return has_point, point, has_point & (at >= 1) & (before > ts)


def _lines_block(buf: np.ndarray, starts: np.ndarray, lines: np.ndarray,
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Lines ``lines`` of a block (see module doc) as a block of their own."""
    ends = np.append(starts[1:], len(buf)) - 1
    return gather_lines(buf, starts, ends, lines)


def parse_number_lines(buf: np.ndarray, starts: np.ndarray, want: int,
                       ) -> tuple[np.ndarray, np.ndarray]:
    """The first ``want`` decimal numbers of every line.

    Numbers of the form ``[-]digits[.digits][e[+-]digits]`` separated by blanks
    or commas. Lines of exactly ``want`` numbers without exponent take the
    plain path; the others the general tokenizer (numbers with an exponent go
    through ``float()`` one by one there).

    Args:
        buf: ``(S,)`` uint8 lines with their keyword blanked (see module doc);
            its bytes are overwritten while parsing.
        starts: ``(L,)`` int64 line starts.
        want: how many numbers to take per line; later ones are ignored.

    Returns:
        ``(values, accepted)``: ``(L, want)`` float64 and ``(L,)`` bool; lines
        not accepted (other characters, too few or malformed numbers) hold
        garbage and must be parsed by the caller.
    """
    values = np.zeros((len(starts), want))
    scan = _PlainScan(buf, starts, _NUMBER_CLASSES)
    plain = _plain_number_lines(buf, scan, starts, want)
    rest = np.flatnonzero(~plain)
    if len(rest):  # copied out first: the plain path blanks them in buf
        block, block_starts = _lines_block(buf, starts, rest)
    if len(rest) < len(starts):
        values[plain] = _plain_numbers(buf, scan, starts, plain).reshape(-1, want)
    if len(rest):
        values[rest], plain[rest] = _general_number_lines(block, block_starts, want)
    # a 309-digit number is inf: the caller's parser names the line
    plain &= np.isfinite(values).all(axis=1)
    return values, plain


def _plain_number_lines(buf: np.ndarray, scan: _PlainScan, starts: np.ndarray,
                        want: int) -> np.ndarray:
    """``(L,)`` bool: the lines of exactly ``want`` numbers ``[-]d+[.d+]``, blank-
    or comma-separated."""
    special, cls, dots, is_digit = scan.special, scan.special_cls, scan.dots, scan.is_digit
    minus = special[cls == MINUS]
    bad = [
        special[(cls != SEP) & (cls != MINUS)],
        minus[(_NUMBER_CLASSES[buf[minus - 1]] != SEP) | ~is_digit[minus + 1]],
        dots[~is_digit[dots - 1] | ~is_digit[dots + 1]],
    ]
    return ~scan.flagged(starts, bad, scan.two_points) & (scan.per_line == want)


def _plain_numbers(buf: np.ndarray, scan: _PlainScan, starts: np.ndarray,
                   plain: np.ndarray) -> np.ndarray:
    """``(T,)`` float64 value of every token on the ``plain`` lines (``(L,)`` bool).

    Blanks the signs, the separators and the other lines in ``buf``: fromstring
    then reads one digit run per number once the points are dropped.
    """
    ts, te, has_point, point = scan.ts, scan.te, scan.has_point, scan.point
    if not plain.all():
        kept = np.repeat(plain, scan.per_line)
        ts, te, has_point, point = ts[kept], te[kept], has_point[kept], point[kept]
        _blank_lines(buf, starts, ~plain)
    frac_len = np.where(has_point, te - 1 - point, 0)
    negative = buf[ts - 1] == ord("-")
    buf[scan.special] = 32
    mantissa = np.fromstring(buf[~scan.is_dot].tobytes(), dtype=np.int64, sep=" ")
    values, decided = decimal_to_float(np.minimum(mantissa, 10**18), np.minimum(frac_len, 22))
    # long (or saturated) mantissas and near-halfway cases: Python decides
    for i in np.flatnonzero(~decided | (mantissa >= 10**18) | (frac_len > 22)).tolist():
        values[i] = float(buf[ts[i] : te[i]].tobytes())
    return np.negative(values, out=values, where=negative)


def _blank_lines(buf: np.ndarray, starts: np.ndarray, lines: np.ndarray) -> None:
    """Overwrite the lines flagged in ``lines`` (``(L,)`` bool) with blanks."""
    chosen = np.flatnonzero(lines)
    if len(chosen) > 1000:  # many: one mask over the block beats a loop
        buf[np.repeat(lines, np.diff(np.append(starts, len(buf))))] = 32
        return
    ends = np.append(starts[1:], len(buf))
    for a, b in zip(starts[chosen].tolist(), ends[chosen].tolist(), strict=True):
        buf[a:b] = 32


def parse_index_lines(buf: np.ndarray, starts: np.ndarray, *, slashes: bool = True,
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The leading integer of every token (``7``, ``-2``, ``7/1/3``, ``7//3``).

    Lines of bare non-negative indices take the plain path, the others the
    general tokenizer.

    Args:
        buf: ``(S,)`` uint8 lines with their keyword blanked (see module doc).
        starts: ``(L,)`` int64 line starts.
        slashes: accept ``v/t/n`` tokens (OBJ's corners); False rejects every
            line holding a ``/`` (for formats whose tokens are bare integers).

    Returns:
        ``(values, counts, accepted)``: ``(T,)`` int64 leading integer of every
        token in order, ``(L,)`` tokens per line and ``(L,)`` bool; lines not
        accepted (no tokens, other characters, malformed tokens, more than 18
        digits) must be parsed by the caller.
    """
    is_digit = (buf - np.uint8(48)) < 10
    special = _special_bytes(buf, is_digit)
    token_starts = np.flatnonzero(is_digit[1:] > is_digit[:-1]) + 1
    _, per_line = _per_line(starts, token_starts)
    plain = ~_lines_of(starts, special[_INDEX_CLASSES[buf[special]] != SEP]) & (per_line > 0)
    if plain.all():  # digits and blanks only: numpy reads the block as it is
        values = np.fromstring(buf.tobytes(), dtype=np.int64, sep=" ")
        if not (values >= 10**18).any():  # none (saturated) beyond the general path
            return values, per_line, plain
    values, counts, accepted = _merge_index_lines(buf, starts, plain, per_line)
    if not slashes:  # a plain line never holds one: only the others are looked at
        accepted &= ~_lines_of(starts, special[buf[special] == ord("/")])
    return values, counts, accepted


def _merge_index_lines(buf: np.ndarray, starts: np.ndarray, plain: np.ndarray,
                       per_line: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`parse_index_lines` of a block with lines that are not plain: the plain
    ones and the others parsed in blocks of their own, merged in line order."""
    plain_lines = np.flatnonzero(plain)
    block, _ = _lines_block(buf, starts, plain_lines)
    plain_values = np.fromstring(block.tobytes(), dtype=np.int64, sep=" ")
    huge = plain_values >= 10**18  # (saturated) beyond what the general path takes
    if huge.any():
        plain = plain.copy()
        plain[np.repeat(plain_lines, per_line[plain_lines])[huge]] = False
        return _merge_index_lines(buf, starts, plain, per_line)
    counts = np.where(plain, per_line, 0)
    accepted = plain.copy()
    rest = np.flatnonzero(~plain)
    block, block_starts = _lines_block(buf, starts, rest)
    rest_values, counts[rest], accepted[rest] = _general_index_lines(block, block_starts)
    values = np.empty(int(counts.sum()), dtype=np.int64)
    in_plain = np.repeat(plain, counts)
    values[in_plain] = plain_values
    values[~in_plain] = rest_values
    return values, counts, accepted


# ------------------------------------------------------------- digit runs


def leading_uints(buf: np.ndarray, at: np.ndarray, max_digits: int = 18,
                  ) -> tuple[np.ndarray, np.ndarray]:
    """The runs of decimal digits that start at given offsets, without a tokenizer.

    For records whose first field is all a reader needs (``.dlfl``'s ``fv``
    lines): each run is read from a window of ``max_digits + 1`` bytes.

    Args:
        buf: ``(B,)`` uint8 text.
        at: ``(N,)`` int64 offsets into ``buf``.
        max_digits: longest run read (at most 18, so that values fit int64).

    Returns:
        ``(values, lengths)``: ``(N,)`` int64 value and ``(N,)`` int64 length of
        each run; length 0 (value 0) where the byte at the offset is not a digit,
        the run is longer than ``max_digits``, or the window would pass the end
        of ``buf`` (the caller parses those itself). The byte at
        ``at + lengths`` ends each run.
    """
    width = max_digits + 1
    if len(buf) < width or len(at) == 0:
        return np.zeros(len(at), dtype=np.int64), np.zeros(len(at), dtype=np.int64)
    near_end = at > len(buf) - width
    # one gather of whole windows (a view of every window of buf): no index per byte
    rows = np.lib.stride_tricks.sliding_window_view(buf, width)[np.where(near_end, 0, at)]
    digits = rows - np.uint8(48)  # non-digits wrap to 10 and above
    lengths = np.argmax(digits > 9, axis=1)  # the first non-digit; 0 when there is none
    lengths[near_end] = 0
    values = np.zeros(len(at), dtype=np.int64)
    for j in range(int(lengths.max())):
        values = np.where(lengths > j, values * 10 + digits[:, j], values)
    return values, lengths.astype(np.int64)
