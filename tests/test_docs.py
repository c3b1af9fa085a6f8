"""The documentation stays true to the code: the generated API reference is up to
date, and the README's example script and every Python example of the docs run."""

from __future__ import annotations

import re
import runpy
import subprocess
from pathlib import Path

import pytest

from livemod.dlfl import Scene, genus, use_scene, validate
from livemod.dlfl.io import save_mesh
from livemod.dlfl.shapes import cube

ROOT = Path(__file__).resolve().parents[1]


def test_api_reference_is_generated_from_the_current_code() -> None:
    generator = runpy.run_path(str(ROOT / "docs" / "gen_api.py"))
    expected = generator["generate"]()
    assert (ROOT / "docs" / "api.md").read_text(encoding="utf-8") == expected, (
        "docs/api.md is out of date: run python docs/gen_api.py")


def test_api_reference_lists_every_thesis_command() -> None:
    import livemod.dlfl as dlfl

    text = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    missing = [name for name in dlfl.commands.__all__ if f"### `{name}(" not in text]
    assert missing == []


def test_every_command_module_is_star_exported_and_has_an_api_section() -> None:
    """The commands registry: each module of livemod/dlfl/commands (but _base) gives
    its names to ``from livemod.dlfl import *`` and has a section of api.md."""
    import importlib

    import livemod.dlfl as dlfl

    generator = runpy.run_path(str(ROOT / "docs" / "gen_api.py"))
    documented = set(generator["COMMAND_MODULES"].values())
    modules = sorted(p.stem for p in (ROOT / "livemod" / "dlfl" / "commands").glob("*.py")
                     if not p.stem.startswith("_"))
    names: list[str] = []
    for stem in modules:
        module = importlib.import_module(f"livemod.dlfl.commands.{stem}")
        assert module.__name__ in documented, stem
        names += module.__all__
        assert all(getattr(dlfl, name) is getattr(module, name) for name in module.__all__)
    assert sorted(names) == sorted(dlfl.commands.__all__)
    assert len(set(names)) == len(names)  # no command in two modules


def test_readme_example_runs() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", readme, flags=re.S)
    assert blocks, "README has a python example"
    with use_scene(Scene()) as scene:
        exec(compile(blocks[0], "README.md", "exec"), {"__name__": "__readme__"})
    validate(scene.mesh)
    assert scene.mesh.num_faces > 100
    assert genus(scene.mesh) == 0


def test_ci_runs_the_readme_test_command() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    test_commands = [block for block in re.findall(r"```sh\n(.*?)\n```", readme, flags=re.S)
                     if "pytest" in block]
    assert len(test_commands) == 1, "README has one test command"
    printed = subprocess.run(["bash", str(ROOT / ".ci" / "run"), "--print-test-command"],
                             capture_output=True, text=True, check=True).stdout
    assert printed == test_commands[0] + "\n"
    assert 'pip install -e ".[test]"' in printed and printed.endswith("python -m pytest -n 2\n")


def _python_blocks() -> list[tuple[str, int, str]]:
    """``(file, line, code)`` of every ```python block of the README and docs/."""
    found = []
    for path in (ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))):
        text = path.read_text(encoding="utf-8")
        for match in re.finditer(r"```python\n(.*?)```", text, flags=re.S):
            line = text.count("\n", 0, match.start(1)) + 1
            found.append((path.relative_to(ROOT).as_posix(), line, match.group(1)))
    return found


@pytest.mark.parametrize(("name", "line", "code"), _python_blocks(),
                         ids=[f"{name}:{line}" for name, line, _ in _python_blocks()])
def test_every_python_example_in_the_docs_runs(name: str, line: int, code: str,
                                               tmp_path: Path, monkeypatch) -> None:
    """Each example runs as written, in a folder that has a model.obj to load."""
    save_mesh(cube(), str(tmp_path / "model.obj"))
    monkeypatch.chdir(tmp_path)
    with use_scene(Scene()):
        # its own file name and first line, so a failure points at the doc
        exec(compile("\n" * (line - 1) + code, str(ROOT / name), "exec"),
             {"__name__": "__doc_example__"})


def test_the_docs_have_python_examples() -> None:
    assert {name for name, _, _ in _python_blocks()} >= {
        "README.md", "docs/guide.md", "docs/extrusions.md", "docs/parameters.md"}


def _dotted_references() -> list[tuple[str, str]]:
    """``(file, name)`` of every ```livemod.…``` name quoted in the docs, the README
    and the docstrings and comments of the package."""
    paths = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
             *sorted((ROOT / "livemod").rglob("*.py"))]
    return sorted({(path.relative_to(ROOT).as_posix(), name) for path in paths
                   for name in re.findall(r"`(livemod(?:\.\w+)+)`", path.read_text("utf-8"))})


def test_every_dotted_name_the_docs_quote_can_be_reached_by_attribute() -> None:
    """``livemod.dlfl.X.y`` must work as typed once the package is imported: a
    module shadowed by a same-named function (``rind``, ``wireframe``, ...) would
    make such a name an AttributeError, so the docs must say ``from ... import``."""
    import importlib
    import pkgutil

    import livemod

    for module in pkgutil.walk_packages(livemod.__path__, "livemod."):
        if not module.name.endswith("__main__"):  # it runs the command line
            importlib.import_module(module.name)
    unreachable = []
    for name, dotted in _dotted_references():
        target: object = livemod
        for part in dotted.split(".")[1:]:
            target = getattr(target, part, None)
        if target is None:
            unreachable.append(f"{name}: {dotted}")
    assert len(_dotted_references()) > 40
    assert not unreachable, "\n".join(unreachable)


def _library_columns() -> list[tuple[str, str, str]]:
    """``(file, module, function)`` for every function named in a docs table column
    headed "library (`livemod.dlfl.X`)", as ``name(`` in its cells."""
    found = []
    for path in sorted((ROOT / "docs").glob("*.md")):
        module, column = None, -1
        for line in path.read_text(encoding="utf-8").splitlines():
            cells = [cell.strip() for cell in line.strip().strip("|").split("|")]
            heads = [re.fullmatch(r"library \(`(livemod(?:\.\w+)+)`\)", c) for c in cells]
            if any(heads):
                column = next(i for i, h in enumerate(heads) if h)
                module = heads[column].group(1)  # type: ignore[union-attr]
            elif not line.startswith("|"):
                module = None  # the table ended
            elif module is not None and len(cells) > column:
                found += [(path.name, module, name)
                          for name in re.findall(r"`(\w+)\(", cells[column])]
    return found


def test_the_functions_a_library_column_names_are_in_that_module() -> None:
    import importlib

    rows = _library_columns()
    assert ("topmod.md", "livemod.dlfl.multihandle", "multi_face_handle") in rows
    missing = [(name, module, function) for name, module, function in rows
               if not hasattr(importlib.import_module(module), function)]
    assert missing == []
