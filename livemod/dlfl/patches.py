"""TopMod's patch preview: one bicubic Bézier patch per corner over level-2 Doo-Sabin.

The rule (TopMod's ``TMPatch*`` classes, TOPMOD.md section 7), vectorized over
every corner at once. ``DS(P)`` below is the Doo-Sabin rule applied to a polygon
``P`` of ``n`` points: ``p_i' = sum_j w_ij p_j`` with ``w_ii = 1/4 + 5/(4n)`` and
``w_ij = (3 + 2 cos(2 pi (i - j) / n)) / (4n)``.

* Level 1: each face's corners get ``L1 = DS(face's vertex positions)``.
* Level 2, four points per corner ``c`` (``level2[c, k]``):
  ``k = 2`` from its face, ``DS(L1 of the face)``; ``k = 1`` and ``k = 3`` from
  the edge after and before ``c``: each edge ``e`` with sides ``(c0, c1)`` gives
  ``DS([L1[next c0], L1[c0], L1[next c1], L1[c1]])``, whose points go to
  ``level2[next c0, 3]``, ``level2[c0, 1]``, ``level2[next c1, 3]`` and
  ``level2[c1, 1]``; ``k = 0`` from its vertex, ``DS(L1 of the corners around
  the vertex in vnext order)``.
* Each of those level-2 polygons gives a point (its centroid) and a normal (its
  normalised Newell sum; a vertex's is negated, since vnext turns clockwise):
  the vertex, edge and face points.
* The patch of corner ``c`` (vertex ``v``, face ``f``, edge ``e`` to the next
  corner, edge ``e'`` from the previous one) has corners ``P[0, 0]`` = the point of
  ``v``, ``P[3, 0]`` = the point of ``e``, ``P[3, 3]`` = the point of ``f`` and
  ``P[0, 3]`` = the point of ``e'``. The eight other boundary points are level-2
  points of ``c`` and of its neighbour across that side, both projected into the
  tangent plane of the nearer patch corner; the point is where the segment between
  the two crosses the side's line (``_split``). The four inner points are ``c``'s
  own level-2 points projected into the nearest corner's tangent plane. Every
  non-corner point is then pushed 4/3 of its way from its nearest corner.
* Control normals: the four corners' normals; the others blend them,
  ``normalize(3 n_near + n_along)`` beside a corner on a side and
  ``normalize(6 n_near + n_side1 + n_side2)`` inside.
* Then three passes make neighbours meet: each edge's point is re-placed where
  the line through its two neighbouring side points crosses the line through the
  two face-side points (shared by the four patches around it); a vertex with four
  corners gets the crossing of its two pairs of opposite side points; a quad's face
  point the crossing of its opposite inner side points.

Neighbouring patches share their boundary control points: each boundary point
is computed once, by the corner owning that side (the rule gives its neighbour
the same point, the two level-2 points swapped), and read by both. So the
surface is continuous, to the bit; its control normals agree along the
boundaries too, so it shades smooth. Degenerate cases, decided here (TopMod divides by zero on them):

* Point-spheres (a face of one corner with no edge) get no patch.
* A hole face gets no patch, but its corners take part in the rule as a face's
  would: the patches around a hole end on the curve the hole's own patches would
  have shared.
* A 2-gon gets its two patches; its face point is the middle of its two level-2
  points and its face normal is zero (no plane: the projections into it are
  skipped, and its blends use the other normals). The same holds for a vertex
  with two corners.
* A one-corner face with an edge (a loop) uses its point as its own Doo-Sabin
  point (the rule's weights would sum to 1.5).
* Where two lines to cross are the same line, or a line has no length, the point
  between the two candidates is taken (half way). A polygon of level-2 points with
  no area to speak of (a Newell vector below ``FLAT`` times its spread) has a zero
  normal, as have blends too short to have a direction.
* Patches with a point that is not finite (a vertex at NaN or inf nearby) are
  left out.

Arrays are computed in a frame centred on the mesh and scaled by a power of two, so
huge or tiny coordinates cost no precision and cross products do not overflow.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .analysis import vertex_normals
from .arrays import MeshArrays, mesh_arrays
from .colors import rgba_bytes
from .errors import InvalidArgumentError
from .mesh import Mesh
from .soup import offsets_of

__all__ = ["CornerPatches", "PatchNet", "Tessellation", "evaluate_patches", "mesh_surface",
           "patch_control_points"]

PUSH = 4.0 / 3.0
MAX_DENSITY = 32
# corners worked on at a time where the work is a long chain of array operations:
# small enough for the temporaries to stay in the cache
CHUNK = 4096
FLAT = 1e-10

# Control point (i, j) is row 4 i + j of a net; the four corners of a patch are
# named V (its vertex's point), E (the point of the edge after the corner), F (its
# face's point) and D (the point of the edge before it).
_CORNER_ROWS = {"V": 0, "E": 12, "F": 15, "D": 3}


def _normal_blend() -> np.ndarray:
    """``(16, 4)`` weights of the corner normals (V, E, F, D) in each control
    normal (TopMod's blends; the corners keep their own)."""
    names = "VEFD"
    beside = {4: ("V", "E"), 1: ("V", "D"), 8: ("E", "V"), 13: ("E", "F"), 14: ("F", "E"),
              11: ("F", "D"), 7: ("D", "F"), 2: ("D", "V")}
    inside = {5: ("V", "E", "D"), 9: ("E", "V", "F"), 10: ("F", "E", "D"), 6: ("D", "V", "F")}
    blend = np.zeros((16, 4))
    for name, row in _CORNER_ROWS.items():
        blend[row, names.index(name)] = 1.0
    for row, (near, along) in beside.items():
        blend[row, names.index(near)] = 3.0
        blend[row, names.index(along)] = 1.0
    for row, (near, side1, side2) in inside.items():
        blend[row, names.index(near)] = 6.0
        blend[row, [names.index(side1), names.index(side2)]] = 1.0
    return blend


NORMAL_BLEND = _normal_blend()


@dataclass(frozen=True)
class PatchNet:
    """The control nets of a set of corner patches, coordinate-major.

    Attributes:
        columns: ``(16, 3, P)`` float64: ``columns[4 i + j, :, p]`` is control
            point ``(i, j)`` of patch ``p``; ``i`` runs from the corner's vertex
            point toward the point of the edge after the corner, ``j`` toward the
            point of the edge before it (so ``d/di x d/dj`` points out of the face).
        normal_columns: ``(16, 3, P)`` float64 control normals, unit (zero where a
            blend has no direction).
        corners: ``(P,)`` int64 dense corner index (in :func:`mesh_arrays` order)
            of each patch.
    """

    columns: np.ndarray
    normal_columns: np.ndarray
    corners: np.ndarray

    def __len__(self) -> int:
        return len(self.corners)

    @property
    def points(self) -> np.ndarray:
        """``(P, 4, 4, 3)`` float64 control points, ``points[p, i, j]`` (a copy)."""
        return self.columns.transpose(2, 0, 1).reshape(-1, 4, 4, 3)

    @property
    def normals(self) -> np.ndarray:
        """``(P, 4, 4, 3)`` float64 control normals, as :attr:`points`."""
        return self.normal_columns.transpose(2, 0, 1).reshape(-1, 4, 4, 3)


@dataclass(frozen=True)
class Tessellation:
    """Patches evaluated on a grid, as triangles ready to draw.

    Attributes:
        positions: ``(N, 3)`` float32 surface points, ``(density + 1)**2`` per
            patch, patch after patch; row ``a * (density + 1) + b`` of a patch is at
            parameters ``(a / density, b / density)``.
        normals: ``(N, 3)`` float32 unit normals at those points (zero where the
            surface has none).
        triangles: ``(T, 3)`` uint32 indices into ``positions``,
            ``2 * density**2`` per patch, counter-clockwise seen from outside.
        density: the grid's steps along each side of a patch (0 for a surface
            that is not made of patches, see :func:`mesh_surface`).
        colors: ``(N, 4)`` uint8 RGBA of the face each point belongs to (see
            :func:`~livemod.dlfl.colors.rgba_bytes`: all zero where the face has no
            colour), or None when no face of the mesh has one. Faces of a
            coloured surface share a point only when they have one colour, so
            that a triangle's three corners carry its face's colour.
    """

    positions: np.ndarray
    normals: np.ndarray
    triangles: np.ndarray
    density: int
    colors: np.ndarray | None = None

    @property
    def nbytes(self) -> int:
        """Bytes of the arrays."""
        own = 0 if self.colors is None else self.colors.nbytes
        return self.positions.nbytes + self.normals.nbytes + self.triangles.nbytes + own


def mesh_surface(mesh: Mesh | MeshArrays) -> Tessellation:
    """A mesh's own faces as a smooth surface: the fans of
    :meth:`MeshArrays.fan_triangles`, with the normalised sum of the face normals
    around each vertex (how a subdivided preview is drawn; ``density`` 0). A point
    per vertex; with face colours, a point per vertex and colour of the faces
    around it (see :attr:`Tessellation.colors`)."""
    a = mesh if isinstance(mesh, MeshArrays) else mesh_arrays(mesh)
    corners, _ = a.fan_triangles()
    normals = vertex_normals(a).astype(np.float32)
    triangles = np.take(a.corner_vertex, corners)
    rgba = rgba_bytes(a.face_colors)
    if rgba is None:
        return Tessellation(a.positions.astype(np.float32), normals,
                            triangles.astype(np.uint32), 0)
    used, colors, index = _points_by_color(triangles.ravel(), np.take(a.corner_face, corners),
                                           rgba, len(a.positions))
    return Tessellation(np.take(a.positions, used, axis=0).astype(np.float32),
                        np.take(normals, used, axis=0), index.reshape(-1, 3).astype(np.uint32),
                        0, colors)


def patch_control_points(mesh: Mesh | MeshArrays,
                         corners: np.ndarray | None = None) -> PatchNet:
    """TopMod's control nets of the corner patches of ``mesh`` (see the module).

    Args:
        mesh: a mesh or its arrays (not changed).
        corners: ``(k,)`` dense corner indices to make patches for; None for
            every corner of every face drawn (not a hole, not a point-sphere).
            Corners of holes and point-spheres in it are left out.

    Returns:
        the nets, in the order of ``corners``, without the patches that have a
        point that is not finite.
    """
    return CornerPatches(mesh).nets(corners)


def evaluate_patches(net: PatchNet, density: int) -> Tessellation:
    """The patches of ``net`` on a ``(density + 1) x (density + 1)`` grid each.

    Normals are the Bézier blend of the control normals, normalised (neighbouring
    patches' agree along their boundary, so the shading is smooth); where that
    blend vanishes, the surface's own normal (the cross product of its
    derivatives); zero where neither has a direction.

    Raises:
        InvalidArgumentError: ``density`` is not an int in [1, MAX_DENSITY].
    """
    grid = Grid(_check_density(density))
    positions = np.empty((len(net), grid.size, 3), dtype=np.float32)
    normals = np.empty_like(positions)
    grid.evaluate(net.columns, net.normal_columns, positions, normals)
    return Tessellation(positions.reshape(-1, 3), normals.reshape(-1, 3),
                        grid_triangles(len(net), grid.steps), grid.steps)


class Grid:
    """The ``(steps + 1)**2`` parameters a patch is evaluated at (row ``a * (steps +
    1) + b`` at ``(a / steps, b / steps)``) and their Bernstein weights."""

    def __init__(self, steps: int) -> None:
        self.steps = steps
        self.size = (steps + 1) ** 2
        t = np.linspace(0.0, 1.0, steps + 1)
        self.basis, self.slope = bernstein(t), _bernstein_slope(t)
        self.weights = np.kron(self.basis, self.basis)      # (G, 16)

    def evaluate(self, columns: np.ndarray, control_normals: np.ndarray,
                 positions: np.ndarray, normals: np.ndarray) -> None:
        """Write the grid points of the ``(16, 3, P)`` ``columns`` into
        ``positions`` ``(P, G, 3)`` and their normals (from ``control_normals``,
        see :func:`evaluate_patches`) into ``normals``."""
        blended = _unit(_blend(self.weights, control_normals))
        flat = np.logical_not(np.any(blended, axis=1))      # (G, P)
        if flat.any():
            self._fill_surface_normals(columns, blended, flat)
        positions[...] = _blend(self.weights, columns).transpose(2, 0, 1)
        normals[...] = blended.transpose(2, 0, 1)

    def _fill_surface_normals(self, columns: np.ndarray, normals: np.ndarray,
                              flat: np.ndarray) -> None:
        """Write the surface's own normal into ``normals`` ``(G, 3, P)`` where
        ``flat`` ``(G, P)`` (the control normals blend to nothing there)."""
        patches = np.flatnonzero(flat.any(axis=0))
        some = columns[:, :, patches]
        with np.errstate(invalid="ignore", over="ignore"):
            own = _unit(_cross(_blend(np.kron(self.slope, self.basis), some),
                               _blend(np.kron(self.basis, self.slope), some), axis=1))
        chosen = normals[:, :, patches]
        where = np.broadcast_to(flat[:, None, patches], chosen.shape)
        chosen[where] = own[where]
        normals[:, :, patches] = chosen


def doo_sabin_weights(n: int) -> np.ndarray:
    """``(n, n)`` Doo-Sabin weights of a polygon of ``n`` points: ``w_ii = 1/4 +
    5/(4n)``, ``w_ij = (3 + 2 cos(2 pi (i - j) / n)) / (4n)``; ``[[1]]`` for one point
    (the rule's would sum to 1.5)."""
    if n == 1:
        return np.ones((1, 1))
    k = np.arange(n)[:, None] - np.arange(n)[None, :]
    weights = (3.0 + 2.0 * np.cos(2.0 * np.pi * k / n)) / (4.0 * n)
    np.fill_diagonal(weights, 0.25 + 1.25 / n)
    return weights


def _check_density(density: object) -> int:
    if isinstance(density, bool) or not isinstance(density, (int, np.integer)) \
            or not 1 <= density <= MAX_DENSITY:
        raise InvalidArgumentError(
            f"density must be an int from 1 to {MAX_DENSITY}, got {density!r}")
    return int(density)


def bernstein(t: np.ndarray) -> np.ndarray:
    """``(n, 4)`` cubic Bernstein polynomials at parameters ``t`` ``(n,)``."""
    s = 1.0 - t
    return np.stack([s**3, 3.0 * t * s**2, 3.0 * t**2 * s, t**3], axis=1)


def _bernstein_slope(t: np.ndarray) -> np.ndarray:
    """``(n, 4)`` derivatives of :func:`bernstein` at ``t``."""
    s = 1.0 - t
    return np.stack([-3.0 * s**2, 3.0 * s**2 - 6.0 * t * s, 6.0 * t * s - 3.0 * t**2,
                     3.0 * t**2], axis=1)


def _blend(weights: np.ndarray, columns: np.ndarray) -> np.ndarray:
    """``(G, 3, P)``: the ``(16, 3, P)`` ``columns`` weighted by ``(G, 16)``
    ``weights`` (one matrix product for every patch at once)."""
    return np.einsum("gs,sxp->gxp", weights, columns)


def grid_triangles(count: int, density: int) -> np.ndarray:
    """``(count * 2 * density**2, 3)`` uint32 triangles of ``count`` grids of
    ``(density + 1)**2`` points laid out as :class:`Tessellation` says."""
    side = density + 1
    a, b = np.meshgrid(np.arange(density), np.arange(density), indexing="ij")
    base = (a * side + b).ravel()
    quad = np.stack([base, base + side, base + side + 1, base, base + side + 1, base + 1],
                    axis=1).reshape(-1, 3).astype(np.uint32)
    offsets = np.arange(count, dtype=np.uint32)[:, None, None] * np.uint32(side * side)
    return (quad[None] + offsets).reshape(-1, 3)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``(N,)`` dot products of the ``(3, N)`` columns of ``a`` and ``b``."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a: np.ndarray, b: np.ndarray, axis: int = 0) -> np.ndarray:
    """Cross products of ``a`` and ``b`` whose coordinates run along ``axis``."""
    a, b = np.moveaxis(a, axis, 0), np.moveaxis(b, axis, 0)
    out = np.stack([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2],
                    a[0] * b[1] - a[1] * b[0]])
    return np.moveaxis(out, 0, axis)


