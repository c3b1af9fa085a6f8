"""Every reader on valid files laid across each of its internal boundaries.

The readers cut their work at fixed sizes: line passes of ``_LINES_PER_PASS``
lines (OBJ, .dlfl, ASCII PLY), scan blocks of ``_lines._BLOCK`` bytes of the
lines a plain path refused, newline searches in ``_lines._NEWLINE_BLOCK`` bytes,
ASCII PLY's token scan in ``_BYTES_PER_SCAN`` slices and its line path from
``_LINE_PATH_MIN_BYTES`` on. A valid file must read the same wherever those cuts
fall: in the middle of its last line, on a line's first or last byte, inside
one line longer than a block. The positions below derive from the modules' own
constants. Two ways: at the real sizes (files of about 1 MiB, the issue's
reproducers among them), and with the constants made small so that a few
hundred bytes cross every boundary many times, on random valid files of every
form, each compared with the mesh it was written from and the fast paths with
the reference paths.
"""

from __future__ import annotations

import random

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from livemod.dlfl import FileFormatError, Mesh, from_polygons, mesh_arrays, validate
from livemod.dlfl.io import (
    _lines,
    _ply_ascii,
    dlflfile,
    obj,
    read_dlfl,
    read_obj,
    read_ply,
    read_stl,
)
from livemod.dlfl.io.dlflfile import dlfl_bytes, parse_dlfl
from livemod.dlfl.io.obj import parse_obj
from livemod.dlfl.io.ply import parse_ply
from livemod.dlfl.io.stl import parse_stl
from tests.io_inputs import (
    FORMATS,
    bumpy_grid,
    dlfl_text,
    obj_text,
    ply_ascii_text,
    quiet_read,
    stl_ascii_text,
)

BLOCK = _lines._BLOCK


def surface(mesh: Mesh) -> tuple[np.ndarray, np.ndarray]:
    """``(sizes, (C, 3) corner positions)`` of the surface faces, face by face."""
    a = mesh_arrays(mesh)
    sizes, vertices = a.surface_polygons()
    return sizes, a.positions[vertices]


def assert_same_surface(read: Mesh, source: Mesh) -> None:
    validate(read)
    got, want = surface(read), surface(source)
    assert np.array_equal(got[0], want[0])
    assert got[1].tobytes() == want[1].tobytes()  # bit for bit


def assert_same_soup(fast: object, slow: object) -> None:
    for name in vars(fast):
        a, b = getattr(fast, name), getattr(slow, name)
        if isinstance(a, np.ndarray):
            assert a.dtype == b.dtype and a.tobytes() == b.tobytes(), name
        else:
            assert a == b, name


def slow_lines(keyword: bytes, total: int, width: int = 256) -> tuple[bytes, int]:
    """``keyword +1 +2 +3`` lines (plus signs: the plain path refuses them, the
    general one takes them), ``total`` bytes in all: lines of ``width`` bytes
    (blanks fill them), the last one longer to make up the rest. Returns the
    lines and how many."""
    count = total // width
    line = keyword + b" +1 +2 +3"
    lines = [line + b" " * (width - len(line) - 1) + b"\n"] * (count - 1)
    last = total - width * (count - 1)
    return b"".join(lines) + line + b" " * (last - len(line) - 1) + b"\n", count


# the scan mark: after the end, on the last byte (the newline), inside the last
# line, at its first byte (lines are 256 bytes), and a second block crossed
CUTS = [0, 1, 17, 256, BLOCK + 1]


@pytest.mark.parametrize("past", CUTS)
def test_obj_slow_lines_across_a_scan_block(past: int) -> None:
    data, count = slow_lines(b"v", BLOCK + past)
    assert count <= obj._LINES_PER_PASS  # all in one pass: one slow-path block
    soup = parse_obj(data, "t.obj")
    assert soup.positions.shape == (count, 3) and (soup.positions == [1, 2, 3]).all()
    assert_same_soup(soup, parse_obj(data, "t.obj", fast=False))
    assert read_obj(data).counts() == (count, 0, count)  # a cloud of point-spheres


def test_the_issues_obj_reproducer_reads() -> None:
    data = b"v 1 2 3 # xxxxxx\n" * 61681  # 1,048,577 bytes
    assert len(data) == BLOCK + 1
    assert read_obj(data).counts() == (61681, 0, 61681)


