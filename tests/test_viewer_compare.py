"""Comparing pictures for ``livemod render --reference`` (no GL)."""

from __future__ import annotations

import numpy as np
import pytest
from PIL import Image

from livemod.viewer.compare import (
    DIFF_COLOR,
    difference_picture,
    image_difference,
    read_picture,
)


def _picture(height: int = 4, width: int = 5, value: int = 100, channels: int = 3) -> np.ndarray:
    return np.full((height, width, channels), value, dtype=np.uint8)


def test_the_same_picture_does_not_differ() -> None:
    difference = image_difference(_picture(), _picture())
    assert difference.share == 0.0 and difference.largest == 0.0
    assert difference.matches(0.0)


def test_a_pixel_differs_only_beyond_a_tenth_of_a_channel() -> None:
    changed = _picture()
    changed[1, 2, 0] += 25  # 25/255 < 0.1: the same
    assert image_difference(changed, _picture()).share == 0.0
    changed[3, 4, 2] -= 26  # 26/255 > 0.1: differs
    difference = image_difference(changed, _picture())
    assert difference.share == 1 / 20
    assert np.argwhere(difference.mask).tolist() == [[3, 4]]
    assert difference.largest == pytest.approx(26 / 255)
    assert difference.matches(0.05) and not difference.matches(0.049)


def test_an_rgb_picture_is_opaque_against_an_rgba_one() -> None:
    rgba = _picture(channels=4, value=100)
    rgba[..., 3] = 255
    assert image_difference(_picture(), rgba).share == 0.0
    rgba[0, 0, 3] = 0  # a transparent pixel is not an opaque one
    assert image_difference(rgba, _picture()).share == 1 / 20


def test_the_summary_names_the_share_the_threshold_and_the_largest_difference() -> None:
    changed = _picture()
    changed[0, :2] = 0  # 2 of 20 pixels, each channel off by 100 of 255
    difference = image_difference(changed, _picture())
    assert difference.summary("ref.png", 0.02) == (
        "10.00% of the pixels differ from ref.png (threshold 2.00%; largest difference 39%)")
    assert difference.summary("ref.png").endswith("(threshold 1.00%; largest difference 39%)")


def test_pictures_of_other_sizes_are_refused() -> None:
    with pytest.raises(ValueError, match="the picture is 5x4 pixels, the reference 4x5"):
        image_difference(_picture(4, 5), _picture(5, 4))


def test_the_difference_picture_is_the_reference_in_grey_with_red_differences() -> None:
    reference = _picture(value=200)
    changed = reference.copy()
    changed[2, 3] = 0
    picture = difference_picture(reference, image_difference(changed, reference))
    assert picture.shape == (4, 5, 3) and picture.dtype == np.uint8
    assert tuple(picture[2, 3]) == DIFF_COLOR
    assert (picture[0, 0] == 80).all()  # 200 dimmed to 0.4


def test_read_picture_names_what_it_could_not_read(tmp_path) -> None:
    with pytest.raises(ValueError, match=f"no reference picture at {tmp_path / 'gone.png'}"):
        read_picture(tmp_path / "gone.png", "reference picture")
    (tmp_path / "text.png").write_text("not a picture")
    with pytest.raises(ValueError, match="is not an image this can read"):
        read_picture(tmp_path / "text.png")


def test_read_picture_keeps_alpha_only_where_there_is_some(tmp_path) -> None:
    Image.fromarray(_picture(value=7)).save(tmp_path / "rgb.png")
    Image.fromarray(_picture(value=7, channels=4)).save(tmp_path / "rgba.png")
    Image.fromarray(_picture(value=7)).convert("P").save(tmp_path / "palette.gif")
    assert read_picture(tmp_path / "rgb.png").shape == (4, 5, 3)
    assert read_picture(tmp_path / "rgba.png").shape == (4, 5, 4)
    assert read_picture(tmp_path / "palette.gif").shape == (4, 5, 3)
    assert (read_picture(tmp_path / "rgb.png") == 7).all()
