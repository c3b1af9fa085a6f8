"""OFF (Object File Format): polygons kept, read and written.

Layout::

    OFF
    V F E                 counts (E is not used; writers put 0)
    x y z                 V lines, vertex j on the j-th
    n i0 i1 ... [r g b a] F lines: a polygon of n 0-based vertex indices,
                          optionally followed by its colour

A face's colour is read when it is three or four numbers after the indices:
integers in ``[0, 255]`` or decimals in ``[0, 1]`` (Geomview's rule; alpha is
dropped). Anything else there (a colour-map index, a colour out of range) leaves
the face without a colour, as readers of the format do.

Comments run from ``#`` to the end of a line; blank lines are passed over.
The header word may be ``OFF``, ``COFF``, ``NOFF``, ``CNOFF`` or with ``ST``
(texture coordinates), all of which start their vertex lines with ``x y z``;
the counts may follow it on the same line. Vertex and face lines are parsed in
blocks with the OBJ reader's vectorized parsers (:mod:`._lines`); a line they
do not take goes through Python, which also words the ``file:line:`` errors.
"""

from __future__ import annotations

import itertools
import os
import re
from collections.abc import Iterator

import numpy as np

from ..arrays import mesh_arrays
from ..build import from_polygons
from ..colors import filled_colors
from ..mesh import Mesh
from ..soup import offsets_of
from ._colors import face_rgba
from ._lines import gather_lines, parse_index_lines, parse_number_lines, split_lines, token_starts
from .atomic import write_atomically
from .obj import index_lines, vertex_lines
from .source import file_error, lf_line_ends, read_source, report_skipped, show_path, show_token

_HEADER = re.compile(rb"(ST)?C?N?OFF")


def write_off(mesh: Mesh, path: str | os.PathLike[str], *, face_colors: object = None) -> None:
    """Write ``mesh`` as OFF, atomically.

    Every vertex in id order (point-spheres too, so they come back); one
    polygon per face that is neither a hole nor a point-sphere, from its head
    corner (holes come back as boundaries, as from OBJ).

    Args:
        mesh: the mesh.
        path: the target file.
        face_colors: optional ``(F, 3)`` or ``(F, 4)`` colours, one row per face
            of ``mesh_arrays(mesh)`` (see :func:`._colors.face_rgba`), written
            as four integers 0-255 after each polygon's indices; by default the
            mesh's own, if it has any (faces without one in the modelling colour).

    Raises:
        InvalidArgumentError: colours of the wrong shape or range.
        OSError: the file cannot be written; an existing file is left intact.
    """
    write_atomically(path, off_pieces(mesh, face_colors))


def off_bytes(mesh: Mesh, face_colors: object = None) -> bytes:
    """The OFF text of ``mesh`` (see :func:`write_off`)."""
    return b"".join(off_pieces(mesh, face_colors))


def off_pieces(mesh: Mesh, face_colors: object = None) -> Iterator[bytes]:
    """The OFF text of ``mesh`` in pieces of whole lines (see :func:`write_off`)."""
    a = mesh_arrays(mesh)
    if face_colors is None and a.face_colors is not None:
        face_colors = filled_colors(a.face_colors)
    rgba = face_rgba(face_colors, len(a.face_ids))
    sizes, vertices = a.surface_polygons()
    rows = [sizes[:, None]]
    if rgba is not None:
        rows.append(rgba[a.face_is_surface].astype(np.int64))
    # each line: n, its n indices, then the colour: one run of integers per face
    starts = np.cumsum(sizes) - sizes
    values = np.zeros(len(vertices) + len(sizes) * (1 + (4 if rgba is not None else 0)),
                      dtype=np.int64)
    width = sizes + 1 + (4 if rgba is not None else 0)
    line_starts = np.cumsum(width) - width
    values[line_starts] = sizes
    within = np.arange(len(vertices)) - np.repeat(starts, sizes)
    values[np.repeat(line_starts + 1, sizes) + within] = vertices
    if rgba is not None:
        values[(line_starts + 1 + sizes)[:, None] + np.arange(4)] = rows[1]
    header = b"OFF\n# livemod OFF\n%d %d 0\n" % (len(a.positions), len(sizes))
    return itertools.chain([header], vertex_lines(a.positions, b""),
                           index_lines(values, width, b""))


