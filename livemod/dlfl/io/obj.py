"""Wavefront OBJ: vectorized reader and writer.

Reading keeps ``v`` positions, ``f`` polygons and their colours (the ``Kd`` of
the ``usemtl`` material in force, from the ``mtllib`` libraries beside the file,
see :mod:`.mtl`) and ignores everything else (``vn``, ``vt``, ``o``, ``g``,
``s``, ``l``, comments, unknown keywords). Faces take the leading index of each ``v``, ``v/t``,
``v//n`` or ``v/t/n`` token; negative indices count back from the last vertex
read so far. Coordinates may be separated by spaces, tabs or commas (TopMod's
own files write ``v 1.0, 1.0, 1.0``); numbers after the third are ignored.
Line endings ``\\n``, ``\\r\\n`` or a lone ``\\r``, mixed or not (Python's
universal newlines); a line ending in ``\\`` continues on the next. The first
``f`` line becomes face id 0.

Plain lines are parsed for the whole file at once with numpy (see
:mod:`._lines`); any other line goes through :func:`_parse_line`, the reference
parser, which also produces the ``file:line: what is wrong`` errors.
"""

from __future__ import annotations

import itertools
import os
from collections.abc import Iterator
from dataclasses import dataclass, field

import numpy as np

from ..arrays import MeshArrays, mesh_arrays
from ..build import from_polygons, point_cloud
from ..errors import DLFLError
from ..mesh import Mesh
from ..soup import offsets_of
from ._lines import gather_lines, parse_index_lines, parse_number_lines, split_lines
from ._numtext import format_floats, format_uints, join_columns
from ._parallel import map_in_order
from .atomic import write_atomically
from .mtl import (
    Materials,
    face_colors_of,
    materials_in_force,
    materials_of,
    mtl_bytes,
    read_libraries,
    runs,
)
from .source import (
    companion_path,
    file_error,
    lf_line_ends,
    read_source,
    report_skipped,
    show_path,
    show_token,
)


@dataclass
class ObjSoup:
    """What an OBJ file holds.

    Attributes:
        positions: ``(V, 3)`` float64, one row per ``v`` line.
        indices: ``(C,)`` int64 0-based vertex index of every face corner.
        offsets: ``(F + 1,)`` int64 face start offsets into ``indices``.
        face_lines: ``(F,)`` int64 1-based line number of every ``f`` line.
        skipped: ``(K,)`` int64 1-based lines whose first word is no OBJ
            statement (nor a comment), which the reader skips.
        first_skipped: the text of the first of them (empty when none).
        binary: the file holds a NUL byte (no text file does).
        materials: ``(1-based line, name)`` of every ``usemtl`` line.
        libraries: the names the ``mtllib`` lines give, in file order.
    """

    positions: np.ndarray
    indices: np.ndarray
    offsets: np.ndarray
    face_lines: np.ndarray
    skipped: np.ndarray
    first_skipped: bytes = b""
    binary: bool = False
    materials: list[tuple[int, str]] = field(default_factory=list)
    libraries: list[str] = field(default_factory=list)

    def materials_in_force(self) -> list[str | None]:
        """The ``usemtl`` material of each face (None before the first)."""
        return materials_in_force(self.materials, self.face_lines)


def read_obj(source: str | os.PathLike[str] | bytes, *, name: str | None = None) -> Mesh:
    """Load an OBJ file into a mesh.

    Args:
        source: a path, or the file contents as bytes.
        name: the file name to use in messages (default: the path, or ``<obj>``).

    Returns:
        The mesh; face ``i`` is the ``i``-th ``f`` line, vertex ``j`` the ``j``-th
        ``v`` line. Open boundaries get hole faces, unused vertices become
        point-spheres, inconsistently oriented components are re-oriented (see
        :func:`livemod.dlfl.from_polygons`). Lines whose first word is no OBJ
        statement are skipped, and said in ``mesh.notes`` and as a
        :class:`~livemod.dlfl.errors.DLFLSkippedLinesWarning`.

    Raises:
        FileFormatError: ``file:line: ...`` for a malformed number, an empty face,
            an index out of range; a file with no vertex that holds a line that
            is no OBJ statement (another format, or not text). A blank file, or
            one of comments and OBJ statements only, is an empty mesh.
        NonManifoldError: the faces do not form an orientable 2-manifold
            (``file:line: ...``, from :func:`livemod.dlfl.from_polygons`).
        OSError: the file cannot be read.
    """
    data, label = read_source(source, name, "<obj>")
    soup = parse_obj(data, label)
    if len(soup.indices) == 0:
        if len(soup.positions) == 0:
            _check_obj_text(soup, label)
        mesh = point_cloud(soup.positions)
    else:
        notes: list[str] = []
        mesh = from_polygons(
            soup.positions, soup.indices, soup.offsets, source=show_path(label),
            face_lines=soup.face_lines, vertex_base=1,  # errors name vertices as f lines do
            face_colors=_face_colors(soup, source, label, notes),
        )
        mesh.notes += notes
    if len(soup.skipped):
        report_skipped(mesh, label, soup.skipped.tolist(), soup.first_skipped)
    return mesh


