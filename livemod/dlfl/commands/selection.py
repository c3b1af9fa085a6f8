"""Selection commands: TopMod's selection tools as functions that return ids.

livemod additions (TopMod had them in its GUI only): each returns a list of ids
of the current object, so a script passes them on, as in
``rind(face_loop(e), False, 0.1)`` or ``extrude("cubical", checkerboard(f), 0.5)``.
Thin wrappers over :mod:`livemod.dlfl.selection`; the window has them on keys
(SHIFT+L, SHIFT+R, CTRL+P for TopMod's SHIFT+P, SHIFT+K, SHIFT+S, CTRL+=, CTRL+-,
CTRL+I, CTRL+A, Esc).
Where a command takes one element (a loop's edge, a checkerboard's face), it
takes a list too and returns the union, each id once, in the order found. The
ones that read a selection (grow, shrink, invert) default to the picks of
their kind; ``clear_selection`` empties the picks themselves.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .. import selection as _selection
from ..mesh import Mesh
from ..scene import Selection
from ._base import id_arguments, mesh, scene

__all__ = [
    "edge_loop", "edge_ring", "face_loop", "checkerboard", "similar_faces", "similar_edges",
    "similar_vertices", "grow_selection", "shrink_selection", "invert_selection", "select_all",
    "clear_selection",
]


def _each(rule: Callable[[Mesh, int], list[int]], ids: Any, name: str) -> list[int]:
    """The union of ``rule`` over ``ids`` (one id or a list), each id once."""
    m = mesh()
    found: dict[int, None] = {}
    for element in id_arguments(ids, name):
        found.update(dict.fromkeys(rule(m, element)))
    return list(found)


def edge_loop(edgeid: Any) -> list[int]:
    """``edge_loop(edgeid)``: the edge loop through an edge (TopMod's SHIFT+L): on
    from each end across every valence-4 vertex to the opposite edge, until it
    closes or meets another valence. Torus grid: a ring of the tube.

    Raises:
        DLFLError: an id that is not an edge.
    """
    return _each(_selection.edge_loop, edgeid, "edgeid")


def edge_ring(edgeid: Any) -> list[int]:
    """``edge_ring(edgeid)``: the edge ring through an edge (TopMod's SHIFT+R):
    across every quad to its opposite edge, both ways, until a face is no quad.

    Raises:
        DLFLError: an id that is not an edge.
    """
    return _each(_selection.edge_ring, edgeid, "edgeid")


def face_loop(edgeid: Any) -> list[int]:
    """``face_loop(edgeid)``: the quads the edge ring through an edge crosses
    (TopMod's SHIFT+P): ``rind(face_loop(e), False, 0.1)`` opens a band.

    Raises:
        DLFLError: an id that is not an edge.
    """
    return _each(_selection.face_loop, edgeid, "edgeid")


def checkerboard(faceid: Any) -> list[int]:
    """``checkerboard(faceid)``: TopMod's SHIFT+K, the faces reached from a face
    through faces that share exactly one vertex and no edge with one reached:
    every other face of a quad grid.

    Raises:
        DLFLError: an id that is not a face.
    """
    return _each(_selection.checkerboard, faceid, "faceid")


def similar_faces(faceid: Any, by: str = "size", delta: float = 0.05) -> list[int]:
    """``similar_faces(faceid[, by, delta])``: faces like a face, TopMod's select
    similar: ``by="size"`` the same number of sides, ``by="area"`` an area within
    ``delta`` (TopMod's select by area, 0.05), ``by="colour"`` a colour within
    ``delta`` in each channel (TopMod's selectFacesByColor).

    Raises:
        DLFLError: an id that is not a face, an unknown measure, a bad delta.
    """
    return _each(lambda m, f: _selection.similar_faces(m, f, by, delta), faceid, "faceid")


def similar_edges(edgeid: Any) -> list[int]:
    """``similar_edges(edgeid)``: edges whose ends have the valences of an edge's
    ends, in either order (TopMod's select similar on edges).

    Raises:
        DLFLError: an id that is not an edge.
    """
    return _each(_selection.matching_edges, edgeid, "edgeid")


def similar_vertices(vertexid: Any) -> list[int]:
    """``similar_vertices(vertexid)``: vertices of a vertex's valence (TopMod's
    select similar on vertices).

    Raises:
        DLFLError: an id that is not a vertex.
    """
    return _each(_selection.matching_vertices, vertexid, "vertexid")


def grow_selection(ids: Any = None, kind: str = "faces") -> list[int]:
    """``grow_selection([ids, kind])``: the ids and their neighbours (TopMod's
    ``=``): faces across an edge, edges at a shared vertex, vertices one edge
    away. ``kind`` is ``"faces"``, ``"edges"`` or ``"vertices"``; the ids default
    to the picks of that kind.

    Raises:
        DLFLError: an unknown kind, or ids that are not ids.
    """
    return _selection.grow(mesh(), _ids(ids, kind), kind)


def shrink_selection(ids: Any = None, kind: str = "faces") -> list[int]:
    """``shrink_selection([ids, kind])``: the ids without those with a neighbour
    (as :func:`grow_selection` has them) outside them (TopMod's ``-``).

    Raises:
        DLFLError: an unknown kind, or ids that are not ids.
    """
    return _selection.shrink(mesh(), _ids(ids, kind), kind)


def invert_selection(ids: Any = None, kind: str = "faces") -> list[int]:
    """``invert_selection([ids, kind])``: every element of ``kind`` (corners too)
    not among the ids (TopMod's CTRL+I).

    Raises:
        DLFLError: an unknown kind, or ids that are not ids.
    """
    return _selection.invert(mesh(), _ids(ids, kind), kind)


def select_all(kind: str = "faces") -> list[int]:
    """``select_all([kind])``: every face (not the holes), edge, vertex or corner
    (TopMod's CTRL+A).

    Raises:
        DLFLError: an unknown kind.
    """
    return _selection.select_all(mesh(), kind)


def clear_selection() -> list[int]:
    """``clear_selection()``: forget the picks (TopMod's Esc), so ``faces(True)``
    and the commands that default to the picks see none for the rest of the
    run; returns the empty list, a selection to build on.
    ``s = grow_selection(faces(True)); clear_selection()`` keeps the grown ids in
    ``s`` and no picks."""
    scene().selection = Selection()
    return []


def _ids(ids: Any, kind: str) -> list[int]:
    """The ids a whole-selection command acts on: ``ids``, or the picks of ``kind``.

    Raises:
        DLFLError: an unknown kind, or ids that are not ids.
    """
    return id_arguments(ids, "ids", _selection.kind_field(kind))
