"""Guards of the package's boundaries, counted by tests/layering.py from the source."""

from __future__ import annotations

import pytest

from tests import layering


def test_only_the_storage_modules_read_the_mesh_tables():
    reads = list(layering.storage_reads())
    assert reads == [], "read the mesh through its public accessors (see mesh.py)"


def count_in(tmp_path, monkeypatch, files: dict[str, str]) -> None:
    """Point the counter at a package of ``files`` (path under livemod/ -> text)."""
    package = tmp_path / "livemod"
    for name, text in files.items():
        (package / name).parent.mkdir(parents=True, exist_ok=True)
        (package / name).write_text(text)
    monkeypatch.setattr(layering, "ROOT", tmp_path)
    monkeypatch.setattr(layering, "PACKAGE", package)


def test_the_counter_sees_table_reads_and_private_mesh_methods(tmp_path, monkeypatch):
    count_in(tmp_path, monkeypatch, {
        "dlfl/mesh.py": (layering.PACKAGE / "dlfl" / "mesh.py").read_text(),
        "dlfl/_storage.py": "class MeshStorage:\n"
                            "    def _row(self):\n"
                            "        return self._spare\n",
        "dlfl/op.py": "def op(mesh, table):\n"
                      "    a = mesh._v.n + len(mesh._ring_slots(0)) + mesh._row()\n"
                      "    b = mesh._spare + table._sorted_cache + mesh.num_faces\n"
                      "    return a + b + picture._repr_png_\n",
    })
    found = [(f.path, f.line, f.text) for f in layering.storage_reads()]
    assert sorted(found) == [("livemod/dlfl/op.py", 2, "mesh._ring_slots"),
                             ("livemod/dlfl/op.py", 2, "mesh._row"),
                             ("livemod/dlfl/op.py", 2, "mesh._v"),
                             ("livemod/dlfl/op.py", 3, "mesh._spare")]


def test_the_counter_refuses_to_lose_a_class_of_the_mesh(tmp_path, monkeypatch):
    count_in(tmp_path, monkeypatch, {
        "dlfl/mesh.py": (layering.PACKAGE / "dlfl" / "mesh.py").read_text(),
        "dlfl/_storage.py": "class RenamedStorage:\n    pass\n",
    })
    with pytest.raises(LookupError, match="no class MeshStorage in livemod/dlfl/_storage.py"):
        layering.storage_reads()


def test_no_module_imports_a_private_name_of_another():
    crossing = [f for f, crosses in layering.private_imports() if crosses]
    assert crossing == [], "give a shared helper a public name in a module below both"


def test_private_modules_share_their_names_only_within_their_package(tmp_path, monkeypatch):
    count_in(tmp_path, monkeypatch, {
        "a/_shared.py": "def _helper(): pass\n",
        "a/public.py": "def _own(): pass\n",
        "a/user.py": "import sys\nfrom ._shared import _helper\nfrom sys import _getframe\n",
        "b/other.py": "from ..a._shared import _helper\nfrom livemod.a.public import _own\n"
                      "import os\nimport livemod.a.public\nfrom ..a import public as pub\n"
                      "pub._own(os._exit, livemod.a.public._own, pub.own, os.__name__)\n",
    })
    found = sorted((f.path, f.text, crosses) for f, crosses in layering.private_imports())
    assert found == [
        ("livemod/a/user.py", "from ._shared import _helper", False),
        ("livemod/a/user.py", "from sys import _getframe", False),
        ("livemod/b/other.py", "from ..a._shared import _helper", True),
        ("livemod/b/other.py", "from livemod.a.public import _own", True),
        ("livemod/b/other.py", "livemod.a.public._own", True),
        ("livemod/b/other.py", "os._exit", False),
        ("livemod/b/other.py", "pub._own", True),
    ]