def read_off(source: str | os.PathLike[str] | bytes, *, name: str | None = None) -> Mesh:
    """Load an OFF file into a mesh, polygons kept.

    Returns:
        The mesh; vertex ``j`` is the ``j``-th vertex line, face ``i`` the
        ``i``-th face line, in the colour its line gives (see the module's
        doc). Open boundaries get hole faces, unused vertices
        become point-spheres (see :func:`livemod.dlfl.from_polygons`). Lines
        after the last face are skipped and reported (mesh notes and a
        :class:`~livemod.dlfl.errors.DLFLSkippedLinesWarning`).

    Raises:
        FileFormatError: ``file:line: ...`` for a missing header or counts, a
            bad number, a face line with fewer indices than it says, an index
            out of range, a file that ends before its counts.
        NonManifoldError: the faces do not form an orientable 2-manifold.
        OSError: the file cannot be read.
    """
    data, label = read_source(source, name, "<off>")
    text = lf_line_ends(data.removeprefix(b"\xef\xbb\xbf"))
    if not text.endswith(b"\n"):
        text += b"\n"
    buf, starts, ends = split_lines(text)
    content = _content_lines(buf, starts, ends)
    num_v, num_f, first = _counts(buf, starts, ends, content, label)
    if len(content) < first + num_v + num_f:
        last = int(content[-1]) + 1 if len(content) else 1
        raise file_error(label, last, f"the file ends after {len(content) - first} of the "
                         f"{num_v} vertex and {num_f} face lines its counts say")
    v_lines = content[first : first + num_v]
    f_lines = content[first + num_v : first + num_v + num_f]
    positions = _vertices(buf, starts, ends, v_lines, label)
    indices, offsets, colors = _faces(buf, starts, ends, f_lines, num_v, label)
    mesh = from_polygons(positions, indices, offsets, source=show_path(label),
                         face_lines=f_lines + 1, face_colors=colors) \
        if num_f else _cloud(positions)
    rest = content[first + num_v + num_f :]
    if len(rest):
        report_skipped(mesh, label, (rest + 1).tolist(), _line(buf, starts, ends, int(rest[0])))
    return mesh


def _cloud(positions: np.ndarray) -> Mesh:
    from ..build import point_cloud

    return point_cloud(positions)


def _line(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, line: int) -> bytes:
    return buf[starts[line] : ends[line]].tobytes()


