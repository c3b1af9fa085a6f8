"""File formats: OBJ, TopMod's .dlfl, STL (binary and ASCII), PLY and OFF, read and
written; glTF 2.0 (``.gltf``/``.glb``) and 3MF written.

:func:`load_mesh` and :func:`save_mesh` choose the format from the file
extension (or ``format=``). Every writer replaces its target atomically (see
:func:`atomic_write`), and no reader executes anything it reads. docs/formats.md
describes what each format accepts and writes.
"""

from __future__ import annotations

import errno
import os
from collections.abc import Callable, Mapping, Sequence

from ..errors import InvalidArgumentError, did_you_mean
from ..mesh import Mesh
from ..scene import Scene
from .atomic import atomic_write, write_atomically
from .dlflfile import read_dlfl, write_dlfl
from .gltf import write_glb, write_gltf
from .obj import read_obj, write_obj
from .off import read_off, write_off
from .ply import read_ply, write_ply
from .source import companion_path, show_path
from .stl import read_stl, write_stl
from .threemf import write_3mf

__all__ = [
    "atomic_write", "companion_paths", "keeps_objects", "load_mesh", "open_mesh", "read_dlfl", "read_obj",
    "read_off", "read_ply", "read_stl", "save_mesh", "save_objects", "scene_objects", "write_3mf",
    "write_atomically", "write_dlfl", "write_glb", "write_gltf", "write_obj", "write_off",
    "write_ply", "write_stl",
]

READERS: dict[str, Callable[[str], Mesh]] = {
    "obj": read_obj, "dlfl": read_dlfl, "stl": read_stl, "ply": read_ply, "off": read_off,
}
WRITERS: dict[str, Callable[[Mesh, str], None]] = {
    "obj": write_obj, "dlfl": write_dlfl, "stl": write_stl, "ply": write_ply, "off": write_off,
    "glb": write_glb, "gltf": write_gltf, "3mf": write_3mf,
}


def _format_of(path: str, format: str | None, table: Mapping[str, object], verb: str) -> str:  # noqa: A002
    """The format key for ``path`` (its extension unless ``format`` is given).

    Raises:
        InvalidArgumentError: no reader (writer) takes that format.
    """
    key = (format or os.path.splitext(path)[1]).lower().lstrip(".")
    if key not in table:
        valid = ", ".join(f".{k}" for k in table)
        what = f"format {format!r}" if format else f"extension {os.path.splitext(path)[1]!r}"
        raise InvalidArgumentError(f"cannot {verb} {show_path(path)}: unknown {what}; use one "
                                   f"of {valid}")
    return key


def load_mesh(path: str | os.PathLike[str], *, format: str | None = None) -> Mesh:  # noqa: A002
    """Read a mesh from an ``.obj``, ``.dlfl``, ``.stl``, ``.ply`` or ``.off`` file.

    Args:
        path: the file.
        format: ``"obj"``, ``"dlfl"``, ``"stl"``, ``"ply"`` or ``"off"`` to
            override the extension.

    Raises:
        InvalidArgumentError: an unknown format.
        FileFormatError: a malformed file (``file:line: ...``).
        NonManifoldError: its faces do not form an orientable 2-manifold.
        OSError: the file cannot be read (IsADirectoryError: it is a folder).
    """
    name = os.fspath(path)
    if os.path.isdir(name):  # before the extension: a folder has none to speak of
        raise IsADirectoryError(errno.EISDIR, "is a folder, not a mesh file", name)
    return READERS[_format_of(name, format, READERS, "read")](name)


def save_mesh(mesh: Mesh, path: str | os.PathLike[str], *, format: str | None = None) -> None:  # noqa: A002
    """Write a mesh as ``.obj``, ``.dlfl``, ``.stl``, ``.ply``, ``.off``, ``.glb``,
    ``.gltf`` (with a ``.bin`` beside it) or ``.3mf``, atomically.

    Args:
        mesh: the mesh.
        path: the target file; an existing file is replaced only on success.
        format: one of those extensions, without its dot, to override the
            extension.

    Raises:
        InvalidArgumentError: an unknown format.
        OSError: the file cannot be written.
    """
    name = os.fspath(path)
    WRITERS[_format_of(name, format, WRITERS, "write")](mesh, name)


# the suffix of the file a writer of the format may put beside its output, named
# after the output's stem: a coloured mesh's material library, a .gltf's buffer
COMPANIONS: dict[str, str] = {"obj": ".mtl", "dlfl": ".mtl", "gltf": ".bin"}


