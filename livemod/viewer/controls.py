"""Key bindings, selection editing and the Python echo of a selection (GL-free).

Keys are named as moderngl-window names them (``"W"``, ``"SPACE"``, ``"NUMBER_1"``,
``"F12"``), so the bindings are independent of the window backend; the help
overlay is generated from :data:`KEY_BINDINGS`, and the key table of
docs/viewer.md is written by hand and checked against it, row by row
(``tests/test_viewer_controls.py``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, replace
from enum import StrEnum

import numpy as np

from livemod.dlfl.arrays import MeshArrays
from livemod.dlfl.scene import SELECTION_READERS, Selection


class PickMode(StrEnum):
    """What a click picks. A ``str`` too: ``PickMode.FACE == "face"``, the kind
    names the renderer's pick pass takes."""

    FACE = "face"
    EDGE = "edge"
    VERTEX = "vertex"
    CORNER = "corner"

    def following(self) -> PickMode:
        """The mode ``M`` goes to from this one: face > edge > vertex > corner > face."""
        modes = list(PickMode)
        return modes[(modes.index(self) + 1) % len(modes)]

    @property
    def selection_field(self) -> str:
        """The :class:`~livemod.dlfl.scene.Selection` field this mode's picks go to."""
        return "vertices" if self is PickMode.VERTEX else f"{self.value}s"


@dataclass(frozen=True)
class Binding:
    """One key: ``key`` name, required ``modifiers`` ("", "shift", "ctrl"), action."""

    key: str
    modifiers: str
    action: str
    help: str

    def label(self) -> str:
        """How the help overlay names the key, e.g. ``Ctrl+F``."""
        name = {"NUMBER_1": "1", "NUMBER_2": "2", "NUMBER_3": "3", "NUMBER_4": "4",
                "SPACE": "Space", "RIGHT": "Right", "LEFT": "Left", "PERIOD": ".",
                "COMMA": ",", "END": "End", "HOME": "Home", "ESCAPE": "Esc", "TAB": "Tab",
                "LEFT_BRACKET": "[", "RIGHT_BRACKET": "]", "MINUS": "-",
                "EQUAL": "=", "PAGE_UP": "PgUp", "PAGE_DOWN": "PgDn"}.get(self.key, self.key)
        prefix = {"": "", "shift": "Shift+", "ctrl": "Ctrl+"}[self.modifiers]
        return prefix + name


