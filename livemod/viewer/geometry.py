"""GL-free preparation of render buffers from :class:`MeshArrays` (numpy only).

Everything the renderer uploads is computed here in one vectorized pass, so it can
be tested and benchmarked without a GL context:

* ``positions``: one float32 position per vertex, shared by faces, edges and points;
* ``triangles``: the fans of every non-hole face, as vertex indices;
* ``triangle_table``: the dense face index of each triangle, with three bits on top
  saying which of its sides are real edges (not fan diagonals); the fragment shader
  looks it up with ``gl_PrimitiveID``, so there is no per-corner vertex duplication,
  flat normals come from screen-space derivatives, and the wireframe is drawn in
  the same pass (distance to the real sides) instead of as line primitives;
* ``lines``: the two vertex indices of each edge (dense edge order).

Pick ids pack an element kind in the top bits and ``dense index + 1`` below, so 0
means background.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.colors import rgba_bytes

KIND_FACE, KIND_EDGE, KIND_VERTEX = 1, 2, 3
KIND_SHIFT = 28
INDEX_MASK = (1 << KIND_SHIFT) - 1
SIDE_SHIFT = 29  # triangle_table: face index below, real-side bits (v0v1, v1v2, v2v0) above


CREASE_ANGLE = 45.0  # degrees between two faces' normals above which their edge is sharp


@dataclass(frozen=True)
class SmoothShading:
    """The faces' fans with a normal per corner that is smooth across the edges
    between faces less than a crease angle apart, and sharp across the others.

    Attributes:
        positions: ``(S, 3)`` float32: one point per smooth sector (the corners
            around a vertex between two sharp edges, or all of them).
        normals: ``(S, 3)`` float32 unit normal of each sector (zero for none).
        triangles: ``(T, 3)`` uint32 sector indices of the fans, in the order of
            :func:`fan_triangles` (so a triangle keeps its place in the face tables).
    """

    positions: np.ndarray
    normals: np.ndarray
    triangles: np.ndarray


@dataclass(frozen=True)
class RenderGeometry:
    """Buffers ready for upload.

    Attributes:
        positions: ``(V, 3)`` float32 vertex positions.
        triangles: ``(T, 3)`` uint32 vertex indices of the face fans (holes left out).
        triangle_table: ``(T,)`` uint32 dense face index of each triangle, ORed with
            its real-side bits shifted by ``SIDE_SHIFT``.
        lines: ``(E, 2)`` uint32 vertex indices of each edge.
        bounds: ``(2, 3)`` float64 min and max corner of the finite positions
            (zeros if there are none).
        face_count: number of faces, holes included (the length of face tables).
        holes: number of hole faces.
        point_spheres: ``(P,)`` uint32 indices of the vertices that are point-spheres
            (a vertex with no edge, whose face is its one corner): drawn as points,
            since they have no faces to show.
        nonfinite: number of vertices whose position is not finite (NaN or inf);
            they are left out of ``bounds``.
        arrays: the arrays it was built from (for what is made on demand).
        smooth: the faces' smooth shading creased at ``crease_angle`` degrees
            (:func:`crease_shading`), when it was prepared with it, else None.
        face_colors: ``(F,)`` uint32 colour of each face packed as RGBA8 (red in
            the low byte), alpha 0 for a face without one; empty when no face
            has one (see :func:`packed_face_colors`).
    """

    positions: np.ndarray
    triangles: np.ndarray
    triangle_table: np.ndarray
    lines: np.ndarray
    bounds: np.ndarray
    face_count: int
    holes: int = 0
    point_spheres: np.ndarray = field(default_factory=lambda: np.zeros(0, np.uint32))
    nonfinite: int = 0
    arrays: MeshArrays | None = None
    smooth: SmoothShading | None = None
    crease_angle: float = CREASE_ANGLE
    face_colors: np.ndarray = field(default_factory=lambda: np.zeros(0, np.uint32))

    @property
    def triangle_face(self) -> np.ndarray:
        """``(T,)`` uint32 dense face index of each triangle."""
        return self.triangle_table & np.uint32((1 << SIDE_SHIFT) - 1)

    @property
    def closed(self) -> bool:
        """True for a mesh with faces and no holes: its back faces are never seen
        from outside, so they can be culled."""
        return self.face_count > 0 and len(self.triangles) > 0 and self.holes == 0

    @property
    def center(self) -> np.ndarray:
        """``(3,)`` float64 centre of the bounding box."""
        return np.asarray(self.bounds.mean(axis=0))

    @property
    def radius(self) -> float:
        """Radius of the sphere around the bounding box (at least 1e-6)."""
        return max(float(np.linalg.norm(self.bounds[1] - self.bounds[0])) / 2.0, 1e-6)


def fan_triangles(arrays: MeshArrays) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The fans of :meth:`MeshArrays.fan_triangles` as the renderer draws them.

    Returns:
        ``(triangles (T, 3) uint32 vertex indices, triangle_face (T,) uint32,
        sides (T,) uint32)``: bit 0, 1, 2 of ``sides`` is set when side v0-v1, v1-v2,
        v2-v0 is an edge of the face rather than a diagonal of the fan.
    """
    corners, faces = arrays.fan_triangles()
    first = corners[:, 1] == corners[:, 0] + 1
    last = corners[:, 2] == arrays.face_offsets[faces + 1] - 1
    sides = (2 | first | (last.astype(np.uint32) << 2)).astype(np.uint32)
    triangles = arrays.corner_vertex[corners].astype(np.uint32)
    return triangles, faces.astype(np.uint32), sides


