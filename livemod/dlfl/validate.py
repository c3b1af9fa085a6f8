"""Exhaustive invariant check of a DLFL mesh.

:func:`validate` checks every link of every element, vectorized over the slot
arrays, and raises :class:`InvalidMeshError` describing the first broken
invariant with the ids involved. Tests call it after every operation.
"""

from __future__ import annotations

import numpy as np

from ._graph import cycle_labels
from ._table import Table
from .errors import InvalidMeshError
from .mesh import Mesh


def validate(mesh: Mesh) -> None:
    """Check every invariant of ``mesh``; return None when it is a valid DLFL mesh.

    Checked: id maps (unique ids, ``moved`` entries, free slots), every corner's
    next/prev/face/vertex/edge reference, every face ring closed and single, each
    edge's two sides at opposite ends, edgeless corners only in point-spheres,
    each vertex's corners forming one rotation cycle, finite positions, face
    colours (a flag of 0 or 1, and three numbers in ``[0, 1]`` when it is 1).

    Raises:
        InvalidMeshError: the first broken invariant, naming the elements by id
            (a broken mesh is a bug in whatever built it, none of the kinds of
            bad input the other subclasses of DLFLError name).
    """
    for table in (mesh._v, mesh._e, mesh._f, mesh._c):
        _check_table(table)
    _check_face_colors(mesh._f)
    corners = mesh._c.live_slots()
    if len(corners) == 0:
        if mesh.num_vertices or mesh.num_edges or mesh.num_faces:
            raise InvalidMeshError("invalid mesh: mesh has no corners but has vertices, edges or faces")
        return
    _check_corner_refs(mesh, corners)
    _check_face_rings(mesh, corners)
    _check_edges(mesh, corners)
    _check_vertices(mesh, corners)


def _check_face_colors(f: Table) -> None:
    if "colored" not in f.arrays:  # no face has had a colour
        return
    slots = f.live_slots()
    colored = f.arrays["colored"][slots]
    color = f.arrays["color"][slots]
    bad = (colored > 1) | (colored == 1) & ~((color >= 0) & (color <= 1)).all(axis=1)
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        _fail(f"face {int(f.ids[slots[k]])} has colour flag {int(colored[k])} and colour "
              f"{color[k].tolist()} (a flag of 0 or 1, three numbers in [0, 1])")


def _fail(message: str) -> None:
    raise InvalidMeshError(f"invalid mesh: {message}")


def _check_table(t: Table) -> None:
    ids = t.ids[: t.n]
    live = ids >= 0
    # the free list's range first: the count relies on it, and the check of its
    # contents raised IndexError on a slot past the used ones (a negative one
    # silently read the last slot)
    outside = [s for s in t.free if not 0 <= s < t.n]
    if outside:
        _fail(f"{t.kind} free list holds slot {outside[0]}, outside the {t.n} used slots")
    if t.count != int(live.sum()):
        _fail(f"{t.kind} table counts {t.count} live elements but {int(live.sum())} slots are used")
    if len(set(t.free)) != len(t.free) or any(ids[s] >= 0 for s in t.free):
        _fail(f"{t.kind} free list holds a live or repeated slot")
    live_ids = ids[live]
    ordered = np.sort(live_ids)  # np.unique is ~100x slower on millions of ids (numpy 2.4)
    if len(ordered) > 1 and not np.all(ordered[1:] != ordered[:-1]):
        _fail(f"{t.kind} ids are not unique")
    if len(live_ids) and live_ids.max() >= t.next_id:
        _fail(f"{t.kind} id {int(live_ids.max())} is not below the id counter {t.next_id}")
    for eid, slot in t.moved.items():
        if not (0 <= slot < t.n) or ids[slot] != eid:
            _fail(f"{t.kind} id map sends {eid} to slot {slot}, which holds {ids[slot] if 0 <= slot < t.n else 'nothing'}")
    slots = np.flatnonzero(live)
    plain = ids[slots] == slots + t.base
    # an entry for an id in its home slot is allowed: a reused slot can be home
    # to its fresh id (see Table.alloc); lookups find it either way
    missing = [int(i) for i in ids[slots[~plain]] if int(i) not in t.moved]
    if missing:
        _fail(f"{t.kind} id map misses id {missing[0]}, stored away from its home slot")


def _live_mask(t: Table) -> np.ndarray:
    mask = np.zeros(max(t.n, 1), dtype=bool)
    mask[: t.n] = t.ids[: t.n] >= 0
    return mask


def _refs_ok(refs: np.ndarray, t: Table) -> np.ndarray:
    ok = (refs >= 0) & (refs < t.n)
    ok[ok] = _live_mask(t)[refs[ok]]
    return ok


def _first_bad(mesh: Mesh, corners: np.ndarray, bad: np.ndarray) -> int:
    return int(mesh._c.ids[corners[np.flatnonzero(bad)[0]]])


def _check_corner_refs(mesh: Mesh, corners: np.ndarray) -> None:
    ca = mesh._c.arrays
    for field, table in (("next", mesh._c), ("prev", mesh._c), ("face", mesh._f),
                         ("vertex", mesh._v)):
        bad = ~_refs_ok(ca[field][corners], table)
        if bad.any():
            _fail(f"corner {_first_bad(mesh, corners, bad)} has a dangling {field} link")
    edges = ca["edge"][corners]
    bad = (edges != -1) & ~_refs_ok(edges, mesh._e)
    if bad.any():
        _fail(f"corner {_first_bad(mesh, corners, bad)} has a dangling edge link")
    nxt, prv = ca["next"], ca["prev"]
    bad = (prv[nxt[corners]] != corners) | (nxt[prv[corners]] != corners)
    if bad.any():
        _fail(f"corner {_first_bad(mesh, corners, bad)}: next and prev links disagree")


