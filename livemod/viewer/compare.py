"""A render against a reference image: ``livemod render --reference`` (GL-free).

Golden-image tests of a model: render it once, keep the picture, and let later
renders say whether they still look the same. Two pictures differ at a pixel where
any channel differs by more than :data:`PIXEL_TOLERANCE` of its range (so the last
bit of anti-aliasing or a driver's rounding does not count); they match when the
share of such pixels is at most the threshold (``--threshold``, :data:`THRESHOLD`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

PIXEL_TOLERANCE = 0.1  # of a channel's range: a pixel differs beyond this
THRESHOLD = 0.01  # the share of differing pixels two matching pictures may have
DIFF_COLOR = (255, 40, 40)  # differing pixels in the difference picture


@dataclass(frozen=True)
class ImageDifference:
    """How two same-sized pictures differ.

    Attributes:
        mask: ``(H, W)`` bool, True where the pixels differ.
        largest: the largest difference of any channel, as a share of its range.
    """

    mask: np.ndarray
    largest: float

    @property
    def share(self) -> float:
        """The share of the pixels that differ, in [0, 1]."""
        return float(self.mask.mean()) if self.mask.size else 0.0

    def matches(self, threshold: float = THRESHOLD) -> bool:
        """True when at most ``threshold`` of the pixels differ."""
        return self.share <= threshold

    def summary(self, reference: str, threshold: float = THRESHOLD) -> str:
        """How much differs, naming the ``reference``: ``"2.10% of the pixels differ
        from REF (threshold 1.00%; largest difference 80%)"``."""
        return (f"{self.share:.2%} of the pixels differ from {reference} "
                f"(threshold {threshold:.2%}; largest difference {self.largest:.0%})")


def image_difference(image: np.ndarray, reference: np.ndarray,
                     tolerance: float = PIXEL_TOLERANCE) -> ImageDifference:
    """Where ``image`` differs from ``reference``, both ``(H, W, C)`` uint8 with C of 3
    (RGB) or 4 (RGBA; an RGB picture counts as opaque against an RGBA one).

    Raises:
        ValueError: the pictures are not of the same size.
    """
    if image.shape[:2] != reference.shape[:2]:
        raise ValueError(f"the picture is {_size(image)} pixels, the reference "
                         f"{_size(reference)}")
    channels = max(image.shape[2], reference.shape[2])
    delta = np.abs(_channels(image, channels).astype(np.int16)
                   - _channels(reference, channels).astype(np.int16))
    largest = delta.max(axis=2) if delta.size else np.zeros(image.shape[:2], np.int16)
    return ImageDifference(largest > tolerance * 255,
                           float(largest.max()) / 255 if largest.size else 0.0)


def difference_picture(reference: np.ndarray, difference: ImageDifference) -> np.ndarray:
    """``(H, W, 3)`` uint8: ``reference`` dimmed to grey, the differing pixels in red."""
    grey = _channels(reference, 3).mean(axis=2, keepdims=True) * 0.4
    picture = np.repeat(grey, 3, axis=2).astype(np.uint8)
    picture[difference.mask] = DIFF_COLOR
    return picture


def read_picture(path: str | Path, what: str = "picture") -> np.ndarray:
    """The first frame of the image file at ``path`` as ``(H, W, 3 or 4)`` uint8.

    Raises:
        ValueError: no such file, or not an image Pillow reads (the message names
            ``what`` and the path).
    """
    from PIL import Image, UnidentifiedImageError

    try:
        with Image.open(path) as opened:
            mode = "RGBA" if "A" in opened.getbands() or "transparency" in opened.info \
                else "RGB"
            return np.asarray(opened.convert(mode))
    except FileNotFoundError:
        raise ValueError(f"no {what} at {path}") from None
    except (UnidentifiedImageError, OSError) as exc:
        raise ValueError(f"the {what} {path} is not an image this can read ({exc})") from None


def _channels(image: np.ndarray, channels: int) -> np.ndarray:
    """``image`` with 3 or 4 ``channels``: an added alpha is opaque, a dropped one ignored."""
    if image.shape[2] == channels:
        return image
    if channels == 3:
        return image[..., :3]
    opaque = np.full(image.shape[:2] + (1,), 255, dtype=image.dtype)
    return np.concatenate([image, opaque], axis=2)


def _size(image: np.ndarray) -> str:
    return f"{image.shape[1]}x{image.shape[0]}"
