"""The mesh passes' GL side: the programs, and the draw calls of each element.

:func:`compile_programs` compiles the renderer's programs (:data:`PROGRAMS`, with
the variants of a program compiled apart: see :func:`shaders.variant`) and fixes
their texture units. :class:`MeshPasses` draws a range of one uploaded mesh's
faces, edges or points, or of the preview's surface, with them: the uniforms of
each draw and the GL state it needs (polygon offset, back-face culling, the
section's cap of a closed mesh). Which passes a frame holds, and in what order,
is the :class:`~livemod.viewer.renderer.Renderer`'s. Every method must be called
on the thread that owns the GL context.
"""

from __future__ import annotations

from collections.abc import Mapping

import moderngl
import numpy as np

from . import shaders
from .geometry import CREASE_ANGLE
from .section_cap import SectionCap
from .uploads import MeshGPU, SurfaceGPU

RGB = tuple[float, float, float]

BACK_COLOR = (0.45, 0.45, 0.62)
SELECTED_COLOR = (0.35, 0.95, 0.35)
EDGE_COLOR = (0.08, 0.08, 0.09)
POINT_COLOR = (0.95, 0.95, 0.2)

# each program's (vertex, fragment) shader sources
# (the variants of a program are compiled apart: see shaders.variant)
PROGRAMS = {
    "face": (shaders.FACE_VERTEX, shaders.FACE_FRAGMENT),
    "face_wire": (shaders.FACE_VERTEX, shaders.variant(shaders.FACE_FRAGMENT, "WIRE")),
    "face_smooth": (shaders.MESH_VERTEX, shaders.variant(shaders.FACE_FRAGMENT, "SMOOTH")),
    "face_smooth_wire": (shaders.MESH_VERTEX,
                         shaders.variant(shaders.FACE_FRAGMENT, "SMOOTH", "WIRE")),
    "surface": (shaders.MESH_VERTEX, shaders.SURFACE_FRAGMENT),
    "surface_quick": (shaders.MESH_VERTEX, shaders.variant(shaders.SURFACE_FRAGMENT, "QUICK")),
    # a surface whose points carry their faces' colours (see SurfaceGPU.vao)
    "surface_colors": (shaders.variant(shaders.MESH_VERTEX, "COLORS"),
                       shaders.variant(shaders.SURFACE_FRAGMENT, "COLORS")),
    "surface_quick_colors": (shaders.variant(shaders.MESH_VERTEX, "COLORS"),
                             shaders.variant(shaders.SURFACE_FRAGMENT, "QUICK", "COLORS")),
    "edge": (shaders.MESH_VERTEX, shaders.EDGE_FRAGMENT),
    # the edges of a picture with none selected: their colour only
    "edge_plain": (shaders.MESH_VERTEX, shaders.variant(shaders.EDGE_FRAGMENT, "PLAIN")),
    "point": (shaders.MESH_VERTEX, shaders.POINT_FRAGMENT),
    "line": (shaders.MESH_VERTEX, shaders.LINE_FRAGMENT),
    "winding": (shaders.MESH_VERTEX, shaders.WINDING_FRAGMENT),  # the section cap's
    "cap": (shaders.CAP_VERTEX, shaders.CAP_FRAGMENT),
    "text": (shaders.TEXT_VERTEX, shaders.TEXT_FRAGMENT),
}

# the texture unit of each sampler, in every program that has it (the text's atlas
# shares unit 0 with the face pass's triangle -> face table: no program has both)
TEXTURE_UNITS = {"triangle_face": 0, "face_flags": 1, "edge_flags": 2, "vertex_flags": 3,
                 "triangle_index": 4, "position_table": 5, "winding": 6, "face_colors": 7,
                 "atlas": 0}


def compile_programs(ctx: moderngl.Context) -> dict[str, moderngl.Program]:
    """Every program of :data:`PROGRAMS` compiled in ``ctx``, by name, each
    sampler bound to its unit of :data:`TEXTURE_UNITS`.

    Raises:
        moderngl.Error: a shader does not compile or link (a GL below 3.3).
    """
    programs = {name: ctx.program(vertex_shader=vertex, fragment_shader=fragment)
                for name, (vertex, fragment) in PROGRAMS.items()}
    for program in programs.values():
        set_uniforms(program, **TEXTURE_UNITS)
    return programs


def set_uniforms(program: moderngl.Program, **values: object) -> None:
    """Set ``program``'s uniforms by name; a variant compiled without one's use
    (see :func:`shaders.variant`) has none, and skips it."""
    for name, value in values.items():
        if name in program:
            program[name].value = value  # type: ignore[union-attr]


def matrix_bytes(matrix: np.ndarray) -> bytes:
    """A row-major numpy ``(4, 4)`` as the column-major float32 GL expects."""
    return np.ascontiguousarray(matrix.T, dtype=np.float32).tobytes()


