"""livemod.dlfl: the Doubly Linked Face List modeling library (numpy only).

Two layers over one implementation:

* the library API: :class:`Mesh` with the minimal operators, free functions per
  family (:func:`from_polygons`, :func:`validate`, :func:`mesh_arrays`, ...);
* the thesis commands (``createVertex``, ``insertEdge``, ``extrude``, ...), which
  act on the current scene. ``from livemod.dlfl import *`` brings the thesis
  commands into a script, and :class:`DLFLError`, the error they raise, with its
  subclasses (:mod:`livemod.dlfl.errors`), so that a script can catch them by the
  names the documentation gives.
"""

from __future__ import annotations

from . import commands
from .analysis import (
    MeshSummary,
    bounds,
    component_genera,
    enclosed_volume,
    euler_characteristic,
    face_centroids,
    face_normals,
    face_size_histogram,
    genus,
    num_components,
    summarize,
    surface_area,
    vertex_normals,
)
from .arrays import MeshArrays, mesh_arrays
from .build import from_corner_arrays, from_polygons
from .commands import *  # noqa: F403
from .errors import (
    BudgetExceededError,
    DLFLError,
    DLFLRepairWarning,
    DLFLSkippedLinesWarning,
    FileFormatError,
    GeometryError,
    InvalidArgumentError,
    InvalidMeshError,
    NonManifoldError,
    UnknownIdError,
)
from .mesh import Mesh
from .run_context import RunContext, current_run, use_run
from .scene import Scene, Selection, current_scene, use_scene
from .soup import Polygons
from .validate import validate

# the errors, so that a script can catch them by the names the documentation gives
ERRORS = [
    "DLFLError", "UnknownIdError", "InvalidArgumentError", "NonManifoldError",
    "BudgetExceededError", "FileFormatError", "GeometryError", "InvalidMeshError",
]
__all__ = [*commands.__all__, *ERRORS]

LIBRARY_API = [
    "Mesh", "MeshArrays", "MeshSummary", "Polygons", "RunContext", "Scene", "Selection",
    "DLFLError", "DLFLRepairWarning", "DLFLSkippedLinesWarning", "bounds",
    "component_genera", "current_run", "current_scene", "enclosed_volume",
    "euler_characteristic", "face_centroids", "face_normals", "face_size_histogram",
    "from_corner_arrays", "from_polygons", "genus", "mesh_arrays", "num_components",
    "summarize", "surface_area", "use_run", "use_scene", "validate", "vertex_normals",
]
