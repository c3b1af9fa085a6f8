"""STL: binary export of the drawn faces as triangle fans; binary and ASCII import.

STL is a triangle soup: every triangle repeats its corners' coordinates. The
reader welds corners with exactly equal coordinates into one vertex (in the
order they first appear), drops triangles that welding collapsed, and builds the
mesh with :func:`livemod.dlfl.from_polygons`, so a closed, consistently
oriented STL comes back as a closed manifold, and one with cracks as an open
mesh with hole faces.
"""

from __future__ import annotations

import functools
import itertools
import os
import warnings
from collections.abc import Callable

import numpy as np

from ..analysis import face_normals
from ..arrays import mesh_arrays
from ..build import from_polygons
from ..errors import DLFLRepairWarning
from ..mesh import Mesh
from ..soup import offsets_of
from ._float32 import check_float32_range
from ._lines import gather_lines, parse_number_lines, split_lines, token_starts
from .atomic import write_atomically
from .source import file_error, lf_line_ends, read_source, show_path, show_token

_TRIANGLE = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])


def write_stl(mesh: Mesh, path: str | os.PathLike[str]) -> None:
    """Write ``mesh`` as binary STL, atomically.

    Every face that is not a hole and has at least 3 corners becomes a fan of
    triangles from its head corner, each carrying the face's unit normal.
    2-gons and point-spheres have no area and are left out.

    Raises:
        GeometryError: a coordinate beyond float32's range (about 3.4e38), which
            the format cannot hold; nothing is written.
        OSError: the file cannot be written; an existing file is left intact.
    """
    data = stl_bytes(mesh)
    write_atomically(path, data)


def stl_bytes(mesh: Mesh) -> bytes:
    """The binary STL of ``mesh`` (see :func:`write_stl`)."""
    a = mesh_arrays(mesh)
    check_float32_range(a.positions, "STL")
    tri_corners, tri_face = a.fan_triangles()
    records = np.zeros(len(tri_face), dtype=_TRIANGLE)
    records["normal"] = face_normals(a)[tri_face]
    records["corners"] = a.positions[a.corner_vertex[tri_corners]]
    header = b"livemod binary STL".ljust(80, b" ")
    return header + np.uint32(len(records)).tobytes() + records.tobytes()


def read_stl(source: str | os.PathLike[str] | bytes, *, name: str | None = None) -> Mesh:
    """Load a binary or ASCII STL file into a mesh.

    A file whose size is exactly 84 bytes plus 50 per triangle its header
    counts is binary (even if its header starts with ``solid``, as some
    exporters write); otherwise a file starting with ``solid`` is ASCII. ASCII
    loops of more than three vertices become polygons. Facet normals are
    ignored: the orientation comes from the corner order, as the format says.

    Args:
        source: a path, or the file contents as bytes.
        name: the file name to use in messages (default: the path, or ``<stl>``).

    Returns:
        The mesh: vertex ``j`` is the ``j``-th distinct corner position, face
        ``i`` the ``i``-th triangle (or loop) welding left with three or more
        corners. Triangles that collapsed are reported in ``mesh.notes`` and as
        a :class:`DLFLRepairWarning`; open boundaries get hole faces (see
        :func:`livemod.dlfl.from_polygons`).

    Raises:
        DLFLError: a file that is neither kind, a truncated binary file, a
            malformed ASCII file (``file:line: ...``), a coordinate that is not
            finite, or triangles that do not form an orientable 2-manifold.
        OSError: the file cannot be read.
    """
    data, label = read_source(source, name, "<stl>")
    corners, offsets, facet_lines = parse_stl(data, label)
    if len(offsets) == 1:
        return Mesh()
    return _welded_mesh(corners, offsets, facet_lines, label)


