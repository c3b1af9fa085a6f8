"""Vectorized tokenizing of text lines held in one uint8 buffer.

The readers split a file into lines once, copy the lines of one kind (``v``,
``f``, ...) into a buffer and parse all of them with whole-array numpy steps.
These fast paths only accept plain input (digits, ``.``, ``-``, separators; for
indices also ``/``); every line they do not accept is reported back, and the
reader parses it with plain Python, which is the reference behaviour and the
one that raises errors. So the fast path never needs to explain an error.

Buffers follow one convention: byte 0 is a separator (the blanked keyword of the
first line) and the last byte is ``\\n``, so every token has a separator on
both sides.
"""

from __future__ import annotations

import numpy as np

from ._numtext import decimal_to_float

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


def split_lines(data: bytes) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split text into lines without copying.

    Args:
        data: the file contents; must end with ``b"\\n"``.

    Returns:
        ``(buf, starts, ends)``: ``(B,)`` uint8 read-only view of ``data``, and
        ``(L,)`` int64 start offsets and offsets of the closing ``\\n``.
    """
    buf = np.frombuffer(data, dtype=np.uint8)
    ends = np.flatnonzero(buf == 10)
    starts = np.empty_like(ends)
    if len(ends):
        starts[0] = 0
        starts[1:] = ends[:-1] + 1
    return buf, starts, ends


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
        cuts = np.unique(starts[np.searchsorted(starts, np.arange(0, len(buf), _BLOCK))])
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


def parse_number_lines(buf: np.ndarray, starts: np.ndarray, want: int) -> tuple[np.ndarray, np.ndarray]:
    """The first ``want`` decimal numbers of every line.

    The fast path takes numbers of the form ``[-]digits[.digits][e[+-]digits]``
    separated by blanks or commas (numbers with an exponent go through
    ``float()`` one by one).

    Args:
        buf: ``(S,)`` uint8 lines with their keyword blanked (see module doc).
        starts: ``(L,)`` int64 line starts.
        want: how many numbers to take per line; later ones are ignored.

    Returns:
        ``(values, accepted)``: ``(L, want)`` float64 and ``(L,)`` bool; lines
        not accepted (other characters, too few or malformed numbers) hold
        garbage and must be parsed by the caller.
    """
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


def parse_index_lines(buf: np.ndarray, starts: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The leading integer of every token (``7``, ``-2``, ``7/1/3``, ``7//3``).

    Args:
        buf: ``(S,)`` uint8 lines with their keyword blanked (see module doc).
        starts: ``(L,)`` int64 line starts.

    Returns:
        ``(values, counts, accepted)``: ``(T,)`` int64 leading integer of every
        token in order, ``(L,)`` tokens per line and ``(L,)`` bool; lines not
        accepted (no tokens, other characters, malformed tokens, more than 18
        digits) must be parsed by the caller.
    """
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
