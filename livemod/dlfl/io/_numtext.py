"""Vectorized conversion between numbers and ASCII text, exact both ways.

Python's ``float()``/``repr`` and numpy's ``fromstring``/``loadtxt`` cost about
0.5 us per float here, too slow for a million-vertex OBJ. These routines do the
same work with whole-array numpy operations:

* :func:`format_floats` writes each float64 as a decimal that parses back to the
  same bits (15 significant digits when they suffice, else 16, else 17), in
  positional notation; values outside ``[1e-6, 1e15)`` fall back to ``repr``.
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
_DIGITS4 = np.array(
    [list(f"{i:04d}".encode()) for i in range(10000)], dtype=np.uint8
)  # (10000, 4) ASCII digits of every 4-digit chunk
_DIGITS4_PACKED = _DIGITS4.view(np.uint32).ravel()  # the same, 4 bytes per uint32
_INT_POW10 = np.array([10**k for k in range(19)], dtype=np.int64)


# ----------------------------------------------------------------- formatting


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
    digits = _fixed_digits(v, width)
    length = _num_digits(v)
    digits[np.arange(width)[None, :] < (width - length)[:, None]] = 0
    return digits


def _fixed_digits(v: np.ndarray, width: int) -> np.ndarray:
    """``(N, width)`` uint8 ASCII digits of ``v``, zero-filled on the left."""
    chunks = -(-width // 4)
    # gathering 4 ASCII bytes as one uint32 is ~8x faster than a (4,) row
    packed = np.empty((len(v), chunks), dtype=np.uint32)
    rest = v
    for i in range(chunks - 1, -1, -1):
        rest, chunk = np.divmod(rest, 10000)
        packed[:, i] = _DIGITS4_PACKED[chunk]
    return packed.view(np.uint8)[:, 4 * chunks - width :]


def _num_digits(v: np.ndarray) -> np.ndarray:
    """``(N,)`` number of decimal digits of each non-negative int64 (0 has 1)."""
    thresholds = np.array([10**k for k in range(1, 19)], dtype=np.int64)
    return np.searchsorted(thresholds, v, side="right") + 1


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
    rows = np.flatnonzero(fast)
    body = _positional(digits[rows], exp10[rows])
    plain_zero = (x == 0.0) & ~np.signbit(x)  # -0.0 goes through repr to keep its sign
    slow = np.flatnonzero(~fast & ~plain_zero)
    out = np.zeros((len(x), max(1 + body.shape[1], 24 if len(slow) else 1)), dtype=np.uint8)
    out[rows, 0] = np.where(x[rows] < 0, ord("-"), 0)
    out[rows, 1 : 1 + body.shape[1]] = body
    out[plain_zero, 0] = ord("0")
    for i in slow.tolist():
        text = repr(float(x[i])).encode()
        out[i, : len(text)] = np.frombuffer(text, dtype=np.uint8)
    return out


def _shortest_digits(ax: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """17 significant digits ``D`` and exponent of each positive value.

    Returns ``(D, exp10, ok)``: ``ax == D * 10**(exp10 - 16)`` to the bit when
    parsed, with ``D`` in ``[1e16, 1e17)`` carrying trailing zeros when 15 or 16
    digits already round-trip; ``ok`` is False where the fast path does not
    apply (zero, non-finite, outside ``[1e-6, 1e15)``).
    """
    ok = np.isfinite(ax) & (ax >= 1e-6) & (ax < 1e15)
    safe = np.where(ok, ax, 1.0)
    k = 16 - np.floor(np.log10(safe)).astype(np.int64)
    k = np.clip(k, 0, 22)
    scaled = safe * _POW10[k]
    # log10 can be off by one next to a power of ten
    k += (scaled < 1e16).astype(np.int64) - (scaled >= 1e17).astype(np.int64)
    ok &= (k >= 2) & (k <= 22)
    # placeholders keep the exact product in range where the fast path is off
    safe = np.where(ok, safe, 1.0)
    k = np.where(ok, k, 16)
    d17 = _round_product(safe, _POW10[k])
    ok &= (d17 >= 10**16) & (d17 < 10**17)
    c15 = (d17 + 50) // 100
    c16 = (d17 + 5) // 10
    ok15 = _as_float(c15, k - 2) == safe
    ok16 = (c16 < 2**53) & (_as_float(c16, k - 1) == safe)
    digits = np.where(ok15, c15 * 100, np.where(ok16, c16 * 10, d17))
    carry = digits >= 10**17  # rounding 9.99.. up to 10.0
    digits = np.where(carry, digits // 10, digits)
    exp10 = 16 - k + carry
    ok &= (exp10 >= -6) & (exp10 <= 15)
    return digits, exp10, ok


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


def _as_float(mantissa: np.ndarray, k: np.ndarray) -> np.ndarray:
    """Correctly rounded ``mantissa * 10**-k`` for ``mantissa < 2**53``, ``|k| <= 22``."""
    m = mantissa.astype(np.float64)
    kk = np.abs(k)
    return np.where(k >= 0, m / _POW10[kk], m * _POW10[kk])


def _positional(d: np.ndarray, exp10: np.ndarray) -> np.ndarray:
    """``d * 10**(exp10 - 16)`` in positional notation, one fixed column layout.

    Args:
        d: ``(N,)`` int64 17-digit significands, ``10**16 <= d < 10**17``.
        exp10: ``(N,)`` int64 decimal exponent of the first digit, in ``[-6, 15]``.

    Returns:
        ``(N, W)`` uint8: integer digits right-aligned, ``.``, fraction digits;
        leading zeros (but the units digit), trailing fraction zeros and a bare
        point are 0 bytes. Every row shares the column of the point, so no row
        needs shifting.
    """
    if len(d) == 0:
        return np.zeros((0, 0), dtype=np.uint8)
    frac_len = 16 - exp10  # fraction digits of the 17-digit form, 1..22
    p = _INT_POW10[np.minimum(frac_len, 16)]
    whole = np.where(frac_len <= 16, d // p, 0)
    frac = d - whole * p
    # the fraction as 22 digits, in two 11-digit halves that fit int64
    shift = 22 - frac_len
    wide = shift >= 11
    hi = np.where(wide, frac * _INT_POW10[np.maximum(shift - 11, 0)],
                  frac // _INT_POW10[np.maximum(11 - shift, 0)])
    lo = np.where(wide, 0, (frac % _INT_POW10[np.maximum(11 - shift, 0)])
                  * _INT_POW10[np.minimum(shift, 11)])
    whole_width = len(str(int(whole.max())))
    whole_digits = _fixed_digits(whole, whole_width)
    length = _num_digits(whole)
    whole_digits[np.arange(whole_width)[None, :] < (whole_width - length)[:, None]] = 0
    frac_width = int(frac_len.max())
    frac_digits = np.concatenate([_fixed_digits(hi, 11), _fixed_digits(lo, 11)], axis=1)
    frac_digits = frac_digits[:, :frac_width]
    significant = frac_digits != ord("0")
    kept = frac_width - np.argmax(significant[:, ::-1], axis=1)
    kept[~significant.any(axis=1)] = 0
    frac_digits[np.arange(frac_width)[None, :] >= kept[:, None]] = 0
    point = np.where(kept > 0, ord("."), 0).astype(np.uint8)[:, None]
    return np.concatenate([whole_digits, point, frac_digits], axis=1)


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
    values = np.where(small, m, 0).astype(np.float64) / _POW10[k]  # Clinger's fast path
    decided = small.copy()
    big = np.flatnonzero(~small)
    if len(big):
        values[big], decided[big] = _big_mantissa(m[big], k[big])
    return values, decided



def _big_mantissa(m: np.ndarray, k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Divide a mantissa above 2**53 by ``10**k`` in double-double arithmetic.

    The quotient ``q1`` plus a tail accurate to about 2**-100 relative decides
    the rounding; values whose residual sits within 2**-40 ulp of a halfway
    point are reported undecided.
    """
    m_hi = m.astype(np.float64)
    m_lo = (m - m_hi.astype(np.int64)).astype(np.float64)  # exact, |m_lo| <= 2**9
    p = _POW10[k]
    q1 = m_hi / p
    q1_hi, q1_lo = _split(q1)
    p_hi, p_lo = _split(p)
    prod = q1 * p
    prod_err = ((q1_hi * p_hi - prod) + q1_hi * p_lo + q1_lo * p_hi) + q1_lo * p_lo
    remainder = ((m_hi - prod) - prod_err) + m_lo
    tail = remainder / p
    s = q1 + tail
    residual = tail - (s - q1)
    up_gap = np.spacing(s)
    down_gap = s - np.nextafter(s, 0.0)
    half_gap = np.where(residual >= 0, up_gap, down_gap) * 0.5
    decided = np.abs(residual) < half_gap - up_gap * 2.0**-40
    return s, decided
