"""execute / run_script: namespace, steps, errors, determinism, cancellation."""

from __future__ import annotations

import ctypes
import importlib
import os
import sys
import threading
import time

import numpy as np
import pytest

from livemod.dlfl.scene import Selection, current_scene, default_scene
from livemod.runner import Cancelled, RunControl, execute, run_script
from livemod.runner.execute import interrupt_user_code
from livemod.runner.instrument import compile_script
from livemod.runner.process import ProcessState

from .runner_scripts.support import host_imports, same_mesh, script_path, wait_until

execute_module = importlib.import_module("livemod.runner.execute")


def write(tmp_path, name: str, text: str) -> str:
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return str(path)


def test_steps_record_label_line_and_counts():
    result = run_script(script_path("cube_steps.py"))
    assert result.status == "ok", result.error
    labels = [s.label for s in result.steps]
    assert labels[0] == "cube" and labels[-1] == "done"
    assert labels[1:3] == ["subdivideEdge", "move"]
    assert [s.line for s in result.steps[:3]] == [11, 14, 15]
    assert result.steps[0].counts == (8, 12, 6)
    assert [s.index for s in result.steps] == list(range(len(result.steps)))
    elapsed = [s.elapsed for s in result.steps]
    assert elapsed == sorted(elapsed)
    assert result.arrays is not None and result.arrays.counts == result.steps[-1].counts


def test_result_arrays_are_read_only_copies():
    result = run_script(script_path("cube_steps.py"))
    assert result.arrays is not None
    assert not result.arrays.positions.flags.writeable
    with pytest.raises(ValueError):
        result.arrays.positions[0, 0] = 5.0


def test_the_scripts_own_helper_wins_over_a_same_named_module_earlier_on_the_path(
        tmp_path, monkeypatch):
    elsewhere, project = tmp_path / "elsewhere", tmp_path / "project"
    elsewhere.mkdir()
    project.mkdir()
    (elsewhere / "shapes_helper.py").write_text("WHO = 'elsewhere'\n")
    (project / "shapes_helper.py").write_text("WHO = 'project'\n")
    # the project folder is on the path already, but after the other one
    monkeypatch.setattr(sys, "path", [str(elsewhere), *sys.path, str(project)])
    monkeypatch.delitem(sys.modules, "shapes_helper", raising=False)
    path = write(project, "main.py", (
        "import shapes_helper\n"
        "from livemod.dlfl import current_run\n"
        "current_run().parameters['who'] = shapes_helper.WHO\n"))
    outcome = execute(path)
    assert outcome.status == "ok", outcome.error
    assert outcome.run.parameters["who"] == "project"
    assert sys.path[0] == str(elsewhere) and sys.path[-1] == str(project)  # as it was


def test_namespace_has_commands_file_and_name(tmp_path):
    path = write(tmp_path, "ns.py", (
        "from livemod.dlfl import current_run\n"
        "current_run().parameters['seen'] = (__name__, __file__, callable(createFace))\n"
        "import sys, os\n"
        "current_run().parameters['on_path'] = os.path.dirname(__file__) in sys.path\n"))
    outcome = execute(path)
    assert outcome.status == "ok", outcome.error
    assert outcome.run.parameters["seen"] == ("__main__", path, True)
    assert outcome.run.parameters["on_path"] is True
    assert str(tmp_path) not in sys.path


def test_each_run_has_its_own_scene(tmp_path):
    path = write(tmp_path, "one.py", "createVertex((0, 0, 0))\n")
    before = default_scene().objects.copy()
    first, second = execute(path), execute(path)
    assert first.scene is not second.scene
    assert first.scene.mesh.counts() == second.scene.mesh.counts() == (1, 0, 1)
    assert default_scene().objects == before and current_scene() is default_scene()


def test_seeded_runs_are_identical_and_seed_matters():
    a = run_script(script_path("cube_steps.py"), seed=7)
    b = run_script(script_path("cube_steps.py"), seed=7)
    c = run_script(script_path("cube_steps.py"), seed=8)
    assert same_mesh(a.arrays, b.arrays)
    assert a.arrays is not None and c.arrays is not None
    assert not np.allclose(a.arrays.positions, c.arrays.positions)


def test_numpy_random_is_seeded(tmp_path):
    path = write(tmp_path, "np_rand.py", (
        "import numpy as np\ncreateVertex(tuple(np.random.random(3)))\n"))
    a, b = run_script(path, seed=3), run_script(path, seed=3)
    assert same_mesh(a.arrays, b.arrays)


