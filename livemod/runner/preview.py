"""The smoothed preview, computed in a background thread.

The default is TopMod's: one bicubic patch per corner over level-2 Doo-Sabin
(:mod:`livemod.dlfl.patches`), evaluated on a grid whose density the user
chooses, with the patches' own normals. The Catmull-Clark limit (two levels of
:func:`~livemod.dlfl.subdivision.subdivide`, smooth vertex normals) is the
other mode. A preview covers every object it is given.

Above the triangle budget the preview degrades instead of vanishing: first a
lower density (patches; at the lowest, 0, the faces are drawn through the
patches' vertex points, which lie on the surface, with the patches' normals) or
fewer levels (Catmull-Clark, which then gives way to patches), then the patches
of part of the mesh only: those seen by the view, nearest first.
:attr:`Preview.description` says what it shows, for the HUD.

A preview that fails is logged (to the logger named "livemod.preview") and the
session goes on without it: the control mesh is what the user asked for.
"""

from __future__ import annotations

import logging
import queue
import threading
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Generic, TypeVar

import numpy as np

from livemod.dlfl.analysis import face_centroids
from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.build import from_corner_arrays
from livemod.dlfl.errors import DLFLError, InvalidArgumentError
from livemod.dlfl.mesh import Mesh
from livemod.dlfl.patches import MAX_DENSITY, CornerPatches, Tessellation, mesh_surface
from livemod.dlfl.subdivision import subdivide

from .results import RunResult, snapshot_mesh

_LOG = logging.getLogger("livemod.preview")

DEFAULT_SCHEME = "catmull-clark"
DEFAULT_LEVELS = 2
DEFAULT_FACE_BUDGET = 2_000_000  # faces of a :func:`preview_arrays` preview; bigger: none

PATCHES, CATMULL_CLARK = "patches", "catmull-clark"
MODES = (PATCHES, CATMULL_CLARK)
DEFAULT_DENSITY = 4
# triangles a preview may have: about what software GL (llvmpipe) draws in a
# frame's 50 ms; a GPU takes ten times as many
DEFAULT_TRIANGLE_BUDGET = 500_000
GPU_TRIANGLE_BUDGET = 5_000_000


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


@dataclass(frozen=True)
class PreviewSettings:
    """What preview to make.

    Attributes:
        mode: ``"patches"`` (TopMod's) or ``"catmull-clark"``.
        density: grid steps along each side of a patch (1 to ``MAX_DENSITY``):
            ``2 * density**2`` triangles per corner.
        levels: Catmull-Clark levels (1 to 4): ``2 * 4**levels`` triangles per quad.
        budget: the most triangles the preview may have (at least 2).

    Raises:
        InvalidArgumentError: a value out of its range.
    """

    mode: str = PATCHES
    density: int = DEFAULT_DENSITY
    levels: int = DEFAULT_LEVELS
    budget: int = DEFAULT_TRIANGLE_BUDGET

    def __post_init__(self) -> None:
        if self.mode not in MODES:
            raise InvalidArgumentError(f"preview mode must be one of {MODES}, got {self.mode!r}")
        for name, low, high in (("density", 1, MAX_DENSITY), ("levels", 1, 4),
                                ("budget", 2, 2**31)):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
                raise InvalidArgumentError(
                    f"preview {name} must be an int from {low} to {high}, got {value!r}")


@dataclass(frozen=True)
class View:
    """What a camera sees, to choose the patches shown when not all fit.

    Attributes:
        eye: ``(3,)`` the camera's position.
        view_projection: ``(4, 4)`` matrix from world to clip coordinates.
    """

    eye: np.ndarray
    view_projection: np.ndarray


@dataclass(frozen=True)
class Preview:
    """A preview ready to draw: every object's smoothed surface as one set of
    triangles.

    Attributes:
        surface: positions, normals (float32) and triangles (uint32), read-only.
        description: what it shows, in a few words for the HUD.
        settings: the settings it was asked with.
        density: the density (patches) or levels (Catmull-Clark) it has.
        shown: patches (or faces subdivided) in it.
        total: patches (or faces) the objects have.
        by_view: it holds the part of the objects the view saw (not all fit).
        parts: triangles of each object in ``surface``, in the request's order.
        closed: its back faces are never seen: every object is closed (no hole
            faces) and shown whole.
    """

    surface: Tessellation
    description: str
    settings: PreviewSettings
    density: int
    shown: int
    total: int
    by_view: bool = False
    parts: tuple[int, ...] = ()
    closed: bool = False