@pytest.mark.parametrize("past", CUTS)
def test_dlfl_slow_lines_across_a_scan_block(past: int) -> None:
    lines, count = slow_lines(b"v", BLOCK + past)
    data = b"DLFL\n#\n" + lines
    records = parse_dlfl(data, "t.dlfl")
    assert records.positions.shape == (count, 3)
    assert_same_soup(records, parse_dlfl(data, "t.dlfl", fast=False))


def test_the_issues_dlfl_reproducer_reads() -> None:
    data = (b"DLFL\n#\n" + b"v +1 +2 +311111\n" * 65534 + b"v +1 +2 +3" + b"1" * 25 + b"\n")
    mesh = read_dlfl(data)
    assert mesh.counts() == (65535, 0, 65535)
    assert mesh_arrays(mesh).positions[-1, 2] == float("3" + "1" * 25)


def polygon(corners: int) -> Mesh:
    """One face of ``corners`` corners round a circle (and its hole)."""
    t = np.arange(corners) * (2 * np.pi / corners)
    return from_polygons(np.stack([np.cos(t), np.sin(t), 0 * t], axis=1), [list(range(corners))])


def test_an_obj_face_line_longer_than_a_scan_block() -> None:
    corners = BLOCK // 16
    mesh = polygon(corners)
    vertices = obj_text(mesh, random.Random(0), slow=0.0).split(b"\nf")[0]
    face = b"f" + b"".join(b" %d/100000/100000" % (i + 1) for i in range(corners)) + b"\n"
    assert len(face) > BLOCK  # one slow-path line, longer than a scan block
    assert_same_surface(read_obj(vertices + b"\n" + face), mesh)