def _face_colors(soup: ObjSoup, source: str | os.PathLike[str] | bytes, label: str,
                 notes: list[str]) -> np.ndarray | None:
    """The faces' colours from the libraries the file names, found beside it (a
    file given as bytes has no folder to find them in: its faces get none)."""
    if not soup.materials or not soup.libraries or isinstance(source, bytes):
        return None
    folder = os.path.dirname(os.path.abspath(os.fspath(source)))
    in_force = soup.materials_in_force()
    library = read_libraries(soup.libraries, folder, label, in_force, notes)
    return face_colors_of(in_force, library)


# every statement of the OBJ specification: a file of no ``v`` line passes when it
# uses one of these (an exported empty group, say), else it is not an OBJ file
_OBJ_KEYWORDS = frozenset(
    b"v vt vn vp f l p o g s mg usemtl mtllib cstype deg bmat step curv curv2 surf "
    b"parm trim hole scrv sp end con bevel c_interp d_interp lod shadow_obj trace_obj "
    b"ctech stech maplib usemap call csh".split())


def _check_obj_text(soup: ObjSoup, label: str) -> None:
    """Refuse a file without vertices unless it is blank, comments only, or OBJ
    statements only: a mesh file of another kind must not load as empty."""
    if soup.binary:
        raise file_error(label, None, "not an OBJ file: it holds binary data")
    if len(soup.skipped):
        word = soup.first_skipped.split(None, 1)[0]
        raise file_error(label, int(soup.skipped[0]), "not an OBJ file: no vertex, and the "
                         f"line starts with {show_token(word)}, not an OBJ keyword")


# a line's first word is looked up as the uint64 of its first bytes (the longer
# statements, shadow_obj and trace_obj, are looked up in Python)
_KEY_BYTES = 8
_BLANK_OR_HASH = np.zeros(256, dtype=bool)
_BLANK_OR_HASH[list(b" \t\n\r\v\f#")] = True


def _word_keys(words: list[bytes]) -> np.ndarray:
    """``(K,)`` sorted uint64 keys of ``words`` (each at most :data:`_KEY_BYTES`)."""
    padded = b"".join(w.ljust(_KEY_BYTES, b"\0") for w in words)
    return np.sort(np.frombuffer(padded, dtype="<u8"))


_OBJ_KEYWORD_KEYS = _word_keys([w for w in _OBJ_KEYWORDS if len(w) <= _KEY_BYTES])


def _not_understood(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, kinds: np.ndarray,
                    ) -> np.ndarray:
    """``(K,)`` int64 0-based lines whose first word is no OBJ statement, nor a
    comment: the lines the reader skips without knowing what they are.

    The lines of kind ``_IGNORED`` (``vn``, ``usemtl``, comments: a million in a
    large file) are looked up by their first word's key, whole-array; the few
    others (a word longer than a key, a line starting with a blank) in Python.
    """
    ignored = np.flatnonzero(kinds == _IGNORED)
    rows = buf[np.minimum(starts[ignored, None] + np.arange(_KEY_BYTES + 1), len(buf) - 1)]
    stop = _BLANK_OR_HASH[rows]
    length = np.where(stop.any(axis=1), stop.argmax(axis=1), _KEY_BYTES + 1)
    rows[np.arange(_KEY_BYTES + 1) >= length[:, None]] = 0
    keys = np.ascontiguousarray(rows[:, :_KEY_BYTES]).view("<u8").ravel()
    at = np.minimum(np.searchsorted(_OBJ_KEYWORD_KEYS, keys), len(_OBJ_KEYWORD_KEYS) - 1)
    known = (length == 0) | (length <= _KEY_BYTES) & (_OBJ_KEYWORD_KEYS[at] == keys)
    doubtful = np.sort(np.concatenate([ignored[~known], np.flatnonzero(kinds == _OTHER_SUSPECT)]))
    unknown = []
    for line in doubtful.tolist():
        words = _line_bytes(buf, starts, ends, line).split(b"#", 1)[0].split(None, 1)
        if words and words[0] not in _OBJ_KEYWORDS:
            unknown.append(line)
    return np.array(unknown, dtype=np.int64)


