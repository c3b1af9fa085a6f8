"""Fuzzing the OBJ and .dlfl readers: bad input raises DLFLError and nothing else.

Random bytes, truncated and mutated valid files must give a clean DLFLError (or
a mesh that validates), never another exception type or a hang. Random valid
OBJ text must parse the same on the vectorized and the reference path.
"""

from __future__ import annotations

import contextlib
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from livemod.dlfl import DLFLError, DLFLRepairWarning, DLFLSkippedLinesWarning, validate
from livemod.dlfl.io import read_dlfl, read_obj
from livemod.dlfl.io.dlflfile import dlfl_bytes
from livemod.dlfl.io.obj import parse_obj
from tests.topmod_samples import sample_bytes

CUBE_OBJ = sample_bytes("cube.obj")
DUAL_OBJ = sample_bytes("soccerballdual.obj")[:3000]
with warnings.catch_warnings():
    warnings.simplefilter("ignore", DLFLRepairWarning)
    warnings.simplefilter("ignore", DLFLSkippedLinesWarning)
    CUBE_DLFL = dlfl_bytes(read_obj(CUBE_OBJ), "cube")
    BEVEL_DLFL = dlfl_bytes(read_obj(sample_bytes("beveledcube.obj")), "bevel")

FUZZ = settings(max_examples=150, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
OBJ_ALPHABET = b"vf0123456789 .-/\t\r\n#,e+x"
DLFL_ALPHABET = b"DLFvfeus 0123456789.-[]\n#"


def only_dlfl_errors(reader, data: bytes) -> None:  # type: ignore[no-untyped-def]
    """Run ``reader``; a result must validate, a failure must be a DLFLError."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DLFLRepairWarning)
        warnings.simplefilter("ignore", DLFLSkippedLinesWarning)
        try:
            mesh = reader(data)
        except DLFLError:
            return
    validate(mesh)


def mutate(data: bytes, edits: list[tuple[int, int, int]]) -> bytes:
    """Apply (kind, position, byte) edits: 0 replace, 1 insert, 2 delete."""
    buf = bytearray(data)
    for kind, pos, byte in edits:
        if not buf:
            break
        i = pos % len(buf)
        if kind == 0:
            buf[i] = byte
        elif kind == 1:
            buf.insert(i, byte)
        else:
            del buf[i]
    return bytes(buf)


edit_lists = st.lists(st.tuples(st.integers(0, 2), st.integers(0, 10**6), st.integers(0, 255)),
                      max_size=8)


@pytest.mark.timeout(60)
@FUZZ
@given(st.binary(max_size=400))
def test_obj_random_bytes(data: bytes) -> None:
    only_dlfl_errors(read_obj, data)


@pytest.mark.timeout(60)
@FUZZ
@given(st.lists(st.sampled_from(list(OBJ_ALPHABET)), max_size=300).map(bytes))
def test_obj_random_obj_like_text(data: bytes) -> None:
    only_dlfl_errors(read_obj, data)


@pytest.mark.timeout(60)
@FUZZ
@given(st.sampled_from([CUBE_OBJ, DUAL_OBJ]), st.integers(0, 3000), edit_lists)
def test_obj_truncated_and_mutated(base: bytes, cut: int, edits: list[tuple[int, int, int]]) -> None:
    only_dlfl_errors(read_obj, mutate(base[: max(cut, 1)], edits))
    only_dlfl_errors(read_obj, mutate(base, edits))


@pytest.mark.timeout(60)
@FUZZ
@given(st.binary(max_size=400))
def test_dlfl_random_bytes(data: bytes) -> None:
    only_dlfl_errors(read_dlfl, b"DLFL\n#\n" + data)
    only_dlfl_errors(read_dlfl, data)


@pytest.mark.timeout(60)
@FUZZ
@given(st.lists(st.sampled_from(list(DLFL_ALPHABET)), max_size=300).map(bytes))
def test_dlfl_random_dlfl_like_text(data: bytes) -> None:
    only_dlfl_errors(read_dlfl, b"DLFL\n#\n" + data)


@pytest.mark.timeout(60)
@FUZZ
@given(st.sampled_from([CUBE_DLFL, BEVEL_DLFL]), st.integers(0, 6000), edit_lists)
def test_dlfl_truncated_and_mutated(base: bytes, cut: int, edits: list[tuple[int, int, int]]) -> None:
    only_dlfl_errors(read_dlfl, mutate(base[: max(cut, 4)], edits))
    only_dlfl_errors(read_dlfl, mutate(base, edits))


# the vectorized OBJ parser must agree with the reference parser wherever it
# accepts a line, and fall back to it everywhere else
number = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False).map(repr),
    st.integers(-10**20, 10**20).map(str),
    st.from_regex(r"-?[0-9]{0,20}\.?[0-9]{0,20}", fullmatch=True),
)
separator = st.sampled_from([" ", "  ", "\t", ", ", ",", " \t "])
vertex_line = st.tuples(st.lists(number, min_size=3, max_size=5), separator).map(
    lambda t: "v " + t[1].join(t[0]))
index = st.one_of(st.integers(-5, 12), st.integers(-10**25, 10**25)).map(str)
corner = st.one_of(index, st.tuples(index, index).map("/".join),
                   st.tuples(index, index).map("//".join),
                   st.tuples(index, index, index).map("/".join))
face_line = st.lists(corner, min_size=0, max_size=6).map(lambda c: "f " + " ".join(c))
other_line = st.sampled_from(["# c", "vn 0 0 1", "usemtl x", "", " ", "g a", "vt 1 2"])
line_end = st.sampled_from(["\n", "\r\n", " \n", "\t\r\n"])
obj_text = st.lists(st.tuples(st.one_of(vertex_line, face_line, other_line), line_end)
                    .map("".join), max_size=25).map("".join)


def parse_or_error(data: bytes, fast: bool) -> object:
    try:
        soup = parse_obj(data, fast=fast)
    except DLFLError as error:
        return str(error)
    return (soup.positions.tobytes(), soup.indices.tolist(), soup.offsets.tolist(),
            soup.face_lines.tolist())


@pytest.mark.timeout(60)
@settings(max_examples=60, deadline=None)
@given(obj_text)
def test_fast_obj_parser_agrees_with_reference(text: str) -> None:
    data = text.encode()
    assert parse_or_error(data, True) == parse_or_error(data, False)


# mostly plain lines (the readers' fastest path) with the odd other line among
# them, so blocks are split between the plain and the general tokenizer
plain_number = st.one_of(
    st.floats(-1e6, 1e6, allow_nan=False).map(lambda x: f"{x:.{abs(hash(x)) % 19}f}"),
    st.integers(-10**19, 10**19).map(str),
    st.from_regex(r"-?[0-9]{1,22}(\.[0-9]{1,24})?", fullmatch=True),
)
plain_vertex = st.tuples(plain_number, plain_number, plain_number).map(
    lambda xyz: "v " + " ".join(xyz))
plain_face = st.lists(st.integers(1, 30).map(str), min_size=1, max_size=5).map(
    lambda c: "f " + " ".join(c))
mostly_plain = st.lists(
    st.one_of(plain_vertex, plain_vertex, plain_face, plain_face, vertex_line, face_line),
    min_size=1, max_size=40).map(lambda lines: "\n".join(lines) + "\n")


@pytest.mark.timeout(60)
@settings(max_examples=60, deadline=None)
@given(mostly_plain)
def test_plain_lines_among_others_parse_as_the_reference_does(text: str) -> None:
    data = text.encode()
    assert parse_or_error(data, True) == parse_or_error(data, False)


@pytest.mark.parametrize("text", [
    # huge indices on otherwise plain lines, alone and beside general ones
    b"v 0 0 0\nf 1 2 3\nf 1 20000000000000000000\nf 1/2 3\n",
    b"f 1 20000000000000000000\n",
    b"v 1 2 3\nf 1 1 1\nf 4611686018427387904 1\nf 1/1\n",
    b"v 0 0 0\nf 0000000000000000000001 1 1\nf 1//1 1\n",
    # long mantissas, leading zeros, negative zero, commas, tabs and CR
    b"v 0.1234567890123456789012 -0000012.5 -0.0\nv 1,2,\t3\r\nv 1.5 2.5 3e1\n",
    b"v 123456789012345678901234 1.0000000000000000000001 -9.999999999999999999\n",
    b"v 1 2\nv 1 2 3 4\nv 1..2 3 4\nv -1 -2 -3\nv 1. 2 3\nv .5 2 3\n",
])
def test_plain_path_edge_cases_parse_as_the_reference_does(text: bytes) -> None:
    assert parse_or_error(text, True) == parse_or_error(text, False)


def test_fast_parser_on_a_big_regular_block_matches_reference() -> None:
    rng = np.random.default_rng(3)
    values = rng.standard_normal((500, 3)) * 10.0 ** rng.integers(-10, 20, (500, 3))
    lines = [f"v {x!r} {y:.6f} {z}" for x, y, z in values.tolist()]
    lines += [f"f {i} {i + 1}/{i}/1 -{j}//2" for i, j in zip(range(1, 400), range(1, 400),
                                                          strict=True)]
    data = "\n".join(lines).encode()
    assert parse_or_error(data, True) == parse_or_error(data, False)


def test_every_truncation_of_a_crlf_file_is_refused_cleanly() -> None:
    # regression: a number cut right after its exponent mark at the very end of
    # the buffer made the vectorized scanner read past it (IndexError)
    mark = DUAL_OBJ.index(b"e-0")  # the first three-digit exponent (as in "6.1e-017")
    assert b"\r\n" in DUAL_OBJ[:mark]
    for cut in range(mark - 25, mark + 25):
        with contextlib.suppress(DLFLError):
            read_obj(DUAL_OBJ[:cut])


@FUZZ
@given(st.binary(max_size=200) | st.text(" \t\n\r\x0b\x0cab1", max_size=60).map(str.encode))
def test_token_starts_find_the_words_bytes_split_finds(data: bytes) -> None:
    from livemod.dlfl.io._lines import token_starts

    starts = token_starts(np.frombuffer(data, dtype=np.uint8)).tolist()
    words = data.split()
    assert len(starts) == len(words)
    assert all(data[s : s + len(w)] == w for s, w in zip(starts, words, strict=True))
