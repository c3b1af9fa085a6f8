"""The section plane controller (GL-free)."""

from __future__ import annotations

import numpy as np
import pytest

from livemod.viewer.look import Look
from livemod.viewer.section import SectionPlane

BOUNDS = np.array([[-1.0, 0.0, 2.0], [3.0, 2.0, 4.0]])


def test_c_cuts_across_x_y_z_through_the_middle_then_not() -> None:
    look, said = Look(), []
    plane = SectionPlane(look, lambda: BOUNDS, said.append)
    cuts = []
    for _ in range(4):
        plane.cycle()
        cuts.append(look.style.section)
    assert cuts == [(0, 1.0), (1, 1.0), (2, 3.0), None]
    assert said == ["section: x <= 1", "section: y <= 1", "section: z <= 3", "section: off"]


def test_the_plane_moves_a_twentieth_never_far_past_the_mesh() -> None:
    look, said = Look(), []
    plane = SectionPlane(look, lambda: BOUNDS, said.append)
    plane.move(1)
    assert said == ["no section to move: C cuts the meshes"] and look.style.section is None
    plane.cycle()
    plane.move(1)
    assert look.style.section == (0, pytest.approx(1.2)) and said[-1] == "section: x <= 1.2"
    for _ in range(30):
        plane.move(-1)
    assert look.style.section == (0, pytest.approx(-1.2))  # a step beyond the low end


def test_nothing_drawn_nothing_to_cut() -> None:
    look, said = Look(), []
    SectionPlane(look, lambda: None, said.append).cycle()
    assert look.style.section is None and said == ["section: off"]