def parse_obj(data: bytes, label: str = "<obj>", *, fast: bool = True) -> ObjSoup:
    """Parse OBJ text into a polygon soup.

    Args:
        data: the file contents.
        label: the file name used in error messages.
        fast: use the vectorized paths (False parses every line in Python; the
            tests use it as the reference).

    Raises:
        FileFormatError: ``label:line: ...`` for malformed ``v`` or ``f`` lines
            and face indices out of range.
    """
    data = lf_line_ends(data.removeprefix(b"\xef\xbb\xbf"))  # a UTF-8 byte order mark
    if not data.endswith(b"\n"):
        data += b"\n"
    data = _join_continued(data)
    buf, starts, ends = split_lines(data)
    kinds = _classify(buf, starts, fast)
    parsed = _Parsed()
    for line in np.flatnonzero(kinds == _OTHER_SUSPECT).tolist():
        parsed.parse_line(_line_bytes(buf, starts, ends, line), line, label)
    _parse_vectorized(buf, starts, ends, kinds, parsed, label)
    if parsed.errors:
        raise parsed.errors[0][1]  # the first bad line of the file, as a reader would
    soup = parsed.soup(label)
    soup.materials = [(line + 1, rest.decode("utf-8", "replace"))
                      for line, rest in _statements(buf, starts, ends, kinds, b"usemtl")]
    soup.libraries = [name.decode("utf-8", "replace") for _, rest in
                      _statements(buf, starts, ends, kinds, b"mtllib") for name in rest.split()]
    skipped = _not_understood(buf, starts, ends, kinds)
    if len(skipped):
        soup.skipped = skipped + 1
        soup.first_skipped = _line_bytes(buf, starts, ends, int(skipped[0]))
    soup.binary = b"\0" in data
    return soup


def _statements(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, kinds: np.ndarray,
                word: bytes) -> list[tuple[int, bytes]]:
    """``(0-based line, the rest of the line)`` of every line that starts with
    ``word`` and a blank (comments cut off), found among the lines of kind
    ``_IGNORED`` in one numpy pass."""
    lines = np.flatnonzero(kinds == _IGNORED)
    n = len(word)
    head = buf[np.minimum(starts[lines, None] + np.arange(n + 1), len(buf) - 1)]
    hit = (head[:, :n] == np.frombuffer(word, np.uint8)).all(axis=1) & (
        (head[:, n] == 32) | (head[:, n] == 9))
    return [(line, _line_bytes(buf, starts, ends, line)[n:].split(b"#", 1)[0].strip())
            for line in lines[hit].tolist()]


def _join_continued(data: bytes) -> bytes:
    """``data`` with every line that ends in ``\\`` joined to the next one (the OBJ
    specification's line continuation; ``data`` ends with ``\\n``).

    The newlines taken out are put back as empty lines after the joined line, so
    the joined line keeps its first line's number and every later line its own.
    A file with no backslash at all (a single-byte search, a memchr) is not copied.
    """
    if b"\\" not in data or (b"\\\n" not in data and b"\\\r\n" not in data):
        return data
    pieces: list[bytes] = []
    held = 0
    for line in data.split(b"\n"):
        body = line[:-1] if line.endswith(b"\r") else line
        if body.endswith(b"\\"):
            pieces.append(body[:-1] + b" ")
            held += 1
        else:
            pieces.append(line + b"\n" * (held + 1))
            held = 0
    return b"".join(pieces)[:-1]  # the split's last, empty piece added one newline


