"""File formats: OBJ, TopMod's .dlfl, STL (binary and ASCII) and PLY, read and written.

:func:`load_mesh` and :func:`save_mesh` choose the format from the file
extension (or ``format=``). Every writer replaces its target atomically (see
:func:`atomic_write`), and no reader executes anything it reads. docs/formats.md
describes what each format accepts and writes.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping

from ..errors import DLFLError
from ..mesh import Mesh
from .atomic import atomic_write, write_atomically
from .dlflfile import read_dlfl, write_dlfl
from .obj import read_obj, write_obj
from .ply import read_ply, write_ply
from .stl import read_stl, write_stl

__all__ = [
    "atomic_write", "load_mesh", "open_mesh", "read_dlfl", "read_obj", "read_ply", "read_stl",
    "save_mesh",
    "write_dlfl",
    "write_atomically", "write_obj", "write_ply", "write_stl",
]

READERS: dict[str, Callable[[str], Mesh]] = {
    "obj": read_obj, "dlfl": read_dlfl, "stl": read_stl, "ply": read_ply,
}
WRITERS: dict[str, Callable[[Mesh, str], None]] = {
    "obj": write_obj, "dlfl": write_dlfl, "stl": write_stl, "ply": write_ply,
}


def _format_of(path: str, format: str | None, table: Mapping[str, object], verb: str) -> str:  # noqa: A002
    """The format key for ``path`` (its extension unless ``format`` is given)."""
    key = (format or os.path.splitext(path)[1]).lower().lstrip(".")
    if key not in table:
        valid = ", ".join(f".{k}" for k in table)
        what = f"format {format!r}" if format else f"extension {os.path.splitext(path)[1]!r}"
        raise DLFLError(f"cannot {verb} {path!r}: unknown {what}; use one of {valid}")
    return key


def load_mesh(path: str | os.PathLike[str], *, format: str | None = None) -> Mesh:  # noqa: A002
    """Read a mesh from an ``.obj``, ``.dlfl``, ``.stl`` or ``.ply`` file.

    Args:
        path: the file.
        format: ``"obj"``, ``"dlfl"``, ``"stl"`` or ``"ply"`` to override the
            extension.

    Raises:
        DLFLError: an unknown format, or a malformed file (``file:line: ...``).
        OSError: the file cannot be read.
    """
    name = os.fspath(path)
    return READERS[_format_of(name, format, READERS, "read")](name)


def save_mesh(mesh: Mesh, path: str | os.PathLike[str], *, format: str | None = None) -> None:  # noqa: A002
    """Write a mesh as ``.obj``, ``.dlfl``, ``.stl`` or ``.ply``, atomically.

    Args:
        mesh: the mesh.
        path: the target file; an existing file is replaced only on success.
        format: ``"obj"``, ``"dlfl"``, ``"stl"`` or ``"ply"`` to override the
            extension.

    Raises:
        DLFLError: an unknown format.
        OSError: the file cannot be written.
    """
    name = os.fspath(path)
    WRITERS[_format_of(name, format, WRITERS, "write")](mesh, name)


def open_mesh(name: str | os.PathLike[str], *, shape_name: str | None = None) -> Mesh:
    """Read the mesh file ``name``, or build the built-in shape of that name
    (``"soccerball"``, ``"cube.obj"``, ...) when no such file exists.

    Args:
        name: a file path or a shape name.
        shape_name: the name to look up among the shapes, when it differs from
            ``name`` (e.g. ``name`` was resolved against a script's folder).

    Raises:
        DLFLError: a malformed file, or neither a file nor a shape of that name
            (the message lists the shapes).
        OSError: the file exists but cannot be read.
    """
    path = os.fspath(name)
    if os.path.exists(path):
        return load_mesh(path)
    from ..shapes import load_shape

    return load_shape(shape_name if shape_name is not None else path)