@dataclass(frozen=True)
class PreviewRequest:
    """A preview to make, of ``objects`` (their arrays) with ``settings``;
    ``view`` chooses the part shown when not all fit (None: the first in order)."""

    objects: tuple[MeshArrays, ...]
    settings: PreviewSettings = field(default_factory=PreviewSettings)
    view: View | None = None


def make_preview(request: PreviewRequest) -> Preview:
    """The preview of ``request`` (see the module): never None, and empty when the
    objects have nothing to smooth."""
    if request.settings.mode == CATMULL_CLARK:
        made, why_not = _catmull_clark(request)
        if made is not None:
            return made
        return _patches(request, note=f"Catmull-Clark {why_not}: ")
    return _patches(request)


def _patches(request: PreviewRequest, note: str = "") -> Preview:
    """TopMod's patches of every object, at the density the budget allows (0: the
    patches' vertex points only), then of the faces nearest in view."""
    settings = request.settings
    makers = [CornerPatches(arrays) for arrays in request.objects]
    corners = [maker.surface_corners() for maker in makers]
    total = sum(len(c) for c in corners)
    density = _density(settings, total)
    cost = _triangles_per_face(density)
    drawn = sum(int(cost(a.face_sizes[faces_of(a, c)]).sum())
                for a, c in zip(request.objects, corners, strict=True))
    by_view = drawn > settings.budget
    if by_view:
        corners = _nearest_patches(request, corners, settings.budget, cost)
    parts = [maker.tessellate(density, chosen) if density else maker.vertex_surface(chosen)
             for maker, chosen in zip(makers, corners, strict=True)]
    shown = sum(len(c) for c in corners)
    return Preview(join_surfaces(parts, density),
                   note + _describe_patches(settings, density, shown, total, by_view),
                   settings, density, shown, total, by_view,
                   tuple(len(p.triangles) for p in parts),
                   not by_view and _all_closed(request.objects))


def _density(settings: PreviewSettings, patches: int) -> int:
    """The highest density up to the one asked whose ``2 density**2`` triangles a
    patch fit in the budget; 0 (vertex points only) when not even 1 does."""
    fits = int(np.sqrt(settings.budget / (2.0 * max(patches, 1))))
    return min(settings.density, fits)


def _triangles_per_face(density: int) -> Callable[[np.ndarray], np.ndarray]:
    """Triangles a face of each size gets at ``density``."""
    if density == 0:
        return lambda sizes: np.maximum(sizes - 2, 0)
    return lambda sizes: 2 * density**2 * sizes


def _all_closed(objects: Sequence[MeshArrays]) -> bool:
    """No object has a hole face (so no patch surface of theirs is seen from behind)."""
    return not any(bool(a.face_hole.any()) for a in objects)


def _describe_patches(settings: PreviewSettings, density: int, shown: int, total: int,
                      by_view: bool) -> str:
    if total == 0:
        return "patches: nothing to smooth"
    text = f"patches, density {density}" if density else "patches at their vertex points"
    if density < settings.density:
        text += f" (of {settings.density}: budget)"
    if by_view:
        text += f", {shown:,} of {total:,} (the nearest in view: budget)"
    return text


def _nearest_patches(request: PreviewRequest, corners: list[np.ndarray], budget: int,
                     cost: Callable[[np.ndarray], np.ndarray]) -> list[np.ndarray]:
    """Of each object's ``corners``, those of the faces the view sees nearest
    (faces whole, whose triangles, ``cost(face sizes)``, fit in ``budget``);
    without a view, faces in order."""
    faces = [faces_of(arrays, chosen)
             for arrays, chosen in zip(request.objects, corners, strict=True)]
    if request.view is None:  # object after object, faces in order
        score = np.arange(sum(len(f) for f in faces), dtype=np.float64)
    else:
        score = np.concatenate([_face_scores(arrays, f, request.view)
                                for arrays, f in zip(request.objects, faces, strict=True)])
    triangles = np.concatenate([cost(arrays.face_sizes[f])
                                for arrays, f in zip(request.objects, faces, strict=True)])
    order = np.argsort(score, kind="stable")
    kept = np.zeros(len(score), dtype=bool)
    kept[order[np.cumsum(triangles[order]) <= budget]] = True
    out, start = [], 0
    for arrays, own_faces, chosen in zip(request.objects, faces, corners, strict=True):
        shown = np.zeros(len(arrays.face_ids), dtype=bool)
        shown[own_faces[kept[start:start + len(own_faces)]]] = True
        start += len(own_faces)
        out.append(chosen[shown[arrays.corner_face[chosen]]])
    return out


