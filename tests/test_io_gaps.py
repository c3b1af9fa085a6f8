"""Regression tests for the file-format gaps the I/O review left (session 22):
binary STL with a header count of 0, and a lone ``\\r`` line end in a mostly-LF file."""

from __future__ import annotations

import re

import numpy as np
import pytest

from livemod.dlfl import DLFLError, validate
from livemod.dlfl.io import read_dlfl, read_obj, read_ply, read_stl
from livemod.dlfl.io.dlflfile import dlfl_bytes
from livemod.dlfl.io.obj import parse_obj
from livemod.dlfl.io.ply import ply_bytes
from livemod.dlfl.io.source import lf_line_ends
from livemod.dlfl.io.stl import stl_bytes
from livemod.dlfl.shapes import cube
from tests.meshes import torus_polygons

CUBE_V = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
CUBE_F = b"f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n"
CUBE_OBJ = CUBE_V + CUBE_F


def _counts(mesh):
    return mesh.num_vertices, mesh.num_edges, mesh.num_faces


def _lone_cr_after_line(data: bytes, line: int) -> bytes:
    """``data`` with the ``\\n`` that ends 1-based line ``line`` made a lone ``\\r``."""
    at = [m.start() for m in re.finditer(b"\n", data)][line - 1]
    return data[:at] + b"\r" + data[at + 1 :]


# ------------------------------------------------------------ STL header count 0


def _zero_count(data: bytes) -> bytes:
    return data[:80] + b"\0\0\0\0" + data[84:]


def test_binary_stl_with_a_zero_count_reads_the_triangles_its_size_shows():
    original = stl_bytes(cube())
    assert original[80:84] != b"\0\0\0\0"
    mesh = read_stl(_zero_count(original))
    validate(mesh)
    assert _counts(mesh) == _counts(read_stl(original)) == (8, 18, 12)
    np.testing.assert_array_equal(mesh.positions_view(), read_stl(original).positions_view())


def test_binary_stl_with_a_zero_count_under_a_solid_header_reads_too():
    data = _zero_count(stl_bytes(cube()))
    data = b"solid exported".ljust(80, b" ") + data[80:]
    assert _counts(read_stl(data)) == (8, 18, 12)


def test_binary_stl_with_a_zero_count_and_no_triangles_is_empty():
    assert _counts(read_stl(_zero_count(stl_bytes(cube()))[:84])) == (0, 0, 0)


@pytest.mark.parametrize("extra", [1, 7, 49])
def test_binary_stl_with_a_zero_count_and_part_of_a_triangle_is_refused(extra):
    data = _zero_count(stl_bytes(cube()))[: 84 + 50 + extra]
    message = (f"<stl>: not an STL file: as binary STL its header counts 0 triangles, and the "
               f"{50 + extra} bytes after the 84-byte header are not whole 50-byte triangles "
               f"({134 + extra} bytes in all); and it does not start with 'solid'")
    with pytest.raises(DLFLError, match=re.escape(message)):
        read_stl(data)


def test_binary_stl_with_a_nonzero_count_that_disagrees_stays_refused():
    data = stl_bytes(cube())[:-50]  # the header still counts 12
    with pytest.raises(DLFLError, match=re.escape(
            f"its header counts 12 triangles (684 bytes), but the file has {len(data)} bytes")):
        read_stl(data)


# ------------------------------------------------------------ lone CR line ends


@pytest.mark.parametrize(("data", "expected"), [
    (b"a\nb\rc\n", b"a\nb\nc\n"),
    (b"a\r\nb\rc\r\n", b"a\r\nb\nc\r\n"),
    (b"a\r\r\nb", b"a\n\r\nb"),
    (b"a\nb\r", b"a\nb\n"),
    (b"a\rb\r", b"a\nb\n"),
    (b"a\nb\r\n", b"a\nb\r\n"),
])
def test_lf_line_ends_gives_universal_newlines(data, expected):
    fixed = lf_line_ends(data)
    assert fixed == expected
    # the same lines as Python's universal newlines (a CRLF's \r stays, as a blank)
    assert [line.rstrip(b"\r") for line in fixed.split(b"\n")][: len(data.splitlines())] \
        == data.splitlines()


def test_lf_line_ends_leaves_lf_and_crlf_files_as_they_are():
    for data in (CUBE_OBJ, CUBE_OBJ.replace(b"\n", b"\r\n")):
        assert lf_line_ends(data) is data


def test_lf_line_ends_finds_a_lone_cr_in_a_large_file():
    # past the block size of the threaded search
    data = CUBE_OBJ.replace(b"\n", b"\r\n") * 20000
    at = len(data) // 2 + 1
    at = data.index(b"\r\n", at)
    fixed = lf_line_ends(data[:at] + b"\r" + data[at + 2 :])
    assert fixed == data[:at] + b"\n" + data[at + 2 :]


