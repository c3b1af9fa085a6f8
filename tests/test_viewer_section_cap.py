"""Tests of livemod.viewer.section_cap's GL-free part (its GL passes are tested
through the renderer in test_viewer_renderer.py and the golden images)."""

from __future__ import annotations

import numpy as np

from livemod.viewer.section_cap import hatch_spacing


def test_hatch_spacing_is_a_power_of_two_near_eight_pixels() -> None:
    assert hatch_spacing(0.01, 1.0) == 0.0625  # 8 pixels of 0.01: 0.08, nearest 2^-4
    assert hatch_spacing(0.01, 0.5) == 0.125  # seen aslant: spread out
    assert hatch_spacing(0.01, 0.01) == hatch_spacing(0.01, 0.25) == 0.25  # by at most 4x
    assert hatch_spacing(1e100, 1.0) == 2.0 ** round(np.log2(8e100))