def test_parameters_are_globals_and_run_parameters():
    result = run_script(script_path("uses_params.py"), parameters={"count": 5, "height": 2.0})
    assert result.arrays is not None and result.arrays.counts == (5, 0, 5)
    assert np.allclose(result.arrays.positions[:, 1], 2.0)
    assert result.values == (("count", 5), ("height", 2.0))


def test_selection_is_what_faces_true_returns():
    outcome = execute(script_path("selected_faces.py"), selection=Selection(faces=(3, 5)))
    assert outcome.status == "ok", outcome.error
    assert outcome.run.parameters["picked"] == (3, 5)


def test_errors_carry_the_script_line_and_trim_library_frames():
    result = run_script(script_path("error_at_line_7.py"))
    error = result.error
    assert result.status == "error" and error is not None
    assert error.kind == "exception"
    assert error.file == script_path("error_at_line_7.py") and error.line == 7
    assert error.message == "UnknownIdError: edge 12345 does not exist"
    assert "livemod" + os.sep not in error.traceback.replace(script_path(""), "")
    assert 'line 10, in <module>' in error.traceback
    assert str(error).startswith(f"{script_path('error_at_line_7.py')}:7: UnknownIdError")
    assert [s.label for s in result.steps] == ["createVertex", "createVertex"]
    assert result.partial is not None and result.partial.counts == (2, 0, 2)


def test_syntax_error_reports_line_and_runs_nothing(tmp_path):
    path = write(tmp_path, "syntax.py", "createVertex((0, 0, 0))\nx = 1\ny = (2 +\n")
    result = run_script(path)
    assert result.status == "error" and result.error is not None
    assert result.error.kind == "syntax" and result.error.line == 3
    assert result.steps == ()


def test_a_misspelt_command_gets_the_suggestion_python_would_give(tmp_path):
    path = write(tmp_path, "typo.py", "load('cube')\nf = faces()[0]\nextrud('cubical', f)\n")
    error = run_script(path).error
    assert error is not None and error.line == 3
    assert error.message == "NameError: name 'extrud' is not defined. Did you mean: 'extrude'?"
    assert error.traceback.endswith(error.message + "\n")


def test_a_misspelt_attribute_gets_a_suggestion_and_a_far_one_none(tmp_path):
    path = write(tmp_path, "attr.py", "import numpy\nnumpy.arange(3).sorted()\n")
    assert run_script(path).error.message.endswith(". Did you mean: 'sort'?")
    path = write(tmp_path, "far.py", "zzzqqq_not_a_name + 1\n")
    assert run_script(path).error.message == "NameError: name 'zzzqqq_not_a_name' is not defined"


def test_the_traceback_keeps_every_line_of_the_text_and_the_notes(tmp_path):
    path = write(tmp_path, "notes.py", (
        "e = ValueError('first line\\nsecond line')\ne.add_note('while doing x')\nraise e\n"))
    error = run_script(path).error
    assert error.message == "ValueError: first line"
    assert error.traceback.endswith("ValueError: first line\nsecond line\nwhile doing x\n")


def test_scripts_are_decoded_as_python_decodes_them(tmp_path):
    bom = tmp_path / "bom.py"  # older Notepad writes a byte-order mark
    bom.write_bytes(b"\xef\xbb\xbfcreateVertex((0, 0, 0))\n")
    assert run_script(str(bom)).status == "ok"
    declared = tmp_path / "declared.py"
    declared.write_bytes(b"# -*- coding: latin-1 -*-\nname = param('name', 'caf\xe9')\n")
    outcome = execute(str(declared))
    assert outcome.status == "ok" and outcome.run.parameters == {} \
        and outcome.declarations["name"].default == "caf\u00e9"


def test_a_script_that_is_not_text_in_its_encoding_is_a_syntax_error(tmp_path):
    latin = tmp_path / "latin.py"
    latin.write_bytes(b"x = 1\ny = 'caf\xe9'\n")
    error = run_script(str(latin)).error
    assert error.kind == "syntax" and error.line == 2
    assert error.message == ("SyntaxError: byte 0xe9 on line 2 is not UTF-8 text: save the "
                             "file as UTF-8, or declare its encoding on the first line "
                             "(# -*- coding: latin-1 -*-)")
    unknown = tmp_path / "unknown.py"
    unknown.write_bytes(b"# -*- coding: martian -*-\nx = 1\n")
    error = run_script(str(unknown)).error
    assert error.kind == "syntax" and error.message == "SyntaxError: unknown encoding: martian"


