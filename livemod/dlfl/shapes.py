"""Primitive shapes, built procedurally (no files on disk).

Each function returns a new :class:`Mesh`; :func:`load_shape` finds one by name.
The cube has exactly the layout of TopMod's ``cube.obj`` (vertices at ±1, the same
face order and orientation), so counts and positions compare with TopMod directly.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .build import from_polygons
from .errors import DLFLError
from .mesh import Mesh

GOLDEN = (1 + 5**0.5) / 2


def cube(size: float = 2.0) -> Mesh:
    """The cube of TopMod's ``cube.obj`` (8/12/6), edge length ``size`` (default 2)."""
    h = size / 2
    positions = np.array([
        (1, 1, 1), (1, 1, -1), (-1, 1, -1), (-1, 1, 1),
        (1, -1, 1), (1, -1, -1), (-1, -1, -1), (-1, -1, 1),
    ], dtype=np.float64) * h
    faces = [(0, 1, 2, 3), (4, 5, 1, 0), (5, 6, 2, 1), (6, 7, 3, 2), (7, 4, 0, 3), (7, 6, 5, 4)]
    return from_polygons(positions, faces)


def tetrahedron() -> Mesh:
    """A regular tetrahedron (4/6/4) inscribed in the unit sphere."""
    positions = np.array([(1, 1, 1), (1, -1, -1), (-1, 1, -1), (-1, -1, 1)]) / 3**0.5
    faces = [(0, 1, 2), (0, 3, 1), (0, 2, 3), (1, 3, 2)]
    return from_polygons(positions, faces)


def octahedron() -> Mesh:
    """A regular octahedron (6/12/8) with vertices on the axes at distance 1."""
    positions = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4),
             (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    return from_polygons(positions, faces)


def icosahedron() -> Mesh:
    """A regular icosahedron (12/30/20) inscribed in the unit sphere."""
    g = GOLDEN
    positions = np.array([
        (-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0),
        (0, -1, g), (0, 1, g), (0, -1, -g), (0, 1, -g),
        (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1),
    ], dtype=np.float64)
    positions /= np.linalg.norm(positions[0])
    faces = [
        (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11),
        (1, 5, 9), (5, 11, 4), (11, 10, 2), (10, 7, 6), (7, 1, 8),
        (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9),
        (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
    ]
    return from_polygons(positions, faces)


def dodecahedron() -> Mesh:
    """A regular dodecahedron (20/30/12): the dual of :func:`icosahedron`, on the unit sphere."""
    ico = icosahedron()
    from .arrays import mesh_arrays

    a = mesh_arrays(ico)
    centres = np.zeros((len(a.face_ids), 3))
    np.add.at(centres, a.corner_face, a.positions[a.corner_vertex])
    centres /= np.linalg.norm(centres, axis=1, keepdims=True)
    # each icosahedron vertex becomes a pentagon through the faces around it,
    # walked against the face order so the pentagon faces outward
    vnext = a.corner_vnext
    faces = []
    for v in range(len(a.vertex_ids)):
        start = int(np.flatnonzero(a.corner_vertex == v)[0])
        ring, c = [], start
        while True:
            ring.append(int(a.corner_face[c]))
            c = int(vnext[c])
            if c == start:
                break
        faces.append(ring[::-1])
    return from_polygons(centres, faces)


def torus(rings: int = 8, sides: int = 6, major: float = 2.0, minor: float = 0.5) -> Mesh:
    """A quad torus of genus 1: ``rings * sides`` quads around the y axis.

    Raises:
        DLFLError: ``rings`` or ``sides`` below 3.
    """
    if rings < 3 or sides < 3:
        raise DLFLError(f"torus needs at least 3 rings and 3 sides, got {rings} and {sides}")
    u = np.arange(rings) * (2 * np.pi / rings)
    v = np.arange(sides) * (2 * np.pi / sides)
    uu, vv = np.meshgrid(u, v, indexing="ij")
    radius = major + minor * np.cos(vv)
    positions = np.stack([radius * np.cos(uu), minor * np.sin(vv), radius * np.sin(uu)], -1)
    i, j = np.meshgrid(np.arange(rings), np.arange(sides), indexing="ij")
    i1, j1 = (i + 1) % rings, (j + 1) % sides
    quads = np.stack([i * sides + j, i * sides + j1, i1 * sides + j1, i1 * sides + j], -1)
    return from_polygons(positions.reshape(-1, 3), quads.reshape(-1, 4))


def grid(nx: int = 4, ny: int = 4, size: float = 1.0) -> Mesh:
    """An open ``nx`` by ``ny`` quad grid in the xz plane facing +y (one hole face)."""
    if nx < 1 or ny < 1:
        raise DLFLError(f"grid needs at least 1x1 cells, got {nx}x{ny}")
    x, z = np.meshgrid(np.linspace(0, size * nx, nx + 1), np.linspace(0, size * ny, ny + 1),
                       indexing="ij")
    positions = np.stack([x, np.zeros_like(x), z], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    row = ny + 1
    quads = np.stack([i * row + j, i * row + j + 1, (i + 1) * row + j + 1, (i + 1) * row + j], -1)
    return from_polygons(positions, quads.reshape(-1, 4))


SHAPES: dict[str, Callable[[], Mesh]] = {
    "cube": cube,
    "tetrahedron": tetrahedron,
    "octahedron": octahedron,
    "icosahedron": icosahedron,
    "dodecahedron": dodecahedron,
    "torus": torus,
    "grid": grid,
}


def load_shape(name: str) -> Mesh:
    """A built-in shape by name (``"cube"``, ``"soccerball"``, ...), with or without ``.obj``.

    Raises:
        DLFLError: no shape has that name (the message lists them).
    """
    key = name.lower().removesuffix(".obj")
    if key not in SHAPES:
        raise DLFLError(
            f"no file {name!r} and no built-in shape of that name; shapes: {', '.join(SHAPES)}"
        )
    return SHAPES[key]()
