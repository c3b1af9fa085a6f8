"""TopMod's ``.dlfl`` format: the DLFL itself, corners and edge pairing included.

Layout (TopMod's ``writeDLFL``; see docs/formats.md)::

    DLFL
    mtllib <name>.mtl
    #
    v x y z                      one per vertex, numbered from 0
    #
    fv <v> [nx ny nz] [u v]      one per corner, face by face from each head
    #
    e <fv1> <fv2>                one per edge: its two corners
    #
    usemtl default
    f <fv0> <fv1> ...            one per face
    #

Because ``e`` lines give the pairing, a ``.dlfl`` file carries every state a
DLFL can be in: 2-gons, multi-edges, self-loops, faces that visit a vertex
twice, point-spheres. livemod marks hole faces with ``usemtl hole``.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from ..analysis import face_normals
from ..arrays import MeshArrays, mesh_arrays
from ..build import from_corner_arrays
from ..errors import DLFLError
from ..mesh import Mesh
from ..validate import validate
from ._numtext import format_floats, format_uints, join_columns
from .atomic import write_atomically
from .obj import index_lines, vertex_lines
from .source import read_source, show_token

HOLE_MATERIAL = "hole"


@dataclass
class _DlflText:
    """The records of a .dlfl file, each with its 1-based line number."""

    label: str
    positions: list[tuple[float, float, float]] = field(default_factory=list)
    corner_vertex: list[int] = field(default_factory=list)
    corner_lines: list[int] = field(default_factory=list)
    edges: list[tuple[int, int, int]] = field(default_factory=list)  # (fv1, fv2, line)
    faces: list[tuple[list[int], int, bool]] = field(default_factory=list)  # (fvs, line, hole)


def read_dlfl(source: str | os.PathLike[str] | bytes, *, name: str | None = None) -> Mesh:
    """Load a TopMod ``.dlfl`` file.

    Normals and texture coordinates on ``fv`` lines are optional and ignored;
    ``[``, ``]`` and ``,`` count as blanks. Faces after ``usemtl hole`` are hole
    faces. A vertex that no corner uses becomes a point-sphere.

    Args:
        source: a path, or the file contents as bytes.
        name: the file name to use in messages.

    Returns:
        The mesh; vertex ``j`` is the ``j``-th ``v`` line, face ``i`` the
        ``i``-th ``f`` line, corner ``c`` the ``c``-th ``fv`` line.

    Raises:
        DLFLError: ``file:line: ...`` for a missing ``DLFL`` magic, malformed
            lines, indices out of range, a corner in two faces or on two edges,
            an edge whose corners are not at opposite ends; ``file: ...`` when
            the result is not a valid DLFL (a vertex whose corners form two fans).
        OSError: the file cannot be read.
    """
    data, label = read_source(source, name, "<dlfl>")
    records = parse_dlfl(data, label)
    return _build(records)


def parse_dlfl(data: bytes, label: str) -> _DlflText:
    """Read the records of a .dlfl file (no topology checks yet).

    Raises:
        DLFLError: ``label:line: ...`` for a file not starting with ``DLFL`` or a
            malformed record (missing coordinates or indices, an empty face).
    """
    if not data.startswith(b"DLFL"):
        raise DLFLError(f"{label}:1: not a .dlfl file (it must start with 'DLFL')")
    records = _DlflText(label)
    lines = data.split(b"\n")
    body = next((i for i, line in enumerate(lines) if line.startswith(b"#")), len(lines))
    hole = False
    for number, raw in enumerate(lines[body:], start=body + 1):
        words = raw.translate(_BLANKS).split()
        if not words or words[0].startswith(b"#"):
            continue
        if words[0] == b"usemtl":
            hole = len(words) > 1 and words[1] == HOLE_MATERIAL.encode()
            continue
        _record(records, words, number, hole)
    return records


_BLANKS = bytes.maketrans(b"[],\r\t", b"     ")


def _record(records: _DlflText, words: list[bytes], line: int, hole: bool) -> None:
    """Store one ``v``/``fv``/``e``/``f`` line; other keywords are ignored."""
    key, args = words[0], words[1:]
    where = f"{records.label}:{line}"
    if key == b"v":
        if len(args) < 3:
            raise DLFLError(f"{where}: a v line needs 3 coordinates, got {len(args)}")
        x, y, z = (_number(a, where) for a in args[:3])
        records.positions.append((x, y, z))
    elif key == b"fv":
        if not args:
            raise DLFLError(f"{where}: an fv line needs a vertex index")
        records.corner_vertex.append(_integer(args[0], where))
        records.corner_lines.append(line)
    elif key == b"e":
        if len(args) < 2:
            raise DLFLError(f"{where}: an e line needs two corner (fv) indices")
        records.edges.append((_integer(args[0], where), _integer(args[1], where), line))
    elif key == b"f":
        if not args:
            raise DLFLError(f"{where}: empty face (an f line with no corners)")
        records.faces.append(([_integer(a, where) for a in args], line, hole))


def _number(word: bytes, where: str) -> float:
    try:
        value = float(word) if b"_" not in word else float("nan")
    except ValueError:
        raise DLFLError(f"{where}: bad number {show_token(word)}") from None
    if not np.isfinite(value):
        raise DLFLError(f"{where}: {show_token(word)} is not a finite number")
    return value


def _integer(word: bytes, where: str) -> int:
    try:
        if b"_" in word:
            raise ValueError(word)
        value = int(word)
    except ValueError:
        raise DLFLError(f"{where}: bad index {show_token(word)}") from None
    if abs(value) >= 2**62:
        raise DLFLError(f"{where}: index {show_token(word)} is out of range")
    return value



# ------------------------------------------------------------------- building


def _build(records: _DlflText) -> Mesh:
    """Check the records and turn them into a mesh (see :func:`read_dlfl`)."""
    label = records.label
    num_v, num_c = len(records.positions), len(records.corner_vertex)
    cvert = np.array(records.corner_vertex, dtype=np.int64)
    bad = np.flatnonzero((cvert < 0) | (cvert >= num_v))
    if len(bad):
        c = int(bad[0])
        raise DLFLError(f"{label}:{records.corner_lines[c]}: vertex index {int(cvert[c])} "
                        f"is out of range (there are {num_v} v lines)")
    order, offsets, holes = _face_layout(records, num_c)
    new_index = np.empty(num_c, dtype=np.int64)
    new_index[order] = np.arange(num_c)
    mate = _edge_mates(records, num_c)
    _check_pairing(records, cvert, mate, order, offsets, new_index)
    dense_mate = np.where(mate >= 0, new_index[np.maximum(mate, 0)], -1)[order]
    vertex_of = cvert[order]
    vertex_of, dense_mate, offsets, holes = _add_point_spheres(
        num_v, vertex_of, dense_mate, offsets, holes)
    positions = np.array(records.positions, dtype=np.float64).reshape(-1, 3)
    mesh = from_corner_arrays(positions, offsets, vertex_of, dense_mate, holes)
    try:
        validate(mesh)
    except DLFLError as error:
        raise DLFLError(f"{label}: not a valid DLFL mesh: {error}") from None
    return mesh


def _face_layout(records: _DlflText, num_c: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Corners in face order, face offsets and hole flags; every corner in one face."""
    owner = np.full(num_c, -1, dtype=np.int64)
    order: list[int] = []
    for index, (corners, line, _) in enumerate(records.faces):
        for c in corners:
            if not 0 <= c < num_c:
                raise DLFLError(f"{records.label}:{line}: corner index {c} is out of range "
                                f"(there are {num_c} fv lines)")
            if owner[c] >= 0:
                other = records.faces[owner[c]][1]
                raise DLFLError(f"{records.label}:{line}: corner {c} is already used "
                                f"by the face on line {other}")
            owner[c] = index
        order.extend(corners)
    orphans = np.flatnonzero(owner < 0)
    if len(orphans):
        c = int(orphans[0])
        raise DLFLError(f"{records.label}:{records.corner_lines[c]}: corner {c} "
                        "belongs to no face (no f line lists it)")
    sizes = np.array([len(f[0]) for f in records.faces], dtype=np.int64)
    offsets = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    holes = np.array([f[2] for f in records.faces], dtype=bool)
    return np.array(order, dtype=np.int64), offsets, holes


