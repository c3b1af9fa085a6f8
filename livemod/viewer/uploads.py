"""The GL objects of uploaded meshes and smooth surfaces, made whole or a slice at
a time.

Uploading a million-face mesh writes some 80 MB into buffers and textures; done
in one go it holds the window's thread for a frame or more. Each maker here is a
generator that writes at most :data:`SLICE_BYTES` between its ``yield``\\ s, so
that :class:`Upload` can spread the work over frames, and give it up (freeing
what it made) when a newer mesh supersedes it. Call everything on the thread
that owns the context.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Generator
from typing import TYPE_CHECKING, Generic, TypeVar

import moderngl
import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.patches import Tessellation, mesh_surface

from .geometry import RenderGeometry, crease_shading
from .shaders import TABLE_SHIFT

if TYPE_CHECKING:
    from livemod.runner.preview import Preview

TABLE_WIDTH = 1 << TABLE_SHIFT  # (the shaders' fetch depends on it)
SLICE_BYTES = 4 << 20  # written between two yields of an upload
_NUMPY_DTYPES = {"u1": np.uint8, "u4": np.uint32, "f4": np.float32}

Made = TypeVar("Made")
Steps = Generator[None, None, Made]
GLObject = moderngl.Buffer | moderngl.Texture | moderngl.VertexArray


def buffer_steps(ctx: moderngl.Context, data: np.ndarray,
                 made: list[GLObject]) -> Steps[moderngl.Buffer]:
    """A GL buffer holding ``data``, written a slice at a time (appended to
    ``made`` first, so an abandoned upload frees it). GL buffers cannot be empty:
    an empty array gets a small zeroed one, which the draws never read."""
    raw = np.ascontiguousarray(data).reshape(-1).view(np.uint8)
    buffer = ctx.buffer(reserve=max(len(raw), 16))
    made.append(buffer)
    for start in range(0, len(raw), SLICE_BYTES):
        buffer.write(raw[start:start + SLICE_BYTES], offset=start)
        yield
    return buffer


def table_steps(ctx: moderngl.Context, values: np.ndarray, dtype: str,
                made: list[GLObject]) -> Steps[moderngl.Texture]:
    """``(n,)`` integers (``dtype`` "u1" or "u4", read by ``fetch`` in GLSL) or
    ``(n, 3)`` float32 points ("f4", read with ``texelFetch``) as a 2-D texture
    ``TABLE_WIDTH`` wide, written some rows at a time."""
    components = 1 if values.ndim == 1 else values.shape[1]
    n = max(len(values), 1)
    width = min(n, TABLE_WIDTH)
    height = (n + width - 1) // width
    padded = np.zeros((width * height, components), dtype=_NUMPY_DTYPES[dtype])
    padded[: len(values)] = values.reshape(len(values), components)
    texture = ctx.texture((width, height), components, dtype=dtype)
    texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
    made.append(texture)
    rows = max(SLICE_BYTES // max(padded[:width].nbytes, 1), 1)
    for top in range(0, height, rows):
        count = min(rows, height - top)
        texture.write(padded[top * width:(top + count) * width].tobytes(),
                      viewport=(0, top, width, count))
        yield
    return texture


def _buffer(objects: dict[str, GLObject], name: str) -> moderngl.Buffer:
    made = objects[name]
    assert isinstance(made, moderngl.Buffer)
    return made


def _texture(objects: dict[str, GLObject], name: str) -> moderngl.Texture:
    made = objects[name]
    assert isinstance(made, moderngl.Texture)
    return made


def finished(steps: Steps[Made]) -> Made:
    """Run an upload's steps to the end; its result."""
    while True:
        try:
            next(steps)
        except StopIteration as done:
            return done.value


