"""The HUD and the error panel (GL-free): what they say, and that it fits the window."""

from __future__ import annotations

from dataclasses import replace
from types import SimpleNamespace

import numpy as np

from livemod.dlfl import mesh_arrays
from livemod.dlfl.shapes import cube
from livemod.runner.errors import syntax_error
from livemod.runner.results import ScriptError
from livemod.viewer.hud import (
    error_lines,
    error_panel,
    hud_lines,
    hud_quads,
    nonfinite_lines,
    run_state,
    step_line,
)
from livemod.viewer.measure import WholeMesh
from livemod.viewer.text import MARGIN, WARN_TEXT
from livemod.viewer.view_state import ViewState

NAMES = ", ".join(f"scheme-{k}" for k in range(38))
NAME_ERROR = ScriptError(
    "exception", "/x/model.py", 4, "NameError: name 'cub' is not defined",
    'Traceback (most recent call last):\n  File "/x/model.py", line 4, in <module>\n'
    "    cub()\nNameError: name 'cub' is not defined\n")


def _texts(lines: list[tuple[str, int]]) -> list[str]:
    return [text for text, _ in lines]


def test_the_error_panel_names_its_run() -> None:
    assert _texts(error_lines(NAME_ERROR, run_id=3)) == [
        "run 3: exception error in model.py:4", "NameError: name 'cub' is not defined",
        "Traceback (most recent call last):", '  File "/x/model.py", line 4, in <module>',
        "    cub()"]


def test_an_error_is_the_previous_runs_while_a_newer_run_works() -> None:
    assert _texts(error_lines(NAME_ERROR, run_id=3, running=4))[0] == \
        "previous run 3: exception error in model.py:4 (run 4 is running)"
    # the run that failed is itself at work no more: not "previous"
    assert _texts(error_lines(NAME_ERROR, run_id=3, running=3))[0] == \
        "run 3: exception error in model.py:4"


def test_a_syntax_error_is_said_once() -> None:
    try:
        compile("x = (\n", "/x/model.py", "exec")
    except SyntaxError as exc:
        error = syntax_error(exc, "/x/model.py")
    texts = _texts(error_lines(error, run_id=2))
    assert texts[0] == "run 2: syntax error in model.py:1"
    assert texts.count("SyntaxError: '(' was never closed") == 1
    assert texts[2:] == ['  File "/x/model.py", line 1', "    x = (", "        ^"]


def _failed(message: str) -> SimpleNamespace:
    error = ScriptError("exception", "/x/model.py", 2, message, f"{message}\n")
    return SimpleNamespace(run_id=5, status="error", error=error, steps=(), step_index=None,
                           arrays=None, partial=None, stale=False, elapsed=0.01)


def test_a_long_message_wraps_inside_the_window() -> None:
    message = f"ValueError: unknown scheme 'doo-sabin-bc'; the schemes are {NAMES}"
    state = ViewState(script="/x/model.py", result=_failed(message), size=(480, 360))
    lines = _texts(error_panel(state))
    assert lines[0] == "run 5: exception error in model.py:2" and len(lines) > 3
    assert " ".join(line.strip() for line in lines[1:]) == message
    quads = hud_quads(state)
    right = quads[:, 0] + quads[:, 3] + quads[:, 5]  # anchor x + offset + width
    assert right.max() <= 480 - MARGIN / 2
    assert np.all(quads[:, 0] >= 0)


def test_no_error_no_panel() -> None:
    result = SimpleNamespace(run_id=1, status="ok", error=None, steps=(), step_index=None,
                             arrays=None, stale=False, elapsed=0.01)
    assert error_panel(ViewState(result=result, size=(400, 300))) == []


def _hud(state: ViewState) -> list[str]:
    from livemod.viewer.hud import hud_lines

    return [text for text, _ in hud_lines(state)]


def _failed_after_steps(good, partial) -> SimpleNamespace:
    steps = tuple(SimpleNamespace(index=i, label=label, line=i + 1, counts=(0, 0, 0),
                                  elapsed=0.0) for i, label in enumerate(("load cube",
                                                                          "subdivide")))
    return SimpleNamespace(run_id=3, status="error", error=NAME_ERROR, steps=steps,
                           step_index=None, arrays=good, partial=partial, stale=True,
                           elapsed=0.02, others=None)


