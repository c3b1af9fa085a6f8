"""What a variant needs from the client's disk, packed to travel to a machine
that cannot see it (``livemod batch --cluster``), and unpacked there.

A :class:`Bundle` holds the script's bytes, the local modules it imports (files
in its folder that :func:`~.errors.is_user_file` calls the user's, as the live
runner watches them), the files it names by a relative path, and the ``--mesh``
file. What is found is found by reading the code, never by running it:

- modules: every ``import`` statement, at any depth (also one in an ``if``
  branch or a function), resolved against the script's folder as the run would
  (that folder is first on ``sys.path``); a package there travels whole, and
  each module that travels is read for its own imports;
- files: every string in that code that names a file relative to the script's
  folder, where ``load``, ``open(Path(__file__).with_name(...))`` and the like
  look. An f-string, ``+`` or ``format``/``%`` with values in it is a pattern
  (``f"parts/{kind}.obj"`` sends every ``parts/*.obj``), so long as its fixed
  text ends in a file suffix or holds a folder.

A module imported by a computed name (``importlib.import_module(name)``), a
file whose name is computed otherwise, an absolute path and a path relative to
the working folder do not travel (docs/batch.md says so).
"""

from __future__ import annotations

import ast
import glob
import hashlib
import importlib.machinery
import os
import re
from collections.abc import Iterator
from dataclasses import dataclass

from .errors import is_user_file

# a pattern must keep some fixed text to be a file name: a suffix, or a folder
_SUFFIX = re.compile(r"\.[A-Za-z0-9]{1,8}$")
_FOLDER = re.compile(r"[^/]/")
_LONGEST_NAME = 400


@dataclass(frozen=True)
class Bundle:
    """A script and what it reads from its folder, as bytes.

    Attributes:
        script: the script's name in ``files``.
        files: ``(path relative to the script's folder, bytes)``, sorted; the
            script first among equals. A path may climb (``../data/x.obj``).
        mesh: ``(file name, bytes)`` of the ``--mesh`` file, or None.
        digest: a hash of all of it (names a copy unpacked on a worker).
    """

    script: str
    files: tuple[tuple[str, bytes], ...]
    mesh: tuple[str, bytes] | None
    digest: str

    @property
    def size(self) -> int:
        """Bytes of all the files, the mesh included."""
        return sum(len(data) for _, data in self.files) + len(self.mesh[1] if self.mesh else b"")

    def summary(self) -> str:
        """``script.py, 2 modules, 3 files, --mesh base.obj (1.2 MB)``."""
        modules = sum(1 for name, _ in self.files if name.endswith(".py")) - 1
        others = len(self.files) - modules - 1
        parts = [self.script]
        if modules:
            parts.append(f"{modules} module{'s' * (modules != 1)}")
        if others:
            parts.append(f"{others} file{'s' * (others != 1)}")
        if self.mesh is not None:
            parts.append(f"--mesh {self.mesh[0]}")
        return f"{', '.join(parts)} ({self.size / 1e6:.1f} MB)"


def bundle_of(script: str, mesh_path: str | None = None) -> Bundle:
    """The :class:`Bundle` of ``script`` (and of the ``--mesh`` file ``mesh_path``).

    Raises:
        OSError: the script, a module or the mesh cannot be read.
        SyntaxError: never: a module that does not parse is sent as it is, unread
            (the run on the worker reports its error).
    """
    script = os.path.abspath(script)
    folder = os.path.dirname(script)
    names = sorted(_needed_files(script) - {script})
    files = [(os.path.basename(script), _read(script))]
    files += [(os.path.relpath(path, folder), _read(path)) for path in names]
    mesh = None if mesh_path is None else (os.path.basename(mesh_path), _read(mesh_path))
    return Bundle(files[0][0], tuple(files), mesh, _digest(files, mesh))


def _read(path: str) -> bytes:
    with open(path, "rb") as handle:
        return handle.read()


def _digest(files: list[tuple[str, bytes]], mesh: tuple[str, bytes] | None) -> str:
    digest = hashlib.blake2b(digest_size=16)
    for name, data in [*files, *([mesh] if mesh else [])]:
        digest.update(f"{name}\0{len(data)}\0".encode())
        digest.update(data)
    return digest.hexdigest()


def _needed_files(script: str) -> set[str]:
    """Absolute paths of the script, the local modules it imports (transitively)
    and the files its code and theirs name relative to the script's folder."""
    folder = os.path.dirname(script)
    modules, unread = {script}, [script]
    files: set[str] = set()
    while unread:
        tree = _parsed(unread.pop())
        if tree is None:
            continue
        for path in _local_modules(tree, script) - modules:
            modules.add(path)
            if path.endswith(".py"):
                unread.append(path)
        files |= _named_files(tree, folder)
    return modules | files


def _parsed(path: str) -> ast.Module | None:
    try:
        with open(path, "rb") as handle:
            return ast.parse(handle.read(), path)
    except (SyntaxError, ValueError, OSError):  # sent as it is; the run reports it
        return None


