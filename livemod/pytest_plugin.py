"""Snapshot tests of models: a pytest plugin, loaded when livemod is installed.

A test asks for the ``livemod_snapshot`` fixture and hands it a script (run
headless, with parameter values as ``--set`` gives them) or a model (a mesh, a
scene, a run's result)::

    def test_tower(livemod_snapshot):
        livemod_snapshot.assert_script("tower.py", parameters={"storeys": 3})

The first run with ``pytest --livemod-update`` stores the model's snapshot beside
the test, in ``__snapshots__/<test module>/<test name>.json`` and ``.png``: its
counts, holes, components, genus per component, face sizes and bounding box, and a
golden picture as ``livemod render SCRIPT --size 240x180`` draws it. Later runs
compare: the numbers exactly (the bounding box to a millionth of its size), the
picture as ``livemod render --reference`` compares pictures (a pixel differs where a
channel differs by more than a tenth, and at most 1% of the pixels may differ). A
failure lists what changed and where the new picture and the difference picture
(the reference dimmed, the differing pixels red) were written. ``--livemod-update``
stores the snapshots that are missing or changed, and passes.
"""

from __future__ import annotations

import json
import os
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import pytest

from livemod.dlfl.analysis import bounds, summarize
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.mesh import Mesh

if TYPE_CHECKING:
    from livemod.dlfl.scene import Selection
    from livemod.runner.execute import RunOutcome
    from livemod.viewer.pictures import ModelParts

UPDATE_OPTION = "--livemod-update"
SNAPSHOT_FOLDER = "__snapshots__"
IMAGE_SIZE = (240, 180)  # (width, height) of a snapshot's picture
BOUNDS_TOLERANCE = 1e-6  # of the box's largest coordinate (at least 1)
FORMAT = 1  # the snapshot files' layout; stored as "livemod snapshot"


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("livemod", "livemod model snapshots")
    group.addoption(UPDATE_OPTION, action="store_true", default=False,
                    help="store the livemod_snapshot snapshots that are missing or "
                         "changed instead of failing")


def pytest_configure(config: pytest.Config) -> None:
    config.stash[_STORED] = _Stored()


def pytest_terminal_summary(terminalreporter: Any, config: pytest.Config) -> None:
    stored = config.stash.get(_STORED, None)
    if stored is not None and (stored.written or stored.updated):
        terminalreporter.write_line(f"livemod snapshots: {len(stored.written)} written, "
                                    f"{len(stored.updated)} updated")


@pytest.fixture
def livemod_snapshot(request: pytest.FixtureRequest,
                     tmp_path_factory: pytest.TempPathFactory) -> ModelSnapshot:
    """Compares models with their stored snapshots (see :class:`ModelSnapshot`)."""
    test_file = Path(request.path)
    return ModelSnapshot(
        base=test_file.parent, folder=test_file.parent / SNAPSHOT_FOLDER / test_file.stem,
        test_name=request.node.name,
        update=bool(request.config.getoption(UPDATE_OPTION)),
        results=tmp_path_factory.getbasetemp() / "livemod-snapshots",
        stored=request.config.stash[_STORED], root=request.config.rootpath)


@dataclass
class _Stored:
    """The snapshots an update run wrote (new) and updated (changed), by path."""

    written: list[Path] = field(default_factory=list)
    updated: list[Path] = field(default_factory=list)


_STORED = pytest.StashKey[_Stored]()


