"""The face budget (livemod.dlfl.budget): where it comes from, what it refuses,
and that every growing operation and command checks it before it allocates."""

from __future__ import annotations

import itertools
import tracemalloc
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from livemod.dlfl import (
    BudgetExceededError,
    DLFLError,
    InvalidArgumentError,
    Mesh,
    Scene,
    budget,
    commands,
    cutting,
    extrusion,
    hull,
    multihandle,
    shapes,
    validate,
)
from livemod.dlfl import connect as con
from livemod.dlfl.build import point_cloud
from livemod.dlfl.rind import crust, rind
from livemod.dlfl.scene import use_scene
from livemod.dlfl.sierpinsky import sierpinsky
from livemod.dlfl.sponge import sponge
from livemod.dlfl.subdivision import COMPOSITES, SCHEMES, subdivide, subdivide_faces
from livemod.dlfl.subdivision._layout import counts_of
from livemod.dlfl.subdivision._sizes import EXACT, SIZES, check_steps
from livemod.dlfl.wireframe import columns, modified_corner_cut, wireframe
from tests.meshes import path_face, snapshot

Op = Callable[[Mesh, Any], object]


@pytest.fixture(autouse=True)
def session_default(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every test starts from the built-in default, whatever the machine sets, and
    leaves the environment as it found it (``--face-budget`` sets the variable)."""
    monkeypatch.setenv(budget.ENVIRONMENT_VARIABLE, "1")  # recorded, so undone after
    monkeypatch.delenv(budget.ENVIRONMENT_VARIABLE)
    monkeypatch.setattr(budget, "_session_default", None)


def needed(mesh: Mesh) -> int:
    """The smallest budget that allows ``mesh``."""
    return max(mesh.num_faces, -(-mesh.num_corners // budget.CORNERS_PER_FACE))


def with_sphere(mesh: Mesh) -> Mesh:
    mesh.create_vertex((9.0, 9.0, 9.0))
    return mesh


MESHES: list[Callable[[], Mesh]] = [
    shapes.cube, lambda: shapes.torus(5, 4), shapes.soccer_ball, lambda: shapes.grid(3, 2),
    lambda: with_sphere(shapes.cube()), path_face,
]


def built(make: Callable[[], Mesh], op: Op, max_faces: object) -> Mesh | None:
    """``op(make(), max_faces)``, or None when the operation refuses that mesh for
    another reason than the budget."""
    mesh = make()
    try:
        op(mesh, max_faces)
    except BudgetExceededError:
        raise
    except DLFLError:
        return None
    validate(mesh)
    return mesh


def assert_guarded(make: Callable[[], Mesh], op: Op, *, exact: bool) -> bool:
    """``op`` on ``make()`` with the budget one short of what its result needs is
    refused, the mesh unchanged; with ``exact``, the budget it needs is enough
    and the error names it. False when ``op`` refuses the mesh anyway."""
    result = built(make, op, None)
    if result is None:
        return False
    need = needed(result)
    mesh = make()
    before = snapshot(mesh)
    with pytest.raises(BudgetExceededError) as refused:
        op(mesh, need - 1)
    assert snapshot(mesh) == before
    assert refused.value.budget == need - 1 and refused.value.needed >= need
    if exact:
        assert refused.value.needed == need
        again = built(make, op, need)
        assert again is not None and again.counts() == result.counts()
    return True


# -- where the budget comes from ------------------------------------------------------

def test_the_default_is_twenty_million_faces():
    assert budget.face_budget() == budget.DEFAULT_FACE_BUDGET == 20_000_000


def test_the_session_default_comes_from_the_environment_or_a_call(monkeypatch):
    monkeypatch.setenv(budget.ENVIRONMENT_VARIABLE, "1234")
    assert budget.face_budget() == 1234
    budget.set_default_face_budget(99)
    assert budget.face_budget() == 99 and budget.face_budget(5) == 5
    budget.set_default_face_budget(None)
    assert budget.face_budget() == 1234


@pytest.mark.parametrize("text", ["x", "0", "-3", "1e6"])
def test_a_bad_environment_variable_is_named(monkeypatch, text):
    monkeypatch.setenv(budget.ENVIRONMENT_VARIABLE, text)
    with pytest.raises(InvalidArgumentError, match=f"LIVEMOD_FACE_BUDGET must be .*{text!r}"):
        budget.face_budget()


@pytest.mark.parametrize("value", ["x", "12", 0, -1, True, 1.5])
def test_a_bad_max_faces_is_an_invalid_argument(value):
    with pytest.raises(InvalidArgumentError, match="max_faces must be a whole number"):
        budget.face_budget(value)
    with pytest.raises(InvalidArgumentError):
        budget.set_default_face_budget(value)


def test_subdivide_checks_max_faces_even_where_nothing_grows():
    m = shapes.cube()
    before = snapshot(m)
    for scheme in ("pentagon", "vertex-cut"):  # vertex-cut at offset 0 changes nothing
        with pytest.raises(InvalidArgumentError, match="max_faces must be a whole number"):
            subdivide(m, scheme, max_faces="x", **({"offset": 0} if scheme == "vertex-cut" else {}))
    assert snapshot(m) == before


def test_the_message_states_the_budget_and_how_to_raise_it():
    with pytest.raises(BudgetExceededError) as refused:
        budget.check_size("loop", 30, 80, max_faces=20)
    message = str(refused.value)
    assert message.startswith("loop would produce 30 faces, more than the budget of 20 faces")
    for way in ("max_faces=N", "current_scene().face_budget = N", "--face-budget N",
                "LIVEMOD_FACE_BUDGET=N"):
        assert way in message
    assert (refused.value.needed, refused.value.budget) == (30, 20)


def test_corners_count_four_to_a_face():
    budget.check_size("f", 2, 40, max_faces=10)
    with pytest.raises(BudgetExceededError, match="would produce 41 corners, more than the "
                       r"budget of 10 faces allows \(4 corners a face: 40\)") as refused:
        budget.check_size("f", 2, 41, max_faces=10)
    assert refused.value.needed == 11


def test_huge_counts_saturate_instead_of_printing_a_million_digits():
    assert budget.repeated(24, 4, 3) == 24 * 64
    assert budget.repeated(0, 4, 10**9) == 0 and budget.repeated(5, 1, 10**9) == 5
    assert budget.repeated(24, 4, 10**9) == budget.SATURATED
    with pytest.raises(BudgetExceededError, match="more than 10\\^18 faces") as refused:
        budget.check_size("x", budget.repeated(3, 2, 10**6))
    assert refused.value.needed == budget.SATURATED


def test_scene_budget_reaches_the_commands_and_survives_a_copy():
    scene = Scene()
    scene.add(shapes.cube())
    scene.face_budget = 23
    assert scene.copy().face_budget == 23
    with use_scene(scene):
        with pytest.raises(BudgetExceededError, match="budget of 23 faces"):
            commands.subdivide("catmull-clark")
        commands.subdivide("catmull-clark", max_faces=24)  # the call's own budget wins
    assert scene.mesh.counts()[2] == 24


# -- every scheme's size, from counts --------------------------------------------------

@pytest.mark.parametrize("scheme", sorted(set(SCHEMES) - set(COMPOSITES)))
def test_each_scheme_refuses_one_face_short_of_its_result(scheme):
    def op(m: Mesh, max_faces: object) -> None:
        subdivide(m, scheme, max_faces=max_faces)
    assert sum(assert_guarded(make, op, exact=True) for make in MESHES) >= 3


@pytest.mark.parametrize("scheme", sorted(COMPOSITES))
def test_each_composite_refuses_one_face_short_of_its_result(scheme):
    # not exact: each of its three steps is checked as the steps would be, and a
    # middle step can be larger than the result (pentagon, dual, dual)
    def op(m: Mesh, max_faces: object) -> None:
        subdivide(m, scheme, max_faces=max_faces)
    assert sum(assert_guarded(make, op, exact=False) for make in MESHES) >= 3


@pytest.mark.parametrize("scheme", sorted(SIZES))
def test_sizes_from_counts_match_the_result(scheme):
    checked = 0
    for make in MESHES:
        mesh = make()
        c = counts_of(mesh)
        result = built(make, lambda m, _: subdivide(m, scheme), None)
        if result is None:
            continue
        faces, corners = SIZES[scheme](c)
        actual = result.num_faces - c.ns, result.num_corners - c.ns
        if scheme in EXACT:
            assert faces >= actual[0] and corners >= actual[1]
        else:
            assert (faces, corners) == actual
        checked += 1
    assert checked >= 3


def test_a_composite_checks_each_of_its_steps():
    m = shapes.cube()  # dual: 8 faces; checker on it: 8 + 48; the dual back: 6 + 48
    assert check_steps(m, ("dual", "checker", "dual"), 56).nf == 54
    with pytest.raises(BudgetExceededError, match="^checker would produce 56 faces"):
        check_steps(m, ("dual", "checker", "dual"), 55)


def test_subdivide_faces_counts_the_selected_faces_exactly():
    for quads in (True, False):
        def op(m: Mesh, max_faces: object, quads: bool = quads) -> None:
            subdivide_faces(m, m.face_ids().tolist()[:2], usequads=quads, max_faces=max_faces)
        assert assert_guarded(lambda: shapes.torus(5, 4), op, exact=True)


# -- the other growing operations ------------------------------------------------------

def _first_two_corners(m: Mesh) -> tuple[int, int]:
    """A corner of face 0 and one of the face opposite it on a cube or prism."""
    faces = m.face_ids().tolist()
    return m.face_corner(faces[0]), m.face_corner(faces[1])


LIBRARY: list[tuple[str, Callable[[], Mesh], Op, bool]] = [
    ("connect_faces 5 segments", shapes.cube,
     lambda m, b: con.connect_faces(m, *_first_two_corners(m), 5, max_faces=b), False),
    ("connect_corners dual", shapes.cube,
     lambda m, b: con.connect_corners(m, *_first_two_corners(m), 4, dual=True, max_faces=b),
     False),
    ("connect_faces_closest", shapes.cube,
     lambda m, b: con.connect_faces_closest(m, 0, 1, 3, max_faces=b), False),
    ("hermite_handle", shapes.cube,
     lambda m, b: con.hermite_handle(m, *_first_two_corners(m), 6, max_faces=b), False),
    ("bezier_handle", shapes.cube,
     lambda m, b: con.bezier_handle(m, *_first_two_corners(m), 6, max_faces=b), False),
    ("crust", shapes.cube, lambda m, b: crust(m, 0.1, max_faces=b), True),
    ("rind", lambda: shapes.torus(6, 4),
     lambda m, b: rind(m, [0, 5, 11], 0.05, max_faces=b), False),
    ("wireframe", shapes.soccer_ball, lambda m, b: wireframe(m, 0.02, max_faces=b),
     True),
    ("wireframe of a grid", lambda: shapes.grid(3, 2),
     lambda m, b: wireframe(m, 0.02, max_faces=b), True),
    ("modified corner cut", shapes.soccer_ball,
     lambda m, b: modified_corner_cut(m, 0.05, max_faces=b), True),
    ("columns", shapes.cube, lambda m, b: columns(m, 0.1, 5, max_faces=b), False),
    ("sponge", shapes.cube, lambda m, b: sponge(m, max_faces=b), False),
    ("sierpinsky", lambda: shapes.torus(5, 4),
     lambda m, b: sierpinsky(m, max_faces=b), True),
    ("convex hull", lambda: point_cloud(np.random.default_rng(1).normal(size=(40, 3))),
     lambda m, b: hull.convex_hull(m, max_faces=b), False),
    ("dual convex hull", lambda: point_cloud(np.random.default_rng(1).normal(size=(40, 3))),
     lambda m, b: hull.dual_convex_hull(m, max_faces=b), False),
    ("multi-face handle", shapes.cube,
     lambda m, b: multihandle.multi_face_handle(m, [0, 2, 4], max_faces=b), False),
    ("closest-edge handle", shapes.cube,
     lambda m, b: multihandle.multi_face_handle_closest_edges(m, [0, 1], max_faces=b), False),
    ("cut vertices", shapes.cube, lambda m, b: cutting.cut_vertices(m, [0, 6], max_faces=b),
     False),
    ("truncate", lambda: with_sphere(shapes.torus(5, 4)),
     lambda m, b: cutting.truncate(m, max_faces=b), True),
]


@pytest.mark.parametrize(("make", "op", "exact"), [case[1:] for case in LIBRARY],
                         ids=[case[0] for case in LIBRARY])
def test_each_growing_operation_refuses_one_face_short(make, op, exact):
    assert assert_guarded(make, op, exact=exact)


def prism(n: int) -> Mesh:
    angles = np.linspace(0, 2 * np.pi, n, endpoint=False)
    ring = np.stack([np.cos(angles), np.sin(angles), np.zeros(n)], axis=1)
    faces = [list(range(n))[::-1], list(range(n, 2 * n))]
    faces += [[i, (i + 1) % n, n + (i + 1) % n, n + i] for i in range(n)]
    from livemod.dlfl import from_polygons

    return from_polygons(np.concatenate([ring, ring + [0, 0, 1]]), faces)


@pytest.mark.parametrize("kind", list(extrusion.KINDS))
def test_each_extrusion_kind_stays_within_its_stated_growth(kind):
    spec = extrusion.KINDS[kind]
    for sides, segments in itertools.product((3, 4, 7), (1, 3) if spec.step else (1,)):
        def op(m: Mesh, b: object, segments: int = segments) -> object:
            if spec.fan is not None:
                return extrusion.extrude_fan(m, 1, kind, 0.5, max_faces=b)
            return extrusion.extrude(m, 1, kind, 0.5, segments, max_faces=b)
        assert assert_guarded(lambda sides=sides: prism(sides), op, exact=False)


# -- huge counts: refused at once, nothing allocated, the scene unchanged ----------------

def scene_snapshot(scene: Scene) -> tuple[Any, ...]:
    return tuple((oid, snapshot(obj.mesh)) for oid, obj in scene.objects.items())


def refused_without_allocating(scene: Scene, call: Callable[[], object]) -> str:
    """Run ``call`` in ``scene``: it must raise BudgetExceededError, allocate
    under 1 MB on the way and leave the scene as it was. Returns the message."""
    before = scene_snapshot(scene)
    with use_scene(scene):
        tracemalloc.start()
        try:
            with pytest.raises(BudgetExceededError) as refused:
                call()
            peak = tracemalloc.get_traced_memory()[1]
        finally:
            tracemalloc.stop()
    assert peak < 2**20, peak
    assert scene_snapshot(scene) == before
    return str(refused.value)


def cube_scene() -> Scene:
    scene = Scene()
    scene.add(shapes.cube())
    return scene


def _corners(scene: Scene) -> tuple[Any, Any]:
    with use_scene(scene):
        return commands.cornerWalk(0)[0], commands.cornerWalk(1)[0]


HUGE: list[tuple[str, Callable[[Scene], object]]] = [
    ("subdivideEdge 10**9", lambda s: commands.subdivideEdge(10**9, 0)),
    ("connectCorners 10**9", lambda s: commands.connectCorners(*_corners(s), 10**9)),
    ("connectCorners dual 10**9",
     lambda s: commands.connectCorners(*_corners(s), 10**9, -1, "dual")),
    ("connectFaces 10**9", lambda s: commands.connectFaces(0, 1, 10**9)),
    ("addHandle hermite 10**9", lambda s: commands.addHandle("hermite", *_corners(s), 10**9)),
    ("addHandle bezier 10**9", lambda s: commands.addHandle("bezier", *_corners(s), 10**9)),
    ("extrude 10**9 segments", lambda s: commands.extrude("cubical", 0, 2.0, 10**9)),
    ("createFace of 10**8 points",  # 2 * 10**8 corners; the budget allows 4 a face
     lambda s: commands.createFace(np.broadcast_to(np.zeros(3), (10**8, 3)))),
    ("catmull-clark levels=10**6", lambda s: commands.subdivide("catmull-clark", levels=10**6)),
    ("catmull-clark levels=10**9", lambda s: commands.subdivide("catmull-clark", levels=10**9)),
    ("column of 10**8 segments", lambda s: commands.column(0.1, 10**8)),
]


@pytest.mark.parametrize("call", [case[1] for case in HUGE], ids=[case[0] for case in HUGE])
def test_huge_counts_are_refused_before_anything_is_allocated(call):
    scene = cube_scene()
    message = refused_without_allocating(scene, lambda: call(scene))
    assert "budget of 20,000,000 faces" in message


def test_create_face_of_ten_million_points_under_a_smaller_budget():
    scene = cube_scene()
    scene.face_budget = 4_000_000  # 16,000,000 corners
    message = refused_without_allocating(
        scene, lambda: commands.createFace(np.broadcast_to(np.zeros(3), (10**7, 3))))
    assert message.startswith("createFace would produce 20,000,024 corners")


def test_an_endless_point_iterator_is_read_only_up_to_the_budget():
    scene = cube_scene()
    scene.face_budget = 100  # room for (400 - 24) / 2 = 188 points
    taken = itertools.count()
    points = ((float(next(taken)), 0.0, 0.0) for _ in itertools.repeat(None))
    refused_without_allocating(scene, lambda: commands.createFace(points))
    assert next(taken) == 189


GROWING_COMMANDS: list[tuple[str, Callable[[], object]]] = [
    ("crust", lambda: commands.crust(0.01)),
    ("wireframe", lambda: commands.wireframe(0.01)),
    ("truncate", lambda: commands.truncate(0.1)),
    ("sierpinsky", commands.sierpinsky),
    ("catmull-clark", lambda: commands.subdivide("catmull-clark")),
    ("loop", lambda: commands.subdivide("loop")),
    ("star", lambda: commands.subdivide("star")),
]


@pytest.mark.parametrize("grow", [case[1] for case in GROWING_COMMANDS],
                         ids=[case[0] for case in GROWING_COMMANDS])
def test_repeated_growth_stops_at_the_scene_budget(grow):
    scene = cube_scene()
    scene.face_budget = 3000
    with use_scene(scene):
        for _ in range(12):
            before = scene_snapshot(scene)
            try:
                grow()
            except BudgetExceededError as refused:
                assert refused.budget == 3000 and refused.needed > 3000
                assert scene_snapshot(scene) == before
                return
            assert needed(scene.mesh) <= 3000
            validate(scene.mesh)
    pytest.fail("never refused")


def test_a_menger_sponge_over_the_budget_is_refused():
    scene = cube_scene()
    scene.face_budget = 83  # 64/156/84: at most 7 E + V faces, 15 C corners
    refused_without_allocating(scene, commands.menger)


# -- the session's budget from the command line ------------------------------------------

GROWS = "load('cube')\nsubdivide('catmull-clark')\nsubdivide('catmull-clark')\n"


def test_run_face_budget_refuses_what_passes_it(tmp_path, capsys):
    from livemod import cli

    script = tmp_path / "grow.py"
    script.write_text(GROWS)
    assert cli.main(["run", str(script), "--face-budget", "95"]) == 1
    assert "catmull-clark would produce 96 faces, more than the budget of 95 faces" in (
        capsys.readouterr().err)
    assert cli.main(["run", str(script), "--face-budget", "96"]) == 0


@pytest.mark.timeout(120)
def test_batch_face_budget_reaches_the_worker_processes(tmp_path, capsys):
    from livemod import cli

    script = tmp_path / "grow.py"
    script.write_text("n = param('n', 1)\n" + GROWS)
    code = cli.main(["batch", str(script), "--param", "n=1:2:2", "--face-budget", "95",
                     "-o", str(tmp_path / "g_{index}.obj"), "-j", "2"])
    captured = capsys.readouterr()
    assert code == 1
    assert captured.err.count("more than the budget of 95 faces") == 2, captured.err


@pytest.mark.parametrize("command", ["run", "batch", "view"])
def test_a_bad_face_budget_is_a_usage_error(command, capsys):
    from livemod import cli

    with pytest.raises(SystemExit) as stopped:
        cli.main([command, "x.py", "--face-budget", "0", *(["--param", "n=1"]
                                                          if command == "batch" else [])])
    assert stopped.value.code == 2
    assert "the face budget must be a whole number >= 1, not '0'" in capsys.readouterr().err


def test_the_environment_is_read_through_whatever_os_environ_is(monkeypatch):
    monkeypatch.setenv(budget.ENVIRONMENT_VARIABLE, "1234")
    assert budget.face_budget() == 1234
    monkeypatch.delenv(budget.ENVIRONMENT_VARIABLE)
    assert budget.face_budget() == budget.DEFAULT_FACE_BUDGET
    # a mapping that is not the interpreter's own (a test's, an embedder's)
    monkeypatch.setattr(budget.os, "environ", {budget.ENVIRONMENT_VARIABLE: "77"})
    assert budget.face_budget() == 77
    with pytest.raises(BudgetExceededError, match="budget of 77 faces"):
        budget.check_size("loop", 78)
