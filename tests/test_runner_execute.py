"""execute / run_script: namespace, steps, errors, determinism, cancellation."""

from __future__ import annotations

import os
import sys
import threading
import time

import numpy as np
import pytest

from livemod.dlfl.scene import Selection, current_scene, default_scene
from livemod.runner import Cancelled, RunControl, execute, run_script
from livemod.runner.instrument import compile_script

from .runner_scripts.support import same_mesh, script_path


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
