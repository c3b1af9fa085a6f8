"""Orientation: turn a mesh, or whole pieces of it, inside out.

TopMod's ``DLFLObject::reverse`` reversed every face (and rewired the edges);
its ``DLFLFace::reverse`` reversed one face and, as its comment warned, left the
object invalid: the faces across that face's edges then run each edge the same
way, which no oriented surface does. livemod turns a face's whole connected
component with it, the smallest piece that can turn over.
"""

from __future__ import annotations

from collections.abc import Iterable

import numpy as np

from ._checks import id_list, shown
from .analysis import component_of_vertices
from .arrays import mesh_arrays
from .errors import UnknownIdError
from .mesh import Mesh

__all__ = ["component_faces", "reverse_orientation"]


def component_faces(mesh: Mesh, faces: Iterable[int]) -> list[int]:
    """Every face of the connected components that hold ``faces``, in id order.

    Raises:
        UnknownIdError: an id that is not a live face.
        InvalidArgumentError: ``faces`` is not a list of integer ids.
    """
    wanted = np.asarray(id_list(faces, "faces"), dtype=np.int64)
    a = mesh_arrays(mesh)
    found = np.isin(wanted, a.face_ids)  # an empty mesh too: none is found
    if not found.all():
        raise UnknownIdError(f"face {shown(int(wanted[~found][0]))} does not exist "
                             "(deleted or never made)")
    _, labels = component_of_vertices(a)
    return a.face_ids[np.isin(labels, labels[np.searchsorted(a.face_ids, wanted)])].tolist()


def reverse_orientation(mesh: Mesh, faces: Iterable[int] | None = None) -> None:
    """Reverse every face of ``mesh`` (None), or of the components holding ``faces``:
    each face's corners run the other way round, so its normal flips; a closed
    surface turns inside out. Ids, heads and positions stay; reversing twice
    gives the mesh back. Cube: still 8/12/6, every face normal pointing in.

    Raises:
        UnknownIdError: an id that is not a live face.
        InvalidArgumentError: ``faces`` is not a list of integer ids.
    """
    mesh.reverse_faces(None if faces is None else component_faces(mesh, faces))
