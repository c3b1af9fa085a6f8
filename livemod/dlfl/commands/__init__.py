"""The thesis's command set (Tett 2007, appendix), acting on the current scene.

``from livemod.dlfl import *`` brings exactly these names into a script.
"""

from __future__ import annotations

from . import cleanup, colors, core, cutting, extrusion, params, sculpt, selection, subdivision
from .cleanup import *  # noqa: F403
from .colors import *  # noqa: F403
from .core import *  # noqa: F403
from .cutting import *  # noqa: F403
from .extrusion import *  # noqa: F403
from .params import *  # noqa: F403
from .sculpt import *  # noqa: F403
from .selection import *  # noqa: F403
from .subdivision import *  # noqa: F403

__all__ = [
    *core.__all__, *subdivision.__all__, *extrusion.__all__, *sculpt.__all__, *params.__all__,
    *cutting.__all__, *cleanup.__all__, *selection.__all__, *colors.__all__,
]