def _content_lines(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> np.ndarray:
    """``(K,)`` int64 0-based lines holding something other than blanks and a comment."""
    tokens = token_starts(buf)
    first = np.searchsorted(tokens, starts)
    has = first < len(tokens)
    has[has] = tokens[first[has]] < ends[has]
    lines = np.flatnonzero(has)
    return lines[buf[tokens[first[lines]]] != ord("#")]


def _counts(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, content: np.ndarray,
            label: str) -> tuple[int, int, int]:
    """``(V, F, k)``: the counts, and the index in ``content`` of the first vertex line."""
    if len(content) == 0:
        raise file_error(label, 1, "not an OFF file: it holds no header ('OFF')")
    words = _line(buf, starts, ends, int(content[0])).split(b"#", 1)[0].split()
    if not _HEADER.fullmatch(words[0]):
        raise file_error(label, int(content[0]) + 1, "not an OFF file: the first word is "
                         f"{show_token(words[0])}, not 'OFF'")
    at, counts = (0, words[1:]) if len(words) > 1 else (1, None)
    if counts is None:
        if len(content) < 2:
            raise file_error(label, int(content[0]) + 1, "the file ends before its counts")
        counts = _line(buf, starts, ends, int(content[1])).split(b"#", 1)[0].split()
    line = int(content[at]) + 1
    if len(counts) < 2 or not all(c.isdigit() for c in counts[:3]):
        raise file_error(label, line, "the counts must be 'V F E' (whole numbers), got "
                         f"{show_token(b' '.join(counts))}")
    return int(counts[0]), int(counts[1]), at + 1


def _blank_led(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, lines: np.ndarray,
               ) -> tuple[np.ndarray, np.ndarray]:
    """Lines ``lines`` copied into one block as :mod:`._lines` wants it: each led
    by a blank (where OBJ's keyword was blanked), the last byte a newline."""
    block, block_starts = gather_lines(buf, starts, ends, lines)
    return np.insert(block, block_starts, np.uint8(32)), block_starts + np.arange(len(lines))


def _vertices(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, lines: np.ndarray,
              label: str) -> np.ndarray:
    """``(V, 3)`` float64 the first three numbers of each of ``lines``."""
    values, accepted = parse_number_lines(*_blank_led(buf, starts, ends, lines), 3)
    for k in np.flatnonzero(~accepted).tolist():
        line = int(lines[k])
        words = _line(buf, starts, ends, line).split(b"#", 1)[0].split()
        if len(words) < 3:
            raise file_error(label, line + 1, f"a vertex line needs 3 coordinates, got {len(words)}")
        for axis, word in enumerate(words[:3]):
            try:
                values[k, axis] = float(word) if b"_" not in word else float("nan")
            except ValueError:
                raise file_error(label, line + 1, f"bad number {show_token(word)}") from None
            if not np.isfinite(values[k, axis]):
                raise file_error(label, line + 1, f"{show_token(word)} is not a finite number")
    return values


def _faces(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, lines: np.ndarray,
           num_v: int, label: str) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """``(indices, offsets, colors)`` of the polygons on ``lines``: ``colors`` is
    ``(F, 3)`` float32 in ``[0, 1]`` with NaN rows for faces without a colour, or
    None when no face has one."""
    values, counts, accepted = parse_index_lines(*_blank_led(buf, starts, ends, lines),
                                                 slashes=False)
    first = np.cumsum(counts) - counts
    size = np.where(counts > 0, values[np.minimum(first, max(len(values) - 1, 0))], 0)
    accepted &= (size >= 1) & (counts >= size + 1)
    sizes = np.where(accepted, size, 0)
    colors = _integer_colors(values, counts, first, sizes, accepted)
    python = {k: _python_face(buf, starts, ends, int(lines[k]), label)
              for k in np.flatnonzero(~accepted).tolist()}
    for k, (face, color) in python.items():
        sizes[k] = len(face)
        colors[k] = color
    offsets = offsets_of(sizes)
    indices = np.empty(int(offsets[-1]), dtype=np.int64)
    taken = np.flatnonzero(accepted)
    local = np.arange(int(sizes[taken].sum())) - np.repeat(
        np.cumsum(sizes[taken]) - sizes[taken], sizes[taken])
    indices[np.repeat(offsets[taken], sizes[taken]) + local] = values[
        np.repeat(first[taken] + 1, sizes[taken]) + local]
    for k, (face, _) in python.items():
        indices[offsets[k] : offsets[k + 1]] = face
    bad = np.flatnonzero((indices < 0) | (indices >= num_v))
    if len(bad):
        k = int(np.searchsorted(offsets, bad[0], side="right")) - 1
        raise file_error(label, int(lines[k]) + 1, f"vertex index {int(indices[bad[0]])} is "
                         f"out of range (there are {num_v} vertices; OFF counts from 0)")
    return indices, offsets, None if np.isnan(colors[:, 0]).all() else colors


def _integer_colors(values: np.ndarray, counts: np.ndarray, first: np.ndarray,
                    sizes: np.ndarray, accepted: np.ndarray) -> np.ndarray:
    """``(F, 3)`` float32 colours of the accepted lines whose indices are followed
    by three or four integers in ``[0, 255]``; NaN rows for the others."""
    colors = np.full((len(counts), 3), np.nan, dtype=np.float32)
    extra = counts - sizes - 1
    has = np.flatnonzero(accepted & ((extra == 3) | (extra == 4)))
    rgb = values[(first[has] + 1 + sizes[has])[:, None] + np.arange(3)]
    fits = ((rgb >= 0) & (rgb <= 255)).all(axis=1)
    colors[has[fits]] = rgb[fits] / np.float32(255)
    return colors


def _extra_color(words: list[bytes]) -> tuple[float, float, float] | float:
    """The colour of the words after a face's indices (see the module's doc), or
    NaN when they are none."""
    if len(words) not in (3, 4):
        return np.nan
    try:
        numbers = [float(w) for w in words[:3]]
    except ValueError:
        return np.nan
    decimal = any(not w.lstrip(b"+-").isdigit() for w in words[:3])
    top = 1.0 if decimal else 255.0
    if not all(0.0 <= v <= top for v in numbers):
        return np.nan
    r, g, b = (v / top for v in numbers)
    return (r, g, b)


def _python_face(buf: np.ndarray, starts: np.ndarray, ends: np.ndarray, line: int,
                 label: str) -> tuple[list[int], tuple[float, float, float] | float]:
    """The polygon on ``line`` (0-based) and its colour (NaN for none), or the
    error that names the line."""
    words = _line(buf, starts, ends, line).split(b"#", 1)[0].split()
    try:
        numbers = [int(w) if b"_" not in w else int("x") for w in words]
    except ValueError:
        numbers = []
        for word in words:
            if not word.isdigit() and not (word[:1] == b"-" and word[1:].isdigit()):
                break
            numbers.append(int(word))
    if not numbers or numbers[0] < 1:
        shown = show_token(words[0]) if words else "nothing"
        raise file_error(label, line + 1, f"a face line starts with its corner count, got {shown}")
    if len(numbers) < numbers[0] + 1:
        raise file_error(label, line + 1, f"the face says {numbers[0]} corners but lists "
                         f"{len(numbers) - 1} whole numbers")
    face = numbers[1 : numbers[0] + 1]
    color = _extra_color(words[numbers[0] + 1 :])
    huge = [i for i in face if abs(i) >= 2**62]  # past int64: no vertex has such an index
    if huge:
        raise file_error(label, line + 1,
                         f"vertex index {show_token(str(huge[0]).encode())} is out of range")
    return face, color