class MeshGPU:
    """The GL objects of one uploaded mesh; ``release`` frees them. A mesh may have
    no triangles (only point-spheres and 2-gons, as while a script builds one from
    createVertex and insertEdge), no edges or no vertices. Make one with
    :meth:`steps` (a slice at a time) or :meth:`made` (at once)."""

    def __init__(self, ctx: moderngl.Context, programs: dict[str, moderngl.Program],
                 geometry: RenderGeometry, objects: dict[str, GLObject]) -> None:
        self.geometry = geometry
        self.positions, self.triangles, self.lines, self.spheres = (
            _buffer(objects, name) for name in ("positions", "triangles", "lines", "spheres"))
        self.triangle_face, self.triangle_index, self.position_table = (
            _texture(objects, name) for name in ("triangle_face", "triangle_index",
                                                 "position_table"))
        self.face_flags, self.edge_flags, self.vertex_flags, self.face_colors = (
            _texture(objects, name) for name in ("face_flags", "edge_flags", "vertex_flags",
                                                 "face_colors"))
        content = [(self.positions, "3f", "in_position")]
        # by wire (the face pass, which pulls its corners from the tables: no
        # attributes) and by plain (the edges' colour only): see Renderer
        self.face_vaos = {wire: ctx.vertex_array(programs["face_wire" if wire else "face"], [])
                          for wire in (False, True)}
        self.winding_vao = ctx.vertex_array(programs["winding"], content, self.triangles, 4)
        self.edge_vaos = {plain: ctx.vertex_array(programs["edge_plain" if plain else "edge"],
                                                  content, self.lines, 4)
                          for plain in (False, True)}
        self.point_vao = ctx.vertex_array(programs["point"], content)
        self.sphere_vao = ctx.vertex_array(programs["point"], content, self.spheres, 4)
        self.ctx, self.edge_program = ctx, programs["edge"]
        self.smooth_programs = {False: programs["face_smooth"],
                                True: programs["face_smooth_wire"]}
        self.selected_lines: tuple[moderngl.Buffer, moderngl.VertexArray] | None = None
        # the smooth face pass: (crease angle, its buffers, its vertex arrays by wire)
        self.smooth: tuple[float, list[moderngl.Buffer],
                           dict[bool, moderngl.VertexArray]] | None = None

    @classmethod
    def steps(cls, ctx: moderngl.Context, programs: dict[str, moderngl.Program],
              geometry: RenderGeometry, made: list[GLObject]) -> Steps[MeshGPU]:
        """Upload ``geometry`` a slice at a time (what is made goes to ``made``)."""
        g = geometry
        objects: dict[str, GLObject] = {}
        for name, data in (("positions", g.positions), ("triangles", g.triangles),
                           ("lines", g.lines), ("spheres", g.point_spheres)):
            objects[name] = yield from buffer_steps(ctx, data, made)
        for name, values, dtype in (
                ("triangle_face", g.triangle_table, "u4"),
                ("triangle_index", g.triangles.reshape(-1), "u4"),
                ("position_table", g.positions, "f4"),
                ("face_flags", np.zeros(g.face_count, np.uint8), "u1"),
                ("edge_flags", np.zeros(len(g.lines), np.uint8), "u1"),
                ("vertex_flags", np.zeros(len(g.positions), np.uint8), "u1"),
                ("face_colors", g.face_colors, "u4")):
            objects[name] = yield from table_steps(ctx, values, dtype, made)
        return cls(ctx, programs, geometry, objects)

    @classmethod
    def made(cls, ctx: moderngl.Context, programs: dict[str, moderngl.Program],
             geometry: RenderGeometry) -> MeshGPU:
        """Upload ``geometry`` at once."""
        return finished(cls.steps(ctx, programs, geometry, []))

    def smooth_vao(self, crease_angle: float, wire: bool = False) -> moderngl.VertexArray:
        """The face pass (with the ``wire`` or not) with smooth normals creased at
        ``crease_angle`` degrees (:func:`~.geometry.crease_shading`), made on first
        use and kept for that angle; the geometry's own when it came prepared
        with it."""
        if self.smooth is not None and self.smooth[0] == crease_angle:
            return self.smooth[2][wire]
        self._release_smooth()
        shading = self.geometry.smooth
        if shading is None or self.geometry.crease_angle != crease_angle:
            assert self.geometry.arrays is not None  # (build_geometry keeps them)
            shading = crease_shading(self.geometry.arrays, crease_angle)
        made: list[GLObject] = []
        buffers = [finished(buffer_steps(self.ctx, data, made))
                   for data in (shading.positions, shading.normals, shading.triangles)]
        vaos = {key: self.ctx.vertex_array(
            program, [(buffers[0], "3f", "in_position"), (buffers[1], "3f", "in_normal")],
            buffers[2], 4) for key, program in self.smooth_programs.items()}
        self.smooth = (crease_angle, buffers, vaos)
        return vaos[wire]

    def set_flags(self, face: np.ndarray, edge: np.ndarray, vertex: np.ndarray) -> None:
        """Replace the selection flags; each ``(n,)`` uint8 in dense order."""
        for texture, flags in ((self.face_flags, face), (self.edge_flags, edge),
                               (self.vertex_flags, vertex)):
            padded = np.zeros(texture.width * texture.height, dtype=np.uint8)
            padded[: len(flags)] = flags
            texture.write(padded.tobytes())
        self._release_selected_lines()
        picked = self.geometry.lines[np.flatnonzero(edge)]
        if len(picked):
            buffer = self.ctx.buffer(np.ascontiguousarray(picked).tobytes())
            vao = self.ctx.vertex_array(self.edge_program, [(self.positions, "3f", "in_position")],
                                        buffer, 4)
            self.selected_lines = (buffer, vao)

    def _release_selected_lines(self) -> None:
        if self.selected_lines is not None:
            self.selected_lines[1].release()
            self.selected_lines[0].release()
            self.selected_lines = None

    def _release_smooth(self) -> None:
        if self.smooth is not None:
            for vao in self.smooth[2].values():
                vao.release()
            for buffer in self.smooth[1]:
                buffer.release()
            self.smooth = None

    def release(self) -> None:
        """Free every GL object of this mesh."""
        self._release_selected_lines()
        self._release_smooth()
        objects: list[GLObject] = [*self.face_vaos.values(), *self.edge_vaos.values()]
        objects += [self.winding_vao, self.point_vao, self.sphere_vao, self.spheres,
                    self.positions, self.triangles, self.lines, self.triangle_face,
                    self.face_flags, self.edge_flags, self.vertex_flags, self.triangle_index,
                    self.position_table, self.face_colors]
        for obj in objects:
            obj.release()