def test_error_in_a_local_module_points_into_it(tmp_path):
    write(tmp_path, "helper_bad.py", "def boom():\n    x = 1\n    raise RuntimeError('bad helper')\n")
    path = write(tmp_path, "main_bad.py", "import helper_bad\n\nhelper_bad.boom()\n")
    result = run_script(path)
    assert result.error is not None
    assert result.error.file == str(tmp_path / "helper_bad.py") and result.error.line == 3
    assert "main_bad.py\", line 3" in result.error.traceback
    assert "helper_bad" not in sys.modules


def test_local_modules_are_reported_and_purged(tmp_path):
    write(tmp_path, "helper_mod.py", "VALUE = 4\n")
    path = write(tmp_path, "main_mod.py", (
        "import helper_mod\nfor i in range(helper_mod.VALUE):\n    createVertex((i, 0, 0))\n"))
    first = execute(path)
    assert first.modules == (str(tmp_path / "helper_mod.py"),)
    assert "helper_mod" not in sys.modules
    write(tmp_path, "helper_mod.py", "VALUE = 6\n")
    assert execute(path).scene.mesh.counts() == (6, 0, 6)


def test_system_exit_zero_ends_the_script_normally(tmp_path):
    path = write(tmp_path, "exits.py", "import sys\ncreateVertex((0, 0, 0))\nsys.exit(0)\n")
    assert run_script(path).status == "ok"


def test_except_exception_in_script_does_not_swallow_cancellation(tmp_path):
    path = write(tmp_path, "swallow.py", (
        "while True:\n    try:\n        createVertex((0, 0, 0))\n"
        "    except Exception:\n        pass\n"))
    control = RunControl()
    timer = threading.Timer(0.2, control.cancel)
    timer.start()
    outcome = execute(path, control=control)
    timer.join()
    assert outcome.status == "cancelled"
    assert outcome.error is not None and outcome.error.kind == "cancelled"


@pytest.mark.timeout(60)
def test_infinite_loop_without_steps_is_cancelled_promptly():
    control = RunControl()
    outcome_box = []
    worker = threading.Thread(target=lambda: outcome_box.append(
        execute(script_path("infinite_loop.py"), control=control)))
    worker.start()
    time.sleep(0.2)
    control.cancel()
    worker.join(10)  # how soon it ends is bench/bench_responsiveness.py's to time
    assert not worker.is_alive()
    assert outcome_box[0].status == "cancelled"
    assert [s.label for s in outcome_box[0].steps] == ["createVertex"]


@pytest.mark.timeout(60)
def test_recursion_and_helper_functions_are_cancellable(tmp_path):
    path = write(tmp_path, "spin.py", "def spin(n):\n    return spin(n + 1) if n < 500 else spin(0)\n"
                 "while True:\n    try:\n        spin(0)\n    except RecursionError:\n        pass\n")
    control = RunControl()
    threading.Timer(0.2, control.cancel).start()
    assert execute(path, control=control).status == "cancelled"


def test_instrumented_code_keeps_docstrings_and_lines():
    source = 'def f():\n    """doc"""\n    return 1\n\nfor i in range(2):\n    x = 1 / 0\n'
    namespace = {"__livemod_cancel__": False, "__livemod_stop__": None}
    code = compile_script(source, "/virtual/s.py")
    with pytest.raises(ZeroDivisionError) as info:
        exec(code, namespace)
    assert namespace["f"].__doc__ == "doc"
    assert info.traceback[-1].lineno + 1 == 6


def test_cancelled_is_a_base_exception():
    assert not issubclass(Cancelled, Exception)


def test_results_carry_the_scenes_other_objects_for_drawing(tmp_path):
    script = tmp_path / "three.py"
    script.write_text("load('cube')\nload('tetrahedron')\ntranslate(4, 0, 0)\n"
                      "load('octahedron')\n")
    result = run_script(script)
    assert result.arrays is not None and result.arrays.counts == (6, 12, 8)  # the current
    assert result.others is not None and result.others.counts == (8 + 4, 12 + 6, 6 + 4)
    assert not result.others.positions.flags.writeable
    assert result.others.positions[8:, 0].min() > 2.0  # the tetrahedron moved with it
    single = tmp_path / "one.py"
    single.write_text("load('cube')\n")
    assert run_script(single).others is None


