"""Drawing text: the HUD's screen text and the id labels of faces, edges and vertices.

:class:`TextPass` owns the glyph atlas and its texture, the quad the text program
instances, the two kept stream buffers (screen text, labels), the id labels' anchors
and the caches of their candidates and layout. The quads themselves are laid out by
:mod:`livemod.viewer.text` (numpy only). Every method of :class:`TextPass` must be
called on the thread that owns the GL context.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import moderngl
import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.scene import Selection

from .camera import Camera
from .geometry import LabelAnchors, dense_flags, label_anchors, visible_labels
from .streams import StreamBuffer
from .text import QUAD_FLOATS, glyph_atlas, layout_labels

if TYPE_CHECKING:
    from .renderer import Style

MAX_LABELS = 2000  # id labels on screen at once, of each kind: the nearest the eye

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

# a label kind's candidates: (anchors (n, 3), candidate indices (k,), their anchors
# (3, k) float32)
_Candidates = tuple[np.ndarray, np.ndarray, np.ndarray]


class TextPass:
    """Draws text and box quads, in screen space or anchored to the mesh.

    Args:
        ctx: the GL context.
        program: the renderer's text program (its ``atlas`` sampler on unit 0).
    """

    def __init__(self, ctx: moderngl.Context, program: moderngl.Program) -> None:
        self.ctx = ctx
        self.program = program
        program["palette"].write(PALETTE.tobytes())  # type: ignore[union-attr]
        program["highlight"].value = (0.15, 0.55, 0.15, 0.9)  # type: ignore[union-attr]
        self.atlas = glyph_atlas()
        height, width = self.atlas.image.shape
        self.atlas_texture = ctx.texture((width, height), 1, self.atlas.image.tobytes())
        self.atlas_texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        corners = np.array([0, 0, 1, 0, 0, 1, 1, 1], dtype=np.float32)
        self.quad = ctx.buffer(corners.tobytes())
        # the buffers each draw refills: screen text (True) and id labels (False)
        self.streams = {screen: StreamBuffer(ctx, self._text_vao) for screen in (True, False)}
        self._label_cache: tuple[object, np.ndarray] | None = None
        self._candidates_cache: dict[str, tuple[object, _Candidates]] = {}
        self._anchors: dict[str, LabelAnchors] = {}  # the current mesh's label anchors

    def _text_vao(self, instances: moderngl.Buffer) -> moderngl.VertexArray:
        """The text program's vertex array: the quad's corners, and one quad per
        ``QUAD_FLOATS`` row of ``instances``."""
        return self.ctx.vertex_array(self.program, [
            (self.quad, "2f", "in_corner"),
            (instances, "3f 2f 2f 4f 1f 1f/i", "in_anchor", "in_offset", "in_size", "in_uv",
             "in_kind", "in_selected"),
        ])

    def new_mesh(self, anchors: dict[str, LabelAnchors]) -> None:
        """The labelled mesh changed: its label ``anchors`` of each kind (as
        prepared off the thread; the kinds missing are made when asked)."""
        self._anchors = dict(anchors)
        self._candidates_cache = {}

    def new_selection(self) -> None:
        """The selection changed: lay the labels out again (they mark the selected)."""
        self._label_cache = None

    def label_quads(self, arrays: MeshArrays, selection: Selection, style: Style,
                    view: np.ndarray | None = None) -> np.ndarray:
        """``(n, QUAD_FLOATS)`` label quads of ``arrays`` for ``style``: of the
        elements a ``view`` (a ``(4, 4)`` view-projection matrix) sees, the
        ``MAX_LABELS`` nearest the eye (without a view, the first ``MAX_LABELS`` of
        each kind). Kept until the content, the labels asked or the view change."""
        key = (style.labels, style.labels_selected_only, style.section, id(arrays),
               None if view is None else np.asarray(view, np.float64).tobytes())
        if self._label_cache is not None and self._label_cache[0] == key:
            return self._label_cache[1]
        parts = [np.zeros((0, QUAD_FLOATS), dtype=np.float32)]
        for name, (kind, ids, picked) in _label_sources(arrays, selection).items():
            if name not in style.labels:
                continue
            anchors, candidates, columns = self._candidates(
                arrays, selection, name, ids, picked, style)
            shown = candidates[visible_labels(columns, view, MAX_LABELS)]
            parts.append(layout_labels(self.atlas, anchors[shown], ids[shown], kind,
                                       dense_flags(ids[shown], picked).astype(bool)))
        quads = np.concatenate(parts)
        self._label_cache = (key, quads)
        return quads

    def _candidates(self, arrays: MeshArrays, selection: Selection, name: str,
                    ids: np.ndarray, picked: tuple, style: Style) -> _Candidates:
        """The labels of kind ``name`` the style lets show (holes, what a section cut
        away and, when asked, the unselected ones left out), before the view chooses.
        With no filter of the style, the anchors' own columns: the first layout of
        a big mesh's labels then projects the columns prepared off the thread."""
        key = (name, style.labels_selected_only, style.section, id(arrays),
               selection if style.labels_selected_only else None)
        cached = self._candidates_cache.get(name)
        if cached is not None and cached[0] == key:
            return cached[1]
        anchors = self._anchors_of(arrays, name)
        candidates, columns = anchors.labelled, anchors.columns
        if style.labels_selected_only or style.section is not None:
            keep = np.ones(len(candidates), bool)
            if style.labels_selected_only:
                keep &= dense_flags(ids[candidates], picked).astype(bool)
            if style.section is not None:  # no labels on what the cut took away
                keep &= anchors.points[candidates, style.section[0]] <= style.section[1]
            candidates, columns = candidates[keep], columns[:, keep]
        made = (anchors.points, candidates, columns)
        self._candidates_cache[name] = (key, made)
        return made

    def _anchors_of(self, arrays: MeshArrays, name: str) -> LabelAnchors:
        """The anchors of the labels of kind ``name`` of ``arrays`` (the mesh of
        :meth:`new_mesh`): as prepared with the mesh, or made now and kept."""
        if name not in self._anchors:
            self._anchors.update(label_anchors(arrays, (name,)))
        return self._anchors[name]

    def draw_labels(self, arrays: MeshArrays, selection: Selection, camera: Camera,
                    style: Style, size: tuple[int, int], center: np.ndarray,
                    radius: float) -> None:
        """The id labels of ``arrays`` over a ``size`` view of ``camera``, faded with
        their depth through the sphere of ``center`` (``(3,)``) and ``radius``."""
        quads = self.label_quads(arrays, selection, style,
                                 camera.view_projection(size[0] / max(size[1], 1)))
        eye_to_center = float(np.linalg.norm(camera.eye() - center))
        self.program["fade_range"].value = (  # type: ignore[union-attr]
            eye_to_center - radius, eye_to_center + radius)
        self.draw_quads(quads, size, screen_space=False)

    def draw_quads(self, quads: np.ndarray, size: tuple[int, int], screen_space: bool) -> None:
        """Draw ``(n, QUAD_FLOATS)`` text/box ``quads`` over ``size`` pixels, through the
        kept stream buffer of screen text or of labels (``screen_space``)."""
        if len(quads) == 0:
            return
        program = self.program
        program["viewport"].value = (float(size[0]), float(size[1]))  # type: ignore[union-attr]
        program["screen_space"].value = int(screen_space)  # type: ignore[union-attr]
        self.ctx.disable(moderngl.DEPTH_TEST)
        self.ctx.enable(moderngl.BLEND)
        self.ctx.blend_func = moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA
        vao = self.streams[screen_space].load(quads)
        self.atlas_texture.use(0)
        vao.render(moderngl.TRIANGLE_STRIP, vertices=4, instances=len(quads))
        self.ctx.disable(moderngl.BLEND)

    def release(self) -> None:
        """Free the streams, then the quad buffer they read and the atlas texture
        (the program is the renderer's to free, after)."""
        self._label_cache = None
        for stream in self.streams.values():
            stream.release()
        self.quad.release()
        self.atlas_texture.release()


def _label_sources(arrays: MeshArrays, selection: Selection,
                   ) -> dict[str, tuple[int, np.ndarray, tuple]]:
    """Each label kind's ``(colour key, ids, selected ids)``."""
    return {"faces": (1, arrays.face_ids, selection.faces),
            "edges": (2, arrays.edge_ids, selection.edges),
            "vertices": (3, arrays.vertex_ids, selection.vertices)}
