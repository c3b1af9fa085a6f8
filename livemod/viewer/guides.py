"""The ground grid and the x, y, z axes drawn under the scene (``Style.grid``).

:func:`guide_lines` lays the lines out for the scene's bounds (numpy only);
:class:`Guides` owns their GL buffers and vertex arrays, made once per bounds and
drawn with the renderer's line program. Every method of :class:`Guides` must be
called on the thread that owns the GL context.
"""

from __future__ import annotations

import moderngl
import numpy as np

GRID_COLOR = (0.30, 0.31, 0.34)
AXIS_COLORS = ((0.85, 0.25, 0.25), (0.30, 0.75, 0.30), (0.30, 0.45, 0.90))


def guide_lines(bounds: np.ndarray) -> list[tuple[np.ndarray, tuple[float, float, float]]]:
    """The ground grid and the three axes for a scene of ``(2, 3)`` ``bounds``.

    The grid lies in the plane y = bounds' bottom, centred under the scene, its
    spacing a power of ten, or twice or five times one, that gives 10 to 25 cells
    across the scene's larger horizontal size; the axes run from the origin, as long as
    the scene is large.

    Returns:
        ``(lines, rgb)`` pairs: ``(2 * L, 3)`` float64 segment ends and their colour.
    """
    size = float(max(np.ptp(bounds[:, [0, 2]], axis=0).max(), 1e-6))
    step = 10.0 ** np.floor(np.log10(size / 10.0))
    step *= 5.0 if size / step > 50 else 2.0 if size / step > 20 else 1.0
    centre = np.round(bounds.mean(axis=0) / step) * step
    half = np.ceil(0.75 * size / step) * step
    ticks = np.arange(-half, half + step / 2, step)
    y = float(bounds[0, 1])
    along_x = [[(centre[0] - half, y, centre[2] + t), (centre[0] + half, y, centre[2] + t)]
               for t in ticks]
    along_z = [[(centre[0] + t, y, centre[2] - half), (centre[0] + t, y, centre[2] + half)]
               for t in ticks]
    grid = np.array(along_x + along_z, dtype=np.float64).reshape(-1, 3)
    length = max(size, float(np.ptp(bounds[:, 1])))
    axes = [(np.array([(0.0, 0.0, 0.0), tuple(length * np.eye(3)[k])]), AXIS_COLORS[k])
            for k in range(3)]
    return [(grid, GRID_COLOR), *axes]


# the GL objects of each guide line: (vertex array, buffer, rgb)
_GuideArrays = list[tuple[moderngl.VertexArray, moderngl.Buffer, tuple]]


class Guides:
    """The guide lines' GL objects, kept for the bounds they were made for.

    Args:
        ctx: the GL context to make them in.
        program: the renderer's line program (``in_position``, ``line_color``),
            its view already set.
    """

    def __init__(self, ctx: moderngl.Context, program: moderngl.Program) -> None:
        self.ctx = ctx
        self.program = program
        # the bounds' bytes and the GL objects made for them
        self.made: tuple[bytes, _GuideArrays] | None = None

    def draw(self, bounds: np.ndarray | None) -> None:
        """Draw the grid and the axes sized to ``(2, 3)`` ``bounds`` of what is drawn
        (see :func:`guide_lines`); nothing when ``bounds`` is None (nothing with a
        finite position: no size to give them)."""
        if bounds is None:
            return
        for vao, _, color in self._arrays(bounds):
            self.program["line_color"].value = color  # type: ignore[union-attr]
            vao.render(moderngl.LINES)

    def _arrays(self, bounds: np.ndarray) -> _GuideArrays:
        """The guide lines' GL objects for ``bounds``: made when the bounds change,
        and kept for the frames after (a turn of the view or a HUD change draws them
        again as they were)."""
        key = np.asarray(bounds, dtype=np.float64).tobytes()
        if self.made is not None and self.made[0] == key:
            return self.made[1]
        made = []
        for lines, color in guide_lines(bounds):
            buffer = self.ctx.buffer(lines.astype(np.float32).tobytes())
            made.append((self.ctx.vertex_array(self.program, [(buffer, "3f", "in_position")]),
                         buffer, color))
        self.release()
        self.made = (key, made)
        return made

    def release(self) -> None:
        """Free the lines' vertex arrays and buffers (the next draw makes them again)."""
        if self.made is not None:
            for vao, buffer, _ in self.made[1]:
                vao.release()
                buffer.release()
            self.made = None
