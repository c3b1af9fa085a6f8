"""The core thesis commands: minimal operators, ids, walks, objects, info, transforms.

Names and arguments follow the appendix of Tett (2007) so TopMod scripts run
after the Python 3 changes alone. Corners are ``(faceid, vertexid)`` tuples (or
corner ids). Every command checks its arguments and raises :class:`DLFLError`.
"""

from __future__ import annotations

import builtins
import itertools
import os
from collections.abc import Callable, Iterable, Sequence
from sys import _getframe
from types import FrameType
from typing import Any

import numpy as np

from .. import geometry as _geometry
from .. import transform as _transform
from .._checks import as_point, flag, is_id, shown, whole_count
from .._vectors import centroid as _centroid
from .._vectors import lengths
from ..analysis import face_centroid, face_normal
from ..analysis import genus as _genus
from ..budget import CORNERS_PER_FACE, check_growth, face_budget
from ..errors import DLFLError, GeometryError, InvalidArgumentError
from ..mesh import Mesh
from ..run_context import announce_step, current_run
from ._base import corner_tuple, mesh, modeling_command, resolve_corner, scene

__all__ = [
    "createVertex", "removeVertex", "insertEdge", "deleteEdge", "subdivideEdge",
    "collapseEdge", "trisectEdge", "spliceCorners", "createFace", "faces", "edges", "verts",
    "corners", "walk", "cornerWalk", "next", "prev", "getCorner", "saveCorner", "restoreCorner", "load",
    "save", "kill", "switch", "printObject", "vertexInfo", "edgeInfo", "faceInfo",
    "cornerInfo", "vertexEdges", "centroid", "translate", "scale", "move",
    "freezeTrans", "step",
]

Point = Sequence[float]


# -- minimal operators ----------------------------------------------------------

@modeling_command
def createVertex(position: Point = (0.0, 0.0, 0.0)) -> tuple[tuple[int, int], int]:
    """Create a point-sphere at ``position``: ``((faceid, vertexid), objectid)``.

    The corner is the point-sphere's only one (carrying its corner id), so
    ``c, _ = createVertex(p)`` then ``insertEdge(c, ...)`` or ``removeVertex(c)``
    work. TopMod returned ``(faceid, vertexid)`` alone. With no object in the
    scene, one is created.
    """
    sc = scene()
    m = sc.mesh
    v = m.create_vertex(position)
    assert sc.current is not None
    return corner_tuple(m, m.vertex_corner(v)), sc.current


@modeling_command
def removeVertex(vertexid: Any) -> None:
    """``removeVertex(vertexid)``: remove a point-sphere with its face and corner.

    ``vertexid`` is a vertex id (the thesis) or the point-sphere's corner as a
    ``(faceid, vertexid)`` tuple, the form :func:`createVertex` returns.

    Raises:
        DLFLError: the vertex has edges, no such vertex or corner, or a pair in
            TopMod's reversed ``(vertexid, faceid)`` order (the message says so).
    """
    m = mesh()
    m.remove_vertex(_vertex_of(m, vertexid))


def _vertex_of(m: Mesh, value: Any) -> Any:
    """The vertex :func:`removeVertex` is given: ``value`` itself, or the vertex of
    the corner a tuple names (checked by ``remove_vertex`` and ``resolve_corner``)."""
    if not isinstance(value, tuple | list):
        return value
    try:
        return m.corner_vertex(resolve_corner(m, value, "vertexid"))
    except DLFLError as exc:
        if len(value) == 2 and _is_point_sphere_corner(m, value[1], value[0]):
            raise type(exc)(f"{exc}; removeVertex takes (faceid, vertexid), as createVertex "
                            "returns it, not TopMod's (vertexid, faceid): write "
                            f"({value[1]}, {value[0]})") from None
        raise


def _is_point_sphere_corner(m: Mesh, face: Any, vertex: Any) -> bool:
    """True when ``(face, vertex)`` names the corner of a point-sphere."""
    try:
        return m.corner_edge(m.corner_at(face, vertex)) < 0
    except DLFLError:
        return False


