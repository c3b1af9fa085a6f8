"""The minimal operators' slot-level bodies: the linked-list surgery behind
:meth:`Mesh.insert_edge <livemod.dlfl.mesh.Mesh.insert_edge>`,
:meth:`~livemod.dlfl.mesh.Mesh.delete_edge` and the other operators of
:class:`~livemod.dlfl.mesh.Mesh`.

This module is one of the storage's own (see :mod:`livemod.dlfl.mesh`): it reads
and writes the element tables ``mesh._c/_e/_f/_v`` directly, by *slot*, and so
must only be called by :class:`Mesh`, whose public methods are the documented
entry points. Those methods check every argument, turn ids into slots and make
room in the tables; the functions here trust both (slots are live, the tables
have the room the operator needs) and change the mesh from one valid state to
the next. Each returns slots (or ids where the entry point returns ids), never
raising but for the errors the entry points document.

The insert/delete pair is the hot path of interactive modeling: the entry points
call :func:`insert_cofacial`, :func:`insert_merge`, :func:`delete_merge`, ... directly
(one call level, as when they were methods) and these inline what a helper
would do twice per call.
"""

from __future__ import annotations

from collections.abc import Iterable
from math import isinf
from typing import TYPE_CHECKING, Any

import numpy as np

from ._table import Table
from .errors import InvalidArgumentError

if TYPE_CHECKING:
    from .mesh import Mesh

NO_EDGE = -1


def alloc(table: Table) -> int:
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


def between(p0: list[float], p1: list[float], t: float) -> list[float]:
    """The point ``t`` of the way from ``p0`` to ``p1`` (3 floats each) as weighted
    ends, which cannot overflow between finite ends (``p1 - p0`` can); clamped to
    the ends, since the rounded sum may step just past one of them."""
    return [min(max(a * (1.0 - t) + b * t, min(a, b)), max(a, b))
            for a, b in zip(p0, p1, strict=True)]


# ------------------------------------------------------------- point-spheres

def add_point_sphere(mesh: Mesh, xyz: tuple[float, float, float]) -> int:
    """A new vertex at ``xyz`` with a one-corner face and no edge; its id."""
    C, F, V = mesh._c, mesh._f, mesh._v
    # most calls find room without growing; reserve() would say the same
    if C.n >= C.cap or F.n >= F.cap or V.n >= V.cap:
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
    if mesh._colors_used:
        F.colored[f] = 0
    V.corner[v] = c
    V.arrays["position"][v] = xyz
    return V.idv[v]


def remove_lone_corner(mesh: Mesh, s: int, face_slot: int) -> None:
    """Remove corner ``s``, its now isolated vertex and, if given (>= 0), its face."""
    if face_slot >= 0:
        mesh._f.release(face_slot)
    mesh._v.release(mesh._c.vertex[s])
    mesh._c.release(s)


def make_point_sphere(mesh: Mesh, s: int, face_slot: int) -> None:
    """Make corner ``s`` the lone, edgeless corner of ``face_slot``."""
    C = mesh._c
    C.next[s] = s
    C.prev[s] = s
    C.edge[s] = NO_EDGE
    C.face[s] = face_slot
    mesh._f.corner[face_slot] = s
    mesh._v.corner[C.vertex[s]] = s


def take_color(F: Table, face_slot: int, source_slot: int) -> None:
    """Give face ``face_slot`` of table ``F`` the colour of ``source_slot`` (a
    merge whose surviving face has none keeps the other face's)."""
    F.colored[face_slot] = 1
    F.arrays["color"][face_slot] = F.arrays["color"][source_slot]


def inherit_color(F: Table, face_slot: int, source_slot: int) -> None:
    """Give the new face ``face_slot`` of table ``F`` the colour of ``source_slot``,
    or none when that has none (a split's new face takes its face's colour).
    Callers skip it while the mesh has no colours (``_colors_used``): the new
    face's flag then is 0 already, as every other is."""
    colored = F.colored[face_slot] = F.colored[source_slot]
    if colored:
        F.arrays["color"][face_slot] = F.arrays["color"][source_slot]


# ---------------------------------------------------------------- insert_edge

def copy_corner(mesh: Mesh, src: int, face: int) -> int:
    """A new corner at ``src``'s vertex in ``face`` that takes over ``src``'s edge."""
    C = mesh._c
    dup = C.alloc()
    C.vertex[dup] = C.vertex[src]
    C.face[dup] = face
    e = C.edge[src]
    C.edge[dup] = e
    if e >= 0:
        E = mesh._e
        if E.c0[e] == src:
            E.c0[e] = dup
        else:
            E.c1[e] = dup
    return dup


