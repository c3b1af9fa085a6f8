"""Thesis commands of the sculpting family: rind, wireframe, column and extras.

``rind``, ``wireframe`` and ``column`` are the thesis appendix's commands.
The extras are livemod additions, named after TopMod's menu entries (its
Python module had ``sierpinsky`` and ``menger`` commented out): ``sierpinsky()``,
``menger([thickness, collapse])``, ``meshsmooth()``, ``planarize()``, ``spheralize()``,
``crust(thickness[, uniform])`` and ``punch([faceids])`` (its crust mode),
``convexHull()`` and ``dualConvexHull()``
(TopMod's sculpting menu), and ``multiConnectFaces(...)`` (its multi-face
handle). Every one but ``multiConnectFaces`` rebuilds or reshapes the current
object; those that rebuild it give all its elements fresh ids.
"""

from __future__ import annotations

from typing import Any
from weakref import WeakKeyDictionary

from .. import geometry, hull, multihandle, sponge
from .. import rind as _rind
from .. import sierpinsky as _sierpinsky
from .. import wireframe as _wire
from .._checks import finite_number, flag, shown
from ..errors import InvalidArgumentError
from ..mesh import Mesh
from ._base import id_arguments, mesh, modeling_command, scene

__all__ = [
    "rind", "wireframe", "column", "crust", "punch", "sierpinsky", "menger", "meshsmooth",
    "planarize", "spheralize", "convexHull", "dualConvexHull", "multiConnectFaces",
]

# multiConnectFaces' methods, with the options each one reads besides the faces
_MULTI_METHODS = {"hull": ("scale", "extrude", "maxOffsets"), "closest-edge": (),
                  "fitted": ("minFactor",)}
_MULTI_DEFAULTS = {"scale": 1.0, "extrude": 0.5, "maxOffsets": False, "minFactor": 0.01}


# the faces a crust() or rind() of each mesh left to punch (TopMod kept its last
# crust's in globals); weak, so a mesh that goes takes its twins with it
_CRUST_TWINS: WeakKeyDictionary[Mesh, _rind.CrustTwins] = WeakKeyDictionary()


@modeling_command
def rind(facelist: Any, useScaling: bool, percent: float, uniform: bool = True, *,
         cleanup: bool = True) -> None:
    """``rind(facelist, useScaling, percent[, uniform])``: crust, then punch the faces.

    ``percent`` is the thickness when ``useScaling`` is false, otherwise the
    scale of the inner copy, ``0 < |percent| < 1`` (TopMod clamped it to [-1, 1],
    where +-1 gave two coincident shells). ``uniform`` keeps the
    thickness exact at corners (TopMod parsed this bool as a double; livemod
    takes a bool). Punching ``k`` faces of a closed genus-0 object gives genus
    ``k - 1``; faces that share an edge open into one hole, unless ``cleanup``
    (TopMod's GUI checkbox, on by default) is off, which keeps the wall of no
    thickness between them. The faces left can be punched later by :func:`punch`.

    Raises:
        DLFLError: a face id that is gone, a zero or inverting thickness/scale,
            or a flag that is not True or False.
    """
    faces = id_arguments(facelist, "facelist")
    value = finite_number(percent, "percent")
    budget, m, tidy = scene().face_budget, mesh(), flag(cleanup, "cleanup")
    if flag(useScaling, "useScaling"):
        twins = _rind.rind(m, faces, use_scaling=True, scale=value, cleanup=tidy,
                           max_faces=budget)
    else:
        twins = _rind.rind(m, faces, value, uniform=flag(uniform, "uniform"), cleanup=tidy,
                           max_faces=budget)
    _CRUST_TWINS[m] = twins


@modeling_command
def crust(thickness: float = 0.5, uniform: bool = True, *, scale: float | None = None) -> None:
    """``crust([thickness, uniform])``: TopMod's createCrust; two shells (livemod
    extra), to :func:`punch` later. With ``scale``, TopMod's createCrustWithScaling
    (GUI "Rind Modeling Scaling", 0.9): the inner shell is the object scaled by
    ``scale`` about its vertex centroid (``0 < |scale| < 1``) instead of moved
    ``thickness`` inward."""
    m, budget = mesh(), scene().face_budget
    if scale is None:
        twins = _rind.crust(m, finite_number(thickness, "thickness"),
                            uniform=flag(uniform, "uniform"), max_faces=budget)
    else:
        twins = _rind.crust(m, use_scaling=True, scale=finite_number(scale, "scale"),
                            max_faces=budget)
    _CRUST_TWINS[m] = twins


