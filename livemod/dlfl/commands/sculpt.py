"""Thesis commands of the sculpting family: rind, wireframe, column and extras.

``rind``, ``wireframe`` and ``column`` are the thesis appendix's commands.
The extras are livemod additions, named after TopMod's menu entries (its
Python module had ``sierpinsky`` and ``menger`` commented out): ``sierpinsky()``,
``menger([thickness])``, ``meshsmooth()``, ``planarize()``, ``spheralize()``,
``crust(thickness[, uniform])``, ``convexHull()`` and ``dualConvexHull()``
(TopMod's sculpting menu). Every one rebuilds or reshapes the current
object; those that rebuild it give all its elements fresh ids.
"""

from __future__ import annotations

from typing import Any

from .. import geometry, hull, sponge
from .. import rind as _rind
from .. import sierpinsky as _sierpinsky
from .. import wireframe as _wire
from .._checks import finite_number, flag
from ..errors import DLFLError
from ._base import id_arguments, mesh, modeling_command

__all__ = [
    "rind", "wireframe", "column", "crust", "sierpinsky", "menger", "meshsmooth",
    "planarize", "spheralize", "convexHull", "dualConvexHull",
]


@modeling_command
def rind(facelist: Any, useScaling: bool, percent: float, uniform: bool = True) -> None:
    """``rind(facelist, useScaling, percent[, uniform])``: crust, then punch the faces.

    ``percent`` is the thickness when ``useScaling`` is false, otherwise the
    scale of the inner copy, ``0 < |percent| < 1`` (TopMod clamped it to [-1, 1],
    where +-1 gave two coincident shells). ``uniform`` keeps the
    thickness exact at corners (TopMod parsed this bool as a double; livemod
    takes a bool). Punching ``k`` faces of a closed genus-0 object gives genus
    ``k - 1``; faces that share an edge open into one hole.

    Raises:
        DLFLError: a face id that is gone, a zero or inverting thickness/scale,
            or a flag that is not True or False.
    """
    faces = id_arguments(facelist, "facelist")
    value = finite_number(percent, "percent")
    if flag(useScaling, "useScaling"):
        _rind.rind(mesh(), faces, use_scaling=True, scale=value)
    else:
        _rind.rind(mesh(), faces, value, uniform=flag(uniform, "uniform"))


@modeling_command
def crust(thickness: float = 0.5, uniform: bool = True) -> None:
    """``crust([thickness, uniform])``: TopMod's createCrust; two shells (livemod extra)."""
    _rind.crust(mesh(), finite_number(thickness, "thickness"), uniform=flag(uniform, "uniform"))


@modeling_command
def wireframe(thickness: float = 0.1, split: bool = True) -> None:
    """``wireframe([thickness, split])``: a solid wire of ``thickness`` along every edge.

    Cube: 48/120/64, genus 5.
    """
    _wire.wireframe(mesh(), finite_number(thickness, "thickness"), flag(split, "split"))


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
        raise DLFLError(f"segments must be a whole number, got {segments!r}")
    _wire.columns(mesh(), finite_number(thickness, "thickness"), segments)


@modeling_command
def sierpinsky() -> None:
    """``sierpinsky()``: TopMod's multiConnectMidpoints (cube 20/60/32, genus 5)."""
    _sierpinsky.sierpinsky(mesh())


@modeling_command
def menger(thickness: float | None = None) -> float:
    """``menger([thickness])``: TopMod's Menger sponge remeshing (cube 64/156/84).

    Without ``thickness``, TopMod's 0.67, scaled down on meshes whose inner shell
    collapses sooner (see :func:`livemod.dlfl.sponge.sponge`).

    Returns:
        The thickness used (TopMod returned nothing).

    Raises:
        DLFLError: see :func:`livemod.dlfl.sponge.sponge`; the mesh is unchanged.
    """
    given = None if thickness is None else finite_number(thickness, "thickness")
    return sponge.sponge(mesh(), given)


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
    from its last corner). Cube: 8/18/12.

    Raises:
        DLFLError: fewer than 4 vertices, or all of them in one plane.
    """
    hull.convex_hull(mesh())


@modeling_command
def dualConvexHull() -> None:
    """``dualConvexHull()``: the polar dual of the object's convex hull (coplanar
    facets merged): one face per hull vertex, one vertex per hull face. Cube: an
    octahedron, 6/12/8 (TopMod's createDualConvexHull cut the bounding box and gave
    the cube back).

    Raises:
        DLFLError: fewer than 4 vertices, or all of them in one plane.
    """
    hull.dual_convex_hull(mesh())