def _edge_mates(records: _DlflText, num_c: int) -> np.ndarray:
    """``(C,)`` the corner paired with each corner by an ``e`` line, -1 if none."""
    mate = np.full(num_c, -1, dtype=np.int64)
    for a, b, line in records.edges:
        for c in (a, b):
            if not 0 <= c < num_c:
                raise DLFLError(f"{records.label}:{line}: corner index {c} is out of range "
                                f"(there are {num_c} fv lines)")
            if mate[c] >= 0:
                raise DLFLError(f"{records.label}:{line}: corner {c} is already on an edge")
        if a == b:
            raise DLFLError(f"{records.label}:{line}: an edge needs two different corners")
        mate[a], mate[b] = b, a
    return mate


def _check_pairing(records: _DlflText, cvert: np.ndarray, mate: np.ndarray, order: np.ndarray,
                   offsets: np.ndarray, new_index: np.ndarray) -> None:
    """Each edge's corners sit at opposite ends; only point-spheres lack an edge."""
    sizes = np.diff(offsets)
    dense_next = np.arange(1, len(order) + 1)
    dense_next[offsets[1:][sizes > 0] - 1] = offsets[:-1][sizes > 0]
    nxt = np.empty_like(order)
    nxt[order] = order[dense_next]  # next corner in file numbering
    size_of = np.repeat(sizes, sizes)[new_index]
    lone = np.flatnonzero((mate < 0) & (size_of > 1))
    if len(lone):
        c = int(lone[0])
        raise DLFLError(f"{records.label}:{records.corner_lines[c]}: corner {c} is on no "
                        "edge (only a point-sphere's single corner may lack an e line)")
    for a, b, line in records.edges:
        if cvert[a] != cvert[nxt[b]] or cvert[b] != cvert[nxt[a]]:
            raise DLFLError(f"{records.label}:{line}: corners {a} and {b} are not at opposite "
                            f"ends of one edge (vertices {cvert[a]}->{cvert[nxt[a]]} and "
                            f"{cvert[b]}->{cvert[nxt[b]]})")