@modeling_command
def insertEdge(c1: Any, c2: Any, check: bool = True) -> tuple[Any, ...]:
    """Insert an edge between two corners.

    ``check`` is TopMod's flag: False skipped its test that the corners differ,
    which corrupted the face given one corner twice; livemod refuses the same
    corner either way, so the flag changes nothing.

    Returns:
        ``(edgeid, cA, cB, cC, cD)``: the new edge and its four corners as
        ``(faceid, vertexid)`` tuples, always in the order of :func:`edgeInfo`:
        the two ends as they are now (``c1``'s, then ``c2``'s), then the corners
        after them.
    """
    flag(check, "check")
    m = mesh()
    a = resolve_corner(m, c1, "c1")
    b = resolve_corner(m, c2, "c2")
    if a == b:
        raise InvalidArgumentError(
            f"insertEdge needs two different corners, c1 and c2 are both {c1!r}")
    e = m.insert_edge(a, b)
    return (e, *_edge_corner_tuples(m, e))


def _edge_corner_tuples(m: Mesh, e: int) -> list[tuple[int, int]]:
    c0, c1 = m.edge_corners(e)
    return [corner_tuple(m, c) for c in (c0, c1, m.corner_next(c0), m.corner_next(c1))]


@modeling_command
def deleteEdge(edgeid: int, cleanup: bool = True) -> list[int]:
    """Delete an edge and return the ids of the faces left on its sides.

    Returns:
        ``[faceid]`` when two faces merged, ``[faceid, faceid]`` when one face
        split. With ``cleanup`` a side left as a point-sphere is removed with its
        vertex and left out; when none is left (an edge between two
        point-spheres) the result is ``[-1]``, as in TopMod.

    Raises:
        DLFLError: ``edgeid`` is not a live edge.
    """
    return mesh().delete_edge(edgeid, flag(cleanup, "cleanup")) or [-1]


@modeling_command
def subdivideEdge(*args: int) -> list[int]:
    """``subdivideEdge([divisions,] edgeid)``: split an edge, return the new vertex ids.

    Raises:
        DLFLError: not a live edge, or ``divisions`` not an integer >= 1.
        BudgetExceededError: the ``2 (divisions - 1)`` new corners would pass the
            scene's face budget (see :mod:`livemod.dlfl.budget`).
    """
    if len(args) == 1:
        return mesh().subdivide_edge(args[0])
    if len(args) == 2:
        m = mesh()
        divisions = whole_count(args[0], "divisions", each=2)
        check_growth(m, "subdivideEdge", faces=0, corners=2 * (divisions - 1),
                     max_faces=scene().face_budget)
        return m.subdivide_edge(args[1], divisions)
    raise InvalidArgumentError(f"subdivideEdge takes ([divisions,] edgeid), got {len(args)} "
                               "arguments")


@modeling_command
def collapseEdge(edgeid: int, cleanup: bool = True) -> int:
    """Collapse an edge to its midpoint; return the surviving vertex id.

    With ``cleanup`` (TopMod's default) a face the collapse leaves with one or
    two sides loses an edge, so no degenerate face remains; ``cleanup=False``
    keeps such 2-gons (as TopMod's ``collapseEdge(e, false)``).
    """
    return mesh().collapse_edge(edgeid, flag(cleanup, "cleanup"))


@modeling_command
def trisectEdge(edgeid: int, num: float, scale: bool) -> list[int]:
    """``trisectEdge(edgeid, num, scale)``: split an edge in three (TopMod's rule).

    With ``scale`` True each new point is ``num * end + (1 - num) * midpoint``
    (``num`` clamped to [0.01, 0.99]); otherwise it lies ``num`` from its end
    along the edge (clamped to [0.01, length/2 - 0.01]).

    Returns:
        ``[vertexid, vertexid]``: the new vertices, the first nearer the edge's
        first end; the edge keeps its id as the part from that end.

    Raises:
        DLFLError: see :func:`livemod.dlfl.geometry.trisect_edge`; the mesh is
            unchanged.
    """
    return _geometry.trisect_edge(mesh(), edgeid, num, scale)


