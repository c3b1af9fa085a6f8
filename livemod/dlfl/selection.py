"""Selection: faces, edges and vertices picked by a rule, as TopMod selects them.

Each function returns a list of ids in increasing id order (loops and rings in
walk order). They take a :class:`Mesh` or its :class:`MeshArrays` (what the
window holds of the mesh it shows). TopMod's counterparts: ``selectMatchingFaces``
(same size), ``selectMatchingEdges`` (same end valences), ``selectMatchingVertices``
(same valence), ``selectFacesByArea`` (within 0.05), checkerboard (SHIFT+K), edge
loop (SHIFT+L, through valence-4 vertices), edge ring (SHIFT+R), face loop
(SHIFT+P, through quads), grow (``=``), shrink (``-``), inverse (CTRL+I) and all
(CTRL+A). Faces never include holes (the boundary loops of an open mesh).

Kinds are named as the fields of :class:`~livemod.dlfl.scene.Selection`:
``"faces"``, ``"edges"``, ``"vertices"``, ``"corners"``.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from ._checks import finite_number, finite_vector, id_list, is_id, shown
from ._graph import component_labels
from ._vectors import unit
from .analysis import face_areas, face_normals
from .arrays import MeshArrays, mesh_arrays
from .colors import SAME_IN_8_BITS, colored_like
from .errors import InvalidArgumentError, UnknownIdError
from .mesh import Mesh

__all__ = [
    "KINDS", "SIMILAR_FACES", "checkerboard", "edge_loop", "edge_ring", "face_loop",
    "faces_by_area", "faces_by_normal", "faces_by_size", "faces_by_vertex_valence",
    "faces_where", "grow", "invert", "kind_field", "matching_edges", "matching_faces", "matching_vertices",
    "select_all", "shrink", "similar_faces", "vertex_valences",
]

Source = Mesh | MeshArrays

#: the kinds of element a selection holds (:class:`~livemod.dlfl.scene.Selection`'s fields)
KINDS = ("faces", "edges", "vertices", "corners")


def _arrays(mesh: Source) -> MeshArrays:
    return mesh if isinstance(mesh, MeshArrays) else mesh_arrays(mesh)


def _index(ids: np.ndarray, element: Any, what: str) -> int:
    """The dense index of ``element`` among ``ids`` (sorted).

    Raises:
        InvalidArgumentError: ``element`` is not an integer id.
        UnknownIdError: no such element.
    """
    if not is_id(element):
        raise InvalidArgumentError(f"expected a {what} id (an integer), got {shown(element)}")
    at = int(np.searchsorted(ids, int(element)))
    if at == len(ids) or ids[at] != int(element):
        raise UnknownIdError(f"{what} {shown(element)} does not exist")
    return at


def _live_face(mesh: Source, a: MeshArrays, face: Any) -> int:
    """The dense index of ``face``; a :class:`Mesh` names a deleted face as such.

    Raises:
        DLFLError: not a face id, or no such face.
    """
    if isinstance(mesh, Mesh):
        mesh.face_size(face)  # raises naming the face (deleted or never made)
    return _index(a.face_ids, face, "face")


def _live_edge(mesh: Source, a: MeshArrays, edge: Any) -> int:
    """The dense index of ``edge`` (see :func:`_live_face`)."""
    if isinstance(mesh, Mesh):
        mesh.edge_vertices(edge)
    return _index(a.edge_ids, edge, "edge")


def _valences(a: MeshArrays) -> np.ndarray:
    """``(V,)`` number of edges at each vertex (point-spheres 0)."""
    return np.bincount(a.corner_vertex[a.corner_edge >= 0], minlength=len(a.vertex_ids))


def faces_by_size(mesh: Source, sizes: int | Iterable[int]) -> list[int]:
    """Faces with ``sizes`` corners (one size or several); holes left out."""
    wanted = [int(sizes)] if is_id(sizes) else id_list(sizes, "sizes")
    a = _arrays(mesh)
    keep = np.isin(a.face_sizes, wanted) & ~a.face_hole
    return a.face_ids[keep].tolist()


def vertex_valences(mesh: Source) -> dict[int, int]:
    """Vertex id -> valence, for every vertex."""
    a = _arrays(mesh)
    return dict(zip(a.vertex_ids.tolist(), _valences(a).tolist(), strict=True))


def faces_by_vertex_valence(mesh: Source, valence: int, *, every: bool = True) -> list[int]:
    """Faces whose vertices all have ``valence`` (``every=False``: at least one does)."""
    a = _arrays(mesh)
    hit = (_valences(a)[a.corner_vertex] == valence).astype(np.int64)
    per_face = np.bincount(a.corner_face, weights=hit, minlength=len(a.face_ids))
    keep = per_face == a.face_sizes if every else per_face > 0
    return a.face_ids[keep & ~a.face_hole].tolist()


def faces_by_normal(mesh: Source, direction: Any, max_angle: float = 1.0) -> list[int]:
    """Faces whose normal lies within ``max_angle`` degrees of ``direction``.

    Raises:
        DLFLError: ``direction`` is not three finite numbers or is zero, or
            ``max_angle`` is not a finite number.
    """
    d = _direction(direction)
    angle = finite_number(max_angle, "max_angle")
    a = _arrays(mesh)
    cosine = face_normals(a) @ d
    keep = (cosine >= np.cos(np.radians(angle)) - 1e-12) & ~a.face_hole
    return a.face_ids[keep].tolist()


def _direction(direction: Any) -> np.ndarray:
    """``(3,)`` unit vector along ``direction`` (three finite numbers, not all zero).

    Raises:
        DLFLError: anything else, naming ``direction``.
    """
    d = finite_vector(direction, "direction")
    if not np.abs(d).max() > 0.0:
        raise InvalidArgumentError("direction must not be zero")
    return unit(d[None])[0]  # brought into range first: (1e308, 1e308, 0) has a norm


def faces_where(mesh: Mesh, predicate: Callable[[int], bool]) -> list[int]:
    """Faces for which ``predicate(face_id)`` is true (holes left out)."""
    return [f for f in mesh.face_ids().tolist() if not mesh.is_hole(f) and predicate(f)]


def matching_faces(mesh: Source, face: int) -> list[int]:
    """TopMod's ``selectMatchingFaces``: every face of the same size as ``face``.

    Raises:
        DLFLError: ``face`` is not a live face.
    """
    a = _arrays(mesh)
    return faces_by_size(a, int(a.face_sizes[_live_face(mesh, a, face)]))


def matching_edges(mesh: Source, edge: int) -> list[int]:
    """TopMod's ``selectMatchingEdges``: edges whose end valences equal ``edge``'s
    (in either order).

    Raises:
        DLFLError: ``edge`` is not a live edge.
    """
    a = _arrays(mesh)
    at = _live_edge(mesh, a, edge)
    ends = np.sort(_valences(a)[a.edge_vertices], axis=1)  # (E, 2): either order matches
    return a.edge_ids[(ends == ends[at]).all(axis=1)].tolist()


def matching_vertices(mesh: Source, vertex: int) -> list[int]:
    """TopMod's ``selectMatchingVertices``: vertices of the same valence.

    Raises:
        DLFLError: ``vertex`` is not a live vertex.
    """
    a = _arrays(mesh)
    if isinstance(mesh, Mesh):
        mesh.valence(vertex)  # raises naming the vertex (deleted or never made)
    valence = _valences(a)
    return a.vertex_ids[valence == valence[_index(a.vertex_ids, vertex, "vertex")]].tolist()


def faces_by_area(mesh: Source, face: int, delta: float = 0.05) -> list[int]:
    """TopMod's ``selectFacesByArea``: faces whose area is within ``delta`` of ``face``'s.

    Raises:
        DLFLError: ``face`` is not a live face, or ``delta`` is not a finite number.
    """
    delta = finite_number(delta, "delta")
    a = _arrays(mesh)
    areas = face_areas(a)
    target = areas[_live_face(mesh, a, face)]
    with np.errstate(invalid="ignore", over="ignore"):  # areas past the float range: inf
        near = (np.abs(areas - target) <= delta) | (areas == target)
    keep = near & ~a.face_hole
    return a.face_ids[keep].tolist()


def faces_by_colour(mesh: Source, face: int, delta: float = SAME_IN_8_BITS) -> list[int]:
    """TopMod's ``selectFacesByColor``: faces whose colour is within ``delta`` of
    ``face``'s in each channel (the faces without one, when it has none); holes
    left out (see :mod:`livemod.dlfl.colors`).

    Raises:
        DLFLError: ``face`` is not a live face, or ``delta`` is not a finite number.
    """
    delta = finite_number(delta, "delta")
    a = _arrays(mesh)
    i = _live_face(mesh, a, face)
    row = None if a.face_colors is None else a.face_colors[i]
    target = None if row is None or np.isnan(row[0]) else (row[0], row[1], row[2])
    chosen = colored_like(a.face_colors, len(a.face_ids), target, delta)
    return a.face_ids[chosen & ~a.face_hole].tolist()


#: the measures :func:`similar_faces` compares faces by (TopMod's similar-face
#: selections)
SIMILAR_FACES: dict[str, Callable[[Source, int, float], list[int]]] = {
    "size": lambda mesh, face, delta: matching_faces(mesh, face),
    "area": faces_by_area,
    "colour": faces_by_colour,
    "color": faces_by_colour,
}


def similar_faces(mesh: Source, face: int, by: str = "size", delta: float = 0.05) -> list[int]:
    """Faces like ``face`` by a measure of :data:`SIMILAR_FACES`: ``"size"`` (the same
    number of sides, TopMod's SHIFT+S in face mode), ``"area"`` or ``"colour"``
    (within ``delta``; each channel for a colour).

    Raises:
        InvalidArgumentError: an unknown measure.
        DLFLError: ``face`` is not a live face, or a bad ``delta``.
    """
    measure = SIMILAR_FACES.get(by) if isinstance(by, str) else None
    if measure is None:
        known = ", ".join(map(repr, SIMILAR_FACES))
        raise InvalidArgumentError(f"faces are compared by {known}, not {shown(by)}")
    return measure(mesh, face, delta)


def checkerboard(mesh: Source, face: int) -> list[int]:
    """TopMod's checkerboard selection (SHIFT+K): from ``face``, spread to faces that
    share exactly one vertex and no edge with a selected face. On a quad grid or
    a cube subdivided into quads this picks every other face.

    Raises:
        DLFLError: ``face`` is not a live face (the message says whether it was
            deleted).
    """
    a = _arrays(mesh)
    start = _live_face(mesh, a, face)
    first, second = _corner_neighbours(a)
    labels = component_labels(len(a.face_ids), first, second)
    chosen = (labels == labels[start]) & ~a.face_hole
    chosen[start] = True
    return a.face_ids[chosen].tolist()


def _corner_neighbours(a: MeshArrays) -> tuple[np.ndarray, np.ndarray]:
    """The pairs of dense faces, neither a hole, that share exactly one vertex and
    no edge: ``(first, second)``, each ``(k,)``."""
    nf = len(a.face_ids)
    c1, c2 = _corners_at_one_vertex(a)
    f1, f2 = a.corner_face[c1], a.corner_face[c2]
    pairs, shared = np.unique((f1 * nf + f2)[f1 < f2], return_counts=True)
    mated = a.corner_mate >= 0
    across = a.corner_face[mated] * nf + a.corner_face[a.corner_mate[mated]]
    keep = (shared == 1) & ~np.isin(pairs, across)
    first, second = pairs[keep] // nf, pairs[keep] % nf
    solid = ~a.face_hole[first] & ~a.face_hole[second]
    return first[solid], second[solid]


def _corners_at_one_vertex(a: MeshArrays) -> tuple[np.ndarray, np.ndarray]:
    """Every ordered pair of corners at one vertex, ``(first, second)`` dense corner
    indices, each ``(sum of valence^2,)``."""
    order = np.argsort(a.corner_vertex, kind="stable")
    counts = np.bincount(a.corner_vertex, minlength=len(a.vertex_ids))
    starts = np.cumsum(counts) - counts
    owner = np.repeat(np.arange(len(counts)), counts)  # the vertex of each sorted corner
    reach = counts[owner]  # sorted corner i pairs with every corner of its vertex
    first = np.repeat(np.arange(len(order)), reach)
    second = starts[owner[first]] + (np.arange(len(first)) - np.repeat(np.cumsum(reach) - reach,
                                                                       reach))
    return order[first], order[second]


def edge_loop(mesh: Source, edge: int) -> list[int]:
    """The edge loop through ``edge`` (SHIFT+L): at every valence-4 vertex the walk
    goes on along the opposite edge, both ways from ``edge``; it stops at other
    vertices or when it closes.

    Raises:
        DLFLError: ``edge`` is not a live edge.
    """
    a = _arrays(mesh)
    start = _live_edge(mesh, a, edge)
    walk = _LoopWalk(a)
    loop = [start]
    for side in a.edge_corners[start]:
        closed = walk.extend(loop, int(side))
        if closed:
            return a.edge_ids[loop].tolist()
        loop.reverse()
    return a.edge_ids[loop].tolist()


class _LoopWalk:
    """Walks edge loops on ``a``: across valence-4 vertices to the opposite edge."""

    def __init__(self, a: MeshArrays) -> None:
        self.valence = _valences(a)
        self.vnext = a.corner_vnext
        self.edge, self.vertex, self.mate = a.corner_edge, a.corner_vertex, a.corner_mate
        self.sides = a.edge_corners

    def extend(self, loop: list[int], corner: int) -> bool:
        """Extend ``loop`` (ending at the edge of ``corner``, which starts at the vertex
        walked past) while vertices have valence 4; True when it closed."""
        seen = set(loop)
        while self.valence[self.vertex[corner]] == 4:
            opposite = self.vnext[self.vnext[corner]]
            edge = int(self.edge[opposite])
            if edge in seen:
                return edge == loop[0] and len(loop) > 1
            loop.append(edge)
            seen.add(edge)
            # the far end of the new edge: its other side starts there
            corner = int(self.mate[opposite])
        return False


def edge_ring(mesh: Source, edge: int) -> list[int]:
    """The edge ring through ``edge`` (SHIFT+R): across every quad to the opposite
    edge, both ways, stopping at faces that are not quads.

    Raises:
        DLFLError: ``edge`` is not a live edge.
    """
    a = _arrays(mesh)
    edges, _ = _ring(a, _live_edge(mesh, a, edge))
    return a.edge_ids[edges].tolist()


def face_loop(mesh: Source, edge: int) -> list[int]:
    """The face loop across ``edge`` (SHIFT+P): the quads its edge ring crosses.

    Raises:
        DLFLError: ``edge`` is not a live edge.
    """
    a = _arrays(mesh)
    _, faces = _ring(a, _live_edge(mesh, a, edge))
    return a.face_ids[faces].tolist()


def _ring(a: MeshArrays, edge: int) -> tuple[list[int], list[int]]:
    """The dense edges and faces of the ring through dense ``edge``, in walk order."""
    nxt, mate, face_of, edge_of = a.corner_next, a.corner_mate, a.corner_face, a.corner_edge
    sizes, hole = a.face_sizes, a.face_hole
    edges: list[int] = [edge]
    faces: list[int] = []
    for side in dict.fromkeys(a.edge_corners[edge].tolist()):
        corner = side
        face = int(face_of[corner])
        while sizes[face] == 4 and not hole[face] and face not in faces:
            faces.append(face)
            opposite = int(nxt[nxt[corner]])
            across = int(edge_of[opposite])
            if across in edges:
                return edges, faces
            edges.append(across)
            corner = int(mate[opposite])
            face = int(face_of[corner])
        edges.reverse()
        faces.reverse()
    return edges, faces


# -- whole selections: grow, shrink, invert, all --------------------------------------

def kind_field(kind: Any) -> str:
    """The :data:`KINDS` entry (a :class:`~livemod.dlfl.scene.Selection` field) that
    ``kind`` names: itself, or ``"vertices"`` for ``"verts"``.

    Raises:
        InvalidArgumentError: anything else.
    """
    name = {"verts": "vertices"}.get(kind, kind) if isinstance(kind, str) else kind
    if name not in KINDS:
        raise InvalidArgumentError(f"kind must be one of {', '.join(map(repr, KINDS))}, "
                                   f"got {shown(kind)}")
    return str(name)


def _all_ids(a: MeshArrays, kind: str) -> np.ndarray:
    """Every id of ``kind`` a selection can hold (faces: no holes)."""
    if kind == "faces":
        return a.face_ids[~a.face_hole]
    return {"edges": a.edge_ids, "vertices": a.vertex_ids, "corners": a.corner_ids}[kind]


def select_all(mesh: Source, kind: str = "faces") -> list[int]:
    """Every element of ``kind`` (TopMod's CTRL+A); faces without holes.

    Raises:
        InvalidArgumentError: an unknown kind.
    """
    return _all_ids(_arrays(mesh), kind_field(kind)).tolist()


def invert(mesh: Source, ids: Iterable[int], kind: str = "faces") -> list[int]:
    """Every element of ``kind`` not in ``ids`` (TopMod's CTRL+I); ids that are not
    in the mesh are ignored.

    Raises:
        InvalidArgumentError: an unknown kind, or ``ids`` not a list of ids.
    """
    everything = _all_ids(_arrays(mesh), kind_field(kind))
    return everything[~np.isin(everything, id_list(ids, "ids"))].tolist()


def _neighbours(a: MeshArrays, kind: str) -> tuple[np.ndarray, np.ndarray]:
    """The pairs of dense elements TopMod's grow and shrink treat as neighbours:
    faces across an edge, edges at a shared vertex, vertices joined by an edge."""
    has = a.corner_mate >= 0
    corners = np.flatnonzero(has)
    if kind == "faces":
        return a.corner_face[corners], a.corner_face[a.corner_mate[corners]]
    if kind == "vertices":
        return a.corner_vertex[corners], a.corner_vertex[a.corner_mate[corners]]
    # edges: every pair of edges at one vertex (each edge has a side at both ends)
    c1, c2 = _corners_at_one_vertex(a)
    both = (a.corner_edge[c1] >= 0) & (a.corner_edge[c2] >= 0)
    return a.corner_edge[c1[both]], a.corner_edge[c2[both]]


def _dense(a: MeshArrays, kind: str, ids: Iterable[int]) -> tuple[np.ndarray, np.ndarray]:
    """``(ids of kind (N,), mask (N,))``: which of them ``ids`` holds (others ignored)."""
    every = {"faces": a.face_ids, "edges": a.edge_ids, "vertices": a.vertex_ids}[kind]
    return every, np.isin(every, id_list(ids, "ids"))


def grow(mesh: Source, ids: Iterable[int], kind: str = "faces") -> list[int]:
    """``ids`` and their neighbours (TopMod's ``=``): faces across an edge of a
    selected face, edges at a vertex of a selected edge, vertices joined to a
    selected vertex by an edge. Ids not in the mesh are ignored.

    Raises:
        InvalidArgumentError: an unknown kind (corners do not grow), or ``ids``
            not a list of ids.
    """
    a, kind = _arrays(mesh), _grown_kind(kind)
    every, chosen = _dense(a, kind, ids)
    first, second = _neighbours(a, kind)
    grown = chosen.copy()
    grown[second[chosen[first]]] = True
    if kind == "faces":
        grown &= ~a.face_hole
    return every[grown].tolist()


def shrink(mesh: Source, ids: Iterable[int], kind: str = "faces") -> list[int]:
    """``ids`` without those with a neighbour outside them (TopMod's ``-``; the
    neighbours of :func:`grow`). Ids not in the mesh are ignored.

    Raises:
        InvalidArgumentError: as :func:`grow`.
    """
    a, kind = _arrays(mesh), _grown_kind(kind)
    every, chosen = _dense(a, kind, ids)
    first, second = _neighbours(a, kind)
    border = np.zeros(len(every), bool)
    border[first[~chosen[second]]] = True
    return every[chosen & ~border].tolist()


def _grown_kind(kind: Any) -> str:
    """``kind`` for :func:`grow` and :func:`shrink`, which have no rule for corners."""
    name = kind_field(kind)
    if name == "corners":
        raise InvalidArgumentError("corners neither grow nor shrink (TopMod's had no rule for "
                                   "them); use faces, edges or vertices")
    return name
