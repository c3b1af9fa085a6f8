"""Who reaches into whom: the mesh's private storage and private names across modules.

    python -m tests.layering        # print the counts and every offending line

Read from the source with :mod:`ast` (nothing is imported), so the counts are exact:

* **storage reads**: ``x._c``, ``x._e``, ``x._f`` or ``x._v`` (a :class:`Mesh`'s
  tables), or a private member of ``Mesh`` or its base (not a ``_hook_`` such as IPython's
  ``_repr_png_``) called on anything but ``self``, in a module that is not one of
  :data:`STORAGE_MODULES`;
* **private imports**: ``from m import _name`` for any module ``m``, and
  ``m._name`` read through a name an import bound to module ``m``
  (``import m``, ``from pkg import m as alias``);
* **cross-module private imports**: those of them whose ``m`` is a livemod module
  that is not a private module (``_x.py``) of the importer's own package. A private
  module exists to share helpers within its package; any other private name is its
  module's own business.
"""

from __future__ import annotations

import ast
import sys
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "livemod"
MESH_TABLES = frozenset({"_c", "_e", "_f", "_v"})

# the modules that are the storage's own (see livemod/dlfl/mesh.py's docstring),
# each with the reason it may read the tables
STORAGE_MODULES: dict[str, str] = {
    "livemod/dlfl/mesh.py": "the mesh: navigation and the operators' entry points",
    "livemod/dlfl/_storage.py": "the mesh's base: the tables, their counts, ids and rows",
    "livemod/dlfl/_operators.py": "the operators' slot-level bodies, called only by Mesh",
    "livemod/dlfl/validate.py": "checks every link of every table",
    "livemod/dlfl/arrays.py": "lays the tables out densely for bulk work",
}


@dataclass(frozen=True)
class Finding:
    """One offending line: ``path`` relative to the repository root."""

    path: str
    line: int
    text: str


def modules() -> list[Path]:
    """Every Python file of the package, sorted."""
    return sorted(PACKAGE.rglob("*.py"))


def _relative(path: Path) -> str:
    return path.relative_to(ROOT).as_posix()


# the classes a Mesh is made of: ``Mesh`` and its base, by module
MESH_CLASSES = {"dlfl/mesh.py": "Mesh", "dlfl/_storage.py": "MeshStorage"}


def mesh_private_members() -> frozenset[str]:
    """Names of the private methods and attributes of ``Mesh`` and its base
    (``_x``, not dunders)."""
    classes = [_class_named(PACKAGE / module, name) for module, name in MESH_CLASSES.items()]
    names = set(MESH_TABLES)
    for node in (inner for cls in classes for inner in ast.walk(cls)):
        if isinstance(node, ast.FunctionDef):
            names.add(node.name)
        elif (isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name)
              and node.value.id == "self"):
            names.add(node.attr)
    # not dunders, nor protocol hooks that end in one underscore too (IPython's
    # ``_repr_png_``): other objects define and get called by those names
    return frozenset(n for n in names
                     if n.startswith("_") and not n.startswith("__") and not n.endswith("_"))


def _class_named(path: Path, name: str) -> ast.ClassDef:
    """The top-level class ``name`` of module ``path``.

    Raises:
        LookupError: it has none (a renamed class must be renamed here too, or
            the guard would stop seeing its private members).
    """
    for node in ast.parse(path.read_text()).body:
        if isinstance(node, ast.ClassDef) and node.name == name:
            return node
    raise LookupError(f"no class {name} in {_relative(path)}")


def storage_reads() -> list[Finding]:
    """Reads of a mesh's tables or private members outside :data:`STORAGE_MODULES`."""
    private = mesh_private_members()
    found = []
    for path in modules():
        rel = _relative(path)
        if rel in STORAGE_MODULES:
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if (isinstance(node, ast.Attribute) and node.attr in private
                    and not (isinstance(node.value, ast.Name)
                             and node.value.id in ("self", "cls"))):
                found.append(Finding(rel, node.lineno, ast.unparse(node)))
    return found


def private_imports() -> list[tuple[Finding, bool]]:
    """Every ``from m import _name`` and ``m._name``, with True where it crosses
    modules (see above)."""
    found = []
    for path in modules():
        rel = _relative(path)
        tree = ast.parse(path.read_text())
        imported: dict[str, Path | None] = {}  # expression -> the module it names
        for node in ast.walk(tree):
            if isinstance(node, ast.ImportFrom):
                source = _source_module(path, node)
                for alias in node.names:
                    module = _submodule(source, alias.name)
                    if module is not None:
                        imported[alias.asname or alias.name] = module
                    elif alias.name.startswith("_") and not alias.name.startswith("__"):
                        text = f"from {'.' * node.level}{node.module or ''} import {alias.name}"
                        found.append((Finding(rel, node.lineno, text), _crosses(path, source)))
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    imported[alias.asname or alias.name] = _absolute_module(alias.name)
        found += [(Finding(rel, node.lineno, ast.unparse(node)), _crosses(path, module))
                  for node, module in _module_attributes(tree, imported)]
    return found


def _submodule(package: Path | None, name: str) -> Path | None:
    """The livemod module ``name`` of ``package`` (an ``__init__.py``), or None
    when ``name`` is not a module of it."""
    if package is None or package.name != "__init__.py":
        return None
    target = package.parent / name
    if target.is_dir():
        return target / "__init__.py"
    return target.with_suffix(".py") if target.with_suffix(".py").is_file() else None


def _absolute_module(name: str) -> Path | None:
    """The file of livemod module ``name`` (dotted), or None outside livemod."""
    if name.split(".")[0] != "livemod":
        return None
    target = ROOT.joinpath(*name.split("."))
    return target / "__init__.py" if target.is_dir() else target.with_suffix(".py")


def _module_attributes(tree: ast.AST, imported: dict[str, Path | None]
                       ) -> list[tuple[ast.Attribute, Path | None]]:
    """Every ``m._name`` (not a dunder) of ``tree`` whose ``m`` is a key of
    ``imported``, with the module it names (None outside livemod)."""
    return [(node, imported[ast.unparse(node.value)]) for node in ast.walk(tree)
            if isinstance(node, ast.Attribute) and node.attr.startswith("_")
            and not node.attr.startswith("__") and ast.unparse(node.value) in imported]


def _source_module(importer: Path, node: ast.ImportFrom) -> Path | None:
    """The livemod file (``x.py`` or ``x/__init__.py``) ``node`` imports from, or
    None for a module outside livemod."""
    if node.level:
        base = importer.parent
        for _ in range(node.level - 1):
            base = base.parent
        parts = (node.module or "").split(".") if node.module else []
    elif node.module and node.module.split(".")[0] == "livemod":
        base, parts = ROOT, node.module.split(".")
    else:
        return None
    target = base.joinpath(*parts)
    return target / "__init__.py" if target.is_dir() else target.with_suffix(".py")


def _crosses(importer: Path, source: Path | None) -> bool:
    if source is None:
        return False
    shares_helpers = source.name.startswith("_") and source.name != "__init__.py"
    return not (shares_helpers and source.parent == importer.parent)


def main() -> int:
    reads = storage_reads()
    imports = private_imports()
    crossing = [finding for finding, crosses in imports if crosses]
    print(f"storage reads outside {sorted(STORAGE_MODULES)}: {len(reads)} in "
          f"{len({f.path for f in reads})} modules")
    for f in reads:
        print(f"  {f.path}:{f.line}: {f.text}")
    print(f"private-name imports: {len(imports)}; across modules: {len(crossing)}")
    for f in crossing:
        print(f"  {f.path}:{f.line}: {f.text}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