@modeling_command
def spliceCorners(c1: Any, c2: Any) -> int:
    """``spliceCorners(c1, c2)``: join two corners' vertices into one, at their
    midpoint (TopMod's insertEdge then collapseEdge).

    Returns:
        The id of the surviving vertex: ``c1``'s, unless only ``c1`` is a
        point-sphere's (then ``c2``'s).

    Raises:
        DLFLError: a corner that does not exist, or two corners at one vertex;
            the mesh is unchanged.
    """
    m = mesh()
    return _geometry.splice_corners(m, resolve_corner(m, c1, "c1"),
                                    resolve_corner(m, c2, "c2"))


@modeling_command
def createFace(points: Sequence[Point], bothNew: bool = False) -> tuple[int, int]:
    """Create a two-sided polygon on new vertices: ``(frontfaceid, backfaceid)``.

    Raises:
        DLFLError: ``points`` is not a list of ``(x, y, z)`` points.
        BudgetExceededError: its ``2 n`` corners would pass the scene's face
            budget (see :mod:`livemod.dlfl.budget`); checked before the points
            are read.
    """
    if isinstance(points, str | bytes) or not isinstance(points, Iterable):
        raise InvalidArgumentError(f"points must be a list of (x, y, z) points, got {points!r}")
    del bothNew  # TopMod's face-type flag; livemod has no face types
    m = mesh()
    return m.create_face(_within_budget(m, points, scene().face_budget))


def _within_budget(m: Mesh, points: Iterable[Any], budget: int | None) -> Sequence[Any]:
    """``points`` for :func:`createFace`, refused past the face budget before the
    points are converted: by its length, or for an iterator without one, after
    reading at most one point more than the budget allows.

    Raises:
        BudgetExceededError: too many points.
    """
    if not hasattr(points, "__len__"):
        room = max(CORNERS_PER_FACE * face_budget(budget) - m.num_corners, 0) // 2
        points = list(itertools.islice(points, room + 1))
    counted: Any = points
    check_growth(m, "createFace", faces=2, corners=2 * len(counted), max_faces=budget)
    return counted


# -- ids and walks --------------------------------------------------------------

def _picked(name: str, is_live: Callable[[int], bool]) -> tuple[int, ...]:
    """The ids of selection field ``name`` that ``is_live`` in the current mesh; the
    others are noted in the run's ``missing_picks``, and a field with nothing
    selected in its ``unselected_reads``."""
    picked: tuple[int, ...] = getattr(scene().selection, name)
    run = current_run()
    if not picked:
        run.unselected_reads.add(name)
        return ()
    kept = tuple(i for i in picked if is_live(i))
    if len(kept) < len(picked):
        run.missing_picks = run.missing_picks.adding(name, (i for i in picked if i not in kept))
    return kept


def faces(selected: bool = False) -> tuple[int, ...]:
    """Ids of all faces (in creation order), or of the selected ones.

    Hole faces (boundaries of open meshes) are left out.
    """
    m = mesh()
    if flag(selected, "selected"):
        return _picked("faces", m.has_face)
    return tuple(m.face_ids()[~m.hole_mask()].tolist())


def edges(selected: bool = False) -> tuple[int, ...]:
    """Ids of all edges (in creation order), or of the selected ones."""
    m = mesh()
    return _picked("edges", m.has_edge) if flag(selected, "selected") else tuple(m.edge_ids().tolist())


def verts(selected: bool = False) -> tuple[int, ...]:
    """Ids of all vertices (in creation order), or of the selected ones."""
    m = mesh()
    return _picked("vertices", m.has_vertex) if flag(selected, "selected") else tuple(m.vertex_ids().tolist())


def corners(selected: bool = False) -> tuple[tuple[int, int], ...]:
    """``((faceid, vertexid), ...)`` of all corners, face by face, or the selected ones."""
    m = mesh()
    if flag(selected, "selected"):
        return tuple(corner_tuple(m, c) for c in _picked("corners", m.has_corner))
    return tuple(corner_tuple(m, c) for f in faces() for c in m.face_corners(f))


