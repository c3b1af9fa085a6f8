"""The DLFL mesh: vertices, edges, faces and corners, and the minimal operators.

A *corner* is one visit of a face's boundary to a vertex (TopMod's face-vertex).
The corners of a face form a circular doubly linked list (``next``/``prev``).
A corner's edge runs from its vertex to the next corner's vertex, and every edge
has exactly two corners, its two sides, possibly in the same face. An edge's
sides ``(c0, c1)`` always sit at opposite ends: ``next(c0).vertex == c1.vertex``
and ``next(c1).vertex == c0.vertex``. This makes every mesh a closed, oriented
2-manifold by construction. Legal states include point-spheres (an isolated
vertex with a one-corner face and no edge), one- and two-sided faces, faces that
visit a vertex twice, multi-edges, self-loops and several components.

Only the methods of :class:`Mesh` touch the linked structure. Every other
operation is a free function in the module of its family, and reads the mesh
through its public queries and bulk accessors (:meth:`Mesh.positions`,
:meth:`Mesh.face_points`, :meth:`Mesh.hole_mask`, :meth:`Mesh.vertex_ids`,
:meth:`Mesh.has_vertex`, ...). The element tables (``_c``, ``_e``, ``_f``,
``_v``: one :class:`~livemod.dlfl._table.Table` per kind, laid out by the
``*_SPEC`` field lists below) are read by this module and by the two that are
the storage's own: :mod:`~livemod.dlfl.validate` (checks every link) and
:mod:`~livemod.dlfl.arrays` (lays the tables out densely for bulk work). Bulk
builders hand their arrays to :meth:`Mesh.from_tables`. ``tests/layering.py``
counts the reads, and a test keeps every other module off the tables.

Elements are named by integer ids, handed out per kind and never reused within a
mesh; using a deleted id raises :class:`UnknownIdError` (a :class:`DLFLError` and a
:class:`LookupError`) naming it. Bulk operations that rebuild the mesh (subdivision,
dual, loading) give all elements fresh ids; their docstrings say so.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from math import isinf
from typing import Any

import numpy as np

from ._checks import as_point, flag, rgb, whole_count
from ._table import FieldSpec, Table
from .errors import InvalidArgumentError, UnknownIdError

CORNER_SPEC: FieldSpec = {
    "next": (np.int32, ()),
    "prev": (np.int32, ()),
    "face": (np.int32, ()),
    "vertex": (np.int32, ()),
    "edge": (np.int32, ()),
}
EDGE_SPEC: FieldSpec = {"c0": (np.int32, ()), "c1": (np.int32, ())}
# a face's colour is ``color`` when ``colored`` is 1; 0 means the default modelling
# colour (zeros, the value of every fresh slot, mean "no colour")
FACE_SPEC: FieldSpec = {"corner": (np.int32, ()), "hole": (np.uint8, ()),
                        "colored": (np.uint8, ()), "color": (np.float32, (3,))}
VERTEX_SPEC: FieldSpec = {"corner": (np.int32, ()), "position": (np.float64, (3,))}

NO_EDGE = -1


def _alloc(table: Table) -> int:
    """:meth:`Table.alloc` for a table with a free slot, the steady state of
    interactive editing; the general method otherwise."""
    free = table.free
    if not free:
        return table.alloc()
    slot = free.pop()
    eid = table.next_id
    table.next_id = eid + 1
    table.moved[eid] = slot  # a reused slot is never home to a fresh id
    table.idv[slot] = eid
    table._sorted_cache = None
    return slot


def _between(p0: list[float], p1: list[float], t: float) -> list[float]:
    """The point ``t`` of the way from ``p0`` to ``p1`` (3 floats each) as weighted
    ends, which cannot overflow between finite ends (``p1 - p0`` can); clamped to
    the ends, since the rounded sum may step just past one of them."""
    return [min(max(a * (1.0 - t) + b * t, min(a, b)), max(a, b))
            for a, b in zip(p0, p1, strict=True)]


# fields a bulk builder may leave out: zeros (no colour) are what they hold then
OPTIONAL_FIELDS = frozenset({"colored", "color"})


def _adopt(kind: str, spec: FieldSpec, first_id: int, fields: dict[str, np.ndarray],
           ids: np.ndarray | None) -> Table:
    """:meth:`Table.from_arrays` of ``fields`` (and ``ids``), once they are checked
    to be the fields of ``spec``, all of one length (see :meth:`Mesh.from_tables`);
    the :data:`OPTIONAL_FIELDS` left out are zeros."""
    missing = [name for name in spec.keys() - fields.keys() if name in OPTIONAL_FIELDS]
    if missing and fields:
        rows = len(next(iter(fields.values())))
        fields = fields | {name: np.zeros((rows, *spec[name][1]), spec[name][0])
                           for name in missing}
    if fields.keys() != spec.keys():
        raise InvalidArgumentError(
            f"the {kind} table needs the fields {sorted(spec)}, got {sorted(fields)}")
    lengths = {name: len(array) for name, array in fields.items()}
    if len(set(lengths.values())) > 1:
        raise InvalidArgumentError(f"the {kind} table's fields differ in length: {lengths}")
    return Table.from_arrays(kind, spec, first_id, fields, ids)


class Mesh:
    """A DLFL mesh: an always-valid oriented 2-manifold with integer element ids.

    Create one empty (``Mesh()``), from polygons (:func:`livemod.dlfl.from_polygons`)
    or from a file (:func:`livemod.dlfl.io.load_mesh`). The minimal operators
    (:meth:`create_vertex`, :meth:`remove_vertex`, :meth:`insert_edge`,
    :meth:`delete_edge`, :meth:`subdivide_edge`, :meth:`collapse_edge`,
    :meth:`create_face`) keep it valid; each checks its arguments first and
    leaves the mesh unchanged when it raises.

    Attributes:
        notes: messages about repairs made while building the mesh.
    """

    def __init__(self) -> None:
        self._c = Table("corner", CORNER_SPEC)
        self._e = Table("edge", EDGE_SPEC)
        self._f = Table("face", FACE_SPEC)
        self._v = Table("vertex", VERTEX_SPEC)
        self.notes: list[str] = []

    # ------------------------------------------------------------------ counts

    @property
    def num_vertices(self) -> int:
        """Number of live vertices."""
        return self._v.count

    @property
    def num_edges(self) -> int:
        """Number of live edges."""
        return self._e.count

    @property
    def num_faces(self) -> int:
        """Number of live faces, holes included."""
        return self._f.count

    @property
    def num_corners(self) -> int:
        """Number of live corners."""
        return self._c.count

    def counts(self) -> tuple[int, int, int]:
        """``(V, E, F)``, holes counted as faces (the mesh is closed inside)."""
        v, e, f = self._v, self._e, self._f
        # Table.count inlined: the runner reads the counts after every command
        return v.n - len(v.free), e.n - len(e.free), f.n - len(f.free)

    def __repr__(self) -> str:
        v, e, f = self.counts()
        return f"<Mesh V={v} E={e} F={f}>"

    def _repr_png_(self) -> bytes | None:
        """A picture of the mesh for Jupyter (see :mod:`livemod.dlfl.display`)."""
        from .display import picture_png

        return picture_png(self)

    # ------------------------------------------------------------- id listings

    def vertex_ids(self) -> np.ndarray:
        """``(V,)`` int64 ids of the live vertices, in creation order."""
        return self._v.live_ids()

    def edge_ids(self) -> np.ndarray:
        """``(E,)`` int64 ids of the live edges, in creation order."""
        return self._e.live_ids()

    def face_ids(self) -> np.ndarray:
        """``(F,)`` int64 ids of the live faces (holes included), in creation order."""
        return self._f.live_ids()

    def corner_ids(self) -> np.ndarray:
        """``(C,)`` int64 ids of the live corners, in creation order."""
        return self._c.live_ids()

    def has_vertex(self, vertex: int) -> bool:
        """True when ``vertex`` is a live vertex id."""
        return self._v.is_live(vertex)

    def has_edge(self, edge: int) -> bool:
        """True when ``edge`` is a live edge id."""
        return self._e.is_live(edge)

    def has_face(self, face: int) -> bool:
        """True when ``face`` is a live face id."""
        return self._f.is_live(face)

    def has_corner(self, corner: int) -> bool:
        """True when ``corner`` is a live corner id."""
        return self._c.is_live(corner)

    # ------------------------------------------------------- element queries

    def corner_next(self, corner: int) -> int:
        """Id of the corner after ``corner`` in its face."""
        c = self._c
        return c.idv[c.next[c.slot(corner)]]

    def corner_prev(self, corner: int) -> int:
        """Id of the corner before ``corner`` in its face."""
        c = self._c
        return c.idv[c.prev[c.slot(corner)]]

    def corner_face(self, corner: int) -> int:
        """Id of the face ``corner`` belongs to."""
        return self._f.idv[self._c.face[self._c.slot(corner)]]

    def corner_vertex(self, corner: int) -> int:
        """Id of the vertex ``corner`` sits at."""
        return self._v.idv[self._c.vertex[self._c.slot(corner)]]

    def corner_edge(self, corner: int) -> int:
        """Id of the edge from ``corner`` to the next corner; -1 for a point-sphere."""
        e = self._c.edge[self._c.slot(corner)]
        return NO_EDGE if e < 0 else self._e.idv[e]

    def corner_vnext(self, corner: int) -> int:
        """The corner at the same vertex in the next face around it (TopMod's vnext).

        Returns ``corner`` itself for a point-sphere.
        """
        c = self._c
        s = c.slot(corner)
        e = c.edge[s]
        if e < 0:
            return corner
        other = self._other_side(e, s)
        return c.idv[c.next[other]]

    def edge_corners(self, edge: int) -> tuple[int, int]:
        """The two sides ``(c0, c1)`` of ``edge``; ``c0`` runs from its vertex to ``c1``'s."""
        e = self._e
        s = e.slot(edge)
        idv = self._c.idv
        return idv[e.c0[s]], idv[e.c1[s]]

    def edge_vertices(self, edge: int) -> tuple[int, int]:
        """The end vertices of ``edge``: the vertices of its sides ``c0`` and ``c1``."""
        c0, c1 = self.edge_corners(edge)
        return self.corner_vertex(c0), self.corner_vertex(c1)

    def edge_faces(self, edge: int) -> tuple[int, int]:
        """The faces on the two sides of ``edge`` (equal when both sides are one face)."""
        c0, c1 = self.edge_corners(edge)
        return self.corner_face(c0), self.corner_face(c1)

    def face_corner(self, face: int) -> int:
        """Id of the head corner of ``face``, where its walks start."""
        f = self._f
        return self._c.idv[f.corner[f.slot(face)]]

    def face_corners(self, face: int) -> list[int]:
        """Corner ids of ``face`` in ring order from its head."""
        idv = self._c.idv
        return [idv[s] for s in self._ring_slots(self._f.slot(face))]

    def face_vertices(self, face: int) -> list[int]:
        """Vertex ids around ``face`` in ring order from its head."""
        vert = self._c.vertex
        vidv = self._v.idv
        return [vidv[vert[s]] for s in self._ring_slots(self._f.slot(face))]

    def face_edges(self, face: int) -> list[int]:
        """Edge ids around ``face`` in ring order (empty for a point-sphere)."""
        edge = self._c.edge
        eidv = self._e.idv
        return [eidv[edge[s]] for s in self._ring_slots(self._f.slot(face)) if edge[s] >= 0]

    def face_size(self, face: int) -> int:
        """Number of corners of ``face``."""
        return len(self._ring_slots(self._f.slot(face)))

    def is_hole(self, face: int) -> bool:
        """True when ``face`` is a hole: a boundary loop of an open input mesh."""
        return bool(self._f.hole[self._f.slot(face)])

    def set_hole(self, face: int, hole: bool = True) -> None:
        """Flag ``face`` as a hole (not drawn, written out as a boundary) or not.

        Raises:
            UnknownIdError: ``face`` is not live.
            InvalidArgumentError: ``hole`` is not a flag (a string such as
                ``"False"`` would otherwise mean True).
        """
        slot = self._f.slot(face)
        self._f.hole[slot] = 1 if flag(hole, "hole") else 0

    def face_color(self, face: int) -> tuple[float, float, float] | None:
        """The colour ``(r, g, b)`` of ``face`` (floats in ``[0, 1]``, each the
        shortest decimal of the float32 kept), or None when it has none (it is
        drawn and written in the default modelling colour).

        Raises:
            UnknownIdError: ``face`` is not live.
        """
        F = self._f
        slot = F.slot(face)
        if not F.colored[slot]:
            return None
        # the shortest decimal of each float32: (0.2, ...) set reads back as 0.2
        red, green, blue = (float(str(v)) for v in F.arrays["color"][slot])
        return red, green, blue

    def set_face_color(self, face: int, color: Any) -> None:
        """Give ``face`` the colour ``(r, g, b)`` (three numbers in ``[0, 1]``, kept as
        float32), or take its colour away with None.

        Faces an operation makes from ``face`` take its colour (a split's new face,
        subdivision's children, an extrusion's sides and end).

        Raises:
            UnknownIdError: ``face`` is not live.
            InvalidArgumentError: ``color`` is neither None nor three numbers in
                ``[0, 1]``; the mesh is unchanged.
        """
        F = self._f
        slot = F.slot(face)
        if color is None:
            F.colored[slot] = 0
            return
        F.arrays["color"][slot] = rgb(color)
        F.colored[slot] = 1

    def face_colors(self) -> np.ndarray | None:
        """``(F, 3)`` float32 colours of the faces in the order of :meth:`face_ids`,
        a row of NaN for a face without one; None when no face has a colour."""
        F = self._f
        if not F.arrays["colored"][: F.n].any():  # the common case, without the slots
            return None
        slots = F.live_slots()
        colored = F.arrays["colored"][slots].astype(bool)
        if not colored.any():
            return None
        colors = F.arrays["color"][slots]
        colors[~colored] = np.nan
        return colors

    def vertex_corner(self, vertex: int) -> int:
        """Id of one corner at ``vertex``."""
        v = self._v
        return self._c.idv[v.corner[v.slot(vertex)]]

    def vertex_corners(self, vertex: int) -> list[int]:
        """Corner ids at ``vertex`` in rotation order (``corner_vnext``)."""
        idv = self._c.idv
        return [idv[s] for s in self._rotation_slots(self._v.slot(vertex))]

    def vertex_edges(self, vertex: int) -> list[int]:
        """Ids of the edges leaving ``vertex``, one per corner, in rotation order.

        A self-loop appears twice (it leaves the vertex twice).
        """
        edge = self._c.edge
        eidv = self._e.idv
        return [
            eidv[edge[s]] for s in self._rotation_slots(self._v.slot(vertex)) if edge[s] >= 0
        ]

    def vertex_faces(self, vertex: int) -> list[int]:
        """Face ids around ``vertex`` in rotation order, one per corner."""
        face = self._c.face
        fidv = self._f.idv
        return [fidv[face[s]] for s in self._rotation_slots(self._v.slot(vertex))]

    def valence(self, vertex: int) -> int:
        """Number of edge ends at ``vertex`` (0 for a point-sphere; a loop counts twice)."""
        edge = self._c.edge
        return sum(1 for s in self._rotation_slots(self._v.slot(vertex)) if edge[s] >= 0)

    def hole_mask(self) -> np.ndarray:
        """``(F,)`` bool, True for the hole faces, in the order of :meth:`face_ids`."""
        F = self._f
        return F.arrays["hole"][F.live_slots()].astype(bool)

    def is_point_sphere(self, vertex: int) -> bool:
        """True when ``vertex`` is isolated: a one-corner face with no edge."""
        s = self._v.corner[self._v.slot(vertex)]
        return self._c.edge[s] < 0

    def position(self, vertex: int) -> np.ndarray:
        """``(3,)`` float64 copy of the position of ``vertex``."""
        return self._v.arrays["position"][self._v.slot(vertex)].copy()

    def positions(self, vertices: Iterable[int] | np.ndarray) -> np.ndarray:
        """``(k, 3)`` float64 copy of the positions of ``vertices``, in their order.

        Args:
            vertices: ``(k,)`` vertex ids (a list, or an int array: one vectorized
                lookup however many there are).

        Raises:
            InvalidArgumentError: an entry is not an integer.
            UnknownIdError: an entry is not a live vertex id (the first such, in
                order).
        """
        return self._v.arrays["position"][self._v.slots(vertices)]

    def face_points(self, face: int) -> np.ndarray:
        """``(k, 3)`` float64 copy of the positions of ``face``'s corners, in ring
        order from its head (a vertex the face visits twice appears twice).

        Raises:
            UnknownIdError: ``face`` is not a live face id.
        """
        # vertex slots straight from the ring: extrusion reads every face it grows here
        vert = self._c.vertex
        return self._v.arrays["position"][[vert[s] for s in self._ring_slots(self._f.slot(face))]]

    def set_position(self, vertex: int, position: Any) -> None:
        """Move ``vertex`` to ``position`` (three numbers)."""
        xyz = as_point(position)
        self._v.arrays["position"][self._v.slot(vertex)] = xyz

    def corner_at(self, face: int, vertex: int) -> int:
        """The corner of ``face`` at ``vertex`` (the thesis's ``(faceid, vertexid)``).

        Raises:
            UnknownIdError: either id is not live, or the face does not visit the
                vertex.
            InvalidArgumentError: the face visits the vertex more than once (the
                message lists the corner ids to use instead).
        """
        fs = self._f.slot(face)
        vs = self._v.slot(vertex)
        vert = self._c.vertex
        found = [s for s in self._ring_slots(fs) if vert[s] == vs]
        if len(found) == 1:
            return self._c.idv[found[0]]
        if not found:
            raise UnknownIdError(f"face {face} has no corner at vertex {vertex}")
        ids = ", ".join(str(self._c.idv[s]) for s in found)
        raise InvalidArgumentError(
            f"corner ({face}, {vertex}) is ambiguous: face {face} visits vertex "
            f"{vertex} {len(found)} times; use one of the corner ids {ids}"
        )

    # ---------------------------------------------------------- slot helpers

    def _ring_slots(self, face_slot: int) -> list[int]:
        nxt = self._c.next
        start = self._f.corner[face_slot]
        out = [start]
        s = nxt[start]
        while s != start:
            out.append(s)
            s = nxt[s]
        return out

    def _rotation_slots(self, vertex_slot: int) -> list[int]:
        C = self._c
        nxt, edge = C.next, C.edge
        start = self._v.corner[vertex_slot]
        out = [start]
        if edge[start] < 0:
            return out
        s = nxt[self._other_side(edge[start], start)]
        while s != start:
            out.append(s)
            s = nxt[self._other_side(edge[s], s)]
        return out

    def _other_side(self, edge_slot: int, corner_slot: int) -> int:
        E = self._e
        c0 = E.c0[edge_slot]
        return E.c1[edge_slot] if c0 == corner_slot else c0

    # ----------------------------------------------------- minimal operators

    def create_vertex(self, position: Any = (0.0, 0.0, 0.0)) -> int:
        """Create a point-sphere: a new vertex with a one-corner face and no edge.

        Returns:
            The new vertex id (its face is ``corner_face(vertex_corner(v))``).
        """
        xyz = as_point(position)
        C, F, V = self._c, self._f, self._v
        C.reserve(1)
        F.reserve(1)
        V.reserve(1)
        c, f, v = C.alloc(), F.alloc(), V.alloc()
        C.next[c] = c
        C.prev[c] = c
        C.face[c] = f
        C.vertex[c] = v
        C.edge[c] = NO_EDGE
        F.corner[f] = c
        F.hole[f] = 0
        F.colored[f] = 0
        V.corner[v] = c
        V.arrays["position"][v] = xyz
        return V.idv[v]

    def remove_vertex(self, vertex: int) -> None:
        """Remove a point-sphere vertex together with its face and corner.

        Raises:
            UnknownIdError: ``vertex`` is not live.
            InvalidArgumentError: ``vertex`` still has edges (only point-spheres
                can go).
        """
        vs = self._v.slot(vertex)
        c = self._v.corner[vs]
        if self._c.edge[c] >= 0:
            raise InvalidArgumentError(
                f"vertex {vertex} has {self.valence(vertex)} edge end(s); only a "
                "point-sphere (a vertex with no edges) can be removed"
            )
        self._f.release(self._c.face[c])
        self._c.release(c)
        self._v.release(vs)

    def insert_edge(self, corner1: int, corner2: int) -> int:
        """Insert an edge between two corners and return its id.

        Co-facial corners split their face in two (E+1, F+1): the face keeps
        ``corner1`` and the corners after ``corner2``; a new face takes the corners
        from after ``corner1`` up to ``corner2``. Corners of different faces merge
        the faces into one (E+1, F-1): a handle (genus+1) within one component,
        or a join of two components; the merged face keeps ``corner1``'s face id
        and is a hole when either face was one. The new edge's sides are ``(corner1,
        corner2)``: :meth:`edge_corners` returns them in that order, and their
        ``corner_next`` are the two copies made at the far ends.

        Raises:
            UnknownIdError: a corner id is not live.
            InvalidArgumentError: both are the same corner.
        """
        C = self._c
        # Table.slot inlined for ids at their home slot (the common case)
        base, n, idv = C.base, C.n, C.idv
        s1 = corner1 - base if type(corner1) is int else -1
        if not (0 <= s1 < n and idv[s1] == corner1):
            s1 = C.slot(corner1)
        s2 = corner2 - base if type(corner2) is int else -1
        if not (0 <= s2 < n and idv[s2] == corner2):
            s2 = C.slot(corner2)
        if s1 == s2:
            raise InvalidArgumentError(
                f"insert_edge needs two different corners, got corner {corner1} twice"
            )
        E, F = self._e, self._f
        # most calls find room without growing; reserve() would say the same
        if C.n + 2 > C.cap or E.n >= E.cap or F.n >= F.cap:
            C.reserve(2)
            E.reserve(1)
            F.reserve(1)
        if C.face[s1] == C.face[s2]:
            return self._insert_cofacial(s1, s2)
        return self._insert_merge(s1, s2)

    def _copy_corner(self, src: int, face: int) -> int:
        """A new corner at ``src``'s vertex in ``face`` that takes over ``src``'s edge."""
        C = self._c
        dup = C.alloc()
        C.vertex[dup] = C.vertex[src]
        C.face[dup] = face
        e = C.edge[src]
        C.edge[dup] = e
        if e >= 0:
            E = self._e
            if E.c0[e] == src:
                E.c0[e] = dup
            else:
                E.c1[e] = dup
        return dup

    def _insert_cofacial(self, s1: int, s2: int) -> int:
        """Split the face of ``s1`` and ``s2``: ``F = [s1, s2', b..]``, ``F' = [s1', a.., s2]``.

        The hot path of interactive modeling, so the copies are made inline.
        """
        C, E, F = self._c, self._e, self._f
        nxt, prv, face, cedge = C.next, C.prev, C.face, C.edge
        f = face[s1]
        a1, b1 = nxt[s1], nxt[s2]
        fn, e = _alloc(F), _alloc(E)
        F.hole[fn] = F.hole[f]
        colored = F.colored[fn] = F.colored[f]
        if colored:
            F.arrays["color"][fn] = F.arrays["color"][f]
        c1p, c2p = C.alloc_pair()
        ec0, ec1, vert = E.c0, E.c1, C.vertex
        # the copies take over the old edges of corner1 and corner2
        vert[c1p], face[c1p], vert[c2p], face[c2p] = vert[s1], fn, vert[s2], f
        old1, old2 = cedge[s1], cedge[s2]
        cedge[c1p], cedge[c2p] = old1, old2
        if ec0[old1] == s1:
            ec0[old1] = c1p
        else:
            ec1[old1] = c1p
        if ec0[old2] == s2:
            ec0[old2] = c2p
        else:
            ec1[old2] = c2p
        head = F.corner[f]
        moved_head = head == s2
        # the corners strictly between corner1 and corner2 move to the new face
        x = a1
        while x != s2:
            face[x] = fn
            moved_head = moved_head or x == head
            x = nxt[x]
        face[s2] = fn
        # new face: c1' -> a1 ... -> c2 -> c1'; old face: c1 -> c2' -> b1 ...
        nxt[c1p], prv[a1], nxt[s2], prv[c1p] = a1, c1p, c1p, s2
        nxt[s1], prv[c2p], nxt[c2p], prv[b1] = c2p, s1, b1, c2p
        ec0[e], ec1[e], cedge[s1], cedge[s2] = s1, s2, e, e
        F.corner[fn] = c1p
        if moved_head:
            F.corner[f] = c2p if head == s2 else s1
        return E.idv[e]

    def _insert_merge(self, s1: int, s2: int) -> int:
        """Join the faces of slots ``s1`` and ``s2`` (different faces) by a new edge.

        The face of ``s1`` takes every corner and survives; the merged face is a
        hole when either face was one, whatever the argument order, as in
        :meth:`delete_edge` (a face merged into a hole opens). Returns the edge id.
        """
        C, E, F = self._c, self._e, self._f
        nxt, prv, face = C.next, C.prev, C.face
        f1, f2 = face[s1], face[s2]
        # the merged face's boundary runs along the hole's loop: the union is open
        F.hole[f1] |= F.hole[f2]
        if F.colored[f2] and not F.colored[f1]:
            self._take_color(f1, f2)
        a, b = nxt[s1], nxt[s2]
        # a point-sphere side is never copied; a one-corner face with a loop is
        lone1, lone2 = C.edge[s1] < 0, C.edge[s2] < 0
        # every corner of the second face joins the first
        x = s2
        while True:
            face[x] = f1
            x = nxt[x]
            if x == s2:
                break
        after1 = s2 if lone2 else self._copy_corner(s2, f1)
        after2 = s1 if lone1 else self._copy_corner(s1, f1)
        nxt[s1] = after1
        prv[after1] = s1
        if not lone2:
            nxt[after1] = b
            prv[b] = after1
        nxt[s2] = after2
        prv[after2] = s2
        if not lone1:
            nxt[after2] = a
            prv[a] = after2
        e = E.alloc()
        E.c0[e] = s1
        E.c1[e] = s2
        C.edge[s1] = e
        C.edge[s2] = e
        F.corner[f1] = a
        F.release(f2)
        return E.idv[e]

    def delete_edge(self, edge: int, cleanup: bool = True) -> list[int]:
        """Delete ``edge``, the inverse of :meth:`insert_edge`, and return the faces left.

        Two different faces on its sides merge into the first (returns ``[face]``);
        when either is a hole the merged face is a hole (the other face opens).
        One face on both sides splits in two (returns ``[face, new_face]``: the
        face keeps side ``c0``, the new face gets ``c1``); a side with no corners
        left becomes a point-sphere, which ``cleanup`` (TopMod's default) removes
        together with its vertex, leaving it out of the result.

        Both side corners survive (only a loop closing a one-corner face takes
        them along): the corners after them are the ones dropped, so deleting an
        edge right after :meth:`insert_edge` restores every corner id, and
        inserting between the old sides again undoes the deletion.

        Raises:
            UnknownIdError: ``edge`` is not a live edge id.
        """
        E, F = self._e, self._f
        # Table.slot inlined: an id at its home slot, else one in a reused slot
        es = edge - E.base if type(edge) is int else -1
        if not (0 <= es < E.n and E.idv[es] == edge):
            es = E.moved.get(edge, -1) if type(edge) is int else -1
            if es < 0:
                es = E.slot(edge)
        s1, s2 = E.c0[es], E.c1[es]
        if F.n >= F.cap:
            F.reserve(1)
        C = self._c
        nxt, face = C.next, C.face
        f1, f2 = face[s1], face[s2]
        fidv = F.idv  # F does not grow below: its room is reserved
        if f1 == f2:
            result = [fidv[f] for f in self._delete_split(s1, s2, cleanup)]
        elif nxt[s1] == s1 or nxt[s2] == s2:
            result = [fidv[f] for f in self._delete_merge_one_gon(s1, s2, cleanup)]
        else:
            # two faces merge: the second joins the first (undoes a co-facial insert)
            x = nxt[s2]
            while x != s2:
                face[x] = f1
                x = nxt[x]
            face[s2] = f1
            self._drop_after_sides(s1, s2)
            F.hole[f1] |= F.hole[f2]  # a face merged into a hole opens: the union is a hole
            if F.colored[f2] and not F.colored[f1]:
                self._take_color(f1, f2)
            F.release(f2)
            result = [fidv[f1]]
        # E.release(es), inlined for the interactive hot path
        eidv = E.idv
        if E.moved:
            E.moved.pop(eidv[es], None)
        eidv[es] = -1
        E.free.append(es)
        E._sorted_cache = None
        return result

    def _delete_merge_one_gon(self, s1: int, s2: int, cleanup: bool) -> list[int]:
        """Delete a loop that closes a one-corner face; both side corners go."""
        C, F, V = self._c, self._f, self._v
        nxt, prv, face, vert = C.next, C.prev, C.face, C.vertex
        f1, f2 = face[s1], face[s2]
        a, p1, b, p2 = nxt[s1], prv[s1], nxt[s2], prv[s2]
        empty1, empty2 = a == s1, b == s2
        if empty1 and empty2:
            # two one-sided faces on a loop: the vertex is left alone
            return self._merge_to_point_sphere(s1, s2, cleanup)
        x = b
        while x != s2:
            face[x] = f1
            x = nxt[x]
        if empty1:
            nxt[p2], prv[b] = b, p2
            head = b
        else:
            nxt[p1], prv[a] = a, p1
            head = a
        # a vertex whose recorded corner is dropped takes the corner now after it
        vc = V.corner
        if vc[vert[s1]] == s1:
            vc[vert[s1]] = a if empty2 else b
        if vc[vert[s2]] == s2:
            vc[vert[s2]] = b if empty1 else a
        F.corner[f1] = head
        F.hole[f1] |= F.hole[f2]
        if F.colored[f2] and not F.colored[f1]:
            self._take_color(f1, f2)
        C.release(s1)
        C.release(s2)
        F.release(f2)
        return [f1]

    def _merge_to_point_sphere(self, s1: int, s2: int, cleanup: bool) -> list[int]:
        face = self._c.face
        f1, f2 = face[s1], face[s2]
        self._c.release(s2)
        self._f.release(f2)
        if cleanup:
            self._remove_lone_corner(s1, f1)
            return []
        self._make_point_sphere(s1, f1)
        return [f1]

    def _drop_after_sides(self, s1: int, s2: int) -> None:
        """Unlink the corners after the two sides of an edge being deleted.

        The sides stay and take over the edges of the corners after them, so
        that deleting an edge right after inserting it restores every corner id.
        Callers have already moved all corners into one face. This is
        :meth:`_take_place` for both sides, inlined for the interactive hot path.
        """
        C, E = self._c, self._e
        nxt, prv, cedge, vert, face = C.next, C.prev, C.edge, C.vertex, C.face
        ec0, ec1, vc, fc = E.c0, E.c1, self._v.corner, self._f.corner
        cidv, moved, free = C.idv, C.moved, C.free
        merged = face[s1]  # both sides are in this face by now
        head = fc[merged]
        for side, gone in ((s1, nxt[s2]), (s2, nxt[s1])):
            e = cedge[gone]
            cedge[side] = e
            if ec0[e] == gone:
                ec0[e] = side
            else:
                ec1[e] = side
            after = nxt[gone]
            nxt[side] = after
            prv[after] = side
            if vc[vert[gone]] == gone:
                vc[vert[gone]] = side
            if head == gone:
                fc[merged] = side
            moved.pop(cidv[gone], None)
            cidv[gone] = -1
            free.append(gone)
        C._sorted_cache = None

    def _take_place(self, side: int, gone: int) -> None:
        """Corner ``side`` replaces ``gone``, the corner after the other side.

        Both sit at the same vertex; ``side`` takes ``gone``'s edge and its link
        to the next corner (its own ``prev`` already is right) and ``gone`` is
        released. ``side`` must already be in its final face.
        """
        C, E = self._c, self._e
        nxt, edge = C.next, C.edge
        e = edge[gone]
        edge[side] = e
        if E.c0[e] == gone:
            E.c0[e] = side
        else:
            E.c1[e] = side
        after = nxt[gone]
        nxt[side] = after
        C.prev[after] = side
        vc = self._v.corner
        if vc[C.vertex[gone]] == gone:
            vc[C.vertex[gone]] = side
        fc = self._f.corner
        if fc[C.face[side]] == gone:
            fc[C.face[side]] = side
        C.release(gone)

    def _delete_split(self, s1: int, s2: int, cleanup: bool) -> list[int]:
        """Delete an edge with one face on both sides, splitting the face in two.

        The ring reads ``s1, a, x.., s2, b, y..``. The face keeps ``s1`` in place
        of ``b`` with the ``y`` corners; a new face takes ``s2`` in place of ``a``
        with the ``x`` corners (the inverse of a merging insert, restoring its
        corner ids). A side with no corners besides its own becomes a
        point-sphere, removed with its vertex under ``cleanup``.
        """
        C, F = self._c, self._f
        nxt, face = C.next, C.face
        f = face[s1]
        a, b = nxt[s1], nxt[s2]
        fn = F.alloc()
        F.hole[fn] = F.hole[f]
        colored = F.colored[fn] = F.colored[f]
        if colored:
            F.arrays["color"][fn] = F.arrays["color"][f]
        head = F.corner[f]
        head_moves = head in (s2, b)
        x = a
        while x != s2:
            face[x] = fn
            head_moves = head_moves or x == head
            x = nxt[x]
        face[s2] = fn
        F.corner[fn] = s2
        if head_moves:
            F.corner[f] = s1
        result = []
        for side, gone, fs in ((s2, a, fn), (s1, b, f)):
            if gone != side:
                self._take_place(side, gone)
            elif cleanup:
                self._remove_lone_corner(side, fs)
                continue
            else:
                self._make_point_sphere(side, fs)
            result.append(fs)
        return result[::-1]

    def _take_color(self, face_slot: int, source_slot: int) -> None:
        """Give face ``face_slot`` the colour of ``source_slot`` (a merge whose
        surviving face has none keeps the other face's)."""
        F = self._f
        F.colored[face_slot] = 1
        F.arrays["color"][face_slot] = F.arrays["color"][source_slot]

    def _remove_lone_corner(self, s: int, face_slot: int) -> None:
        """Remove corner ``s``, its now isolated vertex and, if given, its face."""
        if face_slot >= 0:
            self._f.release(face_slot)
        self._v.release(self._c.vertex[s])
        self._c.release(s)

    def _make_point_sphere(self, s: int, face_slot: int) -> None:
        """Make corner ``s`` the lone, edgeless corner of ``face_slot``."""
        C = self._c
        C.next[s] = s
        C.prev[s] = s
        C.edge[s] = NO_EDGE
        C.face[s] = face_slot
        self._f.corner[face_slot] = s
        self._v.corner[C.vertex[s]] = s

    def subdivide_edge(self, edge: int, divisions: int = 2) -> list[int]:
        """Split ``edge`` into ``divisions`` equal parts; return the new vertex ids.

        The new vertices sit at ``p0 + i (p1 - p0) / divisions`` from the vertex
        ``p0`` of side ``c0`` (as ``(1 - t) p0 + t p1`` when ``p1 - p0`` overflows,
        between ends far apart near the largest float). The edge keeps its id as
        the first part (from ``p0``); each further part is a new edge.

        Raises:
            UnknownIdError: ``edge`` is not live.
            InvalidArgumentError: ``divisions`` is not an integer >= 1 (or makes
                more corners than a mesh holds).
        """
        divisions = whole_count(divisions, "divisions", each=2)  # 2 corners per new vertex
        es = self._e.slot(edge)
        pos = self._v.arrays["position"]
        C = self._c
        # plain floats: a 3-vector's arithmetic is several times faster than numpy's
        p0 = pos[C.vertex[self._e.c0[es]]].tolist()
        p1 = pos[C.vertex[self._e.c1[es]]].tolist()
        d = [b - a for a, b in zip(p0, p1, strict=True)]
        overflows = any(map(isinf, d))
        new_vertices = []
        last = es
        for i in range(1, int(divisions)):
            t = i / divisions
            point = (_between(p0, p1, t) if overflows
                     else [a + x * t for a, x in zip(p0, d, strict=True)])
            vs, last = self._split_edge_slot(last, point)
            new_vertices.append(self._v.idv[vs])
        return new_vertices

    def _split_edge_slot(self, es: int, point: Any) -> tuple[int, int]:
        """Split edge slot ``es`` at ``point``; return (new vertex slot, new edge slot)."""
        C, E, V = self._c, self._e, self._v
        C.reserve(2)
        E.reserve(1)
        V.reserve(1)
        nxt, prv = C.next, C.prev
        s1, s2 = E.c0[es], E.c1[es]
        a, b = nxt[s1], nxt[s2]
        m = V.alloc()
        V.arrays["position"][m] = point
        n1, n2 = C.alloc(), C.alloc()
        for new, owner in ((n1, s1), (n2, s2)):
            C.vertex[new] = m
            C.face[new] = C.face[owner]
        nxt[s1], prv[n1], nxt[n1], prv[a] = n1, s1, a, n1
        nxt[s2], prv[n2], nxt[n2], prv[b] = n2, s2, b, n2
        e2 = E.alloc()
        E.c1[es] = n2
        E.c0[e2], E.c1[e2] = n1, s2
        C.edge[n2] = es
        C.edge[n1] = e2
        C.edge[s2] = e2
        V.corner[m] = n1
        return m, e2

    def collapse_edge(self, edge: int, cleanup: bool = True) -> int:
        """Collapse ``edge`` to its midpoint and return the surviving vertex id.

        The vertex of side ``c0`` survives at the midpoint and takes over every
        corner of the other end; only when that vertex is a dangling end (its
        one corner, valence 1) and the other is not does the other survive. A
        self-loop is deleted instead (its vertex survives, as a point-sphere
        when nothing else is left). With ``cleanup``
        (TopMod's default) a face left with one or two sides loses one edge, so no
        degenerate face remains.

        Raises:
            UnknownIdError: ``edge`` is not a live edge id.
        """
        E, C, V = self._e, self._c, self._v
        es = E.slot(edge)
        s1, s2 = E.c0[es], E.c1[es]
        v1, v2 = C.vertex[s1], C.vertex[s2]
        survivor = V.idv[v1]
        pos = V.arrays["position"]
        if v1 == v2:
            # a loop between two one-corner faces is all that is left of its
            # vertex: the vertex survives as a point-sphere even with cleanup
            lone = C.next[s1] == s1 and C.next[s2] == s2
            self.delete_edge(edge, cleanup and not lone)
            return survivor
        # halves first: the sum of two far-apart points can overflow, their mean cannot
        midpoint = pos[v1] * 0.5 + pos[v2] * 0.5
        nxt = C.next
        leaf2, leaf1 = nxt[s1] == s2, nxt[s2] == s1
        if leaf1 or leaf2:
            # the edge dangles: deleting it leaves the other end (or one of two)
            keep, drop = (v2, v1) if leaf1 and not leaf2 else (v1, v2)
            self.delete_edge(edge, cleanup=not (leaf1 and leaf2))
            if leaf1 and leaf2:
                self.remove_vertex(V.idv[drop])
            pos[keep] = midpoint
            return V.idv[keep]
        faces = self._collapse_link(es, s1, s2, v1, v2)
        pos[v1] = midpoint
        if cleanup:
            self._cleanup_degenerate(faces)
        return survivor

    def _collapse_link(self, es: int, s1: int, s2: int, v1: int, v2: int) -> list[int]:
        C, E, F, V = self._c, self._e, self._f, self._v
        nxt, prv, vert, edge, face = (
            C.next, C.prev, C.vertex, C.edge, C.face,
        )
        moving = self._rotation_slots(v2)
        a = nxt[s1]  # at v2; removed, corner1 takes its edge
        ea = edge[a]
        edge[s1] = ea
        if ea >= 0:
            if E.c0[ea] == a:
                E.c0[ea] = s1
            else:
                E.c1[ea] = s1
        an = nxt[a]
        nxt[s1], prv[an] = an, s1
        p2, b = prv[s2], nxt[s2]
        nxt[p2], prv[b] = b, p2
        f1, f2 = face[s1], face[s2]
        fc = F.corner
        if fc[f1] == a:
            fc[f1] = s1
        if fc[f2] == s2:
            fc[f2] = b
        for s in moving:
            vert[s] = v1
        C.release(a)
        C.release(s2)
        E.release(es)
        V.release(v2)
        return [f1] if f1 == f2 else [f1, f2]

    def _cleanup_degenerate(self, face_slots: list[int]) -> None:
        """Delete one edge of each listed face that has one or two corners left.

        The deletions keep point-spheres, so that the surviving vertex of a
        collapse is never removed.
        """
        F = self._f
        for face in [F.idv[fs] for fs in face_slots]:
            if not F.is_live(face):
                continue
            ring = self._ring_slots(F.slot(face))
            edge = self._c.edge[ring[0]]
            if len(ring) <= 2 and edge >= 0:
                self.delete_edge(self._e.idv[edge], cleanup=False)

    def create_face(self, points: Sequence[Any]) -> tuple[int, int]:
        """Create a two-sided polygon on new vertices: ``(front, back)`` face ids.

        The front face visits the points in the given order, the back face in
        reverse, starting at the first point; they share all their edges
        (V+n, E+n, F+2).

        Raises:
            InvalidArgumentError: fewer than two points, or a point is not three
                finite numbers.
        """
        if isinstance(points, (str, bytes)) or not hasattr(points, "__iter__"):
            raise InvalidArgumentError(
                f"create_face needs a sequence of (x, y, z) points, got {points!r}")
        pts = [as_point(p) for p in points]
        n = len(pts)
        if n < 2:
            raise InvalidArgumentError(f"create_face needs at least 2 points, got {n}")
        C, E, F, V = self._c, self._e, self._f, self._v
        C.reserve(2 * n)
        E.reserve(n)
        F.reserve(2)
        V.reserve(n)
        verts = [V.alloc() for _ in range(n)]
        V.arrays["position"][verts] = pts
        front, back = F.alloc(), F.alloc()
        fc = [C.alloc() for _ in range(n)]
        bc = [C.alloc() for _ in range(n)]
        self._link_ring(fc, front, verts)
        # back ring visits the points reversed, starting at point 0
        back_verts = [verts[0]] + verts[:0:-1]
        self._link_ring(bc, back, back_verts)
        for i in range(n):
            # front corner i runs v_i -> v_{i+1}; its twin runs v_{i+1} -> v_i
            twin = bc[(n - 1 - i) % n]
            e = E.alloc()
            E.c0[e], E.c1[e] = fc[i], twin
            C.edge[fc[i]] = e
            C.edge[twin] = e
        for i, v in enumerate(verts):
            V.corner[v] = fc[i]
        return F.idv[front], F.idv[back]

    def reverse_faces(self, faces: Iterable[int] | None = None) -> None:
        """Reverse the corner order of ``faces`` (None: every face), flipping their
        normals; ids, heads and positions stay.

        Each corner's edge becomes the one to its new next corner (its old
        previous one's), and each edge's sides move along with it, so the sides
        still sit at opposite ends. ``faces`` must hold both sides of every edge
        of theirs, as whole components do: one face alone cannot turn over on an
        oriented surface.

        Raises:
            DLFLError: an id that is not a live face, or an edge with one side in
                ``faces`` and the other not (named); nothing changes.
        """
        C, E = self._c, self._e
        if faces is None:
            corners = C.live_slots()
        else:
            rings = [self._ring_slots(self._f.slot(f)) for f in faces]
            corners = np.array([c for ring in rings for c in ring], dtype=np.int64)
        nxt, prv, edge = C.arrays["next"], C.arrays["prev"], C.arrays["edge"]
        c0, c1 = E.arrays["c0"], E.arrays["c1"]
        sides = np.unique(edge[corners][edge[corners] >= 0]).astype(np.int64)
        inside = np.zeros(C.n, bool)
        inside[corners] = True
        half = sides[inside[c0[sides]] != inside[c1[sides]]]
        if len(half):
            raise InvalidArgumentError(
                f"edge {E.idv[int(half[0])]} has one side in the faces to reverse and one "
                "outside; reverse whole components")
        old_next, old_prev = nxt[corners], prv[corners]
        new_edge = edge[old_prev]
        c0[sides], c1[sides] = nxt[c0[sides]], nxt[c1[sides]]
        nxt[corners], prv[corners], edge[corners] = old_prev, old_next, new_edge

    def _link_ring(self, corners: list[int], face_slot: int, verts: list[int]) -> None:
        C = self._c
        n = len(corners)
        for i, c in enumerate(corners):
            C.next[c] = corners[(i + 1) % n]
            C.prev[c] = corners[i - 1]
            C.face[c] = face_slot
            C.vertex[c] = verts[i]
        self._f.corner[face_slot] = corners[0]
        self._f.hole[face_slot] = 0
        self._f.colored[face_slot] = 0

    # ------------------------------------------------------------ whole mesh

    @classmethod
    def from_tables(
        cls,
        corners: dict[str, np.ndarray],
        edges: dict[str, np.ndarray],
        faces: dict[str, np.ndarray],
        vertices: dict[str, np.ndarray],
        first_ids: tuple[int, int, int, int] = (0, 0, 0, 0),
        ids: tuple[np.ndarray | None, np.ndarray | None, np.ndarray | None,
                   np.ndarray | None] | None = None,
    ) -> Mesh:
        """A mesh adopting ready-made element tables: the bulk builders' constructor.

        Each argument maps every field of its kind's spec (:data:`CORNER_SPEC`,
        :data:`EDGE_SPEC`, :data:`FACE_SPEC`, :data:`VERTEX_SPEC`) to an array with
        one row per element (a face's ``colored`` and ``color`` may be left out:
        no colour); every reference (a corner's ``next``, ``face``, ...,
        an edge's ``c0``/``c1``, a face's or a vertex's ``corner``) is a row index
        of the table it refers to. Element ``i`` of a kind gets the id
        ``first_ids[k] + i``, in the order vertex, edge, face, corner, or, where
        ``ids`` gives that kind's ``(n,)`` distinct ids, ``ids[k][i]`` (later
        elements then get ids past the largest). Arrays whose dtype already
        matches are adopted, not copied.

        The links are trusted, not checked (this is the fast path of every bulk
        operation); run :func:`livemod.dlfl.validate` on the result in tests.

        Raises:
            InvalidArgumentError: a field missing or unknown, or fields of one
                kind of different lengths.
        """
        mesh = cls.__new__(cls)
        mesh.notes = []
        vid, eid, fid, cid = first_ids
        vids, eids, fids, cids = ids or (None, None, None, None)
        mesh._c = _adopt("corner", CORNER_SPEC, cid, corners, cids)
        mesh._e = _adopt("edge", EDGE_SPEC, eid, edges, eids)
        mesh._f = _adopt("face", FACE_SPEC, fid, faces, fids)
        mesh._v = _adopt("vertex", VERTEX_SPEC, vid, vertices, vids)
        return mesh

    def copy(self) -> Mesh:
        """A deep copy with the same ids."""
        other = Mesh.__new__(Mesh)
        other._c = self._c.copy()
        other._e = self._e.copy()
        other._f = self._f.copy()
        other._v = self._v.copy()
        other.notes = list(self.notes)
        return other

    def replace_with(self, other: Mesh) -> None:
        """Take over the contents of ``other`` (used by bulk operations in place)."""
        self._c, self._e, self._f, self._v = other._c, other._e, other._f, other._v
        self.notes = other.notes

    def next_ids(self) -> tuple[int, int, int, int]:
        """The ids the next vertex, edge, face and corner will get."""
        return self._v.next_id, self._e.next_id, self._f.next_id, self._c.next_id

    def positions_view(self) -> np.ndarray:
        """``(V, 3)`` float64 copy of the live vertex positions, in id order."""
        return self._v.arrays["position"][self._v.live_slots()]

    def set_positions(self, vertices: Iterable[int] | np.ndarray, positions: Any) -> None:
        """Set the positions of many vertices at once.

        Args:
            vertices: ``(k,)`` vertex ids.
            positions: ``(k, 3)`` floats, or ``(3,)`` for all of them.

        Raises:
            UnknownIdError: an id that is not a live vertex.
            InvalidArgumentError: positions of another shape, or a NaN or
                infinite coordinate (nothing is moved then).
        """
        if not hasattr(vertices, "__iter__"):
            raise InvalidArgumentError(
                f"set_positions needs a sequence of vertex ids, got {vertices!r}")
        slots = [self._v.slot(v) for v in vertices]
        try:
            values = np.asarray(positions, dtype=np.float64)
        except (TypeError, ValueError):
            raise InvalidArgumentError(f"positions must be numbers, got {positions!r}") from None
        if values.shape not in ((3,), (len(slots), 3)):
            raise InvalidArgumentError(
                f"positions must have shape (3,) or ({len(slots)}, 3), got {values.shape}"
            )
        if not np.isfinite(values).all():
            raise InvalidArgumentError("positions must be finite numbers (NaN or infinity given)")
        self._v.arrays["position"][slots] = values