_IGNORED, _VERTEX, _FACE, _OTHER_SUSPECT = range(4)


def _classify(buf: np.ndarray, starts: np.ndarray, fast: bool) -> np.ndarray:
    """``(L,)`` int8 kind of each line from its first two bytes.

    ``v``/``f`` followed by a blank are plain vertex/face lines; lines that
    start with a blank, or ``v``/``f`` followed by anything but a blank or a
    letter or digit (``v\\r``, ``f#``), need the Python parser to decide.
    """
    if len(starts) == 0:
        return np.zeros(0, dtype=np.int8)
    b0 = buf[starts]
    b1 = buf[np.minimum(starts + 1, len(buf) - 1)]
    blank1 = (b1 == 32) | (b1 == 9)
    word1 = (b1 == 95) | ((b1 | 32) >= 97) & ((b1 | 32) <= 122) | (b1 >= 48) & (b1 <= 57)
    keyword = (b0 == ord("v")) | (b0 == ord("f"))
    kinds = np.full(len(starts), _IGNORED, dtype=np.int8)
    kinds[(b0 == ord("v")) & blank1] = _VERTEX
    kinds[(b0 == ord("f")) & blank1] = _FACE
    suspect = (b0 == 32) | (b0 == 9) | (b0 == 11) | (b0 == 12) | keyword & ~blank1 & ~word1
    kinds[suspect] = _OTHER_SUSPECT
    if not fast:
        kinds[(kinds == _VERTEX) | (kinds == _FACE)] = _OTHER_SUSPECT
    return kinds


def _line_bytes(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, line: int) -> bytes:
    return buf[starts[line] : ends[line]].tobytes()