def walk(faceid: int) -> tuple[list[int], list[int]]:
    """Walk a face's boundary: ``([vertexid, ...], [edgeid, ...])``.

    Called at the top level of a script (not inside a function of it), it also
    prints the walk as the thesis shows it, ``DLFLFace 6 (4) :
    8--(24)-->9--(25)-->10--(26)-->11--(27)-->8``: the face id, its size, then
    each vertex and the edge to the next, back to the first vertex. TopMod's
    ``[backface]`` flag after each vertex is left out (livemod has none).
    """
    m = mesh()
    vertices, edges = m.face_vertices(faceid), m.face_edges(faceid)
    if _at_script_top_level(_getframe(1)):
        print(walk_text(faceid, vertices, edges))
    return vertices, edges


def walk_text(faceid: int, vertices: Sequence[int], edges: Sequence[int]) -> str:
    """The thesis's printed walk of face ``faceid`` with these vertices and edges
    (see :func:`walk`); a point-sphere is its one vertex."""
    steps = "".join(f"{v}--({e})-->" for v, e in zip(vertices, edges, strict=False))
    tail = vertices[0] if edges else ""
    return f"DLFLFace {faceid} ({len(vertices)}) : {steps or vertices[0]}{tail}"


def _at_script_top_level(frame: FrameType) -> bool:
    """True when ``frame`` runs a script's module body: ``python script.py`` or a
    livemod run, both of which name the script's module ``__main__``."""
    return frame.f_code.co_name == "<module>" and frame.f_globals.get("__name__") == "__main__"


def cornerWalk(faceid: int) -> list[tuple[int, int]]:
    """The corners of a face in order: ``[(faceid, vertexid), ...]``."""
    m = mesh()
    return [corner_tuple(m, c) for c in m.face_corners(faceid)]


def next(c: Any, *default: Any) -> Any:  # noqa: A001  (the thesis's name)
    """The corner after ``c`` in its face, as ``(faceid, vertexid)``.

    Called with an iterator (as Python's built-in ``next``), it behaves like the
    built-in, so scripts that import ``*`` keep working.
    """
    if not isinstance(c, tuple | int) or isinstance(c, bool):
        if not hasattr(c, "__next__"):
            raise InvalidArgumentError(f"next takes a corner or an iterator, got {c!r}")
        iterator: Any = c
        return builtins.next(iterator, *default)
    m = mesh()
    return corner_tuple(m, m.corner_next(resolve_corner(m, c)))


def prev(c: Any) -> tuple[int, int]:
    """The corner before ``c`` in its face, as ``(faceid, vertexid)``."""
    m = mesh()
    return corner_tuple(m, m.corner_prev(resolve_corner(m, c)))


def getCorner(edgeid: int, faceid: int) -> tuple[int, int]:
    """The side of edge ``edgeid`` that lies in face ``faceid``, as a corner tuple.

    Raises:
        DLFLError: the edge does not border that face.
    """
    m = mesh()
    sides = m.edge_corners(edgeid)
    if not is_id(faceid):  # True == 1 would otherwise pick face 1
        raise InvalidArgumentError(f"faceid must be a face id (an integer), got {faceid!r}")
    for c in sides:
        if m.corner_face(c) == faceid:
            return corner_tuple(m, c)
    raise InvalidArgumentError(f"edge {edgeid} does not border face {shown(faceid)}")


def saveCorner(c: Any) -> int:
    """A corner id for ``c`` that stays valid while that corner exists."""
    return resolve_corner(mesh(), c)


def restoreCorner(cornerid: int) -> tuple[int, int]:
    """The current ``(faceid, vertexid)`` of a corner saved with :func:`saveCorner`."""
    return corner_tuple(mesh(), resolve_corner(mesh(), cornerid, "cornerid"))


# -- objects --------------------------------------------------------------------

def load(filename: str) -> int:
    """Load ``.obj``/``.dlfl``/``.stl``/``.ply`` (by extension), or a built-in shape by name
    (``load("soccerball")``); push it as the current object and return its id.

    Raises:
        DLFLError: the file cannot be read (InvalidArgumentError for a folder or
            a file the system will not open, as ``save`` does) or names no
            built-in shape.
    """
    from ..io import open_mesh

    path = _path(filename, "load")
    name = os.fspath(filename)
    if os.path.isfile(path):  # before reading: a file that fails to load is watched too
        current_run().files_read.append(os.path.abspath(path))
    try:
        loaded = open_mesh(path, shape_name=name)
    except OSError as exc:  # only the project's errors leave a command
        raise InvalidArgumentError(f"cannot load {path!r}: {exc.strerror or exc}") from None
    oid = scene().add(loaded, os.path.basename(name))
    announce_step(f"load {name}")
    return oid


