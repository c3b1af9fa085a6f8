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
twice, point-spheres. livemod marks hole faces with ``usemtl hole``. Face colours
go where TopMod keeps them: each face's ``usemtl`` material, whose ``Kd`` the
``mtllib`` library beside the file holds (see :mod:`.mtl`; written only for a
mesh with colours, read back when present).

Reading works like the OBJ reader: the lines are split and sorted by their
first bytes once, and the usual ``v``, ``fv``, ``e`` and ``f`` lines (what
livemod and TopMod write, CRLF too) are parsed in passes of 65,536 lines with
numpy (``fv`` lines only as far as their vertex index). Every other line, and
every line a pass does not accept, goes to :func:`_python_record`, the
reference parser, which also words the ``file:line: ...`` errors; the checks of
:mod:`._dlfl_build` then find the first bad record in file order. Writing
formats whole passes of lines with numpy, a few ahead on other threads.
"""


from __future__ import annotations

import itertools
import os
from collections.abc import Callable, Iterator

import numpy as np

from ..analysis import face_normals
from ..arrays import MeshArrays, mesh_arrays
from ..mesh import Mesh
from ..soup import offsets_of
from ._dlfl_build import DlflRecords, build_dlfl
from ._lines import (
    gather_lines,
    leading_uints,
    parse_index_lines,
    parse_number_lines,
    pass_starts,
    split_lines,
)
from ._numtext import format_rounded, format_uints, join_columns
from ._parallel import map_in_order
from .atomic import write_atomically
from .mtl import (
    DEFAULT_MATERIAL,
    HOLE_MATERIAL,
    face_colors_of,
    materials_of,
    mtl_bytes,
    read_libraries,
)
from .obj import (
    CONTROLS_TO_UNDERSCORE,
    index_lines,
    material_face_lines,
    merge_face_blocks,
    vertex_lines,
)
from .source import (
    companion_path,
    file_error,
    file_stem,
    lf_line_ends,
    read_source,
    report_skipped,
    show_token,
)


def read_dlfl(source: str | os.PathLike[str] | bytes, *, name: str | None = None) -> Mesh:
    """Load a TopMod ``.dlfl`` file.

    Normals and texture coordinates on ``fv`` lines are optional and ignored;
    ``[``, ``]`` and ``,`` count as blanks. Faces after ``usemtl hole`` are hole
    faces; faces after another ``usemtl`` take the colour its ``Kd`` gives in the
    header's ``mtllib`` library, read beside the file (a library missing is a
    :class:`~livemod.dlfl.errors.DLFLRepairWarning`). A vertex that no corner
    uses becomes a point-sphere.

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
    skipped = records.skipped.tolist()
    if skipped and len(records.positions) == 0 and len(records.face_lines) == 0:
        word = records.first_skipped.split(None, 1)[0]
        raise file_error(label, skipped[0], f"no geometry, and the line starts with "
                         f"{show_token(word)}, which is no .dlfl record")
    notes: list[str] = []
    if records.libraries and not isinstance(source, bytes):
        folder = os.path.dirname(os.path.abspath(os.fspath(source)))
        in_force = records.materials_in_force()
        library = read_libraries(records.libraries, folder, label, in_force, notes)
        records.face_colors = face_colors_of(in_force, library)
    mesh = build_dlfl(records)
    mesh.notes += notes
    if skipped:
        report_skipped(mesh, label, skipped, records.first_skipped)
    return mesh


def parse_dlfl(data: bytes, label: str = "<dlfl>", *, fast: bool = True) -> DlflRecords:
    """Read the records of a .dlfl file (no topology checks yet).

    Args:
        data: the file contents.
        label: the file name used in error messages.
        fast: parse the usual lines with numpy (False parses every line in
            Python, the reference the tests compare against).

    Returns:
        The records in file order, with 1-based line numbers; the same for
        either value of ``fast``.

    Raises:
        DLFLError: ``label:line: ...`` for a file not starting with ``DLFL`` or
            the first malformed record (missing coordinates or indices, an
            empty face).
    """
    if not data.startswith(b"DLFL"):
        raise file_error(label, 1, "not a .dlfl file (it must start with 'DLFL')")
    data = lf_line_ends(data)
    if not data.endswith(b"\n"):
        data += b"\n"  # split_lines wants it; the line count stays that of data.split
    buf, starts, ends = split_lines(data)
    _check_header_ends(buf, starts, label)
    kinds = _classify(buf, starts, fast)
    records = _Collected(label)
    records.libraries = _header_libraries(buf, starts)
    python_lines = [np.flatnonzero(kinds == _OTHER)]
    for kind, block, rejected in _fast_passes(buf, starts, ends, kinds):
        records.blocks[kind].append(block)
        python_lines.append(rejected)
    for line in np.sort(np.concatenate(python_lines)).tolist():
        raw = buf[starts[line] : ends[line]].tobytes()
        records.add(line, _python_record(raw, line + 1, label))
    return records.finish()


