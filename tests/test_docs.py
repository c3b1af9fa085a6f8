"""The documentation stays true to the code: the generated API reference is up to
date and the README's example script runs."""

from __future__ import annotations

import re
import runpy
from pathlib import Path

from livemod.dlfl import Scene, genus, use_scene, validate

ROOT = Path(__file__).resolve().parents[1]


def test_api_reference_is_generated_from_the_current_code() -> None:
    generator = runpy.run_path(str(ROOT / "docs" / "gen_api.py"))
    expected = generator["generate"]()
    assert (ROOT / "docs" / "api.md").read_text(encoding="utf-8") == expected, (
        "docs/api.md is out of date: run python docs/gen_api.py")


def test_api_reference_lists_every_thesis_command() -> None:
    import livemod.dlfl as dlfl

    text = (ROOT / "docs" / "api.md").read_text(encoding="utf-8")
    missing = [name for name in dlfl.__all__ if f"### `{name}(" not in text]
    assert missing == []


def test_readme_example_runs() -> None:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", readme, flags=re.S)
    assert blocks, "README has a python example"
    with use_scene(Scene()) as scene:
        exec(compile(blocks[0], "README.md", "exec"), {"__name__": "__readme__"})
    validate(scene.mesh)
    assert scene.mesh.num_faces > 100
    assert genus(scene.mesh) == 0
