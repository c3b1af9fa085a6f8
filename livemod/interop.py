"""Bridges to other Python mesh libraries: trimesh, when it is installed.

``to_trimesh(mesh)`` hands a livemod mesh to trimesh's tools (ray tests, booleans,
convex hulls, its many file formats) in one line; ``from_trimesh(tm)`` brings a
trimesh mesh back as a DLFL mesh. trimesh is imported when a bridge is called, so
``import livemod.interop`` costs nothing without it. (The library itself,
:mod:`livemod.dlfl`, depends on numpy only; for bare arrays use
:meth:`~livemod.dlfl.arrays.MeshArrays.triangles`.)
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from livemod.dlfl import Mesh, MeshArrays, from_polygons, mesh_arrays
from livemod.dlfl.colors import filled_colors
from livemod.dlfl.errors import InvalidArgumentError

if TYPE_CHECKING:
    import trimesh

FACE_ID = "livemod_face_id"  # the face attribute naming each triangle's face


def to_trimesh(mesh: Mesh | MeshArrays) -> trimesh.Trimesh:
    """``mesh`` as a ``trimesh.Trimesh`` of its fan triangles.

    Every vertex is kept, in id order (row ``i`` is vertex ``vertex_ids[i]`` of
    :func:`~livemod.dlfl.mesh_arrays`), also a point-sphere's; faces of three or
    more corners become the fans of :meth:`MeshArrays.triangles`, holes and
    2-gons none. ``face_attributes["livemod_face_id"]`` (``(T,)`` int64) names the
    face each triangle came from. trimesh's processing (merging vertices, dropping
    degenerate triangles) is not run, so these indices hold. When a face has a
    colour, every triangle gets its face's colour (``tm.visual.face_colors``,
    ``(T, 4)`` uint8, opaque; a face without one in the modelling colour, as the
    file writers do).

    Raises:
        ImportError: trimesh is not installed (the message says how to install it).
    """
    trimesh = _trimesh("to_trimesh")
    arrays = mesh if isinstance(mesh, MeshArrays) else mesh_arrays(mesh)
    triangles, faces = arrays.triangles()
    colors = None
    if arrays.face_colors is not None:
        colors = np.full((len(faces), 4), 255, dtype=np.uint8)
        colors[:, :3] = np.rint(filled_colors(arrays.face_colors)[faces] * 255)
    return trimesh.Trimesh(vertices=arrays.positions.copy(), faces=triangles, process=False,
                           face_attributes={FACE_ID: arrays.face_ids[faces]},
                           face_colors=colors)


def from_trimesh(tm: trimesh.Trimesh) -> Mesh:
    """A DLFL mesh of the triangles of ``tm`` (through
    :func:`~livemod.dlfl.from_polygons`): vertex ``i`` and triangle ``j`` of
    ``tm`` get ids ``i`` and ``j``; an open mesh gets a hole face per boundary
    loop, a vertex no triangle uses a point-sphere. Face colours
    (``tm.visual.kind == "face"``) become the triangles' colours, alpha dropped;
    vertex colours and textures are not taken (a DLFL face has one colour).

    Raises:
        ImportError: trimesh is not installed.
        InvalidArgumentError: ``tm`` is not a ``trimesh.Trimesh`` (a
            ``trimesh.Scene``: join it first with ``tm.to_geometry()``).
        DLFLError: what :func:`~livemod.dlfl.from_polygons` refuses (an edge of
            three triangles, a vertex where two fans meet, a non-orientable
            surface), the message starting "the trimesh mesh: ".
    """
    trimesh = _trimesh("from_trimesh")
    if not isinstance(tm, trimesh.Trimesh):
        hint = " (join a trimesh.Scene first: scene.to_geometry())" \
            if isinstance(tm, trimesh.Scene) else ""
        raise InvalidArgumentError(f"from_trimesh takes a trimesh.Trimesh, not "
                                   f"{type(tm).__name__}{hint}")
    colors = None
    if tm.visual.kind == "face":
        colors = np.asarray(tm.visual.face_colors)[:, :3] / np.float32(255)
    return from_polygons(tm.vertices, tm.faces, source="the trimesh mesh", face_colors=colors)


def _trimesh(caller: str) -> Any:
    """The trimesh module. Raises ImportError saying how to install it."""
    try:
        import trimesh
    except ImportError as exc:
        raise ImportError(f"{caller} needs trimesh: pip install trimesh") from exc
    return trimesh
