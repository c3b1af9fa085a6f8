"""The repository's own hygiene: tests read only what is in it or what they make.

A test that reads a file beside the checkout (``../shared/data/...``) passes where that
file happens to be and fails in every fresh clone. :func:`outside_paths` finds the ways
a module can name such a path, and every module under tests/ must have none:

- a path built from ``__file__`` (``Path(__file__).parents[2]``, ``.parent`` chains,
  ``os.path.dirname``, ``/ ".."``, names assigned from these) that climbs above the
  repository root, even if it comes back down;
- a path relative to the working directory (the repository root, where pytest runs) that
  starts by climbing out of it, given to a call or joined with ``/``:
  ``read_obj("../shared/data/cube.obj")``;
- an absolute path under a folder where data lives (``/work/``, ``/home/``, ``/root/``,
  ``/Users/``, ``/mnt/``, ``/media/``, ``/srv/``, ``/opt/``), ``~/`` or ``C:\\Users``,
  in code, docstrings or comments;
- the user's home folder (``Path.home()``, ``expanduser``).

Made-up absolute paths that nothing reads (``"/virtual/script.py"``,
``"/nonexistent-dir/x.obj"``) and temporary folders (``tmp_path``) are not flagged.

Every test module is named after the module of livemod it tests
(:func:`module_tested_by`), but for the few listed in ``ACROSS_MODULES``.
"""

from __future__ import annotations

import ast
import io
import re
import tokenize
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TESTS = ROOT / "tests"

ABSOLUTE = re.compile(
    r"(?<![\w.:/\\])(?:/(?:work|home|root|Users|mnt|media|srv|opt)(?![\w.-])|~/"
    r"|[A-Za-z]:[\\/]+Users\b)"
)
CLIMBS_OUT = re.compile(r"^\.\.(?:[/\\]|$)")
UP_ONLY = {"resolve", "absolute", "abspath", "realpath", "normpath", "Path", "PurePath",
           "PosixPath", "fspath", "str"}


class _Climbs(ast.NodeVisitor):
    """Track paths built from ``__file__``: how many folders above the module's file
    each leads (``__file__`` 0, its folder 1, ...), and the highest point on the way."""

    def __init__(self, depth: int) -> None:
        self.depth = depth  # the repository root is this many folders above the file
        self.names: dict[str, tuple[int, int]] = {}
        self.used: set[int] = set()  # ids of the string constants a __file__ path took
        self.found: list[tuple[int, str]] = []

    def climb(self, node: ast.AST) -> tuple[int, int] | None:
        """(where it ends, highest point) of a path from ``__file__``, else None."""
        if isinstance(node, ast.Name):
            return (0, 0) if node.id == "__file__" else self.names.get(node.id)
        if isinstance(node, ast.Attribute) and node.attr == "parent":
            return self._up(self.climb(node.value), 1)
        if (isinstance(node, ast.Subscript) and isinstance(node.value, ast.Attribute)
                and node.value.attr == "parents" and isinstance(node.slice, ast.Constant)
                and isinstance(node.slice.value, int)):
            return self._up(self.climb(node.value.value), node.slice.value + 1)
        if isinstance(node, ast.Call):
            return self._call(node)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div):
            return self._join(self.climb(node.left), [node.right])
        return None

    def _call(self, node: ast.Call) -> tuple[int, int] | None:
        name = _called(node)
        if name == "dirname" and node.args:
            return self._up(self.climb(node.args[0]), 1)
        if name == "join" and node.args:
            return self._join(self.climb(node.args[0]), node.args[1:])
        if name in UP_ONLY:
            if node.args:
                return self.climb(node.args[0])
            if isinstance(node.func, ast.Attribute):  # Path(__file__).resolve()
                return self.climb(node.func.value)
        return None

    @staticmethod
    def _up(at: tuple[int, int] | None, steps: int) -> tuple[int, int] | None:
        return None if at is None else (at[0] + steps, max(at[1], at[0] + steps))

    def _join(self, at: tuple[int, int] | None, parts: list[ast.expr]) -> tuple[int, int] | None:
        if at is None:
            return None
        level, highest = at
        for part in parts:
            if not (isinstance(part, ast.Constant) and isinstance(part.value, str)):
                return level, highest
            self.used.add(id(part))
            for segment in re.split(r"[/\\]", part.value):
                level += 1 if segment == ".." else -1 if segment not in ("", ".") else 0
                highest = max(highest, level)
        return level, highest

    def visit_Assign(self, node: ast.Assign) -> None:
        at = self.climb(node.value)
        for target in node.targets:
            if isinstance(target, ast.Name) and at is not None:
                self.names[target.id] = at
        self.generic_visit(node)

    def generic_visit(self, node: ast.AST) -> None:
        at = self.climb(node) if isinstance(node, ast.expr) else None
        if at is not None and at[1] > self.depth:
            self.found.append((node.lineno, "climbs above the repository root from __file__"))
            return
        if isinstance(node, ast.Call) and _called(node) in ("home", "expanduser"):
            self.found.append((node.lineno, "reads the user's home folder"))
        super().generic_visit(node)


