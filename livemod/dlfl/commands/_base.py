"""Shared machinery of the thesis commands: corner resolution and announcing steps."""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any, TypeVar, cast

from .._checks import id_list, is_id
from ..errors import InvalidArgumentError
from ..mesh import Mesh
from ..run_context import RUN, STANDALONE_RUN
from ..scene import Scene, current_scene

F = TypeVar("F", bound=Callable[..., Any])

CornerRef = tuple[int, int] | int

# the current run context, as current_run() reads it, in one C call
_get_run = RUN.get


def scene() -> Scene:
    """The current scene (see :func:`livemod.dlfl.scene.current_scene`)."""
    return current_scene()


def mesh() -> Mesh:
    """The current object's mesh."""
    return current_scene().mesh


def modeling_command(func: F) -> F:
    """Mark a thesis command that changes the mesh: it is one step when done.

    When the command returns it announces its step to the current run
    (:func:`livemod.dlfl.run_context.announce_step`, which it inlines); commands
    called from inside another command announce none of their own, nor does a
    command that raises. The wrapper returns what the command returns and lets
    its errors through.
    """

    label = func.__name__

    @functools.wraps(func)
    def wrapper(*args: Any, **kwargs: Any) -> Any:
        # announce_step inlined: the run's step hook finds the command's caller
        # fastest when it is called straight from here (STEP_HOOK_CALLER_DEPTH)
        run = _get_run(STANDALONE_RUN)
        run.command_depth += 1
        try:
            result = func(*args, **kwargs)
        finally:
            run.command_depth -= 1
        if not run.command_depth:
            hook = run.step_hook
            if hook is not None:
                hook(label)
        return result

    return cast(F, wrapper)


class Corner(tuple):
    """A ``(faceid, vertexid)`` corner that also carries its corner id.

    Commands return corners in this form. It compares, prints and unpacks as the
    thesis's plain tuple, but when passed back to a command it names exactly one
    corner even where a face visits the vertex twice (where the tuple alone is
    ambiguous), as long as that corner is still at that face and vertex.
    """

    cid: int

    def __new__(cls, face: int, vertex: int, cid: int) -> Corner:
        self = super().__new__(cls, (face, vertex))
        self.cid = cid
        return self

    def __getnewargs__(self) -> tuple[int, int, int]:  # keeps pickling (batch) working
        return self[0], self[1], self.cid


def resolve_corner(m: Mesh, corner: Any, what: str = "corner") -> int:
    """Turn a ``(faceid, vertexid)`` tuple, a :class:`Corner` or a corner id into a
    corner id.

    Raises:
        DLFLError: the face does not visit the vertex, visits it twice (the
            message lists the corner ids), or the id is not a live corner.
    """
    if isinstance(corner, Corner) and _still_there(m, corner):
        return corner.cid
    if isinstance(corner, tuple | list) and len(corner) == 2:
        face, vertex = corner
        return m.corner_at(face, vertex)
    if is_id(corner):
        m.corner_face(int(corner))  # raises DLFLError when not live
        return int(corner)
    raise InvalidArgumentError(
        f"{what} must be a (faceid, vertexid) tuple or a corner id, got {corner!r}"
    )


def id_arguments(ids: Any, name: str, selected: str | None = None) -> list[int]:
    """A command's id argument as a list of ints: one id (Python or numpy), an
    iterable of ids, or, when ``selected`` names a selection field (``"faces"``,
    ``"edges"``, ...), None for the scene's selection of that kind.

    Raises:
        DLFLError: anything else; the message names ``name``.
    """
    if ids is None and selected is not None:
        return list(getattr(scene().selection, selected))
    if is_id(ids):
        return [int(ids)]
    return id_list(ids, name)


def _still_there(m: Mesh, corner: Corner) -> bool:
    return (m.has_corner(corner.cid) and m.corner_face(corner.cid) == corner[0]
            and m.corner_vertex(corner.cid) == corner[1])


def corner_tuple(m: Mesh, corner: int) -> Corner:
    """The ``(faceid, vertexid)`` form of corner id ``corner``, carrying the id."""
    return Corner(m.corner_face(corner), m.corner_vertex(corner), corner)
