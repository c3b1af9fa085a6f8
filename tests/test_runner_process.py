"""A run leaves the process as it found it (issue 30, section 3): headless, each
run gives back what its script changed; in a live session each run starts from
the state the first run saw."""

from __future__ import annotations

import contextlib
import os
import sys
import warnings

import pytest

import livemod.dlfl
from livemod.dlfl.errors import DLFLRepairWarning
from livemod.dlfl.io import load_mesh
from livemod.dlfl.mesh import Mesh
from livemod.runner import execute

from .runner_scripts.support import manual_session, next_result, vertex_count, vertices_script

# two triangles whose shared edge runs the same way in both: loading repairs it
FLIPPED_OBJ = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf 2 3 4\n"


def _run(tmp_path, text: str, name: str = "model.py"):  # noqa: ANN001, ANN202
    script = tmp_path / name
    script.write_text(text)
    return execute(str(script))


@contextlib.contextmanager
def _session_of(tmp_path, first: str, **options):  # noqa: ANN001, ANN003, ANN202
    """``(session, rerun)``: a session whose first run ran ``first``;
    ``rerun(text)`` saves the script and returns the next result."""
    script = tmp_path / "model.py"
    script.write_text(first)
    with manual_session(script, **options) as (live, notifier):
        first_result = next_result(live)
        assert first_result.status == "ok", first_result.error

        def rerun(text: str):  # noqa: ANN202
            script.write_text(text)
            notifier.fire(str(script))
            return next_result(live)

        yield live, rerun


# -- the working directory -----------------------------------------------------------


def test_a_script_that_changes_folder_leaves_the_working_directory_as_it_was(tmp_path):
    (tmp_path / "elsewhere").mkdir()
    before = os.getcwd()
    outcome = _run(tmp_path, f"import os\nos.chdir({str(tmp_path / 'elsewhere')!r})\n"
                             "createVertex((0, 0, 0))\n")
    assert outcome.status == "ok"
    assert os.getcwd() == before


def test_a_failing_script_that_changes_folder_leaves_it_as_it_was_too(tmp_path):
    before = os.getcwd()
    outcome = _run(tmp_path, f"import os\nos.chdir({str(tmp_path)!r})\n1 / 0\n")
    assert outcome.status == "error" and outcome.error is not None
    assert outcome.error.message.startswith("ZeroDivisionError")
    assert os.getcwd() == before


@pytest.mark.timeout(60)
def test_run_watch_output_stays_where_it_was_named_when_a_run_changes_folder(
        tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "elsewhere").mkdir()
    moving = "import os\nos.chdir('elsewhere')\n" + vertices_script(2)
    with _session_of(tmp_path, moving, output="out.obj") as (_, rerun):
        assert vertex_count(rerun(moving + "createVertex((9, 9, 9))\n")) == 3
    assert load_mesh(str(tmp_path / "out.obj")).counts()[0] == 3
    assert not (tmp_path / "elsewhere" / "out.obj").exists()
    assert os.getcwd() == str(tmp_path)


@pytest.mark.timeout(60)
def test_a_folder_the_host_changes_to_between_runs_stands(tmp_path, monkeypatch):
    (tmp_path / "host").mkdir()
    with _session_of(tmp_path, vertices_script(1)) as (_, rerun):
        monkeypatch.chdir(tmp_path / "host")  # the host's own doing, not a script's
        assert vertex_count(rerun("import os\nos.chdir('..')\n" + vertices_script(2))) == 2
        assert os.getcwd() == str(tmp_path / "host")


# -- warnings, streams, recursion limit --------------------------------------------------


def test_warning_filters_are_given_back(tmp_path):
    before = list(warnings.filters)
    outcome = _run(tmp_path, "import warnings\nwarnings.simplefilter('ignore')\n"
                             "warnings.filterwarnings('error', 'x')\n")
    assert outcome.status == "ok"
    assert warnings.filters == before


@pytest.mark.timeout(60)
def test_an_error_filter_of_one_run_does_not_fail_the_next_runs_repair(tmp_path):
    (tmp_path / "flipped.obj").write_text(FLIPPED_OBJ)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DLFLRepairWarning)  # what the session starts from
        strict = "import warnings\nwarnings.simplefilter('error')\n" + vertices_script(1)
        with _session_of(tmp_path, strict) as (_, rerun):
            repaired = rerun("load('flipped.obj')\n")
            assert repaired.status == "ok", repaired.error
            assert repaired.arrays is not None and repaired.arrays.counts[2] >= 2


def test_replaced_standard_streams_are_given_back(tmp_path):
    streams = sys.stdin, sys.stdout, sys.stderr
    outcome = _run(tmp_path, "import io, sys\nsys.stdout = io.StringIO()\n"
                             "sys.stderr = io.StringIO()\nsys.stdin = io.StringIO()\n")
    assert outcome.status == "ok"
    assert (sys.stdin, sys.stdout, sys.stderr) == streams


@pytest.mark.timeout(60)
def test_a_run_that_hides_standard_output_does_not_hide_the_next_runs_prints(
        tmp_path, capsys):
    hiding = "import io, sys\nsys.stdout = io.StringIO()\nprint('hidden')\n"
    with _session_of(tmp_path, hiding) as (_, rerun):
        assert rerun("print('shown')\n").status == "ok"
    assert capsys.readouterr().out.splitlines() == ["shown"]


