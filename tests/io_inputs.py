"""Valid mesh files of every format the readers take, written line by line in the
forms that send a line down each of a reader's paths, and mutations of them.

Shared by the boundary tests (tests/test_io_boundaries.py), the adversarial tests
(tests/test_io_adversarial.py) and the long fuzz run (fuzz/fuzz_readers.py).
Every generator writes coordinates as ``repr`` does, so each form reads back to
the same float64 bits: a reader must return the generating mesh exactly, on
whatever path a line took.
"""

from __future__ import annotations

import random
import re
import struct
import warnings
from collections.abc import Callable

import numpy as np

from livemod.dlfl import DLFLRepairWarning, Mesh, from_polygons, mesh_arrays
from livemod.dlfl.io import read_dlfl, read_obj, read_off, read_ply, read_stl
from livemod.dlfl.io.dlflfile import dlfl_bytes
from livemod.dlfl.io.off import off_bytes

Rng = random.Random


def bumpy_grid(rows: int, cols: int, seed: int = 0) -> Mesh:
    """An open ``rows`` x ``cols`` quad grid with coordinates of every written
    form: negative, fractional, long, integral (rows, cols >= 1)."""
    rng = np.random.default_rng(seed)
    i, j = np.meshgrid(np.arange(rows + 1), np.arange(cols + 1), indexing="ij")
    height = rng.choice([0.0, 1.0, -2.5, 0.1, 1 / 3, -7e-3, 123456.789], size=i.shape)
    positions = np.stack([i - 0.5 * rows, j * 0.25, height], axis=-1).reshape(-1, 3)
    a = i[:-1, :-1] * (cols + 1) + j[:-1, :-1]
    quads = np.stack([a, a + cols + 1, a + cols + 2, a + 1], axis=-1).reshape(-1, 4)
    return from_polygons(positions, quads)


def number(value: float) -> bytes:
    return repr(float(value)).encode()


# Forms of a coordinate triple or an index list. Each keeps every value, so the
# file still describes the same mesh; the ones marked slow are refused by a
# plain path and go down the general or the Python path.
def _plus(word: bytes) -> bytes:
    return word if word.startswith(b"-") else b"+" + word


def _exponent(word: bytes) -> bytes:
    return word if b"e" in word else word + b"e0"


NUMBER_FORMS: list[Callable[[list[bytes]], bytes]] = [
    lambda w: b" ".join(w),  # plain
    lambda w: b" ".join(w) + b" # a comment",  # slow: a comment after the data
    lambda w: b" ".join(map(_plus, w)),  # slow: plus signs
    lambda w: b" ".join(map(_exponent, w)),  # slow: exponents
    lambda w: b" ".join(w) + b" 0.5 0.25 1",  # slow: vertex colours
    lambda w: b"\t".join(w),  # slow: tabs
    lambda w: b", ".join(w),  # commas, as TopMod writes
]


def numbers_line(keyword: bytes, values: np.ndarray, rng: Rng, slow: float) -> bytes:
    """``keyword`` and ``values`` in a plain form, or with odds ``slow`` another."""
    words = [number(v) for v in values]
    form = NUMBER_FORMS[0] if rng.random() >= slow else rng.choice(NUMBER_FORMS[1:])
    return keyword + b" " + form(words)


def _index_words(indices: list[int], rng: Rng, slow: float, corners: bool) -> bytes:
    words = [b"%d" % i for i in indices]
    if rng.random() >= slow:
        return b" ".join(words)
    kind = rng.randrange(3 if corners else 2)
    if kind == 0:
        return b"\t".join(words)
    if kind == 1:
        return b" ".join(words) + b" # a comment"
    return b" ".join(w + rng.choice([b"/1", b"//1", b"/1/1"]) for w in words)


def _surface(mesh: Mesh) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    a = mesh_arrays(mesh)
    sizes, vertices = a.surface_polygons()
    offsets = np.concatenate([[0], np.cumsum(sizes)])
    return a.positions, vertices, offsets