@modeling_command
def punch(faceids: Any = None, cleanup: bool = True) -> list[int]:
    """``punch([faceids, cleanup])``: open faces of a crust made earlier (by
    :func:`crust` or :func:`rind`) into tubes to their twins on the other shell,
    TopMod's makeHole (clicking a face in its crust mode); the ids default to the
    selection. Either shell's copy of a face names the pair. Everything else
    keeps its id, so a crust is made once and punched in later steps:
    ``crust(0.2)``, then ``punch(face_loop(e))``. TopMod's shift-click punched
    every outer face of the clicked one's size: ``punch(similar_faces(f))``.
    With ``cleanup`` the wall of no thickness where two punched faces share an
    edge goes, as in :func:`rind`. Cube crust, one face: 16/28/14.

    Returns:
        The ids of the tubes' faces.

    Raises:
        DLFLError: no crust made on this object, or a face that is not an
            unpunched face of it (punched already, made since, or changed); the
            mesh is unchanged.
    """
    faces, tidy = id_arguments(faceids, "faceids", "faces"), flag(cleanup, "cleanup")
    m = mesh()
    twins = _CRUST_TWINS.get(m)
    if twins is None:
        raise InvalidArgumentError("punch needs a crust: make one on this object with crust() "
                                   "or rind() first")
    return _rind.punch(m, twins, faces, cleanup=tidy, max_faces=scene().face_budget)


@modeling_command
def wireframe(thickness: float = 0.1, split: bool = True, *, width: float | None = None) -> None:
    """``wireframe([thickness, split])``: a solid wire of ``thickness`` along every edge.

    With ``width``, TopMod's makeWireframe2 (GUI "Wireframe Modeling 2"): the
    wires are ``width`` wide on the surface and ``thickness`` deep. Cube:
    48/120/64, genus 5.
    """
    given = None if width is None else finite_number(width, "width")
    _wire.wireframe(mesh(), finite_number(thickness, "thickness"), flag(split, "split"),
                    width=given, max_faces=scene().face_budget)


@modeling_command
def column(thickness: float, segments: Any) -> None:
    """``column(thickness, segments)``: a tube of ``segments`` sides around every edge,
    joined by convex hulls at the vertices. Cube, 4 segments: 96/216/112.

    Raises:
        DLFLError: ``segments`` below 3 or not whole, ``thickness`` not positive.
    """
    if isinstance(segments, float) and segments.is_integer():
        segments = int(segments)
    if not isinstance(segments, int) or isinstance(segments, bool):
        raise InvalidArgumentError(f"segments must be a whole number, got {segments!r}")
    _wire.columns(mesh(), finite_number(thickness, "thickness"), segments,
                  max_faces=scene().face_budget)


@modeling_command
def sierpinsky() -> None:
    """``sierpinsky()``: TopMod's multiConnectMidpoints (cube 20/60/32, genus 5)."""
    _sierpinsky.sierpinsky(mesh(), max_faces=scene().face_budget)


@modeling_command
def menger(thickness: float | None = None, collapse: float = 0.0, *,
           keep2gons: bool = True) -> float:
    """``menger([thickness, collapse])``: TopMod's Menger sponge remeshing
    (``createSponge(t, collapse)``, cube 64/156/84).

    Without ``thickness``, TopMod's 0.67, scaled down on meshes whose inner shell
    collapses sooner (see :func:`livemod.dlfl.sponge.sponge`). ``collapse`` is
    TopMod's "Edge Collapse Threshold Factor" (at least 0): the inner shell's
    joining edges shorter than ``collapse * thickness`` (0.01 for 0) or crossed
    collapse; where faces meet at right angles (the cube) every value gives the
    same sponge. ``keep2gons`` keeps the 2-gons TopMod's edge collapses leave
    along the inner shell's edges; ``keep2gons=False`` gives the clean sponge
    (cube 64/144/72).

    Returns:
        The thickness used (TopMod returned nothing).

    Raises:
        DLFLError: see :func:`livemod.dlfl.sponge.sponge`; the mesh is unchanged.
    """
    given = None if thickness is None else finite_number(thickness, "thickness")
    return sponge.sponge(mesh(), given, collapse=collapse,
                         keep_2gons=flag(keep2gons, "keep2gons"),
                         max_faces=scene().face_budget)


@modeling_command
def meshsmooth() -> None:
    """``meshsmooth()``: one step of TopMod's tangential smoothing."""
    geometry.mesh_smooth(mesh())


