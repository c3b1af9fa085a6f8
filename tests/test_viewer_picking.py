"""The picking controller (GL-free): pick modes, clicks, and what is said of picks."""

from __future__ import annotations

from livemod.dlfl import mesh_arrays
from livemod.dlfl.scene import Selection
from livemod.dlfl.shapes import cube
from livemod.viewer.controls import PickMode
from livemod.viewer.picking import Picking


def test_pick_modes_cycle_and_are_the_renderers_kind_names() -> None:
    assert [mode.following() for mode in PickMode] == [
        PickMode.EDGE, PickMode.VERTEX, PickMode.CORNER, PickMode.FACE]
    assert PickMode.VERTEX == "vertex" and f"{PickMode.CORNER}" == "corner"
    assert [mode.selection_field for mode in PickMode] == ["faces", "edges", "vertices",
                                                          "corners"]
    picking = Picking(lambda: None, print)
    picking.next_mode()
    assert picking.mode is PickMode.EDGE
    picking.set_mode("corner")
    assert picking.mode is PickMode.CORNER


def test_a_click_selects_adds_and_the_background_clears() -> None:
    picking = Picking(lambda: None, print, Selection(faces=(2,)))
    assert picking.clicked(5, add=False) == Selection(faces=(5,))
    assert picking.clicked(5, add=True) == Selection(faces=(2, 5))
    assert picking.clicked(2, add=True) == Selection()
    assert picking.clicked(None, add=False) == Selection()
    assert picking.clicked(None, add=True) is None  # shift on the background: unchanged
    picking.set_mode(PickMode.VERTEX)
    assert picking.clicked(7, add=True) == Selection(faces=(2,), vertices=(7,))


class FakeSelectionInput:
    def __init__(self) -> None:
        self.given: list = []

    def set_selection(self, selection) -> None:
        self.given.append(selection)


def test_a_selection_goes_to_the_session_measured_and_echoed_as_python() -> None:
    session, said = FakeSelectionInput(), []
    picking = Picking(lambda: session, said.append)
    arrays = mesh_arrays(cube())
    face = int(arrays.face_ids[0])
    picking.select(Selection(faces=(face,)), arrays)
    assert session.given == [Selection(faces=(face,))]
    assert said[0] == f"faces(True) == ({face},)"
    assert said[2].startswith(f"face {face}: 4 sides, area 4, normal ")
    assert picking.measures == said[2:]
    picking.remeasure(None)
    assert picking.measures == []


def test_the_hud_tells_picks_held_from_picks_missing() -> None:
    picking = Picking(lambda: FakeSelectionInput(), print, Selection(faces=(1, 40)))
    arrays = mesh_arrays(cube())
    held, missing = picking.hud_lines(arrays, ("vertices",))
    assert held[0] == "faces(True) == (1,)"
    assert missing == ["picked, not in this mesh: face 40",
                       "verts(True) found nothing picked: M to vertex mode, click a vertex"]
    assert picking.hud_lines(arrays, ())[0] is held  # the same picks: not split again
    picking.forget()
    assert picking.hud_lines(arrays, ("faces",)) == (
        [], ["faces(True) found nothing picked: M to face mode, click a face"])


def _quad_torus_arrays():
    from livemod.dlfl.shapes import torus

    return mesh_arrays(torus(8, 6))


def test_selection_tools_act_on_the_picks_as_topmods_keys_do() -> None:
    from livemod.dlfl import selection as rules

    arrays = _quad_torus_arrays()
    picking = Picking(lambda: None, print, Selection(faces=(5,), edges=(0,)))
    loop = picking.tool("edge_loop", arrays)
    assert loop == Selection(faces=(5,), edges=tuple(rules.edge_loop(arrays, 0)))
    assert len(loop.edges) == 6
    faces = picking.tool("face_loop", arrays).faces
    assert faces == (5, *rules.face_loop(arrays, 0)) and len(faces) == 1 + 8
    assert len(picking.tool("checkerboard", arrays).faces) == 24
    assert picking.tool("similar", arrays).faces == tuple(range(48))  # face mode: all quads
    assert len(picking.tool("grow", arrays).faces) == 5
    assert picking.tool("shrink", arrays).faces == ()
    assert len(picking.tool("invert", arrays).faces) == 47
    picking.set_mode(PickMode.EDGE)
    assert len(picking.tool("grow", arrays).edges) == 7
    assert len(picking.tool("all", arrays).edges) == 96
    assert picking.tool("all", arrays).faces == (5,)  # other kinds stay


def test_a_tool_without_picks_or_a_mesh_says_so_and_changes_nothing() -> None:
    said: list[str] = []
    picking = Picking(lambda: None, said.append, Selection(faces=(40,)))
    arrays = mesh_arrays(cube())
    assert picking.tool("edge_loop", arrays) is None
    assert picking.tool("checkerboard", arrays) is None  # face 40 is not in the cube
    assert picking.tool("grow", None) is None
    picking.set_mode(PickMode.CORNER)
    assert picking.tool("similar", arrays) is None
    assert said == ["edge loop: pick an edge first (M to edge mode, click an edge)",
                    "checkerboard: pick a face first (M to face mode, click a face)",
                    "grow: no mesh shown yet",
                    "similar: corners have no similar ones (pick faces, edges or vertices)"]
    assert picking.selection == Selection(faces=(40,))