def _local_modules(tree: ast.Module, script: str) -> set[str]:
    """Files of the modules ``tree`` imports that are the user's, in the script's
    folder: a module's file, or every file of a package."""
    found: set[str] = set()
    for name in _imported_names(tree):
        spec = importlib.machinery.PathFinder.find_spec(name, [os.path.dirname(script)])
        if spec is None:
            continue
        if spec.submodule_search_locations:
            for location in spec.submodule_search_locations:
                found |= {path for path in _package_files(location)
                          if is_user_file(path, script)}
        elif spec.origin and is_user_file(os.path.abspath(spec.origin), script):
            found.add(os.path.abspath(spec.origin))
    return found


def _imported_names(tree: ast.Module) -> set[str]:
    """The first part of every module name ``tree`` imports absolutely."""
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {alias.name.partition(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.partition(".")[0])
    return names


def _package_files(folder: str) -> Iterator[str]:
    """Every file below a package's folder but compiled ones."""
    for root, folders, files in os.walk(folder):
        folders[:] = [f for f in folders if f != "__pycache__"]
        for name in files:
            if not name.endswith((".pyc", ".pyo")):
                yield os.path.abspath(os.path.join(root, name))


def _named_files(tree: ast.Module, folder: str) -> set[str]:
    """Files that strings (or string patterns) in ``tree`` name relative to ``folder``."""
    found: set[str] = set()
    for node in ast.walk(tree):
        parts = _parts(node)
        if parts is None or not _could_be_a_file_name(parts):
            continue
        pattern = "".join("*" if part is None else glob.escape(part) for part in parts)
        for match in glob.glob(pattern, root_dir=folder):
            path = os.path.normpath(os.path.join(folder, match))
            if os.path.isfile(path):
                found.add(path)
    return found


# a placeholder of str.format or of % formatting
_PLACEHOLDER = re.compile(r"\{[^{}]*\}|%[-#0 +]*\d*(?:\.\d+)?[sdifgrx]")


def _parts(node: ast.AST) -> list[str | None] | None:
    """The fixed texts (str) and computed parts (None) of the strings ``node`` can
    make, or None when it makes no string: ``"a.obj"``, ``f"p/{k}.obj"``,
    ``"p/" + k``, ``"p/{}.obj".format(k)``, ``"p/%s.obj" % k``."""
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return [node.value]
    if isinstance(node, ast.JoinedStr):
        return [part.value if isinstance(part, ast.Constant) and isinstance(part.value, str)
                else None for part in node.values]
    if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
        left, right = _parts(node.left), _parts(node.right)
        if left is None and right is None:
            return None
        return (left or [None]) + (right or [None])
    template = _template(node)
    if template is None:
        return None
    fixed = _PLACEHOLDER.split(template)
    return [piece for text in fixed[:-1] for piece in (text, None)] + [fixed[-1]]


def _template(node: ast.AST) -> str | None:
    """The template of ``"...".format(...)`` or ``"..." % ...``, else None."""
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
            and node.func.attr == "format" and isinstance(node.func.value, ast.Constant)
            and isinstance(node.func.value.value, str)):
        return node.func.value.value
    if (isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mod)
            and isinstance(node.left, ast.Constant) and isinstance(node.left.value, str)):
        return node.left.value
    return None


def _could_be_a_file_name(parts: list[str | None]) -> bool:
    """Relative, one line, not too long, and its fixed text ends in a suffix or
    holds a folder (a bare ``f"{x}"`` would match every file)."""
    fixed = "".join(part for part in parts if part is not None)
    if not fixed or len(fixed) > _LONGEST_NAME or "\n" in fixed or "\0" in fixed:
        return False
    if os.path.isabs(fixed) or fixed.startswith("~") or parts[0] is None and fixed[0] == "/":
        return False
    last = parts[-1]
    return ((last is not None and bool(_SUFFIX.search(last)))
            or any(part is not None and _FOLDER.search(part) for part in parts))


@dataclass(frozen=True)
class Unpacked:
    """Where a :class:`Bundle` was unpacked: the folder it went into (``root``),
    the script's path and the mesh's (None without one), with ``folder``, the
    script's folder."""

    root: str
    script: str
    mesh: str | None

    @property
    def folder(self) -> str:
        """The folder the script's relative names start from."""
        return os.path.dirname(self.script)


def unpack(bundle: Bundle, into: str) -> Unpacked:
    """Write ``bundle``'s files below the empty folder ``into``: the script's
    folder is ``into/script`` (deeper by one ``_`` folder for each ``..`` a file
    climbs, so that every file stays inside), the mesh in ``into/mesh``.

    Raises:
        OSError: the files cannot be written.
    """
    climb = max((_climbs(name) for name, _ in bundle.files), default=0)
    folder = os.path.join(into, "script", *["_"] * climb)
    for name, data in bundle.files:
        _write(os.path.normpath(os.path.join(folder, name)), data)
    mesh = None
    if bundle.mesh is not None:
        mesh = os.path.join(into, "mesh", bundle.mesh[0])
        _write(mesh, bundle.mesh[1])
    return Unpacked(into, os.path.join(folder, bundle.script), mesh)


def _climbs(name: str) -> int:
    """How many folders up the relative ``name`` reaches at most."""
    depth = lowest = 0
    for part in name.split(os.sep):
        depth += -1 if part == ".." else (part not in ("", "."))
        lowest = min(lowest, depth)
    return -lowest


def _write(path: str, data: bytes) -> None:
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "wb") as handle:
        handle.write(data)