KEY_BINDINGS: tuple[Binding, ...] = (
    Binding("H", "", "help", "show or hide this help"),
    Binding("F1", "", "help", "show or hide this help"),
    Binding("U", "", "toggle_hud", "show or hide the HUD"),
    Binding("S", "", "toggle_faces", "solid faces on/off"),
    Binding("W", "", "toggle_edges", "wireframe (edges) on/off"),
    Binding("V", "", "toggle_vertices", "vertices on/off"),
    Binding("P", "", "toggle_preview", "smoothed preview (TopMod's patches) on/off"),
    Binding("P", "shift", "preview_mode", "preview: TopMod's patches / Catmull-Clark limit"),
    Binding("PAGE_UP", "", "preview_denser", "a denser patch preview"),
    Binding("PAGE_DOWN", "", "preview_coarser", "a coarser patch preview"),
    Binding("A", "", "toggle_others", "the scene's other objects on/off"),
    Binding("TAB", "", "cycle_others", "the other objects one at a time, then all again"),
    Binding("L", "", "toggle_object_list",
            "the object list: tick or untick each object to show or hide it"),
    Binding("X", "", "toggle_grid", "ground grid and axes on/off"),
    Binding("C", "", "cycle_section",
            "section: cut the meshes at a plane across x, then y, then z, then off"),
    Binding("LEFT_BRACKET", "", "section_back", "move the section plane back (1/20 of the size)"),
    Binding("RIGHT_BRACKET", "", "section_forward",
            "move the section plane forward (1/20 of the size)"),
    Binding("B", "", "toggle_background", "dark / light background"),
    Binding("K", "", "toggle_colors", "faces in their own colours / the flat modelling colour"),
    Binding("N", "", "toggle_smooth",
            "flat / smooth shading (edges between faces over 45 degrees apart stay sharp)"),
    Binding("F", "ctrl", "labels_faces", "face id labels on/off"),
    Binding("E", "ctrl", "labels_edges", "edge id labels on/off"),
    Binding("V", "ctrl", "labels_vertices", "vertex id labels on/off"),
    Binding("D", "", "labels_selected", "labels: all / selected only"),
    Binding("O", "", "toggle_ortho", "orthographic / perspective"),
    Binding("F", "", "fit", "fit the mesh in the view"),
    Binding("NUMBER_1", "", "view_front", "front view"),
    Binding("NUMBER_2", "", "view_top", "top view"),
    Binding("NUMBER_3", "", "view_side", "side view"),
    Binding("NUMBER_4", "", "view_iso", "iso view"),
    Binding("SPACE", "", "play_pause", "play the steps / pause"),
    Binding("RIGHT", "", "step_forward", "next step (held: steps on)"),
    Binding("PERIOD", "", "step_forward", "next step"),
    Binding("LEFT", "", "step_back", "previous step"),
    Binding("COMMA", "", "step_back", "previous step"),
    Binding("HOME", "", "first_step", "go to the first step"),
    Binding("END", "", "run_to_end", "run to the end"),
    Binding("MINUS", "", "slower", "halve the play rate (steps a second)"),
    Binding("EQUAL", "", "faster", "double the play rate (steps a second)"),
    Binding("G", "", "run_to_end", "run to the end"),
    Binding("R", "", "reload", "re-run the script now"),
    Binding("E", "", "toggle_partial",
            "after an error: the mesh as the failed run left it / the last good one"),
    Binding("F12", "", "screenshot", "save a screenshot (PNG, no HUD)"),
    Binding("F12", "shift", "screenshot_transparent",
            "save a screenshot with a transparent background (PNG with alpha)"),
    Binding("M", "", "next_pick_mode", "pick mode: face > edge > vertex > corner"),
    Binding("F", "shift", "pick_face", "pick faces"),
    Binding("E", "shift", "pick_edge", "pick edges"),
    Binding("V", "shift", "pick_vertex", "pick vertices"),
    Binding("C", "shift", "pick_corner", "pick corners"),
    Binding("ESCAPE", "", "clear_selection", "clear the selection"),
    Binding("L", "shift", "select_edge_loop",
            "edge loops of the picked edges (on through valence-4 vertices)"),
    Binding("R", "shift", "select_edge_ring", "edge rings of the picked edges (across quads)"),
    Binding("P", "ctrl", "select_face_loop", "add the face loops across the picked edges"),
    Binding("K", "shift", "select_checkerboard", "checkerboard from the picked faces"),
    Binding("S", "shift", "select_similar",
            "similar: faces of the picked sizes, edges of their end valences, vertices of "
            "their valences (the pick mode's kind)"),
    Binding("A", "shift", "select_similar_area", "faces of the picked faces' areas (+-0.05)"),
    Binding("EQUAL", "ctrl", "select_grow", "grow the picks (the pick mode's kind)"),
    Binding("MINUS", "ctrl", "select_shrink", "shrink the picks (the pick mode's kind)"),
    Binding("I", "ctrl", "select_invert", "invert the picks (the pick mode's kind)"),
    Binding("A", "ctrl", "select_all", "pick everything of the pick mode's kind"),
    Binding("C", "ctrl", "copy_parameters", "copy the parameter values as param(...) lines"),
    Binding("Q", "", "quit", "close the window"),
)

MOUSE_HELP: tuple[tuple[str, str], ...] = (
    ("Left drag", "orbit"),
    ("Right / middle drag, Shift+left drag", "pan"),
    ("Wheel", "zoom"),
    ("Click", "select (in the pick mode)"),
    ("Shift+click", "add to / remove from the selection"),
    ("Drop a file", "open a script (.py) or a mesh"),
)


def action_for(key: str, shift: bool, ctrl: bool) -> str | None:
    """The action bound to ``key`` with these modifiers, or None."""
    modifiers = "ctrl" if ctrl else ("shift" if shift else "")
    for binding in KEY_BINDINGS:
        if binding.key == key and binding.modifiers == modifiers:
            return binding.action
    return None


def help_lines() -> list[str]:
    """The help overlay: one line per key binding, then the mouse."""
    keys_of: dict[str, list[str]] = {}
    help_of: dict[str, str] = {}
    for binding in KEY_BINDINGS:  # keys sharing an action share a line
        keys_of.setdefault(binding.action, []).append(binding.label())
        help_of.setdefault(binding.action, binding.help)
    lines = ["Keys"]
    lines += [f"  {', '.join(keys)}\t{help_of[action]}" for action, keys in keys_of.items()]
    lines.append("Mouse")
    lines += [f"  {what}: {does}" for what, does in MOUSE_HELP]
    return lines