# ---------------------------------------------------------------- line kinds

_SKIP, _VERTEX, _CORNER, _EDGE, _FACE, _OTHER, _UNKNOWN = range(7)
_MATERIAL = _OTHER  # the kind of a usemtl record (those lines are Python's)


def _classify(buf: np.ndarray, starts: np.ndarray, fast: bool) -> np.ndarray:
    """``(L,)`` int8 kind of each line from its first three bytes.

    Lines before the first ``#`` line (the header) and empty or ``#`` lines are
    skipped; ``v``, ``fv``, ``e``, ``f`` then a space or tab are records for the
    numpy passes; every other line (``usemtl``, a line starting with a blank,
    ``v[``...) goes to the Python parser, which decides what it is.
    """
    parts = [starts[i : i + _LINES_PER_PASS] for i in range(0, len(starts), _LINES_PER_PASS)]
    kinds = np.concatenate([np.zeros(0, dtype=np.int8),
                            *map_in_order(lambda part: _kinds(buf, part, fast), parts)])
    kinds[: _body_start(buf, starts)] = _SKIP
    return kinds


def _kinds(buf: np.ndarray, starts: np.ndarray, fast: bool) -> np.ndarray:
    """:func:`_classify` of the lines at ``starts`` (``(n,)``), the header aside."""
    b0 = buf[starts]
    b1 = buf[np.minimum(starts + 1, len(buf) - 1)]
    if not fast:
        return _KIND_ALONE[b0]
    kinds = np.where((b1 == 32) | (b1 == 9), _KIND_BEFORE_BLANK[b0], _KIND_ALONE[b0])
    fv = np.flatnonzero((b0 == ord("f")) & (b1 == ord("v")))
    b2 = buf[starts[fv] + 2]  # b1 is no newline there: b2 is in the same line
    kinds[fv[(b2 == 32) | (b2 == 9)]] = _CORNER
    return kinds


def _body_start(buf: np.ndarray, starts: np.ndarray) -> int:
    """The first line starting with ``#`` (the header's end), or the line count."""
    for i in range(0, len(starts), 256):  # the header is a few lines
        hits = np.flatnonzero(buf[starts[i : i + 256]] == ord("#"))
        if len(hits):
            return i + int(hits[0])
    return len(starts)


def _header_libraries(buf: np.ndarray, starts: np.ndarray) -> list[str]:
    """The names the header's ``mtllib`` lines give (the lines before the first ``#``)."""
    body = _body_start(buf, starts)
    head = buf[: starts[body] if body < len(starts) else len(buf)].tobytes()
    return [name.decode("utf-8", "replace") for line in head.splitlines()
            if line.split()[:1] == [b"mtllib"] for name in line.split()[1:]]


def _check_header_ends(buf: np.ndarray, starts: np.ndarray, label: str) -> None:
    """Refuse records with no ``#`` line before them: everything up to the first
    ``#`` line is header, so such a file would silently load as an empty mesh
    (a file of the ``DLFL`` and ``mtllib`` lines alone is a valid empty one)."""
    if _body_start(buf, starts) < len(starts):
        return
    record = np.flatnonzero(np.isin(buf[starts[1:]], np.frombuffer(b"vef", dtype=np.uint8)))
    if len(record):
        raise file_error(label, int(record[0]) + 2, "no '#' line ends the header before "
                        "this record, so it and every later line would be skipped as header")


def _kind_table(keywords: dict[bytes, int]) -> np.ndarray:
    """``(256,)`` int8 kind of a line by its first byte: ``keywords``' kinds, skipped
    for ``#`` and an empty line, the Python parser's for any other."""
    table = np.full(256, _OTHER, dtype=np.int8)
    table[[ord("#"), ord("\n")]] = _SKIP
    for byte, kind in keywords.items():
        table[ord(byte)] = kind
    return table


