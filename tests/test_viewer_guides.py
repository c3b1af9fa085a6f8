"""Tests of livemod.viewer.guides' layout of the grid and axes (GL-free; their
GL objects are tested through the renderer in test_viewer_renderer.py)."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.viewer.guides import AXIS_COLORS, GRID_COLOR, guide_lines


def test_guide_lines_grid_spacing_and_axes() -> None:
    bounds = np.array([[-1.0, -2.0, -1.0], [1.0, 3.0, 1.0]])
    (grid, grid_color), *axes = guide_lines(bounds)
    assert grid_color == GRID_COLOR and [color for _, color in axes] == list(AXIS_COLORS)
    assert np.all(grid[:, 1] == -2.0)  # on the ground under the scene
    xs = np.unique(grid[:, 0].round(9))
    step = float(np.diff(xs).min())
    assert step == pytest.approx(0.1)  # size 2 -> 20 cells of 0.1 across it
    assert xs.min() <= -1.0 and xs.max() >= 1.0  # it reaches past the scene
    for k, (ends, _) in enumerate(axes):
        assert ends[0].tolist() == [0.0, 0.0, 0.0]
        assert ends[1][k] == pytest.approx(5.0) and np.count_nonzero(ends[1]) == 1
    big = guide_lines(np.array([[0.0, 0.0, 0.0], [300.0, 1.0, 40.0]]))[0][0]
    assert float(np.diff(np.unique(big[:, 0].round(6))).min()) == pytest.approx(20.0)
