"""Vectorized conversion between numbers and ASCII text, exact both ways.

Python's ``float()``/``repr`` and numpy's ``fromstring``/``loadtxt`` cost about
0.5 us per float here, too slow for a million-vertex OBJ. These routines do the
same work with whole-array numpy operations:

* :func:`format_floats` writes each float64 as a decimal that parses back to the
  same bits (15 significant digits when they suffice, else 16, else 17), in
  positional notation; values outside ``[1e-6, 1e15)`` fall back to ``repr``.
* :func:`format_rounded` writes values rounded to a number of decimals, as
  :func:`format_floats` writes the rounded value, from the integer count of
  the last decimal.
* :func:`format_uints` writes non-negative integers.
* :func:`decimal_to_float` turns (mantissa, fraction length) pairs into the
  correctly rounded float64, flagging the rare cases it cannot decide so the
  caller can use ``float()`` on them.

Text is handled as ``(N, W)`` uint8 matrices where 0 marks padding; callers
concatenate columns into lines and drop the zeros in one pass.
"""

from __future__ import annotations

import numpy as np

_POW10 = np.array([10.0**k for k in range(23)])  # exact in float64 up to 1e22
_INT_POW10 = np.array([10**k for k in range(19)], dtype=np.int64)


# ----------------------------------------------------------------- formatting
#
# Digits are written four at a time: a 4-digit chunk indexes a table of 10,000
# uint32 holding its four ASCII bytes, so one gather writes four characters.
# The tables come in variants that leave leading or trailing '0' characters as
# 0 bytes (padding): that is how integers lose their leading zeros and
# fractions their trailing zeros without any per-byte masking.


