"""Vectorized graph helpers: permutation cycles, vertex rings and connected components."""

from __future__ import annotations

import numpy as np

from .soup import offsets_of


def cycle_labels(perm: np.ndarray) -> np.ndarray:
    """Label every element of a permutation with the smallest index in its cycle.

    Args:
        perm: ``(n,)`` int array, a permutation of ``0..n-1``.

    Returns:
        ``(n,)`` int64 array; two elements share a label iff they share a cycle.
        Runs in O(n log L) for a longest cycle of length L (pointer doubling).
    """
    label = np.arange(len(perm), dtype=np.int64)
    step = np.asarray(perm, dtype=np.int64)
    while True:
        merged = np.minimum(label, label[step])
        if np.array_equal(merged, label):
            return label
        label = merged
        step = step[step]


def component_labels(num_nodes: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Label the connected components of an undirected graph.

    Args:
        num_nodes: number of nodes ``n``.
        a, b: ``(m,)`` int arrays, the end nodes of each graph edge.

    Returns:
        ``(n,)`` int64 array: the smallest node index of each node's component.
    """
    parent = np.arange(num_nodes, dtype=np.int64)
    a = np.asarray(a, dtype=np.int64)
    b = np.asarray(b, dtype=np.int64)
    while True:
        pa, pb = parent[a], parent[b]
        differ = pa != pb
        if not differ.any():
            return parent
        lo = np.minimum(pa[differ], pb[differ])
        hi = np.maximum(pa[differ], pb[differ])
        np.minimum.at(parent, hi, lo)
        # shortcut every node to its root
        while True:
            grand = parent[parent]
            if np.array_equal(grand, parent):
                break
            parent = grand


def cycle_layout(perm: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The cycles of a permutation laid out contiguously, each in cycle order.

    Returns ``(order, offsets)``; each cycle starts at its smallest element.
    """
    n = len(perm)
    root = cycle_labels(perm)
    is_root = root == np.arange(n)
    pred = np.empty(n, dtype=np.int64)
    pred[perm] = np.arange(n)
    pred[is_root] = np.flatnonzero(is_root)
    rank = (~is_root).astype(np.int64)
    while True:
        rank += rank[pred]
        jumped = pred[pred]
        if np.array_equal(jumped, pred):
            break
        pred = jumped
    roots = np.flatnonzero(is_root)
    sizes = np.bincount(root, minlength=n)[roots]
    offsets = offsets_of(sizes)
    start = np.zeros(n, dtype=np.int64)
    start[roots] = offsets[:-1]
    order = np.empty(n, dtype=np.int64)
    order[start[root] + rank] = np.arange(n)
    return order, offsets


# walking a ring costs one Python-level numpy step per corner of the longest
# ring; above this, pointer doubling (O(log L) passes over every corner) wins
MAX_WALK = 64


def walk_rings(perm: np.ndarray, cv: np.ndarray, valence: np.ndarray
               ) -> tuple[np.ndarray, np.ndarray] | None:
    """:func:`cycle_layout` of ``perm`` when its cycles are the vertices' rings.

    Each vertex's ring is walked from its smallest corner, all rings in step,
    the longest first (ring ``k`` of a step is active while it has corners left).

    Args:
        perm: ``(C,)`` a permutation whose cycles should each hold the corners of
            one vertex (``vprev``). cv: ``(C,)`` vertex of each corner.
        valence: ``(V,)`` corners per vertex.

    Returns:
        ``(order, offsets)`` as :func:`cycle_layout` gives them, or None when a
        vertex's corners are not one cycle (several fans) or a ring is longer
        than :data:`MAX_WALK`.
    """
    n = len(perm)
    if n == 0 or int(valence.max()) > MAX_WALK:
        return None
    first = np.empty(len(valence), dtype=np.int64)
    first[cv[::-1]] = np.arange(n - 1, -1, -1, dtype=np.int64)  # the smallest wins
    is_first = np.zeros(n, dtype=bool)
    is_first[first[valence > 0]] = True
    starts = np.flatnonzero(is_first)
    sizes = valence[cv[starts]]
    offsets = offsets_of(sizes)
    order = _walk(perm, starts, sizes, offsets)
    seen = np.zeros(n, dtype=bool)
    seen[order] = True
    return (order, offsets) if seen.all() else None


def _walk(perm: np.ndarray, starts: np.ndarray, sizes: np.ndarray, offsets: np.ndarray
          ) -> np.ndarray:
    """``(C,)``: ring ``k`` (from ``starts[k]``, ``sizes[k]`` steps of ``perm``) at
    ``offsets[k]``."""
    by_size = np.argsort(-sizes, kind="stable")  # active rings stay a prefix
    current, base = starts[by_size], offsets[:-1][by_size]
    longer = len(starts) - np.cumsum(np.bincount(sizes))  # rings longer than k
    order = np.empty(int(offsets[-1]), dtype=np.int64)
    for k in range(int(sizes.max())):
        active = int(longer[k])
        current, base = current[:active], base[:active]
        order[base + k] = current
        current = perm[current]
    return order


def one_cycle_each(perm: np.ndarray, group: np.ndarray, sizes: np.ndarray) -> bool | None:
    """Whether the elements of every group form one single cycle of ``perm``.

    Args:
        perm: ``(C,)`` a permutation that maps every element into its own group
            (``vnext`` around vertices, say).
        group: ``(C,)`` group of each element. sizes: ``(G,)`` elements per group.

    Returns:
        True or False; None when a group is larger than :data:`MAX_WALK`, where
        walking costs more than :func:`cycle_labels` (ask that instead).

    Each group's cycle through one of its elements is walked, all groups in
    step; it holds the whole group unless it closes before ``sizes`` steps.
    """
    if len(perm) == 0:
        return True
    if int(sizes.max()) > MAX_WALK:
        return None
    first = np.empty(len(sizes), dtype=np.int64)
    first[group] = np.arange(len(perm), dtype=np.int64)  # any element of a group will do
    start = first[sizes > 0]
    left = sizes[sizes > 0]
    current = perm[start]
    for step in range(1, int(left.max())):
        keep = left > step
        if not keep.all():  # all the same size (a quad torus: valence 4): nothing to drop
            start, left, current = start[keep], left[keep], current[keep]
        if (current == start).any():
            return False  # a cycle closed before it held its whole group
        current = perm[current]
    return True

