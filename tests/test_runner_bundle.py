"""livemod.runner.bundle: what travels with a variant to a machine that cannot
see the client's disk, and a run from the unpacked copy."""

from __future__ import annotations

import os
from pathlib import Path

from livemod.dlfl.io import load_mesh, save_mesh
from livemod.dlfl.shapes import cube, tetrahedron
from livemod.runner.bundle import bundle_of, unpack
from livemod.runner.headless import run_outcome


def _tree(root: Path, files: dict[str, str | bytes]) -> None:
    for name, text in files.items():
        path = root / name
        path.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(text, bytes):
            path.write_bytes(text)
        else:
            path.write_text(text)


def _names(root: Path) -> list[str]:
    return [name for name, _ in bundle_of(str(root / "main.py")).files]


def test_local_modules_travel_at_any_depth_and_installed_ones_do_not(tmp_path):
    _tree(tmp_path, {
        "main.py": "import numpy\nimport helper\nif False:\n    from pkg.sub import f\n"
                   "def later():\n    import lazy\n",
        "helper.py": "from chained import x\n",
        "chained.py": "x = 1\n",
        "lazy.py": "",
        "pkg/__init__.py": "", "pkg/sub.py": "from . import deeper\n", "pkg/deeper.py": "",
        "pkg/__pycache__/sub.cpython-311.pyc": b"\0",
        "unused.py": "",  # nothing imports it
    })
    assert _names(tmp_path) == ["main.py", "chained.py", "helper.py", "lazy.py",
                                "pkg/__init__.py", "pkg/deeper.py", "pkg/sub.py"]


def test_files_named_by_strings_and_patterns_travel(tmp_path):
    home = tmp_path / "project"  # its parent holds the file named from one folder up
    _tree(home, {
        "main.py": "k = 'a'\n"
                   "load('base.obj')\n"
                   "load(f'parts/{k}.obj')\n"
                   "load('../common/up.obj')\n"
                   "open('tables/' + k)\n"
                   "load('lib/{}.stl'.format(k))\n"
                   "load('old/%s.ply' % k)\n"
                   "print(f'{k}')\n",  # a bare pattern names no file
        "base.obj": "", "parts/a.obj": "", "parts/b.obj": "", "parts/notes.txt": "",
        "tables/a": "", "lib/x.stl": "", "old/y.ply": "", "elsewhere.obj": "",
    })
    (tmp_path / "common").mkdir()
    (tmp_path / "common" / "up.obj").write_text("")
    assert _names(home) == ["main.py", "../common/up.obj", "base.obj", "lib/x.stl",
                            "old/y.ply", "parts/a.obj", "parts/b.obj", "tables/a"]


def test_a_module_that_does_not_parse_travels_unread(tmp_path):
    _tree(tmp_path, {"main.py": "import broken\n", "broken.py": "def (:\n 'x.obj'\n",
                     "x.obj": ""})
    assert _names(tmp_path) == ["main.py", "broken.py"]


def test_the_bundle_names_what_travels_and_changes_with_any_byte(tmp_path):
    _tree(tmp_path, {"main.py": "import helper\nload('a.obj')\n", "helper.py": "",
                     "a.obj": "x"})
    save_mesh(cube(), tmp_path / "start.obj")
    bundle = bundle_of(str(tmp_path / "main.py"), str(tmp_path / "start.obj"))
    assert bundle.summary().startswith("main.py, 1 module, 1 file, --mesh start.obj (")
    (tmp_path / "a.obj").write_text("y")
    assert bundle_of(str(tmp_path / "main.py"), str(tmp_path / "start.obj")).digest != bundle.digest


def test_a_run_from_the_unpacked_copy_equals_the_run_at_home(tmp_path):
    home, away = tmp_path / "home" / "project", tmp_path / "away"
    _tree(home, {"main.py": "from helper import amount\nload('../parts/t.obj')\n"
                            "translate(amount, 0, 0)\nsubdivide('loop')\n",
                 "helper.py": "amount = 0.5\n"})
    (home.parent / "parts").mkdir()
    save_mesh(tetrahedron(), home.parent / "parts" / "t.obj")
    save_mesh(cube(), tmp_path / "start.obj")
    away.mkdir()
    copy = unpack(bundle_of(str(home / "main.py"), str(tmp_path / "start.obj")), str(away))
    assert not copy.script.startswith(str(home)) and copy.mesh is not None
    assert os.path.basename(copy.mesh) == "start.obj"
    here = run_outcome(str(home / "main.py"), mesh_path=str(tmp_path / "start.obj"))
    there = run_outcome(copy.script, mesh_path=copy.mesh)
    assert here.error is None and there.error is None
    for outcome, name in ((here, "here.obj"), (there, "there.obj")):
        save_mesh(outcome.scene.objects[outcome.scene.current].mesh, tmp_path / name)
    assert (tmp_path / "here.obj").read_bytes() == (tmp_path / "there.obj").read_bytes()
    assert load_mesh(tmp_path / "there.obj").counts() == (10, 24, 16)
    assert len(outcome.scene.objects) == 2  # the --mesh and the part
