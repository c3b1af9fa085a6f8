"""Reading images back in tests, with the file closed afterwards."""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PIL import Image


def read_image(path: str | Path, mode: str | None = None) -> np.ndarray:
    """The pixels of ``path`` as an ``(H, W, channels)`` uint8 array (converted to
    ``mode`` first when given)."""
    with Image.open(path) as image:
        return np.asarray(image.convert(mode) if mode else image)
