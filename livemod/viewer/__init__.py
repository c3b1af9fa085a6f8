"""livemod.viewer: the live window, the shared renderer and headless rendering.

Modules (only the renderer and its parts, ``headless``, ``painter`` and ``window``
import moderngl; importing this package imports nothing heavy):

* ``geometry``: GL-free buffers from :class:`~livemod.dlfl.arrays.MeshArrays`;
* ``camera``: the orbit camera (fit, presets, ortho), numpy only;
* ``text``, ``hud``, ``controls``: glyph atlas and layout, HUD/help/error overlays,
  key bindings and the selection echo, all GL-free;
* ``renderer``: one :class:`Renderer` for the window and offscreen rendering, with
  integer-id picking; ``mesh_passes`` holds its programs and each element's draw;
* ``headless``: standalone EGL rendering, turntables, PNG/GIF output;
* ``window``: the moderngl-window ``WindowConfig`` over the runner's ``LiveSession``
  (``script_session``: the script and its session; ``painter``: each frame);
* ``cli``: the ``view`` and ``render`` subcommands.
"""