class SurfaceGPU:
    """The GL objects of an uploaded smooth surface (the preview): positions,
    normals and triangles (and the colours of its points, when its faces have
    some), drawn in ``parts`` (triangle counts: the current object's first, then
    the other objects'); ``release`` frees them.

    Attributes:
        closed: its back faces are never seen (all its objects closed, and whole).
        colored: its points carry their faces' colours (see :meth:`vao`).
    """

    def __init__(self, ctx: moderngl.Context, programs: dict[str, moderngl.Program],
                 objects: dict[str, GLObject], count: int, parts: tuple[int, ...],
                 closed: bool) -> None:
        self.positions, self.normals, self.triangles = (
            _buffer(objects, name) for name in ("positions", "normals", "triangles"))
        self.colors = _buffer(objects, "colors") if "colors" in objects else None
        self.count, self.parts, self.closed = count, parts, closed
        self.colored = self.colors is not None
        lit = [(self.positions, "3f", "in_position"), (self.normals, "3f", "in_normal")]
        # by (quick, in the faces' colours): see Renderer.draw
        self.vaos = {(quick, False): ctx.vertex_array(
            programs["surface_quick" if quick else "surface"], lit, self.triangles, 4)
            for quick in (False, True)}
        if self.colors is not None:
            for quick in (False, True):
                self.vaos[quick, True] = ctx.vertex_array(
                    programs["surface_quick_colors" if quick else "surface_colors"],
                    [*lit, (self.colors, "4f1", "in_color")], self.triangles, 4)
        self.winding_vao = ctx.vertex_array(programs["winding"], [
            (self.positions, "3f", "in_position")], self.triangles, 4)

    @classmethod
    def steps(cls, ctx: moderngl.Context, programs: dict[str, moderngl.Program],
              preview: Preview | MeshArrays, made: list[GLObject]) -> Steps[SurfaceGPU]:
        """Upload a preview (see :func:`preview_surface`) a slice at a time."""
        surface, parts, closed = preview_surface(preview)
        objects: dict[str, GLObject] = {}
        for name in ("positions", "normals", "triangles", "colors"):
            data = getattr(surface, name)
            if data is not None:
                objects[name] = yield from buffer_steps(ctx, data, made)
        return cls(ctx, programs, objects, len(surface.triangles), parts, closed)

    def vao(self, quick: bool, colors: bool) -> moderngl.VertexArray:
        """The vertex array (and through it, the program) that draws the surface
        for a quick picture or not, in its faces' colours (when it has them and
        ``colors``) or in one colour."""
        return self.vaos[quick, colors and self.colored]

    def part(self, current: bool) -> tuple[int, int]:
        """``(first triangle, triangles)`` of the current object's part, or of the
        other objects' parts (joined)."""
        first = self.parts[0] if self.parts else 0
        return (0, first) if current else (first, self.count - first)

    def release(self) -> None:
        objects: list[GLObject] = [*self.vaos.values(), self.winding_vao, self.positions,
                                   self.normals, self.triangles]
        if self.colors is not None:
            objects.append(self.colors)
        for obj in objects:
            obj.release()


def preview_surface(preview: Preview | MeshArrays) -> tuple[Tessellation, tuple[int, ...],
                                                             bool]:
    """``(surface, parts, closed)`` of a preview, or of a subdivided mesh's arrays
    (drawn with its own smooth normals, as one part)."""
    if isinstance(preview, MeshArrays):
        surface = mesh_surface(preview)
        return surface, (len(surface.triangles),), not bool(preview.face_hole.any())
    return preview.surface, preview.parts, preview.closed


class Upload(Generic[Made]):
    """Steps of an upload run a few at a time, within a time budget per call.

    Args:
        start: makes the steps, appending each GL object it makes to the list it
            is given (so that :meth:`abandon` can free them).
        done: receives the result once the last step ran.
    """

    def __init__(self, start: Callable[[list[GLObject]], Steps[Made]],
                 done: Callable[[Made], None]) -> None:
        self._made: list[GLObject] = []
        self._steps = start(self._made)
        self._done = done
        self.finished = False
        self.steps_run = 0

    def advance(self, seconds: float) -> bool:
        """Run steps for about ``seconds`` (at least one); True once finished."""
        deadline = time.perf_counter() + seconds
        while not self.finished:
            try:
                next(self._steps)
                self.steps_run += 1
            except StopIteration as last:
                self.finished = True
                self._made.clear()
                self._done(last.value)
                break
            if time.perf_counter() >= deadline:
                break
        return self.finished

    def abandon(self) -> None:
        """Give the upload up: free what it made (nothing, once finished)."""
        if self.finished:
            return
        self._steps.close()
        for obj in self._made:
            obj.release()
        self._made.clear()
        self.finished = True