def insert_cofacial(mesh: Mesh, s1: int, s2: int) -> int:
    """Split the face of corner slots ``s1`` and ``s2`` by a new edge; its id.

    ``F = [s1, s2', b..]``, ``F' = [s1', a.., s2]``. The tables have room for two
    corners, an edge and a face. The hot path of interactive modeling, so the
    copies are made inline.
    """
    C, E, F = mesh._c, mesh._e, mesh._f
    nxt, prv, face, cedge = C.next, C.prev, C.face, C.edge
    f = face[s1]
    a1, b1 = nxt[s1], nxt[s2]
    fn, e = alloc(F), alloc(E)
    F.hole[fn] = F.hole[f]
    if mesh._colors_used:
        inherit_color(F, fn, f)
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


def insert_merge(mesh: Mesh, s1: int, s2: int) -> int:
    """Join the faces of slots ``s1`` and ``s2`` (different faces) by a new edge; its id.

    The face of ``s1`` takes every corner and survives; the merged face is a
    hole when either face was one, whatever the argument order, as in
    :func:`delete_merge` (a face merged into a hole opens). The tables have room
    for two corners and an edge.
    """
    C, E, F = mesh._c, mesh._e, mesh._f
    nxt, prv, face = C.next, C.prev, C.face
    f1, f2 = face[s1], face[s2]
    # the merged face's boundary runs along the hole's loop: the union is open
    if F.hole[f2]:
        F.hole[f1] = 1
    if mesh._colors_used and F.colored[f2] and not F.colored[f1]:
        take_color(F, f1, f2)
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
    after1 = s2 if lone2 else copy_corner(mesh, s2, f1)
    after2 = s1 if lone1 else copy_corner(mesh, s1, f1)
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


# ---------------------------------------------------------------- delete_edge

def delete_merge(mesh: Mesh, s1: int, s2: int, f1: int, f2: int) -> int:
    """Unlink the edge of sides ``s1`` and ``s2``, of faces ``f1`` and ``f2`` of more
    than one corner each: the second face joins the first (undoes a co-facial insert).
    Returns the merged face's slot; the edge's slot is the caller's to release.

    The sides stay and take over the edges of the corners after them, so that
    deleting an edge right after inserting it restores every corner id. This is
    :func:`take_place` for both sides, inlined for the interactive hot path.
    """
    C, E, F = mesh._c, mesh._e, mesh._f
    nxt, prv, cedge, vert, face = C.next, C.prev, C.edge, C.vertex, C.face
    x = nxt[s2]
    while x != s2:
        face[x] = f1
        x = nxt[x]
    face[s2] = f1
    ec0, ec1, vc, fc = E.c0, E.c1, mesh._v.corner, F.corner
    cidv, moved, free = C.idv, C.moved, C.free
    head = fc[f1]
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
            fc[f1] = side
        moved.pop(cidv[gone], None)
        cidv[gone] = -1
        free.append(gone)
    C._sorted_cache = None
    if F.hole[f2]:  # a face merged into a hole opens: the union is a hole
        F.hole[f1] = 1
    if mesh._colors_used and F.colored[f2] and not F.colored[f1]:
        take_color(F, f1, f2)
    F.release(f2)
    return f1


def delete_merge_one_gon(mesh: Mesh, s1: int, s2: int, cleanup: bool) -> list[int]:
    """Delete a loop that closes a one-corner face; both side corners go.
    Returns the slots of the faces left (see :meth:`Mesh.delete_edge`)."""
    C, F, V = mesh._c, mesh._f, mesh._v
    nxt, prv, face, vert = C.next, C.prev, C.face, C.vertex
    f1, f2 = face[s1], face[s2]
    a, p1, b, p2 = nxt[s1], prv[s1], nxt[s2], prv[s2]
    empty1, empty2 = a == s1, b == s2
    if empty1 and empty2:
        # two one-sided faces on a loop: the vertex is left alone
        return merge_to_point_sphere(mesh, s1, s2, cleanup)
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
    if F.hole[f2]:
        F.hole[f1] = 1
    if mesh._colors_used and F.colored[f2] and not F.colored[f1]:
        take_color(F, f1, f2)
    C.release(s1)
    C.release(s2)
    F.release(f2)
    return [f1]


