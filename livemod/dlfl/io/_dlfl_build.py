"""From the records of a ``.dlfl`` file to a mesh: every check, vectorized.

The reader (:mod:`.dlflfile`) hands over whole arrays. Each check first asks a
cheap whole-array question (are the corners of the faces a permutation? is every
corner on at most one edge?); only when the answer is no does it look for the
first offending record, in the order a record-by-record reader meets them, so
the error names the same line as one would.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._graph import cycle_labels, one_cycle_each
from ..build import from_corner_arrays
from ..errors import DLFLError
from ..mesh import Mesh
from ..soup import next_in_face
from ..validate import validate
from .mtl import materials_in_force
from .source import file_error


@dataclass
class DlflRecords:
    """The records of a .dlfl file, in file order, with their 1-based line numbers.

    Attributes:
        label: the file name used in messages.
        positions: ``(V, 3)`` float64, one row per ``v`` line.
        corner_vertex: ``(C,)`` int64 vertex index of each ``fv`` line.
        corner_lines: ``(C,)`` int64 line of each ``fv`` line.
        edges: ``(E, 2)`` int64 the two corner indices of each ``e`` line.
        edge_lines: ``(E,)`` int64 line of each ``e`` line.
        face_corners: ``(K,)`` int64 corner indices of the ``f`` lines, one after
            the other.
        face_offsets: ``(F + 1,)`` int64 start of each face in ``face_corners``.
        face_lines: ``(F,)`` int64 line of each ``f`` line.
        face_hole: ``(F,)`` bool, faces after ``usemtl hole``.
        vertex_lines: ``(V,)`` int64 line of each ``v`` line.
        skipped: ``(K,)`` int64 lines whose first word is no .dlfl record
            (skipped by the reader, and reported).
        first_skipped: the text of the first of them (empty when none).
        materials: ``(line, name)`` of every ``usemtl`` line.
        libraries: the header's ``mtllib`` names.
        face_colors: ``(F,)`` rows of ``(r, g, b)`` (NaN: none), or None.
    """

    label: str
    positions: np.ndarray
    corner_vertex: np.ndarray
    corner_lines: np.ndarray
    edges: np.ndarray
    edge_lines: np.ndarray
    face_corners: np.ndarray
    face_offsets: np.ndarray
    face_lines: np.ndarray
    face_hole: np.ndarray
    vertex_lines: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    skipped: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    first_skipped: bytes = b""
    materials: list[tuple[int, str]] = field(default_factory=list)
    libraries: list[str] = field(default_factory=list)
    face_colors: np.ndarray | None = None

    def materials_in_force(self) -> list[str | None]:
        """The ``usemtl`` material of each face (None before the first)."""
        return materials_in_force(self.materials, self.face_lines)


def build_dlfl(records: DlflRecords, *, full_check: bool = False) -> Mesh:
    """Check the records and turn them into a mesh (see :func:`.read_dlfl`).

    Args:
        records: the parsed file.
        full_check: run :func:`validate` on the result even when the checks
            here already imply it passes (the reference reader in the tests).

    Raises:
        DLFLError: ``file:line: ...`` for the first bad index, a corner in two
            faces, in none, or on two edges, an edge of one corner or whose
            corners are not at opposite ends, a corner of a face of two or more
            on no edge; ``file: not a valid DLFL mesh: ...`` for a vertex whose
            corners form several fans.
    """
    num_v, num_c = len(records.positions), len(records.corner_vertex)
    _check_corner_vertices(records, num_v)
    _check_face_corners(records, num_c)
    mate = _edge_mates(records, num_c)
    order = records.face_corners  # a permutation now: corners in face order
    new_index = np.empty(num_c, dtype=np.int64)
    new_index[order] = np.arange(num_c)
    _check_pairing(records, mate, new_index)
    dense_mate = np.where(mate >= 0, new_index[np.maximum(mate, 0)], -1)[order]
    vertex_of, dense_mate, offsets, holes = _add_point_spheres(
        num_v, records.corner_vertex[order], dense_mate, records.face_offsets, records.face_hole)
    colors = records.face_colors
    if colors is not None and len(colors) < len(holes):  # the point-spheres: no colour
        colors = np.concatenate([colors, np.full((len(holes) - len(colors), 3), np.nan,
                                                 np.float32)])
    mesh = from_corner_arrays(records.positions, offsets, vertex_of, dense_mate, holes,
                              face_colors=colors)
    if full_check or not _one_fan_each(vertex_of, dense_mate, offsets, num_v):
        _fan_error(records, vertex_of, dense_mate, offsets)
        try:
            validate(mesh)
        except DLFLError as error:
            raise file_error(records.label, None, f"not a valid DLFL mesh: {error}") from None
    return mesh


def _fan_error(records: DlflRecords, vertex_of: np.ndarray, mate: np.ndarray,
               offsets: np.ndarray) -> None:
    """Raise naming the ``v`` line of the first vertex whose corners form several
    fans (a bow-tie); return when there is none (the error path of
    :func:`_one_fan_each`, same arguments)."""
    num_v = len(records.positions)
    nxt = next_in_face(offsets)
    labels = cycle_labels(np.where(mate >= 0, nxt[np.maximum(mate, 0)], np.arange(len(mate))))
    fans = np.bincount(vertex_of[labels == np.arange(len(labels))], minlength=num_v)
    bad = np.flatnonzero(fans > 1)
    if len(bad) == 0:
        return
    v = int(bad[0])
    line = int(records.vertex_lines[v]) if len(records.vertex_lines) == num_v else None
    raise file_error(records.label, line, f"vertex {v} is not a manifold vertex: its corners "
                     f"form {int(fans[v])} separate fans (the e lines pair them so)")


def _check_corner_vertices(records: DlflRecords, num_v: int) -> None:
    """Every ``fv`` line names one of the ``num_v`` vertices."""
    cvert = records.corner_vertex
    bad = np.flatnonzero((cvert < 0) | (cvert >= num_v))
    if len(bad):
        c = int(bad[0])
        raise file_error(records.label, int(records.corner_lines[c]), f"vertex index "
                        f"{int(cvert[c])} is out of range (there are {num_v} v lines)")


def _first_occurrences(key: np.ndarray) -> np.ndarray:
    """``(N,)`` int64: for each element of ``key`` (``(N,)`` int64), the position
    of the first element equal to it (an error path: it sorts)."""
    order = np.argsort(key, kind="stable")
    ordered = key[order]
    new = np.ones(len(key), dtype=bool)
    new[1:] = ordered[1:] != ordered[:-1]
    heads = np.flatnonzero(new)
    first = np.empty(len(key), dtype=np.int64)
    first[order] = np.repeat(order[heads], np.diff(np.append(heads, len(key))))
    return first


def _check_face_corners(records: DlflRecords, num_c: int) -> None:
    """The ``f`` lines list every one of the ``num_c`` corners exactly once."""
    listed = records.face_corners
    in_range = len(listed) == 0 or (listed.min() >= 0 and listed.max() < num_c)
    if len(listed) == num_c and in_range and np.bincount(listed, minlength=num_c).max(initial=0) <= 1:
        return  # the usual file: a permutation (the identity, as writers give it)
    _face_corner_error(records, num_c)
    used = np.zeros(num_c, dtype=bool)
    used[listed] = True
    orphans = np.flatnonzero(~used)
    c = int(orphans[0])
    raise file_error(records.label, int(records.corner_lines[c]), f"corner {c} "
                    "belongs to no face (no f line lists it)")


def _face_corner_error(records: DlflRecords, num_c: int) -> None:
    """Raise for the first corner of the ``f`` lines, in file order, that is out
    of range or listed before; return when there is none."""
    listed, label = records.face_corners, records.label
    position = np.arange(len(listed))
    valid = (listed >= 0) & (listed < num_c)
    first = _first_occurrences(np.where(valid, listed, num_c + position))
    bad = np.flatnonzero(~valid | (first < position))
    if len(bad) == 0:
        return
    p = int(bad[0])
    face_of = np.searchsorted(records.face_offsets, [p, first[p]], side="right") - 1
    line, c = int(records.face_lines[face_of[0]]), int(listed[p])
    if not valid[p]:
        raise file_error(label, line, f"corner index {c} is out of range "
                        f"(there are {num_c} fv lines)")
    raise file_error(label, line, f"corner {c} is already used "
                    f"by the face on line {int(records.face_lines[face_of[1]])}")


def _edge_mates(records: DlflRecords, num_c: int) -> np.ndarray:
    """``(C,)`` the corner paired with each corner by an ``e`` line, -1 if none."""
    ends = records.edges
    flat = ends.ravel()
    fine = len(flat) == 0 or (flat.min() >= 0 and flat.max() < num_c
                              and not (ends[:, 0] == ends[:, 1]).any()
                              and np.bincount(flat, minlength=num_c).max() <= 1)
    if not fine:
        _edge_error(records, num_c)
    mate = np.full(num_c, -1, dtype=np.int64)
    mate[ends[:, 0]] = ends[:, 1]
    mate[ends[:, 1]] = ends[:, 0]
    return mate


def _edge_error(records: DlflRecords, num_c: int) -> None:
    """Raise for the first bad ``e`` line: a corner out of range or on an earlier
    edge (each end in turn), or twice the same corner."""
    ends, label = records.edges, records.label
    flat = ends.ravel()
    position = np.arange(len(flat))
    valid = (flat >= 0) & (flat < num_c)
    first = _first_occurrences(np.where(valid, flat, num_c + position))
    earlier = valid & (first < position - position % 2)  # on an edge before this one
    checks = [(~valid[0::2], "index_a"), (earlier[0::2], "used_a"),
              (~valid[1::2], "index_b"), (earlier[1::2], "used_b"),
              (ends[:, 0] == ends[:, 1], "same")]
    failing = np.column_stack([bad for bad, _ in checks])
    i = int(np.flatnonzero(failing.any(axis=1))[0])
    what = checks[int(np.argmax(failing[i]))][1]
    line, c = int(records.edge_lines[i]), int(ends[i, 1 if what.endswith("b") else 0])
    if what == "same":
        raise file_error(label, line, "an edge needs two different corners")
    if what.startswith("index"):
        raise file_error(label, line, f"corner index {c} is out of range (there are {num_c} fv lines)")
    raise file_error(label, line, f"corner {c} is already on an edge")


def _check_pairing(records: DlflRecords, mate: np.ndarray, new_index: np.ndarray) -> None:
    """Each edge's corners sit at opposite ends; only point-spheres lack an edge.

    ``mate`` and ``new_index`` are ``(C,)``: each corner's mate and its place in
    face order (both in file numbering).
    """
    label, cvert, order = records.label, records.corner_vertex, records.face_corners
    offsets = records.face_offsets
    sizes = np.diff(offsets)
    dense_next = next_in_face(offsets)
    nxt = np.empty_like(order)
    nxt[order] = order[dense_next]  # next corner in file numbering
    size_of = np.repeat(sizes, sizes)[new_index]
    lone = np.flatnonzero((mate < 0) & (size_of > 1))
    if len(lone):
        c = int(lone[0])
        raise file_error(label, int(records.corner_lines[c]), f"corner {c} is on no "
                        "edge (only a point-sphere's single corner may lack an e line)")
    a, b = records.edges[:, 0], records.edges[:, 1]
    bad = np.flatnonzero((cvert[a] != cvert[nxt[b]]) | (cvert[b] != cvert[nxt[a]]))
    if len(bad):
        i = int(bad[0])
        a_, b_ = int(a[i]), int(b[i])
        raise file_error(label, int(records.edge_lines[i]), f"corners {a_} and {b_} are not "
                        f"at opposite ends of one edge (vertices {cvert[a_]}->{cvert[nxt[a_]]} "
                        f"and {cvert[b_]}->{cvert[nxt[b_]]})")


def _add_point_spheres(
    num_v: int, vertex_of: np.ndarray, mate: np.ndarray, offsets: np.ndarray, holes: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Give each vertex without a corner a one-corner face (a point-sphere).

    Args: ``(C,)`` vertex and mate of each corner in face order, ``(F + 1,)``
    offsets and ``(F,)`` hole flags. Returns the four arrays extended.
    """
    used = np.zeros(num_v, dtype=bool)
    used[vertex_of] = True
    lonely = np.flatnonzero(~used)
    if len(lonely) == 0:
        return vertex_of, mate, offsets, holes
    extra = offsets[-1] + 1 + np.arange(len(lonely))
    return (np.concatenate([vertex_of, lonely]),
            np.concatenate([mate, np.full(len(lonely), -1, dtype=np.int64)]),
            np.concatenate([offsets, extra]),
            np.concatenate([holes, np.zeros(len(lonely), dtype=bool)]))


def _one_fan_each(vertex_of: np.ndarray, mate: np.ndarray, offsets: np.ndarray,
                  num_v: int) -> bool:
    """Whether every vertex's corners form one cycle around it (``vnext``).

    Given the checks before, this is the one invariant of :func:`validate` the
    records may still break (a bow-tie vertex), at a fraction of its cost.
    ``vertex_of`` and ``mate`` are ``(C,)`` in face order, ``offsets`` ``(F + 1,)``.
    """
    nxt = next_in_face(offsets)
    vnext = np.where(mate >= 0, nxt[np.maximum(mate, 0)], np.arange(len(mate)))
    valence = np.bincount(vertex_of, minlength=num_v)
    quick = one_cycle_each(vnext, vertex_of, valence)
    if quick is not None:
        return quick
    labels = cycle_labels(vnext)  # a vertex of very high valence: the general way
    roots = labels == np.arange(len(labels))
    return bool((np.bincount(vertex_of[roots], minlength=num_v) == 1).all())
