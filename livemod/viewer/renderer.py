"""The renderer shared by the live window and headless rendering.

:class:`Renderer` owns the GL programs and the uploaded mesh; it draws into any
framebuffer (the window's, or an offscreen one) and answers picks through an
integer id framebuffer. Every method must be called on the thread that owns ``ctx``.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import moderngl
import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.scene import Selection

from . import shaders
from .camera import Camera
from .geometry import (
    CREASE_ANGLE,
    PreparedMeshes,
    build_geometry,
    corner_points,
    decode_pick,
    dense_flags,
    label_anchors,
    visible_labels,
)
from .text import QUAD_FLOATS, glyph_atlas, layout_labels
from .uploads import GLObject, MeshGPU, Steps, SurfaceGPU, Upload

if TYPE_CHECKING:
    from livemod.runner.preview import Preview

UPLOAD_SECONDS = 0.02  # of a frame an upload in progress takes by default
CACHED_PRIMITIVES = 100_000  # a bigger scene is kept whole between frames (see draw)
GL_CLIP_DISTANCE0 = 0x3000  # moderngl has no name for it: enable_direct takes the GL enum
NO_CUT = (0.0, 0.0, 0.0, 1.0)  # a clip plane every point is in front of
MAX_LABELS = 2000  # id labels on screen at once, of each kind: the nearest the eye
LABEL_KINDS = ("faces", "edges", "vertices")

PALETTE = np.array([
    (0.93, 0.93, 0.93, 1.0),   # 0 HUD text
    (1.00, 0.86, 0.45, 1.0),   # 1 face label text
    (0.55, 0.90, 1.00, 1.0),   # 2 edge label text
    (1.00, 0.62, 0.85, 1.0),   # 3 vertex label text
    (1.00, 0.45, 0.40, 1.0),   # 4 error text
    (0.62, 0.64, 0.68, 1.0),   # 5 dim text
    (0.55, 0.95, 0.55, 1.0),   # 6 ok text
    (1.00, 0.80, 0.30, 1.0),   # 7 warning text
    (0.05, 0.05, 0.07, 0.72),  # 8 HUD panel
    (0.20, 0.14, 0.02, 0.78),  # 9 face label box
    (0.02, 0.14, 0.20, 0.78),  # 10 edge label box
    (0.20, 0.03, 0.14, 0.78),  # 11 vertex label box
    (0.30, 0.03, 0.03, 0.85),  # 12 error panel
    (0.22, 0.23, 0.28, 0.95),  # 13 parameter slider track / off checkbox
    (0.30, 0.48, 0.80, 0.95),  # 14 parameter slider fill / on checkbox
    (0.32, 0.32, 0.38, 0.95),  # 15 parameter reset button
], dtype=np.float32)

BASE_COLOR = (1.0, 0.59, 0.36)      # TopMod's render colour (255, 151, 92)
PREVIEW_COLOR = (0.62, 0.78, 0.95)
OTHER_COLOR = (0.86, 0.70, 0.60)     # the scene's other objects: the base colour, muted
BACK_COLOR = (0.45, 0.45, 0.62)
SELECTED_COLOR = (0.35, 0.95, 0.35)
EDGE_COLOR = (0.08, 0.08, 0.09)
POINT_COLOR = (0.95, 0.95, 0.2)
CORNER_COLOR = (0.1, 1.0, 1.0)


DARK_BACKGROUND = (0.16, 0.17, 0.19, 1.0)
LIGHT_BACKGROUND = (0.93, 0.93, 0.92, 1.0)   # for pictures on a white page
TRANSPARENT_BACKGROUND = (*DARK_BACKGROUND[:3], 0.0)  # offscreen images with alpha
BACKGROUNDS = {"dark": DARK_BACKGROUND, "light": LIGHT_BACKGROUND,
               "transparent": TRANSPARENT_BACKGROUND}  # ``livemod render --background``


@dataclass(frozen=True)
class Style:
    """What to draw.

    Attributes:
        faces, edges, vertices: show these elements.
        preview: draw the smoothed preview instead of the faces (when present),
            with the normals it has.
        labels: which id labels to draw, a subset of ``LABEL_KINDS``.
        labels_selected_only: label only the selected elements.
        point_size: vertex point size in pixels.
        background: RGBA clear colour.
        others: draw the scene's other objects (see :meth:`Renderer.set_mesh`).
        current: draw the current object (hidden, it is neither labelled nor picked).
        smooth: shade faces with interpolated normals instead of flat, smooth
            across edges between faces less than ``crease_angle`` degrees apart
            and sharp across the others.
        grid: draw a ground grid under the scene and the x, y, z axes (red,
            green, blue) from the origin.
        section: ``(axis, at)``: cut away every part of the meshes whose
            coordinate ``axis`` (0, 1, 2 for x, y, z) is greater than ``at``, and
            show the inside through the cut; None draws them whole.
    """

    faces: bool = True
    edges: bool = True
    vertices: bool = False
    preview: bool = False
    labels: frozenset[str] = field(default_factory=frozenset)
    labels_selected_only: bool = False
    point_size: float = 6.0
    background: tuple[float, float, float, float] = DARK_BACKGROUND
    others: bool = True
    current: bool = True
    grid: bool = False
    smooth: bool = False
    crease_angle: float = CREASE_ANGLE
    section: tuple[int, float] | None = None


@dataclass(frozen=True)
class Pick:
    """A picked element: ``kind`` is "face", "edge", "vertex" or "corner"."""

    kind: str
    dense_index: int
    element_id: int


class _StreamBuffer:
    """A dynamic vertex buffer that a draw refills each time it is called, and the
    vertex array reading it (the HUD's text is drawn every frame: making and
    freeing a buffer and a vertex array for each draw cost two GL objects a frame).

    The buffer only grows (to a power of two of rows), in place: ``orphan`` with a
    new size keeps the GL buffer name, so the vertex array made once stays valid.
    Each refill orphans the old storage first, so a draw still reading it does
    not hold up the write. Draws pass their own vertex or instance count: the
    buffer holds more rows than are drawn.
    """

    def __init__(self, ctx: moderngl.Context,
                 make_vao: Callable[[moderngl.Buffer], moderngl.VertexArray]) -> None:
        self.ctx = ctx
        self._make_vao = make_vao
        self.buffer: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        self._held: np.ndarray | None = None  # the array last written, to skip a rewrite

    def load(self, rows: np.ndarray) -> moderngl.VertexArray:
        """The vertex array, its buffer now holding ``rows`` (``(n, k)`` float32,
        n >= 1). The same array object as last time (a cached HUD or label layout)
        is not written again."""
        if rows is self._held and self.vao is not None:
            return self.vao
        data = np.ascontiguousarray(rows, dtype=np.float32)
        row_bytes = data.nbytes // max(len(data), 1)
        if self.buffer is None:
            self.buffer = self.ctx.buffer(reserve=_capacity(len(data)) * row_bytes,
                                          dynamic=True)
            self.vao = self._make_vao(self.buffer)
        elif self.buffer.size < data.nbytes:
            self.buffer.orphan(_capacity(len(data)) * row_bytes)
        else:
            self.buffer.orphan()
        self.buffer.write(data)
        self._held = rows
        assert self.vao is not None
        return self.vao

    def release(self) -> None:
        """Free the vertex array and the buffer (a later :meth:`load` makes new ones)."""
        if self.vao is not None:
            self.vao.release()
        if self.buffer is not None:
            self.buffer.release()
        self.buffer = self.vao = self._held = None


def _capacity(rows: int) -> int:
    """Rows to reserve for ``rows``: the next power of two, at least 64."""
    return max(64, 1 << max(rows - 1, 0).bit_length())


GRID_COLOR = (0.30, 0.31, 0.34)
AXIS_COLORS = ((0.85, 0.25, 0.25), (0.30, 0.75, 0.30), (0.30, 0.45, 0.90))


def guide_lines(bounds: np.ndarray) -> list[tuple[np.ndarray, tuple[float, float, float]]]:
    """The ground grid and the three axes for a scene of ``(2, 3)`` ``bounds``.

    The grid lies in the plane y = bounds' bottom, centred under the scene, its
    spacing a power of ten, or twice or five times one, that gives 10 to 25 cells
    across the scene's larger horizontal size; the axes run from the origin, as long as
    the scene is large.

    Returns:
        ``(lines, rgb)`` pairs: ``(2 * L, 3)`` float64 segment ends and their colour.
    """
    size = float(max(np.ptp(bounds[:, [0, 2]], axis=0).max(), 1e-6))
    step = 10.0 ** np.floor(np.log10(size / 10.0))
    step *= 5.0 if size / step > 50 else 2.0 if size / step > 20 else 1.0
    centre = np.round(bounds.mean(axis=0) / step) * step
    half = np.ceil(0.75 * size / step) * step
    ticks = np.arange(-half, half + step / 2, step)
    y = float(bounds[0, 1])
    along_x = [[(centre[0] - half, y, centre[2] + t), (centre[0] + half, y, centre[2] + t)]
               for t in ticks]
    along_z = [[(centre[0] + t, y, centre[2] - half), (centre[0] + t, y, centre[2] + half)]
               for t in ticks]
    grid = np.array(along_x + along_z, dtype=np.float64).reshape(-1, 3)
    length = max(size, float(np.ptp(bounds[:, 1])))
    axes = [(np.array([(0.0, 0.0, 0.0), tuple(length * np.eye(3)[k])]), AXIS_COLORS[k])
            for k in range(3)]
    return [(grid, GRID_COLOR), *axes]


def hatch_spacing(pixel_size: float, facing: float, pixels: float = 8.0) -> float:
    """World distance between the section cap's hatch lines.

    Args:
        pixel_size: world size of a pixel at the camera's target.
        facing: |cosine| between the line of sight and the plane's normal; a plane
            seen aslant squeezes the lines together, so they are spread by 1/facing
            (by at most 4x).
        pixels: the wanted gap in pixels on a plane seen face on.

    Returns:
        a power of two near ``pixels * pixel_size / facing``, so that the lines stay
        put while the view turns or zooms a little (they halve or double in number
        at a step).
    """
    wanted = pixels * pixel_size / max(facing, 0.25)
    return float(2.0 ** np.round(np.log2(wanted)))


def release_framebuffer(fbo: moderngl.Framebuffer) -> None:
    """Free ``fbo`` and the textures and renderbuffers attached to it."""
    for attachment in (*fbo.color_attachments, fbo.depth_attachment):
        if attachment is not None:
            attachment.release()
    fbo.release()


def read_image(fbo: moderngl.Framebuffer, style: Style) -> np.ndarray:
    """The colour of ``fbo`` drawn with ``style``: ``(H, W, 3)`` uint8 RGB, row 0
    at the top, or ``(H, W, 4)`` RGBA when ``style.background`` is not opaque (a
    transparent background: alpha 0 where nothing is drawn)."""
    channels = 3 if style.background[3] >= 1.0 else 4
    width, height = fbo.size
    raw = fbo.read(components=channels, alignment=1)
    return np.frombuffer(raw, dtype=np.uint8).reshape(height, width, channels)[::-1].copy()


def _matrix_bytes(matrix: np.ndarray) -> bytes:
    """A row-major numpy ``(4, 4)`` as the column-major float32 GL expects."""
    return np.ascontiguousarray(matrix.T, dtype=np.float32).tobytes()


# each program's (vertex, fragment) shader sources
PROGRAMS = {
    "face": (shaders.MESH_VERTEX, shaders.FACE_FRAGMENT),
    "surface": (shaders.MESH_VERTEX, shaders.SURFACE_FRAGMENT),
    "edge": (shaders.MESH_VERTEX, shaders.EDGE_FRAGMENT),
    "point": (shaders.MESH_VERTEX, shaders.POINT_FRAGMENT),
    "line": (shaders.MESH_VERTEX, shaders.LINE_FRAGMENT),
    "winding": (shaders.MESH_VERTEX, shaders.WINDING_FRAGMENT),  # the section cap's
    "cap": (shaders.CAP_VERTEX, shaders.CAP_FRAGMENT),
    "text": (shaders.TEXT_VERTEX, shaders.TEXT_FRAGMENT),
}


# a pass of a frame: (primitives, draw(first, count))
_Pass = tuple[int, Callable[[int, int], None]]


@dataclass
class _Progress:
    """A picture drawn a slice at a time: for ``key`` (content version and view),
    into ``target``, ``done`` primitives so far."""

    key: tuple
    target: moderngl.Framebuffer
    done: int = 0


class Renderer:
    """Draws meshes, selections, labels and screen text with one set of programs."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.programs = {name: ctx.program(vertex_shader=vertex, fragment_shader=fragment)
                         for name, (vertex, fragment) in PROGRAMS.items()}
        # counts changes of what is drawn (meshes, selection): a frame drawn at the same
        # version, camera and style is the same picture
        self.version = 0
        self._bind_samplers()
        self._set_clip_plane(NO_CUT)
        self.atlas = glyph_atlas()
        height, width = self.atlas.image.shape
        self.atlas_texture = ctx.texture((width, height), 1, self.atlas.image.tobytes())
        self.atlas_texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        corners = np.array([0, 0, 1, 0, 0, 1, 1, 1], dtype=np.float32)
        self.quad = ctx.buffer(corners.tobytes())
        self.arrays: MeshArrays | None = None
        self.preview: Preview | MeshArrays | None = None
        self.others: MeshArrays | None = None
        self.selection = Selection()
        self._mesh: MeshGPU | None = None
        self._others: MeshGPU | None = None
        self._others_shown = True
        self._current_shown = True
        self._section: tuple[int, float] | None = None  # the last frame's, for picking
        self._preview: SurfaceGPU | None = None
        self._label_cache: tuple[object, np.ndarray] | None = None
        self._label_candidates_cache: dict[str, tuple[object, tuple]] = {}
        self._anchors: dict[str, np.ndarray] = {}  # the current mesh's label anchors
        self._uploads: dict[str, Upload] = {}  # "mesh", "preview": uploads in progress
        # the picture drawn in slices, its target, and (version, view) of the last whole one
        self._progress: _Progress | None = None
        self._slices: moderngl.Framebuffer | None = None
        self._drawn: tuple[int, object] = (-1, None)
        self._cached: tuple | None = None  # the key of the whole picture kept in _slices
        self._pick_fbo: moderngl.Framebuffer | None = None
        self._winding: tuple[moderngl.Framebuffer, moderngl.Texture] | None = None
        self._cap_vao = ctx.vertex_array(self.programs["cap"], [])
        # the guide lines' GL objects and the bounds they were made for
        self._guides: tuple[bytes, list[tuple[moderngl.VertexArray, moderngl.Buffer,
                                              tuple]]] | None = None
        # the buffers the per-frame draws refill: screen text (True) and id labels
        # (False); selected vertices and selected corners
        self._text_streams = {screen: _StreamBuffer(ctx, self._text_vao)
                              for screen in (True, False)}
        self._point_streams = {kind: _StreamBuffer(ctx, self._point_vao)
                               for kind in ("vertices", "corners")}
        self._released = False

    def _text_vao(self, instances: moderngl.Buffer) -> moderngl.VertexArray:
        """The text program's vertex array: the quad's corners, and one quad per
        ``QUAD_FLOATS`` row of ``instances``."""
        return self.ctx.vertex_array(self.programs["text"], [
            (self.quad, "2f", "in_corner"),
            (instances, "3f 2f 2f 4f 1f 1f/i", "in_anchor", "in_offset", "in_size", "in_uv",
             "in_kind", "in_selected"),
        ])

    def _point_vao(self, points: moderngl.Buffer) -> moderngl.VertexArray:
        """The point program's vertex array over ``(k, 3)`` float32 ``points``."""
        return self.ctx.vertex_array(self.programs["point"], [(points, "3f", "in_position")])

    def _bind_samplers(self) -> None:
        """Fix each program's texture units: 0 atlas/triangle_face, 1..3 flags."""
        units = {"triangle_face": 0, "face_flags": 1, "edge_flags": 2, "vertex_flags": 3,
                 "triangle_index": 4, "position_table": 5, "winding": 6, "atlas": 0}
        for program in self.programs.values():
            for name, unit in units.items():
                if name in program:
                    program[name].value = unit  # type: ignore[union-attr]
        self.programs["text"]["palette"].write(PALETTE.tobytes())  # type: ignore[union-attr]
        self.programs["text"]["highlight"].value = (0.15, 0.55, 0.15, 0.9)  # type: ignore[union-attr]

    # -- content ---------------------------------------------------------------

    def set_mesh(self, arrays: MeshArrays | None,
                 preview: Preview | MeshArrays | None = None,
                 others: MeshArrays | None = None) -> None:
        """Upload ``arrays`` (and its smoothed ``preview``) in one step, replacing the old.

        ``others``: the scene's other objects, drawn beside it in a muted colour;
        they hide what is behind them but are never picked or labelled.
        """
        self.stage(arrays, preview, others)
        self.advance(math.inf)

    def stage(self, arrays: MeshArrays | None, preview: Preview | MeshArrays | None = None,
              others: MeshArrays | None = None, prepared: PreparedMeshes | None = None,
              keep_preview: bool = False) -> None:
        """Start uploading ``arrays``, its ``preview`` and the ``others`` (see
        :meth:`set_mesh`); what is drawn changes once :meth:`advance` has uploaded
        them all, so each frame can give the upload a slice of its time. Their
        render buffers come ``prepared`` off the thread (for these same arrays),
        or are built here. With ``keep_preview`` the preview drawn stays (until
        :meth:`stage_preview` gives the new content's). An upload in progress is
        given up: the newer content supersedes it. When the upload fails, what
        was drawn stays."""
        if keep_preview:
            self._abandon_mesh()
        else:
            self._abandon(mesh=True)
        if prepared is None or prepared.arrays is not arrays or prepared.others is not others:
            prepared = PreparedMeshes(
                arrays, others, None if arrays is None else build_geometry(arrays),
                None if others is None else build_geometry(others))
        ctx, programs = self.ctx, self.programs

        def start(made: list[GLObject]) -> Steps[tuple]:
            mesh = other = surface = None
            if prepared.mesh is not None:
                mesh = yield from MeshGPU.steps(ctx, programs, prepared.mesh, made)
            if prepared.other is not None:
                other = yield from MeshGPU.steps(ctx, programs, prepared.other, made)
            if preview is not None and not keep_preview:
                surface = yield from SurfaceGPU.steps(ctx, programs, preview, made)
            return mesh, other, surface

        def done(made: tuple) -> None:
            replaced = (self._mesh, self._others) + (() if keep_preview else (self._preview,))
            for old in replaced:
                if old is not None:
                    old.release()
            self._mesh, self._others = made[:2]
            self.arrays, self.others = arrays, others
            if not keep_preview:
                self._preview, self.preview = made[2], preview
            self._anchors = dict(prepared.anchors)
            self._label_candidates_cache = {}
            self.version += 1
            self.set_selection(self.selection)

        self._uploads["mesh"] = Upload(start, done)

    def stage_preview(self, preview: Preview | MeshArrays | None) -> None:
        """Start uploading (or drop, with None) the smoothed preview alone, as
        :meth:`stage` does; it supersedes a preview upload in progress."""
        self._abandon(mesh=False)
        ctx, programs = self.ctx, self.programs

        def start(made: list[GLObject]) -> Steps[SurfaceGPU | None]:
            if preview is None:
                return None
            return (yield from SurfaceGPU.steps(ctx, programs, preview, made))

        def done(surface: SurfaceGPU | None) -> None:
            if self._preview is not None:
                self._preview.release()
            self._preview, self.preview = surface, preview
            self.version += 1

        self._uploads["preview"] = Upload(start, done)

    def set_preview(self, preview: Preview | MeshArrays | None) -> None:
        """Upload (or drop, with None) the smoothed preview now: a
        :class:`~livemod.runner.preview.Preview` (of the current object first, then
        maybe the other objects), or the arrays of a subdivided mesh (drawn with
        smooth vertex normals). When it holds parts for the other objects, the
        preview draws them too in place of their faces."""
        self.stage_preview(preview)
        self.advance(math.inf)

    def advance(self, seconds: float = UPLOAD_SECONDS) -> bool:
        """Give the uploads in progress about ``seconds`` (at least one step each;
        the mesh's first); True when none is left. An upload that fails is given
        up (what it made is freed) and its error raised; what was drawn stays."""
        for name in ("mesh", "preview"):
            upload = self._uploads.get(name)
            if upload is None:
                continue
            try:
                upload.advance(seconds)
            except BaseException:
                upload.abandon()
                del self._uploads[name]
                raise
            if upload.finished:
                del self._uploads[name]
        return not self._uploads

    @property
    def uploading(self) -> bool:
        """An upload is in progress (:meth:`advance` has work to do)."""
        return bool(self._uploads)

    def _abandon(self, mesh: bool) -> None:
        """Give up the preview's upload in progress (and with ``mesh``, the mesh's)."""
        for name in (("mesh", "preview") if mesh else ("preview",)):
            upload = self._uploads.pop(name, None)
            if upload is not None:
                upload.abandon()

    def _abandon_mesh(self) -> None:
        """Give up the mesh's upload in progress (the preview's goes on)."""
        upload = self._uploads.pop("mesh", None)
        if upload is not None:
            upload.abandon()

    @property
    def unfinished(self) -> bool:
        """A picture drawn in slices is not whole yet: draw again (see :meth:`draw`)."""
        return self._progress is not None

    def set_others(self, others: MeshArrays | None) -> None:
        """Upload (or drop, with None) the other objects alone, keeping the mesh."""
        new = None if others is None else MeshGPU.made(self.ctx, self.programs,
                                                        build_geometry(others))
        if self._others is not None:
            self._others.release()
        self._others, self.others = new, others
        self.version += 1

    def set_selection(self, selection: Selection) -> None:
        """Highlight ``selection`` (ids; ids missing from the mesh are ignored)."""
        self.selection = selection
        self._label_cache = None
        self.version += 1
        arrays = self.arrays
        if arrays is None or self._mesh is None:
            return
        self._mesh.set_flags(dense_flags(arrays.face_ids, selection.faces),
                             dense_flags(arrays.edge_ids, selection.edges),
                             dense_flags(arrays.vertex_ids, selection.vertices))

    def _placed(self) -> list[MeshGPU]:
        """The mesh and the other objects uploaded that have a finite position."""
        return [m for m in (self._mesh, self._others)
                if m is not None and len(m.geometry.positions) > m.geometry.nonfinite]

    @property
    def nonfinite(self) -> int:
        """How many vertices of the mesh and the other objects have a position
        that is not finite (NaN or inf): they are left out of :attr:`bounds`."""
        return sum(m.geometry.nonfinite for m in (self._mesh, self._others) if m is not None)

    @property
    def bounds(self) -> np.ndarray | None:
        """``(2, 3)`` bounds of the finite positions of everything drawn (the mesh
        and the other objects), or None when there are none."""
        drawn = [m.geometry.bounds for m in self._placed()]
        if not drawn:
            return None
        return np.stack([np.min([b[0] for b in drawn], axis=0),
                         np.max([b[1] for b in drawn], axis=0)])

    def drawn_positions(self) -> np.ndarray:
        """``(n, 3)`` positions of the mesh and the other objects (for framing)."""
        parts = [a.positions for a in (self.arrays, self.others) if a is not None]
        return np.concatenate(parts) if parts else np.zeros((0, 3))

    # -- drawing ---------------------------------------------------------------

    def draw(self, fbo: moderngl.Framebuffer, camera: Camera, style: Style,
             size: tuple[int, int] | None = None, budget: int | None = None) -> bool:
        """Clear ``fbo`` and draw the scene seen by ``camera`` in ``style``, over
        ``size`` pixels (default ``fbo.size``; a window's screen framebuffer keeps its
        first size after a resize, so the window says the size).

        With a ``budget`` (primitives a call may draw), new content seen from an
        unchanged view is drawn over several calls when it holds more than that:
        each call draws the next slice into a target of the renderer's own and
        copies it to ``fbo`` (the content appears a slice at a time, and no call
        holds the thread for a whole big frame). Returns False while such a picture
        is unfinished (call again with the same view), True once it is whole. A
        changed view or style draws everything at once: a turning view would
        never finish. With a budget too, a scene of more than ``CACHED_PRIMITIVES``
        seen again from the view of the last picture is kept whole in that target:
        drawn again unchanged (only the window's HUD changed, say), it is copied
        instead of drawn."""
        width, height = size or fbo.size
        self.ctx.viewport = (0, 0, width, height)
        if self._mesh is None and self._others is None:
            fbo.use()
            fbo.clear(*style.background)
            return True
        self._others_shown = style.others  # picking hides what the frame hid
        self._current_shown = style.current
        self._section = style.section  # (before the view: the cap's hatch depends on it)
        self._set_view(camera, (width, height))
        # the camera's pose, not its matrices: its clip planes follow the content's reach
        view_key = (camera.pose(), style, (width, height))
        key = (self.version, view_key)
        passes = self._passes(style)
        # kept whole for the next frames once the view rests (a turning view would
        # only pay for the copy)
        kept = (budget is not None and tuple(fbo.size) == (width, height)
                and self._drawn[1] == view_key
                and sum(count for count, _ in passes) > CACHED_PRIMITIVES)
        if kept and self._cached == key and self._slices is not None \
                and self._slices.samples == fbo.samples:
            self.ctx.copy_framebuffer(fbo, self._slices)
            fbo.use()
            return True
        progress = self._progress_of(fbo, (width, height), view_key, passes, budget, style)
        if progress is not None:
            self._cached = None  # (the target is drawn over)
            finished = self._draw_slice(fbo, camera, style, passes, progress, budget or 0)
            self._cached = key if finished else None
            return finished
        target = self._slice_target((width, height), fbo.samples) if kept else fbo
        self._draw_whole(target, camera, style, passes, (width, height))
        self._drawn, self._cached = key, key if kept else self._cached
        if kept:
            self.ctx.copy_framebuffer(fbo, target)
            fbo.use()
        return True

    def _draw_whole(self, fbo: moderngl.Framebuffer, camera: Camera, style: Style,
                    passes: list[_Pass], size: tuple[int, int]) -> None:
        fbo.use()
        fbo.clear(*style.background)
        self._begin_scene(style)
        with self._cut(style.section):
            for count, draw in passes:
                draw(0, count)
        if self._mesh is not None and style.current and style.labels:
            self._draw_labels(camera, style, size)

    def _begin_scene(self, style: Style) -> None:
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.PROGRAM_POINT_SIZE)
        self.ctx.disable(moderngl.CULL_FACE | moderngl.BLEND)
        if style.grid:
            self._draw_guides()

    def _progress_of(self, fbo: moderngl.Framebuffer, size: tuple[int, int], view_key: tuple,
                     passes: list[_Pass], budget: int | None,
                     style: Style) -> _Progress | None:
        """The picture to go on drawing a slice at a time, or None to draw it whole:
        new content, the view of the last picture, more than ``budget`` to draw,
        no section (its cap needs the whole mesh at once) and a ``fbo`` of ``size``."""
        key = (self.version, view_key)
        if self._progress is not None and self._progress.key == key:
            return self._progress
        self._progress = None
        if (budget is None or style.section is not None or tuple(fbo.size) != size
                or self._drawn[0] == self.version or self._drawn[1] != view_key
                or sum(count for count, _ in passes) <= budget):
            return None
        self._progress = _Progress(key, self._slice_target(size, fbo.samples))
        return self._progress

    def _draw_slice(self, fbo: moderngl.Framebuffer, camera: Camera, style: Style,
                    passes: list[_Pass], progress: _Progress, budget: int) -> bool:
        """The next ``budget`` primitives of ``passes`` into the progress's target,
        copied to ``fbo``; True once they are all drawn (the labels with the last)."""
        target = progress.target
        target.use()
        if progress.done == 0:
            target.clear(*style.background)
        self._begin_scene(style)
        start, stop, offset = progress.done, progress.done + budget, 0
        for count, draw in passes:
            first, last = max(start - offset, 0), min(stop - offset, count)
            if first < last:
                draw(first, last - first)
            offset += count
        progress.done = min(stop, offset)
        finished = progress.done >= offset
        if finished:
            if self._mesh is not None and style.current and style.labels:
                self._draw_labels(camera, style, target.size)
            self._drawn, self._progress = progress.key, None
        self.ctx.copy_framebuffer(fbo, target)
        fbo.use()
        return finished

    def _slice_target(self, size: tuple[int, int], samples: int) -> moderngl.Framebuffer:
        """A framebuffer of ``size`` and ``samples`` to draw a picture in slices
        (kept for the next picture of that size)."""
        if self._slices is not None and self._slices.size == size \
                and self._slices.samples == samples:
            return self._slices
        if self._slices is not None:
            release_framebuffer(self._slices)
        self._cached = None
        self._slices = self.ctx.framebuffer(
            [self.ctx.renderbuffer(size, 4, samples=samples)],
            self.ctx.depth_renderbuffer(size, samples=samples))
        return self._slices

    def _passes(self, style: Style) -> list[_Pass]:
        """The passes of a frame in order, each ``(primitives, draw(first, count))``:
        the other objects, then the current one; a pass draws any range of its
        primitives (state set each time)."""
        passes: list[_Pass] = []
        if self._others is not None and style.others:
            passes += self._scenery_passes(self._others, style)
        if self._mesh is not None and style.current:
            passes += self._current_passes(self._mesh, style)
        return passes

    @contextlib.contextmanager
    def _cut(self, section: tuple[int, float] | None) -> Iterator[None]:
        """Clip the mesh passes drawn inside at ``section`` (see :attr:`Style.section`)."""
        if section is None:
            yield
            return
        axis, at = section
        plane = [0.0, 0.0, 0.0, float(at)]
        plane[axis] = -1.0  # distance at - p[axis]: negative beyond the plane
        self._set_clip_plane(tuple(plane))
        self.ctx.enable_direct(GL_CLIP_DISTANCE0)
        try:
            yield
        finally:
            self.ctx.disable_direct(GL_CLIP_DISTANCE0)
            # llvmpipe clips by a written gl_ClipDistance even when the distance is
            # disabled: the plane itself must go back to one that keeps everything
            self._set_clip_plane(NO_CUT)

    def _set_clip_plane(self, plane: tuple[float, ...]) -> None:
        for name in ("face", "edge", "point", "line", "winding", "cap"):
            self.programs[name]["clip_plane"].value = plane  # type: ignore[union-attr]

    def _draw_guides(self) -> None:
        """The ground grid and the axes, sized to what is drawn (see :func:`guide_lines`)."""
        bounds = self.bounds
        if bounds is None:  # nothing with a finite position: no size to give them
            return
        program = self.programs["line"]
        for vao, _, color in self._guide_arrays(bounds):
            program["line_color"].value = color  # type: ignore[union-attr]
            vao.render(moderngl.LINES)

    def _guide_arrays(self, bounds: np.ndarray) -> list[tuple[moderngl.VertexArray,
                                                               moderngl.Buffer, tuple]]:
        """``(vertex array, buffer, rgb)`` of each of the guide lines for ``(2, 3)``
        ``bounds``: made when the bounds change, and kept for the frames after (a
        turn of the view or a HUD change draws them again as they were)."""
        key = np.asarray(bounds, dtype=np.float64).tobytes()
        if self._guides is not None and self._guides[0] == key:
            return self._guides[1]
        program = self.programs["line"]
        made = []
        for lines, color in guide_lines(bounds):
            buffer = self.ctx.buffer(lines.astype(np.float32).tobytes())
            made.append((self.ctx.vertex_array(program, [(buffer, "3f", "in_position")]),
                         buffer, color))
        self._release_guides()
        self._guides = (key, made)
        return made

    def _release_guides(self) -> None:
        if self._guides is not None:
            for vao, buffer, _ in self._guides[1]:
                vao.release()
                buffer.release()
            self._guides = None

    def release(self) -> None:
        """Free every GL object the renderer made: its programs, textures and
        buffers, the uploaded meshes and the pick, winding and guide targets.
        Calling it again does nothing. The renderer must not draw after it; call
        it on the thread that owns ``ctx``, while ``ctx`` is alive (a context that
        is released frees its objects with it)."""
        if self._released:
            return
        self._released = True
        for mesh in (self._mesh, self._others, self._preview):
            if mesh is not None:
                mesh.release()
        self._mesh = self._others = self._preview = None
        self.arrays = self.preview = self.others = None
        self._label_cache = None
        self._release_guides()
        for stream in (*self._text_streams.values(), *self._point_streams.values()):
            stream.release()  # (before the quad buffer and programs they use)
        if self._pick_fbo is not None:
            release_framebuffer(self._pick_fbo)
            self._pick_fbo = None
        if self._winding is not None:
            release_framebuffer(self._winding[0])
            self._winding = None
        if self._slices is not None:
            release_framebuffer(self._slices)
            self._slices = self._progress = None
        self._cap_vao.release()  # (the arrays before the programs they use)
        self.quad.release()
        self.atlas_texture.release()
        for program in self.programs.values():
            program.release()

    def _scenery_passes(self, others: MeshGPU, style: Style) -> list[_Pass]:
        """The other objects: their faces (or their part of the preview), or their
        edges when faces are off. Their wireframe is left out so that the object
        being modelled stands out."""
        preview = self._preview
        if style.preview and preview is not None and len(preview.parts) > 1:
            return [(preview.part(False)[1], lambda first, count: self._draw_surface(
                preview, OTHER_COLOR, False, first, count))]
        if style.faces or style.preview:
            return [(len(others.geometry.triangles), lambda first, count: self._draw_faces(
                others, OTHER_COLOR, smooth=style.smooth, crease_angle=style.crease_angle,
                first=first, count=count))]
        if style.edges:
            return [(len(others.geometry.lines),
                     lambda first, count: self._draw_edges(others, False, first, count))]
        return []

    def _current_passes(self, mesh: MeshGPU, style: Style) -> list[_Pass]:
        """The current object with its preview, selection and points (labels apart)."""
        preview = self._preview if style.preview else None
        # the wireframe over the mesh's own faces is drawn inside the face pass
        # (a mesh with no triangles yet, a segment of createVertex and insertEdge, has
        # its edges drawn as lines)
        wire_in_faces = (style.edges and style.faces and preview is None
                         and len(mesh.geometry.triangles) > 0)
        passes: list[_Pass] = []
        if preview is not None:
            passes.append((preview.part(True)[1], lambda first, count: self._draw_surface(
                preview, PREVIEW_COLOR, True, first, count)))
        elif style.faces:
            passes.append((len(mesh.geometry.triangles), lambda first, count: self._draw_faces(
                mesh, BASE_COLOR, wire=wire_in_faces, smooth=style.smooth,
                crease_angle=style.crease_angle, first=first, count=count)))
        if style.edges and not wire_in_faces:
            passes.append((len(mesh.geometry.lines),
                           lambda first, count: self._draw_edges(mesh, False, first, count)))
        lines = style.edges and not wire_in_faces
        passes.append((1, lambda first, count: self._draw_marks(mesh, style, lines)))
        return passes

    def _draw_marks(self, mesh: MeshGPU, style: Style, lines: bool) -> None:
        """The selected edges (when the edges are not drawn as ``lines``), the
        points, point-spheres and selected corners."""
        if not lines and mesh.selected_lines is not None:
            self._draw_edges(mesh, selected_only=True)
        if style.vertices or self.selection.vertices:
            self._draw_points(mesh, style.point_size, only_selected=not style.vertices)
        if not style.vertices and len(mesh.geometry.point_spheres):
            self._draw_points(mesh, style.point_size, point_spheres=True)
        self._draw_corners(style.point_size)

    def _set_view(self, camera: Camera, size: tuple[int, int]) -> None:
        """Give every program the view of ``camera`` on a ``(width, height)`` target."""
        aspect = size[0] / max(size[1], 1)
        camera.scene_radius = self._scene_reach(camera.target, camera.scene_radius)
        view_matrix = camera.view_matrix()
        mvp = _matrix_bytes(camera.projection_matrix(aspect) @ view_matrix)
        self._set_cap_view(camera, aspect, size[1])
        view = _matrix_bytes(view_matrix)
        for program in self.programs.values():
            program["mvp"].write(mvp)  # type: ignore[union-attr]
            if "view" in program:
                program["view"].write(view)  # type: ignore[union-attr]

    def _scene_reach(self, target: np.ndarray, fallback: float) -> float:
        """Radius around ``target`` of a sphere holding every mesh drawn (``fallback``
        when none is), for the camera's clip planes. Measured from the target, not
        the meshes' centre: a re-run that moves the mesh by less than its size
        keeps the camera (see :func:`~.camera.bounds_changed_a_lot`), and a pan
        moves the target, so the two part. Not the largest radius ever seen
        either: after a large mesh, a small one would get a needlessly deep range."""
        reaches = [float(np.linalg.norm(m.geometry.center - target)) + m.geometry.radius
                   for m in self._placed()]
        return max(reaches) if reaches else fallback

    def _set_cap_view(self, camera: Camera, aspect: float, height: int) -> None:
        """What the cap pass needs to turn each pixel back into a line of sight, and
        the hatch of the section's plane as this view sees it."""
        cap = self.programs["cap"]
        cap["eye"].value = tuple(float(v) for v in camera.eye())  # type: ignore[union-attr]
        basis = camera.basis()
        # a row-major (3, 3) of rows right, up, back is the column-major matrix of columns
        cap["camera_basis"].write(basis.astype(np.float32).tobytes())  # type: ignore[union-attr]
        half = camera.half_height() if camera.ortho else math.tan(math.radians(camera.fov) / 2)
        cap["half_size"].value = (half * aspect, half)  # type: ignore[union-attr]
        cap["ortho"].value = int(camera.ortho)  # type: ignore[union-attr]
        if self._section is None:
            return
        axis = self._section[0]
        along = [1.0, 1.0, 1.0]  # hatch at 45 degrees to the two axes in the plane
        along[axis] = 0.0
        cap["hatch_axis"].value = tuple(along)  # type: ignore[union-attr]
        pixel_size = 2.0 * camera.half_height() / max(height, 1)
        cap["hatch_spacing"].value = hatch_spacing(  # type: ignore[union-attr]
            pixel_size, abs(float(basis[2][axis])))

    def _draw_surface(self, surface: SurfaceGPU, color: tuple[float, float, float],
                      current: bool, first: int = 0, count: int | None = None) -> None:
        """Triangles ``first .. first + count`` (all by default) of the preview's part
        of the current object (or of the others), lit by its own normals, capped
        where a section cuts it."""
        program = self.programs["surface"]
        program["base_color"].value = color  # type: ignore[union-attr]
        program["back_color"].value = BACK_COLOR  # type: ignore[union-attr]
        self.ctx.polygon_offset = (1.0, 1.0)  # the cage's edges, drawn after, win
        if surface.closed:
            self.ctx.enable(moderngl.CULL_FACE)
        start, total = surface.part(current)
        count = total - first if count is None else count
        if count > 0:
            surface.vao.render(moderngl.TRIANGLES, vertices=3 * count, first=3 * (start + first))
        self.ctx.polygon_offset = (0.0, 0.0)
        if surface.closed and self._section is not None:
            self._draw_cap(surface, color, current)
        self.ctx.disable(moderngl.CULL_FACE)

    def _draw_faces(self, mesh: MeshGPU, color: tuple[float, float, float],
                    wire: bool = False, smooth: bool = False,
                    crease_angle: float = CREASE_ANGLE, first: int = 0,
                    count: int | None = None) -> None:
        """Triangles ``first .. first + count`` (all by default) of ``mesh``'s faces."""
        count = len(mesh.geometry.triangles) - first if count is None else count
        if count <= 0:
            return
        program = self.programs["face"]
        program["primitive_base"].value = first  # type: ignore[union-attr]
        program["smooth_shading"].value = int(smooth)  # type: ignore[union-attr]
        program["wire"].value = int(wire)  # type: ignore[union-attr]
        program["pickable"].value = int(mesh is not self._others)  # type: ignore[union-attr]
        program["viewport"].value = tuple(float(v) for v in self.ctx.viewport[2:])  # type: ignore[union-attr]
        program["edge_color"].value = EDGE_COLOR  # type: ignore[union-attr]
        mesh.triangle_index.use(4)
        mesh.position_table.use(5)
        program["base_color"].value = color  # type: ignore[union-attr]
        program["back_color"].value = BACK_COLOR  # type: ignore[union-attr]
        program["selected_color"].value = SELECTED_COLOR  # type: ignore[union-attr]
        mesh.triangle_face.use(0)
        mesh.face_flags.use(1)
        # push faces back so edges and points drawn at the same depth win
        self.ctx.polygon_offset = (1.0, 1.0)
        if mesh.geometry.closed:
            # a closed manifold hides its back faces: skip them (about a third of
            # the frame time on software GL); open meshes show them tinted
            self.ctx.enable(moderngl.CULL_FACE)
        (mesh.smooth_vao(crease_angle) if smooth else mesh.face_vao).render(
            moderngl.TRIANGLES, vertices=3 * count, first=3 * first)
        self.ctx.polygon_offset = (0.0, 0.0)
        if mesh.geometry.closed and self._section is not None:
            self._draw_cap(mesh, color)
        self.ctx.disable(moderngl.CULL_FACE)

    def _draw_cap(self, mesh: MeshGPU | SurfaceGPU,
                  color: tuple[float, float, float], current: bool = True) -> None:
        """The section's cap of a cut closed mesh, in a darker ``color``: the mesh's
        cut triangles count the winding of each pixel into an image, then one pass
        over the viewport draws the plane where it is not 0
        (``shaders.CAP_FRAGMENT``), at its own depth. Must follow the mesh's face
        pass, into the framebuffer now in use."""
        target, viewport = self.ctx.fbo, self.ctx.viewport
        winding = self._count_winding(mesh, (viewport[2], viewport[3]), current)
        target.use()
        self.ctx.viewport = viewport
        self.ctx.enable(moderngl.DEPTH_TEST)
        program = self.programs["cap"]
        program["viewport"].value = tuple(float(v) for v in viewport[2:])  # type: ignore[union-attr]
        program["cap_color"].value = tuple(0.72 * c for c in color)  # type: ignore[union-attr]
        winding.use(6)
        self._cap_vao.render(moderngl.TRIANGLES, vertices=3)

    def _count_winding(self, mesh: MeshGPU | SurfaceGPU, size: tuple[int, int],
                       current: bool = True) -> moderngl.Texture:
        """Draw the cut triangles of ``mesh`` into the winding image of ``size``, front
        faces adding 1 and back faces taking 1 away, and return the image. Leaves
        the winding target bound and the depth test and culling off."""
        target, image = self._winding_target(size)
        target.use()
        target.clear(0.0, 0.0, 0.0, 0.0)
        self.ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        self.ctx.enable(moderngl.BLEND)
        self.ctx.blend_func = moderngl.ONE, moderngl.ONE
        if isinstance(mesh, SurfaceGPU):  # the part of the object capped only
            first, count = mesh.part(current)
            mesh.winding_vao.render(moderngl.TRIANGLES, vertices=3 * count, first=3 * first)
        else:
            mesh.winding_vao.render(moderngl.TRIANGLES)
        self.ctx.disable(moderngl.BLEND)  # the text pass sets its own blend function
        return image

    def _winding_target(self, size: tuple[int, int],
                        ) -> tuple[moderngl.Framebuffer, moderngl.Texture]:
        """A one-channel float framebuffer of ``size`` and its texture, for the cap's
        winding pass (kept for the next frame of that size)."""
        if self._winding is not None and self._winding[0].size == size:
            return self._winding
        if self._winding is not None:
            release_framebuffer(self._winding[0])
        texture = self.ctx.texture(size, 1, dtype="f2")
        texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self._winding = (self.ctx.framebuffer([texture]), texture)
        return self._winding

    def _draw_edges(self, mesh: MeshGPU, selected_only: bool = False, first: int = 0,
                    count: int | None = None) -> None:
        """Edges ``first .. first + count`` (all by default) of ``mesh``, or its
        selected ones."""
        program = self.programs["edge"]
        program["edge_color"].value = EDGE_COLOR  # type: ignore[union-attr]
        program["selected_color"].value = SELECTED_COLOR  # type: ignore[union-attr]
        program["all_selected"].value = int(selected_only)  # type: ignore[union-attr]
        program["primitive_base"].value = first  # type: ignore[union-attr]
        mesh.edge_flags.use(2)
        count = len(mesh.geometry.lines) - first if count is None else count
        if selected_only and mesh.selected_lines is not None:
            program["primitive_base"].value = 0  # type: ignore[union-attr]
            mesh.selected_lines[1].render(moderngl.LINES)
        elif count > 0:
            mesh.edge_vao.render(moderngl.LINES, vertices=2 * count, first=2 * first)

    def _draw_points(self, mesh: MeshGPU, size: float, only_selected: bool = False,
                     point_spheres: bool = False) -> None:
        """The vertices as points: all of them, the selected ones only, or only the
        point-spheres (which no face shows)."""
        program = self.programs["point"]
        program["point_size"].value = size  # type: ignore[union-attr]
        program["point_color"].value = POINT_COLOR  # type: ignore[union-attr]
        program["selected_color"].value = SELECTED_COLOR  # type: ignore[union-attr]
        program["use_flags"].value = 1  # type: ignore[union-attr]
        mesh.vertex_flags.use(3)
        if only_selected:
            # the few selected positions as a batch of their own: cheaper than
            # drawing every vertex and discarding the rest in the shader
            arrays = self.arrays
            assert arrays is not None
            picked = np.flatnonzero(dense_flags(arrays.vertex_ids, self.selection.vertices))
            self._draw_marker_points(arrays.positions[picked].astype(np.float32), size,
                                     SELECTED_COLOR, "vertices")
            return
        if point_spheres:
            mesh.sphere_vao.render(moderngl.POINTS)
        elif len(mesh.geometry.positions):
            mesh.point_vao.render(moderngl.POINTS)

    def _draw_marker_points(self, points: np.ndarray, size: float,
                            color: tuple[float, float, float], kind: str) -> None:
        """Draw ``(k, 3)`` float32 ``points`` in one flat colour (no pick ids),
        through the stream buffer of ``kind`` ("vertices" or "corners")."""
        if len(points) == 0:
            return
        program = self.programs["point"]
        program["point_size"].value = size  # type: ignore[union-attr]
        program["point_color"].value = color  # type: ignore[union-attr]
        program["use_flags"].value = 0  # type: ignore[union-attr]
        vao = self._point_streams[kind].load(points)
        vao.render(moderngl.POINTS, vertices=len(points))

    def _draw_corners(self, size: float) -> None:
        arrays = self.arrays
        if arrays is None or not self.selection.corners:
            return
        picked = np.flatnonzero(dense_flags(arrays.corner_ids, self.selection.corners))
        self._draw_marker_points(corner_points(arrays, picked), size, CORNER_COLOR, "corners")

    # -- text ------------------------------------------------------------------

    def _label_quads(self, style: Style, view: np.ndarray | None = None) -> np.ndarray:
        """``(n, QUAD_FLOATS)`` label quads for ``style``: of the elements a
        ``view`` (a ``(4, 4)`` view-projection matrix) sees, the ``MAX_LABELS``
        nearest the eye (without a view, the first ``MAX_LABELS`` of each kind).
        Kept until the content, the labels asked or the view change."""
        key = (style.labels, style.labels_selected_only, style.section, id(self.arrays),
               None if view is None else np.asarray(view, np.float64).tobytes())
        if self._label_cache is not None and self._label_cache[0] == key:
            return self._label_cache[1]
        arrays = self.arrays
        assert arrays is not None
        parts = [np.zeros((0, QUAD_FLOATS), dtype=np.float32)]
        for name, (kind, ids, picked) in self._label_sources(arrays).items():
            if name not in style.labels:
                continue
            anchors, candidates, columns, selected = self._label_candidates(
                name, ids, picked, style)
            shown = candidates[visible_labels(columns, view, MAX_LABELS)]
            parts.append(layout_labels(self.atlas, anchors[shown], ids[shown], kind,
                                       selected[shown]))
        quads = np.concatenate(parts)
        self._label_cache = (key, quads)
        return quads

    def _label_sources(self, arrays: MeshArrays) -> dict[str, tuple[int, np.ndarray, tuple]]:
        """Each label kind's ``(colour key, ids, selected ids)``."""
        return {"faces": (1, arrays.face_ids, self.selection.faces),
                "edges": (2, arrays.edge_ids, self.selection.edges),
                "vertices": (3, arrays.vertex_ids, self.selection.vertices)}

    def _label_candidates(self, name: str, ids: np.ndarray, picked: tuple, style: Style,
                          ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """``(anchors (n, 3), candidate indices (k,), their anchors (3, k) float32,
        selected (n,) bool)`` of the labels of kind ``name`` the style lets show
        (holes, what a section cut away and, when asked, the unselected ones left
        out), before the view chooses."""
        key = (name, style.labels_selected_only, style.section, id(self.arrays),
               self.selection)
        cached = self._label_candidates_cache.get(name)
        if cached is not None and cached[0] == key:
            return cached[1]
        assert self.arrays is not None
        anchors = self._anchors_of(name)
        selected = dense_flags(ids, picked).astype(bool)
        show = selected.copy() if style.labels_selected_only else np.ones(len(ids), bool)
        if name == "faces":
            show &= ~self.arrays.face_hole
        if style.section is not None:  # no labels on what the cut took away
            show &= anchors[:, style.section[0]] <= style.section[1]
        candidates = np.flatnonzero(show)
        columns = np.ascontiguousarray(anchors[candidates].T, dtype=np.float32)
        made = (anchors, candidates, columns, selected)
        self._label_candidates_cache[name] = (key, made)
        return made

    def _anchors_of(self, name: str) -> np.ndarray:
        """``(n, 3)`` anchors of the current mesh's labels of kind ``name``: as
        prepared with the mesh (off the thread), or made now and kept."""
        if name not in self._anchors:
            assert self.arrays is not None
            self._anchors.update(label_anchors(self.arrays, (name,)))
        return self._anchors[name]

    def _draw_labels(self, camera: Camera, style: Style, size: tuple[int, int]) -> None:
        quads = self._label_quads(style, camera.view_projection(size[0] / max(size[1], 1)))
        eye_to_center = float(np.linalg.norm(camera.eye() - self._scene_center()))
        radius = self._mesh.geometry.radius if self._mesh is not None else 1.0
        self.programs["text"]["fade_range"].value = (  # type: ignore[union-attr]
            eye_to_center - radius, eye_to_center + radius)
        self._draw_quads(quads, size, screen_space=False)

    def _scene_center(self) -> np.ndarray:
        return np.zeros(3) if self._mesh is None else self._mesh.geometry.center

    def draw_overlay(self, fbo: moderngl.Framebuffer, quads: np.ndarray,
                     size: tuple[int, int] | None = None) -> None:
        """Draw screen-space text/box ``quads`` (see :mod:`livemod.viewer.text`) on top,
        laid out for ``size`` pixels (default ``fbo.size``)."""
        fbo.use()
        self._draw_quads(quads, size or fbo.size, screen_space=True)

    def _draw_quads(self, quads: np.ndarray, size: tuple[int, int], screen_space: bool) -> None:
        """Draw ``(n, QUAD_FLOATS)`` text/box ``quads`` over ``size`` pixels, through the
        kept stream buffer of screen text or of labels (``screen_space``)."""
        if len(quads) == 0:
            return
        program = self.programs["text"]
        program["viewport"].value = (float(size[0]), float(size[1]))  # type: ignore[union-attr]
        program["screen_space"].value = int(screen_space)  # type: ignore[union-attr]
        self.ctx.disable(moderngl.DEPTH_TEST)
        self.ctx.enable(moderngl.BLEND)
        self.ctx.blend_func = moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA
        vao = self._text_streams[screen_space].load(quads)
        self.atlas_texture.use(0)
        vao.render(moderngl.TRIANGLE_STRIP, vertices=4, instances=len(quads))
        self.ctx.disable(moderngl.BLEND)

    # -- picking ---------------------------------------------------------------

    def pick(self, camera: Camera, size: tuple[int, int], x: int, y: int, kind: str,
             radius: int = 6) -> Pick | None:
        """The element of ``kind`` under pixel ``(x, y)`` (from the top left), or None.

        Renders an integer id pass at ``size``. Faces and corners are picked at the
        pixel itself; edges and vertices at the nearest id within ``radius`` pixels.
        A corner is its face's corner whose vertex is nearest the click (TopMod).
        """
        arrays = self.arrays
        if self._mesh is None or arrays is None or not self._current_shown:
            return None  # (an object the frame hid is not picked)
        fbo = self._pick_target(size)
        self._render_ids(fbo, camera, kind)
        reach = 0 if kind in ("face", "corner") else radius
        hit = _nearest_id(fbo, x, size[1] - 1 - y, reach, _KIND_CODES[kind])
        if hit is None:
            return None
        if kind == "corner":
            dense = nearest_corner(arrays, hit, camera, size, (x, y))
            return Pick("corner", dense, int(arrays.corner_ids[dense]))
        ids = {"face": arrays.face_ids, "edge": arrays.edge_ids, "vertex": arrays.vertex_ids}
        return Pick(kind, hit, int(ids[kind][hit]))

    def _pick_target(self, size: tuple[int, int]) -> moderngl.Framebuffer:
        if self._pick_fbo is not None and self._pick_fbo.size == tuple(size):
            return self._pick_fbo
        if self._pick_fbo is not None:
            release_framebuffer(self._pick_fbo)
        self._pick_fbo = self.ctx.framebuffer(
            [self.ctx.texture(size, 4), self.ctx.texture(size, 1, dtype="u4")],
            self.ctx.depth_renderbuffer(size))
        return self._pick_fbo

    def _render_ids(self, fbo: moderngl.Framebuffer, camera: Camera, kind: str) -> None:
        """Draw faces (always, they occlude) and the edges or points of ``kind``."""
        assert self._mesh is not None
        fbo.use()
        self.ctx.viewport = (0, 0, *fbo.size)
        fbo.clear(0.0, 0.0, 0.0, 0.0)  # 0 bits in the id attachment: background
        self._set_view(camera, fbo.size)
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.PROGRAM_POINT_SIZE)
        self.ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
        with self._cut(self._section):  # what the cut took away is not picked
            if self._others is not None and self._others_shown:  # they hide, with id 0
                self._draw_faces(self._others, OTHER_COLOR)
            self._draw_faces(self._mesh, BASE_COLOR)
            if kind == "edge":
                self._draw_edges(self._mesh)
            elif kind == "vertex":
                self._draw_points(self._mesh, 9.0)