@dataclass
class ModelSnapshot:
    """The ``livemod_snapshot`` fixture of one test.

    Each call of :meth:`assert_match` or :meth:`assert_script` compares one model
    with its snapshot: the test's name, then ``-2``, ``-3`` ... for further calls,
    or ``-NAME`` for a call given ``name``. Relative script and mesh paths are taken
    from the test file's folder.
    """

    base: Path
    folder: Path
    test_name: str
    update: bool
    results: Path
    stored: _Stored
    root: Path
    _calls: int = 0

    def assert_script(self, script: str | os.PathLike[str], *,
                      parameters: dict[str, Any] | None = None, mesh: str | None = None,
                      seed: int | None = 0, select: Selection | None = None,
                      name: str | None = None, image: bool = True,
                      threshold: float | None = None) -> RunOutcome:
        """Run ``script`` headless (as ``livemod run SCRIPT --set NAME=VALUE ...``
        runs it, with ``parameters`` as the values, ``mesh`` as ``--mesh``, ``seed``
        and ``select`` as ``--seed`` and ``--select``) and :meth:`assert_match` the
        scene it leaves. Returns the run's outcome, for further checks.

        Fails the test when the script fails (naming file and line), or names a
        parameter it does not declare.
        """
        from livemod.runner.declarations import undeclared
        from livemod.runner.headless import run_outcome

        path = self._beside(script)
        outcome = run_outcome(path, mesh_path=None if mesh is None else str(self._beside(mesh)),
                              seed=seed, parameters=parameters, selection=select)
        if outcome.error is not None:
            trace = "\n".join(outcome.error.trace_lines())
            pytest.fail(f"{path} failed: {outcome.error}\n{trace}", pytrace=False)
        problem = undeclared(outcome.declarations, parameters or {}, ran=True)
        if problem is not None:
            pytest.fail(f"{path}: {problem}", pytrace=False)
        self.assert_match(outcome.scene, name=name, image=image, threshold=threshold)
        return outcome

    def assert_match(self, model: object, *, name: str | None = None, image: bool = True,
                     threshold: float | None = None) -> None:
        """Compare ``model`` (a Mesh, MeshArrays, Scene or RunResult; a scene's
        objects all count and are drawn) with its stored snapshot; with
        ``image`` also its picture, where at most ``threshold`` of the pixels may
        differ (default: ``livemod render --reference``'s 1%).

        Fails the test listing what changed (or saying that no snapshot is
        stored); under ``--livemod-update`` stores the snapshot instead.
        """
        from livemod.viewer.compare import THRESHOLD
        from livemod.viewer.pictures import model_parts

        self._calls += 1
        stem = _file_name(self.test_name + (f"-{name}" if name is not None
                                            else f"-{self._calls}" if self._calls > 1 else ""))
        check = _Check(self.folder / f"{stem}.json", self.folder / f"{stem}.png",
                       self.results / stem, THRESHOLD if threshold is None else threshold)
        parts = model_parts(model)
        record = model_record(parts)
        picture = _render(parts) if image else None
        if self.update:
            self._store(check, record, picture)
            return
        problems = check.problems(record, picture, self._shown)
        if problems:
            pytest.fail(self._failure(check, problems), pytrace=False)

    def _beside(self, path: str | os.PathLike[str]) -> Path:
        """``path``, a relative one taken from the test file's folder."""
        return self.base / path

    def _shown(self, path: Path) -> str:
        """``path`` relative to the rootdir where it lies inside, else as it is."""
        try:
            return str(path.relative_to(self.root))
        except ValueError:
            return str(path)

    def _failure(self, check: _Check, problems: list[str]) -> str:
        if not check.json.exists():
            return problems[0]
        lines = "\n".join(f"  {problem}" for problem in problems)
        return (f"the model differs from its snapshot {self._shown(check.json)}:\n{lines}\n"
                f"if the change is meant, store it: pytest {UPDATE_OPTION}")

    def _store(self, check: _Check, record: dict[str, Any],
               picture: np.ndarray | None) -> None:
        """Write the parts of the snapshot that are missing or changed."""
        existed = check.json.exists()
        changed = check.problems(record, picture, self._shown) if existed else ["new"]
        if not changed:
            return
        check.write(record, picture)
        (self.stored.updated if existed else self.stored.written).append(check.json)


@dataclass(frozen=True)
class _Check:
    """One snapshot's files, where a failed comparison writes its pictures
    (``results`` + ``.png`` and ``.diff.png``), and the pixel share allowed."""

    json: Path
    png: Path
    results: Path
    threshold: float

    def problems(self, record: dict[str, Any], picture: np.ndarray | None,
                 shown: Any) -> list[str]:
        """What differs from the stored snapshot, one line each ([] when nothing)."""
        if not self.json.exists():
            return [f"no snapshot stored at {shown(self.json)}: run pytest {UPDATE_OPTION} "
                    f"to store it"]
        try:
            stored = json.loads(self.json.read_text(encoding="utf-8"))
            stored_record = stored["model"]
        except (OSError, ValueError, KeyError, TypeError) as exc:
            return [f"the snapshot {shown(self.json)} cannot be read ({exc!r})"]
        problems = record_changes(stored_record, record)
        if picture is not None:
            problems += self._picture_problems(picture, stored.get("image"), shown)
        return problems

    def _picture_problems(self, picture: np.ndarray, stored_image: Any,
                          shown: Any) -> list[str]:
        from livemod.viewer.compare import difference_picture, image_difference, read_picture
        from livemod.viewer.imagefiles import save_png

        if not stored_image or not self.png.exists():
            return [f"picture: none stored at {shown(self.png)}"]
        reference = read_picture(self.png, "stored picture")
        new = self.results.with_name(f"{self.results.name}.png")
        try:
            difference = image_difference(picture, reference)
        except ValueError as exc:  # another size
            save_png(new, picture)
            return [f"picture: {exc}; the new one is {new}"]
        if difference.matches(self.threshold):
            return []
        diff = self.results.with_name(f"{self.results.name}.diff.png")
        save_png(new, picture)
        save_png(diff, difference_picture(reference, difference))
        return [f"picture: {difference.summary(shown(self.png), self.threshold)}; "
                f"the new picture is {new}, the differing pixels in red: {diff}"]

    def write(self, record: dict[str, Any], picture: np.ndarray | None) -> None:
        """Store ``record`` and ``picture`` (None: remove a stored picture), atomically."""
        from livemod.dlfl.io.atomic import atomic_write
        from livemod.viewer.imagefiles import save_png

        self.json.parent.mkdir(parents=True, exist_ok=True)
        image = None if picture is None else {"file": self.png.name,
                                              "size": [picture.shape[1], picture.shape[0]]}
        text = _snapshot_text({"livemod snapshot": FORMAT, "model": record, "image": image})
        with atomic_write(self.json) as handle:
            handle.write(text.encode("utf-8"))
        if picture is None:
            self.png.unlink(missing_ok=True)
        else:
            save_png(self.png, picture)