def merge_to_point_sphere(mesh: Mesh, s1: int, s2: int, cleanup: bool) -> list[int]:
    """Delete a loop between two one-corner faces: ``s1``'s face is left as a
    point-sphere, or removed with its vertex under ``cleanup``. The face slots left."""
    face = mesh._c.face
    f1, f2 = face[s1], face[s2]
    mesh._c.release(s2)
    mesh._f.release(f2)
    if cleanup:
        remove_lone_corner(mesh, s1, f1)
        return []
    make_point_sphere(mesh, s1, f1)
    return [f1]


def take_place(mesh: Mesh, side: int, gone: int) -> None:
    """Corner ``side`` replaces ``gone``, the corner after the other side.

    Both sit at the same vertex; ``side`` takes ``gone``'s edge and its link
    to the next corner (its own ``prev`` already is right) and ``gone`` is
    released. ``side`` must already be in its final face.
    """
    C, E = mesh._c, mesh._e
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
    vc = mesh._v.corner
    if vc[C.vertex[gone]] == gone:
        vc[C.vertex[gone]] = side
    fc = mesh._f.corner
    if fc[C.face[side]] == gone:
        fc[C.face[side]] = side
    C.release(gone)


def delete_split(mesh: Mesh, s1: int, s2: int, cleanup: bool) -> list[int]:
    """Delete an edge with one face on both sides, splitting the face in two; the
    slots of the faces left. The face table has room for one face.

    The ring reads ``s1, a, x.., s2, b, y..``. The face keeps ``s1`` in place
    of ``b`` with the ``y`` corners; a new face takes ``s2`` in place of ``a``
    with the ``x`` corners (the inverse of a merging insert, restoring its
    corner ids). A side with no corners besides its own becomes a
    point-sphere, removed with its vertex under ``cleanup``.
    """
    C, F = mesh._c, mesh._f
    nxt, face = C.next, C.face
    f = face[s1]
    a, b = nxt[s1], nxt[s2]
    fn = F.alloc()
    F.hole[fn] = F.hole[f]
    if mesh._colors_used:
        inherit_color(F, fn, f)
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
            take_place(mesh, side, gone)
        elif cleanup:
            remove_lone_corner(mesh, side, fs)
            continue
        else:
            make_point_sphere(mesh, side, fs)
        result.append(fs)
    return result[::-1]


# ------------------------------------------------------ subdivide and collapse

def subdivide_edge_slot(mesh: Mesh, es: int, divisions: int) -> list[int]:
    """Split edge slot ``es`` into ``divisions`` (a checked count) equal parts; the
    new vertex ids (see :meth:`Mesh.subdivide_edge`)."""
    pos = mesh._v.arrays["position"]
    C, E = mesh._c, mesh._e
    # plain floats: a 3-vector's arithmetic is several times faster than numpy's
    p0 = pos[C.vertex[E.c0[es]]].tolist()
    p1 = pos[C.vertex[E.c1[es]]].tolist()
    d = [b - a for a, b in zip(p0, p1, strict=True)]
    overflows = any(map(isinf, d))
    new_vertices = []
    last = es
    for i in range(1, int(divisions)):
        t = i / divisions
        point = (between(p0, p1, t) if overflows
                 else [a + x * t for a, x in zip(p0, d, strict=True)])
        vs, last = split_edge_slot(mesh, last, point)
        new_vertices.append(mesh._v.idv[vs])
    return new_vertices


def split_edge_slot(mesh: Mesh, es: int, point: Any) -> tuple[int, int]:
    """Split edge slot ``es`` at ``point``; return (new vertex slot, new edge slot)."""
    C, E, V = mesh._c, mesh._e, mesh._v
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


