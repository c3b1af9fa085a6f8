"""The livemod_snapshot pytest plugin, run on test suites of its own (pytester)."""

from __future__ import annotations

import json
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from livemod.cli import main as livemod_main
from livemod.pytest_plugin import record_changes
from livemod.viewer.compare import DIFF_COLOR
from tests.images import read_image

ROOT = Path(__file__).resolve().parents[1]
PLUGIN = ("-p", "livemod.pytest_plugin")

CUBE_TEST = """
from livemod.dlfl.extrusion import extrude
from livemod.dlfl.shapes import cube

def test_cube(livemod_snapshot):
    mesh = cube()
    {edit}
    livemod_snapshot.assert_match(mesh)
"""
STORED = Path("__snapshots__", "test_model")

TOWER_SCRIPT = """from livemod.dlfl import *
storeys = param("storeys", 2, min=1, max=9)
load("cube")
face = faces()[0]
for _ in range(storeys):
    face = extrude("cubical", face, 0.5)
"""


def run(pytester: pytest.Pytester, *args: str) -> pytest.RunResult:
    return pytester.runpytest(*PLUGIN, "-p", "no:cacheprovider", *args)


def cube_test(pytester: pytest.Pytester, edit: str = "pass") -> None:
    pytester.makepyfile(test_model=CUBE_TEST.format(edit=edit))


def stored(pytester: pytest.Pytester, name: str = "test_cube") -> dict:
    return json.loads((pytester.path / STORED / f"{name}.json").read_text())


def test_an_update_run_stores_the_snapshot_and_later_runs_match(pytester: pytest.Pytester):
    cube_test(pytester)
    result = run(pytester, "--livemod-update")
    result.assert_outcomes(passed=1)
    result.stdout.fnmatch_lines(["livemod snapshots: 1 written, 0 updated"])
    snapshot = stored(pytester)
    assert snapshot["livemod snapshot"] == 1
    assert snapshot["model"] == {
        "vertices": 8, "edges": 12, "faces": 6, "holes": 0, "point_spheres": 0,
        "components": 1, "genus": 0, "component_genera": [0], "face_sizes": {"4": 6},
        "bounds": [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]}  # TopMod's cube: 2 wide
    assert snapshot["image"] == {"file": "test_cube.png", "size": [240, 180]}
    picture = read_image(pytester.path / STORED / "test_cube.png")
    assert picture.shape == (180, 240, 3)
    files = {path: path.read_bytes() for path in (pytester.path / STORED).iterdir()}

    run(pytester).assert_outcomes(passed=1)
    again = run(pytester, "--livemod-update")  # nothing changed: nothing written
    again.assert_outcomes(passed=1)
    assert "livemod snapshots:" not in again.stdout.str()
    assert {path: path.read_bytes() for path in (pytester.path / STORED).iterdir()} == files


def test_a_changed_model_fails_naming_what_changed_and_the_difference_picture(
        pytester: pytest.Pytester):
    cube_test(pytester)
    run(pytester, "--livemod-update").assert_outcomes(passed=1)
    cube_test(pytester, "extrude(mesh, mesh.face_ids()[0], distance=1.0)")
    result = run(pytester)
    result.assert_outcomes(failed=1)
    lines = result.stdout.lines
    start = lines.index(f"the model differs from its snapshot {STORED / 'test_cube.json'}:")
    assert lines[start + 1:start + 6] == [
        "  vertices: 8 stored, 12 now",
        "  edges: 12 stored, 20 now",
        "  faces: 6 stored, 10 now",
        "  face_sizes: {'4': 6} stored, {'4': 10} now",
        "  bounds: [(-1, -1, -1), (1, 1, 1)] stored, [(-1, -1, -1), (1, 2, 1)] now",
    ]  # the top face (+y) went up by 1
    assert re.fullmatch(
        rf"  picture: \d+\.\d\d% of the pixels differ from "
        rf"{re.escape(str(STORED / 'test_cube.png'))} \(threshold 1\.00%; largest "
        rf"difference \d+%\); the new picture is \S+/test_cube\.png, the differing "
        rf"pixels in red: \S+/test_cube\.diff\.png", lines[start + 6])
    assert lines[start + 7] == "if the change is meant, store it: pytest --livemod-update"
    found = re.search(r"the new picture is (\S+), the differing pixels in red: (\S+)",
                      result.stdout.str())
    assert found is not None
    new, diff = (Path(path) for path in found.groups())
    assert read_image(new).shape == (180, 240, 3)
    red = np.all(read_image(diff, "RGB") == DIFF_COLOR, axis=2)
    assert 0.01 < red.mean() < 0.5  # the taller box differs where it grew
    assert stored(pytester)["model"]["faces"] == 6  # a failing run stores nothing