def _check_face_rings(mesh: Mesh, corners: np.ndarray) -> None:
    ca, fa = mesh._c.arrays, mesh._f.arrays
    face = ca["face"]
    bad = face[ca["next"][corners]] != face[corners]
    if bad.any():
        _fail(f"corner {_first_bad(mesh, corners, bad)} links to a corner of another face")
    faces = mesh._f.live_slots()
    heads = fa["corner"][faces]
    ok = _refs_ok(heads, mesh._c)
    ok[ok] = face[heads[ok]] == faces[ok]
    if not ok.all():
        f = int(mesh._f.ids[faces[np.flatnonzero(~ok)[0]]])
        _fail(f"face {f} has a head corner that is dead or belongs to another face")
    # one cycle of `next` per face: cycles counted must equal faces
    dense = np.full(mesh._c.n, -1, dtype=np.int64)
    dense[corners] = np.arange(len(corners))
    labels = cycle_labels(dense[ca["next"][corners]])
    cycles = int((labels == np.arange(len(corners))).sum())
    if cycles != len(faces):
        per_face = np.bincount(face[corners], minlength=mesh._f.n)[faces]
        ring_len = np.bincount(labels, minlength=len(corners))[labels[dense[heads]]]
        bad = np.flatnonzero(per_face != ring_len)
        f = int(mesh._f.ids[faces[bad[0]]]) if len(bad) else -1
        _fail(f"{cycles} corner rings for {len(faces)} faces: face {f} has corners "
              "outside the ring of its head corner")


def _check_edges(mesh: Mesh, corners: np.ndarray) -> None:
    ca, ea = mesh._c.arrays, mesh._e.arrays
    edges = mesh._e.live_slots()
    c0, c1 = ea["c0"][edges], ea["c1"][edges]
    ok = _refs_ok(c0, mesh._c) & _refs_ok(c1, mesh._c)
    if not ok.all():
        _fail(f"edge {int(mesh._e.ids[edges[np.flatnonzero(~ok)[0]]])} has a dead side corner")
    checks = (
        (c0 == c1, "has the same corner on both sides"),
        ((ca["edge"][c0] != edges) | (ca["edge"][c1] != edges), "has a side corner that does not point back to it"),
        (ca["vertex"][ca["next"][c0]] != ca["vertex"][c1], "has sides that do not meet at its second end"),
        (ca["vertex"][ca["next"][c1]] != ca["vertex"][c0], "has sides that do not meet at its first end"),
    )
    for bad, what in checks:
        if bad.any():
            _fail(f"edge {int(mesh._e.ids[edges[np.flatnonzero(bad)[0]]])} {what}")
    edge_of = ca["edge"][corners]
    with_edge = edge_of >= 0
    uses = np.bincount(edge_of[with_edge], minlength=mesh._e.n)
    if (uses[edges] != 2).any():
        e = int(mesh._e.ids[edges[np.flatnonzero(uses[edges] != 2)[0]]])
        _fail(f"edge {e} is the edge of {int(uses[mesh._e.slot(e)])} corners, not 2")
    lone = ~with_edge & ((ca["next"][corners] != corners) | (ca["prev"][corners] != corners))
    if lone.any():
        _fail(f"corner {_first_bad(mesh, corners, lone)} has no edge but is not a point-sphere")


def _check_vertices(mesh: Mesh, corners: np.ndarray) -> None:
    ca, va = mesh._c.arrays, mesh._v.arrays
    verts = mesh._v.live_slots()
    head = va["corner"][verts]
    ok = _refs_ok(head, mesh._c)
    ok[ok] = ca["vertex"][head[ok]] == verts[ok]
    if not ok.all():
        v = int(mesh._v.ids[verts[np.flatnonzero(~ok)[0]]])
        _fail(f"vertex {v} points to a corner that is dead or at another vertex")
    if not np.isfinite(va["position"][verts]).all():
        v = int(mesh._v.ids[verts[np.flatnonzero(~np.isfinite(va["position"][verts]).all(axis=1))[0]]])
        _fail(f"vertex {v} has a position that is not finite")
    vnext = _vnext_slots(mesh, corners)
    bad = ca["vertex"][vnext] != ca["vertex"][corners]
    if bad.any():
        _fail(f"corner {_first_bad(mesh, corners, bad)}: the next corner around its vertex is at another vertex")
    dense = np.full(mesh._c.n, -1, dtype=np.int64)
    dense[corners] = np.arange(len(corners))
    labels = cycle_labels(dense[vnext])
    roots = labels == np.arange(len(corners))
    cycles_per_vertex = np.bincount(ca["vertex"][corners[roots]], minlength=mesh._v.n)[verts]
    if (cycles_per_vertex != 1).any():
        i = int(np.flatnonzero(cycles_per_vertex != 1)[0])
        _fail(f"vertex {int(mesh._v.ids[verts[i]])} has {int(cycles_per_vertex[i])} "
              "separate fans of corners (a non-manifold vertex)")


def _vnext_slots(mesh: Mesh, corners: np.ndarray) -> np.ndarray:
    """``(C,)`` slot of the next corner around each corner's vertex (TopMod vnext)."""
    ca, ea = mesh._c.arrays, mesh._e.arrays
    edge = ca["edge"][corners]
    has = edge >= 0
    c0, c1 = ea["c0"][edge[has]], ea["c1"][edge[has]]
    other = np.where(c0 == corners[has], c1, c0)
    vnext = corners.astype(np.int64).copy()
    vnext[has] = ca["next"][other]
    return vnext