def _unit(vectors: np.ndarray) -> np.ndarray:
    """``vectors`` (coordinates along axis 0 or, for 3-D arrays, axis 1) scaled to
    unit length; those of length zero (or not finite) become zero."""
    axis = 1 if vectors.ndim == 3 else 0
    coordinates = np.moveaxis(vectors, axis, 0)
    length2 = coordinates[0] * coordinates[0]
    length2 += coordinates[1] * coordinates[1]
    length2 += coordinates[2] * coordinates[2]
    with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
        scale = 1.0 / np.sqrt(length2)
    scale[~np.isfinite(scale) | (length2 < 1e-300)] = 0.0
    return vectors * np.expand_dims(scale, axis)


@dataclass(frozen=True)
class _Rings:
    """Polygons laid out one after another in ``(3, N)`` columns: ring ``r`` owns
    columns ``offsets[r]:offsets[r + 1]`` (at least one each), in order."""

    offsets: np.ndarray

    @property
    def sizes(self) -> np.ndarray:
        return np.diff(self.offsets)

    @property
    def ring(self) -> np.ndarray:
        """``(N,)`` ring of each column."""
        return np.repeat(np.arange(len(self.sizes)), self.sizes)

    def _sums(self, values: np.ndarray) -> np.ndarray:
        """``(3, R)`` each ring's sum of ``(3, N)`` ``values``."""
        if len(self.sizes) == 0:
            return np.zeros((3, 0))
        return np.add.reduceat(values, self.offsets[:-1], axis=1)

    def doo_sabin(self, points: np.ndarray) -> np.ndarray:
        """``(3, N)`` the Doo-Sabin points of every ring of ``(3, N)`` ``points``
        (a ring of one point keeps it)."""
        sizes = self.sizes
        if len(sizes) and sizes[0] == sizes.min() == sizes.max():
            # one size (all quads, say): one matrix for every ring
            n = int(sizes[0])
            rings = points.reshape(3, -1, n)
            # (einsum, not matmul: BLAS is slower for these tiny matrices)
            return np.einsum("xri,ji->xrj", rings, doo_sabin_weights(n)).reshape(3, -1)
        return self._doo_sabin_any(points)

    def _doo_sabin_any(self, points: np.ndarray) -> np.ndarray:
        """:meth:`doo_sabin` for rings of any sizes, in time linear in the sizes:
        ``sum_j w_ij p_j = p_i / 4 + 3 S / (4n) + (cos t_i A + sin t_i B) / (2n)``
        with ``t_i = 2 pi i / n``, ``S`` the sum of the ring's points and ``A``,
        ``B`` their sums weighted by ``cos t_j`` and ``sin t_j``."""
        ring = self.ring
        n = np.take(self.sizes, ring).astype(np.float64)
        angle = (2.0 * np.pi) * (np.arange(len(ring)) - np.take(self.offsets, ring)) / n
        cos, sin = np.cos(angle), np.sin(angle)
        spread = [np.take(sums, ring, axis=1) for sums in
                  (self._sums(points), self._sums(points * cos), self._sums(points * sin))]
        out = 0.25 * points + (0.75 / n) * spread[0] + (0.5 / n) * (cos * spread[1]
                                                                     + sin * spread[2])
        single = n == 1.0
        out[:, single] = points[:, single]
        return out

    def centroids(self, points: np.ndarray) -> np.ndarray:
        """``(3, R)`` mean of each ring's points."""
        return self._sums(points) / np.maximum(self.sizes, 1)

    def normals(self, points: np.ndarray, centroids: np.ndarray) -> np.ndarray:
        """``(3, R)`` unit Newell normal of each ring, taken about its centroid;
        zero for a ring with no area to speak of (fewer than three points, or a
        Newell vector below ``FLAT`` times the sum of its squared distances from
        the centroid: rounding noise, with no direction worth having)."""
        sizes = self.sizes
        if len(sizes) and sizes[0] == sizes.min() == sizes.max() and sizes[0] in (3, 4):
            newell, spread = _small_newell(points.reshape(3, len(sizes), -1), centroids)
        else:
            following = np.arange(1, points.shape[1] + 1)
            following[self.offsets[1:] - 1] = self.offsets[:-1]
            rel = points - np.take(centroids, self.ring, axis=1)
            newell = self._sums(_cross(rel, np.take(rel, following, axis=1)))
            spread = self._sums(rel * rel).sum(axis=0)
        newell[:, np.sqrt(_dot(newell, newell)) <= FLAT * spread] = 0.0
        return _unit(newell)


