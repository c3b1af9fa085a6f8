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

Only :class:`Mesh` changes the linked structure: its operators are the entry
points, which check their arguments and hand slots to their bodies in
:mod:`~livemod.dlfl._operators`. Every other operation is a free function in the
module of its family, and reads the mesh through its public queries and bulk
accessors (:meth:`Mesh.positions`, :meth:`Mesh.face_points`, :meth:`Mesh.hole_mask`,
:meth:`Mesh.vertex_ids`, :meth:`Mesh.has_vertex`, ...). The element tables (``_c``,
``_e``, ``_f``, ``_v``: one :class:`~livemod.dlfl._table.Table` per kind, laid out
by the field lists of :mod:`~livemod.dlfl._storage`) are read by this module and
by those that are the storage's own: :mod:`~livemod.dlfl._storage` (the tables,
``Mesh``'s base), :mod:`~livemod.dlfl._operators` (the operators' slot-level
bodies), :mod:`~livemod.dlfl.validate` (checks every link) and
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
from typing import Any

import numpy as np

from ._checks import as_point, whole_count
from ._operators import (
    NO_EDGE,
    add_point_sphere,
    collapse_edge_slot,
    create_face_rings,
    delete_merge,
    delete_merge_one_gon,
    delete_split,
    insert_cofacial,
    insert_merge,
    reverse_rings,
    subdivide_edge_slot,
)
from ._storage import MeshStorage
from .errors import InvalidArgumentError, UnknownIdError


class Mesh(MeshStorage):
    """A DLFL mesh: an always-valid oriented 2-manifold with integer element ids.

    Create one empty (``Mesh()``), from polygons (:func:`livemod.dlfl.from_polygons`)
    or from a file (:func:`livemod.dlfl.io.load_mesh`). The minimal operators
    (:meth:`create_vertex`, :meth:`remove_vertex`, :meth:`insert_edge`,
    :meth:`delete_edge`, :meth:`subdivide_edge`, :meth:`collapse_edge`,
    :meth:`create_face`) keep it valid; each checks its arguments first and
    leaves the mesh unchanged when it raises.

    The class is two layers, each a concern of its own: :class:`MeshStorage`
    (its base, in :mod:`~livemod.dlfl._storage`) holds the element tables and
    what reads one element's row (counts, ids, positions, hole flags, colours,
    :meth:`from_tables`, :meth:`copy`); this class holds the links between them,
    the navigation that follows them and the operators that change them.

    Attributes:
        notes: messages about repairs made while building the mesh.
    """

    def __repr__(self) -> str:
        v, e, f = self.counts()
        return f"<Mesh V={v} E={e} F={f}>"

    def _repr_png_(self) -> bytes | None:
        """A picture of the mesh for Jupyter (see :mod:`livemod.dlfl.display`)."""
        from .display import picture_png

        return picture_png(self)

    # -------------------------------------------------------------- navigation

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

    def is_point_sphere(self, vertex: int) -> bool:
        """True when ``vertex`` is isolated: a one-corner face with no edge."""
        s = self._v.corner[self._v.slot(vertex)]
        return self._c.edge[s] < 0

    def face_points(self, face: int) -> np.ndarray:
        """``(k, 3)`` float64 copy of the positions of ``face``'s corners, in ring
        order from its head (a vertex the face visits twice appears twice).

        Raises:
            UnknownIdError: ``face`` is not a live face id.
        """
        # vertex slots straight from the ring: extrusion reads every face it grows here
        vert = self._c.vertex
        return self._v.arrays["position"][[vert[s] for s in self._ring_slots(self._f.slot(face))]]

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

    # ------------------------------------------------------------ slot helpers

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

    # ------------------------------------------------------- minimal operators

    def create_vertex(self, position: Any = (0.0, 0.0, 0.0)) -> int:
        """Create a point-sphere: a new vertex with a one-corner face and no edge.

        Returns:
            The new vertex id (its face is ``corner_face(vertex_corner(v))``).
        """
        return add_point_sphere(self, as_point(position))

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
            return insert_cofacial(self, s1, s2)
        return insert_merge(self, s1, s2)

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
            result = [fidv[f] for f in delete_split(self, s1, s2, cleanup)]
        elif nxt[s1] == s1 or nxt[s2] == s2:
            result = [fidv[f] for f in delete_merge_one_gon(self, s1, s2, cleanup)]
        else:
            # two faces merge: the second joins the first (undoes a co-facial insert)
            result = [fidv[delete_merge(self, s1, s2, f1, f2)]]
        # E.release(es), inlined for the interactive hot path
        eidv = E.idv
        if E.moved:
            E.moved.pop(eidv[es], None)
        eidv[es] = -1
        E.free.append(es)
        E._sorted_cache = None
        return result

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
        return subdivide_edge_slot(self, self._e.slot(edge), divisions)

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
        return collapse_edge_slot(self, self._e.slot(edge), cleanup)

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
        return create_face_rings(self, pts)

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
        reverse_rings(self, faces)
