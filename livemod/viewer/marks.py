"""The selection's marker points: the selected vertices and the selected corners.

:class:`SelectionMarks` owns the two kept stream buffers their points are drawn
through (one flat colour each, no pick ids): a few selected positions drawn as a
batch of their own cost less than drawing every vertex and discarding the rest in
the shader. Every method must be called on the thread that owns the GL context.
"""

from __future__ import annotations

import moderngl
import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.scene import Selection

from .geometry import corner_points, dense_flags
from .streams import StreamBuffer

RGB = tuple[float, float, float]


class SelectionMarks:
    """Draws the selection's marker points with the renderer's point ``program``
    (``in_position``, ``point_size``, ``point_color``, ``use_flags``) in ``ctx``."""

    def __init__(self, ctx: moderngl.Context, program: moderngl.Program) -> None:
        self.ctx = ctx
        self.program = program
        self.streams = {kind: StreamBuffer(ctx, self._point_vao)
                        for kind in ("vertices", "corners")}

    def _point_vao(self, points: moderngl.Buffer) -> moderngl.VertexArray:
        """The point program's vertex array over ``(k, 3)`` float32 ``points``."""
        return self.ctx.vertex_array(self.program, [(points, "3f", "in_position")])

    def draw_vertices(self, arrays: MeshArrays, selection: Selection, size: float,
                      color: RGB) -> None:
        """The selected vertices of ``arrays`` as ``size`` pixel points of ``color``."""
        picked = np.flatnonzero(dense_flags(arrays.vertex_ids, selection.vertices))
        self._draw(arrays.positions[picked].astype(np.float32), size, color, "vertices")

    def draw_corners(self, arrays: MeshArrays | None, selection: Selection, size: float,
                     color: RGB) -> None:
        """The selected corners of ``arrays`` (each a point inside its face, near its
        vertex) as ``size`` pixel points of ``color``."""
        if arrays is None or not selection.corners:
            return
        picked = np.flatnonzero(dense_flags(arrays.corner_ids, selection.corners))
        self._draw(corner_points(arrays, picked), size, color, "corners")

    def _draw(self, points: np.ndarray, size: float, color: RGB, kind: str) -> None:
        """Draw ``(k, 3)`` float32 ``points`` in one flat colour (no pick ids),
        through the stream buffer of ``kind`` ("vertices" or "corners")."""
        if len(points) == 0:
            return
        self.program["point_size"].value = size  # type: ignore[union-attr]
        self.program["point_color"].value = color  # type: ignore[union-attr]
        self.program["use_flags"].value = 0  # type: ignore[union-attr]
        vao = self.streams[kind].load(points)
        vao.render(moderngl.POINTS, vertices=len(points))

    def release(self) -> None:
        """Free the streams (before the point program, which the renderer frees)."""
        for stream in self.streams.values():
            stream.release()
