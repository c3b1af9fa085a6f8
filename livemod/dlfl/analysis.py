"""Measurements of a whole mesh: normals, centroids, bounds, components, genus.

Every function takes a :class:`Mesh` or the :class:`MeshArrays` of one (pass the
arrays when calling several functions on the same mesh, to lay it out once).
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, field

import numpy as np

from ._graph import component_labels
from ._vectors import (
    RingVectors,
    centroid,
    face_ring_vectors,
    newell,
    scaled_mean,
    true_lengths,
)
from ._vectors import unit as _normalize
from .arrays import MeshArrays, mesh_arrays
from .mesh import Mesh
from .normals import RingNormals, polygon_normal, ring_normals


def _arrays(mesh: Mesh | MeshArrays) -> MeshArrays:
    return mesh if isinstance(mesh, MeshArrays) else mesh_arrays(mesh)


def face_centroids(mesh: Mesh | MeshArrays) -> np.ndarray:
    """``(F, 3)`` float64 mean of each face's corner positions (TopMod's centroid)."""
    a = _arrays(mesh)
    return scaled_mean(a.positions[a.corner_vertex], a.corner_face, len(a.face_ids),
                       a.face_sizes)


def corner_normals(mesh: Mesh | MeshArrays) -> np.ndarray:
    """``(C, 3)`` float64 unit normal of each corner: TopMod's rule
    (:mod:`.normals`): ``normalize((next - p) x (prev - p))``, flipped at a
    concave corner; a straight ("winged") corner copies the nearest other
    one's. Point-spheres, 2-gons and corners of faces that have no normal get
    zero. Any scale and offset of the mesh gives the same."""
    return _ring_normals(_arrays(mesh)).corner


def _ring_normals(a: MeshArrays) -> RingNormals:
    return ring_normals(a.positions, a.corner_vertex, a.face_offsets)


def _ring_vectors(a: MeshArrays) -> RingVectors:
    """The corner points of ``a`` relative to their face's first corner, in range."""
    return face_ring_vectors(a.positions, a.corner_vertex, a.face_offsets, a.corner_face)


def face_normals(mesh: Mesh | MeshArrays) -> np.ndarray:
    """``(F, 3)`` float64 unit face normals: the normalised sum of the corner
    normals (TopMod's rule, :mod:`.normals`).

    Faces are counter-clockwise seen from outside, so on a closed mesh the
    normals point out. Degenerate faces (point-spheres, 2-gons) get zero.
    """
    return _ring_normals(_arrays(mesh)).face


def face_areas(mesh: Mesh | MeshArrays) -> np.ndarray:
    """``(F,)`` float64 vector area of each face (exact for planar faces).

    Any offset and scale of the mesh works; an area beyond the float range
    (about 1.8e308) is inf.
    """
    a = _arrays(mesh)
    r = _ring_vectors(a)
    sums = newell(r, r.along(a.corner_next), a.corner_face, len(a.face_ids))
    return true_lengths(np.linalg.norm(sums, axis=1) * 0.5, r, 2)


def surface_area(mesh: Mesh | MeshArrays) -> float:
    """The total area of the faces (hole faces left out); inf beyond the float range."""
    a = _arrays(mesh)
    return float(face_areas(a)[~a.face_hole].sum())


def enclosed_volume(mesh: Mesh | MeshArrays) -> float | None:
    """The volume the faces enclose, by the divergence theorem over each face's fan
    of triangles from its first corner; None when the mesh has hole faces (an open
    surface encloses nothing).

    Signed: negative for a mesh whose faces point inward, and a crust (an outer
    shell around an inward-facing inner one) gets the volume of its material.
    Exact for planar faces; computed about the middle of the bounding box in
    units of its size, so far offsets and large or tiny scales cost no precision
    (beyond the float range it is inf).
    """
    a = _arrays(mesh)
    if a.face_hole.any():
        return None
    if len(a.corner_vertex) == 0:
        return 0.0
    low, high = bounds(a)
    half = max(float(np.max(high / 2 - low / 2)), 1e-300)  # halves: no overflow
    size = np.float64(2.0) ** (np.ceil(np.log2(half)) + 1)  # a power of two: exact
    p = a.positions / size - (low / 2 + high / 2) / size
    x, y, z = (np.ascontiguousarray(p[:, k]) for k in range(3))
    here, ahead = a.corner_vertex, a.corner_vertex[a.corner_next]
    # each face's sum of p x next, then dotted with its first corner (one column at a
    # time: np.cross's temporaries cost three times as much)
    count = len(a.face_ids)
    sums = [np.bincount(a.corner_face, u[here] * v[ahead] - v[here] * u[ahead], count)
            for u, v in ((y, z), (z, x), (x, y))]
    first = here[a.face_offsets[:-1]]
    volume = (x[first] @ sums[0] + y[first] @ sums[1] + z[first] @ sums[2]) / 6.0
    with np.errstate(over="ignore"):  # beyond the float range: inf, as documented
        return float(volume * size**3)