def _snapshot_text(snapshot: dict[str, Any]) -> str:
    """``snapshot`` as JSON with a line per number of the model (a change to the
    model is a change to its lines in a diff)."""
    def entry(key: str, value: Any, indent: str) -> str:
        if isinstance(value, dict) and key == "model":
            inner = ",\n".join(entry(k, v, indent + " ") for k, v in value.items())
            return f"{indent}{json.dumps(key)}: {{\n{inner}\n{indent}}}"
        return f"{indent}{json.dumps(key)}: {json.dumps(value)}"

    return "{\n" + ",\n".join(entry(k, v, " ") for k, v in snapshot.items()) + "\n}\n"


def model_record(parts: ModelParts) -> dict[str, Any]:
    """What a snapshot keeps of a model's numbers: counts, holes, point-spheres,
    components, genus (and per component), face sizes, bounding box. The objects
    of a scene count together."""
    joined = parts.joined()
    if joined is None:  # an empty scene
        joined = mesh_arrays(Mesh())
    summary = summarize(joined)
    return {
        "vertices": summary.vertices, "edges": summary.edges, "faces": summary.faces,
        "holes": summary.holes, "point_spheres": summary.point_spheres,
        "components": summary.components, "genus": summary.genus,
        "component_genera": summary.component_genera,
        "face_sizes": {str(size): count for size, count in sorted(summary.face_sizes.items())},
        "bounds": bounds(joined).tolist(),
    }


def record_changes(stored: dict[str, Any], now: dict[str, Any]) -> list[str]:
    """``"faces: 6 stored, 10 now"`` for each number of ``now`` that differs from
    ``stored`` (the bounding box to :data:`BOUNDS_TOLERANCE` of its size)."""
    changes = []
    for key, value in now.items():
        old = stored.get(key)
        if key == "bounds" and old is not None and _same_box(old, value):
            continue
        if key != "bounds" and old == value:
            continue
        changes.append(f"{key}: {_text(old)} stored, {_text(value)} now")
    return changes


def _same_box(old: Any, new: list[list[float]]) -> bool:
    try:
        old_box = np.asarray(old, dtype=np.float64)
    except (TypeError, ValueError):
        return False
    new_box = np.asarray(new)
    scale = max(1.0, float(np.abs(new_box).max(initial=0.0)))
    return old_box.shape == new_box.shape and bool(
        np.all(np.abs(old_box - new_box) <= BOUNDS_TOLERANCE * scale))


def _text(value: Any) -> str:
    """A stored or new value as the failure shows it (a box rounded to 6 digits)."""
    if isinstance(value, list) and value and isinstance(value[0], list):
        return "[" + ", ".join("(" + ", ".join(f"{x:.6g}" for x in row) + ")"
                               for row in value) + "]"
    return "none" if value is None else str(value)


def _render(parts: ModelParts) -> np.ndarray:
    """The snapshot picture of ``parts``, as ``livemod render --size 240x180`` draws it;
    fails the test where there is no offscreen GL (saying what to install)."""
    from livemod.viewer.headless import NoOffscreenGL
    from livemod.viewer.pictures import View, render_model

    try:
        return render_model(parts, View(size=IMAGE_SIZE))[0]
    except NoOffscreenGL as exc:
        pytest.fail(f"the snapshot's picture cannot be drawn: {exc} (or compare the numbers "
                    f"only: image=False)", pytrace=False)


def _file_name(text: str) -> str:
    """``text`` with what file names cannot hold replaced by ``_``."""
    return re.sub(r"[^\w\-.\[\]=,+]", "_", text)