def crease_shading(arrays: MeshArrays, crease_angle: float = CREASE_ANGLE) -> SmoothShading:
    """:class:`SmoothShading` of ``arrays``: around each vertex, the corners between
    two sharp edges (whose faces' normals are more than ``crease_angle`` degrees
    apart) share one normal, the area-weighted sum of their faces' normals. Faces
    whose normal is not finite count as having none."""
    from livemod.dlfl.analysis import face_areas, face_normals
    from livemod.dlfl.patches import cycle_layout

    corners, _ = arrays.fan_triangles()
    count = len(arrays.corner_vertex)
    with np.errstate(invalid="ignore", over="ignore"):  # (faces not finite: no normal)
        unit = np.nan_to_num(face_normals(arrays), nan=0.0, posinf=0.0, neginf=0.0)
        area = np.nan_to_num(face_areas(arrays), nan=0.0, posinf=0.0)
    vnext = arrays.corner_vnext
    along = np.einsum("ij,ij->i", unit[arrays.corner_face], unit[arrays.corner_face[vnext]])
    smooth_to_next = along >= np.cos(np.radians(crease_angle))
    longest = int(np.bincount(arrays.corner_vertex).max()) if count else 1
    order, offsets = cycle_layout(vnext, longest)
    sector = np.empty(count, dtype=np.int64)
    sector[order] = _sectors(smooth_to_next[order], offsets)
    weighted = unit * area[:, None]
    sums = np.zeros((int(sector.max()) + 1 if count else 0, 3))
    np.add.at(sums, sector, weighted[arrays.corner_face])
    first = np.zeros(len(sums), dtype=np.int64)
    first[sector[::-1]] = np.arange(count)[::-1]
    length = np.linalg.norm(sums, axis=1, keepdims=True)
    normals = np.divide(sums, length, out=np.zeros_like(sums), where=length > 0)
    return SmoothShading(arrays.positions[arrays.corner_vertex[first]].astype(np.float32),
                         normals.astype(np.float32), sector[corners].astype(np.uint32))


def _sectors(smooth_to_next: np.ndarray, offsets: np.ndarray) -> np.ndarray:
    """``(N,)`` sector number of each element of rings laid out by ``offsets``:
    runs of elements joined by smooth links (``smooth_to_next[k]``: element ``k``
    to the next in its ring, the last to the first). A ring with no sharp link is
    one sector; elements before a ring's first sharp link belong to its last run."""
    count = len(smooth_to_next)
    ring = np.repeat(np.arange(len(offsets) - 1), np.diff(offsets))
    starts = offsets[:-1]
    # element k starts a run when the link into it (from the one before, in its
    # ring) is sharp; a ring's first element's link comes from its last
    before = np.arange(-1, count - 1)
    before[starts] = offsets[1:] - 1
    opens = ~smooth_to_next[before]
    run = np.cumsum(opens) - 1
    has_open = np.add.reduceat(opens, starts) > 0 if count else np.zeros(0, bool)
    # elements before their ring's first opening: the ring's last run (or, for a
    # ring with no opening, one run of its own)
    first_open = np.full(len(starts), count)
    positions = np.flatnonzero(opens)
    np.minimum.at(first_open, ring[positions], positions)
    prefix = np.arange(count) < first_open[ring]
    last = offsets[1:] - 1
    closed_ring = ~has_open[ring]
    run = np.where(prefix & ~closed_ring, run[last][ring], run)
    # rings with no opening get numbers after all the runs
    run = np.where(closed_ring, int(opens.sum()) + np.cumsum(~has_open)[ring] - 1, run)
    return run