def _called(node: ast.Call) -> str:
    """The name a call calls: ``dirname`` of ``os.path.dirname(x)``, ``Path`` of ``Path(x)``."""
    func = node.func
    return func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", "")


def _path_operands(tree: ast.AST) -> list[ast.expr]:
    """The expressions used as paths: the arguments of every call and both sides of
    every ``/`` (a string merely compared or written into a file is no path read)."""
    operands: list[ast.expr] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            operands += [*node.args, *(keyword.value for keyword in node.keywords)]
        elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Div):
            operands += [node.left, node.right]
    return operands


def outside_paths(source: str, depth: int) -> list[tuple[int, str]]:
    """``(line, what)`` for every path outside the repository ``source`` names.

    Args:
        source: the text of a Python module.
        depth: how many folders the module's file is below the repository root
            (``tests/test_x.py``: 2).
    """
    climbs = _Climbs(depth)
    tree = ast.parse(source)
    climbs.visit(tree)
    found = climbs.found
    for node in _path_operands(tree):
        if (isinstance(node, ast.Constant) and isinstance(node.value, str)
                and id(node) not in climbs.used and CLIMBS_OUT.match(node.value)):
            found.append((node.lineno, f"climbs out of the working folder: {node.value!r}"))
    for token in tokenize.generate_tokens(io.StringIO(source).readline):
        if token.type in (tokenize.STRING, tokenize.COMMENT) and ABSOLUTE.search(token.string):
            found.append((token.start[0], f"names an absolute path: {token.string.strip()[:60]}"))
    return sorted(set(found))


def test_no_test_module_names_a_path_outside_the_repository() -> None:
    offences = []
    for path in sorted(TESTS.rglob("*.py")):
        if path == Path(__file__).resolve():
            continue  # this module: its planted examples below name outside paths on purpose
        depth = len(path.relative_to(ROOT).parts)
        for line, what in outside_paths(path.read_text(encoding="utf-8"), depth):
            offences.append(f"{path.relative_to(ROOT)}:{line}: {what}")
    assert offences == []


PLANTED = [
    'SAMPLES = Path(__file__).resolve().parents[2] / "shared" / "data" / "topmod-objs"',
    "DATA = Path(__file__).parent.parent.parent / 'shared'",
    'ROOT = Path(__file__).resolve().parents[1]\nDATA = ROOT.parent / "shared"',
    'ROOT = Path(__file__).parents[1]\nDATA = ROOT / ".." / "shared"',
    'DATA = Path(__file__).parents[1] / "../shared/data"',
    'DATA = Path(__file__).parents[1] / "../livemod/docs"',  # out and back in: still out
    'DATA = os.path.join(os.path.dirname(__file__), "..", "..", "shared")',
    "DATA = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))",
    'read_obj("../shared/data/topmod-objs/cube.obj")',
    'read_obj("/work/shared/data/topmod-objs/cube.obj")',
    'mesh = load_mesh(Path("/home/someone/models/cube.obj"))',
    'mesh = load_mesh("C:\\\\Users\\\\someone\\\\cube.obj")',
    'mesh = load_mesh("D:/Users/someone/cube.obj")',
    '"""Regression tests (see /work/notes/io_review.md)."""',
    "x = 1  # the file from /root/samples/cube.obj",
    'path = Path.home() / "cube.obj"',
    'path = os.path.expanduser("~/cube.obj")',
]


@pytest.mark.parametrize("source", PLANTED)
def test_the_guard_flags_a_planted_path_outside(source: str) -> None:
    last_line = source.count("\n") + 1
    assert {line for line, _ in outside_paths(source, depth=2)} == {last_line}


INSIDE = [
    'DOC = Path(__file__).resolve().parents[1] / "docs" / "extrusions.md"',
    'root = Path(__file__).resolve().parent.parent\nscript = root / "scripts" / "tower.py"',
    'DOCS = Path(__file__).parent / ".." / "docs"',
    'HERE = os.path.dirname(os.path.abspath(__file__))\nDATA = os.path.join(HERE, "data")',
    'run("/virtual/script.py")',
    'save("/nonexistent-dir/x.obj")',
    'locked = Path("/sys")',
    'path = tmp_path / "a" / "b.obj"',
    'url = "https://example.com/home/index.html"',
    'text = "v 0 0 0\\nf 1 /2 1\\n"',
    'message = "step 3/5 ... done"',
    'script = "if n:\\n    load(\\"cube\\")\\n"',
    # a script in a temporary folder loads a file beside that folder: the test checks
    # the name it gives, and writes the script's text (no path the test reads)
    'assert names == ["main.py", "../shared/up.obj"]',
    'main.write_text("load(\'../shared/up.obj\')\\n")',
]


@pytest.mark.parametrize("source", INSIDE)
def test_the_guard_passes_paths_inside_or_made_up(source: str) -> None:
    assert outside_paths(source, depth=2) == []


