"""Remeshing: every TopMod subdivision scheme and the dual, vectorized.

``subdivide(mesh, scheme, **options)`` runs a scheme by its thesis name;
:data:`SCHEMES` maps every name to its function; one function per scheme is
exported too (``catmull_clark(mesh)``, ``doo_sabin(mesh)``, ...). Every scheme
rebuilds the mesh in one step (see :mod:`._layout`): every element of the
result gets a fresh id (ids are never reused). Defaults are TopMod's GUI ones
(TOPMOD.md section 3) and every option is honoured.

The GUI's composite schemes are available by name:

========================== ===========================================
name                       steps
========================== ===========================================
root3, root-3              dual, honeycomb, dual
cubic-pentagonalization    pentagon, dual, dual (options go to pentagon)
dual-pentagonalization     dual, pentagon, dual
dual-pentagon-preserving   dual, pentagon-preserve, dual
six-preserving-loop-style  dual, root4, dual (GUI six-preservation "Loop Style")
dual-loop                  dual, loop, dual
12.6.4                     dual, dual-12.6.4, dual
dual-checkerboard          dual, checker, dual
========================== ===========================================

Otherwise a composite's options go to its middle step. Each composite computes
its result in one step (the face budget is checked before anything is built; a
failure leaves the mesh unchanged): ``cubic-pentagonalization`` is :func:`pentagon`
with the double dual's vertex positions, ``dual-checkerboard`` is
:func:`checker`'s topology with the positions of the dual of checker on the
dual; the others lay out the final dual over the old corners
(:mod:`.composites`). The same mesh as the three steps up to the order of its
elements and rounding. Aliases: "dual-pentagon" = "pentagon-preserve" (TopMod's Python
name), "allfaces" = "linear-vertex" (Python's ``subdivideAllFaces``); GUI
"Stellate" is ``linear-vertex`` with ``usequads=False``. ``sierpinsky`` (TopMod's
``multiConnectMidpoints``, TOPMOD.md section 5) and ``modified-corner-cut`` are
implemented by the sculpting family and registered here by delegation.

Holes and point-spheres: every scheme treats a hole face as a face (as TopMod
does) and flags the faces made inside it as holes; faces made around old
vertices or edges are ordinary faces (so a dual turns a hole into a vertex).
Point-spheres are set aside and come through unchanged.
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

from ..budget import face_budget
from ..errors import InvalidArgumentError, unknown_name
from ..mesh import Mesh
from ._sizes import check_steps
from .composites import (
    dual_loop,
    dual_pentagon_preserving,
    dual_pentagonalization,
    root3,
    six_preserving_loop_style,
    twelve_six_four,
)
from .convert import (
    cubic_pentagonalization,
    double_stellate,
    dual,
    dual_1264,
    fractal,
    honeycomb,
    linear_vertex,
    pentagon,
    pentagon_preserve,
    root4,
    simplest,
    sqrt3,
    star,
    stellate,
    subdivide_all_edges,
    subdivide_faces,
    triangulate,
    vertex_cut,
)
from .extra import checker, dome, doo_sabin_bc_new, dual_checkerboard
from .smooth import catmull_clark, corner_cut, doo_sabin, doo_sabin_bc, loop, loop_style

Scheme = Callable[..., None]


def modified_corner_cut(mesh: Mesh, *, thickness: float = 0.25, variant: int = 1,
                        max_faces: int | None = None) -> None:
    """Modified corner cutting (TopMod ``modifiedCornerCuttingSubdivide``,
    "modified-corner-cut"): delegates to the wireframe family's
    ``from livemod.dlfl.wireframe import modified_corner_cut``. GUI default 0.25.
    Cube: 24/48/26. ``variant=2``: TopMod's ``modifiedCornerCuttingSubdivide2``,
    every corner point ``thickness (n1 + n2)`` from its vertex.

    Raises:
        DLFLError: a bad ``thickness`` or ``variant``, or the face budget.
    """
    from ..wireframe import modified_corner_cut as cut

    check_steps(mesh, ("modified-corner-cut",), max_faces)
    _point_spheres_aside(mesh, lambda work: cut(work, thickness, variant))


def sierpinsky(mesh: Mesh, *, max_faces: int | None = None) -> None:
    """Sierpinsky (TopMod ``multiConnectMidpoints``, "sierpinsky"): delegates to
    ``from livemod.dlfl.sierpinsky import sierpinsky``. Cube: 20/60/32, genus 5.

    Raises:
        DLFLError: the face budget, or input that scheme refuses.
    """
    from ..sierpinsky import sierpinsky as run

    check_steps(mesh, ("sierpinsky",), max_faces)
    _point_spheres_aside(mesh, run)


def _point_spheres_aside(mesh: Mesh, scheme: Callable[[Mesh], Any]) -> None:
    """Run ``scheme`` (which refuses point-spheres) on ``mesh`` without its
    point-spheres, then put them back at their places, as every other scheme
    leaves them, in their colours. On an error the mesh is unchanged."""
    spheres = [v for v in mesh.vertex_ids().tolist() if mesh.is_point_sphere(v)]
    if not spheres:
        scheme(mesh)
        return
    places = mesh.positions(spheres)
    colors = [mesh.face_color(mesh.corner_face(mesh.vertex_corner(v))) for v in spheres]
    work = mesh.copy()
    for v in spheres:
        work.remove_vertex(v)
    if work.counts()[2]:
        scheme(work)
    for place, color in zip(places, colors, strict=True):
        v = work.create_vertex(place)
        if color is not None:
            work.set_face_color(work.corner_face(work.vertex_corner(v)), color)
    mesh.replace_with(work)


SCHEMES: dict[str, Scheme] = {
    "loop": loop,
    "checker": checker,
    "simplest": simplest,
    "vertex-cut": vertex_cut,
    "pentagon": pentagon,
    "dual-pentagon": pentagon_preserve,
    "pentagon-preserve": pentagon_preserve,
    "honeycomb": honeycomb,
    "doo-sabin": doo_sabin,
    "doo-sabin-bc": doo_sabin_bc,
    "doo-sabin-bc-new": doo_sabin_bc_new,
    "corner-cut": corner_cut,
    "modified-corner-cut": modified_corner_cut,
    "root4": root4,
    "catmull-clark": catmull_clark,
    "star": star,
    "sqrt3": sqrt3,
    "fractal": fractal,
    "stellate": stellate,
    "double-stellate": double_stellate,
    "dome": dome,
    "dual-12.6.4": dual_1264,
    "loop-style": loop_style,
    "linear-vertex": linear_vertex,
    "allfaces": linear_vertex,
    "triangulate": triangulate,
    "dual": dual,
    "subdivide-all-edges": subdivide_all_edges,
    "sierpinsky": sierpinsky,
}
COMPOSITES: dict[str, Scheme] = {
    "root3": root3,
    "root-3": root3,
    "cubic-pentagonalization": cubic_pentagonalization,
    "dual-pentagonalization": dual_pentagonalization,
    "dual-pentagon-preserving": dual_pentagon_preserving,
    "six-preserving-loop-style": six_preserving_loop_style,
    "dual-loop": dual_loop,
    "12.6.4": twelve_six_four,
    "dual-checkerboard": dual_checkerboard,
}
SCHEMES.update(COMPOSITES)


def scheme_options(scheme: str) -> list[str]:
    """The option names of ``scheme`` in TopMod's argument order (no ``max_faces``).

    Raises:
        DLFLError: an unknown scheme, listing the valid names.
    """
    func = _lookup(scheme)
    params = inspect.signature(func).parameters.values()
    return [p.name for p in params
            if p.kind is inspect.Parameter.KEYWORD_ONLY and p.name != "max_faces"]


def _lookup(scheme: object) -> Scheme:
    if not isinstance(scheme, str) or scheme not in SCHEMES:
        raise InvalidArgumentError(unknown_name("unknown subdivision scheme", scheme,
                                                sorted(SCHEMES), "valid schemes"))
    return SCHEMES[scheme]


def subdivide(mesh: Mesh, scheme: str, **options: Any) -> None:
    """Remesh ``mesh`` in place with the named scheme.

    Args:
        mesh: the mesh; rebuilt with fresh ids.
        scheme: a name of :data:`SCHEMES`.
        **options: the scheme's options (see its function) and ``max_faces``.

    Raises:
        DLFLError: an unknown scheme (listing the valid names), an unknown option
            (listing the scheme's), a bad option value, or a result over the face
            budget. The mesh is unchanged.
    """
    func = _lookup(scheme)
    face_budget(options.get("max_faces"))  # a bad budget, even where nothing grows
    allowed = scheme_options(scheme)
    for name in options:
        if name not in allowed and name != "max_faces":
            valid = ", ".join(allowed) or "none"
            raise InvalidArgumentError(
                f"scheme {scheme!r} has no option {name!r}; its options: {valid} (and max_faces)"
            )
    func(mesh, **options)


__all__ = [
    "SCHEMES", "catmull_clark", "checker", "corner_cut", "cubic_pentagonalization", "dome",
    "doo_sabin", "doo_sabin_bc", "doo_sabin_bc_new", "double_stellate", "dual", "dual_1264",
    "dual_checkerboard", "dual_loop", "dual_pentagon_preserving",
    "dual_pentagonalization", "fractal", "honeycomb",
    "linear_vertex", "loop", "loop_style", "modified_corner_cut", "pentagon",
    "pentagon_preserve", "root3", "root4", "scheme_options", "sierpinsky",
    "simplest", "six_preserving_loop_style", "sqrt3", "star", "stellate", "subdivide",
    "subdivide_all_edges", "subdivide_faces", "triangulate", "twelve_six_four", "vertex_cut",
]