# by the first byte, when the second is a space or tab, and else
_KIND_BEFORE_BLANK = _kind_table({b"v": _VERTEX, b"e": _EDGE, b"f": _FACE})
_KIND_ALONE = _kind_table({})
# what ends a token: the blanks of bytes.split() and the bytes .dlfl reads as blanks
_ENDS_TOKEN = np.zeros(256, dtype=bool)
_ENDS_TOKEN[list(b" \t\n\r\v\f[],")] = True


# ------------------------------------------------------------ numpy passes

# lines per pass: the OBJ reader's figure (temporaries stay in the cache)
_LINES_PER_PASS = 1 << 16

_Block = tuple[np.ndarray, ...]  # (lines, values) or (lines, counts, values)
_Pass = Callable[[np.ndarray, np.ndarray, np.ndarray, np.ndarray], tuple[_Block, np.ndarray]]


def _fast_passes(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, kinds: np.ndarray,
                 ) -> Iterator[tuple[int, _Block, np.ndarray]]:
    """``(kind, block, rejected lines)`` of every pass, kind by kind in file order.

    The passes run on a few threads (numpy lets go of the GIL in them); a
    block holds the 0-based lines the pass accepted and their values.
    """
    tasks: list[tuple[int, np.ndarray]] = []
    for kind in (_VERTEX, _CORNER, _EDGE, _FACE):
        lines = np.flatnonzero(kinds == kind)
        tasks += [(kind, lines[i : i + _LINES_PER_PASS])
                  for i in range(0, len(lines), _LINES_PER_PASS)]
    # a small file's passes cost less than starting threads for them
    threads = 1 if sum(len(part) for _, part in tasks) <= _LINES_PER_PASS else None
    results = map_in_order(lambda task: _PASSES[task[0]](buf, starts, ends, task[1]), tasks,
                           threads)
    for (kind, _), (block, rejected) in zip(tasks, results, strict=True):
        yield kind, block, rejected


def _vertex_pass(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, part: np.ndarray,
                 ) -> tuple[_Block, np.ndarray]:
    """``((lines, (n, 3) positions), rejected lines)`` of the ``v`` lines ``part``."""
    block, block_starts = gather_lines(buf, starts, ends, part)
    block[block_starts] = 32  # blank the keyword
    values, accepted = parse_number_lines(block, block_starts, 3)
    return (_kept(part, accepted), _kept(values, accepted)), part[~accepted]


def _corner_pass(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, part: np.ndarray,
                 ) -> tuple[_Block, np.ndarray]:
    """``((lines, (n,) vertex indices), rejected lines)`` of the ``fv`` lines ``part``.

    Only the first field counts (the rest of the line is ignored), so only its
    digits are read: the lines accepted start ``fv``, a blank, digits, a blank.
    """
    vertex, length = leading_uints(buf, starts[part] + 3)
    ends_ok = _ENDS_TOKEN[buf[starts[part] + 3 + length]]
    accepted = (length > 0) & ends_ok
    return (_kept(part, accepted), _kept(vertex, accepted)), part[~accepted]


def _edge_pass(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, part: np.ndarray,
               ) -> tuple[_Block, np.ndarray]:
    """``((lines, (n, 2) corner indices), rejected lines)`` of the ``e`` lines ``part``:
    lines ``e a b`` (one space between), anything after ``b`` and a blank ignored."""
    a, a_len = leading_uints(buf, starts[part] + 2)
    b_at = starts[part] + 3 + a_len
    b, b_len = leading_uints(buf, b_at)
    accepted = (a_len > 0) & (buf[b_at - 1] == ord(" ")) & (b_len > 0)
    accepted &= _ENDS_TOKEN[buf[np.minimum(b_at + b_len, len(buf) - 1)]]
    return (_kept(part, accepted), _kept(np.column_stack([a, b]), accepted)), part[~accepted]


def _face_pass(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, part: np.ndarray,
               ) -> tuple[_Block, np.ndarray]:
    """``((lines, counts, corner indices), rejected lines)`` of the ``f`` lines ``part``."""
    block, block_starts = gather_lines(buf, starts, ends, part)
    block[block_starts] = 32
    values, counts, accepted = parse_index_lines(block, block_starts, slashes=False)
    if accepted.all():  # the usual pass: nothing to drop, nothing to copy
        return (part, counts, values), part[:0]
    keep = np.repeat(accepted, counts)
    return (part[accepted], counts[accepted], values[keep]), part[~accepted]


