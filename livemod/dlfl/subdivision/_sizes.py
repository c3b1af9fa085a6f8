"""The size of every scheme's result, for the face budget, from counts alone.

``SIZES[name](c)`` is the ``(faces, corners)`` of the result of scheme ``name``
on a mesh of counts ``c`` (:class:`~._layout.Counts`: ``nv``, ``ne``, ``nf``,
``nc`` without point-spheres, which every scheme passes through and the budget
check adds back). Every entry is exact, except for the schemes whose result
depends on face sizes or valences: there ``SIZES`` gives an upper bound and
``EXACT`` the exact size from the topology (:func:`._layout.budgeted_topology`
reads it only when the bound passes the budget). A scheme makes ``2 E'``
corners for its ``E'`` edges, so every corner count is even.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..budget import repeated
from ..mesh import Mesh
from ._layout import Counts, Size, Topology, check_budget, counts_of


def catmull_clark_size(c: Any, levels: int = 1) -> tuple[int, int]:
    """``(faces, corners)`` after ``levels`` Catmull-Clark steps (a quad per
    corner each level), at most :data:`~livemod.dlfl.budget.SATURATED`."""
    return repeated(c.nc, 4, levels - 1), repeated(c.nc, 4, levels)


def dual_size(c: Any) -> tuple[int, int]:
    """A face per vertex, the same corners."""
    return c.nv, c.nc


SIZES: dict[str, Size] = {
    "catmull-clark": catmull_clark_size,
    "linear-vertex": lambda c: (c.nc, 4 * c.nc),
    "loop": lambda c: (c.nf + c.nc, 4 * c.nc),
    "loop-style": lambda c: (c.nf + c.nc, 4 * c.nc),
    "checker": lambda c: (c.nf + 2 * c.nc, 9 * c.nc),
    "simplest": lambda c: (c.nf + c.nv, 2 * c.nc),
    "vertex-cut": lambda c: (c.nf + c.nv, 3 * c.nc),
    "honeycomb": lambda c: (c.nf + c.nv, 3 * c.nc),
    "pentagon": lambda c: (c.nc, 5 * c.nc),
    "pentagon-preserve": lambda c: (c.nf + c.nc, 6 * c.nc),
    "doo-sabin-bc-new": lambda c: (c.nf + c.nc, 7 * c.nc),
    "modified-corner-cut": lambda c: (c.nf + c.ne + c.nv, 4 * c.nc),
    "root4": lambda c: (c.nf + c.ne, 4 * c.nc),
    "star": lambda c: (3 * c.nc, 9 * c.nc),
    "sqrt3": lambda c: (c.nc, 3 * c.nc),
    "fractal": lambda c: (2 * c.nc, 6 * c.nc),
    "stellate": lambda c: (c.ne, 2 * c.nc),
    "double-stellate": lambda c: (c.ne + c.nc, 6 * c.nc),
    "dual-12.6.4": lambda c: (c.nf + c.ne + c.nv, 6 * c.nc),
    "dual": dual_size,
    "subdivide-all-edges": lambda c: (c.nf, 2 * c.nc),
    "sierpinsky": lambda c: (c.nv + c.nc, 5 * c.nc),
    # every edge split in four, then seven Doo-Sabin extrusions of every face:
    # seven rings of quads, four a corner, and the end faces
    "dome": lambda c: (c.nf + 28 * c.nc, 116 * c.nc),
    # bounds (EXACT below): every face fanned; a face per vertex
    "triangulate": lambda c: (c.nc, 3 * c.nc),
    "doo-sabin": lambda c: (c.nf + c.ne + c.nv, 4 * c.nc),
    "corner-cut": lambda c: (c.nf + c.ne + c.nv, 4 * c.nc),
    "doo-sabin-bc": lambda c: (c.nf + c.nc + c.nv, 7 * c.nc),
}


def _ring_counts(t: Topology) -> tuple[int, int, int]:
    """``(vertices of valence >= 3, their corners, vertices of valence 1)``."""
    valence = t.valence
    ring = valence >= 3
    return (int(np.count_nonzero(ring)), int(valence[ring].sum()),
            int(np.count_nonzero(valence == 1)))


def doo_sabin_size(t: Topology) -> tuple[int, int]:
    """Doo-Sabin's topology: a face per face, a quad per edge (a triangle at a
    valence-1 end), a face per vertex of valence >= 3."""
    rings, ring_corners, ends = _ring_counts(t)
    return t.nf + t.ne + rings, t.nc + 4 * t.ne + ring_corners - ends


def doo_sabin_bc_size(t: Topology) -> tuple[int, int]:
    """:func:`doo_sabin_size` of ``t`` with every edge split (``2C`` corners,
    ``2E`` edges, the midpoints of valence 2)."""
    rings, ring_corners, ends = _ring_counts(t)
    return t.nf + t.nc + rings, 6 * t.nc + ring_corners - ends


def triangulate_size(t: Topology) -> tuple[int, int]:
    """A fan of ``n`` triangles per ``n``-gon that is no triangle."""
    faces = t.nc - 2 * int(np.count_nonzero(t.sizes == 3))
    return faces, 3 * faces


EXACT: dict[str, Size] = {
    "triangulate": triangulate_size,
    "doo-sabin": doo_sabin_size,
    "corner-cut": doo_sabin_size,
    "doo-sabin-bc": doo_sabin_bc_size,
}


def check_steps(mesh: Mesh, steps: tuple[str, ...], max_faces: object) -> Counts:
    """Check the face budget of each of a composite's ``steps`` (names of
    :data:`SIZES` whose entries are exact), in turn, as the steps would, from
    ``mesh``'s counts; return the counts of the result.

    Raises:
        BudgetExceededError: the first step over the budget, named.
    """
    c = counts_of(mesh)
    for name in steps:
        size = SIZES[name](c)
        check_budget(c, *size, name, max_faces)
        c = c.after(size)
    return c