def vertex_normals(mesh: Mesh | MeshArrays) -> np.ndarray:
    """``(V, 3)`` float64 unit normals: the normalised sum of the adjacent face normals."""
    a = _arrays(mesh)
    sums = np.zeros((len(a.vertex_ids), 3))
    np.add.at(sums, a.corner_vertex, face_normals(a)[a.corner_face])
    return _normalize(sums)


def bounds(mesh: Mesh | MeshArrays) -> np.ndarray:
    """``(2, 3)`` float64 ``[min, max]`` corners of the bounding box (zeros if empty)."""
    a = _arrays(mesh)
    if len(a.positions) == 0:
        return np.zeros((2, 3))
    return np.stack([a.positions.min(axis=0), a.positions.max(axis=0)])


def component_of_vertices(mesh: Mesh | MeshArrays) -> tuple[np.ndarray, np.ndarray]:
    """Connected components: ``(vertex_labels (V,), face_labels (F,))``.

    Labels are ``0..k-1``, numbered in order of each component's first vertex.
    """
    a = _arrays(mesh)
    nv = len(a.vertex_ids)
    labels = component_labels(nv + len(a.face_ids), a.corner_vertex, nv + a.corner_face)
    _, dense = np.unique(labels, return_inverse=True)
    return dense[:nv], dense[nv:]


def num_components(mesh: Mesh | MeshArrays) -> int:
    """Number of connected components (each point-sphere is one)."""
    vlabels, _ = component_of_vertices(mesh)
    return int(vlabels.max()) + 1 if len(vlabels) else 0


def component_genera(mesh: Mesh | MeshArrays) -> list[int]:
    """Genus of each connected component, ``(2 - (V - E + F)) / 2`` per component."""
    a = _arrays(mesh)
    vlab, flab = component_of_vertices(a)
    k = int(vlab.max()) + 1 if len(vlab) else 0
    v = np.bincount(vlab, minlength=k)
    f = np.bincount(flab, minlength=k)
    e = np.bincount(vlab[a.corner_vertex[a.edge_corners[:, 0]]], minlength=k)
    return [int(g) for g in (2 - (v - e + f)) // 2]


def genus(mesh: Mesh | MeshArrays) -> int:
    """Total genus: the sum over components (two spheres are genus 0, not -1)."""
    return sum(component_genera(mesh))


def euler_characteristic(mesh: Mesh | MeshArrays) -> int:
    """``V - E + F`` (holes count as faces)."""
    v, e, f = _arrays(mesh).counts
    return v - e + f


def face_size_histogram(mesh: Mesh | MeshArrays, *, holes: bool = False) -> dict[int, int]:
    """Face size -> number of faces of that size, holes left out unless asked for."""
    a = _arrays(mesh)
    sizes = a.face_sizes if holes else a.face_sizes[~a.face_hole]
    return dict(sorted(Counter(sizes.tolist()).items()))


@dataclass
class MeshSummary:
    """What ``livemod info`` prints about a mesh."""

    vertices: int
    edges: int
    faces: int
    holes: int
    point_spheres: int
    genus: int
    component_genera: list[int] = field(default_factory=list)
    face_sizes: dict[int, int] = field(default_factory=dict)

    @property
    def components(self) -> int:
        """Number of connected components (one genus each in ``component_genera``)."""
        return len(self.component_genera)


def summarize(mesh: Mesh | MeshArrays) -> MeshSummary:
    """Counts, components, genus per component and the face-size histogram
    (:func:`bounds`, :func:`surface_area` and :func:`enclosed_volume` measure the
    geometry)."""
    a = _arrays(mesh)
    genera = component_genera(a)
    v, e, f = a.counts
    return MeshSummary(
        vertices=v, edges=e, faces=f,
        holes=int(a.face_hole.sum()),
        point_spheres=int((a.corner_edge < 0).sum()),
        genus=sum(genera), component_genera=genera,
        face_sizes=face_size_histogram(a),
    )


def face_normal(mesh: Mesh, face: int) -> np.ndarray:
    """``(3,)`` unit normal of one face (see :func:`face_normals`)."""
    return polygon_normal(face_points(mesh, face))


def face_points(mesh: Mesh, face: int) -> np.ndarray:
    """``(k, 3)`` positions of a face's corners in ring order (:meth:`Mesh.face_points`)."""
    return mesh.face_points(face)


def face_centroid(mesh: Mesh, face: int) -> np.ndarray:
    """``(3,)`` mean of one face's corner positions (no overflow near the float
    maximum: see :func:`._vectors.centroid`)."""
    return centroid(face_points(mesh, face))