def _kept(rows: np.ndarray, accepted: np.ndarray) -> np.ndarray:
    """The ``accepted`` (``(n,)`` bool) rows of ``rows``: ``rows`` itself when all
    are (no copy of a pass's arrays in the usual case)."""
    return rows if accepted.all() else rows[accepted]


_PASSES: dict[int, _Pass] = {
    _VERTEX: _vertex_pass, _CORNER: _corner_pass, _EDGE: _edge_pass, _FACE: _face_pass}


# ------------------------------------------------------------ Python parser

_BLANKS = bytes.maketrans(b"[],\r\t", b"     ")


def _python_record(raw: bytes, line: int, label: str) -> tuple[int, object] | None:
    """Reference parser for one line: ``(kind, value)``, or None for a line the
    reader passes over (blank, comment, ``mtllib``).

    Values: ``(x, y, z)`` for ``v``, the vertex index for ``fv``, ``(a, b)`` for
    ``e``, the list of corner indices for ``f``, the material's name for
    ``usemtl``; ``(_UNKNOWN, raw)`` for a line whose first word
    is none of these (it is skipped and reported).

    Raises:
        FileFormatError: ``label:line: ...`` for a malformed ``v``, ``fv``, ``e``
            or ``f`` line.
    """
    words = raw.translate(_BLANKS).split()
    if not words or words[0].startswith(b"#") or words[0] == b"mtllib":
        return None
    key, args = words[0], words[1:]
    if key == b"usemtl":
        return _MATERIAL, args[0].decode("utf-8", "replace") if args else ""
    if key not in _NEEDS:
        return _UNKNOWN, raw
    least, what = _NEEDS[key]
    if len(args) < least:
        raise file_error(label, line, what if key != b"v" else f"{what}, got {len(args)}")
    if key == b"v":
        return _VERTEX, tuple(_number(a, label, line) for a in args[:3])
    indices = [_integer(a, label, line) for a in (args if key == b"f" else args[:least])]
    return {b"fv": _CORNER, b"e": _EDGE, b"f": _FACE}[key], (
        indices[0] if key == b"fv" else tuple(indices) if key == b"e" else indices)


# each record's keyword: how many values it needs, and the error when it has fewer
_NEEDS = {
    b"v": (3, "a v line needs 3 coordinates"),
    b"fv": (1, "an fv line needs a vertex index"),
    b"e": (2, "an e line needs two corner (fv) indices"),
    b"f": (1, "empty face (an f line with no corners)"),
}


def _number(word: bytes, label: str, line: int) -> float:
    try:
        value = float(word) if b"_" not in word else float("nan")
    except ValueError:
        raise file_error(label, line, f"bad number {show_token(word)}") from None
    if not np.isfinite(value):
        raise file_error(label, line, f"{show_token(word)} is not a finite number")
    return value


def _integer(word: bytes, label: str, line: int) -> int:
    try:
        if b"_" in word:
            raise ValueError(word)
        value = int(word)
    except ValueError:
        raise file_error(label, line, f"bad index {show_token(word)}") from None
    if abs(value) >= 2**62:
        raise file_error(label, line, f"index {show_token(word)} is out of range")
    return value


# ----------------------------------------------------------------- merging