def parse_stl(data: bytes, label: str = "<stl>") -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """The polygon soup of an STL file, before welding.

    Returns:
        ``(corners, offsets, facet_lines)``: ``(C, 3)`` float64 corner positions
        face by face, ``(F + 1,)`` int64 face start offsets into ``corners``, and
        the ``(F,)`` 1-based line of each ``facet`` (None for binary files).

    Raises:
        DLFLError: as :func:`read_stl` says, naming ``label``.
    """
    count = _binary_count(data)
    if count is not None and len(data) == 84 + 50 * count:
        triangles = np.frombuffer(data, _TRIANGLE, count, 84)
        corners = triangles["corners"].reshape(-1, 3).astype(np.float64)
        _check_finite(corners, label, lambda k: (None, f"triangle {k // 3}: "))
        return corners, np.arange(0, 3 * count + 1, 3, dtype=np.int64), None
    solid = data.lstrip()[:5].lower() == b"solid"
    # a NUL byte is binary data (every float32 0.0 and attribute word holds some):
    # a binary file under a 'solid' header read as ASCII would give no facet at all
    if solid and b"\0" not in data:
        return _AsciiStl(lf_line_ends(data), label).soup()  # lone \r: a line end
    why = ("it starts with 'solid' but holds binary data, so it is no ASCII STL either"
           if solid else "it does not start with 'solid', as ASCII STL does")
    if count == 0:
        raise file_error(label, None, "not an STL file: as binary STL its header counts 0 "
                         f"triangles, and the {len(data) - 84} bytes after the 84-byte header "
                         f"are not whole 50-byte triangles ({len(data)} bytes in all); and {why}")
    if count is not None:
        raise file_error(label, None, "not an STL file: as binary STL its header counts "
                         f"{count} triangles ({84 + 50 * count} bytes), but the file has "
                         f"{len(data)} bytes; and {why}")
    raise file_error(label, None, f"not an STL file: {len(data)} bytes, too short for binary "
                     f"STL, and {why}")


def _binary_count(data: bytes) -> int | None:
    """The triangle count of ``data`` read as binary STL: its header's, except that a
    header count of 0 followed by exactly ``k`` whole 50-byte triangles gives ``k``.

    Some exporters never fill in the count. Four zero bytes are never ASCII STL
    text, so this cannot take an ASCII file for binary; any other mismatch of
    size and count stays a mismatch (None: shorter than a header).
    """
    count = _header_count(data)
    if count == 0 and len(data) > 84 and (len(data) - 84) % 50 == 0:
        return (len(data) - 84) // 50
    return count


def _header_count(data: bytes) -> int | None:
    """The triangle count a binary header gives, or None for a file shorter than one
    (binary files are 84 bytes plus 50 per triangle)."""
    return int(np.frombuffer(data, "<u4", 1, 80)[0]) if len(data) >= 84 else None


def _check_finite(corners: np.ndarray, label: str,
                  where: Callable[[int], tuple[int | None, str]]) -> None:
    """Raise for the first corner with a NaN or infinite coordinate; ``where(k)``
    gives the line of corner ``k`` (None in a binary file) and what the message
    says before the problem (its triangle)."""
    bad = np.flatnonzero(~np.isfinite(corners).all(axis=1))
    if len(bad):
        line, what = where(int(bad[0]))
        raise file_error(label, line, f"{what}a vertex coordinate is not finite: "
                         f"{corners[bad[0]].tolist()}")


def _welded_mesh(corners: np.ndarray, offsets: np.ndarray, facet_lines: np.ndarray | None,
                 label: str) -> Mesh:
    """The mesh of an STL soup: equal positions welded, collapsed faces dropped."""
    positions, vertex_of_corner = weld_positions(corners)
    indices, offsets, kept = drop_collapsed(vertex_of_corner, offsets)
    positions, indices = _used_vertices_only(positions, indices)
    lines = None if facet_lines is None else facet_lines[kept]
    mesh = Mesh() if len(indices) == 0 else from_polygons(
        positions, indices, offsets, source=show_path(label), face_lines=lines)
    dropped = len(kept) - int(np.count_nonzero(kept))
    if dropped:
        note = (f"{show_path(label)}: {dropped} degenerate facet{'s' if dropped > 1 else ''} (two corners "
                f"at the same point) left out")
        mesh.notes.append(note)
        warnings.warn(note, DLFLRepairWarning, stacklevel=3)
    return mesh


