"""Vertex buffers that a per-frame draw refills: :class:`StreamBuffer`.

The HUD's text, the id labels and the selection's marker points are drawn every
frame from arrays made on the CPU; each is streamed through one kept buffer and
vertex array instead of a new pair per draw. Every method must be called on the
thread that owns the GL context.
"""

from __future__ import annotations

from collections.abc import Callable

import moderngl
import numpy as np


class StreamBuffer:
    """A dynamic vertex buffer that a draw refills each time it is called, and the
    vertex array reading it (the HUD's text is drawn every frame: making and
    freeing a buffer and a vertex array for each draw cost two GL objects a frame).

    The buffer only grows (to a power of two of rows), in place: ``orphan`` with a
    new size keeps the GL buffer name, so the vertex array made once stays valid.
    Each refill orphans the old storage first, so a draw still reading it does
    not hold up the write. Draws pass their own vertex or instance count: the
    buffer holds more rows than are drawn.
    """

    def __init__(self, ctx: moderngl.Context,
                 make_vao: Callable[[moderngl.Buffer], moderngl.VertexArray]) -> None:
        self.ctx = ctx
        self._make_vao = make_vao
        self.buffer: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        self._held: np.ndarray | None = None  # the array last written, to skip a rewrite

    def load(self, rows: np.ndarray) -> moderngl.VertexArray:
        """The vertex array, its buffer now holding ``rows`` (``(n, k)`` float32,
        n >= 1). The same array object as last time (a cached HUD or label layout)
        is not written again."""
        if rows is self._held and self.vao is not None:
            return self.vao
        data = np.ascontiguousarray(rows, dtype=np.float32)
        row_bytes = data.nbytes // max(len(data), 1)
        if self.buffer is None:
            self.buffer = self.ctx.buffer(reserve=_capacity(len(data)) * row_bytes,
                                          dynamic=True)
            self.vao = self._make_vao(self.buffer)
        elif self.buffer.size < data.nbytes:
            self.buffer.orphan(_capacity(len(data)) * row_bytes)
        else:
            self.buffer.orphan()
        self.buffer.write(data)
        self._held = rows
        assert self.vao is not None
        return self.vao

    def release(self) -> None:
        """Free the vertex array and the buffer (a later :meth:`load` makes new ones)."""
        if self.vao is not None:
            self.vao.release()
        if self.buffer is not None:
            self.buffer.release()
        self.buffer = self.vao = self._held = None


def _capacity(rows: int) -> int:
    """Rows to reserve for ``rows``: the next power of two, at least 64."""
    return max(64, 1 << max(rows - 1, 0).bit_length())