def obj_text(mesh: Mesh, rng: Rng, slow: float = 0.5, newline: bytes = b"\n") -> bytes:
    """OBJ of ``mesh`` with odds ``slow`` of a slow form per line (and some faces
    with relative indices)."""
    positions, vertices, offsets = _surface(mesh)
    lines = [b"# bumpy"] + [numbers_line(b"v", p, rng, slow) for p in positions]
    count = len(positions)
    for f in range(len(offsets) - 1):
        face = (vertices[offsets[f] : offsets[f + 1]] + 1).tolist()
        if rng.random() < slow / 4:
            face = [i - count - 1 for i in face]  # relative: -1 is the last v line
        lines.append(b"f " + _index_words(face, rng, slow, corners=True))
    return newline.join(lines) + newline


def dlfl_text(mesh: Mesh, rng: Rng, slow: float = 0.5, newline: bytes = b"\n") -> bytes:
    """livemod's ``.dlfl`` of ``mesh`` with its lines rewritten, odds ``slow``
    each, into a form the numpy passes refuse."""
    positions = mesh_arrays(mesh).positions
    out: list[bytes] = []
    v = 0
    for line in dlfl_bytes(mesh, "bumpy").split(b"\n")[:-1]:
        if line.startswith(b"v "):
            line = numbers_line(b"v", positions[v], rng, slow)
            v += 1
        elif line.startswith((b"f ", b"e ")) and rng.random() < slow:
            words = line.split()
            line = words[0] + rng.choice([b"\t", b"  "]) + b" ".join(words[1:])
        elif line.startswith(b"fv ") and rng.random() < slow:
            line = rng.choice([b"fv\t", b"fv  "]) + line[3:]
        out.append(line)
    return newline.join(out) + newline


KEYWORD_CASES: list[Callable[[bytes], bytes]] = [bytes.lower, bytes.upper, bytes.title]


def stl_ascii_text(mesh: Mesh, rng: Rng, slow: float = 0.5, case: int | None = None) -> bytes:
    """ASCII STL of ``mesh``'s faces (as loops, any size), keywords in lower case,
    capitals or title case (``Facet Normal``) as exporters write them."""
    positions, vertices, offsets = _surface(mesh)
    cased = KEYWORD_CASES[case] if case is not None else (lambda w: rng.choice(KEYWORD_CASES)(w))
    lines = [cased(b"solid") + b" bumpy"]
    for f in range(len(offsets) - 1):
        lines += [b" " + cased(b"facet") + b" " + cased(b"normal") + b" 0 0 1",
                  b"  " + cased(b"outer") + b" " + cased(b"loop")]
        for vertex in vertices[offsets[f] : offsets[f + 1]]:
            words = [number(v) for v in positions[vertex]]
            if rng.random() < slow:  # the forms STL has: signs, exponents, tabs
                words = [rng.choice([_plus, _exponent])(w) for w in words]
            blank = b"\t" if rng.random() < slow / 2 else b" "
            lines.append(b"   " + cased(b"vertex") + blank + blank.join(words))
        lines += [b"  " + cased(b"endloop"), b" " + cased(b"endfacet")]
    lines.append(cased(b"endsolid") + b" bumpy")
    return b"\n".join(lines) + b"\n"


def ply_ascii_text(mesh: Mesh, rng: Rng, slow: float = 0.5) -> bytes:
    """ASCII PLY of ``mesh``, one row a line, some rows in slower forms."""
    positions, vertices, offsets = _surface(mesh)
    header = [b"ply", b"format ascii 1.0", b"element vertex %d" % len(positions),
              b"property double x", b"property double y", b"property double z",
              b"element face %d" % (len(offsets) - 1),
              b"property list uchar int vertex_indices", b"end_header"]
    rows = []
    for p in positions:
        words = [number(v) for v in p]
        if rng.random() < slow:
            words = [rng.choice([_plus, _exponent])(w) for w in words]
        rows.append(rng.choice([b" ", b"\t"]).join(words) if rng.random() < slow
                    else b" ".join(words))
    for f in range(len(offsets) - 1):
        face = vertices[offsets[f] : offsets[f + 1]].tolist()
        words = [b"%d" % len(face)] + [b"%d" % i for i in face]
        rows.append((b"\t" if rng.random() < slow else b" ").join(words))
    return b"\n".join(header + rows) + b"\n"


