"""Picking: the integer id pass and reading the element under a click back.

:class:`IdPass` owns the pick target (a colour attachment, a ``u4`` id attachment
and depth) and turns the ids drawn into it around a click into a :class:`Pick`;
the renderer draws the ids (its face, edge and point passes write them, see
:func:`~livemod.viewer.geometry.decode_pick`). Every method of :class:`IdPass` must
be called on the thread that owns the GL context.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import moderngl
import numpy as np

from livemod.dlfl.arrays import MeshArrays

from .camera import Camera
from .framebuffers import release_framebuffer
from .geometry import decode_pick

KIND_CODES = {"face": 1, "corner": 1, "edge": 2, "vertex": 3}  # a pick kind's id code


@dataclass(frozen=True)
class Pick:
    """A picked element: ``kind`` is "face", "edge", "vertex" or "corner"."""

    kind: str
    dense_index: int
    element_id: int


class IdPass:
    """The pick target, kept for the next pick of the same size.

    Args:
        ctx: the GL context to make the target in.
    """

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.target: moderngl.Framebuffer | None = None

    def pick(self, arrays: MeshArrays, camera: Camera, size: tuple[int, int],
             point: tuple[int, int], kind: str, radius: int,
             draw_ids: Callable[[moderngl.Framebuffer], None]) -> Pick | None:
        """The element of ``kind`` of ``arrays`` under pixel ``point`` (from the top
        left) of a ``size`` view of ``camera``, or None; ``draw_ids`` draws the ids
        into the target it is given (bound, cleared, its viewport set). Faces and
        corners are picked at the pixel itself; edges and vertices at the nearest
        id within ``radius`` pixels. A corner is its face's corner whose vertex is
        nearest the click (TopMod)."""
        fbo = self._target(size)
        fbo.use()
        self.ctx.viewport = (0, 0, *fbo.size)
        fbo.clear(0.0, 0.0, 0.0, 0.0)  # 0 bits in the id attachment: background
        draw_ids(fbo)
        x, y = point
        reach = 0 if kind in ("face", "corner") else radius
        hit = _nearest_id(fbo, x, size[1] - 1 - y, reach, KIND_CODES[kind])
        if hit is None:
            return None
        if kind == "corner":
            dense = nearest_corner(arrays, hit, camera, size, point)
            return Pick("corner", dense, int(arrays.corner_ids[dense]))
        ids = {"face": arrays.face_ids, "edge": arrays.edge_ids, "vertex": arrays.vertex_ids}
        return Pick(kind, hit, int(ids[kind][hit]))

    def _target(self, size: tuple[int, int]) -> moderngl.Framebuffer:
        if self.target is not None and self.target.size == tuple(size):
            return self.target
        if self.target is not None:
            release_framebuffer(self.target)
        self.target = self.ctx.framebuffer(
            [self.ctx.texture(size, 4), self.ctx.texture(size, 1, dtype="u4")],
            self.ctx.depth_renderbuffer(size))
        return self.target

    def release(self) -> None:
        """Free the pick target (the next pick makes it again)."""
        if self.target is not None:
            release_framebuffer(self.target)
            self.target = None


def _nearest_id(fbo: moderngl.Framebuffer, x: int, y: int, reach: int, code: int) -> int | None:
    """Dense index of the ``code`` id nearest ``(x, y)`` (GL pixels) within ``reach``."""
    width, height = fbo.size
    x0, y0 = max(x - reach, 0), max(y - reach, 0)
    x1, y1 = min(x + reach + 1, width), min(y + reach + 1, height)
    if x0 >= x1 or y0 >= y1:
        return None
    raw = fbo.read(viewport=(x0, y0, x1 - x0, y1 - y0), components=1, attachment=1,
                   dtype="u4")
    ids = np.frombuffer(raw, dtype=np.uint32).reshape(y1 - y0, x1 - x0)
    rows, cols = np.nonzero((ids >> 28) == code)
    if len(rows) == 0:
        return None
    dist = (rows + y0 - y) ** 2 + (cols + x0 - x) ** 2
    best = int(np.argmin(dist))
    decoded = decode_pick(int(ids[rows[best], cols[best]]))
    return None if decoded is None else decoded[1]


def nearest_corner(arrays: MeshArrays, face: int, camera: Camera, size: tuple[int, int],
                   point: tuple[int, int]) -> int:
    """Dense index of the corner of dense ``face`` whose vertex projects nearest
    ``point`` (window pixels from the top left, of a ``size`` view).

    Only corners in front of the eye count: one behind it (clip w <= 0, as when a
    perspective eye is inside the mesh) has no place on the screen, and dividing
    by its w would mirror it through the centre of the view, maybe onto the click.
    A face picked at a pixel has a corner in front (w is linear over its triangle,
    and the pixel's point is in front); when none is, the one nearest to being
    in front (the largest w) is returned.
    """
    start, stop = int(arrays.face_offsets[face]), int(arrays.face_offsets[face + 1])
    at = arrays.positions[arrays.corner_vertex[start:stop]]
    clip = np.c_[at, np.ones(len(at))] @ camera.view_projection(size[0] / max(size[1], 1)).T
    w = clip[:, 3]
    front = np.flatnonzero(w > 0.0)  # (a vertex that is not finite is left out too)
    if len(front) == 0:
        return start + int(np.argmax(w))
    ndc = clip[front, :2] / w[front, None]
    pixels = np.c_[(ndc[:, 0] + 1) * 0.5 * size[0], (1 - ndc[:, 1]) * 0.5 * size[1]]
    return start + int(front[np.argmin(((pixels - np.asarray(point)) ** 2).sum(axis=1))])