def _used_vertices_only(positions: np.ndarray, indices: np.ndarray
                        ) -> tuple[np.ndarray, np.ndarray]:
    """``(positions, indices)`` without the vertices only dropped facets used
    (they would become point-spheres), the others keeping their order."""
    used = np.zeros(len(positions), dtype=bool)
    used[indices] = True
    if used.all():
        return positions, indices
    return positions[used], (np.cumsum(used) - 1)[indices]


def weld_positions(corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Merge corners whose coordinates are exactly equal (``-0.0`` equals ``0.0``).

    Args:
        corners: ``(C, 3)`` float64 positions.

    Returns:
        ``(positions, vertex_of_corner)``: ``(V, 3)`` float64 distinct positions
        in the order they first appear, and the ``(C,)`` int64 vertex of each corner.
    """
    bits = np.ascontiguousarray(corners + 0.0).view(np.uint64)  # + 0.0: -0.0 becomes 0.0
    order, starts = _sorted_groups(bits)
    group = np.cumsum(starts) - 1
    # each group lists its corners in file order, so its start is its first corner,
    # and numbering the first corners in file order numbers the vertices as they appear
    first_corner = order[starts]
    is_first = np.zeros(len(corners), dtype=bool)
    is_first[first_corner] = True
    rank = (np.cumsum(is_first) - 1)[first_corner]
    vertex_of_corner = np.empty(len(corners), dtype=np.int64)
    vertex_of_corner[order] = rank[group]
    positions = np.empty((len(first_corner), 3))
    positions[rank] = corners[first_corner] + 0.0
    return positions, vertex_of_corner


def _sorted_groups(bits: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """An order of the rows of ``bits`` (``(C, 3)`` uint64, C >= 1) that
    puts equal rows together, each group in file order, and the ``(C,)`` bool
    mask of where each group starts.

    Sorting values is several times faster in numpy than sorting indices, so the
    sort key is a 64-bit hash of the row with the row's index in its low bits.
    Different rows whose hashes agree in the high bits (rare: about one pair in
    four for a million distinct points) end up interleaved; those few runs are
    put right by :func:`_untangle`.
    """
    index_bits = max(1, (len(bits) - 1).bit_length())
    low = np.uint64((1 << index_bits) - 1)
    key = (_mix(bits) & ~low) | np.arange(len(bits), dtype=np.uint64)
    key.sort()
    order = (key & low).astype(np.int64)
    same_hash = (key[1:] & ~low) == (key[:-1] & ~low)
    differs = _rows_differ(bits, order)
    if np.any(same_hash & differs):
        order = _untangle(bits, order, same_hash, differs)
        differs = _rows_differ(bits, order)
    return order, np.concatenate([[True], differs])


def _untangle(bits: np.ndarray, order: np.ndarray, same_hash: np.ndarray,
              differs: np.ndarray) -> np.ndarray:
    """``order`` with each run of equal hashes that holds different rows sorted
    by row, then by index (``same_hash``, ``differs``: ``(C - 1,)`` bool of each
    neighbouring pair)."""
    run = np.concatenate([[0], np.cumsum(~same_hash)])
    tangled = np.zeros(run[-1] + 1, dtype=bool)
    tangled[run[1:][same_hash & differs]] = True
    at = np.flatnonzero(tangled[run])
    rows = order[at]
    by_row = np.lexsort((rows, bits[rows, 2], bits[rows, 1], bits[rows, 0], run[at]))
    untangled = order.copy()
    untangled[at] = rows[by_row]
    return untangled


def _mix(bits: np.ndarray) -> np.ndarray:
    """``(C,)`` uint64 hash of each row of ``bits`` (``(C, 3)`` uint64).

    Every step folds the high bits down before the next multiplication: a float
    read from float32 has 29 zero low bits, which a plain product keeps zero.
    """
    mixed = bits[:, 0].copy()
    with np.errstate(over="ignore"):
        for column, factor in ((1, 0xBF58476D1CE4E5B9), (2, 0x94D049BB133111EB)):
            mixed ^= mixed >> np.uint64(31)
            mixed *= np.uint64(factor)
            mixed ^= bits[:, column]
        mixed ^= mixed >> np.uint64(29)
        mixed *= np.uint64(0x9E3779B97F4A7C15)
        mixed ^= mixed >> np.uint64(32)
    return mixed


def _rows_differ(bits: np.ndarray, order: np.ndarray) -> np.ndarray:
    """``(C - 1,)`` bool: row ``order[k + 1]`` of ``bits`` differs from row ``order[k]``.

    Column by column, so no ``(C, 3)`` copy is made (fresh memory is slow here).
    """
    differs = np.zeros(len(order) - 1, dtype=bool)
    for column in range(bits.shape[1]):
        values = bits[:, column][order]
        differs |= values[1:] != values[:-1]
    return differs


def drop_collapsed(indices: np.ndarray, offsets: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Remove each corner equal to the next one in its face, then faces left
    with fewer than three corners.

    Args:
        indices: ``(C,)`` int64 vertex of every corner, face by face.
        offsets: ``(F + 1,)`` int64 face start offsets into ``indices``.

    Returns:
        ``(indices, offsets, kept)``: the new soup, and the ``(F,)`` bool mask
        of the faces kept.
    """
    sizes = np.diff(offsets)
    face = np.repeat(np.arange(len(sizes)), sizes)
    nxt = np.arange(len(indices)) + 1
    nxt[offsets[1:] - 1] = offsets[:-1]  # each face's last corner is followed by its first
    distinct = indices != indices[nxt]
    left = np.bincount(face[distinct], minlength=len(sizes))
    kept = left >= 3
    keep_corner = distinct & kept[face]
    new_offsets = np.concatenate([[0], np.cumsum(left[kept])]).astype(np.int64)
    return indices[keep_corner], new_offsets, kept


# the ASCII keywords the parser looks for, as word codes (0: any other word), and
# the code of the words that name a solid
_FACET, _NORMAL, _OUTER, _LOOP, _VERTEX, _ENDLOOP, _ENDFACET, _ENDSOLID, _SOLID, _NAME = range(1, 11)
_KEYWORDS = {b"facet": _FACET, b"normal": _NORMAL, b"outer": _OUTER, b"loop": _LOOP,
             b"vertex": _VERTEX, b"endloop": _ENDLOOP, b"endfacet": _ENDFACET,
             b"endsolid": _ENDSOLID, b"solid": _SOLID}


class _AsciiStl:
    """The words of an ASCII STL file and the positions of its keywords.

    Keywords are matched in any case: the format writes them in lower case,
    old exporters in capitals, others ``Facet Normal``, ``EndLoop``.

    Attributes:
        data: the file in lower case (``bytes.lower``: ASCII letters only, so
            every byte stays where it was); ``original`` as it was.
        words: ``data`` split at ASCII blanks, as ``bytes.split`` splits it.
        codes: ``(W,)`` int8 keyword code of each word (0 for other words).
        facet, outer, endloop, endfacet, vertex: ``(K,)`` int64 word index of
            each occurrence of that keyword.
    """

    def __init__(self, data: bytes, label: str) -> None:
        self.label, self.original, self.data = label, data, data.lower()
        self.words = self.data.split()
        get = _KEYWORDS.get
        self.codes = np.fromiter(map(get, self.words, itertools.repeat(0)), np.int8,
                                 len(self.words))
        self._forget_names()
        self.facet, self.outer, self.endloop, self.endfacet, self.vertex = (
            np.flatnonzero(self.codes == code)
            for code in (_FACET, _OUTER, _ENDLOOP, _ENDFACET, _VERTEX))

    def _forget_names(self) -> None:
        """Code the words that name a solid as names: they run from ``solid``
        (the first word) or ``endsolid`` to the end of its line, so ``solid facet``
        names a solid 'facet'. In a file on one line a name ends at ``facet
        normal`` or ``solid``. Names are a word or two: the loop is short."""
        heads = np.flatnonzero((self.codes == _SOLID) | (self.codes == _ENDSOLID)).tolist()
        for k in sorted({0, *heads}):
            line = self._line_index(np.array([k]))[0]
            j = k + 1
            while j < len(self.words) and not self._name_ends(j, line):
                self.codes[j] = _NAME
                j += 1

    def _name_ends(self, j: int, line: int) -> bool:
        """Whether word ``j`` is past the name on (0-based) line ``line``."""
        if self.codes[j] == _SOLID or self._line_index(np.array([j]))[0] != line:
            return True
        return bool(self.codes[j] == _FACET and j + 1 < len(self.words)
                    and self.codes[j + 1] == _NORMAL)

    def soup(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """See :func:`parse_stl`."""
        self._check_structure()
        self._check_strays()
        sizes = (self.endloop - self.outer - 2) // 4  # well formed now: 4 words a vertex
        corners = self._coordinates()
        _check_finite(corners, self.label,
                      lambda k: (int(self.line_of(self.vertex[k : k + 1])[0]), ""))
        offsets = offsets_of(sizes)
        return corners, offsets, self.line_of(self.facet)

    def _check_structure(self) -> None:
        """Raise, naming the first facet that is not ``facet normal NX NY NZ /
        outer loop / vertex X Y Z (three or more) / endloop / endfacet``."""
        bad = self._first_bad_facet()
        if bad is None:
            return
        if bad < len(self.facet):
            line = self.line_of(self.facet[bad : bad + 1])[0]
            what = f"facet {bad}"
        else:
            line = self.line_of(np.array([len(self.words) - 1]))[0]
            what = f"after facet {bad - 1} (the file may be cut short)"
        raise file_error(self.label, int(line), f"{what} is not 'facet normal NX NY NZ, outer "
                         "loop, vertex X Y Z (three or more), endloop, endfacet'")

    def _check_strays(self) -> None:
        """Raise, naming its line, for the first word outside every facet that is
        neither ``solid``, ``endsolid`` nor a solid's name: text that is no STL
        (the facets are well formed now)."""
        marks = np.zeros(len(self.words) + 1, dtype=np.int64)
        marks[self.facet] += 1
        marks[self.endfacet + 1] -= 1
        covered = np.cumsum(marks[:-1]) > 0
        covered |= (self.codes == _SOLID) | (self.codes == _ENDSOLID) | (self.codes == _NAME)
        stray = np.flatnonzero(~covered)
        if len(stray):
            k = int(stray[0])
            raise file_error(self.label, int(self.line_of(stray[:1])[0]),
                             f"{show_token(self._original_word(k))} is not part of a facet "
                             "(an ASCII STL file is 'solid NAME', facets, 'endsolid NAME')")

    def _original_word(self, k: int) -> bytes:
        """Word ``k`` as the file writes it (before the lowering)."""
        start = int(self._word_starts[k])
        return self.original[start : start + len(self.words[k])]

    def _first_bad_facet(self) -> int | None:
        """The index of the first malformed facet, or None when all are well formed.

        Keyword positions say it all: a facet is ``facet normal NX NY NZ`` (5 words
        up to ``outer``), ``outer loop``, 4 words per ``vertex X Y Z``, then
        ``endloop endfacet``, directly followed by the next ``facet`` (or by
        ``endsolid``). Keywords missing from the end show as unequal counts.
        """
        f, o, el, ef = self.facet, self.outer, self.endloop, self.endfacet
        n = min(len(f), len(o), len(el), len(ef))
        f, o, el, ef = f[:n], o[:n], el[:n], ef[:n]
        loop_of, vertex_ok, sizes = self._vertices_in_loops(o, el)
        after = np.append(f[1:], len(self.words))
        ok = ((o - f == 5) & (self._code_after(f) == _NORMAL) & (self._code_after(o) == _LOOP)
              & (sizes >= 3) & (el - o - 2 == 4 * sizes) & (ef - el == 1) & (ef < after)
              & ((after - ef == 1) | (self._code_after(ef) == _ENDSOLID)))
        bad = [int(k) for k in np.flatnonzero(~ok)[:1]]
        bad += [max(int(loop_of[k]), 0) for k in np.flatnonzero(~vertex_ok)[:1]]
        if max(len(self.facet), len(self.outer), len(self.endloop), len(self.endfacet)) > n:
            bad.append(n)
        return min(bad) if bad else None

    def _vertices_in_loops(self, outer: np.ndarray, endloop: np.ndarray
                           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(loop_of, ok, sizes)``: the loop each ``vertex`` word follows (-1 before
        any), whether it sits inside that loop at a 4-word step, and how many do,
        per loop (``outer``/``endloop``: ``(n,)`` word indices of complete loops)."""
        n = len(outer)
        loop_of = np.searchsorted(self.outer, self.vertex) - 1
        ok = (loop_of >= 0) & (loop_of < n)
        step = self.vertex[ok] - outer[loop_of[ok]] - 2
        ok[ok] = (self.vertex[ok] < endloop[loop_of[ok]]) & (step % 4 == 0)
        return loop_of, ok, np.bincount(loop_of[ok], minlength=n)[:n]

    def _code_after(self, at: np.ndarray) -> np.ndarray:
        """``(K,)`` keyword code of the word after each of ``at`` (0 past the end)."""
        codes = np.append(self.codes, np.int8(0))
        return codes[at + 1]

    def line_of(self, word_index: np.ndarray) -> np.ndarray:
        """``(K,)`` 1-based line of each given word."""
        return self._line_index(word_index) + 1

    def _line_index(self, word_index: np.ndarray) -> np.ndarray:
        """``(K,)`` 0-based line of each given word (an index into :attr:`_text_lines`)."""
        return np.searchsorted(self._text_lines[2], self._word_starts[word_index])

    @functools.cached_property
    def _text_lines(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """:func:`._lines.split_lines` of the file (a last newline added if missing)."""
        return split_lines(self.data if self.data.endswith(b"\n") else self.data + b"\n")

    @functools.cached_property
    def _word_starts(self) -> np.ndarray:
        """``(W,)`` int64 byte offset of every word."""
        return token_starts(np.frombuffer(self.data, dtype=np.uint8))

    def _coordinates(self) -> np.ndarray:
        """``(C, 3)`` float64 coordinates following each ``vertex``.

        Lines holding just ``vertex X Y Z`` go through the OBJ reader's
        vectorized number parser; any other vertex is read word by word.
        """
        values, accepted = self._vertex_lines()
        for k in np.flatnonzero(~accepted).tolist():
            values[k] = [self._number(self.vertex[k] + 1 + axis) for axis in range(3)]
        return values

    def _vertex_lines(self) -> tuple[np.ndarray, np.ndarray]:
        """``(values, accepted)`` as :func:`._lines.parse_number_lines` gives them,
        for the line of every ``vertex`` word (none accepted where two share a line)."""
        buf, starts, ends = self._text_lines
        at = self._word_starts[self.vertex]
        lines = self._line_index(self.vertex)
        if np.any(np.diff(lines) <= 0):
            return np.zeros((len(at), 3)), np.zeros(len(at), dtype=bool)
        block, block_starts = gather_lines(buf, starts, ends, lines)
        keyword = block_starts + (at - starts[lines])
        block[keyword[:, None] + np.arange(len(b"vertex"))] = 32  # blank the keyword
        return parse_number_lines(block, block_starts, 3)

    def _number(self, k: int) -> float:
        """Word ``k`` as a float, or a ``file:line: bad number`` error."""
        word = self._original_word(k) if k < len(self.words) else b""
        try:
            if b"_" in word:  # float() takes '1_0' as 10; the OBJ reader refuses it too
                raise ValueError(word)
            return float(word)
        except ValueError:
            line = self.line_of(np.array([min(k, len(self.words) - 1)]))[0]
            raise file_error(self.label, int(line), f"bad number {show_token(word)}") from None
