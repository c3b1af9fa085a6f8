"""Reading a file's bytes for the readers (livemod.dlfl.io.source): line ends."""

from __future__ import annotations

import pytest

from livemod.dlfl.io.source import lf_line_ends
from tests.io_inputs import UNIT_CUBE_OBJ

# -- lf_line_ends: a lone CR ends a line, as in Python's universal newlines


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
    for data in (UNIT_CUBE_OBJ, UNIT_CUBE_OBJ.replace(b"\n", b"\r\n")):
        assert lf_line_ends(data) is data


def test_lf_line_ends_finds_a_lone_cr_in_a_large_file():
    # past the block size of the threaded search
    data = UNIT_CUBE_OBJ.replace(b"\n", b"\r\n") * 20000
    at = len(data) // 2 + 1
    at = data.index(b"\r\n", at)
    fixed = lf_line_ends(data[:at] + b"\r" + data[at + 2 :])
    assert fixed == data[:at] + b"\n" + data[at + 2 :]
