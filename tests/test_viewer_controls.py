"""Key bindings, selection editing and the Python echo of a selection (GL-free)."""

from __future__ import annotations

import re
from pathlib import Path

from livemod.dlfl import mesh_arrays
from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import cube
from livemod.viewer.controls import (
    KEY_BINDINGS,
    action_for,
    help_lines,
    missing_lines,
    selection_python,
    split_picks,
    toggle_pick,
)


def test_keys_cover_the_issue_and_are_unique() -> None:
    actions = {b.action for b in KEY_BINDINGS}
    needed = {"toggle_edges", "toggle_vertices", "labels_faces", "labels_edges",
              "labels_vertices", "labels_selected", "toggle_preview", "toggle_ortho",
              "play_pause", "step_forward", "step_back", "run_to_end", "reload",
              "screenshot", "help", "fit", "view_front", "view_top", "view_side", "view_iso",
              "next_pick_mode"}
    assert needed <= actions
    keys = [(b.key, b.modifiers) for b in KEY_BINDINGS]
    assert len(keys) == len(set(keys))
    assert action_for("F", shift=False, ctrl=True) == "labels_faces"
    assert action_for("F", shift=True, ctrl=False) == "pick_face"
    assert action_for("F", shift=False, ctrl=False) == "fit"
    assert len(help_lines()) > len(KEY_BINDINGS)



def test_click_and_shift_click_edit_the_selection() -> None:
    sel = toggle_pick(Selection(edges=(4,)), "face", 12, add=False)
    assert sel == Selection(faces=(12,))
    sel = toggle_pick(sel, "face", 31, add=True)
    assert sel.faces == (12, 31)
    assert toggle_pick(sel, "face", 12, add=True).faces == (31,)



def test_selection_echo_is_python() -> None:
    arrays = mesh_arrays(cube())
    corner = int(arrays.corner_ids[5])
    lines = selection_python(Selection(faces=(12, 31), vertices=(2,), corners=(corner,)),
                             arrays)
    assert lines[0] == "faces(True) == (12, 31)"
    assert lines[1] == "verts(True) == (2,)"
    face = int(arrays.face_ids[arrays.corner_face[5]])
    vertex = int(arrays.vertex_ids[arrays.corner_vertex[5]])
    assert lines[2] == f"corners(True) == (({face}, {vertex}),)"
    assert lines[3] == (f"(headless: livemod run|render|batch SCRIPT --select faces=12,31 "
                        f"--select verts=2 --select corners={corner})")
    assert selection_python(Selection(), arrays) == ["faces(True) == ()"]



def test_picks_the_mesh_lacks_are_told_apart() -> None:
    arrays = mesh_arrays(cube())  # faces 0-5, vertices 0-7
    picked = Selection(faces=(5, 12, 2), edges=(40,), vertices=(7,))
    present, missing = split_picks(picked, arrays)
    assert present == Selection(faces=(5, 2), vertices=(7,))  # in pick order
    assert missing == Selection(faces=(12,), edges=(40,))
    assert missing_lines(missing) == ["picked, not in this mesh: face 12; edge 40"]
    assert missing_lines(Selection(faces=(8, 9), vertices=(20,))) == [
        "picked, not in this mesh: faces 8, 9; vertex 20"]
    assert missing_lines(Selection()) == []
    assert split_picks(picked, None) == (picked, Selection())  # no mesh: nothing to tell



def _documented_keys() -> list[str]:
    """The keys of the rows of the key table of docs/viewer.md (``| `H`, `F1` | ...``)."""
    doc = (Path(__file__).resolve().parent.parent / "docs" / "viewer.md").read_text()
    table = doc.split("| Key | Does |", 1)[1].split("\n\n", 1)[0]
    rows = [line.split(" | ", 1)[0] for line in table.splitlines() if line.startswith("| `")]
    return [key for row in rows for key in re.findall(r"`([^`]+)`", row)]


def test_the_key_table_of_the_docs_lists_every_binding_and_no_other_key() -> None:
    documented = _documented_keys()
    bound = [binding.label() for binding in KEY_BINDINGS]
    missing = [key for key in bound if key not in documented]
    assert not missing, f"keys without a row in the key table of docs/viewer.md: {missing}"
    unbound = [key for key in documented if key not in bound]
    assert not unbound, f"rows of docs/viewer.md's key table for keys not bound: {unbound}"