class _Collected:
    """The records from the numpy passes and from the Python parser, by kind."""

    def __init__(self, label: str) -> None:
        self.label = label
        self.libraries: list[str] = []
        self.blocks: dict[int, list[_Block]] = {k: [] for k in (_VERTEX, _CORNER, _EDGE, _FACE)}
        self.python: dict[int, list[tuple[int, object]]] = {
            k: [] for k in (_VERTEX, _CORNER, _EDGE, _FACE, _MATERIAL, _UNKNOWN)}

    def add(self, line: int, record: tuple[int, object] | None) -> None:
        """Keep the record of 0-based line ``line`` (None: nothing to keep)."""
        if record is not None:
            self.python[record[0]].append((line, record[1]))

    def finish(self) -> DlflRecords:
        """The records of every kind, in file order."""
        v_lines, positions = self._fixed(_VERTEX, (3,), np.float64)
        c_lines, corner_vertex = self._fixed(_CORNER, (), np.int64)
        e_lines, edges = self._fixed(_EDGE, (2,), np.int64)
        f_lines, counts, corners = self._faces()
        offsets = offsets_of(counts)
        for lines in (v_lines, c_lines, e_lines, f_lines):
            lines += 1  # 1-based, in place: fresh arrays (a million-face file's 100 MB)
        materials = [(line + 1, str(name)) for line, name in self.python[_MATERIAL]]
        unknown = self.python[_UNKNOWN]
        records = DlflRecords(self.label, positions, corner_vertex, c_lines, edges, e_lines,
                              corners, offsets, f_lines, np.zeros(0, bool), v_lines,
                              np.array([line + 1 for line, _ in unknown], dtype=np.int64),
                              bytes(unknown[0][1]) if unknown else b"",  # type: ignore[call-overload]
                              materials=materials, libraries=self.libraries)
        records.face_hole = np.array([name == HOLE_MATERIAL for name in
                                      records.materials_in_force()], dtype=bool)
        return records

    def _fixed(self, kind: int, shape: tuple[int, ...], dtype: type,
               ) -> tuple[np.ndarray, np.ndarray]:
        """``(lines, values)`` of a kind with one value or a fixed row per line."""
        items = self.python[kind]
        py_lines = np.array([line for line, _ in items], dtype=np.int64)
        py_values: np.ndarray = np.array([value for _, value in items], dtype=dtype)
        py_values = py_values.reshape(-1, *shape)
        blocks = [*self.blocks[kind], (py_lines, py_values)]
        lines = np.concatenate([b[0] for b in blocks])
        values: np.ndarray = np.concatenate([b[1] for b in blocks]).astype(dtype, copy=False)
        if len(items) == 0:  # the numpy blocks come in file order
            return lines, values
        order = np.argsort(lines, kind="stable")
        return lines[order], values[order]

    def _faces(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(lines, corner counts, corner indices)`` of the ``f`` lines."""
        items: list[tuple[int, list[int]]] = self.python[_FACE]  # type: ignore[assignment]
        py_lines = np.array([line for line, _ in items], dtype=np.int64)
        py_counts = np.array([len(c) for _, c in items], dtype=np.int64)
        py_corners = np.array([i for _, c in items for i in c], dtype=np.int64)
        blocks = [*self.blocks[_FACE], (py_lines, py_counts, py_corners)]
        if len(items) == 0:
            return tuple(np.concatenate([b[i] for b in blocks]) for i in range(3))  # type: ignore[return-value]
        return merge_face_blocks(blocks)  # type: ignore[arg-type]


# --------------------------------------------------------------------- writer


def write_dlfl(mesh: Mesh, path: str | os.PathLike[str], *, reverse: bool = False) -> None:
    """Write ``mesh`` as a TopMod ``.dlfl`` file, atomically.

    Args:
        mesh: the mesh.
        path: the target file; its stem names the ``mtllib`` (TopMod wrote a
            null pointer there when it had no file name). A mesh with face
            colours gets that library beside the file, written first: one
            material per colour, chosen by the faces' ``usemtl`` (see :mod:`.mtl`).
        reverse: write every face backwards (head first, then along ``prev``)
            and each edge as ``(V1.next, V2.next)``, which describes the mesh
            with all faces flipped (TopMod's crust uses it).

    Raises:
        OSError: the file cannot be written; an existing file is left intact.
    """
    name = os.fspath(path)
    colors = mesh.face_colors()
    if colors is not None:  # the library first: the file never names a missing one
        write_atomically(companion_path(name, ".mtl"), mtl_bytes(materials_of(colors)))
    write_atomically(name, dlfl_pieces(mesh, file_stem(name), reverse=reverse))


def dlfl_bytes(mesh: Mesh, mtl_name: str = "mesh", *, reverse: bool = False) -> bytes:
    """The ``.dlfl`` text of ``mesh`` (see :func:`write_dlfl`)."""
    return b"".join(dlfl_pieces(mesh, mtl_name, reverse=reverse))


def dlfl_pieces(mesh: Mesh, mtl_name: str = "mesh", *, reverse: bool = False,
                ) -> Iterator[bytes]:
    """The ``.dlfl`` text of ``mesh`` in pieces of about 65,536 lines, for
    :func:`write_dlfl` (the pieces are formatted a few ahead on other threads).

    Precondition: the mesh is not changed while the pieces are consumed.
    """
    a = mesh_arrays(mesh)
    # a newline in the name (a file name may hold one) would end the header early
    name = mtl_name.encode("utf-8", "replace").translate(CONTROLS_TO_UNDERSCORE)
    header = b"DLFL\nmtllib %s.mtl\n#\n" % name
    return itertools.chain(
        [header], vertex_lines(a.positions, b"v"), [b"#\n"], _corner_lines(a), [b"#\n"],
        _edge_lines(a, reverse), [b"#\n"], _face_lines(a, reverse), [b"#\n"],
    )




def _corner_lines(a: MeshArrays) -> Iterator[bytes]:
    """``fv <v> [nx ny nz] [0 0] `` per corner, with its face's unit normal rounded
    to 6 decimals, in passes of whole faces (about ``_LINES_PER_PASS`` corners)."""
    return map_in_order(lambda faces: _corner_pass_text(a, *faces), _face_passes(a.face_offsets))


def _face_passes(offsets: np.ndarray) -> list[tuple[int, int]]:
    """``(first, end)`` face ranges of about ``_LINES_PER_PASS`` corners each, from
    the ``(F + 1,)`` face offsets."""
    bounds = [*pass_starts(offsets[:-1], int(offsets[-1]), _LINES_PER_PASS).tolist(),
              len(offsets) - 1]
    return list(zip(bounds[:-1], bounds[1:], strict=True))


def _corner_pass_text(a: MeshArrays, first: int, end: int) -> bytes:
    """The ``fv`` lines of faces ``first:end``.

    The normals are :func:`face_normals` of those faces alone: each face's
    normal involves only its own corners (bit for bit the whole mesh's, inside
    the band of ``livemod.dlfl._vectors``), and a pass's temporaries stay in
    the cache where the whole mesh's (hundreds of MB at a million faces) did not.
    """
    part = _faces_alone(a, first, end)
    fields = format_rounded(face_normals(part).ravel(), 6).reshape(end - first, 3, -1)
    space = np.full((end - first, 1), ord(" "), dtype=np.uint8)
    normals = np.concatenate([fields[:, 0], space, fields[:, 1], space, fields[:, 2]], axis=1)
    return join_columns(len(part.corner_vertex), [
        b"fv ", format_uints(part.corner_vertex), b" [", normals[part.corner_face],
        b"] [0 0] \n"])


def _faces_alone(a: MeshArrays, first: int, end: int) -> MeshArrays:
    """The faces ``first:end`` of ``a`` and their corners, without edges (all the
    rings and positions a face measure reads)."""
    lo, hi = int(a.face_offsets[first]), int(a.face_offsets[end])
    no_edge = np.full(hi - lo, -1, dtype=np.int64)
    return MeshArrays(
        positions=a.positions, vertex_ids=a.vertex_ids, face_ids=a.face_ids[first:end],
        face_offsets=a.face_offsets[first : end + 1] - lo, face_hole=a.face_hole[first:end],
        corner_ids=a.corner_ids[lo:hi], corner_vertex=a.corner_vertex[lo:hi],
        corner_face=a.corner_face[lo:hi] - first, corner_edge=no_edge, corner_mate=no_edge,
        edge_ids=np.zeros(0, dtype=np.int64), edge_corners=np.zeros((0, 2), dtype=np.int64))


def _edge_lines(a: MeshArrays, reverse: bool) -> Iterator[bytes]:
    ends = a.edge_corners
    if reverse:
        ends = a.corner_next[ends]
    return index_lines(ends.ravel(), np.full(len(ends), 2, dtype=np.int64), b"e")


def _face_lines(a: MeshArrays, reverse: bool) -> Iterator[bytes]:
    """``usemtl`` whenever the material changes, and ``f`` lines of corner indices."""
    corners = np.arange(len(a.corner_vertex), dtype=np.int64)
    sizes = a.face_sizes
    if reverse:
        # head first, then the other corners backwards
        start = np.repeat(a.face_offsets[:-1], sizes)
        rank = corners - start
        corners = np.where(rank == 0, start, start + sizes[a.corner_face] - rank)
    names, index = _face_materials(a)
    return material_face_lines(corners, sizes, names, index, b"f")


def _face_materials(a: MeshArrays) -> tuple[list[str], np.ndarray]:
    """The material names and ``(F,)`` material of each face: ``hole`` for holes,
    one per colour (:func:`.mtl.materials_of`) or ``default`` for the others."""
    if a.face_colors is None:
        return [DEFAULT_MATERIAL, HOLE_MATERIAL], a.face_hole.astype(np.int64)
    materials = materials_of(a.face_colors)
    names = [*materials.names, HOLE_MATERIAL]
    return names, np.where(a.face_hole, len(names) - 1, materials.index)
