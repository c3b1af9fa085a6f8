"""Primitive shapes, built procedurally (no files on disk).

Each function returns a new :class:`Mesh`; :func:`load_shape` finds one by name.
The cube has exactly the layout of TopMod's ``cube.obj`` (vertices at ±1, the same
face order and orientation), so counts and positions compare with TopMod directly.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from .analysis import face_centroids
from .arrays import MeshArrays, mesh_arrays
from .build import from_polygons
from .errors import InvalidArgumentError, unknown_name
from .mesh import Mesh
from .soup import offsets_of
from .wireframe import vertex_rings

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
    a = mesh_arrays(icosahedron())
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
        raise InvalidArgumentError(
            f"torus needs at least 3 rings and 3 sides, got {rings} and {sides}")
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
    """An open ``nx`` by ``ny`` quad grid in the xz plane facing +y (one hole face).

    Raises:
        DLFLError: fewer than 1 cell along a side.
    """
    if nx < 1 or ny < 1:
        raise InvalidArgumentError(f"grid needs at least 1x1 cells, got {nx}x{ny}")
    x, z = np.meshgrid(np.linspace(0, size * nx, nx + 1), np.linspace(0, size * ny, ny + 1),
                       indexing="ij")
    positions = np.stack([x, np.zeros_like(x), z], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    row = ny + 1
    quads = np.stack([i * row + j, i * row + j + 1, (i + 1) * row + j + 1, (i + 1) * row + j], -1)
    return from_polygons(positions, quads.reshape(-1, 4))


def _truncated(mesh: Mesh, fraction: float) -> Mesh:
    """Cut every vertex of ``mesh`` at ``fraction`` of each edge (vertex truncation).

    Each face keeps its place with twice the corners; each vertex becomes a
    polygon of its valence, walked against ``vnext`` so it faces outward.
    """
    a = mesh_arrays(mesh)
    p = a.positions
    cv, mate = a.corner_vertex, a.corner_mate
    # the point of corner c lies on c's edge, ``fraction`` of the way from c's vertex
    points = p[cv] + fraction * (p[cv[a.corner_next]] - p[cv])
    pairs = np.stack([np.arange(len(cv)), mate], axis=1).ravel()
    sizes = np.concatenate([2 * a.face_sizes, np.bincount(cv)])
    ring, _ = vertex_rings(a)
    return from_polygons(points, np.concatenate([pairs, ring]), offsets_of(sizes))


def soccer_ball() -> Mesh:
    """The truncated icosahedron of TopMod's ``soccerball.obj``: 60/90/32 (12x5 + 20x6).

    The icosahedron with vertices ``(0, +-1, +-phi)`` cut at a third of every
    edge (circumradius 1.652, as in the file).
    """
    ico = icosahedron()
    ico.set_positions(ico.vertex_ids(), ico.positions_view() * np.sqrt(1 + GOLDEN**2))
    return _truncated(ico, 1.0 / 3.0)


def _on_sphere(positions: np.ndarray) -> np.ndarray:
    return positions / np.linalg.norm(positions, axis=1, keepdims=True)


def _centroid_fan(mesh: Mesh) -> tuple[np.ndarray, list[list[int]]]:
    """Positions and triangles of ``mesh`` with every face fanned from its centroid."""
    a = mesh_arrays(mesh)
    nv = len(a.vertex_ids)
    centres = face_centroids(a)
    tris = np.stack([a.corner_vertex, a.corner_vertex[a.corner_next], nv + a.corner_face], 1)
    return np.concatenate([a.positions, centres]), tris.tolist()


def _sqrt3_flip(positions: np.ndarray, triangles: list[list[int]]) -> Mesh:
    """Sqrt(3) refinement without smoothing: a centre per triangle, old edges flipped."""

    base = from_polygons(positions, triangles)
    a = mesh_arrays(base)
    nv = len(a.vertex_ids)
    centres = nv + a.corner_face[a.edge_corners]
    ends = a.corner_vertex[a.edge_corners]
    # edge a->b between centres z0 (a->b side) and z1 gives [a, z1, z0] and [b, z0, z1]
    tris = np.concatenate([
        np.stack([ends[:, 0], centres[:, 1], centres[:, 0]], 1),
        np.stack([ends[:, 1], centres[:, 0], centres[:, 1]], 1),
    ])
    return from_polygons(np.concatenate([a.positions, face_centroids(a)]), tris)


def geodesic_dome() -> Mesh:
    """A geodesic sphere with the counts of ``geodesicdome.obj``: 272/810/540 triangles.

    The soccer ball fanned from its face centroids (180 triangles), refined by
    sqrt(3) (a centre per triangle, old edges flipped) and projected to the unit
    sphere.
    """
    mesh = _sqrt3_flip(*_centroid_fan(soccer_ball()))
    mesh.set_positions(mesh.vertex_ids(), _on_sphere(mesh.positions_view()))
    return mesh


def buckminster() -> Mesh:
    """The dual of :func:`geodesic_dome` on the unit sphere, as ``buckminister.obj``:
    540/810/272 (12x5 + 260x6)."""
    return _dual_on_sphere(geodesic_dome())


def _dual_on_sphere(mesh: Mesh) -> Mesh:

    a = mesh_arrays(mesh)
    ring, offsets = vertex_rings(a)
    return from_polygons(_on_sphere(face_centroids(a)), a.corner_face[ring], offsets)


def spherical_cube(divisions: int = 4) -> Mesh:
    """A cube with every face cut into ``divisions`` x ``divisions`` quads, projected
    to the unit sphere; 4 gives ``sphericalcube.obj``'s 98/192/96.

    Raises:
        DLFLError: ``divisions`` below 1.
    """
    if divisions < 1:
        raise InvalidArgumentError(f"spherical_cube needs at least 1 division, got {divisions}")
    base = cube()
    points: dict[tuple[int, int, int], int] = {}
    faces = []
    n = divisions
    for f in base.face_ids():
        faces.extend(_face_grid(base.face_points(f), n, points))
    positions = np.array(list(points), dtype=np.float64) / n
    return from_polygons(_on_sphere(positions), faces)


def _face_grid(corners: np.ndarray, n: int, points: dict[tuple[int, int, int], int]) -> list[list[int]]:
    """Quads of one cube face cut n x n, vertices keyed by integer lattice position."""
    c0, c1, _, c3 = (np.rint(c * n).astype(int) for c in corners)
    du, dv = (c1 - c0) // n, (c3 - c0) // n

    def vid(i: int, j: int) -> int:
        key = tuple(int(x) for x in c0 + i * du + j * dv)
        return points.setdefault(key, len(points))  # type: ignore[arg-type]

    return [[vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)]
            for i in range(n) for j in range(n)]


def hex_torus(rings: int = 10, sides: int = 5, major: float = 0.87, minor: float = 0.37) -> Mesh:
    """A torus of hexagons, three at every vertex: ``rings * sides`` hexagons.

    The dual of a regularly triangulated ``rings`` x ``sides`` torus, vertices at
    the triangle centroids. 10 x 5 has ``donuthexa1.obj``'s counts, 100/150/50.

    Raises:
        DLFLError: ``rings`` or ``sides`` below 3.
    """
    a = mesh_arrays(torus(rings, sides, major, minor))
    # split every quad [a, b, c, d] along a-c
    quads = a.corner_vertex.reshape(-1, 4)
    triangles = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    return _dual(from_polygons(a.positions, triangles))


def _dual(mesh: Mesh) -> Mesh:
    """Dual with vertices at face centroids (not projected)."""
    a = mesh_arrays(mesh)
    ring, offsets = vertex_rings(a)
    return from_polygons(face_centroids(a), a.corner_face[ring], offsets)


def hex_refine(mesh: Mesh) -> Mesh:
    """One step of root-4 remeshing (TopMod's ``root4Subdivide(0, 0)`` topology).

    Every face gets an inner copy (the honeycomb weights on its edge
    midpoints); every edge becomes a hexagon of its two ends and the four inner
    points beside it. F -> F + E, E -> 4E, V -> V + 2E; hexagons stay
    hexagons, so ``donuthexa1`` refines to ``donuthexa3`` in two steps.
    """
    a = mesh_arrays(mesh)
    nv = len(a.vertex_ids)
    inner = _honeycomb_points(a)
    q = nv + np.arange(len(a.corner_vertex))
    nxt = a.corner_next
    c0, c1 = a.edge_corners[:, 0], a.edge_corners[:, 1]
    cv = a.corner_vertex
    hexes = np.stack([q[nxt[c0]], q[c0], cv[c0], q[nxt[c1]], q[c1], cv[c1]], 1).ravel()
    sizes = np.concatenate([a.face_sizes, np.full(len(c0), 6)])
    return from_polygons(np.concatenate([a.positions, inner]), np.concatenate([q, hexes]),
                         offsets_of(sizes))


def _honeycomb_points(a: MeshArrays) -> np.ndarray:
    """``(C, 3)`` root-4 inner point of every corner: sum_j w_ij m_j over the face's
    edge midpoints, w_ii = 1/sqrt(2) - 1/4 + 5/(4n),
    w_ij = (1 - w_ii)(3 + 2 cos(2 pi (i - j) / n)) / (3n - 5)."""
    p = a.positions
    mid = (p[a.corner_vertex] + p[a.corner_vertex[a.corner_next]]) / 2
    out = np.empty_like(mid)
    for f in range(len(a.face_ids)):
        lo, hi = a.face_offsets[f], a.face_offsets[f + 1]
        n = hi - lo
        k = np.arange(n)
        alpha = 2**-0.5 - 0.25 + 5 / (4 * n)
        w = (1 - alpha) * (3 + 2 * np.cos(2 * np.pi * (k[:, None] - k) / n)) / (3 * n - 5)
        np.fill_diagonal(w, alpha)
        out[lo:hi] = w @ mid[lo:hi]
    return out


def donut_hexa(level: int = 1) -> Mesh:
    """The hexagon torus ``donuthexa1`` (level 1, 100/150/50), refined by
    :func:`hex_refine` ``level - 1`` times: level 3 has ``donuthexa3``'s counts,
    1600/2400/800.

    Raises:
        DLFLError: ``level`` not 1, 2 or 3.
    """
    if level not in (1, 2, 3):
        raise InvalidArgumentError(f"donut_hexa level must be 1, 2 or 3, got {level}")
    mesh = hex_torus()
    for _ in range(level - 1):
        mesh = hex_refine(mesh)
    return mesh


def genus3_hexa(level: int = 1) -> Mesh:
    """A genus-3 hexagon mesh with the counts of ``genus3hexa1.obj`` (level 1:
    161/247/82, 80x6 + 2x7, 11 valence-4 vertices) and ``genus3hexa3.obj``
    (level 3, two :func:`hex_refine` steps: 2631/3952/1317, 1315x6 + 2x7).

    Built procedurally, not copied: three hexagon tori of 28, 30 and 28 faces in a
    row, glued where they touch (one hexagon removed from each side, the two
    rims identified: six valence-4 vertices per seam), then one seam vertex split
    in two, which turns the two faces beside the new edge into heptagons.

    Raises:
        DLFLError: ``level`` is not 1, 2 or 3.
    """
    if level not in (1, 2, 3):
        raise InvalidArgumentError(f"genus3_hexa level must be 1, 2 or 3, got {level}")
    mesh = _vertex_split(_glued_tori([(7, 4), (10, 3), (7, 4)]))
    for _ in range(level - 1):
        mesh = hex_refine(mesh)
    return mesh


def _glued_tori(sizes: list[tuple[int, int]], major: float = 0.3, minor: float = 0.13) -> Mesh:
    """Hexagon tori side by side along x, each glued to the next across the
    hexagons that face each other."""

    positions: list[np.ndarray] = []
    faces: list[list[int]] = []
    step = 2 * (major + minor)
    start = -step * (len(sizes) - 1) / 2
    for k, (rings, sides) in enumerate(sizes):
        a = mesh_arrays(hex_torus(rings, sides, major, minor))
        base = sum(len(p) for p in positions)
        positions.append(a.positions + [start + k * step, 0.0, 0.0])
        faces.extend((base + a.corner_vertex[a.face_offsets[f]:a.face_offsets[f + 1]]).tolist()
                     for f in range(len(a.face_ids)))
    pos = np.concatenate(positions)
    alias = np.arange(len(pos))
    for k in range(len(sizes) - 1):
        _glue(pos, faces, alias, start + (k + 0.5) * step)
    used = np.unique(alias)
    renumber = np.full(len(pos), -1)
    renumber[used] = np.arange(len(used))
    return from_polygons(pos[used], [[int(renumber[alias[v]]) for v in f] for f in faces])


def _glue(pos: np.ndarray, faces: list[list[int]], alias: np.ndarray, x: float) -> None:
    """Remove the two faces nearest the plane ``x`` from both sides and identify
    their rims (reversed, rotated to the closest match); positions averaged."""
    centres = np.array([pos[f].mean(axis=0) for f in faces])
    left = min((i for i in range(len(faces)) if centres[i, 0] < x),
               key=lambda i: np.linalg.norm(centres[i] - [x, 0, 0]))
    right = min((i for i in range(len(faces)) if centres[i, 0] > x),
                key=lambda i: np.linalg.norm(centres[i] - [x, 0, 0]))
    rim_l, rim_r = faces[left], faces[right][::-1]
    n = len(rim_l)
    shift = min(range(n), key=lambda s: sum(
        np.linalg.norm(pos[rim_l[i]] - pos[rim_r[(i + s) % n]]) for i in range(n)))
    for i in range(n):
        keep, drop = rim_l[i], rim_r[(i + shift) % n]
        pos[keep] = (pos[keep] + pos[drop]) / 2
        alias[alias == drop] = keep
    for i in sorted((left, right), reverse=True):
        del faces[i]


def _vertex_split(mesh: Mesh) -> Mesh:
    """Split one valence-4 vertex into two valence-3 vertices joined by a new edge.

    Around the vertex the faces are F1..F4 in rotation order; the new edge runs
    between F1 and F3, which each gain a corner; F2 keeps the old vertex and F4
    gets the new one.
    """
    v = next(v for v in mesh.vertex_ids().tolist() if mesh.valence(v) == 4)
    f1, f2, f3, f4 = mesh.vertex_faces(v)
    ids = mesh.vertex_ids().tolist()
    index = {vid: i for i, vid in enumerate(ids)}
    new = len(ids)
    faces = []
    for f in mesh.face_ids().tolist():
        ring = [index[u] for u in mesh.face_vertices(f)]
        if f in (f1, f3):
            ring = _insert_split(ring, index[v], new, mesh, f, f2, index)
        elif f == f4:
            ring = [new if u == index[v] else u for u in ring]
        faces.append(ring)
    pos = mesh.positions_view()
    centre = np.mean([pos[index[u]] for u in mesh.face_vertices(f4)], axis=0)
    pos = np.concatenate([pos, [pos[index[v]] * 0.7 + centre * 0.3]])
    return from_polygons(pos, faces)


def _insert_split(ring: list[int], old: int, new: int, mesh: Mesh, face: int, keeper: int,
                  index: dict[int, int]) -> list[int]:
    """Replace ``old`` in ``ring`` by the pair (old, new) or (new, old): ``old`` stays
    on the side shared with face ``keeper``."""
    i = ring.index(old)
    after = ring[(i + 1) % len(ring)]
    keeper_ring = [index[u] for u in mesh.face_vertices(keeper)]
    shares_after = after in keeper_ring
    pair = [new, old] if shares_after else [old, new]
    return ring[:i] + pair + ring[i + 1:]


def genus_torus(genus: int = 2, thickness: float = 0.5) -> Mesh:
    """A quad slab with ``genus`` square holes in a row: a closed surface of that genus.

    A (2g+1) x 3 grid of unit cells with every other middle cell left out, its
    top and bottom joined by side quads along every boundary. Genus 0 is a box.

    Raises:
        DLFLError: ``genus`` negative or ``thickness`` not positive.
    """
    if genus < 0 or thickness <= 0:
        raise InvalidArgumentError(
            f"genus_torus needs genus >= 0 and thickness > 0, got {genus}, {thickness}")
    nx, ny = 2 * genus + 1, 3
    kept = [(i, j) for i in range(nx) for j in range(ny) if not (j == 1 and i % 2 == 1)]
    row = ny + 1
    top = lambda i, j: i * row + j  # noqa: E731
    nvtop = (nx + 1) * row
    faces = []
    for i, j in kept:
        quad = [top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1)]
        faces.append(quad)
        faces.append([v + nvtop for v in reversed(quad)])
    faces.extend(_slab_sides(set(kept), nx, ny, nvtop, top))
    x, y = np.meshgrid(np.arange(nx + 1, dtype=float), np.arange(ny + 1, dtype=float), indexing="ij")
    grid_xy = np.stack([x.ravel(), y.ravel()], 1)
    positions = np.concatenate([
        np.column_stack([grid_xy, np.full(nvtop, thickness / 2)]),
        np.column_stack([grid_xy, np.full(nvtop, -thickness / 2)]),
    ])
    return from_polygons(positions, faces)


def _slab_sides(kept: set[tuple[int, int]], nx: int, ny: int, nvtop: int,
                top: Callable[[int, int], int]) -> list[list[int]]:
    """Side quads under every edge of a kept cell whose neighbour cell is missing."""
    sides = []
    for i, j in kept:
        ring = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
        across = [(i, j - 1), (i + 1, j), (i, j + 1), (i - 1, j)]
        for k in range(4):
            if across[k] in kept:
                continue
            a, b = top(*ring[k]), top(*ring[(k + 1) % 4])
            sides.append([b, a, a + nvtop, b + nvtop])
    return sides


SHAPES: dict[str, Callable[[], Mesh]] = {
    "cube": cube,
    "tetrahedron": tetrahedron,
    "octahedron": octahedron,
    "icosahedron": icosahedron,
    "dodecahedron": dodecahedron,
    "torus": torus,
    "grid": grid,
    "soccerball": soccer_ball,
    "geodesicdome": geodesic_dome,
    "buckminster": buckminster,
    "buckminister": buckminster,
    "sphericalcube": spherical_cube,
    "hextorus": hex_torus,
    "donuthexa1": lambda: donut_hexa(1),
    "donuthexa3": lambda: donut_hexa(3),
    "genus3hexa1": lambda: genus3_hexa(1),
    "genus3hexa3": lambda: genus3_hexa(3),
    "genustorus": genus_torus,
}


def load_shape(name: str) -> Mesh:
    """A built-in shape by name (``"cube"``, ``"soccerball"``, ...), with or without ``.obj``.

    Raises:
        DLFLError: no shape has that name (the message lists them).
    """
    key = name.lower().removesuffix(".obj")
    if key not in SHAPES:
        raise InvalidArgumentError(unknown_name("no file and no built-in shape named", name,
                                                SHAPES, "shapes"))
    return SHAPES[key]()