def save(filename: str) -> bool:
    """Save the current object (``.obj``, ``.dlfl``, ``.stl``, ``.ply``); True on success.

    Raises:
        InvalidArgumentError: ``filename`` is not a path, or cannot be written (the
            system's reason in the message, as :func:`load` says it).
    """
    from ..io import save_mesh

    path = _path(filename, "save")
    current_run().files_written.append(os.path.abspath(path))
    try:
        save_mesh(mesh(), path)
    except OSError as exc:
        raise InvalidArgumentError(f"cannot save {path!r}: {exc.strerror or exc}") from None
    return True


def _path(filename: Any, command: str) -> str:
    """``filename`` as a string path, or a DLFLError naming the command.

    A relative name is taken relative to the run's folder (the script's folder
    when the runner runs it), as if the script ran from where it lives.
    """
    if not isinstance(filename, str | os.PathLike):
        raise InvalidArgumentError(f"{command} takes a file name, got {filename!r}")
    path = os.fspath(filename)
    folder = current_run().directory
    if folder is not None and not os.path.isabs(path):
        return os.path.join(folder, path)
    return path


def kill(objectid: int) -> None:
    """Remove an object from the scene."""
    scene().kill(objectid)


def switch(objectid: int) -> int:
    """Make an object current; return its id."""
    return scene().switch(objectid)


# -- information ----------------------------------------------------------------

def printObject() -> None:
    """Print the current object's counts and genus (the thesis's format)."""
    m = mesh()
    print(f"Number of vertices : {m.num_vertices}")
    print(f"Number of faces : {m.num_faces}")
    print(f"Number of edges : {m.num_edges}")
    print("Number of materials : 1")
    print(f"Genus : {_genus(m)}")


def _vec(v: np.ndarray) -> tuple[float, float, float]:
    return float(v[0]), float(v[1]), float(v[2])


def vertexInfo(vertexid: int) -> dict[str, Any]:
    """``{'id', 'type', 'coords', 'valence'}`` of a vertex."""
    m = mesh()
    kind = "point-sphere" if m.is_point_sphere(vertexid) else "normal"
    return {"id": vertexid, "type": kind, "coords": _vec(m.position(vertexid)),
            "valence": m.valence(vertexid)}


def edgeInfo(edgeid: int) -> dict[str, Any]:
    """``{'id', 'type', 'midpoint', 'normal', 'cornerA'..'cornerD', 'length'}``.

    cornerA and cornerB are the edge's two sides, cornerC and cornerD the
    corners after them (the order :func:`insertEdge` returns). The normal is the
    normalised sum of the normals of the two faces.
    """
    m = mesh()
    va, vb = m.edge_vertices(edgeid)
    pa, pb = m.position(va), m.position(vb)
    ca, cb, cc, cd = _edge_corner_tuples(m, edgeid)
    n = face_normal(m, ca[0]) + face_normal(m, cb[0])
    n = n / max(float(np.linalg.norm(n)), 1e-300)
    with np.errstate(over="ignore"):  # ends near the float maximum: a length of inf
        length = float(lengths((pb - pa)[None])[0])
    # halves first: the sum of two far-apart points can overflow, their mean cannot
    return {"id": edgeid, "type": "normal", "midpoint": _vec(pa * 0.5 + pb * 0.5),
            "normal": _vec(n), "cornerA": ca, "cornerB": cb, "cornerC": cc,
            "cornerD": cd, "length": length}


def faceInfo(faceid: int) -> dict[str, Any]:
    """``{'id', 'type', 'centroid', 'normal', 'size', 'color'}`` of a face; its
    colour is ``(r, g, b)`` in ``[0, 1]``, or None when it has none."""
    m = mesh()
    kind = "hole" if m.is_hole(faceid) else "normal"
    return {"id": faceid, "type": kind, "centroid": _vec(face_centroid(m, faceid)),
            "normal": _vec(face_normal(m, faceid)), "size": m.face_size(faceid),
            "color": m.face_color(faceid)}