class MeshPasses:
    """Draws the elements of uploaded meshes with ``programs`` (see
    :func:`compile_programs`) in ``ctx``; a closed mesh cut by :attr:`section`
    gets its cap from ``cap``.

    Attributes:
        section: ``Style.section`` of the frame drawn (None: no cut).
        quick: the frame drawn is a quick picture (the preview's surface is drawn
            with its quick variant).
    """

    def __init__(self, ctx: moderngl.Context, programs: Mapping[str, moderngl.Program],
                 cap: SectionCap) -> None:
        self.ctx = ctx
        self.programs = programs
        self.cap = cap
        self.section: tuple[int, float] | None = None
        self.quick = False

    def set_view(self, projection_view: np.ndarray, view: np.ndarray) -> None:
        """Give every program the ``(4, 4)`` row-major ``projection_view`` (its
        ``mvp``) and, where it has one, the ``view`` matrix."""
        mvp, view_bytes = matrix_bytes(projection_view), matrix_bytes(view)
        for program in self.programs.values():
            program["mvp"].write(mvp)  # type: ignore[union-attr]
            if "view" in program:
                program["view"].write(view_bytes)  # type: ignore[union-attr]

    def surface(self, surface: SurfaceGPU, color: RGB, current: bool, first: int = 0,
                count: int | None = None, own_colors: bool = False) -> None:
        """Triangles ``first .. first + count`` (all by default) of the preview's part
        of the current object (or of the others), lit by its own normals, capped
        where a section cuts it; in ``color`` (or, with ``own_colors``, in their
        faces' own colours where they have one, muted for the others)."""
        vao = surface.vao(self.quick, own_colors)
        set_uniforms(vao.program, base_color=color, back_color=BACK_COLOR,
                     mute=0.0 if current else shaders.MUTE)
        self.ctx.polygon_offset = (1.0, 1.0)  # the cage's edges, drawn after, win
        if surface.closed:
            self.ctx.enable(moderngl.CULL_FACE)
        start, total = surface.part(current)
        count = total - first if count is None else count
        if count > 0:
            vao.render(moderngl.TRIANGLES, vertices=3 * count, first=3 * (start + first))
        self.ctx.polygon_offset = (0.0, 0.0)
        if surface.closed and self.section is not None:
            self.cap.draw(surface, color, current)
        self.ctx.disable(moderngl.CULL_FACE)

    def faces(self, mesh: MeshGPU, color: RGB, pickable: bool, wire: bool = False,
              smooth: bool = False, crease_angle: float = CREASE_ANGLE, first: int = 0,
              count: int | None = None, own_colors: bool = False) -> None:
        """Triangles ``first .. first + count`` (all by default) of ``mesh``'s faces,
        in ``color`` (or, with ``own_colors``, in their own colours where they have
        one, muted for the other objects), with the wireframe over them (``wire``), shaded smooth across edges
        of less than ``crease_angle`` degrees (``smooth``); ``pickable``: they
        write their face ids into the pick target (else id 0: they only hide)."""
        count = len(mesh.geometry.triangles) - first if count is None else count
        if count <= 0:
            return
        program = self.programs[("face_smooth" if smooth else "face") + ("_wire" if wire else "")]
        use = own_colors and len(mesh.geometry.face_colors) > 0
        set_uniforms(program, primitive_base=first, pickable=int(pickable),
                     mute=0.0 if pickable else shaders.MUTE,
                     viewport=tuple(float(v) for v in self.ctx.viewport[2:]),
                     edge_color=EDGE_COLOR, base_color=color, back_color=BACK_COLOR,
                     selected_color=SELECTED_COLOR, use_face_colors=int(use))
        mesh.triangle_index.use(4)
        mesh.position_table.use(5)
        mesh.triangle_face.use(0)
        mesh.face_flags.use(1)
        mesh.face_colors.use(7)
        # push faces back so edges and points drawn at the same depth win
        self.ctx.polygon_offset = (1.0, 1.0)
        if mesh.geometry.closed:
            # a closed manifold hides its back faces: skip them (about a third of
            # the frame time on software GL); open meshes show them tinted
            self.ctx.enable(moderngl.CULL_FACE)
        (mesh.smooth_vao(crease_angle, wire) if smooth else mesh.face_vaos[wire]).render(
            moderngl.TRIANGLES, vertices=3 * count, first=3 * first)
        self.ctx.polygon_offset = (0.0, 0.0)
        if mesh.geometry.closed and self.section is not None:
            self.cap.draw(mesh, color, True)
        self.ctx.disable(moderngl.CULL_FACE)

    def edges(self, mesh: MeshGPU, selected_only: bool = False, first: int = 0,
              count: int | None = None, picking: bool = False) -> None:
        """Edges ``first .. first + count`` (all by default) of ``mesh``, or its
        selected ones; ``picking``: into the pick target, with their ids."""
        # with no edge selected, a picture's edges need neither flags nor ids
        plain = not selected_only and not picking and mesh.selected_lines is None
        program = self.programs["edge_plain" if plain else "edge"]
        set_uniforms(program, edge_color=EDGE_COLOR, selected_color=SELECTED_COLOR,
                     all_selected=int(selected_only), primitive_base=first)
        mesh.edge_flags.use(2)
        count = len(mesh.geometry.lines) - first if count is None else count
        if selected_only and mesh.selected_lines is not None:
            set_uniforms(program, primitive_base=0)
            mesh.selected_lines[1].render(moderngl.LINES)
        elif count > 0:
            mesh.edge_vaos[plain].render(moderngl.LINES, vertices=2 * count, first=2 * first)

    def points(self, mesh: MeshGPU, size: float, point_spheres: bool = False) -> None:
        """``mesh``'s vertices as ``size`` pixel points, the selected ones in the
        selection's colour (with their ids in the pick target), or only its
        point-spheres (which no face shows)."""
        program = self.programs["point"]
        set_uniforms(program, point_size=size, point_color=POINT_COLOR,
                     selected_color=SELECTED_COLOR, use_flags=1)
        mesh.vertex_flags.use(3)
        if point_spheres:
            # (the index buffer is at least 16 bytes: a count of 1 to 3 is not all of it)
            mesh.sphere_vao.render(moderngl.POINTS, vertices=len(mesh.geometry.point_spheres))
        elif len(mesh.geometry.positions):
            mesh.point_vao.render(moderngl.POINTS)