def faces_of(arrays: MeshArrays, corners: np.ndarray) -> np.ndarray:
    """``(k,)`` int64 the faces of dense ``corners``, each once, in order (a mask,
    not a sort: linear)."""
    has = np.zeros(len(arrays.face_ids), dtype=bool)
    has[arrays.corner_face[corners]] = True
    return np.flatnonzero(has)


def _face_scores(arrays: MeshArrays, faces: np.ndarray, view: View) -> np.ndarray:
    """``(k,)`` float: lower for faces to show first: in view and near the eye
    (faces out of view come after all in view)."""
    centres = face_centroids(arrays)[faces]
    # (einsum: BLAS's threads cost more than they give on a busy machine)
    clip = np.einsum("ij,kj->ik", centres, np.asarray(view.view_projection)[:, :3]) \
        + np.asarray(view.view_projection)[:, 3]
    w = clip[:, 3]
    inside = (w > 0) & (np.abs(clip[:, 0]) <= w) & (np.abs(clip[:, 1]) <= w)
    distance = np.linalg.norm(centres - np.asarray(view.eye), axis=1)
    distance = np.where(np.isfinite(distance), distance, np.inf)
    return np.where(inside, distance, distance + 1e300)


def join_surfaces(parts: Sequence[Tessellation], density: int) -> Tessellation:
    """One surface of several, their triangles' indices shifted; read-only. It has
    colours when a part has (the points of the parts without, none: all zero)."""
    positions = [p.positions for p in parts] or [np.zeros((0, 3), np.float32)]
    normals = [p.normals for p in parts] or [np.zeros((0, 3), np.float32)]
    starts = np.cumsum([0] + [len(p.positions) for p in parts])
    triangles = [p.triangles + np.uint32(start) for p, start in zip(parts, starts,
                                                                     strict=False)]
    colors = None
    if any(p.colors is not None for p in parts):
        colors = np.concatenate([np.zeros((len(p.positions), 4), np.uint8) if p.colors is None
                                 else p.colors for p in parts])
    joined = Tessellation(np.concatenate(positions), np.concatenate(normals),
                          np.concatenate(triangles or [np.zeros((0, 3), np.uint32)]), density,
                          colors)
    for array in (joined.positions, joined.normals, joined.triangles, joined.colors):
        if array is not None:
            array.flags.writeable = False
    return joined


def _catmull_clark(request: PreviewRequest) -> tuple[Preview | None, str]:
    """Each object subdivided as many levels as the settings ask and the budget
    allows (a face of n corners gives n quads at the first level, four times as
    many at each next); ``(None, why)`` when one level does not fit or a mesh
    cannot be rebuilt."""
    settings = request.settings
    quads = sum(int(a.face_sizes[~a.face_hole].sum()) for a in request.objects)
    levels = settings.levels
    while levels > 0 and 2 * quads * 4 ** (levels - 1) > settings.budget:
        levels -= 1
    if levels == 0:
        return None, "over the budget"
    try:
        parts = [_subdivided_surface(arrays, levels) for arrays in request.objects]
    except DLFLError as exc:  # (a position that is not finite, say)
        _LOG.info("no Catmull-Clark preview (%s): showing patches", exc)
        return None, "impossible"
    text = f"Catmull-Clark, {levels} level{'s' if levels > 1 else ''}"
    if levels < settings.levels:
        text += f" (of {settings.levels}: budget)"
    faces = sum(int((~a.face_hole).sum()) for a in request.objects)
    return Preview(join_surfaces(parts, 0), text, settings, levels, faces, faces, False,
                   tuple(len(p.triangles) for p in parts), _all_closed(request.objects)), ""


