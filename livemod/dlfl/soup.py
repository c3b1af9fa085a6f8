"""Polygon soups: the flat form every bulk builder and reader works on.

:class:`Polygons` holds a soup (positions, every face's vertex indices flat,
face offsets), :func:`as_polygons` makes one from the forms users give,
:func:`next_in_face` links each corner to the next in its face, and
:class:`SoupNames` names a soup's faces and vertices in error messages the way
its source does (by file line, OBJ vertices from 1).
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np


@dataclass
class Polygons:
    """A polygon soup in flat form.

    Attributes:
        positions: ``(V, 3)`` float64 vertex positions.
        indices: ``(C,)`` int64 vertex index of every corner, face after face.
        offsets: ``(F + 1,)`` int64; face ``i`` uses ``indices[offsets[i]:offsets[i+1]]``.
    """

    positions: np.ndarray
    indices: np.ndarray
    offsets: np.ndarray

    @property
    def sizes(self) -> np.ndarray:
        """``(F,)`` int64 number of corners of each face."""
        return np.diff(self.offsets)

    @functools.cached_property
    def single_corners(self) -> np.ndarray:
        """``(C,)`` bool, True for the corner of a one-corner face (a point-sphere)."""
        sizes = self.sizes
        if len(sizes) == 0 or sizes.min() > 1:
            return np.zeros(len(self.indices), dtype=bool)
        return np.repeat(sizes, sizes) == 1

    @functools.cached_property
    def next_corner(self) -> np.ndarray:
        """``(C,)`` int64 index of the next corner in the same face (computed once)."""
        return next_in_face(self.offsets)


def as_polygons(positions: Any, faces: Any, offsets: Any = None) -> Polygons:
    """Normalise a polygon soup to :class:`Polygons`.

    Args:
        positions: ``(V, 3)`` numbers.
        faces: a sequence of vertex-index sequences, a ``(F, k)`` int array, or,
            with ``offsets``, the flat ``(C,)`` index array.
        offsets: ``(F + 1,)`` face start offsets into a flat ``faces``.
    """
    # a copy: the mesh owns its positions and must not alias the caller's array
    pos = np.array(positions, dtype=np.float64).reshape(-1, 3)
    if offsets is not None:
        idx = np.asarray(faces, dtype=np.int64).ravel()
        off = np.asarray(offsets, dtype=np.int64).ravel()
    elif isinstance(faces, np.ndarray) and faces.ndim == 2:
        idx = faces.astype(np.int64).ravel()
        off = np.arange(0, idx.size + 1, max(faces.shape[1], 1), dtype=np.int64)
        if faces.shape[0] == 0:
            off = np.zeros(1, dtype=np.int64)
    else:
        lists = [list(f) for f in faces]
        sizes = np.array([len(f) for f in lists], dtype=np.int64)
        off = offsets_of(sizes)
        idx = np.fromiter(itertools.chain.from_iterable(lists), dtype=np.int64, count=int(off[-1]))
    return Polygons(pos, idx, off)


class SoupNames:
    """How error messages name a soup's faces and vertices: faces by their
    OBJ/.dlfl line when known, vertices as the source numbers them (OBJ from 1).

    Attributes:
        source: the file name (None: messages say "polygons").
        lines: ``(F,)`` source line of each face, or None.
        vertex_base: what the source calls vertex index 0.
    """

    def __init__(self, source: str | None, face_lines: np.ndarray | None,
                 vertex_base: int = 0) -> None:
        self.source = source
        self.lines = face_lines
        self.vertex_base = vertex_base

    def vertex(self, v: int) -> int:
        """The number the source gives vertex index ``v``."""
        return int(v) + self.vertex_base

    def face(self, f: int) -> str:
        """Face index ``f`` as a message names it: ``"line 12"`` or ``"face 3"``."""
        if self.lines is not None:
            return f"line {int(self.lines[f])}"
        return f"face {f}"

    def prefix(self, faces: Sequence[int] = ()) -> str:
        """The message's ``"file:line: "`` start, at the first of ``faces``' lines."""
        src = self.source or "polygons"
        if faces and self.lines is not None:
            return f"{src}:{int(self.lines[faces[0]])}: "
        return f"{src}: "


def offsets_of(sizes: np.ndarray) -> np.ndarray:
    """``(F + 1,)`` int64 offsets of faces of ``(F,)`` ``sizes``: where each face's
    corners start, then their total."""
    # empty, not zeros: offsets can be long, and zeroing them costs as
    # much as summing (calloc clears reused memory)
    offsets = np.empty(len(sizes) + 1, dtype=np.int64)
    offsets[0] = 0
    np.cumsum(sizes, out=offsets[1:])
    return offsets


def next_in_face(offsets: np.ndarray) -> np.ndarray:
    """``(C,)`` index of the next corner in the same face, wrapping around."""
    count = int(offsets[-1])
    nxt = np.arange(1, count + 1, dtype=np.int64)
    sizes = np.diff(offsets)
    k = int(sizes[0]) if len(sizes) else 0
    if k > 0 and sizes.min() == k == sizes.max():
        nxt[k - 1 :: k] -= k  # all faces k-gons (an (F, k) array): a strided step, no masks
        return nxt
    ends = offsets[1:][sizes > 0] - 1
    nxt[ends] = offsets[:-1][sizes > 0]
    return nxt