def companion_paths(path: str | os.PathLike[str], *, format: str | None = None) -> list[str]:  # noqa: A002
    """The files :func:`save_mesh` and :func:`save_objects` may write beside
    ``path`` in its format (``format`` overriding its extension): ``<stem>.mtl``
    of an OBJ or ``.dlfl`` (written only for a mesh with face colours) and
    ``<stem>.bin`` of a ``.gltf``; none for the other formats."""
    name = os.fspath(path)
    suffix = COMPANIONS.get((format or os.path.splitext(name)[1]).lower().lstrip("."))
    return [] if suffix is None else [companion_path(name, suffix)]


# the formats that keep a scene's objects apart: one node or object each
SCENE_WRITERS: dict[str, Callable[[Sequence[tuple[str, Mesh]], str], None]] = {
    "glb": write_glb, "gltf": write_gltf, "3mf": write_3mf,
}


def scene_objects(scene: Scene, all_objects: bool = True) -> list[tuple[str, Mesh]]:
    """``(name, mesh)`` of every object of ``scene`` in creation order (an unnamed
    one called ``object <id>``), or without ``all_objects`` of its current object
    alone; none for an empty scene (or a current id the script killed)."""
    if all_objects:
        chosen = list(scene.objects.items())
    elif scene.current in scene.objects:
        chosen = [(scene.current, scene.objects[scene.current])]
    else:
        chosen = []
    return [(obj.name or f"object {oid}", obj.mesh) for oid, obj in chosen]


def keeps_objects(path: str | os.PathLike[str], *, format: str | None = None) -> bool:  # noqa: A002
    """True when :func:`save_objects` keeps a scene's objects apart in ``path``'s
    format (``format`` overriding its extension): glTF and 3MF."""
    return (format or os.path.splitext(os.fspath(path))[1]).lower().lstrip(".") in SCENE_WRITERS


def save_objects(objects: Sequence[tuple[str, Mesh]] | Scene,
                 path: str | os.PathLike[str], *, format: str | None = None) -> None:  # noqa: A002
    """Write a scene's objects: glTF gives each a node and 3MF an object, under its
    name; the other formats hold one mesh, so several objects are joined into one
    (each a component, numbered anew) and one object is written as
    :func:`save_mesh` writes it.

    Args:
        objects: ``(name, mesh)`` pairs, at least one, or a scene (its objects,
            named as :func:`scene_objects` names them).
        path, format: as for :func:`save_mesh`.

    Raises:
        InvalidArgumentError: an unknown format, or no object.
        OSError: the file cannot be written.
    """
    name = os.fspath(path)
    key = _format_of(name, format, WRITERS, "write")
    if isinstance(objects, Scene):
        objects = scene_objects(objects)
    if not objects:
        raise InvalidArgumentError(f"cannot write {show_path(name)}: no object")
    if key in SCENE_WRITERS:
        SCENE_WRITERS[key](list(objects), name)
        return
    if len(objects) == 1:  # as it is: joining would renumber its ids
        WRITERS[key](objects[0][1], name)
        return
    from ..build import join_meshes

    WRITERS[key](join_meshes([mesh for _, mesh in objects]), name)


def open_mesh(name: str | os.PathLike[str], *, shape_name: str | None = None) -> Mesh:
    """Read the mesh file ``name``, or build the built-in shape of that name
    (``"soccerball"``, ``"cube.obj"``, ...) when no such file exists.

    Args:
        name: a file path or a shape name.
        shape_name: the name to look up among the shapes, when it differs from
            ``name`` (e.g. ``name`` was resolved against a script's folder).

    Raises:
        InvalidArgumentError: neither a file nor a shape of that name: the
            message names the folder looked in, and lists the shapes when the
            name has no extension (a name with one is meant as a file).
        FileFormatError, NonManifoldError: a malformed file.
        OSError: the file exists but cannot be read.
    """
    path = os.fspath(name)
    if os.path.exists(path):
        return load_mesh(path)
    from ..shapes import SHAPES, load_shape

    shape = os.fspath(shape_name) if shape_name is not None else path
    if shape.lower().removesuffix(".obj") in SHAPES:
        return load_shape(shape)
    where = f"no file {show_path(os.path.basename(path))} in {show_path(_folder_of(path))}"
    if os.path.splitext(shape)[1]:
        raise InvalidArgumentError(where)
    hint = did_you_mean(shape, SHAPES) or ";"
    raise InvalidArgumentError(f"{where}, and no built-in shape "
                               f"{show_path(os.path.basename(shape))}{hint} shapes: "
                               f"{', '.join(SHAPES)}")


def _folder_of(path: str) -> str:
    """The folder ``path`` is looked for in, as an absolute path."""
    return os.path.dirname(os.path.abspath(path))
