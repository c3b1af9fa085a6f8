"""The errors and notes of the readers: their type, the file and line they name.

A file that cannot be read raises :class:`FileFormatError` with ``path`` and
``line`` set (``line`` None only where the format has no lines: binary files,
and problems of the whole file); an unknown extension or a missing file is an
:class:`InvalidArgumentError`; lines a reader passes over are said in a
:class:`DLFLSkippedLinesWarning` and in ``mesh.notes``.
"""

from __future__ import annotations

import os
import random
from pathlib import Path

import pytest

from livemod.dlfl import validate
from livemod.dlfl.errors import (
    DLFLSkippedLinesWarning,
    FileFormatError,
    InvalidArgumentError,
    NonManifoldError,
)
from livemod.dlfl.io import load_mesh, open_mesh, read_dlfl, read_obj, read_ply, read_stl
from livemod.dlfl.io.source import show_path
from tests.io_inputs import KEYWORD_CASES, bumpy_grid, stl_ascii_text

TRIANGLE_STL = (b"solid x\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n"
                b"   vertex 0 1 0\n  endloop\n endfacet\nendsolid x\n")
CUBE_PLY_HEAD = (b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                 b"property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                 b"end_header\n")


def refused(reader, data: bytes, name: str = "m.x") -> FileFormatError:  # type: ignore[no-untyped-def]
    with pytest.raises(FileFormatError) as caught:
        reader(data, name=name)
    return caught.value


@pytest.mark.parametrize(("reader", "data", "line", "what"), [
    (read_obj, b"v 0 0 0\nv 1 x 0\n", 2, "bad number 'x'"),
    (read_obj, b"v 0 0 0\nf 1 2\n", 2, "vertex index 2 is out of range"),
    (read_obj, b"v 0 0\n", 1, "a v line needs 3 coordinates, got 2"),
    (read_obj, b"v 1 2 3\nv 1 2 1" + b"0" * 308 + b"0\n", 2, "is not finite"),
    (read_dlfl, b"DLFL\n#\nv 0 0 0\nv 0 0 " + b"9" * 309 + b"\n", 4, "is not a finite number"),
    (read_dlfl, b"DLFL\n#\nv 0 0 0\nfv 3\n", 4, "vertex index 3 is out of range"),
    (read_dlfl, b"DLFX\n", 1, "not a .dlfl file"),
    (read_dlfl, b"DLFL\n#\nhello world\n", 3, "no geometry, and the line starts with 'hello'"),
    (read_stl, TRIANGLE_STL.replace(b"vertex 1 0 0", b"vertex 1 zz 0"), 5, "bad number 'zz'"),
    (read_stl, b"solid x\nthis is garbage\nendsolid x\n", 2, "'this' is not part of a facet"),
    (read_stl, TRIANGLE_STL + b"more text\n", 10, "'more' is not part of a facet"),
    (read_stl, TRIANGLE_STL.replace(b"endloop", b"endlop"), 2, "facet 0 is not"),
    (read_ply, CUBE_PLY_HEAD + b"0 0 0\n1 0 0\n0 1 zz\n3 0 1 2\n", 12, "bad number 'zz'"),
    (read_ply, CUBE_PLY_HEAD + b"0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n", 13, "face 0: vertex index 7"),
    (read_ply, CUBE_PLY_HEAD.replace(b"float z", b"float128 z"), 6, "unknown property type"),
])
def test_a_file_error_names_its_file_and_line(reader, data: bytes, line: int,  # type: ignore[no-untyped-def]
                                              what: str) -> None:
    error = refused(reader, data, "my model.x")
    assert (error.path, error.line) == ("my model.x", line)
    assert str(error).startswith(f"'my model.x':{line}: ") and what in str(error)


def test_binary_files_name_the_record_and_no_line() -> None:
    data = b"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n" \
           b"property float y\nproperty float z\nend_header\n" + b"\0\0\xc0\x7f" + b"\0" * 8
    error = refused(read_ply, data, "b.ply")
    assert (error.path, error.line) == ("b.ply", None)
    assert str(error) == "b.ply: vertex 0: coordinate nan is not finite"
    assert refused(read_stl, b"\0" * 90, "b.stl").line is None


def test_topology_errors_are_no_format_errors_and_name_the_line() -> None:
    data = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 3 2 1\nf 1 2 4\n"
    with pytest.raises(NonManifoldError, match=r"^'t 1\.obj':5: edge \(1, 2\) is used by 4 face sides") as caught:
        read_obj(data, name="t 1.obj")
    assert not isinstance(caught.value, FileFormatError)  # the file reads: its surface is wrong


@pytest.mark.parametrize("case", range(len(KEYWORD_CASES)))
def test_ascii_stl_keywords_in_any_case_are_read(case: int) -> None:
    mesh = bumpy_grid(2, 3)
    got = read_stl(stl_ascii_text(mesh, random.Random(case), case=case))
    validate(got)
    assert got.counts() == mesh.counts()


def test_ascii_stl_of_mixed_case_words_as_exporters_write_them() -> None:
    data = (b"solid part\nFacet Normal 0 0 1\nOuter Loop\nVertex 0 0 0\nVertex 1 0 0\n"
            b"VERTEX 0 1 0\nEndLoop\nEndFacet\nEndSolid part\n")
    assert read_stl(data).counts() == (3, 3, 2)


def test_an_empty_solid_is_an_empty_mesh() -> None:
    assert read_stl(b"solid x\nendsolid x\n").counts() == (0, 0, 0)


def test_skipped_obj_lines_are_counted_and_the_first_is_shown() -> None:
    data = (b"# made by hand\nv 0 0 0\nv 1 0 0\nv 0 1 0\nhello world\nvn 0 0 1\nusemtl red\n"
            b"shadow_obj x.obj\n  bogus 1\nf 1 2 3\n")
    with pytest.warns(DLFLSkippedLinesWarning) as caught:
        mesh = read_obj(data, name="h.obj")
    message = "h.obj: ignored 2 lines not understood: line 5 'hello world' and 1 more"
    assert [str(w.message) for w in caught] == [message] and mesh.notes == [message]
    warning = caught[0].message
    assert isinstance(warning, DLFLSkippedLinesWarning)
    assert (warning.path, warning.count, warning.first_line, warning.first_text) == (
        "h.obj", 2, 5, "hello world")
    assert mesh.counts() == (3, 3, 2)


def test_one_skipped_line_is_said_in_the_singular() -> None:
    with pytest.warns(DLFLSkippedLinesWarning) as caught:
        read_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nhello world\n", name="a.obj")
    assert str(caught[0].message) == "a.obj: ignored 1 line not understood: line 5 'hello world'"


def test_obj_statements_that_are_not_used_are_skipped_silently(
        recwarn: pytest.WarningsRecorder) -> None:
    statements = b"vt 0 0\nvn 0 0 1\nvp 0\ng a\no b\ns 1\nusemtl m\nmtllib m.mtl\nl 1 2\n" \
                 b"trace_obj t\nshadow_obj s\nc_interp on\n"
    mesh = read_obj(b"v 0 0 0\nv 1 0 0\nv 0 1 0\n" + statements + b"f 1 2 3\n")
    assert mesh.notes == [] and len(recwarn) == 0


def test_an_obj_of_no_geometry_and_a_line_not_understood_is_refused() -> None:
    error = refused(read_obj, b"# header\n\nthis is garbage\n", "g.obj")
    assert (error.path, error.line) == ("g.obj", 3)
    assert "'this', not an OBJ keyword" in str(error)
    assert read_obj(b"# only a comment\nvn 0 0 1\n").counts() == (0, 0, 0)


def test_skipped_dlfl_lines_are_reported() -> None:
    data = b"DLFL\nmtllib m.mtl\n#\nv 0 0 0\nwhat is this\n#\n"
    with pytest.warns(DLFLSkippedLinesWarning, match=r"^d\.dlfl: ignored 1 line not "
                      r"understood: line 5 'what is this'$"):
        mesh = read_dlfl(data, name="d.dlfl")
    assert mesh.counts() == (1, 0, 1)


def test_a_folder_is_said_to_be_a_folder(tmp_path: Path) -> None:
    with pytest.raises(IsADirectoryError, match="is a folder, not a mesh file"):
        load_mesh(tmp_path)


def test_a_missing_file_names_the_folder_and_lists_shapes_only_without_extension(
        tmp_path: Path) -> None:
    missing = tmp_path / "sub dir" / "x.obj"
    with pytest.raises(InvalidArgumentError) as caught:
        open_mesh(missing)
    assert str(caught.value) == f"no file x.obj in {show_path(str(tmp_path / 'sub dir'))}"
    with pytest.raises(InvalidArgumentError) as caught:
        open_mesh(tmp_path / "sphere")
    assert str(caught.value).startswith(
        f"no file sphere in {show_path(str(tmp_path))}, and no built-in shape sphere; shapes: cube,")
    assert open_mesh(tmp_path / "cube.obj", shape_name="cube.obj").counts() == (8, 12, 6)


def test_an_unknown_extension_is_an_invalid_argument(tmp_path: Path) -> None:
    with pytest.raises(InvalidArgumentError, match=r"^cannot read .*x\.abc: unknown extension"):
        load_mesh(tmp_path / "x.abc")


@pytest.mark.parametrize(("name", "shown"), [
    ("model.obj", "model.obj"), ("out/a-1_b.stl", "out/a-1_b.stl"), ("my model.obj", "'my model.obj'"),
    ("", "''"), ("<obj>", "<obj>"), ("it's.obj", "'it'\"'\"'s.obj'"),
])
def test_file_names_are_shown_as_a_shell_would_take_them(name: str, shown: str) -> None:
    assert show_path(name) == shown
    assert show_path(os.fsencode(name).decode()) == shown