def test_a_closed_standard_output_is_open_again_after_the_run(tmp_path, monkeypatch):
    with open(tmp_path / "out.txt", "w") as owner:
        # as Python's own sys.stdout: a text stream on a descriptor it does not own
        monkeypatch.setattr(sys, "stdout", open(owner.fileno(), "w", closefd=False))  # noqa: SIM115
        outcome = _run(tmp_path, "import sys\nsys.stdout.close()\n")
        assert outcome.status == "ok"
        print("after", flush=True)  # noqa: T201  (the point: printing works again)
    assert (tmp_path / "out.txt").read_text() == "after\n"


def test_the_recursion_limit_is_given_back(tmp_path):
    before = sys.getrecursionlimit()
    assert _run(tmp_path, "import sys\nsys.setrecursionlimit(80)\n").status == "ok"
    assert sys.getrecursionlimit() == before


def test_environment_variables_are_given_back(tmp_path, monkeypatch):
    monkeypatch.setenv("LIVEMOD_TEST_KEPT", "1")
    monkeypatch.delenv("LIVEMOD_TEST_ADDED", raising=False)
    outcome = _run(tmp_path, "import os\nos.environ['LIVEMOD_TEST_ADDED'] = 'x'\n"
                             "del os.environ['LIVEMOD_TEST_KEPT']\n")
    assert outcome.status == "ok"
    assert os.environ.get("LIVEMOD_TEST_KEPT") == "1"
    assert "LIVEMOD_TEST_ADDED" not in os.environ


# -- livemod's own modules -------------------------------------------------------------------


def test_a_monkeypatched_library_function_and_method_are_given_back(tmp_path):
    load, copy, print_ = livemod.dlfl.load, Mesh.copy, print
    outcome = _run(tmp_path, (
        "import builtins, livemod.dlfl, livemod.dlfl.mesh\n"
        "livemod.dlfl.load = None\n"
        "del livemod.dlfl.createVertex\n"
        "livemod.dlfl.mesh.Mesh.copy = None\n"
        "livemod.dlfl.mesh.Mesh.extra = 1\n"
        "builtins.print = None\n"
    ))
    assert outcome.status == "ok", outcome.error
    assert livemod.dlfl.load is load and Mesh.copy is copy and print is print_
    assert callable(livemod.dlfl.createVertex) and not hasattr(Mesh, "extra")


def test_a_replaced_library_module_is_given_back(tmp_path):
    module = sys.modules["livemod.dlfl"]
    outcome = _run(tmp_path, "import sys\nsys.modules['livemod.dlfl'] = None\n"
                             "del sys.modules['livemod.dlfl.mesh']\n")
    assert outcome.status == "ok"
    assert sys.modules["livemod.dlfl"] is module
    assert sys.modules["livemod.dlfl.mesh"].Mesh is Mesh


@pytest.mark.timeout(60)
def test_a_run_that_breaks_load_does_not_break_the_next_runs(tmp_path):
    breaking = ("import livemod.dlfl\n"
                "def broken(*args):\n    raise RuntimeError('patched')\n"
                "livemod.dlfl.load = broken\n" + vertices_script(1))
    with _session_of(tmp_path, breaking) as (_, rerun):
        cube = rerun("load('cube')\n")
        assert cube.status == "ok", cube.error
        assert cube.arrays is not None and cube.arrays.counts == (8, 12, 6)


# -- os._exit ------------------------------------------------------------------------------


def test_os_exit_in_a_script_ends_the_run_not_the_process(tmp_path):
    outcome = _run(tmp_path, "import os\ncreateVertex((0, 0, 0))\nos._exit(3)\n"
                             "createVertex((1, 0, 0))\n")
    assert outcome.status == "error" and outcome.error is not None
    assert outcome.error.line == 3
    assert "os._exit(3)" in outcome.error.message
    assert len(outcome.steps) == 1


def test_os_exit_0_in_a_script_ends_the_run_as_a_success(tmp_path):
    outcome = _run(tmp_path, "import os\ncreateVertex((0, 0, 0))\nos._exit(0)\n")
    assert outcome.status == "ok" and len(outcome.steps) == 1


def test_os_exit_outside_a_run_is_python_s_own(tmp_path):
    _run(tmp_path, "pass\n")  # the guard is in place from the first run on
    read, write = os.pipe()
    pid = os.fork()
    if pid == 0:  # the child exits at once, by os._exit, with its own status
        os._exit(7)
    os.close(write)
    os.close(read)
    _, status = os.waitpid(pid, 0)
    assert os.waitstatus_to_exitcode(status) == 7


def test_os_exit_in_a_thread_the_run_forks_exits_that_child(tmp_path):
    outcome = _run(tmp_path, (
        "import os\n"
        "pid = os.fork()\n"
        "if pid == 0:\n    os._exit(5)\n"
        "_, status = os.waitpid(pid, 0)\n"
        "assert os.waitstatus_to_exitcode(status) == 5, status\n"
    ))
    assert outcome.status == "ok", outcome.error


def test_the_capturing_io_of_a_run_is_its_own(tmp_path):
    # a script may print into a buffer of its own and read it back
    outcome = _run(tmp_path, (
        "import contextlib, io\nbuffer = io.StringIO()\n"
        "with contextlib.redirect_stdout(buffer):\n    print('x')\n"
        "assert buffer.getvalue() == 'x\\n'\n"
    ))
    assert outcome.status == "ok", outcome.error
