"""The scene: the thesis's object stack, the current object and the selection.

Thesis commands act on the *current scene*, held in a context variable so that
each run of the runner binds its own copy (two runs never share meshes) while a
plain ``python script.py`` uses one process-wide default scene. What a run
does with the scene (its steps, files, parameters and declarations) is the
run's: see :mod:`livemod.dlfl.run_context`.
"""

from __future__ import annotations

import contextlib
import contextvars
import operator
from collections.abc import Iterable, Iterator
from dataclasses import dataclass, field, replace
from typing import TypeVar

import numpy as np

from ._checks import is_id, shown
from .errors import UnknownIdError
from .mesh import Mesh

T = TypeVar("T")


@dataclass(frozen=True)
class Selection:
    """Ids picked in the viewer; what ``faces(True)`` and friends return.

    Corners are corner ids (see :meth:`Mesh.corner_at`).
    """

    faces: tuple[int, ...] = ()
    edges: tuple[int, ...] = ()
    vertices: tuple[int, ...] = ()
    corners: tuple[int, ...] = ()

    def is_empty(self) -> bool:
        """True when nothing of any kind is selected."""
        return not (self.faces or self.edges or self.vertices or self.corners)

    def adding(self, name: str, ids: Iterable[int]) -> Selection:
        """This selection with ``ids`` added to field ``name`` (``"faces"``,
        ``"edges"``, ``"vertices"`` or ``"corners"``), each id once (numpy
        integers become ints, so the selection prints as a script writes it)."""
        have: tuple[int, ...] = getattr(self, name)
        wanted = dict.fromkeys(operator.index(i) for i in ids)
        return replace(self, **{name: have + tuple(i for i in wanted if i not in have)})

    @classmethod
    def parse(cls, texts: Iterable[str]) -> Selection:
        """The selection that ``--select`` options name, e.g. ``["faces=12,31",
        "corners=88"]``: a kind (``faces``, ``edges``, ``verts`` or ``vertices``,
        ``corners``, or the singular of one, as in ``face=3``), ``=``, and ids
        separated by commas (corners by corner id).
        A kind given twice gets the ids of both, each once, in the order given.

        Raises:
            ValueError: an unknown kind, or an id that is not a whole number >= 0.
        """
        selection = cls()
        for text in texts:
            kind, _, ids = text.partition("=")
            name = _SELECTION_KINDS.get(kind.strip().lower())
            if name is None:
                raise ValueError(f"--select {text!r}: the kind must be one of "
                                 f"{', '.join(dict.fromkeys(_SELECTION_KINDS.values()))} "
                                 f"(or its singular, as in faces=12,31 or face=3)")
            selection = selection.adding(name, _selection_ids(text, ids))
        return selection

    def options(self) -> str:
        """The ``--select`` options that give this selection to ``livemod run``,
        ``render``, ``batch`` or ``view`` (empty for an empty selection)."""
        parts = [f"--select {kind}={','.join(map(str, getattr(self, name)))}"
                 for name, kind in SELECTION_READERS.items() if getattr(self, name)]
        return " ".join(parts)


# the kinds ``Selection.parse`` accepts -> Selection field; ``options`` writes the first
_SELECTION_KINDS = {"faces": "faces", "face": "faces", "edges": "edges", "edge": "edges",
                    "verts": "vertices", "vert": "vertices", "vertices": "vertices",
                    "vertex": "vertices", "corners": "corners", "corner": "corners"}
# each Selection field, in field order -> the command that returns it (``verts(True)``
# gives the vertices), which is also the kind ``Selection.options`` writes
SELECTION_READERS = {"faces": "faces", "edges": "edges", "vertices": "verts",
                     "corners": "corners"}


def _selection_ids(text: str, ids: str) -> list[int]:
    """The ids of one ``--select`` option, ``ids`` being what follows its ``=``."""
    found = []
    for part in ids.split(","):
        part = part.strip()
        if not part.isdigit() or not part.isascii():
            raise ValueError(f"--select {text!r}: {part!r} is not an id (a whole number "
                             f"0 or more); ids are separated by commas, as in faces=12,31")
        found.append(int(part))
    return found