def ply_binary_bytes(mesh: Mesh, order: str = "<") -> bytes:
    """Binary PLY of ``mesh`` in byte order ``order`` (``<`` or ``>``), float
    coordinates and a ``uchar``/``int`` index list."""
    positions, vertices, offsets = _surface(mesh)
    name = "binary_little_endian" if order == "<" else "binary_big_endian"
    header = (f"ply\nformat {name} 1.0\nelement vertex {len(positions)}\n"
              "property double x\nproperty double y\nproperty double z\n"
              f"element face {len(offsets) - 1}\nproperty list uchar int vertex_indices\n"
              "end_header\n").encode()
    body = positions.astype(order + "f8").tobytes()
    for f in range(len(offsets) - 1):
        face = vertices[offsets[f] : offsets[f + 1]]
        body += struct.pack("B", len(face)) + face.astype(order + "i4").tobytes()
    return header + body


def stl_binary_bytes(mesh: Mesh) -> bytes:
    from livemod.dlfl.io.stl import stl_bytes

    return stl_bytes(mesh)


# name -> (make valid bytes from a mesh and a Random, the reader)
FORMATS: dict[str, tuple[Callable[[Mesh, Rng], bytes], Callable[[bytes], Mesh]]] = {
    "obj": (lambda m, r: obj_text(m, r), read_obj),
    "obj-crlf": (lambda m, r: obj_text(m, r, newline=b"\r\n"), read_obj),
    "dlfl": (lambda m, r: dlfl_text(m, r), read_dlfl),
    "dlfl-crlf": (lambda m, r: dlfl_text(m, r, newline=b"\r\n"), read_dlfl),
    "stl-ascii": (lambda m, r: stl_ascii_text(m, r), read_stl),
    "stl-binary": (lambda m, r: stl_binary_bytes(m), read_stl),
    "ply-ascii": (lambda m, r: ply_ascii_text(m, r), read_ply),
    "ply-binary-le": (lambda m, r: ply_binary_bytes(m, "<"), read_ply),
    "ply-binary-be": (lambda m, r: ply_binary_bytes(m, ">"), read_ply),
    "off": (lambda m, r: off_bytes(m), read_off),
}


def mutate(data: bytes, rng: Rng, edits: int) -> bytes:
    """``data`` with ``edits`` random edits: a byte replaced, inserted or deleted,
    a span duplicated or cut, or a digit run stretched past 300 digits."""
    buf = bytearray(data)
    for _ in range(edits):
        if not buf:
            break
        i = rng.randrange(len(buf))
        kind = rng.randrange(6)
        if kind == 0:
            buf[i] = rng.choice(b"0123456789-+.eE/#\n\r\t ,[]vfx\0\xff")
        elif kind == 1:
            buf.insert(i, rng.randrange(256))
        elif kind == 2:
            del buf[i]
        elif kind == 3:
            buf[i:i] = buf[i : i + rng.randrange(1, 200)]
        elif kind == 4:
            del buf[i:]
        else:
            buf[i:i] = b"9" * rng.choice([19, 23, 309, 400])
    return bytes(buf)


def quiet_read(reader: Callable[[bytes], Mesh], data: bytes) -> Mesh:
    """``reader(data)`` with the repair and skipped-line warnings silenced."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DLFLRepairWarning)
        warnings.simplefilter("ignore", UserWarning)
        return reader(data)


# -- the unit cube of tests.meshes as OBJ text, and lone CR line ends

UNIT_CUBE_OBJ = (b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                 b"f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n")


def lone_cr_after_line(data: bytes, line: int) -> bytes:
    """``data`` with the ``\\n`` that ends 1-based line ``line`` made a lone ``\\r``."""
    at = [m.start() for m in re.finditer(b"\n", data)][line - 1]
    return data[:at] + b"\r" + data[at + 1 :]
