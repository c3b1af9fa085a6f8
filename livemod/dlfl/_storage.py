"""The storage of a mesh: its four element tables and each element's own row.

:class:`MeshStorage` is the base of :class:`~livemod.dlfl.mesh.Mesh`, and the one
place that defines the tables' layout: a
:class:`~livemod.dlfl._table.Table` per kind (``_c`` corners, ``_e`` edges,
``_f`` faces, ``_v`` vertices) with the fields of :data:`CORNER_SPEC`,
:data:`EDGE_SPEC`, :data:`FACE_SPEC` (and :data:`COLOR_SPEC` once a face has a
colour) and :data:`VERTEX_SPEC`. It holds what reads
or writes one kind's rows alone: creating and adopting tables
(:meth:`MeshStorage.from_tables`, :meth:`~MeshStorage.copy`), counts, live ids,
and the attributes of an element that are not links (a vertex's position, a
face's hole flag and colour). The links between the tables (a corner's
``next``, ``face``, ``edge``; an edge's sides) are the business of ``Mesh``: its
navigation follows them and its operators (with their bodies in
:mod:`~livemod.dlfl._operators`) are the only code that changes them.

The split is the one of OpenMesh's ``ArrayKernel`` (storage and element
properties) under its ``PolyConnectivity`` (navigation and Euler operators):
everything here is correct for any contents of the link fields, so a change to
how elements are stored or what they carry stays in this module, and a change
to the topology stays in ``mesh.py`` and ``_operators.py``. ``MeshStorage`` is
not used on its own; this module is one of the storage's own (see
``tests/layering.py``).
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, Self

import numpy as np

from ._checks import as_point, flag, rgb
from ._table import FieldSpec, Table
from .errors import InvalidArgumentError

CORNER_SPEC: FieldSpec = {
    "next": (np.int32, ()),
    "prev": (np.int32, ()),
    "face": (np.int32, ()),
    "vertex": (np.int32, ()),
    "edge": (np.int32, ()),
}
EDGE_SPEC: FieldSpec = {"c0": (np.int32, ()), "c1": (np.int32, ())}
FACE_SPEC: FieldSpec = {"corner": (np.int32, ()), "hole": (np.uint8, ())}
VERTEX_SPEC: FieldSpec = {"corner": (np.int32, ()), "position": (np.float64, (3,))}
# a face's colour is ``color`` when ``colored`` is 1; 0 means the default modelling
# colour. The face table has these fields only once a face of the mesh has had a
# colour (``MeshStorage._colors_used``): a mesh without colours neither stores
# nor zeroes nor copies them (13 bytes a face).
COLOR_SPEC: FieldSpec = {"colored": (np.uint8, ()), "color": (np.float32, (3,))}


def _adopt(kind: str, spec: FieldSpec, first_id: int, fields: dict[str, np.ndarray],
           ids: np.ndarray | None, optional: FieldSpec | None = None) -> Table:
    """:meth:`Table.from_arrays` of ``fields`` (and ``ids``), once they are checked
    to be the fields of ``spec``, with all of ``optional`` or none of them, all of
    one length (see :meth:`MeshStorage.from_tables`)."""
    needed = spec
    if optional and optional.keys() & fields.keys():
        spec = spec | optional
    if fields.keys() != spec.keys():
        extra = f" and all or none of {sorted(optional)}" if optional else ""
        raise InvalidArgumentError(
            f"the {kind} table needs the fields {sorted(needed)}{extra}, got {sorted(fields)}")
    lengths = {name: len(array) for name, array in fields.items()}
    if len(set(lengths.values())) > 1:
        raise InvalidArgumentError(f"the {kind} table's fields differ in length: {lengths}")
    return Table.from_arrays(kind, spec, first_id, fields, ids)


class MeshStorage:
    """The element tables of a :class:`~livemod.dlfl.mesh.Mesh`, their counts, ids
    and per-element attributes (positions, hole flags, colours).

    Attributes:
        notes: messages about repairs made while building the mesh.
    """

    # True when the face table has the fields of COLOR_SPEC, added by the mesh's
    # first colour (or given to from_tables); while False, no face has a colour
    # and the operators skip the colour inheritance of the faces they make (the
    # usual mesh: the insert/delete pair pays nothing for colours). Cleared only
    # by a rebuild without colours.
    _colors_used = False

    def __init__(self) -> None:
        self._c = Table("corner", CORNER_SPEC)
        self._e = Table("edge", EDGE_SPEC)
        self._f = Table("face", FACE_SPEC)
        self._v = Table("vertex", VERTEX_SPEC)
        self.notes: list[str] = []
        self._colors_used = False

    # ------------------------------------------------------------------ counts

    @property
    def num_vertices(self) -> int:
        """Number of live vertices."""
        return self._v.count

    @property
    def num_edges(self) -> int:
        """Number of live edges."""
        return self._e.count

    @property
    def num_faces(self) -> int:
        """Number of live faces, holes included."""
        return self._f.count

    @property
    def num_corners(self) -> int:
        """Number of live corners."""
        return self._c.count

    def counts(self) -> tuple[int, int, int]:
        """``(V, E, F)``, holes counted as faces (the mesh is closed inside)."""
        v, e, f = self._v, self._e, self._f
        # Table.count inlined, a table without free slots the usual case: the
        # runner reads the counts after every command, and a high-water mark is
        # an int that exists already (a subtraction makes a new one each step)
        return (v.n - len(v.free) if v.free else v.n, e.n - len(e.free) if e.free else e.n,
                f.n - len(f.free) if f.free else f.n)

    # ------------------------------------------------------------- id listings

    def vertex_ids(self) -> np.ndarray:
        """``(V,)`` int64 ids of the live vertices, in creation order."""
        return self._v.live_ids()

    def edge_ids(self) -> np.ndarray:
        """``(E,)`` int64 ids of the live edges, in creation order."""
        return self._e.live_ids()

    def face_ids(self) -> np.ndarray:
        """``(F,)`` int64 ids of the live faces (holes included), in creation order."""
        return self._f.live_ids()

    def corner_ids(self) -> np.ndarray:
        """``(C,)`` int64 ids of the live corners, in creation order."""
        return self._c.live_ids()

    def has_vertex(self, vertex: int) -> bool:
        """True when ``vertex`` is a live vertex id."""
        return self._v.is_live(vertex)

    def has_edge(self, edge: int) -> bool:
        """True when ``edge`` is a live edge id."""
        return self._e.is_live(edge)

    def has_face(self, face: int) -> bool:
        """True when ``face`` is a live face id."""
        return self._f.is_live(face)

    def has_corner(self, corner: int) -> bool:
        """True when ``corner`` is a live corner id."""
        return self._c.is_live(corner)

    def next_ids(self) -> tuple[int, int, int, int]:
        """The ids the next vertex, edge, face and corner will get."""
        return self._v.next_id, self._e.next_id, self._f.next_id, self._c.next_id

    # --------------------------------------------------------------- positions

    def position(self, vertex: int) -> np.ndarray:
        """``(3,)`` float64 copy of the position of ``vertex``."""
        return self._v.arrays["position"][self._v.slot(vertex)].copy()

    def positions(self, vertices: Iterable[int] | np.ndarray) -> np.ndarray:
        """``(k, 3)`` float64 copy of the positions of ``vertices``, in their order.

        Args:
            vertices: ``(k,)`` vertex ids (a list, or an int array: one vectorized
                lookup however many there are).

        Raises:
            InvalidArgumentError: an entry is not an integer.
            UnknownIdError: an entry is not a live vertex id (the first such, in
                order).
        """
        return self._v.arrays["position"][self._v.slots(vertices)]

    def positions_view(self) -> np.ndarray:
        """``(V, 3)`` float64 copy of the live vertex positions, in id order."""
        return self._v.arrays["position"][self._v.live_slots()]

    def set_position(self, vertex: int, position: Any) -> None:
        """Move ``vertex`` to ``position`` (three numbers)."""
        xyz = as_point(position)
        self._v.arrays["position"][self._v.slot(vertex)] = xyz

    def set_positions(self, vertices: Iterable[int] | np.ndarray, positions: Any) -> None:
        """Set the positions of many vertices at once.

        Args:
            vertices: ``(k,)`` vertex ids.
            positions: ``(k, 3)`` floats, or ``(3,)`` for all of them.

        Raises:
            UnknownIdError: an id that is not a live vertex.
            InvalidArgumentError: positions of another shape, or a NaN or
                infinite coordinate (nothing is moved then).
        """
        if not hasattr(vertices, "__iter__"):
            raise InvalidArgumentError(
                f"set_positions needs a sequence of vertex ids, got {vertices!r}")
        slots = [self._v.slot(v) for v in vertices]
        try:
            values = np.asarray(positions, dtype=np.float64)
        except (TypeError, ValueError):
            raise InvalidArgumentError(f"positions must be numbers, got {positions!r}") from None
        if values.shape not in ((3,), (len(slots), 3)):
            raise InvalidArgumentError(
                f"positions must have shape (3,) or ({len(slots)}, 3), got {values.shape}"
            )
        if not np.isfinite(values).all():
            raise InvalidArgumentError("positions must be finite numbers (NaN or infinity given)")
        self._v.arrays["position"][slots] = values

    # ------------------------------------------------------- holes and colours

    def is_hole(self, face: int) -> bool:
        """True when ``face`` is a hole: a boundary loop of an open input mesh."""
        return bool(self._f.hole[self._f.slot(face)])

    def set_hole(self, face: int, hole: bool = True) -> None:
        """Flag ``face`` as a hole (not drawn, written out as a boundary) or not.

        Raises:
            UnknownIdError: ``face`` is not live.
            InvalidArgumentError: ``hole`` is not a flag (a string such as
                ``"False"`` would otherwise mean True).
        """
        slot = self._f.slot(face)
        self._f.hole[slot] = 1 if flag(hole, "hole") else 0

    def hole_mask(self) -> np.ndarray:
        """``(F,)`` bool, True for the hole faces, in the order of :meth:`face_ids`."""
        F = self._f
        return F.arrays["hole"][F.live_slots()].astype(bool)

    def face_color(self, face: int) -> tuple[float, float, float] | None:
        """The colour ``(r, g, b)`` of ``face`` (floats in ``[0, 1]``, each the
        shortest decimal of the float32 kept), or None when it has none (it is
        drawn and written in the default modelling colour).

        Raises:
            UnknownIdError: ``face`` is not live.
        """
        F = self._f
        slot = F.slot(face)
        if not (self._colors_used and F.colored[slot]):
            return None
        # the shortest decimal of each float32: (0.2, ...) set reads back as 0.2
        red, green, blue = (float(str(v)) for v in F.arrays["color"][slot])
        return red, green, blue

    def set_face_color(self, face: int, color: Any) -> None:
        """Give ``face`` the colour ``(r, g, b)`` (three numbers in ``[0, 1]``, kept as
        float32), or take its colour away with None.

        Faces an operation makes from ``face`` take its colour (a split's new face,
        subdivision's children, an extrusion's sides and end).

        Raises:
            UnknownIdError: ``face`` is not live.
            InvalidArgumentError: ``color`` is neither None nor three numbers in
                ``[0, 1]``; the mesh is unchanged.
        """
        F = self._f
        slot = F.slot(face)
        if color is None:
            if self._colors_used:
                F.colored[slot] = 0
            return
        value = rgb(color)  # checked before the fields are added: a refusal changes nothing
        if not self._colors_used:
            F.add_fields(COLOR_SPEC)
            self._colors_used = True
        F.arrays["color"][slot] = value
        F.colored[slot] = 1

    def face_colors(self) -> np.ndarray | None:
        """``(F, 3)`` float32 colours of the faces in the order of :meth:`face_ids`,
        a row of NaN for a face without one; None when no face has a colour."""
        F = self._f
        if not (self._colors_used and F.arrays["colored"][: F.n].any()):
            return None  # the common case, without the slots
        slots = F.live_slots()
        colored = F.arrays["colored"][slots].astype(bool)
        if not colored.any():
            return None
        colors = F.arrays["color"][slots]
        colors[~colored] = np.nan
        return colors

    # -------------------------------------------------------------- whole mesh

    @classmethod
    def from_tables(
        cls,
        corners: dict[str, np.ndarray],
        edges: dict[str, np.ndarray],
        faces: dict[str, np.ndarray],
        vertices: dict[str, np.ndarray],
        first_ids: tuple[int, int, int, int] = (0, 0, 0, 0),
        ids: tuple[np.ndarray | None, np.ndarray | None, np.ndarray | None,
                   np.ndarray | None] | None = None,
    ) -> Self:
        """A mesh adopting ready-made element tables: the bulk builders' constructor.

        Each argument maps every field of its kind's spec (:data:`CORNER_SPEC`,
        :data:`EDGE_SPEC`, :data:`FACE_SPEC`, :data:`VERTEX_SPEC`) to an array with
        one row per element, faces with both or neither of the fields of
        :data:`COLOR_SPEC` (``colored``, ``color``; neither: no face has a
        colour); every reference (a corner's ``next``, ``face``, ...,
        an edge's ``c0``/``c1``, a face's or a vertex's ``corner``) is a row index
        of the table it refers to. Element ``i`` of a kind gets the id
        ``first_ids[k] + i``, in the order vertex, edge, face, corner, or, where
        ``ids`` gives that kind's ``(n,)`` distinct ids, ``ids[k][i]`` (later
        elements then get ids past the largest). Arrays whose dtype already
        matches are adopted, not copied.

        The links are trusted, not checked (this is the fast path of every bulk
        operation); run :func:`livemod.dlfl.validate` on the result in tests.

        Raises:
            InvalidArgumentError: a field missing or unknown, or fields of one
                kind of different lengths.
        """
        mesh = cls.__new__(cls)
        mesh.notes = []
        vid, eid, fid, cid = first_ids
        vids, eids, fids, cids = ids or (None, None, None, None)
        mesh._c = _adopt("corner", CORNER_SPEC, cid, corners, cids)
        mesh._e = _adopt("edge", EDGE_SPEC, eid, edges, eids)
        mesh._f = _adopt("face", FACE_SPEC, fid, faces, fids, optional=COLOR_SPEC)
        mesh._v = _adopt("vertex", VERTEX_SPEC, vid, vertices, vids)
        mesh._colors_used = "colored" in faces
        return mesh

    def copy(self) -> Self:
        """A deep copy with the same ids."""
        other = type(self).__new__(type(self))
        other._c = self._c.copy()
        other._e = self._e.copy()
        other._f = self._f.copy()
        other._v = self._v.copy()
        other.notes = list(self.notes)
        other._colors_used = self._colors_used
        return other

    def replace_with(self, other: MeshStorage) -> None:
        """Take over the contents of ``other`` (used by bulk operations in place)."""
        self._c, self._e, self._f, self._v = other._c, other._e, other._f, other._v
        self.notes = other.notes
        self._colors_used = other._colors_used
