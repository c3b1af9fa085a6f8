"""The window's actions by name: the one table every key binding resolves through.

:data:`~livemod.viewer.controls.KEY_BINDINGS` names an action for each key;
:func:`window_actions` maps every action name to the controller method that does
it. The window checks its table with :func:`check_bindings` when it opens, so a
binding without a handler fails there (and in the tests), never at a key press.
To add a key: a :class:`~livemod.viewer.controls.Binding`, an entry here, a line
in docs/viewer.md.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from functools import partial
from typing import TYPE_CHECKING

from livemod.dlfl.scene import Selection

from .controls import KEY_BINDINGS, Binding, PickMode
from .look import TOGGLED_FIELDS
from .picking import SELECTION_TOOLS

if TYPE_CHECKING:
    from .window import LiveViewer

Action = Callable[[], object]

LABEL_KINDS = ("faces", "edges", "vertices")
PRESET_NAMES = ("front", "top", "side", "iso")


def window_actions(viewer: LiveViewer) -> dict[str, Action]:
    """The action table of ``viewer``: action name -> what it does."""
    look, stepping, picking = viewer.look, viewer.stepping, viewer.picking
    objects, section, camera = viewer.objects, viewer.section, viewer.camera
    return {
        "help": look.toggle_help,
        "toggle_hud": look.toggle_hud,
        **{f"toggle_{name}": partial(look.toggle, name) for name in TOGGLED_FIELDS},
        "toggle_background": look.toggle_background,
        **{f"labels_{kind}": partial(look.toggle_labels, kind) for kind in LABEL_KINDS},
        "labels_selected": look.toggle_labels_selected,
        "toggle_ortho": camera.toggle_ortho,
        "fit": viewer.display.fit,
        **{f"view_{name}": partial(camera.preset, name) for name in PRESET_NAMES},
        "play_pause": stepping.play_pause,
        "step_forward": stepping.step_forward,
        "step_back": stepping.step_back,
        "first_step": stepping.first_step,
        "run_to_end": stepping.run_to_end,
        "faster": stepping.faster,
        "slower": stepping.slower,
        "reload": stepping.reload,
        "toggle_partial": lambda: viewer.display.toggle_partial(viewer.runs.result),
        "preview_mode": viewer.smoothing.toggle_mode,
        "preview_denser": partial(viewer.smoothing.change_density, 1),
        "preview_coarser": partial(viewer.smoothing.change_density, -1),
        "cycle_others": objects.cycle,
        "toggle_object_list": objects.toggle_list,
        "cycle_section": section.cycle,
        "section_back": partial(section.move, -1),
        "section_forward": partial(section.move, 1),
        "screenshot": viewer.save_screenshot,
        "screenshot_transparent": partial(viewer.save_screenshot, transparent=True),
        "next_pick_mode": picking.next_mode,
        **{f"pick_{mode}": partial(picking.set_mode, mode) for mode in PickMode},
        "clear_selection": partial(viewer.set_selection, Selection()),
        **{f"select_{name}": partial(use_tool, viewer, name) for name in SELECTION_TOOLS},
        "copy_parameters": partial(viewer.parameters.copy, viewer.clipboard),
        "quit": viewer.wnd.close,
    }


def use_tool(viewer: LiveViewer, name: str) -> None:
    """Apply TopMod's selection tool ``name`` to the picks on the mesh shown."""
    selection = viewer.picking.tool(name, viewer.renderer.arrays)
    if selection is not None:
        viewer.set_selection(selection)


def check_bindings(actions: Mapping[str, Action],
                   bindings: Iterable[Binding] = KEY_BINDINGS) -> None:
    """Make sure every binding's action has a handler in ``actions``.

    Raises:
        LookupError: the actions no handler does, with the keys bound to them.
    """
    missing = [f"{binding.label()}: {binding.action}" for binding in bindings
               if binding.action not in actions]
    if missing:
        raise LookupError(f"key bindings with no handler: {', '.join(missing)}")