def _subdivided_surface(arrays: MeshArrays, levels: int) -> Tessellation:
    """The Catmull-Clark surface of ``arrays`` after ``levels`` levels, smooth."""
    if not len(arrays.face_ids):
        return mesh_surface(arrays)
    mesh = from_corner_arrays(arrays.positions, arrays.face_offsets, arrays.corner_vertex,
                              arrays.corner_mate, arrays.face_hole,
                              face_colors=arrays.face_colors)
    subdivided = preview_arrays(mesh, levels=levels, face_budget=2**62)
    assert subdivided is not None
    return mesh_surface(subdivided)


Key = TypeVar("Key")
Job = TypeVar("Job")
Made = TypeVar("Made")


class PreviewWorker(Generic[Key, Job, Made]):
    """One daemon thread computing previews, newest first.

    Args:
        post: receives ``(key, preview)``; it decides whether to publish.
        is_current: tells whether a key is still worth a preview (a newer
            request makes older ones pointless; they are dropped).
        compute: makes a preview of a job (None: no preview).
        name: the thread's name, which says in a thread dump what it works on.
    """

    def __init__(self, post: Callable[[Key, Made], None], is_current: Callable[[Key], bool],
                 compute: Callable[[Job], Made | None], name: str = "livemod-preview") -> None:
        self._post = post
        self._is_current = is_current
        self._compute = compute
        self._requests: queue.Queue[tuple[Key, Job] | None] = queue.Queue()
        self._thread = threading.Thread(target=self._loop, name=name, daemon=True)
        self._thread.start()

    def request(self, key: Key, job: Job) -> None:
        """Compute a preview of ``job`` (which must no longer change) for ``key``."""
        self._requests.put((key, job))

    def close(self) -> None:
        """Stop the thread after the request in progress."""
        self._requests.put(None)

    def _loop(self) -> None:
        while True:
            item = self._latest()
            if item is None:
                return
            key, job = item
            if not self._is_current(key):
                continue
            try:
                preview = self._compute(job)
            except Exception:  # a failing preview must never take the session down
                _LOG.exception("the preview of %s failed; showing the mesh unsmoothed",
                               _name(key))
                preview = None
            if preview is not None:
                self._post(key, preview)

    def _latest(self) -> tuple[Key, Job] | None:
        """The newest pending request (older ones are skipped), None to stop."""
        item = self._requests.get()
        while item is not None:
            try:
                newer = self._requests.get_nowait()
            except queue.Empty:
                return item
            item = newer
        return None


def _name(key: object) -> str:
    return f"run {key.run_id}" if isinstance(key, RunResult) else repr(key)


class NewestJob(Generic[Job, Made]):
    """Work done on a thread of its own for a window, newest request first: ask
    for it whenever what it depends on changes, and take the newest finished
    result, once, without waiting.

    Args:
        compute: does the work of a request (None: nothing to hand back).
        name: the name of its thread.
    """

    def __init__(self, compute: Callable[[Job], Made | None],
                 name: str = "livemod-preview") -> None:
        self._lock = threading.Lock()
        self._asked = 0
        self._done: tuple[int, Made] | None = None
        self.ready = threading.Event()  # set when a result is waiting to be taken
        self._worker: PreviewWorker[int, Job, Made] = PreviewWorker(
            self._finished, self._wanted, compute, name)

    def ask(self, request: Job) -> int:
        """Do ``request``; it supersedes every earlier request (theirs will never be
        handed back). Returns the request's number."""
        with self._lock:
            self._asked += 1
            number = self._asked
        self._worker.request(number, request)
        return number

    def take(self) -> tuple[int, Made] | None:
        """``(request number, result)`` of the newest request once it is done,
        or None (not done yet, or taken already)."""
        with self._lock:
            done, self._done = self._done, None
            self.ready.clear()
        return done

    def close(self) -> None:
        """Stop the worker after the request in progress."""
        self._worker.close()

    def _wanted(self, number: int) -> bool:
        with self._lock:
            return number == self._asked

    def _finished(self, number: int, made: Made) -> None:
        with self._lock:
            if number == self._asked:
                self._done = (number, made)
                self.ready.set()


class ScenePreviews(NewestJob[PreviewRequest, Preview]):
    """The viewer's previews (see :class:`NewestJob`), made by ``compute``
    (:func:`make_preview` by default)."""

    def __init__(self, compute: Callable[[PreviewRequest], Preview | None] = make_preview,
                 ) -> None:
        super().__init__(compute)
