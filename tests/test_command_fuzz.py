"""Bad arguments to every thesis command: a seeded fuzz (tests/command_fuzz.py) and
the cases it and issue 30 found, each kept as a regression.

The contract: a refusal is a DLFLError and leaves the scene byte-identical, and
every mesh passes validate after every call; no numpy warning on the way
(pytest turns warnings into errors). fuzz/fuzz_commands.py runs the same
engine far longer.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from livemod.dlfl import (
    BudgetExceededError,
    DLFLError,
    GeometryError,
    InvalidArgumentError,
    Scene,
    UnknownIdError,
    commands,
    shapes,
    validate,
)
from livemod.dlfl._checks import finite_number, finite_vector, id_list, shown
from livemod.dlfl.scene import current_scene, use_scene
from tests.command_fuzz import Fuzzer, Report, describe, run, scene_state


def test_a_seeded_run_keeps_the_contract(tmp_path):
    report = run(range(2), 150, str(tmp_path))
    assert report.failures == [] and report.slow == [], describe(report, float("nan"))
    assert report.calls == 300
    # the mix reaches most commands and refuses a good share of the calls
    assert len(report.commands_called) >= 45
    assert 0.2 * report.calls < sum(report.refusals.values()) < 0.8 * report.calls


def test_the_fuzz_catches_a_broken_contract(tmp_path, monkeypatch):
    """A command that changes the scene and then refuses is reported."""
    def broken(*args: Any, **keywords: Any) -> None:
        current_scene().mesh.create_vertex((0.0, 0.0, 0.0))
        raise DLFLError("refused after a change")

    monkeypatch.setattr(commands, "meshsmooth", broken)
    fuzzer = Fuzzer(0, str(tmp_path))
    fuzzer.call = lambda: ("meshsmooth()", commands.meshsmooth)  # type: ignore[method-assign]
    report = Report()
    fuzzer.step(0, report)
    assert [what for *_, what in report.failures] == [
        "refusal changed the scene: refused after a change"]


def cube_scene() -> Scene:
    scene = Scene()
    scene.add(shapes.cube())
    return scene


def refused(call: Callable[[], object], error: type[DLFLError], message: str,
            scene: Scene | None = None) -> None:
    """``call()`` in a cube scene raises ``error`` matching ``message``, the scene
    unchanged and valid."""
    scene = scene or cube_scene()
    before = scene_state(scene)
    with use_scene(scene), pytest.raises(error, match=message):
        call()
    assert scene_state(scene) == before
    validate(scene.mesh)


# -- issue 30 section 5: only the project's errors escape a command -------------------

def test_ids_beyond_int64_are_unknown_ids_not_overflow_errors():
    refused(lambda: commands.move([2**64], (0, 0, 0)), UnknownIdError,
            "no element has the id 18446744073709551616")
    refused(lambda: commands.rind([2**64], False, 0.1), UnknownIdError, "no element has the id")
    refused(lambda: commands.cutVertices([np.uint64(2**64 - 1)]), UnknownIdError,
            "no element has the id")
    refused(lambda: commands.subdivideFaces([-2**63 - 1]), UnknownIdError, "below 2\\*\\*63")


def test_numbers_beyond_the_float_range_are_invalid_arguments():
    refused(lambda: commands.crust(10**400), InvalidArgumentError,
            "thickness must be finite, got an integer of 401 digits")
    refused(lambda: commands.createVertex((10**400, 0, 0)), DLFLError, "three finite numbers|"
            "three numbers")
    refused(lambda: commands.translate(10**400, 0, 0), DLFLError, "three numbers")
    refused(lambda: commands.addHandle("hermite", (0, 0), (1, 4), 3, 10**400), DLFLError,
            "w1 must be finite")


def test_a_number_too_long_to_print_is_named_by_its_size():
    # str() of over 4,300 digits raises ValueError: the message must not try
    refused(lambda: commands.subdivideEdge(10**5000, 0), InvalidArgumentError,
            "an integer of over 4,000 digits")
    refused(lambda: commands.wireframe(-10**5000), InvalidArgumentError, "over 4,000 digits")
    assert shown([10**5000]) == "a list holding a number too long to print"
    assert shown("x" * 500).endswith("...") and len(shown("x" * 500)) == 80


def test_a_bad_face_budget_is_an_invalid_argument():
    refused(lambda: commands.subdivide("pentagon", max_faces="x"), InvalidArgumentError,
            "max_faces must be a whole number of faces >= 1, got 'x'")


def test_param_bounds_must_be_numbers():
    refused(lambda: commands.param("n", 1, 0.2, "0.5"), InvalidArgumentError,
            "parameter 'n': max must be a number, got '0.5'")
    refused(lambda: commands.param("n", 1, step=0), InvalidArgumentError,
            "step must be a positive number")
    refused(lambda: commands.param("n", 1, choices=5), InvalidArgumentError,
            "choices must be a non-empty list, got 5")


def scaled_cube(factor: float) -> Scene:
    scene = cube_scene()
    m = scene.mesh
    m.set_positions(m.vertex_ids(), m.positions_view() * factor)
    return scene


@pytest.mark.parametrize("factor", [1e-320, 1e-300, 1.7e308])
@pytest.mark.parametrize("command", [commands.planarize, commands.meshsmooth,
                                     commands.spheralize, lambda: commands.crust(0.1),
                                     lambda: commands.edgeInfo(0)])
def test_denormal_and_huge_coordinates_warn_of_nothing(command, factor):
    """Rings of denormal coordinates scaled by one power of two past 2**1024
    overflowed (_vectors.ring_vectors); the commands either work or refuse."""
    scene = scaled_cube(factor)
    before = scene_state(scene)
    with use_scene(scene):
        try:
            command()
        except DLFLError:
            assert scene_state(scene) == before
    validate(scene.mesh)


def test_columns_of_a_mesh_beyond_the_float_range_are_refused():
    refused(commands.convexHull, DLFLError, "overflow", scaled_cube(1.7e308))
    refused(lambda: commands.column(0.1, 4), DLFLError, "shorter than the float range",
            scaled_cube(1.7e308))


@pytest.mark.parametrize("collapse", [[0, 1], [0, 1, 2, 3], list(range(8))])
def test_columns_of_degenerate_meshes_are_refused(collapse):
    """Vertices pulled onto one point: a joint's hull turned a plane about a zero
    vector (0/0 in hull._unit3)."""
    scene = cube_scene()
    m = scene.mesh
    m.set_positions(collapse, np.zeros(3))
    refused(lambda: commands.column(0.1, 4), DLFLError, ".", scene)


def test_the_helpers_name_what_was_wrong():
    with pytest.raises(InvalidArgumentError, match="x must be finite, got an integer of 401"):
        finite_number(10**400, "x")
    with pytest.raises(InvalidArgumentError, match="p must be three finite numbers"):
        finite_vector([10**400, 0, 0], "p")
    with pytest.raises(UnknownIdError, match="ids: no element has the id"):
        id_list([0, 2**63], "ids")
    assert id_list([np.int64(-1), 2**63 - 1], "ids") == [-1, 2**63 - 1]


def test_a_budget_refusal_is_a_refusal_like_any_other():
    scene = cube_scene()
    scene.face_budget = 10
    refused(lambda: commands.subdivide("catmull-clark"), BudgetExceededError,
            "budget of 10 faces", scene)


def test_loading_a_folder_is_a_refusal(tmp_path):
    """The readers raise IsADirectoryError for a folder; the command says so as a
    DLFLError, as ``save`` does for what the system refuses."""
    refused(lambda: commands.load(str(tmp_path)), InvalidArgumentError,
            "cannot load .*is a folder, not a mesh file")


def test_a_scale_whose_running_total_overflows_is_refused():
    """A point-sphere at the origin never overflows, but the object's total scale
    did, with a numpy warning (the fuzz's seed 1 found it)."""
    scene = Scene()
    with use_scene(scene):
        commands.createVertex((0, 0, 0))
        commands.scale((1e200, 1e200, 1e200))
    refused(lambda: commands.scale((1e200, 1.0, 1.0)), GeometryError,
            r"total scale overflow: \[inf, 1e\+200, 1e\+200\]", scene)
