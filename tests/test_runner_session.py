"""LiveSession (livemod.runner.session): the helper modules it watches and a
script a save left empty."""

from __future__ import annotations

import contextlib
import sys

import pytest

from .runner_scripts.support import (
    drain,
    host_imports,
    manual_session,
    next_result,
    settle,
    vertex_count,
    vertices_script,
    wait_until,
    write_in_place,
)

# -- a helper module the host imported before the first run is watched


@pytest.mark.timeout(60)
def test_a_helper_the_host_imported_first_is_watched_by_the_session(tmp_path, monkeypatch):
    host_copy = host_imports(tmp_path, monkeypatch, "helper_seen", "COUNT = 2\n")
    script = tmp_path / "model.py"
    script.write_text("import helper_seen\nfor i in range(helper_seen.COUNT):\n"
                      "    createVertex((i, 0, 0))\n")
    with manual_session(script) as (live, notifier):
        assert vertex_count(next_result(live)) == 2
        (tmp_path / "helper_seen.py").write_text("COUNT = 7  # edited\n")
        notifier.fire(str(tmp_path / "helper_seen.py"))
        assert [vertex_count(r) for r in settle(live)] == [7]
    assert sys.modules["helper_seen"] is host_copy


# -- an emptied script keeps the last result and says so (empty_script)


@contextlib.contextmanager
def _three_vertex_session(tmp_path):  # noqa: ANN001, ANN202
    """``(session, script, notifier)``: a started session on ``model.py``, which
    makes 3 vertices, its first result taken; closed afterwards."""
    script = tmp_path / "model.py"
    script.write_text(vertices_script(3))
    with manual_session(script) as (live, notifier):
        assert vertex_count(next_result(live)) == 3
        yield live, script, notifier


@pytest.mark.timeout(60)
@pytest.mark.parametrize("empty", ["", "  \n\n\t\n"], ids=["no bytes", "whitespace"])
def test_an_emptied_script_keeps_the_last_result_and_says_so(tmp_path, empty):
    with _three_vertex_session(tmp_path) as (live, script, notifier):
        assert live.empty_script is None
        write_in_place(str(script), empty)
        notifier.fire(str(script))
        assert drain(live, quiet=0.5) == []  # nothing runs: the last mesh stays shown
        assert live.empty_script == str(script)
        write_in_place(str(script), vertices_script(4))
        notifier.fire(str(script))
        assert [vertex_count(r) for r in settle(live)] == [4]
        assert live.empty_script is None


@pytest.mark.timeout(60)
def test_an_emptied_script_given_its_old_text_back_is_not_empty_any_more(tmp_path):
    with _three_vertex_session(tmp_path) as (live, script, notifier):
        write_in_place(str(script), "")
        notifier.fire(str(script))
        wait_until(lambda: live.empty_script == str(script))
        write_in_place(str(script), vertices_script(3))  # undone: the same text again
        notifier.fire(str(script))
        wait_until(lambda: live.empty_script is None)
        assert drain(live, quiet=0.5) == []  # the text that shows ran already


@pytest.mark.timeout(60)
def test_a_reload_of_an_emptied_script_runs_it_and_clears_the_state(tmp_path):
    with _three_vertex_session(tmp_path) as (live, script, notifier):
        write_in_place(str(script), "\n")
        notifier.fire(str(script))
        wait_until(lambda: live.empty_script == str(script))
        live.reload()  # asked for: the empty script runs
        result = next_result(live)
        assert result.status == "ok" and result.arrays is None
        assert live.empty_script is None