def _add_point_spheres(
    num_v: int, vertex_of: np.ndarray, mate: np.ndarray, offsets: np.ndarray, holes: np.ndarray,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Give each vertex without a corner a one-corner face (a point-sphere)."""
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


# --------------------------------------------------------------------- writer


def write_dlfl(mesh: Mesh, path: str | os.PathLike[str], *, reverse: bool = False) -> None:
    """Write ``mesh`` as a TopMod ``.dlfl`` file, atomically.

    Args:
        mesh: the mesh.
        path: the target file; its stem names the ``mtllib`` (TopMod wrote a
            null pointer there when it had no file name).
        reverse: write every face backwards (head first, then along ``prev``)
            and each edge as ``(V1.next, V2.next)``, which describes the mesh
            with all faces flipped (TopMod's crust uses it).

    Raises:
        OSError: the file cannot be written; an existing file is left intact.
    """
    stem = os.path.splitext(os.path.basename(os.fspath(path)))[0] or "mesh"
    write_atomically(path, dlfl_pieces(mesh, stem, reverse=reverse))


def dlfl_bytes(mesh: Mesh, mtl_name: str = "mesh", *, reverse: bool = False) -> bytes:
    """The ``.dlfl`` text of ``mesh`` (see :func:`write_dlfl`)."""
    return b"".join(dlfl_pieces(mesh, mtl_name, reverse=reverse))


def dlfl_pieces(mesh: Mesh, mtl_name: str = "mesh", *, reverse: bool = False,
                ) -> Iterator[bytes]:
    """The ``.dlfl`` text of ``mesh`` in pieces, for :func:`write_dlfl`.

    Precondition: the mesh is not changed while the pieces are consumed.
    """
    a = mesh_arrays(mesh)
    header = b"DLFL\nmtllib %s.mtl\n#\n" % mtl_name.encode("utf-8", "replace")
    return itertools.chain(
        [header], vertex_lines(a.positions, b"v"), [b"#\n", _corner_lines(a), b"#\n"],
        _edge_lines(a, reverse), [b"#\n"], _face_lines(a, reverse), [b"#\n"],
    )


def _corner_lines(a: MeshArrays) -> bytes:
    """``fv <v> [nx ny nz] [0 0] `` per corner, with its face's normal (6 decimals)."""
    if len(a.corner_vertex) == 0:
        return b""
    normals = np.round(face_normals(a), 6)[a.corner_face] + 0.0  # + 0.0 drops -0.0
    fields = format_floats(normals.ravel()).reshape(len(normals), 3, -1)
    return join_columns(len(normals), [
        b"fv ", format_uints(a.corner_vertex), b" [", fields[:, 0], b" ", fields[:, 1], b" ",
        fields[:, 2], b"] [0 0] \n",
    ])


def _edge_lines(a: MeshArrays, reverse: bool) -> Iterator[bytes]:
    ends = a.edge_corners
    if reverse:
        ends = a.corner_next[ends]
    return index_lines(ends.ravel(), np.full(len(ends), 2, dtype=np.int64), b"e")


def _face_lines(a: MeshArrays, reverse: bool) -> Iterator[bytes]:
    """``usemtl`` whenever the material changes, and ``f`` lines of corner indices."""
    corners = np.arange(len(a.corner_vertex), dtype=np.int64)
    if reverse:
        # head first, then the other corners backwards
        sizes = a.face_sizes
        start = np.repeat(a.face_offsets[:-1], sizes)
        rank = corners - start
        corners = np.where(rank == 0, start, start + sizes[a.corner_face] - rank)
    sizes = a.face_sizes
    runs = np.flatnonzero(np.diff(a.face_hole.astype(np.int8))) + 1
    bounds = [0, *runs.tolist(), len(sizes)]
    for lo, hi in zip(bounds[:-1], bounds[1:], strict=True):
        if hi == lo:
            continue
        material = HOLE_MATERIAL if a.face_hole[lo] else "default"
        c_lo, c_hi = a.face_offsets[lo], a.face_offsets[hi]
        yield b"usemtl %s\n" % material.encode()
        yield from index_lines(corners[c_lo:c_hi], sizes[lo:hi], b"f")
