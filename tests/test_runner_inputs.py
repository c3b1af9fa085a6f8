"""RunInputs alone: the digests that decide when a save asks for a run, the
--mesh scene kept between runs, and the parameters that must fit the script."""

from __future__ import annotations

import threading

import pytest

from livemod.dlfl.errors import DLFLError
from livemod.dlfl.scene import Scene
from livemod.runner.inputs import RunInputs
from livemod.runner.watch import FileWatcher, ManualNotifier


@pytest.fixture
def make_inputs(tmp_path):
    """Inputs of a script model.py (with ``text``), watching by hand; stopped after."""
    made: list[RunInputs] = []

    def make(text: str = "pass\n", *, mesh_file: str | None = None, output: str | None = None,
             parameters: dict | None = None) -> RunInputs:
        script = tmp_path / "model.py"
        script.write_text(text)
        watcher = FileWatcher(lambda: None, notifier=ManualNotifier())
        inputs = RunInputs(threading.RLock(), str(script), mesh_file=mesh_file, base=None,
                           parameters=parameters, output=output, watcher=watcher)
        inputs.start_watching()
        made.append(inputs)
        return inputs

    yield make
    for inputs in made:
        inputs.stop_watching()


def test_only_a_change_of_content_asks_for_a_run(tmp_path, make_inputs):
    inputs = make_inputs()
    assert inputs.files_changed()  # no run read it yet: its first save runs it
    assert inputs.text(inputs.script, None) == "pass\n"
    assert not inputs.files_changed()  # saved with the same bytes
    (tmp_path / "model.py").write_text("x = 1\n")
    assert inputs.files_changed()
    assert not inputs.files_changed()  # the new content is what was seen now


def test_a_script_left_empty_asks_for_nothing_and_says_so(tmp_path, make_inputs):
    inputs = make_inputs()
    inputs.text(inputs.script, None)
    (tmp_path / "model.py").write_bytes(b"\xef\xbb\xbf \n\t\n")
    assert not inputs.files_changed()
    assert inputs.empty_script == inputs.script
    (tmp_path / "model.py").write_text("pass\n")  # the same text back
    assert not inputs.files_changed()
    assert inputs.empty_script is None


def test_the_text_given_is_run_without_reading_the_script(tmp_path, make_inputs):
    inputs = make_inputs()
    assert inputs.text(inputs.script, "y = 2\n") == "y = 2\n"
    assert inputs.source == "y = 2\n"
    assert inputs.files_changed()  # the file itself was never read: its save runs it


def test_a_script_that_is_not_text_raises_syntax_error(tmp_path, make_inputs):
    inputs = make_inputs()
    (tmp_path / "model.py").write_bytes(b"\xff\xfe\x00bad")
    with pytest.raises(SyntaxError):
        inputs.text(inputs.script, None)
    assert inputs.source is None


def test_the_mesh_scene_is_loaded_once_and_again_after_the_file_changed(tmp_path, make_inputs):
    shape = tmp_path / "start.obj"
    shape.write_text("v 0 0 0\n")
    inputs = make_inputs(mesh_file=str(shape))
    loads: list[str] = []

    def load(path: str) -> Scene:
        loads.append(path)
        return Scene()

    inputs.text(inputs.script, None)
    first = inputs.base_scene(load)
    assert inputs.base_scene(load) is first and loads == [str(shape)]
    assert not inputs.files_changed()
    shape.write_text("v 1 0 0\n")
    assert inputs.files_changed()
    assert inputs.base_scene(load) is not first and loads == [str(shape)] * 2


def test_the_output_file_is_never_watched(tmp_path, make_inputs):
    out, helper = tmp_path / "out.obj", tmp_path / "helper.py"
    out.write_text("v 0 0 0\n")
    helper.write_text("N = 1\n")
    inputs = make_inputs(output=str(out))
    inputs.text(inputs.script, None)
    inputs.watch_files(inputs.script, (str(out), str(helper)))
    out.write_text("v 1 0 0\n")
    assert not inputs.files_changed()
    helper.write_text("N = 2\n")
    assert inputs.files_changed()


def test_values_that_no_longer_fit_the_script_are_forgotten(tmp_path, make_inputs):
    inputs = make_inputs(parameters={"n": 12, "scale": 2.0})
    first = 'n = param("n", 4, min=1, max=20)\nscale = param("scale", 1.0)\n'
    assert inputs.fit_parameters(inputs.script, first, dict(inputs.parameters)) == {
        "n": 12, "scale": 2.0}
    edited = 'n = param("n", 4, min=1, max=8)\nscale = param("scale", 1.0)\n'
    assert inputs.fit_parameters(inputs.script, edited, dict(inputs.parameters)) == {
        "scale": 2.0}
    assert inputs.parameters == {"scale": 2.0}
    assert set(inputs.declarations) == {"n", "scale"}


def test_a_value_that_does_not_fit_the_declarations_changes_nothing(tmp_path, make_inputs):
    inputs = make_inputs()
    inputs.fit_parameters(inputs.script, 'n = param("n", 4, min=1, max=20)\n', {})
    with pytest.raises(DLFLError, match="'m'"):
        inputs.update_parameters({"n": 5, "m": 1})
    assert inputs.parameters == {}
    inputs.update_parameters({"n": 5})
    inputs.forget_parameters(None)
    assert inputs.parameters == {}


def test_switching_scripts_drops_the_old_scripts_text_and_values(tmp_path, make_inputs):
    inputs = make_inputs(parameters={"n": 3})
    inputs.text(inputs.script, None)
    other = tmp_path / "other.py"
    other.write_text("pass\n")
    inputs.switch(str(other))  # alone here: no lock to hold
    assert (inputs.script, inputs.source, inputs.parameters) == (str(other), None, {})
    assert inputs.files_changed()  # no run read the new script yet
