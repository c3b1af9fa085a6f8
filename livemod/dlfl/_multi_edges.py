"""Pairing the sides of vertex pairs joined by several edges, for :mod:`.build`.

A polygon soup's sides ``a -> b`` and ``b -> a`` between two vertices joined by
more than one edge (2-gons, parallel edges) can be paired in many ways. Each
makes the same faces but links the corners around ``a`` and ``b`` differently,
and only some make each vertex's ring one cycle (a manifold). This module finds
such a pairing: exactly for a group alone, by exact refusals and a bounded search
for groups sharing a vertex.
"""

from __future__ import annotations

import random
from typing import TYPE_CHECKING

import numpy as np

from .errors import NonManifoldError

if TYPE_CHECKING:
    from .soup import Polygons, SoupNames


def pair_multi_edges(
    soup: Polygons, mate: np.ndarray, order: np.ndarray, starts: np.ndarray,
    counts: np.ndarray, u: np.ndarray, w: np.ndarray, nxt: np.ndarray, where: SoupNames,
) -> None:
    """Pair the sides of vertex pairs joined by several edges (2-gons, multi-edges).

    Every pairing of a group's sides ``a -> b`` with its sides ``b -> a`` makes the
    same faces; it only decides how the corners of ``a`` and ``b`` link up around
    those two vertices (no other vertex sees it). A manifold needs each of those
    corner rings to be one cycle, and :func:`_solve_group` finds such a pairing
    for a group whenever one exists. Groups sharing a vertex constrain each other:
    they are solved in turn, then refused when an exact obstruction shows, else
    searched for by a bounded random walk (see :meth:`_Rings.solve_cluster`).

    Sets ``mate`` for every side of every group. Leaves a vertex that is
    non-manifold whatever the pairing (its other corners close a fan of their
    own, or its boundary is ambiguous) to the checks that follow, which name it.

    Raises:
        DLFLError: the sides of a group cannot be paired into manifold rings, or
            the search for a pairing of groups sharing vertices gave up.
    """
    groups = []
    for start, count in zip(starts.tolist(), counts.tolist(), strict=True):
        group = order[start : start + count]
        up = u[group] < w[group]
        fwd, back = group[up].tolist(), group[~up].tolist()
        mate[fwd], mate[back] = back, fwd  # a first pairing; every side has a mate now
        groups.append((fwd, back))
    rings = _Rings.around(soup, mate, nxt, groups)
    if rings is None:
        return  # an ambiguous boundary: _close_boundaries names it
    if rings.has_closed_fan():
        # that vertex is split whatever the pairing: pair each group as well as it
        # allows, so that the fan check names it and not a vertex pairing would mend
        for fwd, back in groups:
            _solve_group(rings, fwd, back)
        return
    for cluster in rings.clusters():
        outcome = rings.solve_cluster(cluster)
        if outcome != "solved":
            raise _unpaired(where, u, w, groups[cluster[0]][0], len(cluster),
                            None if outcome == "impossible" else rings.walk_budget(cluster))


def _unpaired(where: SoupNames, u: np.ndarray, w: np.ndarray, fwd: list[int], cluster_size: int,
              steps: int | None) -> NonManifoldError:
    """The error for a cluster of groups left unpaired, named by its first group
    (sides ``fwd``): proven impossible when ``steps`` is None, else the search
    of that many steps gave up, which does not prove there is no pairing."""
    a, b = int(u[fwd[0]]), int(w[fwd[0]])
    joined = (f"{where.prefix()}vertices {where.vertex(a)} and {where.vertex(b)} are "
              f"joined by {len(fwd)} edges")
    if steps is None:
        return NonManifoldError(f"{joined} that cannot be arranged into a manifold")
    return NonManifoldError(
        f"{joined}, which share vertices with {cluster_size - 1} other groups of parallel "
        f"edges; the search for a manifold arrangement of them gave up after {steps} steps "
        "(one may still exist)")


