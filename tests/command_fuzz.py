"""Random thesis commands with bad arguments mixed in: the engine of the command
fuzz (tests/test_command_fuzz.py runs a small seeded budget of it in CI,
fuzz/fuzz_commands.py a long one).

Every command of :mod:`livemod.dlfl.commands` is called with arguments drawn
from pools of good values (live ids, corners of the mesh, sensible numbers) and
bad ones (huge and negative ids, floats and bools for ids, NaN, infinities,
huge counts, 10**400, strings, wrong shapes). After every call the contract is
checked:

* a refusal is a :class:`~livemod.dlfl.errors.DLFLError` (no other exception, no
  numpy RuntimeWarning: warnings are errors here) and leaves the scene
  byte-identical (every object's dense arrays and id counters, the current
  object, the selection);
* the scene's meshes pass :func:`~livemod.dlfl.validate` after every call.

A call over :data:`SLOW` seconds is recorded as slow (a hang, if it never
ends). A scene budget keeps the meshes small, so refusals by the budget are
part of the mix; a mesh over :data:`RESET_FACES` faces is replaced.
"""

from __future__ import annotations

import contextlib
import io
import math
import random
import time
import traceback
import warnings
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from livemod.dlfl import DLFLError, DLFLRepairWarning, Scene, commands, mesh_arrays, validate
from livemod.dlfl._checks import shown
from livemod.dlfl.commands._base import Corner
from livemod.dlfl.extrusion import kind_names
from livemod.dlfl.run_context import RunContext, use_run
from livemod.dlfl.scene import Selection, use_scene
from livemod.dlfl.subdivision import SCHEMES, scheme_options

SLOW = 5.0
RESET_FACES = 400
MAX_OBJECTS = 3
SCENE_BUDGET = 3000
SHAPES = ("cube", "tetrahedron", "octahedron", "torus", "soccerball", "dodecahedron")

BAD_IDS: list[Any] = [-1, -2**70, 2**31, 2**63, 2**64, 10**30, 10**5000, 0.0, 1.5, float("nan"),
                      float("inf"), True, False, None, "0", b"1", [0], (0,), {0: 0},
                      np.int64(-5), np.uint64(2**64 - 1), np.float64(2.0), complex(1, 0)]
BAD_NUMBERS: list[Any] = [float("nan"), float("inf"), -float("inf"), 1e308, -1e308, 1e-308,
                          10**400, -10**400, 10**5000, 2**64, "0.5", None, True, [0.5],
                          complex(0, 1),
                          np.float32(3e38), np.float64("nan"), 0, -0.0, 1e200, -1e200]
GOOD_NUMBERS: list[Any] = [0.05, 0.1, 0.25, 0.3, 0.5, 1.0, 2.0, -0.25, 0.9, 3, np.float64(0.2)]
BAD_COUNTS: list[Any] = [0, -1, 10**9, 10**12, 2**64, 10**400, 10**5000, 1.5, 2.0, "3", None, True,
                         float("nan"), float("inf"), np.int64(2**40)]
GOOD_COUNTS: list[Any] = [1, 2, 3, 4, np.int64(2)]
BAD_POINTS: list[Any] = [(1, 2), (1, 2, 3, 4), "abc", b"xyz", None, 5, (float("nan"), 0, 0),
                         (float("inf"), 0, 0), (1e308, 1e308, 1e308), (-1e308, 1e308, 0),
                         (10**400, 0, 0), [[1, 2, 3]], ("1", "2", "3"), {1: 2}, np.zeros(4)]
BAD_STRINGS: list[Any] = ["", "nope", "CATMULL-CLARK", None, 3, b"loop", ["loop"], "d", "\x00"]


@dataclass
class Report:
    """What a fuzz run found.

    Attributes:
        calls: commands called. refusals: DLFLError type name -> count.
        failures: (seed, step, call, what went wrong) for every broken contract:
            another exception or a warning, a refusal that changed the scene, a
            mesh that fails validate.
        slow: (seconds, call) of each call over :data:`SLOW` seconds.
    """

    calls: int = 0
    refusals: Counter[str] = field(default_factory=Counter)
    failures: list[tuple[int, int, str, str]] = field(default_factory=list)
    slow: list[tuple[float, str]] = field(default_factory=list)
    commands_called: Counter[str] = field(default_factory=Counter)