def toggle_pick(selection: Selection, mode: PickMode, element_id: int,
                add: bool) -> Selection:
    """The selection after clicking ``element_id`` in pick ``mode``.

    A plain click selects only that element (clicking it again keeps it); with
    ``add`` (shift) the element is added, or removed if it was selected.
    """
    name = PickMode(mode).selection_field
    current: tuple[int, ...] = getattr(selection, name)
    if not add:
        return replace(Selection(), **{name: (element_id,)})
    if element_id in current:
        return replace(selection, **{name: tuple(i for i in current if i != element_id)})
    return replace(selection, **{name: (*current, element_id)})


def section_text(section: tuple[int, float] | None) -> str:
    """How the HUD names a :attr:`Style.section`: ``x <= 0.25`` (what is kept), or ``off``."""
    if section is None:
        return "off"
    return f"{'xyz'[section[0]]} <= {section[1]:.4g}"


def selection_python(selection: Selection, arrays: MeshArrays | None) -> list[str]:
    """The selection as the Python a script would see, e.g. ``faces(True) == (12, 31)``,
    then the ``--select`` options that give it to a headless run.

    Corners are shown as ``(faceid, vertexid)`` pairs, as ``corners(True)`` returns
    (and by corner id in the options).
    """
    lines = []
    for call, ids in (("faces", selection.faces), ("edges", selection.edges),
                      ("verts", selection.vertices)):
        if ids:
            lines.append(f"{call}(True) == {tuple(ids)!r}")
    if selection.corners:
        pairs = tuple(_corner_pair(arrays, c) for c in selection.corners)
        lines.append(f"corners(True) == {pairs!r}")
    if not lines:
        return ["faces(True) == ()"]
    return [*lines, f"(headless: livemod run|render|batch SCRIPT {selection.options()})"]


_ARRAY_IDS = {"faces": "face_ids", "edges": "edge_ids", "vertices": "vertex_ids",
              "corners": "corner_ids"}


def split_picks(selection: Selection, arrays: MeshArrays | None,
                ) -> tuple[Selection, Selection]:
    """``(present, missing)``: the picks ``arrays`` holds and those it lacks (a later
    run removed them, or the step shown comes before they were made). Without
    arrays nothing can be told missing."""
    if arrays is None or selection.is_empty():
        return selection, Selection()
    present, missing = {}, {}
    for name, table in _ARRAY_IDS.items():
        ids: tuple[int, ...] = getattr(selection, name)
        held = np.isin(np.asarray(ids, dtype=np.int64), getattr(arrays, table)) if ids else ()
        present[name] = tuple(i for i, ok in zip(ids, held, strict=True) if ok)
        missing[name] = tuple(i for i, ok in zip(ids, held, strict=True) if not ok)
    return Selection(**present), Selection(**missing)


_KIND = {mode.selection_field: mode.value for mode in PickMode}


def unpicked_lines(unselected: Sequence[str], selection: Selection) -> list[str]:
    """The HUD's note for each selection field in ``unselected`` (those a run's
    ``faces(True)`` and the like found empty) that ``selection`` still has nothing
    of, e.g. ``faces(True) found nothing picked: M to face mode, click a face``."""
    return [f"{SELECTION_READERS[field]}(True) found nothing picked: M to {_KIND[field]} mode, "
            f"click a {_KIND[field]}"
            for field in unselected if not getattr(selection, field)]


def missing_lines(missing: Selection) -> list[str]:
    """The HUD's note of picks the mesh shown lacks, e.g. ``picked, not in this
    mesh: faces 12, 31`` (a run's ``faces(True)`` returns what the mesh holds when
    it is called, so one that removed its picks, as ``rind`` does, got them)."""
    parts = []
    for name in _ARRAY_IDS:
        ids: tuple[int, ...] = getattr(missing, name)
        if ids:
            kind = name if len(ids) > 1 else {"vertices": "vertex"}.get(name, name[:-1])
            parts.append(f"{kind} {', '.join(str(i) for i in ids)}")
    return [f"picked, not in this mesh: {'; '.join(parts)}"] if parts else []


def _corner_pair(arrays: MeshArrays | None, corner_id: int) -> tuple[int, int]:
    """``(faceid, vertexid)`` of a corner id (``(-1, -1)`` if it is not in ``arrays``)."""
    if arrays is None:
        return (-1, -1)
    where = np.flatnonzero(arrays.corner_ids == corner_id)
    if len(where) == 0:
        return (-1, -1)
    dense = int(where[0])
    return (int(arrays.face_ids[arrays.corner_face[dense]]),
            int(arrays.vertex_ids[arrays.corner_vertex[dense]]))
