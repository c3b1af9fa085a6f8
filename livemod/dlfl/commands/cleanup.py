"""Thesis-style commands of TopMod's cleanup helpers and of orientation.

livemod additions (TopMod's Python module had none of them), named after its
C++ functions: ``edgeCleanup``, ``cleanup2gons``, ``cleanupWingedVertices`` and
``splitValence2Vertices`` (thin wrappers over :mod:`livemod.dlfl.geometry`),
and ``reverseOrientation`` (TopMod's ``DLFLObject::reverse``, over
:mod:`livemod.dlfl.orientation`). Each acts on the current object in place and
keeps the ids of everything it does not delete.
"""

from __future__ import annotations

from typing import Any

from .. import geometry as _geometry
from .. import orientation as _orientation
from .._checks import finite_number
from ._base import id_arguments, mesh, modeling_command

__all__ = ["edgeCleanup", "cleanup2gons", "cleanupWingedVertices", "splitValence2Vertices",
           "reverseOrientation"]


@modeling_command
def edgeCleanup(edgeids: Any = None) -> int:
    """``edgeCleanup([edgeids])``: delete every edge (or every one of ``edgeids``)
    whose two faces are coplanar or are one face, merging its faces; returns
    how many went. The cube after ``subdivide("triangulate")`` (14/36/24): its
    24 spokes lie in the cube's faces, so all go and the cube is back, 8/12/6.

    Raises:
        DLFLError: ``edgeids`` is not an id or a list of ids; nothing is deleted.
    """
    edges = None if edgeids is None else id_arguments(edgeids, "edgeids")
    return _geometry.edge_cleanup(mesh(), edges)


@modeling_command
def cleanup2gons() -> int:
    """``cleanup2gons()``: delete one edge of every 2-gon (merging it into a
    neighbour); returns how many went."""
    return _geometry.cleanup_2gons(mesh())


@modeling_command
def cleanupWingedVertices() -> int:
    """``cleanupWingedVertices()``: remove every valence-2 vertex, joining its two
    neighbours by one edge; returns how many went."""
    return _geometry.cleanup_winged_vertices(mesh())


@modeling_command
def splitValence2Vertices(offset: float = -0.1) -> list[int]:
    """``splitValence2Vertices([offset])``: split every valence-2 vertex in two,
    pushed apart across its corner by ``offset`` (by a tenth of each edge's
    length when ``offset <= 0``, TopMod's default -0.1); returns the new vertices.

    Raises:
        DLFLError: ``offset`` is not a finite number; the mesh is unchanged.
    """
    return _geometry.split_valence2_vertices(mesh(), finite_number(offset, "offset"))


@modeling_command
def reverseOrientation(faceids: Any = None) -> None:
    """``reverseOrientation([faceids])``: turn the current object inside out (every
    face's corners in the opposite order, so every normal flips), or with
    ``faceids`` the pieces (connected components) holding those faces.

    A face alone cannot turn over: the faces across its edges would then run
    those edges the same way, which no oriented surface does, so a face's whole
    piece turns with it (TopMod's ``DLFLFace::reverse`` left the object
    invalid; its ``DLFLObject::reverse`` turned everything). Ids stay.

    Raises:
        DLFLError: an id that is not a face; the mesh is unchanged.
    """
    faces = None if faceids is None else id_arguments(faceids, "faceids")
    _orientation.reverse_orientation(mesh(), faces)