def scene_state(scene: Scene) -> tuple[Any, ...]:
    """Everything a refused command must leave as it was: per object its dense
    arrays byte for byte and its id counters (what :func:`tests.meshes.snapshot`
    compares, as bytes: many times faster), its name and transform record."""
    meshes = tuple((oid, obj.name, _mesh_bytes(obj.mesh), obj.origin.tobytes(),
                    obj.factor.tobytes()) for oid, obj in scene.objects.items())
    return scene.current, scene.selection, meshes


def _mesh_bytes(mesh: Any) -> tuple[Any, ...]:
    a = mesh_arrays(mesh)
    arrays = (getattr(a, name) for name in a.__dataclass_fields__)
    return (*(None if x is None else x.tobytes() for x in arrays), mesh.next_ids())


class Fuzzer:
    """Draws commands and arguments from one seeded generator for one scene."""

    def __init__(self, seed: int, directory: str) -> None:
        self.rng = random.Random(seed)
        self.seed = seed
        self.directory = directory
        self.scene = Scene()
        self.scene.face_budget = SCENE_BUDGET
        self.run = RunContext(directory=directory)  # file names are relative to it

    # -- values -------------------------------------------------------------------

    def pick(self, good: Callable[[], Any], bad: list[Any], bad_share: float = 0.3) -> Any:
        if self.rng.random() < bad_share:
            return self.rng.choice(bad)
        return good()

    def _live(self, ids: np.ndarray) -> Any:
        return int(self.rng.choice(ids.tolist())) if len(ids) else 0

    def face(self) -> Any:
        return self.pick(lambda: self._live(self.scene.mesh.face_ids()), BAD_IDS)

    def edge(self) -> Any:
        return self.pick(lambda: self._live(self.scene.mesh.edge_ids()), BAD_IDS)

    def vertex(self) -> Any:
        return self.pick(lambda: self._live(self.scene.mesh.vertex_ids()), BAD_IDS)

    def ids(self, one: Callable[[], Any]) -> Any:
        def good() -> Any:
            return [one() for _ in range(self.rng.randint(0, 4))]
        return self.pick(good, ["abc", 5, None, [[0]], {1, 2}, range(3), np.arange(3.0),
                                [2**64], np.array([-1])], 0.25)

    def corner(self) -> Any:
        m = self.scene.mesh

        def good() -> Any:
            cid = self._live(m.corner_ids())
            if not m.has_corner(cid):
                return (0, 0)
            face, vertex = m.corner_face(cid), m.corner_vertex(cid)
            return self.rng.choice([(face, vertex), Corner(face, vertex, cid), cid, [face, vertex]])
        return self.pick(good, [(0,), (0, 0, 0), ("a", "b"), (2**64, 0), (0, 2**64), 1.5,
                                None, "c", (True, False), (-1, -1)])

    def number(self) -> Any:
        return self.pick(lambda: self.rng.choice(GOOD_NUMBERS), BAD_NUMBERS)

    def count(self) -> Any:
        return self.pick(lambda: self.rng.choice(GOOD_COUNTS), BAD_COUNTS)

    def flag(self) -> Any:
        return self.rng.choice([True, False, 0, 1, np.bool_(True), "no", None, 2, 0.5])

    def point(self) -> Any:
        return self.pick(lambda: tuple(self.rng.uniform(-3, 3) for _ in range(3)), BAD_POINTS)

    def points(self) -> Any:
        def good() -> Any:
            return [self.point() for _ in range(self.rng.randint(0, 6))]
        return self.pick(good, ["abc", None, 5, np.zeros((3, 2)), np.zeros((4, 3)),
                                np.broadcast_to(np.ones(3), (10**8, 3)), iter([(0, 0, 0)] * 3),
                                [(0, 0, 0)] * 3, [[0, 0]] * 3], 0.3)

    def color(self) -> Any:
        return self.pick(lambda: tuple(self.rng.choice([0, 0.25, 1.0]) for _ in range(3)),
                         [*BAD_POINTS, None, (255, 0, 0), (-0.1, 0, 0), (1.5, 0.5, 0.5)])

    def maybe(self, *makers: Callable[[], Any]) -> list[Any]:
        """A prefix of the optional arguments ``makers`` make, each drawn."""
        return [make() for make in makers[: self.rng.randint(0, len(makers))]]

    def scheme(self) -> Any:
        return self.pick(lambda: self.rng.choice(sorted(SCHEMES)), BAD_STRINGS, 0.15)

    def scheme_keywords(self, scheme: Any) -> dict[str, Any]:
        try:
            names = scheme_options(scheme)
        except DLFLError:
            names = []
        keywords = {name: self.number() for name in names if self.rng.random() < 0.4}
        if self.rng.random() < 0.2:
            keywords["max_faces"] = self.rng.choice([1, 10, "x", 0, 2**64, None, 1.5])
        if self.rng.random() < 0.1:
            keywords["levels"] = self.count()
        if self.rng.random() < 0.05:
            keywords["bogus"] = 1
        return keywords

    def keyword_options(self, name: str) -> dict[str, Any]:
        """Now and then some of the options of ``name`` that only a keyword sets
        (TopMod's GUI options), drawn good or bad."""
        pinch = {"pinch": self.number, "pinchCenter": self.number, "bubble": self.number}
        shape = {"angle": self.number, "l1": self.number, "l2": self.number, "l3": self.number}
        table: dict[str, dict[str, Callable[[], Any]]] = {
            "extrude": {"fan": self.flag, "segments": self.count, "mesh": self.flag, **shape},
            "connectFaces": pinch, "connectCorners": pinch, "addHandle": pinch,
            "wireframe": {"width": self.number}, "crust": {"scale": self.number},
            "menger": {"keep2gons": self.flag, "collapse": self.number}, "rind": {"cleanup": self.flag},
        }
        options = table.get(name, {})
        return {key: make() for key, make in options.items() if self.rng.random() < 0.25}

    def kind(self) -> Any:
        """A kind of element a selection holds, now and then a wrong one."""
        return self.rng.choice(["faces", "edges", "vertices", "verts", "corners", "loops", 3])

    def filename(self) -> Any:
        return self.rng.choice([*SHAPES, "nope", "missing.obj", f"{self.directory}/out.obj",
                                f"{self.directory}/out.dlfl", f"{self.directory}/out.stl",
                                f"{self.directory}/out.ply", f"{self.directory}/out.xyz",
                                self.directory, "", None, 5, b"cube"])

    # -- calls ----------------------------------------------------------------------

    def call(self) -> tuple[str, Callable[[], Any]]:
        """A command and its arguments, as ``(text, thunk)``."""
        name = self.rng.choice(commands.__all__)
        args, keywords = self.arguments(name)
        text = f"{name}({', '.join(_short(a) for a in args)}"
        text += "".join(f", {k}={_short(v)}" for k, v in keywords.items()) + ")"
        return text, lambda: getattr(commands, name)(*args, **keywords)

    def arguments(self, name: str) -> tuple[list[Any], dict[str, Any]]:
        r = self.rng
        table: dict[str, Callable[[], list[Any]]] = {
            "createVertex": lambda: self.maybe(self.point),
            "removeVertex": lambda: [r.choice([self.vertex(), self.corner()])],
            "insertEdge": lambda: [self.corner(), self.corner(), *self.maybe(self.flag)],
            "deleteEdge": lambda: [self.edge(), *self.maybe(self.flag)],
            "subdivideEdge": lambda: r.choice([[self.edge()], [self.count(), self.edge()], []]),
            "collapseEdge": lambda: [self.edge(), *self.maybe(self.flag)],
            "trisectEdge": lambda: [self.edge(), self.number(), self.flag()],
            "spliceCorners": lambda: [self.corner(), self.corner()],
            "createFace": lambda: [self.points(), *self.maybe(self.flag)],
            "walk": lambda: [self.face()],
            "cornerWalk": lambda: [self.face()],
            "next": lambda: [self.corner()],
            "prev": lambda: [self.corner()],
            "getCorner": lambda: [self.edge(), self.face()],
            "saveCorner": lambda: [self.corner()],
            "restoreCorner": lambda: [self.pick(lambda: self._live(self.scene.mesh.corner_ids()),
                                                BAD_IDS)],
            "load": lambda: [self.filename()],
            "save": lambda: [self.filename()],
            "kill": lambda: [self.pick(lambda: r.choice(list(self.scene.objects) or [0]),
                                       BAD_IDS)],
            "switch": lambda: [self.pick(lambda: r.choice(list(self.scene.objects) or [0]),
                                         BAD_IDS)],
            "vertexInfo": lambda: [self.vertex()],
            "edgeInfo": lambda: [self.edge()],
            "faceInfo": lambda: [self.face()],
            "cornerInfo": lambda: [self.corner()],
            "vertexEdges": lambda: [self.vertex()],
            "centroid": lambda: self.maybe(lambda: self.ids(self.vertex)),
            "translate": lambda: r.choice([[self.point()], [self.number(), self.number(),
                                                            self.number()], []]),
            "scale": lambda: r.choice([[self.point()], [self.number()] * 3]),
            "move": lambda: [self.ids(self.vertex), self.point(), *self.maybe(self.flag)],
            "step": lambda: self.maybe(lambda: r.choice(["s", 5, None, "x" * 300])),
            "subdivide": lambda: [self.scheme()],
            "subdivideFace": lambda: [self.face(), *self.maybe(self.flag)],
            "subdivideFaces": lambda: self.maybe(lambda: self.ids(self.face), self.flag),
            "dual": lambda: self.maybe(self.flag),
            "extrude": lambda: [self.pick(lambda: r.choice(kind_names()), BAD_STRINGS, 0.15),
                                r.choice([self.face(), self.face(), self.ids(self.face)]),
                                *self.maybe(self.number, self.count, self.number,
                                                         self.number, self.flag)],
            "connectEdges": lambda: [(self.edge(), self.face()), (self.edge(), self.face()),
                                     *self.maybe(self.flag)],
            "connectCorners": lambda: [self.corner(), self.corner(),
                                       *self.maybe(self.count, lambda: r.choice([-1, 0, 1, 2.5]),
                                                   lambda: r.choice(["dual", "x", True, 0]))],
            "connectFaces": lambda: [self.face(), self.face(),
                                     *self.maybe(self.count, lambda: r.choice([-1, 1, "a"]))],
            "addHandle": lambda: [r.choice(["hermite", "bezier", "spline", None]), self.corner(),
                                  self.corner(), self.count(),
                                  *self.maybe(self.number, self.number,
                                              lambda: r.choice([-1, 2]), self.count)],
            "rind": lambda: [self.ids(self.face), self.flag(), self.number(),
                             *self.maybe(self.flag)],
            "wireframe": lambda: self.maybe(self.number, self.flag),
            "column": lambda: [self.number(), self.pick(lambda: r.choice([3, 4, 5, 6.0]),
                                                        BAD_COUNTS)],
            "crust": lambda: self.maybe(self.number, self.flag),
            "menger": lambda: self.maybe(self.number, self.number),
            "multiConnectFaces": lambda: [self.ids(self.face),
                                          *self.maybe(self.number, self.number, self.flag,
                                                      lambda: r.choice(["hull", "closest-edge",
                                                                        "fitted", "x"]),
                                                      self.number)],
            "param": lambda: [r.choice(["n", "t", "", 5, "not a name"]),
                              r.choice([1, 0.5, "a", True, None, [1]]),
                              *self.maybe(self.number, self.number)],
            "cutVertices": lambda: self.maybe(lambda: self.ids(self.vertex), self.number),
            "cutEdges": lambda: self.maybe(lambda: self.ids(self.edge), self.number),
            "cutFaces": lambda: self.maybe(lambda: self.ids(self.face), self.number),
            "truncate": lambda: self.maybe(self.number),
            "punch": lambda: self.maybe(lambda: self.ids(self.face), self.flag),
            "edgeCleanup": lambda: self.maybe(lambda: self.ids(self.edge)),
            "splitValence2Vertices": lambda: self.maybe(self.number),
            "reverseOrientation": lambda: self.maybe(lambda: self.ids(self.face)),
            "edge_loop": lambda: [r.choice([self.edge(), self.ids(self.edge)])],
            "edge_ring": lambda: [self.edge()],
            "face_loop": lambda: [self.edge()],
            "checkerboard": lambda: [r.choice([self.face(), self.ids(self.face)])],
            "similar_faces": lambda: [self.face(), *self.maybe(
                lambda: r.choice(["size", "area", "colour", 3]), self.number)],
            "similar_edges": lambda: [self.edge()],
            "similar_vertices": lambda: [self.vertex()],
            "grow_selection": lambda: self.maybe(lambda: self.ids(self.face), self.kind),
            "shrink_selection": lambda: self.maybe(lambda: self.ids(self.edge), self.kind),
            "invert_selection": lambda: self.maybe(lambda: self.ids(self.vertex), self.kind),
            "select_all": lambda: self.maybe(self.kind),
            "setFaceColor": lambda: [r.choice([self.face(), self.ids(self.face), None]),
                                     self.color()],
            "selectFacesByColor": lambda: [r.choice([self.color(), self.face()]),
                                           *self.maybe(self.number)],
        }
        args = table[name]() if name in table else []
        keywords = self.keyword_options(name)
        if name == "subdivide":
            keywords = self.scheme_keywords(args[0])
        if name == "menger" and len(args) > 1:  # collapse given positionally already
            keywords.pop("collapse", None)
        if name in ("faces", "edges", "verts", "corners"):
            args = self.maybe(self.flag)
        return args, keywords

    # -- the contract ---------------------------------------------------------------

    def reset_if_large(self) -> None:
        """A fresh shape as the current object when there is none or it grew past
        :data:`RESET_FACES` (and now and then anyway); at most
        :data:`MAX_OBJECTS` objects are kept, the oldest killed first."""
        scene = self.scene
        if not scene.objects or scene.mesh.counts()[2] > RESET_FACES or self.rng.random() < 0.02:
            with use_scene(scene), use_run(self.run):
                commands.load(self.rng.choice(SHAPES))
            scene.selection = self.selection()
        while len(scene.objects) > MAX_OBJECTS:
            scene.kill(next(iter(scene.objects)))

    def selection(self) -> Selection:
        m = self.scene.mesh
        picks = [int(i) for i in m.face_ids()[:3]] + [99999]
        return Selection(faces=tuple(self.rng.sample(picks, self.rng.randint(0, 3))))

    def step(self, index: int, report: Report) -> None:
        """One call and the checks of the contract; findings go to ``report``."""
        self.reset_if_large()
        text, thunk = self.call()
        report.calls += 1
        report.commands_called[text.split("(")[0]] += 1
        before = scene_state(self.scene)
        start = time.perf_counter()
        try:
            with use_scene(self.scene), use_run(self.run), warnings.catch_warnings(), \
                    contextlib.redirect_stdout(io.StringIO()):
                warnings.simplefilter("ignore", DLFLRepairWarning)  # a loader's note
                warnings.simplefilter("error", RuntimeWarning)
                thunk()
        except DLFLError as refused:
            report.refusals[_public_type(refused)] += 1
            if scene_state(self.scene) != before:
                report.failures.append((self.seed, index, text, f"refusal changed the scene: "
                                                                f"{refused}"))
        except Exception as exc:  # noqa: BLE001  (the fuzz records whatever escapes)
            frames = traceback.extract_tb(exc.__traceback__)
            where = next((f for f in reversed(frames) if "/livemod/" in f.filename), frames[-1])
            report.failures.append((self.seed, index, text, f"{type(exc).__name__}: {exc} "
                                    f"({where.filename}:{where.lineno})"))
            self.scene = _fresh(self)
            return
        finally:
            seconds = time.perf_counter() - start
            if seconds > SLOW:
                report.slow.append((seconds, text))
        self._check_valid(index, text, report)

    def _check_valid(self, index: int, text: str, report: Report) -> None:
        for oid, obj in self.scene.objects.items():
            try:
                validate(obj.mesh)
            except DLFLError as broken:
                report.failures.append((self.seed, index, text, f"object {oid}: {broken}"))
                self.scene = _fresh(self)
                return


