"""Tests of livemod.dlfl.run_context: announcing steps, binding a run, and what the
library does not know (the runner's step record)."""

from __future__ import annotations

import ast
import subprocess
import sys
import textwrap
import threading
from pathlib import Path

import pytest

from livemod.dlfl import (
    DLFLError,
    RunContext,
    Scene,
    createVertex,
    current_run,
    use_run,
    use_scene,
)
from livemod.dlfl.commands._base import modeling_command
from livemod.dlfl.run_context import STANDALONE_RUN, announce_step
from livemod.runner import recording

DLFL = Path(__file__).resolve().parents[1] / "livemod" / "dlfl"


@modeling_command
def outer() -> None:
    """A command made of other commands (and a step() inside), one step in all."""
    createVertex((0, 0, 0))
    announce_step("inside")
    createVertex((1, 0, 0))


@modeling_command
def broken() -> None:
    createVertex((0, 0, 0))
    raise DLFLError("boom")


def test_only_outermost_commands_announce_steps(scene, run):
    seen: list[str] = []
    run.step_hook = seen.append
    outer()
    announce_step("plain")
    createVertex((2, 0, 0))
    assert seen == ["outer", "plain", "createVertex"] and run.command_depth == 0
    assert scene.mesh.counts() == (11, 12, 9)


def test_a_failed_command_announces_nothing_and_unwinds(scene, run):
    seen: list[str] = []
    run.step_hook = seen.append
    with pytest.raises(DLFLError, match="boom"):
        broken()
    assert seen == [] and run.command_depth == 0
    createVertex((0, 0, 0))
    assert seen == ["createVertex"]


def test_no_hook_announces_to_no_one(scene, run):
    assert run.step_hook is None
    outer()
    announce_step("nobody listens")
    assert run.command_depth == 0 and scene.mesh.counts() == (10, 12, 8)


def test_use_run_binds_per_thread_and_the_standalone_run_is_the_default():
    mine, seen = RunContext(directory="/somewhere", parameters={"n": 3}), {}

    def other_thread() -> None:
        seen["other"] = current_run()

    with use_run(mine) as bound:
        assert bound is mine and current_run() is mine
        worker = threading.Thread(target=other_thread)
        worker.start()
        worker.join()
    assert seen["other"] is STANDALONE_RUN and current_run() is STANDALONE_RUN
    assert (mine.directory, mine.parameters) == ("/somewhere", {"n": 3})


def test_parameters_are_the_run_s_own_copy():
    given = {"n": 3}
    run = RunContext(parameters=given)
    run.parameters["n"] = 4
    assert given == {"n": 3}


def test_a_run_hears_of_its_files_and_a_scene_knows_nothing_of_runs(tmp_path):
    run = RunContext(directory=str(tmp_path))
    scene = Scene()
    with use_scene(scene), use_run(run):
        from livemod.dlfl import load, save

        save("out.obj")
        load("out.obj")
    written = str(tmp_path / "out.obj")
    assert run.files_written == [written] and run.files_read == [written]
    run_fields = set(RunContext.__slots__)
    assert not run_fields & set(vars(scene)) and not run_fields & set(vars(scene.copy()))


def test_a_plain_script_runs_without_a_runner(tmp_path):
    script = tmp_path / "plain.py"
    script.write_text(textwrap.dedent("""\
        import sys
        from livemod.dlfl import *
        from livemod.dlfl import current_run, current_scene

        (c1, _), (c2, _) = createVertex((0, 0, 0)), createVertex((1, 0, 0))
        insertEdge(c1, c2)
        step("checkpoint")
        save("tri.obj")
        assert current_run().step_hook is None
        print(current_scene().mesh.counts(), current_run().files_written,
              sorted(m for m in sys.modules if m.startswith("livemod.runner")))
        """), encoding="utf-8")
    done = subprocess.run([sys.executable, str(script)], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == f"(2, 1, 1) ['{tmp_path / 'tri.obj'}'] []"


# -- what the library does not know -----------------------------------------------------

# the names of the step record: its classes, its layout and what reads it back
RECORD_NAMES = frozenset({
    "StepRecord", "StepList", "StepLog", "StepRecorder", "STEP_FIELDS", "NO_COUNTS",
    "code_line", "script_frame",
})
# frame introspection: how the recorder finds a step's script line
FRAME_NAMES = frozenset({"f_lasti", "f_lineno", "f_back", "f_code", "_getframe",
                         "currentframe"})


def _dlfl_modules() -> list[Path]:
    return sorted(DLFL.rglob("*.py"))


def _names(tree: ast.AST) -> set[str]:
    """Every identifier ``tree`` uses: names, attributes, imported names."""
    found: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Name):
            found.add(node.id)
        elif isinstance(node, ast.Attribute):
            found.add(node.attr)
        elif isinstance(node, ast.alias):
            found.update(node.name.split("."))
    return found


def test_the_record_names_are_the_runner_s():
    used = _names(ast.parse(Path(recording.__file__).read_text(encoding="utf-8")))
    # the lists name what the recorder really uses
    assert RECORD_NAMES.issubset(used) and {"f_lasti", "f_back", "f_code", "_getframe"}.issubset(used)


# the one frame read the library keeps, and why: walk() echoes the thesis's printed
# walk when a script's module body calls it, as TopMod's console echoed it; it asks
# whether its caller is that body, which is no step record
ECHOING_WALK = {"commands/core.py": ["_getframe", "f_code"]}


def test_the_library_names_nothing_of_the_step_record_nor_reads_frames():
    knowing = {path.relative_to(DLFL).as_posix(): sorted(names)
               for path in _dlfl_modules()
               if (names := _names(ast.parse(path.read_text(encoding="utf-8")))
                   & (RECORD_NAMES | FRAME_NAMES))}
    assert knowing == ECHOING_WALK


def _imported_modules(path: Path) -> list[str]:
    """The absolute modules ``path`` imports (relative imports stay in the package)."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found += [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            found.append(node.module)
    return found


def test_the_library_imports_numpy_the_standard_library_and_itself_only():
    foreign = {}
    for path in _dlfl_modules():
        top = {name.split(".")[0] for name in _imported_modules(path)
               if not name.startswith("livemod.dlfl")}
        outside = sorted(top - sys.stdlib_module_names - {"numpy"})
        if outside:
            foreign[path.relative_to(DLFL).as_posix()] = outside
    assert foreign == {}


def test_importing_the_library_loads_no_runner_and_no_gl():
    code = ("import sys, livemod.dlfl, livemod.dlfl.io, livemod.dlfl.run_context\n"
            "print(sorted(m for m in sys.modules if m.split('.')[0] in "
            "('moderngl', 'moderngl_window', 'glfw') or m.startswith(('livemod.runner', "
            "'livemod.viewer'))))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "[]"