def test_a_missing_snapshot_says_how_to_store_it(pytester: pytest.Pytester):
    cube_test(pytester)
    result = run(pytester)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines([f"*no snapshot stored at {STORED / 'test_cube.json'}: run "
                                 f"pytest --livemod-update to store it"])
    assert not (pytester.path / STORED).exists()


def test_an_update_run_stores_a_changed_model(pytester: pytest.Pytester):
    cube_test(pytester)
    run(pytester, "--livemod-update").assert_outcomes(passed=1)
    before = (pytester.path / STORED / "test_cube.png").read_bytes()
    cube_test(pytester, "extrude(mesh, mesh.face_ids()[0], distance=1.0)")
    result = run(pytester, "--livemod-update")
    result.assert_outcomes(passed=1)
    result.stdout.fnmatch_lines(["livemod snapshots: 0 written, 1 updated"])
    assert stored(pytester)["model"]["faces"] == 10
    assert (pytester.path / STORED / "test_cube.png").read_bytes() != before
    run(pytester).assert_outcomes(passed=1)


def test_a_test_may_snapshot_several_models_by_call_or_by_name(pytester: pytest.Pytester):
    pytester.makepyfile(test_model="""
        from livemod.dlfl.shapes import cube, tetrahedron

        def test_two(livemod_snapshot):
            livemod_snapshot.assert_match(cube(), image=False)
            livemod_snapshot.assert_match(tetrahedron(), image=False)
            livemod_snapshot.assert_match(tetrahedron(), name="tetra", image=False)
        """)
    run(pytester, "--livemod-update").assert_outcomes(passed=1)
    assert sorted(path.name for path in (pytester.path / STORED).iterdir()) == [
        "test_two-2.json", "test_two-tetra.json", "test_two.json"]
    assert stored(pytester, "test_two")["model"]["faces"] == 6
    assert stored(pytester, "test_two-2")["model"]["faces"] == 4
    assert stored(pytester, "test_two")["image"] is None
    run(pytester).assert_outcomes(passed=1)


def test_a_script_runs_with_its_parameters_and_is_drawn_as_livemod_render_draws_it(
        pytester: pytest.Pytester):
    pytester.makefile(".py", tower=TOWER_SCRIPT)
    pytester.makepyfile(test_model="""
        import pytest

        @pytest.mark.parametrize("storeys", [2])
        def test_tower(livemod_snapshot, storeys):
            outcome = livemod_snapshot.assert_script("tower.py",
                                                     parameters={"storeys": storeys})
            assert outcome.scene.mesh.counts() == (8 + 4 * storeys, 12 + 8 * storeys,
                                                   6 + 4 * storeys)
        """)
    run(pytester, "--livemod-update").assert_outcomes(passed=1)
    snapshot = pytester.path / STORED / "test_tower[2].json"
    assert json.loads(snapshot.read_text())["model"]["faces"] == 14
    reference = snapshot.with_suffix(".png")
    assert livemod_main(["render", str(pytester.path / "tower.py"), "--set", "storeys=2",
                         "--size", "240x180", "-o", str(pytester.path / "render.png"),
                         "--reference", str(reference)]) == 0

    pytester.makepyfile(test_model="""
        def test_tower(livemod_snapshot):
            livemod_snapshot.assert_script("tower.py", parameters={"storeys": 3},
                                           name="2")
        """)
    result = run(pytester)
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*no snapshot stored at*test_tower-2.json*"])