class _Rings:
    """The corner rings around the vertices of multi-edge groups, as the pairing
    of the groups' sides (``mate``, changed in place) links them.

    A corner ``c`` is followed around its vertex by ``nxt[mate[c]]``. For a corner
    on a boundary, whose side has no mate yet, the hole face that
    :func:`_close_boundaries` adds decides the next corner: ``nxt[d]`` for the
    one open side ``d`` ending at the vertex (the hole corner in between is left
    out, which changes no ring's cycle count).
    """

    def __init__(self, mate: np.ndarray, nxt: np.ndarray,
                 groups: list[tuple[list[int], list[int]]],
                 corners_at: dict[int, list[int]], link: dict[int, int],
                 group_of: dict[int, int], vertex_of: dict[int, int]) -> None:
        self.mate, self.nxt, self.groups = mate, nxt, groups
        self.corners_at, self.link = corners_at, link
        self.group_of, self.vertex_of = group_of, vertex_of

    @classmethod
    def around(cls, soup: Polygons, mate: np.ndarray, nxt: np.ndarray,
               groups: list[tuple[list[int], list[int]]]) -> _Rings | None:
        """The rings around the groups' vertices; None when a boundary through
        one of them is ambiguous (a later check then refuses it)."""
        sides = [s for fwd, back in groups for s in fwd + back]
        verts = np.unique(soup.indices[sides])
        at = np.flatnonzero(np.isin(soup.indices, verts))
        vertex_of = dict(zip(at.tolist(), soup.indices[at].tolist(), strict=True))
        corners_at: dict[int, list[int]] = {int(v): [] for v in verts}
        for c, v in vertex_of.items():
            corners_at[v].append(c)
        group_of = {s: g for g, (fwd, back) in enumerate(groups) for s in fwd + back}
        link = _fixed_links(soup, mate, nxt, vertex_of, group_of)
        if link is None:
            return None
        return cls(mate, nxt, groups, corners_at, link, group_of, vertex_of)

    def succ(self, c: int) -> int:
        """The corner after ``c`` around its vertex, under the current pairing."""
        if c in self.group_of:
            return int(self.nxt[self.mate[c]])
        return self.link[c]

    def has_closed_fan(self) -> bool:
        """True when corners of no group close a ring of their own at some vertex."""
        for corners in self.corners_at.values():
            seen = {c for c in corners if c in self.group_of}
            for c in corners:
                if c in self.group_of:
                    x = int(self.nxt[self.mate[c]])
                    while x not in seen:
                        seen.add(x)
                        x = self.link[x]
            if len(seen) < len(corners):
                return True
        return False

    def ring_count(self, vertex: int) -> int:
        """Number of cycles the corners of ``vertex`` form."""
        seen: set[int] = set()
        cycles = 0
        for c in self.corners_at[vertex]:
            if c not in seen:
                cycles += 1
                x = c
                while x not in seen:
                    seen.add(x)
                    x = self.succ(x)
        return cycles

    def clusters(self) -> list[list[int]]:
        """The groups, gathered into sets that share vertices (each sorted)."""
        parent = list(range(len(self.groups)))

        def root(g: int) -> int:
            while parent[g] != g:
                g = parent[g]
            return g

        first_at: dict[int, int] = {}
        for g, (fwd, back) in enumerate(self.groups):
            for v in (self.vertex_of[fwd[0]], self.vertex_of[back[0]]):
                other = first_at.setdefault(v, g)
                parent[root(g)] = root(other)
        out: dict[int, list[int]] = {}
        for g in range(len(self.groups)):
            out.setdefault(root(g), []).append(g)
        return list(out.values())

    def solve_cluster(self, cluster: list[int]) -> str:
        """Pair the sides of ``cluster``'s groups so that each of their vertices
        has one ring.

        One group alone is solved exactly (:func:`_solve_group`). Groups sharing
        vertices are first solved one at a time, the others' pairings fixed; when
        that leaves a vertex split and :meth:`cannot_join` does not rule every
        pairing out, :meth:`walk` searches on.

        Returns:
            ``"solved"``, ``"impossible"`` (no pairing exists) or ``"gave up"``
            (the bounded search found none; one may exist).
        """
        verts = {self.vertex_of[s] for g in cluster for s in self.groups[g][0] + self.groups[g][1]}
        for g in cluster:
            _solve_group(self, *self.groups[g])
        if all(self.ring_count(v) == 1 for v in verts):
            return "solved"
        if len(cluster) == 1 or self.cannot_join(verts):
            return "impossible"
        return "solved" if self.walk(cluster, verts, self.walk_budget(cluster)) else "gave up"

    def cannot_join(self, verts: set[int]) -> bool:
        """True when no pairing gives every vertex of ``verts`` one ring.

        Two exact obstructions. Parity: swapping the mates of two sides of a
        group changes the ring count at both its ends by one, and every
        re-pairing is made of such swaps, so the parity of the rings in excess
        over ``verts`` never changes. Separation: the groups at a vertex whose
        sides never lead to one another's (:meth:`groups_meet`) keep their
        corners in separate rings whatever their pairings.
        """
        excess = sum(self.ring_count(v) - 1 for v in verts)
        return excess % 2 == 1 or not all(self.groups_meet(v) for v in verts)

    def groups_meet(self, vertex: int) -> bool:
        """Whether the groups at ``vertex`` are connected by leads: the ring
        through the corner after a side ending at ``vertex`` reaches a side of
        another group first. Independent of the pairings (a group's sides end
        at ``vertex`` whichever sides start there they pair with)."""
        sides = [c for c in self.corners_at[vertex] if c in self.group_of]
        parent = {self.group_of[c]: self.group_of[c] for c in sides}

        def root(g: int) -> int:
            while parent[g] != g:
                parent[g] = g = parent[parent[g]]
            return g

        for c in sides:
            x = int(self.nxt[self.mate[c]])
            while x not in self.group_of:
                x = self.link[x]
            parent[root(self.group_of[c])] = root(self.group_of[x])
        return len({root(g) for g in parent}) == 1

    def walk_budget(self, cluster: list[int]) -> int:
        """Steps :meth:`walk` may take on ``cluster``: each counts the rings at
        both ends of a group, so the steps times twice the largest ring stay
        within :data:`MULTI_EDGE_WORK` corners, well under a second."""
        ends = {self.vertex_of[self.groups[g][end][0]] for g in cluster for end in (0, 1)}
        largest = max(len(self.corners_at[v]) for v in ends)
        return max(MULTI_EDGE_WORK // (2 * largest), 1)

    def walk(self, cluster: list[int], verts: set[int], steps: int) -> bool:
        """Random swaps and rotations of mates within the groups of ``cluster``,
        kept when the rings at ``verts`` do not split further (now and then
        anyway, to get out of a dead end); True once every ring is one cycle.

        Seeded: the same soup always gives the same mesh.
        """
        rng = random.Random(len(cluster))
        excess = {v: self.ring_count(v) - 1 for v in verts}
        total = sum(excess.values())
        for _ in range(steps):
            if total == 0:
                return True
            fwd, back = self.groups[rng.choice(cluster)]
            if len(fwd) < 2:
                continue
            picks = rng.sample(fwd, 3 if len(fwd) > 2 and rng.random() < 0.5 else 2)
            _swap_mates(self.mate, picks, picks[1:] + picks[:1])
            ends = (self.vertex_of[fwd[0]], self.vertex_of[back[0]])
            new = {v: self.ring_count(v) - 1 for v in ends}
            delta = sum(new[v] - excess[v] for v in ends)
            if delta <= 0 or rng.random() < 0.05:
                excess.update(new)
                total += delta
            else:
                _swap_mates(self.mate, picks, picks[-1:] + picks[:-1])  # undo
        return total == 0


MULTI_EDGE_WORK = 200_000  # corners :meth:`_Rings.walk` may visit counting rings, per cluster


def _fixed_links(soup: Polygons, mate: np.ndarray, nxt: np.ndarray, vertex_of: dict[int, int],
                 group_of: dict[int, int]) -> dict[int, int] | None:
    """The next corner around its vertex of every corner in ``vertex_of`` that is
    no group side (see :class:`_Rings`), itself for a one-corner face; None when
    a boundary through one of these vertices is ambiguous."""
    open_side = (mate < 0) & ~soup.single_corners  # the groups' sides are paired by now
    opens = np.flatnonzero(open_side)
    ending_at: dict[int, int] = {}
    starts_at: dict[int, int] = {}
    for c, v in zip(opens.tolist(), soup.indices[nxt[opens]].tolist(), strict=True):
        ending_at[v] = -1 if v in ending_at else c
    for c in opens.tolist():
        v = int(soup.indices[c])
        starts_at[v] = starts_at.get(v, 0) + 1
    link = {}
    for c, v in vertex_of.items():
        if c in group_of:
            continue
        if mate[c] >= 0:
            link[c] = int(nxt[mate[c]])
        elif open_side[c] and starts_at[v] == 1 and ending_at.get(v, -1) >= 0:
            link[c] = int(nxt[ending_at[v]])
        elif not open_side[c]:
            link[c] = c  # a point-sphere's corner: a fan of its own
        else:
            return None
    return link


def _swap_mates(mate: np.ndarray, sides: list[int], partners: list[int]) -> None:
    """Give ``sides[i]`` the old mate of ``partners[i]``, both ways round."""
    old = [int(mate[p]) for p in partners]
    for s, m in zip(sides, old, strict=True):
        mate[s], mate[m] = m, s


def _solve_group(rings: _Rings, fwd: list[int], back: list[int]) -> bool:
    """Pair one group's sides ``fwd`` (``a -> b``) with ``back`` (``b -> a``), the
    other groups' pairings fixed, so that ``a`` and ``b`` each get one ring if any
    pairing does that; returns whether it did.

    Following the rings from the corner after each side ``s`` to the first side of
    the group met gives ``lead[s]``; a pairing ``mate`` then links the group's
    sides at the far end as ``lead[mate[.]]``. The rings are one cycle when
    these links are (given that no fan closes without them). First the sides at
    ``a`` are linked into one cycle; then, while the sides at ``b`` form three or
    more cycles, rotating the mates of three sides whose mates lie in three of
    those cycles joins them into one, and one of the two rotations keeps ``a`` one
    cycle. Two cycles left at ``b`` is a matter of parity: no pairing joins them.
    """
    lead = _leads(rings, fwd + back)
    if lead is None:
        return False
    reach = {lead[b]: b for b in back}
    # a's cycle in a seeded random order: in side order, a face running a, b, a, b,
    # ... round k times would leave k cycles at b, each merge an O(k) recount
    order = random.Random(len(fwd)).sample(fwd, len(fwd))
    for f, f_next in zip(order, order[1:] + order[:1], strict=True):
        b = reach[f_next]
        rings.mate[f], rings.mate[b] = b, f
    while True:
        cycles = _link_cycles(back, rings.mate, lead)
        if len(cycles) < 3:
            return len(cycles) == 1
        x, y, z = (cycle[0] for cycle in cycles[:3])
        f1, f2, f3 = (int(rings.mate[s]) for s in (x, y, z))
        _swap_mates(rings.mate, [f1, f2, f3], [f2, f3, f1])
        if len(_link_cycles(fwd, rings.mate, lead)) != 1:
            _swap_mates(rings.mate, [f1, f2, f3], [f3, f1, f2])  # undo
            _swap_mates(rings.mate, [f1, f2, f3], [f3, f1, f2])  # the other rotation


def _leads(rings: _Rings, sides: list[int]) -> dict[int, int] | None:
    """For each side, the first side of the same group met going round the far
    vertex from the corner after it (the group's sides not followed); None when
    such a walk runs into a ring without them."""
    own = set(sides)
    lead = {}
    for s in sides:
        x, seen = int(rings.nxt[s]), set()
        while x not in own:
            if x in seen:
                return None  # other groups' pairings close a fan here: theirs to change
            seen.add(x)
            x = rings.succ(x)
        lead[s] = x
    return lead


def _link_cycles(sides: list[int], mate: np.ndarray, lead: dict[int, int]) -> list[list[int]]:
    """The cycles of ``s -> lead[mate[s]]`` on ``sides`` (one end of a group)."""
    seen: set[int] = set()
    cycles = []
    for s in sides:
        if s in seen:
            continue
        cycle = []
        while s not in seen:
            seen.add(s)
            cycle.append(s)
            s = lead[int(mate[s])]
        cycles.append(cycle)
    return cycles