def build_geometry(arrays: MeshArrays, crease_angle: float | None = None) -> RenderGeometry:
    """Prepare all buffers of ``arrays`` (see the module docstring); with a
    ``crease_angle``, its smooth shading too (:func:`crease_shading`)."""
    positions = np.ascontiguousarray(arrays.positions, dtype=np.float32)
    triangles, triangle_face, sides = fan_triangles(arrays)
    triangle_table = triangle_face | (sides << np.uint32(SIDE_SHIFT))
    lines = arrays.edge_vertices.astype(np.uint32)
    finite = finite_rows(arrays.positions)
    spheres = arrays.corner_vertex[arrays.corner_edge < 0].astype(np.uint32)
    smooth = None if crease_angle is None else crease_shading(arrays, crease_angle)
    return RenderGeometry(positions, triangles, triangle_table, lines, finite_bounds(finite),
                          len(arrays.face_ids), int(arrays.face_hole.sum()), spheres,
                          len(arrays.positions) - len(finite), arrays, smooth,
                          CREASE_ANGLE if crease_angle is None else crease_angle,
                          packed_face_colors(arrays))


def packed_face_colors(arrays: MeshArrays) -> np.ndarray:
    """``(F,)`` uint32 face colours as RGBA8 (red in the low byte, alpha 255) for
    the faces with one, 0 for the others; ``(0,)`` when no face has one."""
    rgba = rgba_bytes(arrays.face_colors)
    if rgba is None:
        return np.zeros(0, np.uint32)
    return rgba.view("<u4").reshape(-1).astype(np.uint32)


@dataclass(frozen=True)
class LabelAnchors:
    """Where the id labels of one kind sit, with the float32 columns their choice
    in every view reads (:func:`visible_labels`), made once per mesh: off the
    window's thread for a big mesh (a million anchors' columns take 20 ms).

    Attributes:
        points: ``(n, 3)`` float64 anchors, one per element of the kind (face
            centroids, edge midpoints, vertex positions).
        labelled: ``(k,)`` int64 indices of the elements labelled before the
            style's filters: all of them, but for the faces the holes.
        columns: ``(3, k)`` float32 C-contiguous ``points[labelled]``, one row
            per coordinate.
    """

    points: np.ndarray
    labelled: np.ndarray
    columns: np.ndarray


@dataclass(frozen=True)
class PreparedMeshes:
    """The render buffers of a mesh and of the other objects beside it, built off
    the window's thread (see :func:`prepare_meshes`); None where there is none.
    ``anchors``: the mesh's label anchors of the kinds asked (see :func:`label_anchors`)."""

    arrays: MeshArrays | None
    others: MeshArrays | None
    mesh: RenderGeometry | None
    other: RenderGeometry | None
    anchors: dict[str, LabelAnchors] = field(default_factory=dict)


def prepare_meshes(arrays: MeshArrays | None, others: MeshArrays | None = None,
                   crease_angle: float | None = None,
                   labels: Iterable[str] = ()) -> PreparedMeshes:
    """:func:`build_geometry` of ``arrays`` and ``others`` (GL-free, any thread);
    with a ``crease_angle``, their smooth shading too; the anchors of the
    ``labels`` kinds ("faces", "edges", "vertices") of ``arrays``."""
    return PreparedMeshes(arrays, others,
                          None if arrays is None else build_geometry(arrays, crease_angle),
                          None if others is None else build_geometry(others, crease_angle),
                          {} if arrays is None else label_anchors(arrays, labels))