class _Parsed:
    """Vertex and face lines collected from the fast and the Python paths."""

    def __init__(self) -> None:
        self.vertex_blocks: list[tuple[np.ndarray, np.ndarray]] = []  # (lines, (n,3))
        self.face_blocks: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []  # lines, counts, raw
        self.py_vertices: dict[int, tuple[float, float, float]] = {}
        self.py_faces: dict[int, list[int]] = {}
        self.errors: list[tuple[int, DLFLError]] = []

    def parse_line(self, raw: bytes, line: int, label: str) -> None:
        """Parse line ``line`` (0-based) in Python; keep its error for later.

        Lines after the first bad one found so far are skipped: only an earlier
        error could still be reported (this keeps a garbage file quick to refuse).
        """
        if self.errors and line > self.errors[0][0]:
            return
        try:
            self.add(line, _parse_line(raw, line + 1, label))
        except DLFLError as error:
            self.errors = [min(self.errors + [(line, error)], key=lambda item: item[0])]

    def add(self, line: int, item: tuple[str, list[float] | list[int]] | None) -> None:
        if item is None:
            return
        kind, values = item
        if kind == "v":
            self.py_vertices[line] = (values[0], values[1], values[2])
        else:
            self.py_faces[line] = [int(v) for v in values]

    def soup(self, label: str) -> ObjSoup:
        v_lines, positions = self._vertices()
        f_lines, counts, raw = self._faces()
        offsets = np.zeros(len(f_lines) + 1, dtype=np.int64)
        np.cumsum(counts, out=offsets[1:])
        if len(raw) == 0 or (raw.min() > 0 and raw.max() <= len(v_lines)):
            indices = raw - 1  # the usual case: no relative or bad indices
        else:
            before = np.repeat(np.searchsorted(v_lines, f_lines), counts)
            indices = _resolve_indices(raw, before, len(v_lines), offsets, f_lines, label)
        return ObjSoup(positions, indices, offsets, f_lines + 1, np.zeros(0, np.int64))

    def _vertices(self) -> tuple[np.ndarray, np.ndarray]:
        py_lines = np.array(sorted(self.py_vertices), dtype=np.int64)
        py_pos = np.array([self.py_vertices[i] for i in py_lines.tolist()], dtype=np.float64)
        blocks = [*self.vertex_blocks, (py_lines, py_pos.reshape(-1, 3))]
        lines = np.concatenate([b[0] for b in blocks])
        positions = np.concatenate([b[1] for b in blocks])
        if len(py_lines) == 0:  # the fast blocks come in file order
            return lines, positions
        order = np.argsort(lines, kind="stable")
        return lines[order], positions[order]

    def _faces(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        py_lines = np.array(sorted(self.py_faces), dtype=np.int64)
        py_lists = [self.py_faces[i] for i in py_lines.tolist()]
        py_counts = np.array([len(f) for f in py_lists], dtype=np.int64)
        py_raw = np.array([i for f in py_lists for i in f], dtype=np.int64)
        blocks = [*self.face_blocks, (py_lines, py_counts, py_raw)]
        if len(py_lines) == 0:  # the fast blocks come in file order
            return tuple(np.concatenate([b[i] for b in blocks]) for i in range(3))  # type: ignore[return-value]
        return merge_face_blocks(blocks)


def merge_face_blocks(
    blocks: list[tuple[np.ndarray, np.ndarray, np.ndarray]],
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Interleave face blocks by line number (the readers parse faces in blocks).

    Args:
        blocks: per block ``(lines (k,), counts (k,), raw (sum of counts,))``:
            each face's line, its corner count and its corners' raw indices.

    Returns:
        The same three arrays over all blocks, faces in line order (stable).
    """
    lines = np.concatenate([b[0] for b in blocks])
    counts = np.concatenate([b[1] for b in blocks])
    raw = np.concatenate([b[2] for b in blocks])
    order = np.argsort(lines, kind="stable")
    src_start = np.concatenate([[0], np.cumsum(counts)[:-1]]).astype(np.int64)
    sorted_counts = counts[order]
    # corner k of sorted face j comes from src_start[order[j]] + k
    local = np.arange(int(sorted_counts.sum())) - np.repeat(
        np.cumsum(sorted_counts) - sorted_counts, sorted_counts
    )
    gather = np.repeat(src_start[order], sorted_counts) + local
    return lines[order], sorted_counts, raw[gather]


def _resolve_indices(
    raw: np.ndarray, before: np.ndarray, num_vertices: int, offsets: np.ndarray,
    f_lines: np.ndarray, label: str,
) -> np.ndarray:
    """0-based vertex indices from OBJ's 1-based and negative (relative) ones."""
    indices = np.where(raw > 0, raw - 1, before + raw)
    bad = (raw == 0) | (indices < 0) | (indices >= num_vertices)
    if bad.any():
        c = int(np.flatnonzero(bad)[0])
        line = int(f_lines[np.searchsorted(offsets, c, side="right") - 1]) + 1
        value = int(raw[c])
        if value == 0:
            raise file_error(label, line, "vertex index 0 (OBJ indices start at 1)")
        raise file_error(label, line, f"vertex index {value} is out of range: {int(before[c])} "
                         f"vertices are defined before this line, {num_vertices} in all")
    return indices


# lines parsed per numpy pass: big enough to amortise the calls, small enough
# that temporaries stay in the cache and reuse freed memory instead of mapping
# fresh pages (which is what dominated on a million-vertex file)
_LINES_PER_PASS = 1 << 16


def _passes(rows: np.ndarray) -> list[np.ndarray]:
    """``rows`` (line numbers, positions, ...) cut into views of ``_LINES_PER_PASS``."""
    return [rows[i : i + _LINES_PER_PASS] for i in range(0, len(rows), _LINES_PER_PASS)]


def _parse_vectorized(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray,
                      kinds: np.ndarray, parsed: _Parsed, label: str) -> None:
    """Parse the ``v`` and ``f`` lines pass by pass with numpy, the passes on a few
    threads (numpy releases the GIL in them); the lines a pass does not accept go
    to the Python parser, in file order."""
    passes = [(_vertex_lines_pass, part) for part in _passes(np.flatnonzero(kinds == _VERTEX))]
    passes += [(_face_lines_pass, part) for part in _passes(np.flatnonzero(kinds == _FACE))]
    results = map_in_order(lambda task: task[0](buf, starts, ends, task[1]), passes)
    for (kind, _), (block, rejected) in zip(passes, results, strict=True):
        blocks = parsed.vertex_blocks if kind is _vertex_lines_pass else parsed.face_blocks
        blocks.append(block)  # type: ignore[arg-type]
        for line in rejected.tolist():
            parsed.parse_line(_line_bytes(buf, starts, ends, line), line, label)


def _vertex_lines_pass(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, part: np.ndarray,
                       ) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """``((lines, (n, 3) positions), rejected lines)`` of the ``v`` lines ``part``."""
    block, block_starts = gather_lines(buf, starts, ends, part)
    block[block_starts] = 32  # blank the keyword
    values, accepted = parse_number_lines(block, block_starts, 3)
    return (part[accepted], values[accepted]), part[~accepted]


def _face_lines_pass(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, part: np.ndarray,
                     ) -> tuple[tuple[np.ndarray, ...], np.ndarray]:
    """``((lines, counts, raw indices), rejected lines)`` of the ``f`` lines ``part``."""
    block, block_starts = gather_lines(buf, starts, ends, part)
    block[block_starts] = 32
    values, counts, accepted = parse_index_lines(block, block_starts)
    keep = np.repeat(accepted, counts)
    return (part[accepted], counts[accepted], values[keep]), part[~accepted]


def _parse_line(raw: bytes, line: int, label: str) -> tuple[str, list[float] | list[int]] | None:
    """Reference parser for one line: ``("v", xyz)``, ``("f", raw indices)`` or None.

    Raises:
        DLFLError: ``label:line: ...`` for a malformed ``v`` or ``f`` line.
    """
    tokens = raw.split(b"#", 1)[0].split()
    if not tokens or tokens[0] not in (b"v", b"f"):
        return None
    if tokens[0] == b"v":
        numbers = b" ".join(tokens[1:]).replace(b",", b" ").split()
        if len(numbers) < 3:
            raise file_error(label, line, f"a v line needs 3 coordinates, got {len(numbers)}")
        return "v", [_float(t, line, label) for t in numbers[:3]]
    if len(tokens) == 1:
        raise file_error(label, line, "empty face (an f line with no vertex indices)")
    return "f", [_index(t, line, label) for t in tokens[1:]]


def _float(token: bytes, line: int, label: str) -> float:
    try:
        if b"_" in token:
            raise ValueError(token)
        value = float(token)
    except ValueError:
        raise file_error(label, line, f"bad number {show_token(token)}") from None
    if not np.isfinite(value):
        raise file_error(label, line, f"coordinate {show_token(token)} is not finite")
    return value


def _index(token: bytes, line: int, label: str) -> int:
    head = token.split(b"/", 1)[0]
    try:
        if b"_" in head or b"+" in head:
            raise ValueError(head)
        value = int(head)
    except ValueError:
        raise file_error(label, line, f"bad vertex index {show_token(token)}") from None
    if abs(value) >= 2**62:
        raise file_error(label, line, f"vertex index {show_token(head)} is out of range")
    return value



# ---------------------------------------------------------------------- writer


def write_obj(mesh: Mesh, path: str | os.PathLike[str]) -> None:
    """Write ``mesh`` as OBJ, atomically.

    ``v`` lines in vertex id order with coordinates that parse back to the same
    bits; one ``f`` line per face in face id order, 1-based, from each face's
    head corner. Hole faces are left out (they come back as boundaries) and so
    are point-sphere faces (their vertices come back as point-spheres). A mesh
    with face colours also gets ``<stem>.mtl`` beside the file (written first),
    one material per colour, named by ``mtllib`` and chosen by ``usemtl`` (see
    :mod:`.mtl`).

    Raises:
        OSError: a file cannot be written; an existing file is left intact.
    """
    name = os.fspath(path)
    library = companion_path(name, ".mtl")
    a = mesh_arrays(mesh)
    materials = None if a.face_colors is None else materials_of(a.face_colors)
    if materials is not None:
        write_atomically(library, mtl_bytes(materials))
    write_atomically(name, _obj_text(a, materials, os.path.basename(library)))


def obj_bytes(mesh: Mesh, mtl_name: str = "mesh.mtl") -> bytes:
    """The OBJ text of ``mesh`` (see :func:`write_obj`; ``mtl_name`` is the
    library its ``mtllib`` line names when the mesh has face colours)."""
    return b"".join(obj_pieces(mesh, mtl_name))


def obj_pieces(mesh: Mesh, mtl_name: str = "mesh.mtl") -> Iterator[bytes]:
    """The OBJ text of ``mesh`` in pieces of at most ``_LINES_PER_PASS`` lines
    (for :func:`write_obj`: a million-vertex file is never whole in memory).

    Precondition: the mesh is not changed while the pieces are consumed.
    """
    a = mesh_arrays(mesh)
    return _obj_text(a, None if a.face_colors is None else materials_of(a.face_colors),
                     mtl_name)


def _obj_text(a: MeshArrays, materials: Materials | None, mtl_name: str) -> Iterator[bytes]:
    sizes, vertices = a.surface_polygons()
    header = b"# livemod OBJ: %d vertices, %d faces\n" % (len(a.positions), len(sizes))
    if materials is None:
        faces = index_lines(vertices + 1, sizes, b"f")
    else:
        header += b"mtllib %s\n" % _one_line(mtl_name)
        faces = material_face_lines(vertices + 1, sizes, materials.names,
                                    materials.index[a.face_is_surface], b"f")
    return itertools.chain([header], vertex_lines(a.positions, b"v"), faces)


def _one_line(name: str) -> bytes:
    """``name`` for a line of its own: control characters (a newline in a file
    name would end the line) become ``_``."""
    return name.encode("utf-8", "replace").translate(CONTROLS_TO_UNDERSCORE)


CONTROLS_TO_UNDERSCORE = bytes.maketrans(bytes([*range(32), 127]), b"_" * 33)


def material_face_lines(values: np.ndarray, sizes: np.ndarray, names: list[str],
                        index: np.ndarray, keyword: bytes) -> Iterator[bytes]:
    """:func:`index_lines` with a ``usemtl`` line before every run of faces of one
    material (``names[index[i]]`` is face ``i``'s)."""
    offsets = offsets_of(sizes)
    for lo, hi in runs(index):
        yield b"usemtl %s\n" % _one_line(names[int(index[lo])])
        yield from index_lines(values[offsets[lo] : offsets[hi]], sizes[lo:hi], keyword)


def vertex_lines(positions: np.ndarray, keyword: bytes) -> Iterator[bytes]:
    """Lines ``keyword x y z`` (``x y z`` for an empty keyword) with coordinates
    that parse back to the same bits,
    ``_LINES_PER_PASS`` lines a piece (``(V, 3)`` float64 ``positions``), the
    pieces formatted a few ahead on other threads."""
    return map_in_order(lambda chunk: _vertex_pass(chunk, keyword), _passes(positions))


def _vertex_pass(positions: np.ndarray, keyword: bytes) -> bytes:
    fields = format_floats(positions.ravel()).reshape(len(positions), 3, -1)
    lead = [keyword + b" "] if keyword else []  # OFF's lines have no keyword
    return join_columns(len(positions), [
        *lead, fields[:, 0], b" ", fields[:, 1], b" ", fields[:, 2], b"\n",
    ])


def index_lines(values: np.ndarray, sizes: np.ndarray, keyword: bytes) -> Iterator[bytes]:
    """Lines ``keyword v0 v1 ...`` of non-negative integers, ``sizes[i]`` per line,
    ``_LINES_PER_PASS`` lines a piece (formatted a few ahead on other threads).

    Args:
        values: ``(C,)`` non-negative int64.
        sizes: ``(L,)`` int64 values per line (each >= 1), summing to ``C``.
        keyword: the line's first word.
    """
    offsets = offsets_of(sizes)
    bounds = [(i, min(i + _LINES_PER_PASS, len(sizes))) for i in range(0, len(sizes), _LINES_PER_PASS)]
    return map_in_order(
        lambda ij: _index_pass(values[offsets[ij[0]] : offsets[ij[1]]], sizes[ij[0] : ij[1]], keyword),
        bounds)


def _index_pass(values: np.ndarray, sizes: np.ndarray, keyword: bytes) -> bytes:
    digits = format_uints(values)
    kw = np.frombuffer(keyword, dtype=np.uint8)
    cells = np.zeros((len(values), len(kw) + 2 + digits.shape[1]), dtype=np.uint8)
    firsts = np.cumsum(sizes) - sizes
    cells[firsts, : len(kw)] = kw
    cells[:, len(kw)] = ord(" ")
    if not keyword:  # OFF's lines have none: no blank before the first value either
        cells[firsts, 0] = 0
    cells[:, len(kw) + 1 : -1] = digits
    cells[firsts + sizes - 1, -1] = ord("\n")
    flat = cells.ravel()
    return flat[flat != 0].tobytes()
