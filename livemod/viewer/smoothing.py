"""The smoothed preview the window shows (``P``): TopMod's patches of every object
drawn, or the Catmull-Clark limit (``Shift+P``), at a density the user sets
(``PgUp``/``PgDn``).

:class:`PreviewControl` asks for a preview (made on a thread of its own, see
:class:`~livemod.runner.preview.ScenePreviews`) whenever what it would show
changes: the meshes drawn, the settings, or, when the budget left room for the
part of the mesh in view only, the view once it has come to rest. The newest
finished one goes to the renderer, which uploads it a slice at a time.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from typing import TYPE_CHECKING

from livemod.runner.preview import (
    CATMULL_CLARK,
    DEFAULT_TRIANGLE_BUDGET,
    GPU_TRIANGLE_BUDGET,
    MAX_DENSITY,
    PATCHES,
    PreviewRequest,
    PreviewSettings,
    ScenePreviews,
    View,
)

from .camera import Camera
from .look import Look

if TYPE_CHECKING:
    from livemod.dlfl.arrays import MeshArrays

    from .renderer import Renderer

SETTLE = 0.3  # seconds a view rests before a preview of its part is asked for


def triangle_budget(renderer_name: str) -> int:
    """The preview's triangle budget for the GL renderer named ``renderer_name``
    (``GL_RENDERER``): software GL's (llvmpipe, softpipe) or a GPU's."""
    software = any(name in renderer_name.lower() for name in ("llvmpipe", "softpipe",
                                                              "swrast"))
    return DEFAULT_TRIANGLE_BUDGET if software else GPU_TRIANGLE_BUDGET


class PreviewControl:
    """Which preview the window shows, and asking for it.

    Args:
        renderer: draws it (:meth:`~.renderer.Renderer.stage_preview`).
        look: whether the preview is drawn (``style.preview``).
        camera: the view, for a preview of the part in view.
        content: gives the meshes the window shows (or is uploading): the
            current object's arrays and the other objects drawn, joined.
        aspect: gives the framebuffer's width over its height.
        echo: prints a line in the terminal.
        previews: makes them (a :class:`ScenePreviews` of its own when None).

    Attributes:
        settings: mode, density and budget asked for.
        description: what the preview drawn shows ("" before the first).
    """

    def __init__(self, renderer: Renderer, look: Look, camera: Camera,
                 content: Callable[[], tuple[MeshArrays | None, MeshArrays | None]],
                 aspect: Callable[[], float], echo: Callable[[str], None],
                 previews: ScenePreviews | None = None) -> None:
        self._renderer, self._look, self._camera = renderer, look, camera
        self._content, self._aspect, self._echo = content, aspect, echo
        self._previews = previews if previews is not None else ScenePreviews()
        budget = triangle_budget(str(renderer.ctx.info.get("GL_RENDERER", "")))
        self.settings = PreviewSettings(budget=budget)
        self.description = ""
        # the newest request's (content, camera pose), and its number while outstanding
        self._asked: tuple | None = None
        self._number: int | None = None
        self._by_view = False                # the preview shown holds the part in view
        self._pose: tuple | None = None      # the camera's pose, and when it last moved
        self._moved_at = 0.0

    @property
    def updating(self) -> bool:
        """A preview was asked for and has not come yet."""
        return self._number is not None

    def hud_line(self) -> str:
        """The HUD's line about the preview ("" while it is not drawn)."""
        if not self._look.style.preview:
            return ""
        if not self.description:
            return "preview: computing..." if self.updating else "preview: none"
        return f"preview: {self.description}" + ("  (updating...)" if self.updating else "")

    def update(self) -> None:
        """Each frame: hand a finished preview to the renderer, and ask for a new one
        when what it would show changed (never waits)."""
        taken = self._previews.take()
        if taken is not None and taken[0] == self._number:
            number, preview = taken
            self._renderer.stage_preview(preview)
            self.description, self._by_view = preview.description, preview.by_view
            self._number = None
        if self._look.style.preview:
            self._ask_if_changed()

    def _ask_if_changed(self) -> None:
        """Ask for the preview of the meshes shown with the settings, unless asked
        already; when the one shown holds the part in view only, ask again for a
        view that moved and came to rest."""
        arrays, others = self._content()
        if arrays is None:
            return
        if not self._look.style.others:
            others = None
        pose, now = self._camera.pose(), time.monotonic()
        if pose != self._pose:
            self._pose, self._moved_at = pose, now
        content = (id(arrays), id(others), self.settings)
        if self._asked is not None and self._asked[0] == content:
            moved = self._by_view and pose != self._asked[1]
            if not moved or now - self._moved_at < SETTLE or self.updating:
                return
        view = View(self._camera.eye(), self._camera.view_projection(self._aspect()))
        objects = (arrays,) if others is None else (arrays, others)
        self._asked = (content, pose)
        self._number = self._previews.ask(PreviewRequest(objects, self.settings, view))

    # -- keys ------------------------------------------------------------------------

    def change_density(self, step: int) -> None:
        """``PgUp`` / ``PgDn``: a denser or coarser preview (shown, if it was not)."""
        density = min(max(self.settings.density + step, 1), MAX_DENSITY)
        self._set(dataclasses.replace(self.settings, density=density, mode=PATCHES))
        self._echo(f"preview: patches, density {density}")

    def toggle_mode(self) -> None:
        """``Shift+P``: TopMod's patches or the Catmull-Clark limit."""
        mode = CATMULL_CLARK if self.settings.mode == PATCHES else PATCHES
        self._set(dataclasses.replace(self.settings, mode=mode))
        self._echo(f"preview: {mode}")

    def _set(self, settings: PreviewSettings) -> None:
        self.settings = settings
        self._look.change(preview=True)

    def close(self) -> None:
        """Stop the preview thread."""
        self._previews.close()
