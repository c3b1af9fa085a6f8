"""The mesh on screen: which mesh of a result is drawn, its upload, and the framing.

:class:`MeshDisplay` gives the renderer the mesh of each result: its own, or
after an error the last good one (the failed run's own with ``E``), with the
other objects; it measures what it shows, and frames it when its bounds changed a
lot (the camera is kept across re-runs otherwise). A big mesh's render buffers
are built on a thread of their own and uploaded a slice a frame (see
:meth:`MeshDisplay.advance`), so that no frame waits for it; the mesh before it
stays on screen meanwhile, and a newer result supersedes it.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from livemod.runner.preview import NewestJob

from .camera import Camera, bounds_changed_a_lot
from .geometry import PreparedMeshes, prepare_meshes, sample_points
from .look import Look
from .measure import WholeMeshMeasurer
from .objects import SceneObjects
from .picking import Picking
from .renderer import UPLOAD_SECONDS, Renderer

# meshes (with the other objects) of more corners are prepared off the thread
PREPARED_CORNERS = 200_000

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
                 picking: Picking, objects: SceneObjects, look: Look,
                 screen_size: Callable[[], tuple[int, int]],
                 echo: Callable[[str], None]) -> None:
        self._renderer = renderer
        self._camera = camera
        self._whole = whole
        self._picking = picking
        self._objects = objects
        self._look = look
        self._screen_size = screen_size
        self._echo = echo
        self._preparing: NewestJob[tuple, PreparedMeshes] = NewestJob(_prepare, "livemod-buffers")
        self._waiting: int | None = None             # the preparation awaited
        self._staged: MeshArrays | None = None        # uploading, to be measured once shown
        self.content: tuple[MeshArrays | None, MeshArrays | None] = (None, None)
        self.forget()

    def forget(self) -> None:
        """Another script: frame its first mesh, and show last good meshes again."""
        self.show_partial = False
        self.fit_bounds: np.ndarray | None = None

    @property
    def pending(self) -> bool:
        """A mesh is being prepared or uploaded (the one before it is on screen)."""
        return self._waiting is not None or self._staged is not None

    def show(self, result: RunResult) -> None:
        """Draw the mesh of ``result`` (a new one only when it changed: a result
        re-posted with its preview only adds the preview)."""
        arrays = self._drawn_arrays(result)
        if arrays is not None and arrays is not self.content[0]:
            self._show_mesh(result, arrays)
        elif result.arrays is None and result.error is None:
            self.upload(None, None, None)  # the script ended with no mesh: show none
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
        """Draw ``arrays`` with the ``others`` beside it (and ``preview``, when one
        comes with it; else the preview drawn stays until the window's next),
        measured, and framed when its bounds changed a lot since the last framing
        (None: draw no mesh). A mesh of more than ``PREPARED_CORNERS`` corners is
        drawn a few frames later (see :meth:`advance`)."""
        self.content = (arrays, others)
        corners = sum(len(a.corner_vertex) for a in (arrays, others) if a is not None)
        if corners > PREPARED_CORNERS and preview is None:
            style = self._look.style
            self._waiting = self._preparing.ask(
                (arrays, others, style.crease_angle if style.smooth else None, style.labels))
            return
        self._waiting = None
        self._renderer.stage(arrays, preview, others, keep_preview=preview is None
                             and arrays is not None)
        self._renderer.advance(math.inf)
        self._staged = None
        self._shown(arrays)

    def advance(self) -> None:
        """Each frame: stage a mesh prepared off the thread, give the upload in
        progress its slice of the frame, and measure and frame the mesh once it is
        on screen (never waits)."""
        taken = self._preparing.take()
        if taken is not None and taken[0] == self._waiting:
            prepared = taken[1]
            self._renderer.stage(prepared.arrays, None, prepared.others, prepared,
                                 keep_preview=True)
            self._waiting, self._staged = None, prepared.arrays
        if self._renderer.uploading:
            self._renderer.advance(UPLOAD_SECONDS)
        if self._staged is not None and self._renderer.arrays is self._staged \
                and not self._renderer.uploading:
            staged, self._staged = self._staged, None
            self._shown(staged)

    def show_others(self, others: MeshArrays | None) -> None:
        """Draw ``others`` beside the mesh now (the object list changed)."""
        self.content = (self.content[0], others)
        self._renderer.set_others(others)

    def _shown(self, arrays: MeshArrays | None) -> None:
        """``arrays`` is on screen now: its selection, measures and framing."""
        self._renderer.set_selection(self._picking.selection)
        self._picking.remeasure(arrays)
        self._whole.measure(arrays)
        bounds = self._renderer.bounds
        drawn = arrays is not None and len(arrays.positions) > 0
        if drawn and bounds is not None and bounds_changed_a_lot(self.fit_bounds, bounds):
            self.fit()
            self.fit_bounds = bounds

    def close(self) -> None:
        """Stop the preparing thread."""
        self._preparing.close()

    def fit(self) -> None:
        """Frame what is drawn."""
        positions = self._renderer.drawn_positions()
        if len(positions):
            width, height = self._screen_size()
            self._camera.fit_points(sample_points(positions), width / max(height, 1))


def _prepare(job: tuple) -> PreparedMeshes:
    """:func:`~.geometry.prepare_meshes` of ``(arrays, others, crease angle or None,
    label kinds)``, on the preparing thread."""
    arrays, others, crease_angle, labels = job
    return prepare_meshes(arrays, others, crease_angle, labels)