def label_anchors(arrays: MeshArrays, kinds: Iterable[str]) -> dict[str, LabelAnchors]:
    """``{kind: anchors}`` of the id labels of each of ``kinds`` ("faces",
    "edges", "vertices") of ``arrays`` (numpy only, any thread)."""
    from livemod.dlfl.analysis import face_centroids

    makers = {"faces": lambda: face_centroids(arrays),
              "edges": lambda: arrays.positions[arrays.edge_vertices].mean(axis=1),
              "vertices": lambda: np.asarray(arrays.positions)}
    made = {}
    for kind in kinds:
        points = makers[kind]()
        labelled = (np.flatnonzero(~arrays.face_hole) if kind == "faces"
                    else np.arange(len(points)))
        columns = np.ascontiguousarray(points[labelled].T, dtype=np.float32)
        made[kind] = LabelAnchors(points, labelled, columns)
    return made


def visible_labels(columns: np.ndarray, view: np.ndarray | None, limit: int) -> np.ndarray:
    """``(k,)`` int64 indices of the anchors to label, in order: of those in front of
    the eye and inside the ``(4, 4)`` view-projection ``view``, the ``limit`` nearest
    the eye (without a view: the first ``limit``). A million labels are never
    readable at once; this keeps the layout and the draw of the labels to what the
    screen can show.

    Args:
        columns: ``(3, n)`` float32 anchors, one row per coordinate (a million are
            projected in a few milliseconds so).
    """
    count = columns.shape[1]
    if view is None:
        return np.arange(min(count, limit))
    m = np.asarray(view, dtype=np.float32)
    with np.errstate(invalid="ignore", over="ignore"):
        x, y, w = (columns[0] * m[k, 0] + columns[1] * m[k, 1] + columns[2] * m[k, 2]
                   + m[k, 3] for k in (0, 1, 3))
        inside = (w > 0) & (np.abs(x) <= w) & (np.abs(y) <= w)
    index = np.flatnonzero(inside)
    if len(index) > limit:
        nearest = np.argpartition(w[index], limit - 1)[:limit]
        index = np.sort(index[nearest])
    return index


def finite_rows(points: np.ndarray) -> np.ndarray:
    """The rows of ``(n, 3)`` ``points`` whose three coordinates are finite, as
    ``(k, 3)``. A script may leave NaN or inf in a position (say, a division by a
    zero length): one such vertex must not turn the bounds, and so the camera
    framed on them, into NaN, which would blank the whole view."""
    points = np.asarray(points)
    if len(points) == 0 or np.isfinite(points).all():
        return points  # (the usual case: no copy)
    return points[np.isfinite(points).all(axis=1)]


def finite_bounds(points: np.ndarray) -> np.ndarray:
    """``(2, 3)`` float64 min and max corner of the finite rows of ``(n, 3)``
    ``points`` (zeros when there are none)."""
    finite = finite_rows(points)
    if len(finite) == 0:
        return np.zeros((2, 3))
    # a column at a time: numpy reduces a narrow (n, 3) array along axis 0 a row
    # at a time, 7x slower (70 of the 150 ms of a million-face mesh's buffers)
    columns = [finite[:, axis] for axis in range(3)]
    return np.array([[column.min() for column in columns],
                     [column.max() for column in columns]], dtype=np.float64)


def decode_pick(pick_id: int) -> tuple[int, int] | None:
    """``(kind, dense index)`` of a pick id, or None for background."""
    if pick_id == 0:
        return None
    return pick_id >> KIND_SHIFT, (pick_id & INDEX_MASK) - 1


def corner_points(arrays: MeshArrays, corners: np.ndarray, inset: float = 0.2) -> np.ndarray:
    """``(k, 3)`` float32 marker positions of dense ``corners``: each vertex pulled
    ``inset`` of the way toward its face's centroid, so a corner shows inside its face."""
    from livemod.dlfl.analysis import face_centroids

    if len(corners) == 0:
        return np.zeros((0, 3), dtype=np.float32)
    centroids = face_centroids(arrays)[arrays.corner_face[corners]]
    at = arrays.positions[arrays.corner_vertex[corners]]
    return (at + inset * (centroids - at)).astype(np.float32)


def dense_flags(all_ids: np.ndarray, picked: tuple[int, ...]) -> np.ndarray:
    """``(n,)`` uint8: 1 where ``all_ids`` is one of ``picked`` (ids, not indices)."""
    return np.isin(all_ids, np.asarray(picked, dtype=np.int64)).astype(np.uint8)


def sample_points(positions: np.ndarray, limit: int = 200_000) -> np.ndarray:
    """At most about ``limit`` of ``(n, 3)`` ``positions`` (an even stride), for fitting."""
    stride = max(len(positions) // limit, 1)
    return np.asarray(positions[::stride])
