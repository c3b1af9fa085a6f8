"""How the window draws: the renderer's style and which overlays are up (GL-free).

:class:`Look` holds the :class:`~livemod.viewer.renderer.Style` (replaced, never
changed in place, so a frame's style can be compared with the last) and the HUD
and help switches; the style keys and the other controllers change it here.
"""

from __future__ import annotations

import dataclasses
from typing import Any

from .renderer import DARK_BACKGROUND, LIGHT_BACKGROUND, Style

# the Style fields a key flips on and off (``toggle_<field>`` actions)
TOGGLED_FIELDS = ("faces", "edges", "vertices", "preview", "others", "grid", "smooth",
                  "colors")


class Look:
    """The style drawn and the overlays shown.

    Attributes:
        style: what the renderer draws.
        show_hud: the HUD (and the panels and timeline with it) is up.
        show_help: the help overlay is up (it hides the panels).
    """

    def __init__(self) -> None:
        self.style = Style()
        self.show_hud = True
        self.show_help = False

    @property
    def panels_shown(self) -> bool:
        """The parameters panel, the object list and the timeline are drawn."""
        return self.show_hud and not self.show_help

    def change(self, **fields: Any) -> None:
        """Draw with these :class:`Style` fields changed."""
        self.style = dataclasses.replace(self.style, **fields)

    def toggle(self, field_name: str) -> None:
        """Flip a yes/no :class:`Style` field (one of :data:`TOGGLED_FIELDS`)."""
        self.change(**{field_name: not getattr(self.style, field_name)})

    def toggle_labels(self, kind: str) -> None:
        """Id labels of ``kind`` ("faces", "edges", "vertices") on or off."""
        self.change(labels=self.style.labels ^ {kind})

    def toggle_labels_selected(self) -> None:
        """Label all elements, or only the selected ones."""
        self.change(labels_selected_only=not self.style.labels_selected_only)

    def toggle_background(self) -> None:
        """Dark or light background."""
        light = self.style.background == DARK_BACKGROUND
        self.change(background=LIGHT_BACKGROUND if light else DARK_BACKGROUND)

    def toggle_hud(self) -> None:
        self.show_hud = not self.show_hud

    def toggle_help(self) -> None:
        self.show_help = not self.show_help