@modeling_command
def planarize() -> None:
    """``planarize()``: TopMod's 100-step pull of vertices onto their face planes."""
    geometry.planarize(mesh())


@modeling_command
def spheralize() -> None:
    """``spheralize()``: move every vertex to the unit sphere about the centroid."""
    geometry.spheralize(mesh())


@modeling_command
def convexHull() -> None:
    """``convexHull()``: TopMod's createConvexHull; the object becomes the convex hull
    of its vertices, in triangles (coplanar facets merged, then each cut into a fan
    from its last corner). Cube: 8/18/12. Up to 1,000 vertices the faces come in
    the order gift wrapping finds them; above, sorted by their least vertex.

    Raises:
        DLFLError: fewer than 4 vertices, or all of them in one plane.
    """
    hull.convex_hull(mesh(), max_faces=scene().face_budget)


@modeling_command
def dualConvexHull() -> None:
    """``dualConvexHull()``: the polar dual of the object's convex hull (coplanar
    facets merged): one face per hull vertex, one vertex per hull face. Cube: an
    octahedron, 6/12/8 (TopMod's createDualConvexHull cut the bounding box and gave
    the cube back).

    Raises:
        DLFLError: fewer than 4 vertices, or all of them in one plane.
    """
    hull.dual_convex_hull(mesh(), max_faces=scene().face_budget)


@modeling_command
def multiConnectFaces(faces: Any = None, scale: float = 1.0, extrude: float = 0.5,
                      maxOffsets: bool = False, method: str = "hull",
                      minFactor: float = 0.01) -> None:
    """``multiConnectFaces([faces, scale, extrude, maxOffsets, method, minFactor])``:
    join several faces (default: the selected ones) at once, TopMod's multi-face handle.

    ``method`` picks TopMod's variant (its C++ told them apart by their arguments):

    * ``"hull"`` (default, ``multiConnectFaces(faces, scale, extrude, maxOffsets)``):
      a hub, the convex hull of the face points pushed ``extrude`` along their
      normals (with ``maxOffsets``, each face as far as the others' side walls let
      it) and scaled by ``scale``, joined to every face by a tube. Cube faces 0, 2,
      4: 20/42/20, genus 2.
    * ``"closest-edge"`` (TopMod's ``multiConnectFaces(faces)``): quads between the
      closest nearly coplanar edges of different faces. Cube top and bottom: 8/16/8.
    * ``"fitted"`` (``multiConnectFaces(faces, min_factor, true)``): the smallest
      hub keeping every point, found by moving the faces toward their common
      centre in steps down to ``minFactor``; for faces that face each other.

    See :mod:`livemod.dlfl.multihandle` for the rules.

    Raises:
        DLFLError: an unknown ``method``, an option the method does not read set
            away from its default, or what the method refuses (too few faces, no
            hull face facing a face, no qualifying edge pair, ...); the mesh is
            unchanged.
    """
    ids = id_arguments(faces, "faces", "faces")
    given = {"scale": scale, "extrude": extrude, "maxOffsets": maxOffsets, "minFactor": minFactor}
    _check_multi_options(method, given)
    m = mesh()
    budget = scene().face_budget
    if method == "hull":
        multihandle.multi_face_handle(m, ids, scale, extrude, max_offsets=maxOffsets,
                                      max_faces=budget)
    elif method == "closest-edge":
        multihandle.multi_face_handle_closest_edges(m, ids, max_faces=budget)
    else:
        multihandle.multi_face_handle_fitted(m, ids, minFactor, max_faces=budget)


def _check_multi_options(method: Any, given: dict[str, Any]) -> None:
    """Raises DLFLError unless ``method`` is known and every option of ``given``
    it does not read keeps its default (a value it would silently ignore)."""
    if not isinstance(method, str) or method not in _MULTI_METHODS:
        raise InvalidArgumentError(f"method must be one of {', '.join(map(repr, _MULTI_METHODS))}, "
                                   f"got {method!r}")
    for name, value in given.items():
        if name not in _MULTI_METHODS[method] and not _is_default(value, _MULTI_DEFAULTS[name]):
            raise InvalidArgumentError(f"multiConnectFaces method {method!r} does not use {name} "
                                       f"(got {shown(value)})")


def _is_default(value: Any, default: Any) -> bool:
    # a bool default matches only a bool (0 is not False here), a number only a number
    if isinstance(default, bool):
        return value is default
    return not isinstance(value, bool) and isinstance(value, int | float) and value == default