def test_a_failing_script_or_an_undeclared_parameter_fails_the_test(pytester: pytest.Pytester):
    pytester.makefile(".py", tower=TOWER_SCRIPT, broken="from livemod.dlfl import *\n"
                                                      "load('cube')\nextrude('nosuch', 0)\n")
    pytester.makepyfile(test_model="""
        def test_misspelt(livemod_snapshot):
            livemod_snapshot.assert_script("tower.py", parameters={"storys": 3})

        def test_broken(livemod_snapshot):
            livemod_snapshot.assert_script("broken.py")
        """)
    result = run(pytester, "--livemod-update")
    result.assert_outcomes(failed=2)
    result.stdout.fnmatch_lines([
        "*tower.py: the run declared no parameter 'storys'; did you mean 'storeys'? (it declared: storeys)*",
        "*broken.py failed: *broken.py:3: *"])
    assert not (pytester.path / "__snapshots__").exists()


def test_record_changes_compare_the_box_to_a_millionth_of_its_size():
    box = [[0.0, 0.0, 0.0], [1000.0, 1.0, 1.0]]
    near = [[0.0, 0.0, 0.0], [1000.0 + 5e-4, 1.0, 1.0]]
    far = [[0.0, 0.0, 0.0], [1000.0 + 2e-3, 1.0, 1.0]]
    assert record_changes({"bounds": box, "faces": 6}, {"bounds": near, "faces": 6}) == []
    assert record_changes({"bounds": box}, {"bounds": far}) == [
        "bounds: [(0, 0, 0), (1000, 1, 1)] stored, [(0, 0, 0), (1000, 1, 1)] now"]
    assert record_changes({}, {"genus": 2}) == ["genus: none stored, 2 now"]


def test_the_entry_point_loads_the_plugin_once_with_or_without_p(
        pytester: pytest.Pytester, monkeypatch: pytest.MonkeyPatch):
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"][
        "entry-points"]["pytest11"]
    assert declared == {"livemod.pytest_plugin": "livemod.pytest_plugin"}
    # an installed distribution that declares the same entry point
    info = pytester.mkdir("site") / "livemod_probe-0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: livemod-probe\nVersion: 0\n")
    (info / "entry_points.txt").write_text(
        "[pytest11]\n" + "".join(f"{name} = {value}\n" for name, value in declared.items()))
    monkeypatch.setenv("PYTHONPATH", f"{pytester.path / 'site'}:{ROOT}")
    cube_test(pytester)
    for extra in ((), PLUGIN):
        result = pytester.runpytest_subprocess(*extra, "-p", "no:cacheprovider",
                                               "--livemod-update")
        result.assert_outcomes(passed=1)


def test_without_offscreen_gl_the_failure_says_so(pytester: pytest.Pytester):
    # the module the plugin will import, from sys.modules: an earlier in-process run's
    # copy may still be bound on the package after pytester took it out of sys.modules
    pytester.makeconftest("""
        import sys

        import pytest
        import livemod.viewer.pictures
        from livemod.viewer.headless import NoOffscreenGL

        pictures = sys.modules["livemod.viewer.pictures"]

        @pytest.fixture(autouse=True)
        def no_gl(monkeypatch):
            def refuse(*args, **kwargs):
                raise NoOffscreenGL("no EGL here")
            monkeypatch.setattr(pictures, "render_model", refuse)
        """)
    cube_test(pytester)
    result = run(pytester, "--livemod-update")
    result.assert_outcomes(failed=1)
    result.stdout.fnmatch_lines(["*the snapshot's picture cannot be drawn: no EGL here (or "
                                 "compare the numbers only: image=False)"])
