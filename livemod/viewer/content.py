"""What the renderer draws, and its upload to the GPU.

:class:`DrawnContent` owns the current object's arrays, its smoothed preview and
the scene's other objects, their uploads (in progress, a slice of a frame at a
time, and done: the :class:`~livemod.viewer.uploads.MeshGPU` and
:class:`~livemod.viewer.uploads.SurfaceGPU` drawn), the selection, the version that
counts their changes, and the bounds and reach of what is drawn.
:class:`~livemod.viewer.renderer.Renderer` is the content that draws itself: it
adds the programs' passes over it. Every method must be called on the thread that
owns the GL context.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import moderngl
import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.scene import Selection

from .geometry import LabelAnchors, PreparedMeshes, build_geometry, dense_flags
from .uploads import GLObject, MeshGPU, Steps, SurfaceGPU, Upload

if TYPE_CHECKING:
    from livemod.runner.preview import Preview

UPLOAD_SECONDS = 0.02  # of a frame an upload in progress takes by default


class DrawnContent:
    """The meshes drawn, uploaded with ``programs`` (by name) in ``ctx``.

    Attributes:
        arrays, preview, others: the content drawn now (None: none).
        selection: the ids highlighted.
        version: counts changes of what is drawn (meshes, selection): a frame
            drawn at the same version, camera and style is the same picture.
    """

    def __init__(self, ctx: moderngl.Context, programs: dict[str, moderngl.Program]) -> None:
        self.ctx = ctx
        self.programs = programs
        self.version = 0
        self.arrays: MeshArrays | None = None
        self.preview: Preview | MeshArrays | None = None
        self.others: MeshArrays | None = None
        self.selection = Selection()
        self._mesh: MeshGPU | None = None
        self._flagged: tuple[Selection, MeshGPU] | None = None  # what the flags show
        self._others: MeshGPU | None = None
        self._preview: SurfaceGPU | None = None
        self._uploads: dict[str, Upload] = {}  # "mesh", "preview": uploads in progress

    def _new_mesh(self, anchors: dict[str, LabelAnchors]) -> None:
        """Hook, called once a new mesh is drawn with its label ``anchors`` of each
        kind (as prepared off the thread): a subclass drops what it kept
        of the old mesh (here, nothing is kept)."""

    def _new_selection(self) -> None:
        """Hook, called once the selection changed, before its flags are uploaded: a
        subclass drops what it kept of the old selection."""

    def set_mesh(self, arrays: MeshArrays | None,
                 preview: Preview | MeshArrays | None = None,
                 others: MeshArrays | None = None) -> None:
        """Upload ``arrays`` (and its smoothed ``preview``) in one step, replacing the old.

        ``others``: the scene's other objects, drawn beside it in a muted colour;
        they hide what is behind them but are never picked or labelled.
        """
        self.stage(arrays, preview, others)
        self.advance(math.inf)

    def stage(self, arrays: MeshArrays | None, preview: Preview | MeshArrays | None = None,
              others: MeshArrays | None = None, prepared: PreparedMeshes | None = None,
              keep_preview: bool = False) -> None:
        """Start uploading ``arrays``, its ``preview`` and the ``others`` (see
        :meth:`set_mesh`); what is drawn changes once :meth:`advance` has uploaded
        them all, so each frame can give the upload a slice of its time. Their
        render buffers come ``prepared`` off the thread (for these same arrays),
        or are built here. With ``keep_preview`` the preview drawn stays (until
        :meth:`stage_preview` gives the new content's). An upload in progress is
        given up: the newer content supersedes it. When the upload fails, what
        was drawn stays."""
        if keep_preview:
            self._abandon_mesh()
        else:
            self._abandon(mesh=True)
        if prepared is None or prepared.arrays is not arrays or prepared.others is not others:
            prepared = PreparedMeshes(
                arrays, others, None if arrays is None else build_geometry(arrays),
                None if others is None else build_geometry(others))
        ctx, programs = self.ctx, self.programs

        def start(made: list[GLObject]) -> Steps[tuple]:
            mesh = other = surface = None
            if prepared.mesh is not None:
                mesh = yield from MeshGPU.steps(ctx, programs, prepared.mesh, made)
            if prepared.other is not None:
                other = yield from MeshGPU.steps(ctx, programs, prepared.other, made)
            if preview is not None and not keep_preview:
                surface = yield from SurfaceGPU.steps(ctx, programs, preview, made)
            return mesh, other, surface

        def done(made: tuple) -> None:
            replaced = (self._mesh, self._others) + (() if keep_preview else (self._preview,))
            for old in replaced:
                if old is not None:
                    old.release()
            self._mesh, self._others = made[:2]
            self.arrays, self.others = arrays, others
            if not keep_preview:
                self._preview, self.preview = made[2], preview
            self._new_mesh(prepared.anchors)
            self.version += 1
            self.set_selection(self.selection)

        self._uploads["mesh"] = Upload(start, done)

    def stage_preview(self, preview: Preview | MeshArrays | None) -> None:
        """Start uploading (or drop, with None) the smoothed preview alone, as
        :meth:`stage` does; it supersedes a preview upload in progress."""
        self._abandon(mesh=False)
        ctx, programs = self.ctx, self.programs

        def start(made: list[GLObject]) -> Steps[SurfaceGPU | None]:
            if preview is None:
                return None
            return (yield from SurfaceGPU.steps(ctx, programs, preview, made))

        def done(surface: SurfaceGPU | None) -> None:
            if self._preview is not None:
                self._preview.release()
            self._preview, self.preview = surface, preview
            self.version += 1

        self._uploads["preview"] = Upload(start, done)

    def set_preview(self, preview: Preview | MeshArrays | None) -> None:
        """Upload (or drop, with None) the smoothed preview now: a
        :class:`~livemod.runner.preview.Preview` (of the current object first, then
        maybe the other objects), or the arrays of a subdivided mesh (drawn with
        smooth vertex normals). When it holds parts for the other objects, the
        preview draws them too in place of their faces."""
        self.stage_preview(preview)
        self.advance(math.inf)

    def advance(self, seconds: float = UPLOAD_SECONDS) -> bool:
        """Give the uploads in progress about ``seconds`` (at least one step each;
        the mesh's first); True when none is left. An upload that fails is given
        up (what it made is freed) and its error raised; what was drawn stays."""
        for name in ("mesh", "preview"):
            upload = self._uploads.get(name)
            if upload is None:
                continue
            try:
                upload.advance(seconds)
            except BaseException:
                upload.abandon()
                del self._uploads[name]
                raise
            if upload.finished:
                del self._uploads[name]
        return not self._uploads

    @property
    def uploading(self) -> bool:
        """An upload is in progress (:meth:`advance` has work to do)."""
        return bool(self._uploads)

    def _abandon(self, mesh: bool) -> None:
        """Give up the preview's upload in progress (and with ``mesh``, the mesh's)."""
        for name in (("mesh", "preview") if mesh else ("preview",)):
            upload = self._uploads.pop(name, None)
            if upload is not None:
                upload.abandon()

    def _abandon_mesh(self) -> None:
        """Give up the mesh's upload in progress (the preview's goes on)."""
        upload = self._uploads.pop("mesh", None)
        if upload is not None:
            upload.abandon()

    def set_others(self, others: MeshArrays | None) -> None:
        """Upload (or drop, with None) the other objects alone, keeping the mesh."""
        new = None if others is None else MeshGPU.made(self.ctx, self.programs,
                                                        build_geometry(others))
        if self._others is not None:
            self._others.release()
        self._others, self.others = new, others
        self.version += 1

    def set_selection(self, selection: Selection) -> None:
        """Highlight ``selection`` (ids; ids missing from the mesh are ignored).

        Nothing happens when the mesh uploaded already shows ``selection`` itself
        (the same object): the frame that shows a new mesh hands it over twice,
        and each upload checks every id (about 1.5 ms at a million faces)."""
        flagged = self._flagged
        if flagged is not None and flagged[0] is selection and flagged[1] is self._mesh:
            return
        self.selection = selection
        self._new_selection()
        self.version += 1
        arrays = self.arrays
        if arrays is None or self._mesh is None:
            return
        self._mesh.set_flags(dense_flags(arrays.face_ids, selection.faces),
                             dense_flags(arrays.edge_ids, selection.edges),
                             dense_flags(arrays.vertex_ids, selection.vertices))
        self._flagged = (selection, self._mesh)

    def _placed(self) -> list[MeshGPU]:
        """The mesh and the other objects uploaded that have a finite position."""
        return [m for m in (self._mesh, self._others)
                if m is not None and len(m.geometry.positions) > m.geometry.nonfinite]

    @property
    def nonfinite(self) -> int:
        """How many vertices of the mesh and the other objects have a position
        that is not finite (NaN or inf): they are left out of :attr:`bounds`."""
        return sum(m.geometry.nonfinite for m in (self._mesh, self._others) if m is not None)

    @property
    def bounds(self) -> np.ndarray | None:
        """``(2, 3)`` bounds of the finite positions of everything drawn (the mesh
        and the other objects), or None when there are none."""
        drawn = [m.geometry.bounds for m in self._placed()]
        if not drawn:
            return None
        return np.stack([np.min([b[0] for b in drawn], axis=0),
                         np.max([b[1] for b in drawn], axis=0)])

    def drawn_positions(self) -> np.ndarray:
        """``(n, 3)`` positions of the mesh and the other objects (for framing)."""
        parts = [a.positions for a in (self.arrays, self.others) if a is not None]
        return np.concatenate(parts) if parts else np.zeros((0, 3))

    def _scene_reach(self, target: np.ndarray, fallback: float) -> float:
        """Radius around ``target`` of a sphere holding every mesh drawn (``fallback``
        when none is), for the camera's clip planes. Measured from the target, not
        the meshes' centre: a re-run that moves the mesh by less than its size
        keeps the camera (see :func:`~.camera.bounds_changed_a_lot`), and a pan
        moves the target, so the two part. Not the largest radius ever seen
        either: after a large mesh, a small one would get a needlessly deep range."""
        reaches = [float(np.linalg.norm(m.geometry.center - target)) + m.geometry.radius
                   for m in self._placed()]
        return max(reaches) if reaches else fallback

    def _release_content(self) -> None:
        """Free the uploaded meshes and forget the content."""
        for mesh in (self._mesh, self._others, self._preview):
            if mesh is not None:
                mesh.release()
        self._mesh = self._others = self._preview = None
        self.arrays = self.preview = self.others = None
