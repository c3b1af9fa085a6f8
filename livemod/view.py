"""Seeing models from Python: in a notebook, or in a session without a script file.

* :func:`picture` (a still), :func:`turntable` (an animation around the up axis)
  and :func:`film` (a frame per modeling step of a script) return objects a
  notebook shows inline, as PNG and animated PNG, and that ``save(path)`` to a
  file as ``livemod render`` writes it. A bare :class:`~livemod.dlfl.Mesh`, a
  :class:`~livemod.dlfl.Scene` or a run's result shows as a picture by itself.

Everything is drawn headless by the renderer of ``livemod render``; no window opens.
"""

from __future__ import annotations

from livemod.viewer.film import film
from livemod.viewer.pictures import Animation, Picture, picture, turntable

__all__ = ["Animation", "Picture", "film", "picture", "turntable"]