def _public_type(error: DLFLError) -> str:
    """The name of the error's nearest type of :mod:`livemod.dlfl.errors` (a
    module's private subclass counts as the public type it refines)."""
    return next(kind.__name__ for kind in type(error).__mro__
                if kind.__module__ == "livemod.dlfl.errors")


def _fresh(fuzzer: Fuzzer) -> Scene:
    scene = Scene()
    scene.face_budget = SCENE_BUDGET
    return scene


def _short(value: Any) -> str:
    """How a call's argument is written in the report (big arrays by shape)."""
    if isinstance(value, np.ndarray):
        return f"array{value.shape}"
    return shown(value)


def run(seeds: range, steps: int, directory: str) -> Report:
    """``steps`` calls for each seed of ``seeds``, each seed on a fresh scene."""
    report = Report()
    for seed in seeds:
        fuzzer = Fuzzer(seed, directory)
        for index in range(steps):
            fuzzer.step(index, report)
    return report


def describe(report: Report, seconds: float) -> str:
    """The figures of a run, as the fuzz script prints them."""
    slowest = max((s for s, _ in report.slow), default=0.0)
    lines = [f"calls: {report.calls} in {seconds:.1f} s, commands: {len(report.commands_called)}",
             f"refusals: {sum(report.refusals.values())} ({dict(report.refusals)})",
             f"contract broken: {len(report.failures)}",
             f"calls over {SLOW:g} s: {len(report.slow)} (slowest {slowest:.1f} s)"]
    lines += [f"  seed {seed} step {step}: {text}\n    {what}"
              for seed, step, text, what in report.failures[:50]]
    lines += [f"  slow {s:.1f} s: {text}" for s, text in report.slow[:20]]
    return "\n".join(lines) + ("\n" if math.isfinite(seconds) else "")
