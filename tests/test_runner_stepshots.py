"""The scene after each step of a headless run (livemod.runner.stepshots)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from livemod.dlfl import mesh_arrays
from livemod.runner.execute import execute
from livemod.runner.stepshots import shoot_steps

SCRIPTS = Path(__file__).resolve().parents[1] / "scripts"

TWO_OBJECTS = """from livemod.dlfl import *
load("cube")
load("tetrahedron")
subdivide("catmull-clark")
"""


def test_every_step_is_shot_with_the_counts_its_record_says():
    shots = shoot_steps(SCRIPTS / "steps_demo.py")
    steps = shots.outcome.steps
    assert shots.outcome.status == "ok" and len(steps) == 12
    assert [shot.index for shot in shots.shots] == list(range(12))
    assert [shot.arrays.counts for shot in shots.shots] == [step.counts for step in steps]
    assert shots.steps == tuple(steps)
    assert all(not shot.arrays.positions.flags.writeable for shot in shots.shots)


def test_the_last_shot_is_the_scene_an_unpaused_run_leaves():
    shots = shoot_steps(SCRIPTS / "tower.py", parameters={"storeys": 3})
    plain = mesh_arrays(execute(SCRIPTS / "tower.py", parameters={"storeys": 3}).scene.mesh)
    last = shots.shots[-1].arrays
    assert last.counts == plain.counts
    assert np.array_equal(last.positions, plain.positions)
    assert np.array_equal(last.face_offsets, plain.face_offsets)


def test_only_the_steps_asked_for_are_shot_and_the_run_goes_to_its_end():
    shots = shoot_steps(SCRIPTS / "steps_demo.py", which={2, 5, 99})
    assert [shot.index for shot in shots.shots] == [2, 5]
    assert [step.label for step in shots.steps] == ["extrude", "storey 2"]
    assert len(shots.outcome.steps) == 12 and shots.outcome.status == "ok"
    assert shoot_steps(SCRIPTS / "steps_demo.py", which=()).shots == ()


def test_the_other_objects_are_shot_beside_the_current_one(tmp_path: Path):
    script = tmp_path / "two.py"
    script.write_text(TWO_OBJECTS)
    shots = shoot_steps(script)
    assert [step.label for step in shots.steps] == ["load cube", "load tetrahedron",
                                                   "subdivide"]
    assert [shot.others is None for shot in shots.shots] == [True, False, False]
    assert shots.shots[1].others.counts == (8, 12, 6)
    assert shots.shots[2].arrays.counts == (4 + 6 + 4, 2 * 12, 12)  # Catmull-Clark


def test_a_failing_run_keeps_the_shots_before_its_error(tmp_path: Path):
    script = tmp_path / "fails.py"
    script.write_text("from livemod.dlfl import *\nload('cube')\ndual()\nraise ValueError('x')\n")
    shots = shoot_steps(script)
    assert shots.outcome.error is not None and shots.outcome.error.line == 4
    assert [shot.arrays.counts for shot in shots.shots] == [(8, 12, 6), (6, 12, 8)]
