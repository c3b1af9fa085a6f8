"""The mesh on screen: which mesh of a result is drawn, its upload, and the framing.

:class:`MeshDisplay` gives the renderer the mesh of each result: its own, or
after an error the last good one (the failed run's own with ``E``), with the
other objects and the patch preview; it measures what it shows, and frames it
when its bounds changed a lot (the camera is kept across re-runs otherwise).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from .camera import Camera, bounds_changed_a_lot
from .geometry import sample_points
from .measure import WholeMeshMeasurer
from .objects import SceneObjects
from .picking import Picking
from .renderer import Renderer

if TYPE_CHECKING:
    from livemod.dlfl.arrays import MeshArrays
    from livemod.runner.results import RunResult


class MeshDisplay:
    """Shows results' meshes.

    Args:
        renderer: draws them.
        camera: framed on a new mesh.
        whole: measures the genus and volume of the mesh shown.
        picking: measures the picks on it.
        objects: says which other objects are drawn beside it.
        screen_size: gives the framebuffer's size (its shape frames the mesh).
        echo: prints a line in the terminal.

    Attributes:
        show_partial: after an error, the failed run's own mesh is shown (``E``).
        fit_bounds: the bounds the camera was last framed on (None: frame the next).
    """

    def __init__(self, renderer: Renderer, camera: Camera, whole: WholeMeshMeasurer,
                 picking: Picking, objects: SceneObjects,
                 screen_size: Callable[[], tuple[int, int]],
                 echo: Callable[[str], None]) -> None:
        self._renderer = renderer
        self._camera = camera
        self._whole = whole
        self._picking = picking
        self._objects = objects
        self._screen_size = screen_size
        self._echo = echo
        self.forget()

    def forget(self) -> None:
        """Another script: frame its first mesh, and show last good meshes again."""
        self.show_partial = False
        self.fit_bounds: np.ndarray | None = None

    def show(self, result: RunResult) -> None:
        """Draw the mesh of ``result`` (a new one only when it changed: a result
        re-posted with its preview only adds the preview)."""
        arrays = self._drawn_arrays(result)
        if arrays is not None and arrays is not self._renderer.arrays:
            self._show_mesh(result, arrays)
        elif result.arrays is None and result.error is None:
            self._renderer.set_mesh(None)  # the script ended with no mesh: show none
            self._picking.remeasure(None)
            self._whole.measure(None)
        elif result.preview is not None and result.preview is not self._renderer.preview:
            self._renderer.set_preview(result.preview)

    def toggle_partial(self, result: RunResult | None) -> None:
        """``E``: after an error, the mesh as the failed run left it, or the last good one."""
        if result is None or result.error is None or result.partial is None:
            self._echo("no failed run to show: E shows the mesh a failed run left")
            return
        self.show_partial = not self.show_partial
        self._show_mesh(result, self._drawn_arrays(result))
        self._echo("showing the mesh as the failed run left it" if self.show_partial
                   else "showing the last good mesh")

    def _drawn_arrays(self, result: RunResult) -> MeshArrays | None:
        """The mesh to show of ``result``: the failed run's own (E), or the last good one."""
        if self.show_partial and result.error is not None and result.partial is not None:
            return result.partial
        return result.arrays

    def _show_mesh(self, result: RunResult, arrays: MeshArrays | None) -> None:
        """Upload ``arrays`` (``result``'s own mesh, or its failed run's) with the
        result's preview when it is the preview of those arrays, and its others."""
        preview = result.preview if arrays is result.arrays else None
        self.upload(arrays, preview, self._objects.visible_others(result))

    def upload(self, arrays: MeshArrays | None, preview: MeshArrays | None,
               others: MeshArrays | None) -> None:
        """Draw ``arrays`` with its ``preview`` and the ``others`` beside it, measured,
        and framed when its bounds changed a lot since the last framing (None: draw
        no mesh)."""
        self._renderer.set_mesh(arrays, preview, others)
        self._renderer.set_selection(self._picking.selection)
        self._picking.remeasure(arrays)
        self._whole.measure(arrays)
        bounds = self._renderer.bounds
        drawn = arrays is not None and len(arrays.positions) > 0
        if drawn and bounds is not None and bounds_changed_a_lot(self.fit_bounds, bounds):
            self.fit()
            self.fit_bounds = bounds

    def fit(self) -> None:
        """Frame what is drawn."""
        positions = self._renderer.drawn_positions()
        if len(positions):
            width, height = self._screen_size()
            self._camera.fit_points(sample_points(positions), width / max(height, 1))
