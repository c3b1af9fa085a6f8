"""The renderer shared by the live window and headless rendering.

:class:`Renderer` composes the frames of its content
(:class:`~.content.DrawnContent`: the meshes uploaded and the selection): which
passes a frame holds (the other objects, then the current one's faces or preview,
edges and points), drawn whole, in slices or quick, into any framebuffer (the
window's, or an offscreen one). Its parts each own one job's GL objects:
:class:`~.mesh_passes.MeshPasses` the programs and the draw call of each mesh
element, :class:`~.text_pass.TextPass` the screen text and id labels,
:class:`~.id_pass.IdPass` the pick target, :class:`~.section_cap.SectionCap` the
clip plane and the section's cap, :class:`~.slices.SlicedFrames` frames drawn in
slices or kept whole, :class:`~.guides.Guides` the grid and axes, and
:class:`~.marks.SelectionMarks` the selection's marker points. Every method must
be called on the thread that owns ``ctx``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import moderngl
import numpy as np

from .camera import Camera
from .content import UPLOAD_SECONDS as UPLOAD_SECONDS
from .content import DrawnContent
from .framebuffers import release_framebuffer as release_framebuffer
from .geometry import CREASE_ANGLE, LabelAnchors
from .guides import Guides
from .id_pass import IdPass
from .id_pass import Pick as Pick
from .marks import SelectionMarks
from .mesh_passes import SELECTED_COLOR as SELECTED_COLOR
from .mesh_passes import MeshPasses, compile_programs
from .section_cap import SectionCap
from .slices import Frame, SlicedFrames
from .slices import Pass as _Pass
from .streams import StreamBuffer
from .text_pass import MAX_LABELS as MAX_LABELS
from .text_pass import PALETTE as PALETTE
from .text_pass import TextPass
from .uploads import MeshGPU

CACHED_PRIMITIVES = 100_000  # a bigger scene is kept whole between frames (see draw)
# a bigger picture is drawn quick while the view moves (see Renderer.quick_style)
QUICK_PRIMITIVES = 100_000
GL_MULTISAMPLE = 0x809D  # (moderngl has no name for it)
LABEL_KINDS = ("faces", "edges", "vertices")

BASE_COLOR = (1.0, 0.59, 0.36)      # TopMod's render colour (255, 151, 92)
PREVIEW_COLOR = (0.62, 0.78, 0.95)
OTHER_COLOR = (0.86, 0.70, 0.60)     # the scene's other objects: the base colour, muted
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
        colors: draw the faces in their own colours (the colour mode), the
            preview's patches in their faces' and the other objects' muted; faces
            without one, and every face when off, in the flat modelling colour
            (the preview's colour, the others' muted one).
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
    colors: bool = True


def read_image(fbo: moderngl.Framebuffer, style: Style) -> np.ndarray:
    """The colour of ``fbo`` drawn with ``style``: ``(H, W, 3)`` uint8 RGB, row 0
    at the top, or ``(H, W, 4)`` RGBA when ``style.background`` is not opaque (a
    transparent background: alpha 0 where nothing is drawn)."""
    channels = 3 if style.background[3] >= 1.0 else 4
    width, height = fbo.size
    raw = fbo.read(components=channels, alignment=1)
    return np.frombuffer(raw, dtype=np.uint8).reshape(height, width, channels)[::-1].copy()


def render_offscreen(renderer: Renderer, camera: Camera, style: Style,
                     size: tuple[int, int]) -> np.ndarray:
    """What ``renderer`` draws through ``camera`` with ``style`` at ``size``, into a
    framebuffer of its own (no HUD, nothing on screen changes): see
    :func:`read_image` for the array. The caller makes its own framebuffer
    current again afterwards."""
    ctx = renderer.ctx
    fbo = ctx.framebuffer([ctx.renderbuffer(size, 4)], ctx.depth_renderbuffer(size))
    try:
        renderer.draw(fbo, camera, style)
        return read_image(fbo, style)
    finally:
        release_framebuffer(fbo)


class Renderer(DrawnContent):
    """Draws the content (see :class:`~.content.DrawnContent`): meshes, selections,
    labels and screen text with one set of programs."""

    def __init__(self, ctx: moderngl.Context) -> None:
        super().__init__(ctx, compile_programs(ctx))
        self._others_shown = True
        self._current_shown = True
        self._text = TextPass(ctx, self.programs["text"])
        self._ids = IdPass(ctx)
        self._cap = SectionCap(ctx, self.programs)
        # (its section is the last frame's, also for picking)
        self._meshes = MeshPasses(ctx, self.programs, self._cap)
        self._frames = SlicedFrames(ctx)
        self._guide_lines = Guides(ctx, self.programs["line"])
        self._marks = SelectionMarks(ctx, self.programs["point"])
        self._released = False

    def _new_mesh(self, anchors: dict[str, LabelAnchors]) -> None:
        self._text.new_mesh(anchors)

    def _new_selection(self) -> None:
        self._text.new_selection()

    # the parts' GL objects, under the names the renderer's tests look at them by
    @property
    def _text_streams(self) -> dict[bool, StreamBuffer]:
        return self._text.streams

    @property
    def _point_streams(self) -> dict[str, StreamBuffer]:
        return self._marks.streams

    @property
    def _guides(self) -> tuple[bytes, list] | None:
        return self._guide_lines.made

    @property
    def _pick_fbo(self) -> moderngl.Framebuffer | None:
        return self._ids.target

    @property
    def _winding(self) -> tuple[moderngl.Framebuffer, moderngl.Texture] | None:
        return self._cap.winding

    @property
    def unfinished(self) -> bool:
        """A picture drawn in slices is not whole yet: draw again (see :meth:`draw`)."""
        return self._frames.unfinished

    @property
    def hidden(self) -> bool:
        """The last :meth:`draw` drew a slice of a picture drawn behind what its
        framebuffer shows, and nothing on it."""
        return self._frames.hidden

    @property
    def sliced(self) -> int:
        """Primitives the last :meth:`draw` drew of a picture drawn in slices (0:
        it drew none; such a call finishes its drawing before it returns)."""
        return self._frames.sliced

    # -- drawing ---------------------------------------------------------------

    def draw(self, fbo: moderngl.Framebuffer, camera: Camera, style: Style,
             size: tuple[int, int] | None = None, budget: int | None = None,
             quick: bool = False, behind: bool = False) -> bool:
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
        seen again from the view of the last picture is kept whole in that target
        (see :class:`~.slices.SlicedFrames`): drawn again unchanged (only the
        window's HUD changed, say), it is copied instead of drawn.

        With ``quick`` (the window's view moves), a big picture is drawn as
        :meth:`quick_style` says, and without multisampling. With ``behind`` and a
        budget (the view came to rest after quick pictures), a picture of more than
        the budget is drawn in slices whatever changed, and nothing is drawn on
        ``fbo`` until it is whole (:attr:`hidden` meanwhile): the quick picture
        stays on the screen."""
        width, height = size or fbo.size
        fast = self.quick_style(style) if quick else None
        if fast is not None:
            self.ctx.disable_direct(GL_MULTISAMPLE)
            try:
                return self._draw(fbo, camera, fast, (width, height), budget, quick=True)
            finally:
                self.ctx.enable_direct(GL_MULTISAMPLE)
        return self._draw(fbo, camera, style, (width, height), budget, quick=False,
                          behind=behind)

    def quick_style(self, style: Style) -> Style | None:
        """The style of the quick picture of what ``style`` draws, for a view that
        moves (adaptive quality, as CAD programs draw big models while they turn):
        without its edges (the preview's cage, the wire over the faces), when the
        picture holds more than ``QUICK_PRIMITIVES`` primitives and shows faces or
        the preview without them. None: the picture is drawn whole. On software
        GL the edges of a 100,000-face preview cost more than its surface, and
        multisampling triples both."""
        if not style.edges or not (style.faces or (style.preview and self._preview is not None)):
            return None
        if sum(count for count, _ in self._passes(style)) <= QUICK_PRIMITIVES:
            return None
        return replace(style, edges=False)

    def _draw(self, fbo: moderngl.Framebuffer, camera: Camera, style: Style,
              size: tuple[int, int], budget: int | None, quick: bool,
              behind: bool = False) -> bool:
        """:meth:`draw`, of ``style`` (quick: the quick picture's)."""
        width, height = size
        self._meshes.quick = quick
        self.ctx.viewport = (0, 0, width, height)
        if self._mesh is None and self._others is None:
            fbo.use()
            fbo.clear(*style.background)
            return True
        self._others_shown = style.others  # picking hides what the frame hid
        self._current_shown = style.current
        self._meshes.section = style.section  # (before the view: the cap's hatch depends on it)
        self._set_view(camera, (width, height))
        # the camera's pose, not its matrices: its clip planes follow the content's reach
        view_key = (camera.pose(), style, (width, height), quick)
        frame = Frame((self.version, view_key), (width, height), self._passes(style),
                      style.background, sliceable=style.section is None,
                      begin=lambda: self._begin_scene(style),
                      finish=lambda drawn: self._draw_labels(camera, style, drawn),
                      whole=lambda target: self._draw_whole(target, frame, style),
                      finish_apart=bool(style.labels) and style.current)
        return self._frames.draw(fbo, frame, budget, CACHED_PRIMITIVES, behind)

    def _draw_whole(self, fbo: moderngl.Framebuffer, frame: Frame, style: Style) -> None:
        """All of ``frame`` into ``fbo``, its passes cut at ``style``'s section."""
        fbo.use()
        fbo.clear(*frame.background)
        frame.begin()
        with self._cap.cut(style.section):
            for count, draw in frame.passes:
                draw(0, count)
        frame.finish(frame.size)

    def _begin_scene(self, style: Style) -> None:
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.PROGRAM_POINT_SIZE)
        self.ctx.disable(moderngl.CULL_FACE | moderngl.BLEND)
        if style.grid:
            self._guide_lines.draw(self.bounds)

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

    def release(self) -> None:
        """Free every GL object the renderer made: its programs, textures and
        buffers, the uploaded meshes and the pick, winding and guide targets.
        Calling it again does nothing. The renderer must not draw after it; call
        it on the thread that owns ``ctx``, while ``ctx`` is alive (a context that
        is released frees its objects with it)."""
        if self._released:
            return
        self._released = True
        self._release_content()
        self._guide_lines.release()
        # each part frees its arrays and buffers before the programs they use go
        for part in (self._text, self._marks, self._ids, self._cap, self._frames):
            part.release()
        for program in self.programs.values():
            program.release()

    def _scenery_passes(self, others: MeshGPU, style: Style) -> list[_Pass]:
        """The other objects: their faces (or their part of the preview), or their
        edges when faces are off. Their wireframe is left out so that the object
        being modelled stands out."""
        preview = self._preview
        if style.preview and preview is not None and len(preview.parts) > 1:
            return [(preview.part(False)[1], lambda first, count: self._meshes.surface(
                preview, OTHER_COLOR, False, first, count, own_colors=style.colors))]
        if style.faces or style.preview:
            return [(len(others.geometry.triangles), lambda first, count: self._meshes.faces(
                others, OTHER_COLOR, False, smooth=style.smooth, crease_angle=style.crease_angle,
                first=first, count=count, own_colors=style.colors))]
        if style.edges:
            return [(len(others.geometry.lines),
                     lambda first, count: self._meshes.edges(others, False, first, count))]
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
            passes.append((preview.part(True)[1], lambda first, count: self._meshes.surface(
                preview, PREVIEW_COLOR, True, first, count, own_colors=style.colors)))
        elif style.faces:
            passes.append((len(mesh.geometry.triangles), lambda first, count: self._meshes.faces(
                mesh, BASE_COLOR, True, wire=wire_in_faces, smooth=style.smooth,
                crease_angle=style.crease_angle, first=first, count=count,
                own_colors=style.colors)))
        if style.edges and not wire_in_faces:
            passes.append((len(mesh.geometry.lines),
                           lambda first, count: self._meshes.edges(mesh, False, first, count)))
        lines = style.edges and not wire_in_faces
        passes.append((1, lambda first, count: self._draw_marks(mesh, style, lines)))
        return passes

    def _draw_marks(self, mesh: MeshGPU, style: Style, lines: bool) -> None:
        """The selected edges (when the edges are not drawn as ``lines``), the
        points, point-spheres and selected corners."""
        if not lines and mesh.selected_lines is not None:
            self._meshes.edges(mesh, selected_only=True)
        if style.vertices:
            self._meshes.points(mesh, style.point_size)
        elif self.selection.vertices:
            assert self.arrays is not None
            self._marks.draw_vertices(self.arrays, self.selection, style.point_size,
                                      SELECTED_COLOR)
        if not style.vertices and len(mesh.geometry.point_spheres):
            self._meshes.points(mesh, style.point_size, point_spheres=True)
        self._marks.draw_corners(self.arrays, self.selection, style.point_size, CORNER_COLOR)

    def _set_view(self, camera: Camera, size: tuple[int, int]) -> None:
        """Give every program the view of ``camera`` on a ``(width, height)`` target."""
        aspect = size[0] / max(size[1], 1)
        camera.scene_radius = self._scene_reach(camera.target, camera.scene_radius)
        view_matrix = camera.view_matrix()
        self._cap.set_view(camera, aspect, size[1], self._meshes.section)
        self._meshes.set_view(camera.projection_matrix(aspect) @ view_matrix, view_matrix)

    # -- text ------------------------------------------------------------------

    def _label_quads(self, style: Style, view: np.ndarray | None = None) -> np.ndarray:
        """The current mesh's label quads (see :meth:`TextPass.label_quads`)."""
        assert self.arrays is not None
        return self._text.label_quads(self.arrays, self.selection, style, view)

    def _draw_labels(self, camera: Camera, style: Style, size: tuple[int, int]) -> None:
        """The id labels ``style`` asks for of the current mesh, when it is drawn."""
        if self._mesh is None or not style.current or not style.labels:
            return
        assert self.arrays is not None
        geometry = self._mesh.geometry
        self._text.draw_labels(self.arrays, self.selection, camera, style, size,
                               geometry.center, geometry.radius)

    def draw_overlay(self, fbo: moderngl.Framebuffer, quads: np.ndarray,
                     size: tuple[int, int] | None = None) -> None:
        """Draw screen-space text/box ``quads`` (see :mod:`livemod.viewer.text`) on top,
        laid out for ``size`` pixels (default ``fbo.size``)."""
        fbo.use()
        self._text.draw_quads(quads, size or fbo.size, screen_space=True)

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
        return self._ids.pick(arrays, camera, size, (x, y), kind, radius,
                              lambda fbo: self._render_ids(fbo, camera, kind))

    def _render_ids(self, fbo: moderngl.Framebuffer, camera: Camera, kind: str) -> None:
        """Draw faces (always, they occlude) and the edges or points of ``kind``
        into the bound and cleared ``fbo``."""
        assert self._mesh is not None
        self._set_view(camera, fbo.size)
        self.ctx.enable(moderngl.DEPTH_TEST | moderngl.PROGRAM_POINT_SIZE)
        self.ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
        with self._cap.cut(self._meshes.section):  # what the cut took away is not picked
            if self._others is not None and self._others_shown:  # they hide, with id 0
                self._meshes.faces(self._others, OTHER_COLOR, False)
            self._meshes.faces(self._mesh, BASE_COLOR, True)
            if kind == "edge":
                self._meshes.edges(self._mesh, picking=True)
            elif kind == "vertex":
                self._meshes.points(self._mesh, 9.0)
