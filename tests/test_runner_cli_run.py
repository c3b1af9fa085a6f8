"""``livemod run``: what a script does to the process cannot move its output, end
the command, or keep it from exiting (issue 30, sections 2 and 3)."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from livemod.dlfl.io import load_mesh
from livemod.runner import cli

from .runner_scripts.support import WAIT, vertices_script, wait_until, write_by_rename

LIVEMOD = [sys.executable, "-m", "livemod"]
# a child's Python finds this tree first, as the tests' own does
ENV = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}


def _livemod(*args: str, cwd: str, timeout: float = WAIT * 3) -> subprocess.CompletedProcess:
    """Run ``livemod ARGS`` in ``cwd``; the timeout is a wait, not a measure."""
    return subprocess.run([*LIVEMOD, *args], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout, env=ENV)


def test_run_writes_its_output_where_it_was_named_when_the_script_changes_folder(
        tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "elsewhere").mkdir()
    (tmp_path / "moving.py").write_text("import os\nos.chdir('elsewhere')\n"
                                        + vertices_script(2))
    assert cli.main(["run", "moving.py", "-o", "out.obj"]) == 0
    assert "wrote out.obj" in capsys.readouterr().out
    assert load_mesh(str(tmp_path / "out.obj")).counts()[0] == 2
    assert not (tmp_path / "elsewhere" / "out.obj").exists()
    assert os.getcwd() == str(tmp_path)


@pytest.mark.timeout(120)
def test_run_exits_once_written_though_the_script_left_a_thread_running(tmp_path):
    (tmp_path / "threads.py").write_text(
        "import threading\n"
        "threading.Thread(target=threading.Event().wait, name='waiter').start()\n"
        + vertices_script(2))
    done = _livemod("run", "threads.py", "-o", "out.obj", cwd=str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert "wrote out.obj" in done.stdout
    assert load_mesh(str(tmp_path / "out.obj")).counts()[0] == 2
    assert "livemod: note: the script left 1 thread running (waiter)" in done.stderr


@pytest.mark.timeout(120)
def test_os_exit_in_a_script_fails_the_run_with_a_message(tmp_path):
    (tmp_path / "exits.py").write_text("import os\ncreateVertex((0, 0, 0))\nos._exit(3)\n")
    done = _livemod("run", "exits.py", "-o", "out.obj", cwd=str(tmp_path))
    assert done.returncode == 1
    assert "exits.py:3: ProcessExit: os._exit(3)" in done.stderr
    assert not (tmp_path / "out.obj").exists()


@pytest.mark.timeout(120)
def test_os_exit_in_a_watched_script_does_not_end_the_watch(tmp_path):
    (tmp_path / "exits.py").write_text("import os\nos._exit(3)\n")
    done = _livemod("run", "--watch", "exits.py", "--max-runs", "1", cwd=str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert "run 1: " in done.stderr and "os._exit(3)" in done.stderr


@pytest.mark.timeout(120)
def test_a_script_that_closes_standard_output_does_not_end_the_watch(tmp_path):
    (tmp_path / "closes.py").write_text("import os\nos.close(1)\nos.close(2)\n"
                                        + vertices_script(2))
    done = _livemod("run", "--watch", "closes.py", "--max-runs", "1", cwd=str(tmp_path))
    assert done.returncode == 0, done.stderr
    assert done.stdout.startswith("run 1: ok, 2 steps, V=2")


@pytest.mark.timeout(120)
def test_run_watch_says_a_run_goes_on_in_the_background(tmp_path):
    script = tmp_path / "model.py"
    marker = tmp_path / "started"
    script.write_text(f"open({str(marker)!r}, 'w').close()\nimport time\ntime.sleep(10**6)\n")
    proc = subprocess.Popen([*LIVEMOD, "run", "--watch", str(script), "--max-runs", "1"],
                            cwd=str(tmp_path), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True, env=ENV)
    try:
        wait_until(marker.exists, timeout=WAIT * 3)
        write_by_rename(str(script), vertices_script(2))
        out, err = proc.communicate(timeout=WAIT * 3)
    finally:
        proc.kill()
        proc.wait()
    assert proc.returncode == 0, err
    assert out.startswith("run 2: ok, 2 steps, V=2")
    assert ("livemod: note: run 1 did not stop when asked; it goes on in the "
            "background, and its result will be discarded") in err