def test_the_counts_and_the_step_say_which_run_they_are_of() -> None:
    from livemod.dlfl import mesh_arrays
    from livemod.dlfl.shapes import cube, tetrahedron

    good, partial = mesh_arrays(cube()), mesh_arrays(tetrahedron())
    result = _failed_after_steps(good, partial)
    state = ViewState(script="/x/model.py", result=result, arrays=good, good_run=2,
                      total_steps=2)
    lines = _hud(state)
    assert "last good mesh (run 2): V 8  E 12  F 6  genus ..." in lines
    assert "failed run 3: step 2/2: subdivide (line 2)" in lines
    unseen = _hud(ViewState(result=result, arrays=good, total_steps=2))  # run 2 never shown
    assert "last good mesh: V 8  E 12  F 6  genus ..." in unseen
    own = _hud(ViewState(result=result, arrays=partial, partial=True, total_steps=2))  # E
    assert "failed run 3: V 4  E 6  F 4  genus ..." in own
    assert "failed run 3: step 2/2: subdivide (line 2)" in own
    cancelled = _hud(ViewState(result=SimpleNamespace(**{**vars(result), "status": "cancelled"}),
                               arrays=good, good_run=2))
    assert "cancelled run 3: step 2/2: subdivide (line 2)" in cancelled
    ok = SimpleNamespace(**{**vars(result), "status": "ok", "error": None, "stale": False})
    plain = _hud(ViewState(result=ok, arrays=good, good_run=3))
    assert "V 8  E 12  F 6  genus ..." in plain and "step 2/2: subdivide (line 2)" in plain


def _result(status: str = "ok", stale: bool = False, step_index: int | None = None):
    steps = tuple(SimpleNamespace(index=i, label=f"op{i}", line=10 + i, counts=(1, 1, 1),
                                  elapsed=0.0) for i in range(3))
    return SimpleNamespace(status=status, stale=stale, steps=steps, step_index=step_index,
                           arrays=mesh_arrays(cube()), elapsed=0.25, error=None, others=None)



def test_hud_shows_state_counts_genus_and_step() -> None:
    assert run_state(None, True) == "running"
    assert run_state(_result(), False, 1.5) == run_state(None, True, 1.5) == "running... 1.5 s"
    assert run_state(_result("error", stale=True), False) == "error, stale"
    assert step_line(_result(step_index=1)) == "step 2/3: op1 (line 11)"
    assert step_line(_result()) == "step 3/3: op2 (line 12)"
    result = _result()
    state = ViewState(script="/x/tower.py", result=result, arrays=result.arrays,
                      whole=WholeMesh(0, 8.0), fps=59.6, selection=("faces(True) == (1,)",))
    text = "\n".join(line for line, _ in hud_lines(state))
    for part in ("tower.py", "ok", "0.250 s", "V 8  E 12  F 6  genus 0  volume 8\n",
                 "step 3/3", "60 fps", "faces(True) == (1,)"):
        assert part in text
    running = "\n".join(line for line, _ in hud_lines(replace(state, working=2.0)))
    assert "running... 2.0 s\n" in running and "0.250 s" not in running  # not the last run's
    missing = hud_lines(replace(state, missing=("picked, not in this mesh: face 12",)))
    assert ("picked, not in this mesh: face 12", WARN_TEXT) in missing
    emptied = hud_lines(replace(state, empty_script="/x/tower.py"))
    assert ("tower.py is empty: showing the last result", WARN_TEXT) in emptied
    hidden = "\n".join(line for line, _ in hud_lines(replace(state, current_hidden=True)))
    assert "volume 8  (hidden: L lists it)" in hidden
    for whole, said in ((None, "genus ...\n"), (WholeMesh(1, None), "genus 1\n"),
                        (WholeMesh(0, -1.5), "genus 0  volume -1.5 (inside out)\n")):
        assert said in "\n".join(line for line, _ in hud_lines(replace(state, whole=whole)))



def test_the_help_overlay_fits_the_window_in_columns() -> None:
    from livemod.viewer.hud import hud_quads

    state = ViewState(script="/x/tower.py", waiting=True, hud=False, help=True)
    boxes = {}
    for height in (2000, 800, 400):
        quads = hud_quads(replace(state, size=(1200, height)))
        assert quads[:, 0].min() >= 0 and (quads[:, 1] + quads[:, 6]).max() <= height
        boxes[height] = int((quads[:, 11] == 8).sum())  # one panel box per column
    assert boxes[2000] == 1 and boxes[800] == 2 and boxes[400] >= 3


def test_the_hud_says_how_many_vertices_are_not_finite() -> None:
    assert nonfinite_lines(0) == []
    assert nonfinite_lines(1)[0][0] == \
        "1 vertex not finite (NaN or inf): left out of the framing"
    assert nonfinite_lines(3)[0][0] == \
        "3 vertices not finite (NaN or inf): left out of the framing"


def test_the_hud_says_which_runs_still_finish_in_the_background() -> None:
    result = _result()
    state = ViewState(script="/x/tower.py", result=result, arrays=result.arrays)
    assert not any("background" in line for line, _ in hud_lines(state))
    lines = hud_lines(replace(state, background=(3,)))
    assert lines[2] == ("run 3 is still finishing in the background", WARN_TEXT)
    several = hud_lines(replace(state, background=(3, 5, 8)))
    assert several[2] == ("runs 3, 5 and 8 are still finishing in the background", WARN_TEXT)
    assert replace(state, background=(3,)) != state  # a new frame's overlay says it