def _small_newell(rings: np.ndarray, centroids: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The Newell vectors ``(3, R)`` of triangles or quads ``rings`` ``(3, R, n)``
    and their points' squared distances from their ``centroids``, summed ``(R,)``:
    a triangle's is the cross product of two sides, a quad's that of its diagonals
    (each equals the Newell sum, with one product instead of n)."""
    first, second = (rings[:, :, 1] - rings[:, :, 0], rings[:, :, 2] - rings[:, :, 0]) \
        if rings.shape[2] == 3 else (rings[:, :, 2] - rings[:, :, 0],
                                     rings[:, :, 3] - rings[:, :, 1])
    rel = rings - centroids[:, :, None]
    return _cross(first, second), (rel * rel).sum(axis=(0, 2))


def cycle_layout(successor: np.ndarray, longest: int) -> tuple[np.ndarray, np.ndarray]:
    """The cycles of the permutation ``successor`` ``(N,)`` laid out as rings.

    Each cycle starts at its smallest element and follows ``successor``; cycles
    come in the order of their smallest elements. ``longest`` (at least the
    length of the longest cycle) bounds the rounds of pointer doubling:
    O(N log longest).

    Returns:
        ``(order (N,), offsets (R + 1,))``: the elements in ring order, and where
        each ring starts in ``order``.
    """
    count = len(successor)
    rounds = max(int(longest) - 1, 0).bit_length()     # ceil(log2(longest))
    index = np.arange(count, dtype=np.int64)
    head, jump = index.copy(), successor.astype(np.int64)
    for _ in range(rounds):
        head = np.minimum(head, np.take(head, jump))
        jump = np.take(jump, jump)
    # steps to the cycle's last element (the one before its head): list ranking
    last = successor == head
    link = np.where(last, index, successor)
    to_end = (~last).astype(np.int64)
    for _ in range(rounds):
        to_end += np.take(to_end, link)
        link = np.take(link, link)
    is_head = head == index
    ring = np.take(np.cumsum(is_head) - 1, head)
    sizes = np.bincount(ring, minlength=int(is_head.sum()))
    offsets = offsets_of(sizes)
    order = np.empty(count, dtype=np.int64)
    order[np.take(offsets[1:], ring) - 1 - to_end] = index
    return order, offsets


class CornerPatches:
    """The level-2 Doo-Sabin points of a mesh and the boundary points they give,
    from which any corner's patch is made (see the module): computed once, then
    ask :meth:`nets` for the patches of any corners.

    Args:
        mesh: a mesh or its arrays (not changed; arrays are kept, not copied).
    """

    def __init__(self, mesh: Mesh | MeshArrays) -> None:
        a = mesh if isinstance(mesh, MeshArrays) else mesh_arrays(mesh)
        self.arrays = a
        self.center, self.scale = _frame(a.positions)
        self.next, self.prev, self.vnext = a.corner_next, a.corner_prev, a.corner_vnext
        self.vprev = np.empty_like(self.vnext)
        self.vprev[self.vnext] = np.arange(len(self.vnext))
        # corners with no edge (point-spheres) read edge 0: what they get is never used
        self.edge = np.maximum(a.corner_edge, 0)
        self.edge_before = np.take(self.edge, self.prev)
        with np.errstate(invalid="ignore", over="ignore", divide="ignore"):
            self._level2()
            self._sides()
            self._snap()

    def _level2(self) -> None:
        """Level 1 and 2 points, and the vertex, edge and face points and normals."""
        a = self.arrays
        corner_points = np.take(a.positions, a.corner_vertex, axis=0) - self.center
        points = np.ascontiguousarray(corner_points.T) / self.scale
        faces = _Rings(a.face_offsets)
        level1 = faces.doo_sabin(points)
        self.level2 = np.zeros((4, 3, len(a.corner_vertex)))
        self.level2[2] = faces.doo_sabin(level1)
        self.face_point = faces.centroids(self.level2[2])
        self.face_normal = faces.normals(self.level2[2], self.face_point)
        self._edges(level1)
        self._vertices(level1)

    def _edges(self, level1: np.ndarray) -> None:
        """Each edge's quad of level-1 points, its Doo-Sabin points, point and normal."""
        c0, c1 = self.arrays.edge_corners[:, 0], self.arrays.edge_corners[:, 1]
        quad = np.stack([np.take(self.next, c0), c0, np.take(self.next, c1), c1], axis=1)
        rings = _Rings(np.arange(0, 4 * len(c0) + 1, 4))
        points = rings.doo_sabin(np.take(level1, quad.ravel(), axis=1))
        for k, slot in enumerate((3, 1, 3, 1)):
            self.level2[slot][:, quad[:, k]] = points[:, k::4]
        self.edge_point = rings.centroids(points)
        self.edge_normal = rings.normals(points, self.edge_point)

    def _vertices(self, level1: np.ndarray) -> None:
        """The rings of corners around each vertex (vnext order), their points and
        normals (negated: vnext turns clockwise seen from outside)."""
        a = self.arrays
        longest = int(np.bincount(a.corner_vertex).max()) if len(a.corner_vertex) else 1
        order, offsets = cycle_layout(self.vnext, longest)
        rings = _Rings(offsets)
        self.vertex_rings = (order, offsets)
        self.ring_of = np.empty(len(order), dtype=np.int64)
        self.ring_of[order] = rings.ring
        points = rings.doo_sabin(np.take(level1, order, axis=1))
        self.level2[0][:, order] = points
        self.vertex_point = rings.centroids(points)
        self.vertex_normal = -rings.normals(points, self.vertex_point)

    def _corner_frame(self, corners: np.ndarray, snapped: bool = False,
                     ) -> tuple[dict[str, np.ndarray], dict[str, np.ndarray]]:
        """The points and normals of the patch corners (V, E, F, D: ``(3, k)``
        each) of dense ``corners`` ``(k,)``, before or after the passes that make
        neighbours meet."""
        face, ring = np.take(self.arrays.corner_face, corners), np.take(self.ring_of, corners)
        edge, before = np.take(self.edge, corners), np.take(self.edge_before, corners)
        if snapped:
            sources = (self.snapped_vertex, self.snapped_edge, self.snapped_face)
        else:
            sources = (self.vertex_point, self.edge_point, self.face_point)
        where = {"V": (sources[0], ring), "E": (sources[1], edge), "F": (sources[2], face),
                 "D": (sources[1], before)}
        normals = {"V": self.vertex_normal, "E": self.edge_normal, "F": self.face_normal,
                   "D": self.edge_normal}
        points = {k: np.take(table, index, axis=1) for k, (table, index) in where.items()}
        return points, {k: np.take(normals[k], where[k][1], axis=1) for k in where}

    def _sides(self) -> None:
        """The boundary and inner control points of every corner's patch that the
        corner owns (see the module): ``side[0..3]`` are points (1, 0), (2, 0),
        (3, 1), (3, 2); ``inner[0..3]`` are (1, 1), (2, 1), (2, 2), (1, 2). The
        other four boundary points of a patch are its neighbours' (across the
        side). Made a slice of corners at a time, so that the temporaries stay in
        the cache."""
        count = len(self.next) if len(self.arrays.edge_ids) else 0
        self.side = np.empty((4, 3, count))
        self.inner = np.empty((4, 3, count))
        for start in range(0, count, CHUNK):
            part = np.arange(start, min(start + CHUNK, count))
            self._sides_of(part, self.side[:, :, start:start + CHUNK],
                           self.inner[:, :, start:start + CHUNK])

    def _sides_of(self, corners: np.ndarray, side: np.ndarray, inner: np.ndarray) -> None:
        """:meth:`_sides` of ``corners`` ``(k,)``, into ``side`` and ``inner``
        ``(4, 3, k)``."""
        point, normal = self._corner_frame(corners)
        own = np.take(self.level2, corners, axis=2)
        vnext, nxt = np.take(self.vnext, corners), np.take(self.next, corners)
        side[0] = _side(point["V"], point["E"], own[0], np.take(self.level2[0], vnext, axis=1),
                        normal["V"])
        side[1] = _side(point["E"], point["V"], own[1], np.take(self.level2[3], vnext, axis=1),
                        normal["E"])
        side[2] = _side(point["E"], point["F"], own[1], np.take(self.level2[3], nxt, axis=1),
                        normal["E"])
        side[3] = _side(point["F"], point["E"], own[2], np.take(self.level2[2], nxt, axis=1),
                        normal["F"])
        for k, name in enumerate("VEFD"):
            inner[k] = _inner(point[name], own[k], normal[name])

    def _snap(self) -> None:
        """The corner points after the three passes that make neighbours meet."""
        a = self.arrays
        side = self.side
        if not len(a.edge_ids):  # no edge, no patch: nothing to snap
            self.snapped_edge, self.snapped_vertex = self.edge_point, self.vertex_point
            self.snapped_face = self.face_point
            return
        c0, c1 = a.edge_corners[:, 0], a.edge_corners[:, 1]
        self.snapped_edge = _split(side[1][:, c0], side[1][:, c1], side[2][:, c0], side[2][:, c1])
        order, offsets = self.vertex_rings
        self.snapped_vertex = self.vertex_point.copy()
        four = np.flatnonzero((np.diff(offsets) == 4) & (a.corner_edge[order[offsets[:-1]]] >= 0))
        first, third = order[offsets[four]], order[offsets[four] + 2]
        self.snapped_vertex[:, four] = _split(
            side[0][:, first], side[0][:, third],
            side[0][:, self.vprev[first]], side[0][:, self.vprev[third]])
        self.snapped_face = self.face_point.copy()
        quads = np.flatnonzero(a.face_sizes == 4)
        first, third = a.face_offsets[quads], a.face_offsets[quads] + 2
        self.snapped_face[:, quads] = _split(
            side[3][:, first], side[3][:, third],
            side[3][:, self.prev[first]], side[3][:, self.prev[third]])

    def surface_corners(self) -> np.ndarray:
        """``(k,)`` dense indices of the corners that get a patch: those of faces
        that are neither holes nor point-spheres."""
        a = self.arrays
        return np.flatnonzero(~a.face_hole[a.corner_face] & (a.corner_edge >= 0))

    def _drawn(self, corners: np.ndarray | None) -> np.ndarray:
        """``corners`` (all when None) less those of holes and point-spheres."""
        if corners is None:
            return self.surface_corners()
        a = self.arrays
        corners = np.asarray(corners, dtype=np.int64).reshape(-1)
        return corners[~a.face_hole[a.corner_face[corners]] & (a.corner_edge[corners] >= 0)]

    def nets(self, corners: np.ndarray | None = None) -> PatchNet:
        """The control nets of ``corners`` (see :func:`patch_control_points`)."""
        corners = self._drawn(corners)
        with np.errstate(invalid="ignore", over="ignore"):
            columns, normals = self._columns(corners)
        finite = np.isfinite(columns).all(axis=(0, 1))
        if finite.all():
            return PatchNet(columns, normals, corners)
        return PatchNet(columns[:, :, finite], normals[:, :, finite], corners[finite])

    def tessellate(self, density: int, corners: np.ndarray | None = None) -> Tessellation:
        """:func:`evaluate_patches` of :meth:`nets` (``corners``: all when None),
        made a slice of patches at a time: the nets are never all in memory.

        Raises:
            InvalidArgumentError: ``density`` is not an int in [1, MAX_DENSITY].
        """
        steps = _check_density(density)
        corners = self._drawn(corners)
        corners = corners[self._finite(corners)]
        grid = Grid(steps)
        positions = np.empty((len(corners), grid.size, 3), dtype=np.float32)
        normals = np.empty_like(positions)
        for start in range(0, len(corners), CHUNK):
            part = slice(start, start + CHUNK)
            with np.errstate(invalid="ignore", over="ignore"):
                columns, control_normals = self._columns(corners[part])
            grid.evaluate(columns, control_normals, positions[part], normals[part])
        return Tessellation(positions.reshape(-1, 3), normals.reshape(-1, 3),
                            grid_triangles(len(corners), steps), steps,
                            self._point_colors(corners, grid.size))

    def _point_colors(self, corners: np.ndarray, points: int) -> np.ndarray | None:
        """``(k * points, 4)`` uint8: the colour of each corner's face, ``points``
        times over (the points of its patch); None when no face has a colour."""
        rgba = rgba_bytes(self.arrays.face_colors)
        if rgba is None:
            return None
        return np.repeat(np.take(rgba, np.take(self.arrays.corner_face, corners), axis=0),
                         points, axis=0)

    def vertex_surface(self, corners: np.ndarray | None = None) -> Tessellation:
        """The patch surface at its coarsest: the faces of ``corners`` (all drawn
        faces when None; whole faces, as fans) with their corners at the patches'
        vertex points, which lie on the surface, and the patches' normals there.
        About a quarter of the triangles of density 1 (``density`` 0). Faces share
        their points (faces of one colour only, when the mesh has colours)."""
        a = self.arrays
        shown = np.zeros(len(a.face_ids), dtype=bool)
        shown[np.take(a.corner_face, self._drawn(corners))] = True
        fan, face = a.fan_triangles()
        fans = fan[shown[face]]                                      # (T, 3) corners
        rings = np.take(self.ring_of, fans.ravel())
        rgba, colors = rgba_bytes(a.face_colors), None
        if rgba is None:
            used, index = _compact(rings, len(self.vertex_point[0]))
        else:
            used, colors, index = _points_by_color(rings, np.take(a.corner_face, fans), rgba,
                                                   len(self.vertex_point[0]))
        with np.errstate(invalid="ignore", over="ignore"):
            points = self.snapped_vertex[:, used].T * self.scale + self.center
        finite = np.isfinite(points).all(axis=1)
        keep = finite[index.reshape(-1, 3)].all(axis=1)
        return Tessellation(points.astype(np.float32),
                            self.vertex_normal[:, used].T.astype(np.float32),
                            index.reshape(-1, 3)[keep].astype(np.uint32), 0, colors)

    def _columns(self, corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(16, 3, k)`` control points (in the mesh's coordinates) and unit
        control normals of the patches of ``corners`` ``(k,)``."""
        columns = np.empty((16, 3, len(corners)))
        point, normal = self._corner_frame(corners, snapped=True)
        for name, row in _CORNER_ROWS.items():
            columns[row] = point[name]
        vprev, prev = np.take(self.vprev, corners), np.take(self.prev, corners)
        owners = {4: (0, corners), 8: (1, corners), 13: (2, corners), 14: (3, corners),
                  1: (0, vprev), 2: (1, vprev), 7: (2, prev), 11: (3, prev)}
        for row, (k, owner) in owners.items():
            columns[row] = np.take(self.side[k], owner, axis=1)
        for row, k in ((5, 0), (9, 1), (10, 2), (6, 3)):
            columns[row] = np.take(self.inner[k], corners, axis=1)
        columns *= self.scale
        columns += self.center[:, None]
        corner_normals = np.stack([normal[k] for k in "VEFD"])
        return columns, _unit(np.einsum("sk,kxp->sxp", NORMAL_BLEND, corner_normals))

    def _finite(self, corners: np.ndarray) -> np.ndarray:
        """``(k,)`` bool: the patches of ``corners`` whose control points are all
        finite (the rows :meth:`_columns` reads, checked where they are kept)."""
        if not len(self.arrays.edge_ids):
            return np.zeros(len(corners), dtype=bool)
        side = np.all(np.isfinite(self.side), axis=1)       # (4, C)
        own = side.all(axis=0) & np.isfinite(self.inner).all(axis=(0, 1))
        tables = ((self.snapped_vertex, self.ring_of), (self.snapped_edge, self.edge),
                  (self.snapped_edge, self.edge_before),
                  (self.snapped_face, self.arrays.corner_face))
        for table, index in tables:
            own &= np.take(np.isfinite(table).all(axis=0), index)
        vprev, prev = np.take(self.vprev, corners), np.take(self.prev, corners)
        return (np.take(own, corners) & np.take(side[0] & side[1], vprev)
                & np.take(side[2] & side[3], prev))


def _compact(values: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray]:
    """``(used, index)``: the distinct ``values`` (all below ``count``) in order,
    and where each value is in ``used`` (``np.unique`` with ``return_inverse``, in
    linear time)."""
    has = np.zeros(count, dtype=bool)
    has[values] = True
    used = np.flatnonzero(has)
    place = np.zeros(count, dtype=np.int64)
    place[used] = np.arange(len(used))
    return used, place[values]


def _points_by_color(points: np.ndarray, faces: np.ndarray, rgba: np.ndarray,
                     count: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The distinct pairs of a point and a face colour among the corners of a
    surface, so that faces of one colour share their points and faces of two do not.

    Args:
        points: ``(n,)`` int point of each corner, each below ``count``.
        faces: int face of each corner (``n`` of them, in any shape).
        rgba: ``(F, 4)`` uint8 colour of each face (see :func:`rgba_bytes`).
        count: how many points there are.

    Returns:
        ``(used (k,) points, colors (k, 4) uint8, index (n,))``: each pair's point
        and colour, in the order of the pairs' keys, and the pair of each corner.
    """
    palette, shade = np.unique(rgba.view("<u4").reshape(-1), return_inverse=True)
    shades = len(palette)
    keys = points.astype(np.int64) * shades + np.take(shade.reshape(-1), faces.reshape(-1))
    if count * shades <= 4 * len(keys) + count:  # few colours: linear time
        pairs, index = _compact(keys, count * shades)
    else:
        pairs, index = np.unique(keys, return_inverse=True)
    colors = palette[pairs % shades].view(np.uint8).reshape(-1, 4)
    return pairs // shades, colors, index.reshape(-1)


def _frame(positions: np.ndarray) -> tuple[np.ndarray, float]:
    """The centre of the finite ``positions`` and a power of two at least their
    half extent: coordinates ``(p - centre) / scale`` lie in [-1, 1]."""
    finite = positions[np.isfinite(positions).all(axis=1)] if len(positions) else positions
    if len(finite) == 0:
        return np.zeros(3), 1.0
    low, high = finite.min(axis=0), finite.max(axis=0)
    center = low / 2 + high / 2
    half = float(np.max(high / 2 - low / 2))
    if not 0.0 < half < np.inf:
        return center, 1.0
    return center, float(2.0 ** np.ceil(np.log2(half)))


def _project(points: np.ndarray, at: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """``(3, k)`` ``points`` projected into the planes through ``at`` with unit (or
    zero: no projection) ``normal`` (all ``(3, k)``)."""
    return points - _dot(points - at, normal) * normal


def _side(at: np.ndarray, far: np.ndarray, inner: np.ndarray, outer: np.ndarray,
          normal: np.ndarray) -> np.ndarray:
    """``(3, k)`` boundary control points: on the side from patch corner ``at``
    toward ``far``, where the segment from this patch's level-2 point ``inner`` to
    the neighbour's ``outer`` crosses it, all projected into the tangent plane of
    ``at`` (``normal``); then pushed 4/3 of the way from ``at``."""
    crossing = _split(at, _project(far, at, normal), _project(inner, at, normal),
                      _project(outer, at, normal))
    return at + PUSH * (crossing - at)


def _inner(at: np.ndarray, point: np.ndarray, normal: np.ndarray) -> np.ndarray:
    """``(3, k)`` inner control points: ``point`` projected into the tangent plane of
    patch corner ``at`` (``normal``), pushed 4/3 of the way from ``at``."""
    return at + PUSH * (_project(point, at, normal) - at)


def _split(line0: np.ndarray, line1: np.ndarray, start: np.ndarray,
           end: np.ndarray) -> np.ndarray:
    """``(3, k)``: the point of segment ``start``-``end`` where it crosses the
    line through ``line0`` and ``line1``, found as TopMod does from the two ends'
    distances to the line (exact when the lines are coplanar). Half way when
    both ends lie on the line."""
    near, far = _distance_to_line(start, line0, line1), _distance_to_line(end, line0, line1)
    total = near + far
    share = np.divide(near, total, out=np.full_like(total, 0.5), where=total > 0.0)
    return start + share * (end - start)


def _distance_to_line(points: np.ndarray, line0: np.ndarray, line1: np.ndarray) -> np.ndarray:
    """``(k,)`` distance of each ``(3, k)`` point to the line through ``line0`` and
    ``line1`` (to ``line0`` where the two coincide)."""
    along, rel = line1 - line0, points - line0
    length2 = _dot(along, along)
    t = np.divide(_dot(rel, along), length2, out=np.zeros_like(length2), where=length2 > 0.0)
    off = rel - t * along
    return np.sqrt(_dot(off, off))