def collapse_edge_slot(mesh: Mesh, es: int, cleanup: bool) -> int:
    """Collapse edge slot ``es`` to its midpoint; the surviving vertex id (see
    :meth:`Mesh.collapse_edge`)."""
    E, C, V = mesh._e, mesh._c, mesh._v
    edge = E.idv[es]
    s1, s2 = E.c0[es], E.c1[es]
    v1, v2 = C.vertex[s1], C.vertex[s2]
    survivor = V.idv[v1]
    pos = V.arrays["position"]
    if v1 == v2:
        # a loop between two one-corner faces is all that is left of its
        # vertex: the vertex survives as a point-sphere even with cleanup
        lone = C.next[s1] == s1 and C.next[s2] == s2
        mesh.delete_edge(edge, cleanup and not lone)
        return survivor
    # halves first: the sum of two far-apart points can overflow, their mean cannot
    midpoint = pos[v1] * 0.5 + pos[v2] * 0.5
    nxt = C.next
    leaf2, leaf1 = nxt[s1] == s2, nxt[s2] == s1
    if leaf1 or leaf2:
        # the edge dangles: deleting it leaves the other end (or one of two)
        keep, drop = (v2, v1) if leaf1 and not leaf2 else (v1, v2)
        mesh.delete_edge(edge, cleanup=not (leaf1 and leaf2))
        if leaf1 and leaf2:
            mesh.remove_vertex(V.idv[drop])
        pos[keep] = midpoint
        return V.idv[keep]
    faces = collapse_link(mesh, es, s1, s2, v1, v2)
    pos[v1] = midpoint
    if cleanup:
        cleanup_degenerate(mesh, faces)
    return survivor


def collapse_link(mesh: Mesh, es: int, s1: int, s2: int, v1: int, v2: int) -> list[int]:
    """Merge vertex slot ``v2`` into ``v1`` along edge slot ``es`` (sides ``s1`` at
    ``v1``, ``s2`` at ``v2``), dropping the edge, ``v2`` and a corner of each
    side's face; the slots of those faces."""
    C, E, F, V = mesh._c, mesh._e, mesh._f, mesh._v
    nxt, prv, vert, edge, face = (
        C.next, C.prev, C.vertex, C.edge, C.face,
    )
    moving = mesh._rotation_slots(v2)
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


def cleanup_degenerate(mesh: Mesh, face_slots: list[int]) -> None:
    """Delete one edge of each listed face that has one or two corners left.

    The deletions keep point-spheres, so that the surviving vertex of a
    collapse is never removed.
    """
    F = mesh._f
    for face in [F.idv[fs] for fs in face_slots]:
        if not F.is_live(face):
            continue
        ring = mesh._ring_slots(F.slot(face))
        edge = mesh._c.edge[ring[0]]
        if len(ring) <= 2 and edge >= 0:
            mesh.delete_edge(mesh._e.idv[edge], cleanup=False)


# ------------------------------------------------------------- whole faces

def create_face_rings(mesh: Mesh, points: list[tuple[float, float, float]]) -> tuple[int, int]:
    """A two-sided polygon on new vertices at ``points`` (n >= 2 checked points):
    ``(front, back)`` face ids (see :meth:`Mesh.create_face`)."""
    n = len(points)
    C, E, F, V = mesh._c, mesh._e, mesh._f, mesh._v
    C.reserve(2 * n)
    E.reserve(n)
    F.reserve(2)
    V.reserve(n)
    verts = [V.alloc() for _ in range(n)]
    V.arrays["position"][verts] = points
    front, back = F.alloc(), F.alloc()
    fc = [C.alloc() for _ in range(n)]
    bc = [C.alloc() for _ in range(n)]
    link_ring(mesh, fc, front, verts)
    # back ring visits the points reversed, starting at point 0
    back_verts = [verts[0]] + verts[:0:-1]
    link_ring(mesh, bc, back, back_verts)
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


def link_ring(mesh: Mesh, corners: list[int], face_slot: int, verts: list[int]) -> None:
    """Link corner slots ``corners`` (at vertex slots ``verts``) into the ring of
    ``face_slot``, an uncoloured face that is not a hole."""
    C = mesh._c
    n = len(corners)
    for i, c in enumerate(corners):
        C.next[c] = corners[(i + 1) % n]
        C.prev[c] = corners[i - 1]
        C.face[c] = face_slot
        C.vertex[c] = verts[i]
    mesh._f.corner[face_slot] = corners[0]
    mesh._f.hole[face_slot] = 0
    if mesh._colors_used:
        mesh._f.colored[face_slot] = 0


def reverse_rings(mesh: Mesh, faces: Iterable[int] | None) -> None:
    """Reverse the corner order of ``faces`` (None: every face); see
    :meth:`Mesh.reverse_faces`, whose errors it raises."""
    C, E = mesh._c, mesh._e
    if faces is None:
        corners = C.live_slots()
    else:
        rings = [mesh._ring_slots(mesh._f.slot(f)) for f in faces]
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