def test_a_dlfl_face_longer_than_a_pass_and_a_block_writes_and_reads() -> None:
    corners = dlflfile._LINES_PER_PASS + 1  # the writer's corner passes: one face
    mesh = polygon(corners)
    text = dlfl_bytes(mesh)
    head, face = text.rsplit(b"\nf ", 1)
    blanks = b"\t" * (BLOCK // corners + 1)  # tabs: the general path, past a block
    data = head + b"\nf" + blanks + face.replace(b" ", blanks)
    assert len(data.rsplit(b"\nf", 1)[1].split(b"\n")[0]) > BLOCK
    assert_same_surface(read_dlfl(data), mesh)


def test_an_ascii_stl_of_slow_vertex_lines_past_a_block() -> None:
    mesh = bumpy_grid(100, 100)
    data = stl_ascii_text(mesh, random.Random(1), slow=1.0, case=1)
    vertex_lines = [line for line in data.split(b"\n") if b"VERTEX" in line]
    assert sum(map(len, vertex_lines)) > BLOCK  # each in a form the plain path refuses
    assert_same_surface(read_stl(data), mesh)


def test_ascii_ply_across_scan_slices_passes_and_the_path_threshold(
        monkeypatch: pytest.MonkeyPatch) -> None:
    rows = _ply_ascii._LINES_PER_PASS // 120 + 1
    mesh = bumpy_grid(rows, 120)
    data = ply_ascii_text(mesh, random.Random(2), slow=0.3)
    body = len(data) - data.index(b"end_header")
    assert body > max(_ply_ascii._BYTES_PER_SCAN, BLOCK, _ply_ascii._LINE_PATH_MIN_BYTES)
    line_path = parse_ply(data)
    assert_same_surface(read_ply(data), mesh)
    monkeypatch.setattr(_ply_ascii, "_LINE_PATH_MIN_BYTES", len(data) + 1)
    assert_same_soup(line_path, parse_ply(data))


def test_newline_search_blocks_meet_lines_at_their_edges() -> None:
    size = _lines._NEWLINE_BLOCK
    for at in (size - 1, size, size + 1):
        buf = np.full(2 * size + 3, ord("x"), dtype=np.uint8)
        buf[[0, at, 2 * size, len(buf) - 1]] = 10
        assert np.array_equal(_lines.byte_offsets(buf, 10), np.flatnonzero(buf == 10))


@given(st.lists(st.integers(1, 50), min_size=1, max_size=40), st.integers(1, 60))
def test_pass_starts_cut_at_records_and_never_leave_one_empty(lengths: list[int],
                                                              size: int) -> None:
    starts = np.concatenate([[0], np.cumsum(lengths)[:-1]])
    total = int(np.sum(lengths))
    cuts = _lines.pass_starts(starts, total, size)
    assert cuts[0] == 0 and (np.diff(cuts) > 0).all() and cuts[-1] < len(starts)
    ends = np.append(starts[cuts[1:]], total)
    # a pass ends at the first record start at or after the next multiple of size
    for begin, end in zip(starts[cuts].tolist(), ends.tolist(), strict=True):
        mark = (begin // size + 1) * size
        assert end == total or end == starts[np.searchsorted(starts, mark)]


# ------------------------------------------------- every boundary, made small


@pytest.fixture
def small_boundaries(monkeypatch: pytest.MonkeyPatch) -> None:
    """Every size the readers cut at, made a few lines or bytes long."""
    monkeypatch.setattr(_lines, "_BLOCK", 48)
    monkeypatch.setattr(_lines, "_NEWLINE_BLOCK", 40)
    for module in (obj, dlflfile, _ply_ascii):
        monkeypatch.setattr(module, "_LINES_PER_PASS", 3)
    monkeypatch.setattr(_ply_ascii, "_BYTES_PER_SCAN", 32)
    monkeypatch.setattr(_ply_ascii, "_LINE_PATH_MIN_BYTES", 0)


SMALL = settings(max_examples=60, deadline=None, derandomize=True)


@pytest.mark.usefixtures("small_boundaries")
@SMALL
@given(rows=st.integers(1, 6), cols=st.integers(1, 6), seed=st.integers(0, 2**32),
       slow=st.sampled_from([0.0, 0.3, 1.0]))
def test_every_reader_reads_its_source_wherever_the_cuts_fall(rows: int, cols: int,
                                                              seed: int, slow: float) -> None:
    mesh = bumpy_grid(rows, cols, seed)
    rng = random.Random(seed)
    for name, make_text in [("obj", obj_text), ("dlfl", dlfl_text),
                            ("ply", ply_ascii_text), ("stl", stl_ascii_text)]:
        data = make_text(mesh, rng, slow)  # type: ignore[operator]
        read = {"obj": read_obj, "dlfl": read_dlfl, "ply": read_ply, "stl": read_stl}[name]
        assert_same_surface(read(data), mesh)


@pytest.mark.usefixtures("small_boundaries")
@SMALL
@given(rows=st.integers(1, 5), cols=st.integers(1, 5), seed=st.integers(0, 2**32),
       crlf=st.booleans())
def test_fast_and_reference_paths_agree_wherever_the_cuts_fall(rows: int, cols: int,
                                                               seed: int, crlf: bool) -> None:
    mesh = bumpy_grid(rows, cols, seed)
    rng, newline = random.Random(seed), b"\r\n" if crlf else b"\n"
    data = obj_text(mesh, rng, 0.5, newline)
    assert_same_soup(parse_obj(data), parse_obj(data, fast=False))
    data = dlfl_text(mesh, rng, 0.5, newline)
    assert_same_soup(parse_dlfl(data), parse_dlfl(data, fast=False))
    data = ply_ascii_text(mesh, rng, 0.5)
    line_path = parse_ply(data)
    _ply_ascii._LINE_PATH_MIN_BYTES = len(data) + 1  # the fixture puts it back
    assert_same_soup(line_path, parse_ply(data))


@pytest.mark.usefixtures("small_boundaries")
@pytest.mark.parametrize("name", sorted(FORMATS))
def test_every_format_reads_back_with_small_boundaries(name: str) -> None:
    make, read = FORMATS[name]
    mesh = bumpy_grid(4, 3, 7)
    got = quiet_read(read, make(mesh, random.Random(3)))
    validate(got)
    if name.startswith("stl-binary"):  # a soup of float32 triangles: counts only
        assert got.counts()[2] == 2 * 12 + 1
    else:
        assert_same_surface(got, mesh)


def test_binary_stl_soup_keeps_every_triangle() -> None:
    corners, offsets, lines = parse_stl(FORMATS["stl-binary"][0](bumpy_grid(3, 3), random.Random()))
    assert lines is None and len(offsets) - 1 == 2 * 9 and corners.shape == (54, 3)


def test_a_309_digit_coordinate_is_refused_on_its_line_on_every_path() -> None:
    huge = b"9" * 309  # past the largest float64: inf
    for data, line in [(b"v 0 0 0\nv " + huge + b" 0 0\n", 2),
                       (b"v 0 0 0\nv " + huge + b" 0 0 # c\n", 2),
                       (b"DLFL\n#\nv 0 0 0\nv " + huge + b" 0 0\n", 4)]:
        reader = read_dlfl if data.startswith(b"DLFL") else read_obj
        with pytest.raises(FileFormatError, match=f"^<(obj|dlfl)>:{line}: .*not (a )?finite"):
            reader(data)