@pytest.mark.parametrize("fast", [True, False])
@pytest.mark.parametrize("line", [2, 8, 9, 13])  # after v, the last v, an f, the last but one f
def test_obj_lone_cr_ends_a_line(fast, line):
    data = _lone_cr_after_line(CUBE_OBJ, line)
    soup = parse_obj(data, fast=fast)
    reference = parse_obj(CUBE_OBJ, fast=fast)
    np.testing.assert_array_equal(soup.positions, reference.positions)
    np.testing.assert_array_equal(soup.indices, reference.indices)
    mesh = read_obj(data)
    validate(mesh)
    assert _counts(mesh) == (8, 12, 6)


def test_obj_lone_cr_counts_in_line_numbers():
    data = _lone_cr_after_line(CUBE_OBJ, 2).replace(b"f 2 3 7 6", b"f 2 3 7 x")
    with pytest.raises(DLFLError, match=r"^<obj>:12: bad vertex index 'x'"):
        read_obj(data)


def test_obj_lone_cr_ends_a_continued_line():
    data = b"v 0 0 0\nv 1 0 0\rv 0 1 0\nf 1 \\\r2 3\n"
    mesh = read_obj(data)
    assert _counts(mesh) == (3, 3, 2)


@pytest.mark.parametrize("key", [b"v ", b"fv ", b"e ", b"f "])
def test_dlfl_lone_cr_ends_a_line(key):
    data = dlfl_bytes(cube())
    lines = data.split(b"\n")
    line = next(i for i, text in enumerate(lines, 1) if text.startswith(key))
    mesh = read_dlfl(_lone_cr_after_line(data, line))
    validate(mesh)
    assert _counts(mesh) == (8, 12, 6)
    np.testing.assert_array_equal(mesh.positions_view(), cube().positions_view())


def test_dlfl_lone_cr_counts_in_line_numbers():
    data = dlfl_bytes(cube())
    lines = data.split(b"\n")
    last_v = max(i for i, text in enumerate(lines, 1) if text.startswith(b"v "))
    broken = _lone_cr_after_line(data, 4).replace(lines[last_v - 1], b"v 1 x 1")
    with pytest.raises(DLFLError, match=rf"^<dlfl>:{last_v}: "):
        read_dlfl(broken)


ASCII_STL = (b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
             b"vertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
             b"vertex 1 0 0\nvertex 1 1 0\nvertex x 1 0\nendloop\nendfacet\nendsolid t\n")


def test_ascii_stl_lone_cr_counts_in_line_numbers():
    with pytest.raises(DLFLError, match=r"^<stl>:13: bad number 'x'"):
        read_stl(ASCII_STL)
    with pytest.raises(DLFLError, match=r"^<stl>:13: bad number 'x'"):
        read_stl(_lone_cr_after_line(ASCII_STL, 8))


def test_ascii_stl_lone_cr_reads_the_same_mesh():
    data = ASCII_STL.replace(b"vertex x", b"vertex 0")
    mesh = read_stl(_lone_cr_after_line(_lone_cr_after_line(data, 1), 8))
    assert _counts(mesh) == _counts(read_stl(data)) == (4, 5, 3)


@pytest.mark.parametrize("line", [1, 2, 4, 9])  # after ply, format, element, end_header-1
def test_ply_header_lone_cr_ends_a_line(line):
    data = ply_bytes(cube())
    assert data.split(b"\n")[line - 1] != b"end_header"
    mesh = read_ply(_lone_cr_after_line(data, line))
    validate(mesh)
    assert _counts(mesh) == (8, 12, 6)
    np.testing.assert_array_equal(mesh.positions_view(), cube().positions_view())


def test_ply_header_lone_cr_after_end_header_starts_the_body():
    data = ply_bytes(cube())
    end = data.index(b"end_header\n") + len(b"end_header")
    mesh = read_ply(data[:end] + b"\r" + data[end + 1 :])
    assert _counts(mesh) == (8, 12, 6)


def test_ply_ascii_body_lone_cr_ends_a_row_on_the_line_path():
    # a body above the line path's minimum; it was already right (the token
    # path takes over where lines merge): kept so that it stays right
    positions, quads = torus_polygons(120, 120)
    rows = [" ".join(repr(x) for x in p) for p in positions.tolist()]
    rows += [" ".join(map(str, [4, *quad])) for quad in quads.tolist()]
    header = (f"ply\nformat ascii 1.0\nelement vertex {len(positions)}\nproperty double x\n"
              f"property double y\nproperty double z\nelement face {len(quads)}\n"
              "property list uchar int vertex_indices\nend_header\n")
    data = (header + "\n".join(rows) + "\n").encode()
    assert len(data) > 1 << 17
    read = read_ply(_lone_cr_after_line(data, 500))
    assert _counts(read) == (14400, 28800, 14400)
    np.testing.assert_array_equal(read.positions_view(), positions)
