"""The patch-smoothed preview, computed in a background thread.

TopMod draws a smoothed "patch" version of the control mesh; livemod
approximates it with two levels of Catmull-Clark (or Doo-Sabin) subdivision
from :mod:`livemod.dlfl.subdivision`. Above the face budget there is no preview
(None). A preview that fails is logged (to the logger named "livemod.preview") and the
session goes on without it: the control mesh is what the user asked for.
"""

from __future__ import annotations

import logging
import queue
import threading
from collections.abc import Callable

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.subdivision import subdivide

from .results import RunResult, snapshot_mesh

_LOG = logging.getLogger("livemod.preview")

DEFAULT_SCHEME = "catmull-clark"
DEFAULT_LEVELS = 2
DEFAULT_FACE_BUDGET = 2_000_000  # faces of the *preview*; bigger meshes get none


def preview_arrays(mesh: Mesh, *, scheme: str = DEFAULT_SCHEME, levels: int = DEFAULT_LEVELS,
                   face_budget: int = DEFAULT_FACE_BUDGET) -> MeshArrays | None:
    """Read-only arrays of ``mesh`` subdivided ``levels`` times, or None.

    ``mesh`` is not changed. None when the mesh is empty or the preview would
    exceed ``face_budget`` faces (each level multiplies the face count by about
    four). Raises what :func:`~livemod.dlfl.subdivision.subdivide` raises.
    """
    faces = mesh.counts()[2]
    if faces == 0 or faces * 4**levels > face_budget:
        return None
    smoothed = mesh.copy()
    for _ in range(levels):
        subdivide(smoothed, scheme)
    return snapshot_mesh(smoothed)


class PreviewWorker:
    """One daemon thread computing previews for results, newest first.

    Args:
        post: receives ``(result, preview)``; it decides whether to publish.
        is_current: tells whether a result is still worth a preview (a newer
            run makes older requests pointless; they are dropped).
        compute: the preview function (injectable for tests).
    """

    def __init__(self, post: Callable[[RunResult, MeshArrays], None],
                 is_current: Callable[[RunResult], bool],
                 compute: Callable[[Mesh], MeshArrays | None] = preview_arrays) -> None:
        self._post = post
        self._is_current = is_current
        self._compute = compute
        self._requests: queue.Queue[tuple[RunResult, Mesh] | None] = queue.Queue()
        self._thread = threading.Thread(target=self._loop, name="livemod-preview", daemon=True)
        self._thread.start()

    def request(self, result: RunResult, mesh: Mesh) -> None:
        """Compute a preview of ``mesh`` (which must no longer change) for ``result``."""
        self._requests.put((result, mesh))

    def close(self) -> None:
        """Stop the thread after the request in progress."""
        self._requests.put(None)

    def _loop(self) -> None:
        while True:
            item = self._latest()
            if item is None:
                return
            result, mesh = item
            if not self._is_current(result):
                continue
            try:
                preview = self._compute(mesh)
            except Exception:  # a failing preview must never take the session down
                _LOG.exception("the preview of run %d failed; showing the mesh unsmoothed",
                               result.run_id)
                preview = None
            if preview is not None:
                self._post(result, preview)

    def _latest(self) -> tuple[RunResult, Mesh] | None:
        """The newest pending request (older ones are skipped), None to stop."""
        item = self._requests.get()
        while item is not None:
            try:
                newer = self._requests.get_nowait()
            except queue.Empty:
                return item
            item = newer
        return None
