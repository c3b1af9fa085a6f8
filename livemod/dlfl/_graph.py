"""Vectorized graph helpers: permutation cycles and connected components."""

from __future__ import annotations

import numpy as np


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