_KIND_CODES = {"face": 1, "corner": 1, "edge": 2, "vertex": 3}


def _nearest_id(fbo: moderngl.Framebuffer, x: int, y: int, reach: int, code: int) -> int | None:
    """Dense index of the ``code`` id nearest ``(x, y)`` (GL pixels) within ``reach``."""
    width, height = fbo.size
    x0, y0 = max(x - reach, 0), max(y - reach, 0)
    x1, y1 = min(x + reach + 1, width), min(y + reach + 1, height)
    if x0 >= x1 or y0 >= y1:
        return None
    raw = fbo.read(viewport=(x0, y0, x1 - x0, y1 - y0), components=1, attachment=1,
                   dtype="u4")
    ids = np.frombuffer(raw, dtype=np.uint32).reshape(y1 - y0, x1 - x0)
    rows, cols = np.nonzero((ids >> 28) == code)
    if len(rows) == 0:
        return None
    dist = (rows + y0 - y) ** 2 + (cols + x0 - x) ** 2
    best = int(np.argmin(dist))
    decoded = decode_pick(int(ids[rows[best], cols[best]]))
    return None if decoded is None else decoded[1]


def nearest_corner(arrays: MeshArrays, face: int, camera: Camera, size: tuple[int, int],
                   point: tuple[int, int]) -> int:
    """Dense index of the corner of dense ``face`` whose vertex projects nearest
    ``point`` (window pixels from the top left, of a ``size`` view).

    Only corners in front of the eye count: one behind it (clip w <= 0, as when a
    perspective eye is inside the mesh) has no place on the screen, and dividing
    by its w would mirror it through the centre of the view, maybe onto the click.
    A face picked at a pixel has a corner in front (w is linear over its triangle,
    and the pixel's point is in front); when none is, the one nearest to being
    in front (the largest w) is returned.
    """
    start, stop = int(arrays.face_offsets[face]), int(arrays.face_offsets[face + 1])
    at = arrays.positions[arrays.corner_vertex[start:stop]]
    clip = np.c_[at, np.ones(len(at))] @ camera.view_projection(size[0] / max(size[1], 1)).T
    w = clip[:, 3]
    front = np.flatnonzero(w > 0.0)  # (a vertex that is not finite is left out too)
    if len(front) == 0:
        return start + int(np.argmax(w))
    ndc = clip[front, :2] / w[front, None]
    pixels = np.c_[(ndc[:, 0] + 1) * 0.5 * size[0], (1 - ndc[:, 1]) * 0.5 * size[1]]
    return start + int(front[np.argmin(((pixels - np.asarray(point)) ** 2).sum(axis=1))])