@dataclass
class SceneObject:
    """One mesh of the scene with the transform record of the thesis commands.

    livemod applies ``translate``/``scale`` to the vertices at once; ``origin``
    and ``factor`` remember the object's placement so that absolute
    (``relative=False``) moves and scales can be computed.
    """

    mesh: Mesh
    name: str = ""
    origin: np.ndarray = field(default_factory=lambda: np.zeros(3))
    factor: np.ndarray = field(default_factory=lambda: np.ones(3))


class Scene:
    """Several meshes (objects by integer id), the current one and the selection.

    What a run of a script does with the scene (its steps, the files it reads,
    its parameters) is the run's, not the scene's: see
    :mod:`livemod.dlfl.run_context`.

    Attributes:
        objects: object id -> :class:`SceneObject`, in creation order.
        current: id of the current object, or None when the scene is empty.
        selection: the viewer's selection, applied to the current object.
        face_budget: the face budget of the commands acting on this scene (see
            :mod:`livemod.dlfl.budget`); None for the session's default.
    """

    def __init__(self) -> None:
        self.objects: dict[int, SceneObject] = {}
        self.current: int | None = None
        self.selection = Selection()
        self.face_budget: int | None = None
        self._next_object = 0

    def _repr_png_(self) -> bytes | None:
        """A picture of the scene's objects for Jupyter (see :mod:`livemod.dlfl.display`)."""
        from .display import picture_png

        return picture_png(self)

    # -- objects -------------------------------------------------------------

    def add(self, mesh: Mesh, name: str = "") -> int:
        """Push ``mesh`` as a new object, make it current and return its id."""
        oid = self._next_object
        self._next_object += 1
        self.objects[oid] = SceneObject(mesh, name)
        self.current = oid
        return oid

    @property
    def mesh(self) -> Mesh:
        """The current object's mesh; an empty object is created when there is none."""
        if self.current is None:
            self.add(Mesh())
        assert self.current is not None
        return self.objects[self.current].mesh

    @property
    def current_object(self) -> SceneObject:
        """The current :class:`SceneObject` (created empty when there is none)."""
        self.mesh  # noqa: B018  (creates the object on demand)
        assert self.current is not None
        return self.objects[self.current]

    def switch(self, oid: int) -> int:
        """Make object ``oid`` current and return it."""
        self._check_object(oid)
        self.current = int(oid)
        return self.current

    def kill(self, oid: int) -> None:
        """Remove object ``oid``; the most recent remaining object becomes current."""
        self._check_object(oid)
        del self.objects[oid]
        if self.current == oid:
            self.current = next(reversed(self.objects), None)

    def _check_object(self, oid: object) -> None:
        if not is_id(oid) or oid not in self.objects:
            have = ", ".join(str(k) for k in self.objects) or "none"
            raise UnknownIdError(f"object {shown(oid)} does not exist (objects: {have})")

    def copy(self) -> Scene:
        """A deep copy: meshes copied with their ids, selection and objects kept."""
        other = Scene()
        for oid, obj in self.objects.items():
            other.objects[oid] = SceneObject(
                obj.mesh.copy(), obj.name, obj.origin.copy(), obj.factor.copy()
            )
        other.current = self.current
        other.selection = replace(self.selection)
        other.face_budget = self.face_budget
        other._next_object = self._next_object
        return other


_default_scene = Scene()
_scene_var: contextvars.ContextVar[Scene] = contextvars.ContextVar("livemod_scene")


def current_scene() -> Scene:
    """The scene thesis commands act on: the one bound by :func:`use_scene`, or the
    process-wide default scene."""
    return _scene_var.get(_default_scene)


def default_scene() -> Scene:
    """The process-wide scene used when no run has bound one."""
    return _default_scene


@contextlib.contextmanager
def binding(var: contextvars.ContextVar[T], value: T) -> Iterator[T]:
    """Set ``var`` to ``value`` in the calling context (thread) while the block runs,
    then back to what it was; the block gets ``value``."""
    token = var.set(value)
    try:
        yield value
    finally:
        var.reset(token)


def use_scene(scene: Scene) -> contextlib.AbstractContextManager[Scene]:
    """Bind ``scene`` as the current scene for the calling context (thread)."""
    return binding(_scene_var, scene)


def reset_default_scene() -> Scene:
    """Replace the default scene with an empty one and return it."""
    global _default_scene
    _default_scene = Scene()
    return _default_scene