def test_a_deeper_module_may_climb_further() -> None:
    source = 'ROOT = Path(__file__).resolve().parents[2]\nDOC = ROOT / "docs"'
    assert outside_paths(source, depth=3) == []
    assert [line for line, _ in outside_paths(source, depth=2)] == [1, 2]


# -- every test module is named after the module of livemod it tests

# test_<path>[_<aspect>]: <path> names a module or package under livemod/ or
# livemod/dlfl/ (its "/" written "_", a private module's leading "_" left out),
# and an aspect may follow a module's name (test_runner_session_abandon)
LIVEMOD_ROOTS = (ROOT / "livemod", ROOT / "livemod" / "dlfl")

# the test modules that test one feature across many modules, and so can be
# named after none: keep this list short, and rename a module that belongs to
# one source module instead of adding it here
ACROSS_MODULES = {
    "test_command_fuzz": "bad arguments to every thesis command",
    "test_commands_conformance": "every thesis command against Tett (2007) and API.md",
    "test_docs": "the docs against the code",
    "test_io_adversarial": "mutated files through every reader",
    "test_io_boundaries": "every reader across its internal block boundaries",
    "test_io_errors": "the readers' error types and the file and line they name",
    "test_io_fuzz": "random bytes through the OBJ and .dlfl readers",
    "test_layering": "the import boundaries between the packages",
    "test_notebook": "the example notebook, run as Jupyter runs it",
    "test_properties": "random operator sequences over the whole library",
    "test_repository": "the repository's own hygiene (this module)",
    "test_runner_races": "races between caller, supervisor, worker and watcher",
    "test_script_parameters": "param() from declaration through run, CLI and batch",
    "test_scripts": "every example script, run headless against its snapshot",
    "test_subdivision_geometry": "every scheme's positions against hand-derived formulas",
    "test_viewer_buffers": "the GL buffers the renderer, HUD text and measures keep",
    "test_viewer_golden": "preview and renderer together against golden pictures",
}


def _groupings(parts: list[str]) -> list[list[str]]:
    """Every way to join consecutive ``parts`` with "_" into path segments."""
    if len(parts) == 1:
        return [parts]
    rest = _groupings(parts[1:])
    return [[parts[0], *tail] for tail in rest] + [[f"{parts[0]}_{tail[0]}", *tail[1:]]
                                                   for tail in rest]


def _source_named(parts: list[str], *, packages: bool) -> Path | None:
    """The module (or, with ``packages``, package) of livemod that ``parts`` name."""
    for root, segments in ((r, s) for r in LIVEMOD_ROOTS for s in _groupings(parts)):
        folder = root.joinpath(*segments[:-1])
        for name in (segments[-1], f"_{segments[-1]}"):
            if (folder / f"{name}.py").is_file():
                return folder / f"{name}.py"
            if packages and (folder / name / "__init__.py").is_file():
                return folder / name
    return None


def module_tested_by(test_module: str) -> Path | None:
    """The module or package of livemod that ``test_module`` (``test_io_obj``) is
    named after, or None if its name names none."""
    parts = test_module.removeprefix("test_").split("_")
    whole = _source_named(parts, packages=True)
    aspects = (_source_named(parts[:k], packages=False) for k in range(len(parts) - 1, 0, -1))
    return whole or next((module for module in aspects if module is not None), None)


def test_every_test_module_is_named_after_a_module_of_livemod() -> None:
    names = {path.stem for path in TESTS.glob("test_*.py")}
    unnamed = {name for name in names if module_tested_by(name) is None}
    assert sorted(unnamed - ACROSS_MODULES.keys()) == []  # rename it, or list it above
    assert sorted(ACROSS_MODULES.keys() - unnamed) == []  # renamed or gone: drop it


@pytest.mark.parametrize(("test_module", "source"), [
    ("test_io_obj", "livemod/dlfl/io/obj.py"),
    ("test_io_dlflfile", "livemod/dlfl/io/dlflfile.py"),
    ("test_io", "livemod/dlfl/io"),
    ("test_runner_watch", "livemod/runner/watch.py"),
    ("test_runner_session_abandon", "livemod/runner/session.py"),
    ("test_viewer_hud", "livemod/viewer/hud.py"),
    ("test_viewer_section_cap", "livemod/viewer/section_cap.py"),
    ("test_graph", "livemod/dlfl/_graph.py"),
    ("test_commands_core", "livemod/dlfl/commands/core.py"),
    ("test_cli", "livemod/cli.py"),
])
def test_a_test_module_name_maps_to_its_module(test_module: str, source: str) -> None:
    assert module_tested_by(test_module) == ROOT / source


@pytest.mark.parametrize("test_module", [
    "test_core_gaps", "test_core_review", "test_io_gaps", "test_io_review",
    "test_runner_gaps", "test_sculpt_review", "test_session_22"])
def test_a_test_module_named_after_a_review_maps_to_none(test_module: str) -> None:
    assert module_tested_by(test_module) is None
