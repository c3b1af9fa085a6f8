"""Issue 8 headless: declarations in results, --set, params, batch sweeps and index."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pytest

from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.errors import DLFLError
from livemod.dlfl.io import load_mesh
from livemod.runner import LiveSession, ManualNotifier, cli, run_outcome, run_script
from livemod.runner.batch import declared_sweep
from livemod.runner.declarations import declared_parameters
from livemod.runner.results import current_mesh
from livemod.viewer import cli as viewer_cli

from .runner_scripts.support import closing_session, next_result, script_path

RING = script_path("ring.py")

SHAPED = '''
import math
sides = param("sides", 3, min=3, max=8, doc="corners")
lift = param("lift", 0.0, min=0.0, max=2.0)
shape = param("shape", "flat", choices=["flat", "tent"], doc="how the corners rise")
closed = param("closed", True)
points = []
for i in range(sides):
    z = lift * (i % 2) if shape == "tent" else lift
    points.append((math.cos(2 * math.pi * i / sides), math.sin(2 * math.pi * i / sides), z))
createFace(points)
if not closed:
    createVertex((0.0, 0.0, 5.0))
'''


def _shaped(tmp_path) -> str:
    path = tmp_path / "shaped.py"
    path.write_text(SHAPED)
    return str(path)


def test_declarations_are_recorded_and_values_applied():
    result = run_script(RING, parameters={"count": 6, "radius": 2.0})
    assert [spec.name for spec in result.parameters] == ["count", "radius"]
    assert result.parameters[0].kind == "int" and result.parameters[0].max == 64
    assert result.values == (("count", 6), ("radius", 2.0))
    assert result.arrays.counts == (6, 6, 2)
    assert np.allclose(np.linalg.norm(result.arrays.positions, axis=1), 2.0)
    outcome = run_outcome(RING)
    assert list(outcome.declarations) == ["count", "radius"]
    assert current_mesh(outcome.scene).counts() == (4, 4, 2)  # the defaults


@pytest.mark.parametrize("setting, message", [
    ("cuont=5", "declares no parameter 'cuont'; did you mean 'count'? (it declares: count, radius)"),
    ("count=0", "below its minimum 1"),
    ("count=abc", "is an integer; got 'abc'"),
    ("radius", "expects name=value"),
])
def test_set_with_a_bad_name_or_value_fails_clearly(setting, message, capsys, tmp_path):
    out = tmp_path / "never.obj"
    assert cli.main(["run", RING, "--set", setting, "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and len(err.splitlines()) == 1
    assert not out.exists()
    assert viewer_cli.main(["render", RING, "--set", setting, "-o", str(tmp_path / "x.png")]) == 2
    assert message in capsys.readouterr().err


def test_run_set_applies_values_and_param_is_an_alias(capsys):
    assert cli.main(["run", RING, "--set", "count=7", "--param", "radius=3"]) == 0
    assert "V=7 E=7 F=2" in capsys.readouterr().out


def test_params_lists_the_declarations_without_running(tmp_path, capsys):
    script = _shaped(tmp_path)
    (tmp_path / "shaped.py").write_text(SHAPED + "raise SystemExit(3)\n")  # never reached
    assert cli.main(["params", script]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0] == "sides = 3  [int] (range 3..8)  corners"
    assert lines[2].startswith("shape = 'flat'  [choice] (choices 'flat', 'tent')")
    assert lines[3] == "closed = True  [bool]"


def test_sweeps_are_typed_and_checked_against_the_declarations(tmp_path):
    specs = declared_parameters(_shaped(tmp_path))
    assert declared_sweep("sides=3:8:4", specs) == ("sides", [3, 5, 6, 8])
    assert declared_sweep("lift=0:1:3", specs) == ("lift", [0.0, 0.5, 1.0])
    assert declared_sweep("shape=flat,tent", specs) == ("shape", ["flat", "tent"])
    assert declared_sweep("closed=true,false", specs) == ("closed", [True, False])
    for bad in ("sides=2:5:4", "shape=flat,round", "side=3:4:2", "lift=0:3:2"):
        with pytest.raises(DLFLError):
            declared_sweep(bad, specs)


def test_batch_checks_names_and_ranges_before_anything_runs(tmp_path, capsys):
    out = tmp_path / "out"
    pattern = str(out / "v_{index}.obj")
    assert cli.main(["batch", RING, "--param", "count=3:70:3", "-o", pattern, "-j", "1"]) == 2
    assert "above its maximum 64" in capsys.readouterr().err
    assert cli.main(["batch", RING, "--param", "corners=3:5:3", "-o", pattern, "-j", "1"]) == 2
    assert "declares no parameter 'corners'" in capsys.readouterr().err
    assert not out.exists()


def test_batch_variants_match_single_runs_and_the_index_lists_them(tmp_path, capsys):
    script = _shaped(tmp_path)
    pattern = str(tmp_path / "out" / "s_{sides}_{shape}.obj")
    code = cli.main(["batch", script, "--param", "sides=4:5:2", "--param", "shape=flat,tent",
                     "--param", "lift=1.5", "-o", pattern, "-j", "1"])
    assert code == 0, capsys.readouterr().err
    index = json.loads((tmp_path / "out" / "index.json").read_text())
    assert [p["name"] for p in index["parameters"]] == ["sides", "lift", "shape", "closed"]
    variants = index["variants"]
    assert [v["values"] for v in variants] == [
        {"sides": s, "shape": k, "lift": 1.5} for s in (4, 5) for k in ("flat", "tent")]
    for variant in variants:
        assert variant["status"] == "ok" and variant["genus"] == 0
        single = current_mesh(run_outcome(script, parameters=variant["values"]).scene)
        assert (variant["V"], variant["E"], variant["F"]) == single.counts()
        written = load_mesh(variant["output"])
        assert written.counts() == single.counts()
        assert np.allclose(mesh_arrays(written).positions, mesh_arrays(single).positions)
    assert os.path.basename(variants[3]["output"]) == "s_5_tent.obj"


def test_the_session_keeps_values_across_saves_while_they_fit(tmp_path):
    script = tmp_path / "ring.py"
    script.write_text(Path(RING).read_text())
    live = LiveSession(str(script), notifier=ManualNotifier(), preview=False)
    with closing_session(live):
        live.start()
        assert next_result(live).arrays.counts == (4, 4, 2)
        live.set_parameters({"count": 9, "radius": 5.0})
        assert next_result(live, lambda r: r.values == (("count", 9), ("radius", 5.0)))
        with pytest.raises(DLFLError, match="declares no parameter"):
            live.set_parameters({"size": 3})
        edited = Path(RING).read_text().replace("max=10.0", "max=4.0") + "# saved\n"
        script.write_text(edited)  # radius 5 no longer fits: dropped, count kept
        live.reload()
        result = next_result(live, lambda r: r.status == "ok" and r.values == (("count", 9),))
        assert result.arrays.counts == (9, 9, 2)
        assert [s.max for s in result.parameters] == [64, 4.0]
        assert live.parameters == {"count": 9}
        live.reset_parameters()
        assert next_result(live, lambda r: r.values == ()).arrays.counts == (4, 4, 2)


COMPUTED = '''
LIMIT = 9
n = param("n", 3, min=3, max=LIMIT)      # a computed max: found only by running
createFace([(float(i), float(i * i % 5), 0.0) for i in range(n)])
'''


def test_a_parameter_declared_in_a_branch_that_did_not_run(tmp_path, capsys):
    script = tmp_path / "branch.py"
    script.write_text('big = param("big", False)\nif big:\n    n = param("n", 3, max=9)\n'
                      'else:\n    n = 1\nload("cube")\n')
    assert cli.main(["run", str(script), "--set", "big=true", "--set", "n=4"]) == 0
    assert cli.main(["run", str(script), "--set", "n=12"]) == 2  # checked before running
    assert "above its maximum 9" in capsys.readouterr().err
    assert cli.main(["run", str(script), "--set", "n=4"]) == 2
    err = capsys.readouterr().err
    assert ("the run declared no parameter 'n' (it declared: big); a param() call declares "
            "it only when it runs (not in an if branch") in err


def test_computed_declarations_are_checked_by_the_run(tmp_path, capsys):
    script = tmp_path / "computed.py"
    script.write_text(COMPUTED)
    assert cli.main(["run", str(script), "--set", "n=5"]) == 0
    assert "V=5 E=5 F=2" in capsys.readouterr().out
    assert cli.main(["run", str(script), "--set", "m=5"]) == 2
    assert "the run declared no parameter 'm' (it declared: n)" in capsys.readouterr().err
    assert cli.main(["run", str(script), "--set", "n=12"]) == 1   # the run's error
    assert "above its maximum 9" in capsys.readouterr().err
    assert cli.main(["params", str(script)]) == 0
    assert capsys.readouterr().out.startswith("n = 3  [int] (range 3..9)")
