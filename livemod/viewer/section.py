"""The section plane: ``C`` cuts the meshes across x, then y, then z, then not;
``[`` and ``]`` move the plane (GL-free).

The plane is the :class:`~livemod.viewer.renderer.Style`'s ``section``; it is put
through the middle of what is drawn, and moved in steps of 1/20 of its size.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .controls import section_text
from .look import Look

MOVES_ACROSS = 20  # [ and ] move the plane this fraction of the size of what is drawn


class SectionPlane:
    """Cuts through what is drawn.

    Args:
        look: the style whose ``section`` this sets.
        bounds: gives the ``(2, 3)`` bounds of what is drawn (None: nothing is).
        echo: prints a line in the terminal.
    """

    def __init__(self, look: Look, bounds: Callable[[], np.ndarray | None],
                 echo: Callable[[str], None]) -> None:
        self._look = look
        self._bounds = bounds
        self._echo = echo

    def cycle(self) -> None:
        """Cut across the next axis through the middle of what is drawn (x after
        none, none after z, or when nothing is drawn)."""
        section = self._look.style.section
        axis = 0 if section is None else section[0] + 1
        bounds = self._bounds()
        if axis > 2 or bounds is None:
            self._look.change(section=None)
            self._echo("section: off")
            return
        self._look.change(section=(axis, float(bounds[:, axis].mean())))
        self._echo(f"section: {section_text(self._look.style.section)}")

    def move(self, direction: int) -> None:
        """Move the plane by 1/:data:`MOVES_ACROSS` of what is drawn along its axis
        (``direction`` 1 forward, -1 back), never more than a step beyond it."""
        bounds, section = self._bounds(), self._look.style.section
        if section is None or bounds is None:
            self._echo("no section to move: C cuts the meshes")
            return
        axis, at = section
        low, high = float(bounds[0, axis]), float(bounds[1, axis])
        step = (high - low) / MOVES_ACROSS or 1.0
        at = min(max(at + direction * step, low - step), high + step)
        self._look.change(section=(axis, at))
        self._echo(f"section: {section_text(self._look.style.section)}")