def _chunk_tables() -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Four ``(10000,)`` uint32 tables: the four ASCII bytes of every chunk ``i``.

    In order: every digit (42 is ``0042``); leading zeros as padding (42 is two
    0 bytes then ``42``, and 0 is all padding); the same but 0 written ``0``
    (the units chunk of an integer); trailing zeros as padding (1200 is ``12``
    then two 0 bytes). Whole-array steps: a Python loop over the 40,000
    entries took 70 ms of every import.
    """
    i = np.arange(10000, dtype=np.int64)[:, None]
    place = np.array([1000, 100, 10, 1], dtype=np.int64)
    digits = (48 + i // place % 10).astype(np.uint8)
    # a digit stays when a non-zero digit comes at or before it (lead), at or after it (trail)
    lead = np.where(i >= place, digits, 0).astype(np.uint8)
    trail = np.where(i % (10 * place) != 0, digits, 0).astype(np.uint8)
    units = lead.copy()
    units[0, 3] = ord("0")
    return (digits.view(np.uint32).ravel(), lead.view(np.uint32).ravel(),
            units.view(np.uint32).ravel(), trail.view(np.uint32).ravel())


_FULL, _LEAD, _UNITS, _TRAIL = _chunk_tables()
# index ``chunk + 10000 * flag``: flag 0 picks the padded variant, 1 every digit
_LEAD_OR_FULL = np.concatenate([_LEAD, _FULL])
_UNITS_OR_FULL = np.concatenate([_UNITS, _FULL])  # the last chunk: 0 is written "0"
_TRAIL_OR_FULL = np.concatenate([_TRAIL, _FULL])


def _chunks(v: np.ndarray, count: int) -> list[np.ndarray]:
    """The ``count`` 4-digit chunks of non-negative int64 ``v``, most significant first.

    Floor division by a scalar, which numpy turns into a multiplication, rather
    than ``divmod``, which is an order of magnitude slower on int64.
    """
    parts = []
    rest = v
    for _ in range(count - 1):
        high = rest // 10000
        parts.append(rest - high * 10000)
        rest = high
    parts.append(rest)
    return parts[::-1]


def _integer_text(v: np.ndarray, width: int) -> np.ndarray:
    """``(N, width)`` uint8 digits of non-negative int64 ``v < 10**width``,
    right-aligned, leading zeros as padding; 0 is written ``0``."""
    count = -(-width // 4)
    packed = np.empty((len(v), count), dtype=np.uint32)
    started = np.zeros(len(v), dtype=bool)  # a nonzero chunk came before
    for i, chunk in enumerate(_chunks(v, count)):
        table = _UNITS_OR_FULL if i == count - 1 else _LEAD_OR_FULL
        packed[:, i] = table[chunk + started * 10000]
        started |= chunk != 0
    return packed.view(np.uint8)[:, 4 * count - width :]


def _fraction_text(chunks: list[np.ndarray]) -> np.ndarray:
    """``(N, 4 * len(chunks))`` uint8 fraction digits from 4-digit chunks (most
    significant first), trailing zeros as padding; all zero is all padding."""
    packed = np.empty((len(chunks[0]), len(chunks)), dtype=np.uint32)
    later = np.zeros(len(chunks[0]), dtype=bool)  # a nonzero chunk follows
    for i in range(len(chunks) - 1, -1, -1):
        packed[:, i] = _TRAIL_OR_FULL[chunks[i] + later * 10000]
        later |= chunks[i] != 0
    return packed.view(np.uint8)


def format_uints(values: np.ndarray) -> np.ndarray:
    """Decimal digits of non-negative integers, right-aligned.

    Args:
        values: ``(N,)`` integers, ``0 <= v < 10**16``.

    Returns:
        ``(N, W)`` uint8 ASCII digits, left-padded with 0 bytes, where ``W`` is
        the number of digits of the largest value.
    """
    v = np.asarray(values, dtype=np.int64)
    width = len(str(int(v.max()))) if len(v) else 1
    return _integer_text(v, width)


def format_floats(values: np.ndarray) -> np.ndarray:
    """Decimal text of float64 values that parses back to the same bits.

    Args:
        values: ``(N,)`` float64.

    Returns:
        ``(N, W)`` uint8 ASCII with 0 bytes as padding (remove them to get the
        text). ``0.0`` is written ``0``; integral values have no decimal point.
    """
    x = np.asarray(values, dtype=np.float64).ravel()
    digits, exp10, fast = _shortest_digits(np.abs(x))
    out = _positional(digits, exp10, x < 0)  # rows not fast hold a placeholder
    slow = np.flatnonzero(~fast)
    if len(slow) == 0:
        return out
    plain_zero = (x[slow] == 0.0) & ~np.signbit(x[slow])  # -0.0 goes through repr
    spelled = slow[~plain_zero]
    if len(spelled):
        out = np.concatenate([out, np.zeros((len(x), max(24 - out.shape[1], 0)), np.uint8)], 1)
    out[slow] = 0
    out[slow[plain_zero], 0] = ord("0")
    for i in spelled.tolist():
        text = repr(float(x[i])).encode()
        out[i, : len(text)] = np.frombuffer(text, dtype=np.uint8)
    return out


def format_rounded(values: np.ndarray, decimals: int) -> np.ndarray:
    """Decimal text of float64 values rounded to ``decimals`` places.

    The same text as ``format_floats(np.round(values, decimals) + 0.0)`` (so
    ``-0.0`` and values that round to zero are written ``0``), several times
    cheaper: the rounded value is an integer count of ``10**-decimals``, and
    its digits are written straight from that integer (for a value ``k /
    10**decimals`` of at most 14 digits the shortest text that parses back is
    those digits).

    Args:
        values: ``(N,)`` float64.
        decimals: ``0 <= decimals <= 6`` (format_floats spells smaller values
            with an exponent).

    Returns:
        ``(N, W)`` uint8 ASCII with 0 bytes as padding, as :func:`format_floats`.
    """
    x = np.asarray(values, dtype=np.float64).ravel()
    limit = 10.0 ** (14 - decimals)
    fixed = np.abs(x) < limit  # False for NaN and infinities too
    count = np.rint(np.where(fixed, x, 0.0) * 10.0**decimals).astype(np.int64)
    out = _fixed_point(np.abs(count), decimals, count < 0)
    others = np.flatnonzero(~fixed)
    if len(others) == 0:
        return out
    with np.errstate(over="ignore", invalid="ignore"):  # np.round's inf near the top
        spelled = format_floats(np.round(x[others], decimals) + 0.0)
    width = max(out.shape[1], spelled.shape[1])
    out = np.pad(out, ((0, 0), (0, width - out.shape[1])))
    out[others] = np.pad(spelled, ((0, 0), (0, width - spelled.shape[1])))
    return out


def _fixed_point(count: np.ndarray, decimals: int, negative: np.ndarray) -> np.ndarray:
    """``(N, W)`` uint8 text of ``±count * 10**-decimals`` (``(N,)`` int64
    ``count >= 0``): sign, integer digits (0 written ``0``), and a point and
    the fraction digits without trailing zeros unless the fraction is zero."""
    scale = 10**decimals
    whole = count // scale
    frac = count - whole * scale
    whole_width = len(str(int(whole.max()))) if len(count) else 1
    chunks = -(-decimals // 4)
    out = np.empty((len(count), 2 + whole_width + decimals), dtype=np.uint8)
    out[:, 0] = np.where(negative, ord("-"), 0)
    out[:, 1 : 1 + whole_width] = _integer_text(whole, whole_width)
    out[:, 1 + whole_width] = np.where(frac != 0, ord("."), 0)
    if decimals:  # the fraction left-aligned in whole 4-digit chunks, then cut
        padded = frac * 10 ** (4 * chunks - decimals)
        out[:, 2 + whole_width :] = _fraction_text(_chunks(padded, chunks))[:, :decimals]
    return out


def _shortest_digits(ax: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """17 significant digits ``D`` and exponent of each positive value.

    Returns ``(D, exp10, ok)``: ``ax == D * 10**(exp10 - 16)`` to the bit when
    parsed, with ``D`` in ``[1e16, 1e17)`` carrying trailing zeros when 15 or 16
    digits already round-trip; ``ok`` is False where the fast path does not
    apply (zero, non-finite, outside ``[1e-6, 1e15)``), and there ``D`` is
    ``1e16`` and ``exp10`` 0, a placeholder in range.
    """
    ok = np.isfinite(ax) & (ax >= 1e-6) & (ax < 1e15)
    safe = np.where(ok, ax, 1.0)
    # floor(e2 * log10 2) from the binary exponent: floor(log10) or one less
    # (numpy's log10 costs ~35 ns a value here)
    e2 = (safe.view(np.int64) >> 52) - 1023
    k = np.minimum(16 - ((e2 * 78913) >> 18), 22)
    scaled = safe * _POW10[k]
    k -= scaled >= 1e17
    d17 = _round_product(safe, _POW10[k])
    ok &= (d17 >= 10**16) & (d17 < 10**17)
    c15 = (d17 + 50) // 100
    c16 = (d17 + 5) // 10
    ok15 = c15.astype(np.float64) / _POW10[k - 2] == safe  # k >= 2 below 1e15
    ok16 = (c16 < 2**53) & (c16.astype(np.float64) / _POW10[k - 1] == safe)
    digits = np.where(ok15, c15 * 100, np.where(ok16, c16 * 10, d17))
    carry = digits >= 10**17  # rounding 9.99.. up to 10.0
    digits = np.where(carry, digits // 10, digits)
    exp10 = 16 - k + carry
    ok &= exp10 <= 15
    return np.where(ok, digits, 10**16), np.where(ok, exp10, 0), ok


def _round_product(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``(N,)`` int64 ``round(a * b)`` computed exactly (Dekker's two-product).

    Precondition: ``a * b`` lies in ``[2**53, 2**62)`` so the rounded product is
    an integer and the error term is exact.
    """
    product = a * b
    a_hi, a_lo = _split(a)
    b_hi, b_lo = _split(b)
    error = ((a_hi * b_hi - product) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo
    return product.astype(np.int64) + np.rint(error).astype(np.int64)


def _split(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Veltkamp split of float64 into two 26-bit halves with ``hi + lo == a``."""
    c = 134217729.0 * a  # 2**27 + 1
    hi = c - (c - a)
    return hi, a - hi


def _positional(d: np.ndarray, exp10: np.ndarray, negative: np.ndarray) -> np.ndarray:
    """``±d * 10**(exp10 - 16)`` in positional notation, one fixed column layout.

    Args:
        d: ``(N,)`` int64 17-digit significands, ``10**16 <= d < 10**17``.
        exp10: ``(N,)`` int64 decimal exponent of the first digit, in ``[-6, 15]``.
        negative: ``(N,)`` bool, where to write a minus sign.

    Returns:
        ``(N, W)`` uint8: sign, integer digits right-aligned, ``.``, fraction
        digits; leading zeros (but the units digit), trailing fraction zeros and
        a bare point are 0 bytes. Every row shares the column of the point, so
        no row needs shifting.
    """
    frac_len = 16 - exp10  # fraction digits of the 17-digit form, 1..22
    p = _INT_POW10[np.minimum(frac_len, 16)]
    whole = np.where(frac_len <= 16, d // p, 0)
    frac = d - whole * p
    # the fraction as 24 digits, in two 12-digit halves that fit int64
    q = _INT_POW10[np.maximum(frac_len - 12, 0)]
    high = frac // q
    hi = high * _INT_POW10[np.maximum(12 - frac_len, 0)]
    lo = (frac - high * q) * _INT_POW10[np.minimum(24 - frac_len, 12)]
    whole_width = len(str(int(whole.max()))) if len(d) else 1
    frac_width = int(frac_len.max()) if len(d) else 0
    fraction = _fraction_text(_chunks(hi, 3) + _chunks(lo, 3))[:, :frac_width]
    out = np.empty((len(d), 2 + whole_width + frac_width), dtype=np.uint8)
    out[:, 0] = np.where(negative, ord("-"), 0)
    out[:, 1 : 1 + whole_width] = _integer_text(whole, whole_width)
    out[:, 1 + whole_width] = np.where(frac != 0, ord("."), 0)
    out[:, 2 + whole_width :] = fraction
    return out


def join_columns(rows: int, parts: list[bytes | np.ndarray]) -> bytes:
    """Text lines from columns: constants and ``(rows, W)`` uint8 cells.

    Args:
        rows: number of lines.
        parts: per column either bytes written on every line or a ``(rows, W)``
            uint8 matrix whose 0 bytes are padding.

    Returns:
        The lines concatenated, padding removed (add ``b"\\n"`` as last part).
    """
    if rows == 0:
        return b""
    widths = [len(p) if isinstance(p, bytes) else p.shape[1] for p in parts]
    cells = np.empty((rows, sum(widths)), dtype=np.uint8)
    col = 0
    for part, width in zip(parts, widths, strict=True):
        if isinstance(part, bytes):
            cells[:, col : col + width] = np.frombuffer(part, dtype=np.uint8)
        else:
            cells[:, col : col + width] = part
        col += width
    flat = cells.ravel()
    return flat[flat != 0].tobytes()


# -------------------------------------------------------------------- parsing


def decimal_to_float(mantissa: np.ndarray, frac_len: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Correctly rounded float64 of ``mantissa * 10**-frac_len``.

    Args:
        mantissa: ``(N,)`` int64, ``0 <= mantissa < 2**62``.
        frac_len: ``(N,)`` int64 in ``[0, 22]``.

    Returns:
        ``(values, decided)``: ``(N,)`` float64 and a bool mask; where
        ``decided`` is False the value lies too close to a rounding boundary to
        be sure, and the caller must parse that number with ``float()``.
    """
    m = np.asarray(mantissa, dtype=np.int64)
    k = np.asarray(frac_len, dtype=np.int64)
    small = m < 2**53
    exact = np.where(small, m, 0).astype(np.float64) / _POW10[k]  # Clinger's fast path
    big = np.flatnonzero(~small)
    if 2 * len(big) > len(m):  # mostly 17 digits and more, as most writers give:
        values, decided = _big_mantissa(np.where(small, 2**53, m), k)  # no scatter
        return np.where(small, exact, values), decided | small
    decided = small.copy()
    if len(big):
        exact[big], decided[big] = _big_mantissa(m[big], k[big])
    return exact, decided


# the powers' Veltkamp halves, gathered per value instead of split per value
_POW10_HI, _POW10_LO = _split(_POW10)


def _big_mantissa(m: np.ndarray, k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Divide a positive mantissa (above 2**53) by ``10**k`` in double-double arithmetic.

    The quotient ``q1`` plus a tail accurate to about 2**-100 relative decides
    the rounding. Values whose residual is not clearly below half the gap to
    the next float down (the smaller of the two gaps, with a margin of 2**-40
    of it) are reported undecided.
    """
    m_hi = m.astype(np.float64)
    m_lo = (m - m_hi.astype(np.int64)).astype(np.float64)  # exact, |m_lo| <= 2**9
    p = _POW10[k]
    q1 = m_hi / p
    q1_hi, q1_lo = _split(q1)
    p_hi, p_lo = _POW10_HI[k], _POW10_LO[k]
    prod = q1 * p
    prod_err = ((q1_hi * p_hi - prod) + q1_hi * p_lo + q1_lo * p_hi) + q1_lo * p_lo
    remainder = ((m_hi - prod) - prod_err) + m_lo
    tail = remainder / p
    s = q1 + tail
    residual = tail - (s - q1)
    # the gap to the next float down, from the bits (s is positive and normal)
    gap_down = s - (s.view(np.int64) - 1).view(np.float64)
    decided = np.abs(residual) < gap_down * (0.5 - 2.0**-40)
    return s, decided