def cornerInfo(c: Any) -> dict[str, Any]:
    """``{'face', 'vertex', 'edge', 'type'}`` of a corner (``edge`` is -1 for a
    point-sphere)."""
    m = mesh()
    cid = resolve_corner(m, c)
    return {"face": m.corner_face(cid), "vertex": m.corner_vertex(cid),
            "edge": m.corner_edge(cid), "type": "normal", "id": cid}


def vertexEdges(vertexid: int) -> list[int]:
    """Ids of the edges at a vertex, in rotation order."""
    return mesh().vertex_edges(vertexid)


def centroid(vertexids: Iterable[int] | None = None) -> tuple[float, float, float]:
    """Mean position of the given vertices (all vertices when omitted)."""
    m = mesh()
    ids = m.vertex_ids().tolist() if vertexids is None else _id_list(vertexids, "centroid")
    if not ids:
        raise InvalidArgumentError("centroid needs at least one vertex id")
    return _vec(_centroid(m.positions(ids)))


def _id_list(ids: Any, command: str) -> list[Any]:
    """``ids`` as a list, or a DLFLError when it is not a sequence of ids."""
    if isinstance(ids, str | bytes) or not hasattr(ids, "__iter__"):
        raise InvalidArgumentError(f"{command} takes a list of vertex ids, got {ids!r}")
    return list(ids)


# -- transforms -----------------------------------------------------------------

def _xyz(args: tuple[Any, ...], name: str) -> tuple[np.ndarray, tuple[Any, ...]]:
    """Accept both ``f(x, y, z, ...)`` and ``f((x, y, z), ...)``."""
    if args and isinstance(args[0], Sequence | np.ndarray):
        return np.array(as_point(args[0])), args[1:]
    if len(args) >= 3:
        return np.array(as_point(args[:3])), args[3:]
    raise InvalidArgumentError(f"{name} takes (x, y, z) or ((x, y, z)), got {args!r}")


@modeling_command
def translate(*args: Any, relative: bool = True) -> None:
    """``translate(x, y, z[, relative])``: move the current object.

    livemod moves the vertices at once; with ``relative=False`` the object is
    placed so that its origin lands at ``(x, y, z)``.
    """
    offset, rest = _xyz(args, "translate")
    if rest:
        relative = flag(rest[0], "relative")
    obj = scene().current_object
    delta = offset if relative else offset - obj.origin
    _transform.translate(obj.mesh, delta)
    obj.origin = obj.origin + delta


@modeling_command
def scale(*args: Any) -> None:
    """``scale((x, y, z))``: scale the current object about its origin, per axis."""
    factors, _ = _xyz(args, "scale")
    obj = scene().current_object
    with np.errstate(over="ignore"):
        factor = obj.factor * factors
    if not np.isfinite(factor).all():
        # a vertex the scale would lose is the better answer (a trial on a copy: this
        # path is rare); a mesh too small to overflow still has a total that does
        _transform.scale(obj.mesh.copy(), factors, center=obj.origin)
        raise GeometryError(f"scale{shown(tuple(factors.tolist()))} would make the "
                            f"object's total scale overflow: {factor.tolist()}")
    _transform.scale(obj.mesh, factors, center=obj.origin)
    obj.factor = factor


@modeling_command
def move(vertexids: Iterable[int], *args: Any, relative: bool = True) -> None:
    """``move(vertexids, (x, y, z)[, relative])``: move vertices by (or to) a point."""
    target, rest = _xyz(args, "move")
    if rest:
        relative = flag(rest[0], "relative")
    ids = _id_list(vertexids, "move")
    if relative:
        _transform.translate(mesh(), target, vertices=ids)
    else:
        mesh().set_positions(ids, target)


def freezeTrans() -> None:
    """Make the current placement the object's new origin and unit scale.

    livemod already applied translate/scale to the vertices, so this only resets
    the transform record that absolute moves are measured from.
    """
    obj = scene().current_object
    obj.origin = np.zeros(3)
    obj.factor = np.ones(3)


def step(label: str = "step") -> None:
    """Mark a playback checkpoint with a label (a livemod addition)."""
    announce_step(str(label))
