"""The range of the formats that store coordinates as float32 (STL, glTF)."""

from __future__ import annotations

import numpy as np

from ..errors import GeometryError

_FLOAT32_MAX = float(np.finfo(np.float32).max)


def check_float32_range(positions: np.ndarray, format_name: str) -> None:
    """Refuse ``(V, 3)`` ``positions`` that a format storing float32 cannot hold.

    Raises:
        GeometryError: a coordinate beyond float32's range (it would be written
            as infinity), naming the format and the largest coordinate.
    """
    largest = float(np.abs(positions).max()) if positions.size else 0.0
    if largest > _FLOAT32_MAX:
        raise GeometryError(f"{format_name} stores coordinates as float32, up to about "
                            f"{_FLOAT32_MAX:.3g}; this mesh has one of {largest:.3g}")