def test_packages_installed_in_the_scripts_folder_are_library_not_script(tmp_path):
    """A project with its virtual environment inside (``.venv``): the packages there
    are neither trimmed into the traceback, nor watched, nor purged after a run
    (purging a C extension and importing it again breaks it)."""
    packages = tmp_path / ".venv" / "lib" / "python3.11" / "site-packages"
    packages.mkdir(parents=True)
    (packages / "vendored_lib.py").write_text("def fail():\n    raise ValueError('inside')\n")
    path = write(tmp_path, "uses_vendored.py", (
        f"import sys\nsys.path.insert(0, {str(packages)!r})\nimport vendored_lib\n"
        "sys.path.pop(0)\nvendored_lib.fail()\n"))
    try:
        outcome = execute(path)
        assert outcome.error is not None
        assert (outcome.error.file, outcome.error.line) == (path, 5)
        assert "vendored_lib.py" not in outcome.error.traceback
        assert outcome.modules == ()
        assert "vendored_lib" in sys.modules
    finally:
        sys.modules.pop("vendored_lib", None)


# -- a helper module the host imported before the first run


def _local_names(folder) -> set[str]:  # noqa: ANN001
    """Names in ``sys.modules`` of modules whose file lies in ``folder``."""
    return {name for name, module in list(sys.modules.items())
            if str(getattr(module, "__file__", None) or "").startswith(str(folder) + os.sep)}


def test_a_helper_the_host_imported_first_is_fresh_in_each_run_and_given_back(
        tmp_path, monkeypatch):
    host_copy = host_imports(tmp_path, monkeypatch, "helper_host", "VALUE = 2\n")
    script = tmp_path / "main_host.py"
    script.write_text("import helper_host\nfor i in range(helper_host.VALUE):\n"
                      "    createVertex((i, 0, 0))\n")
    path = list(sys.path)
    first = execute(str(script))
    assert first.status == "ok" and first.scene.mesh.counts()[0] == 2
    assert first.modules == (str(tmp_path / "helper_host.py"),)  # so it is watched
    (tmp_path / "helper_host.py").write_text("VALUE = 5  # edited\n")
    assert execute(str(script)).scene.mesh.counts()[0] == 5
    assert sys.modules["helper_host"] is host_copy and host_copy.VALUE == 2
    assert _local_names(tmp_path) == {"helper_host"} and sys.path == path


# -- a forced interrupt landing in a run's cleanup still gives back path and modules


def _cancelled_once(real):  # noqa: ANN001, ANN202
    """``real``, raising Cancelled (as PyThreadState_SetAsyncExc would) on its first call."""
    calls = []

    def step(*args):  # noqa: ANN002, ANN202
        calls.append(args)
        if len(calls) == 1:
            raise Cancelled
        return real(*args)

    return step


@pytest.mark.parametrize("owner,step", [(execute_module._HostState, "_remove_run_modules"),
                                        (ProcessState, "restore")])
def test_an_interrupt_landing_in_the_cleanup_still_gives_back_path_and_modules(
        tmp_path, monkeypatch, owner, step):
    host_copy = host_imports(tmp_path, monkeypatch, "helper_late", "VALUE = 1\n")
    (tmp_path / "other_late.py").write_text("OTHER = 1\n")
    script = tmp_path / "late.py"
    script.write_text("import helper_late, other_late\ncreateVertex((0, 0, 0))\n")
    path = list(sys.path)
    monkeypatch.setattr(owner, step, _cancelled_once(getattr(owner, step)))
    outcome = execute(str(script))
    assert outcome.status == "cancelled"  # it was being cancelled: that still shows
    assert outcome.error is not None and outcome.error.line == 2  # its last step
    assert sys.path == path and _local_names(tmp_path) == {"helper_late"}
    assert sys.modules["helper_late"] is host_copy


def test_an_interrupt_landing_while_the_runs_modules_are_looked_at_gives_them_back(
        tmp_path, monkeypatch):
    # the point where local_modules' finally used to be
    (tmp_path / "first_late.py").write_text("FIRST = 1\n")
    (tmp_path / "other_late.py").write_text("OTHER = 1\n")
    script = tmp_path / "late.py"
    script.write_text("import first_late, other_late\ncreateVertex((0, 0, 0))\n")
    path = list(sys.path)
    real, raised = execute_module.is_user_file, []

    def interrupted_once(filename: str, script_path: str) -> bool:
        if not raised and filename.endswith("late.py") and filename != str(script):
            raised.append(filename)
            raise Cancelled
        return real(filename, script_path)

    monkeypatch.setattr(execute_module, "is_user_file", interrupted_once)
    assert execute(str(script)).status == "cancelled"
    assert len(raised) == 1
    assert sys.path == path and _local_names(tmp_path) == set()


