"""The mouse: the panels, the object list and the timeline first, the model after
(GL-free).

:class:`Pointer` takes the window's mouse events in window points and sends each
to what lies under it: a press on the parameters panel sets a value or starts a
slider's drag, one on the object list ticks a box, one on the timeline scrubs;
on the model a press that does not move is a click (a pick, which the window
makes), and one that moves orbits or pans the camera. The wheel scrolls the
object list under the pointer, else zooms.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from .camera import Camera
from .objects import SceneObjects
from .overlay import Overlay
from .parameters import Parameters
from .stepping import Stepping

CLICK_SLOP = 3  # window pixels a press may move and still be a click (a pick)
ORBIT_PER_PIXEL = 0.4  # degrees


@dataclass(frozen=True)
class Buttons:
    """The buttons held during a drag, and the shift key."""

    left: bool = False
    right: bool = False
    middle: bool = False
    shift: bool = False


class Pointer:
    """Sends the mouse to the panels, the timeline or the camera.

    Args:
        overlay: where the panels lie.
        parameters, objects, stepping: what a press on the parameters panel, the
            object list or the timeline acts on.
        camera: what a drag on the model turns and the wheel zooms.
        framebuffer: gives ``(framebuffer size, framebuffer pixels per window
            point)`` now (a window moved to another screen changes the ratio).
    """

    def __init__(self, overlay: Overlay, parameters: Parameters, objects: SceneObjects,
                 stepping: Stepping, camera: Camera,
                 framebuffer: Callable[[], tuple[tuple[int, int], float]]) -> None:
        self._overlay = overlay
        self._parameters = parameters
        self._objects = objects
        self._stepping = stepping
        self._camera = camera
        self._framebuffer = framebuffer
        self.forget()
        self.at: tuple[float, float] = (-1.0, -1.0)  # window point of the mouse

    def forget(self) -> None:
        """Drop a press on the model (another script opened meanwhile)."""
        self._press: tuple[float, float] | None = None
        self._moved = False

    def press(self, x: float, y: float) -> None:
        """A button went down at window point ``(x, y)``."""
        size, ratio = self._framebuffer()
        px, py = x * ratio, y * ratio
        hit = self._overlay.parameters_hit(px, py, size)
        if hit is not None:
            self._parameters.press(hit, px, size)
            return
        hit = self._overlay.objects_hit(px, py, size)
        if hit is not None:
            self._objects.press(hit)
            return
        if self._overlay.timeline_hit(px, py, size):
            self._stepping.scrub_to(self._overlay.timeline_step(px, size))
            return
        self._press, self._moved = (x, y), False

    def move(self, x: float, y: float) -> None:
        """The pointer moved with no button down: highlight the row under it."""
        self.at = (x, y)
        size, ratio = self._framebuffer()
        hit = self._overlay.parameters_hit(x * ratio, y * ratio, size)
        self._parameters.panel.hover = hit.row if hit is not None and hit.row >= 0 else None
        self._objects.panel.point_at(self._overlay.objects_hit(x * ratio, y * ratio, size))

    def drag(self, x: float, y: float, dx: float, dy: float, buttons: Buttons) -> None:
        """Drag a slider or the timeline, else orbit (left) or pan (shift-left,
        right, middle)."""
        self.at = (x, y)
        size, ratio = self._framebuffer()
        if self._parameters.dragged is not None:
            self._parameters.drag_to(x * ratio, size)
            return
        if self._stepping.scrubbing:
            self._stepping.scrub_to(self._overlay.timeline_step(x * ratio, size))
            return
        if self._press is not None and \
                abs(x - self._press[0]) + abs(y - self._press[1]) > CLICK_SLOP:
            self._moved = True
        if buttons.left and not buttons.shift:
            self._camera.orbit(dx * ORBIT_PER_PIXEL, dy * ORBIT_PER_PIXEL)
        elif buttons.left or buttons.right or buttons.middle:
            self._camera.pan(dx * ratio, dy * ratio, size[1])

    def release(self) -> bool:
        """A button went up: end a drag (a slider's value is sent now); True when it
        ends a click on the model that did not move (the window picks)."""
        if self._parameters.dragged is not None:
            self._parameters.let_go()
            return False
        if self._stepping.scrubbing:
            self._stepping.end_scrub()
            return False
        clicked = self._press is not None and not self._moved
        self._press = None
        return clicked

    def scroll(self, y_offset: float) -> None:
        """The wheel scrolls the object list under the pointer, else zooms."""
        size, ratio = self._framebuffer()
        over_list = self._overlay.objects_hit(self.at[0] * ratio, self.at[1] * ratio, size)
        if y_offset and over_list is not None:
            rows = max(1, round(abs(y_offset)))
            self._objects.panel.scroll(-rows if y_offset > 0 else rows, size)
            return
        self._camera.zoom(y_offset)
