"""The look (GL-free): the style's switches and the overlays."""

from __future__ import annotations

import pytest

from livemod.viewer.look import TOGGLED_FIELDS, Look
from livemod.viewer.renderer import DARK_BACKGROUND, LIGHT_BACKGROUND, Style


@pytest.mark.parametrize("field_name", TOGGLED_FIELDS)
def test_each_switch_flips_its_field_and_back(field_name: str) -> None:
    look = Look()
    before = getattr(look.style, field_name)
    look.toggle(field_name)
    assert getattr(look.style, field_name) is (not before)
    look.toggle(field_name)
    assert look.style == Style()


def test_labels_background_and_overlays() -> None:
    look = Look()
    look.toggle_labels("faces")
    look.toggle_labels("edges")
    look.toggle_labels("faces")
    assert look.style.labels == {"edges"}
    look.toggle_labels_selected()
    assert look.style.labels_selected_only
    look.toggle_background()
    assert look.style.background == LIGHT_BACKGROUND
    look.toggle_background()
    assert look.style.background == DARK_BACKGROUND
    assert look.panels_shown
    look.toggle_help()
    assert look.show_help and not look.panels_shown  # the help hides the panels
    look.toggle_help()
    look.toggle_hud()
    assert not look.show_hud and not look.panels_shown