def test_an_interrupt_landing_as_the_script_ends_cancels_the_run_cleanly(tmp_path, monkeypatch):
    script = tmp_path / "ends.py"
    script.write_text("createVertex((0, 0, 0))\n")
    path, scene = list(sys.path), current_scene()
    monkeypatch.setattr(execute_module, "_leave_user_code",
                        _cancelled_once(execute_module._leave_user_code))
    outcome = execute(str(script))
    assert outcome.status == "cancelled" and outcome.error is not None
    assert outcome.error.kind == "cancelled"
    assert sys.path == path and current_scene() is scene


# -- interrupt_user_code: only inside the run it names


def _innermost(thread: threading.Thread) -> str | None:
    """The name of the function ``thread`` runs now (its innermost Python frame)."""
    frame = sys._current_frames().get(thread.ident)  # type: ignore[arg-type]
    return None if frame is None else frame.f_code.co_name


@pytest.mark.timeout(60)
def test_an_interrupt_sent_as_the_run_leaves_user_code_is_raised_by_the_leaving():
    """The supervisor sends under the lock the worker leaves by: an exception it sent
    just before comes out of _leave_user_code (in _run_code's finally), never later."""
    where: list[str] = []
    for _ in range(20):
        ready, go = threading.Event(), threading.Event()

        def worker(ready: threading.Event = ready, go: threading.Event = go) -> None:
            execute_module._enter_user_code()
            ready.set()
            go.wait()
            try:
                execute_module._leave_user_code()  # waits for the lock the sender holds
            except Cancelled:
                where.append("leaving")
                execute_module._leave_user_code()  # as _exec does after it
                return
            try:
                for _ in range(1000):  # bytecodes enough for a pending exception
                    pass
            except Cancelled:
                where.append("after")

        thread = threading.Thread(target=worker)
        thread.start()
        ready.wait()
        with execute_module._INTERRUPT_LOCK:
            go.set()
            # the worker is in _leave_user_code now, waiting for the lock (or about to)
            wait_until(lambda thread=thread: _innermost(thread) == "_leave_user_code")
            ctypes.pythonapi.PyThreadState_SetAsyncExc(
                ctypes.c_ulong(thread.ident), ctypes.py_object(Cancelled))
        thread.join(10)
        assert thread.ident not in execute_module._IN_USER_CODE
    assert where == ["leaving"] * 20


@pytest.mark.timeout(60)
def test_code_of_a_script_s_file_outside_a_run_is_never_interrupted(tmp_path):
    script = str(tmp_path / "model.py")
    code = compile("def spin(stop):\n    while not stop.is_set():\n        pass\n", script, "exec")
    namespace: dict = {}
    exec(code, namespace)  # noqa: S102
    stop = threading.Event()
    thread = threading.Thread(target=namespace["spin"], args=(stop,))
    thread.start()
    try:
        time.sleep(0.05)  # spinning in the script's file, but not inside a run
        assert interrupt_user_code(thread, script) is False
    finally:
        stop.set()
        thread.join()


@pytest.mark.timeout(60)
def test_code_of_a_script_s_file_inside_a_run_is_interrupted(tmp_path):
    (tmp_path / "spin_in_run.py").write_text("def spin():\n    while True:\n        pass\n")
    script = tmp_path / "model.py"
    script.write_text("import spin_in_run\nspin_in_run.spin()\n")
    control, outcomes = RunControl(), []
    thread = threading.Thread(target=lambda: outcomes.append(
        execute(str(script), control=control)))
    thread.start()
    deadline = time.monotonic() + 10
    while not interrupt_user_code(thread, str(script)):
        assert time.monotonic() < deadline
        time.sleep(0.01)
    thread.join(10)
    assert [o.status for o in outcomes] == ["cancelled"]


@pytest.mark.timeout(60)
def test_an_interrupt_asked_for_another_run_is_not_sent(tmp_path):
    # an abandoned run's thread id may be a newer run's once it has ended: the
    # interrupt names its run, and a thread running any other is left alone
    (tmp_path / "spin_in_run.py").write_text("def spin():\n    while True:\n        pass\n")
    script = tmp_path / "model.py"
    script.write_text("import spin_in_run\nspin_in_run.spin()\n")
    running, other, outcomes = RunControl(), RunControl(), []
    thread = threading.Thread(target=lambda: outcomes.append(
        execute(str(script), control=running)))
    thread.start()
    wait_until(lambda: _innermost(thread) == "spin")  # in the run's own code, interruptible
    assert interrupt_user_code(thread, str(script), other) is False
    assert interrupt_user_code(thread, str(script), running) is True
    thread.join(10)
    assert [o.status for o in outcomes] == ["cancelled"]
