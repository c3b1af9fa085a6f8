"""OBJ reading and writing (livemod.dlfl.io.obj) and its exact number text."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from livemod.dlfl import (
    DLFLRepairWarning,
    DLFLSkippedLinesWarning,
    FileFormatError,
    InvalidArgumentError,
    Mesh,
    NonManifoldError,
    from_polygons,
    genus,
    validate,
)
from livemod.dlfl.io import _numtext, load_mesh, read_obj, write_obj
from livemod.dlfl.io._numtext import decimal_to_float, format_floats, format_uints
from livemod.dlfl.io.obj import obj_bytes, parse_obj
from tests.io_inputs import UNIT_CUBE_OBJ, lone_cr_after_line
from tests.meshes import CUBE_FACE_COLORS, coloured_cube, cube, expected_written_colors
from tests.topmod_samples import SAMPLE_COUNTS, sample_bytes

CUBE = b"""# a unit cube
v 1.0, 1.0, 1.0
v 1.0, 1.0, -1.0
v -1.0, 1.0, -1.0
v -1.0, 1.0, 1.0
v 1.0, -1.0, 1.0
v 1.0, -1.0, -1.0
v -1.0, -1.0, -1.0
v -1.0, -1.0, 1.0
f 1 2 3 4
f 5 6 2 1
f 6 7 3 2
f 7 8 4 3
f 8 5 1 4
f 8 7 6 5
"""


def load_quietly(source: Path | bytes) -> Mesh:
    """``read_obj(source)`` without the notes of what it mended or skipped (the
    samples have TopMod's quirks; their own tests catch the notes)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DLFLRepairWarning)
        warnings.simplefilter("ignore", DLFLSkippedLinesWarning)
        return read_obj(source)


# ------------------------------------------------------------------ samples


@pytest.mark.parametrize("name", sorted(SAMPLE_COUNTS))
def test_every_topmod_sample_loads_with_its_counts(name: str, topmod_samples: Path) -> None:
    mesh = load_quietly(topmod_samples / name)
    validate(mesh)
    v, e, f, g = SAMPLE_COUNTS[name]
    assert mesh.counts() == (v, e, f)
    assert genus(mesh) == g
    assert not any(mesh.is_hole(face) for face in mesh.face_ids())


@pytest.mark.parametrize("name", sorted(SAMPLE_COUNTS))
def test_fast_parser_agrees_with_reference_parser_on_samples(name: str) -> None:
    data = sample_bytes(name)
    fast, slow = parse_obj(data, name), parse_obj(data, name, fast=False)
    assert np.array_equal(fast.positions, slow.positions)
    assert np.array_equal(fast.indices, slow.indices)
    assert np.array_equal(fast.offsets, slow.offsets)
    assert np.array_equal(fast.face_lines, slow.face_lines)


def test_well_formed_lines_never_reach_the_reference_parser(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    import livemod.dlfl.io.obj as obj_module

    def refuse(raw: bytes, line: int, label: str) -> None:
        raise AssertionError(f"line {line} fell back to the Python parser: {raw!r}")

    monkeypatch.setattr(obj_module, "_parse_line", refuse)
    # plain lines, and lines only the general tokenizer reads, in one block
    text = b"".join(
        b"v %d.5 -0.25 %s\n" % (i, b"6.1e-17" if i % 7 == 0 else b"3") for i in range(200)
    ) + b"".join(b"f %d %d/1 -1//2\n" % (i + 1, i + 2) if i % 5 == 0 else
                 b"f %d %d %d\n" % (i + 1, i + 2, i + 3) for i in range(150))
    soup = parse_obj(text)
    assert soup.positions.shape == (200, 3) and len(soup.offsets) == 151
    assert soup.positions[7, 2] == 6.1e-17 and soup.positions[8, 2] == 3.0


@pytest.mark.parametrize("name", ["soccerballdual.obj", "genus3hexa3.obj", "beveledcube.obj"])
def test_many_small_passes_on_threads_read_and_write_as_one_pass_does(
    name: str, monkeypatch: pytest.MonkeyPatch,
) -> None:
    import livemod.dlfl.io.obj as obj_module

    data = sample_bytes(name)
    slow = parse_obj(data, fast=False)
    mesh = load_quietly(data)
    text_in_one_piece = obj_bytes(mesh)
    monkeypatch.setattr(obj_module, "_LINES_PER_PASS", 37)  # dozens of passes, threaded
    fast = parse_obj(data)
    assert np.array_equal(fast.positions, slow.positions)
    assert np.array_equal(fast.indices, slow.indices)
    assert np.array_equal(fast.offsets, slow.offsets)
    assert np.array_equal(fast.face_lines, slow.face_lines)
    assert obj_bytes(mesh) == text_in_one_piece


def test_beveledcube_is_reoriented_with_a_note(topmod_samples: Path) -> None:
    # the sample names a material library TopMod did not ship: said, not refused
    with pytest.warns(DLFLRepairWarning, match="re-oriented 4 faces"), \
            pytest.warns(DLFLSkippedLinesWarning, match=r"line 56 '1 14'$"), \
            pytest.warns(DLFLRepairWarning, match="library 'beveledcube.mtl' not found"):
        mesh = read_obj(topmod_samples / "beveledcube.obj")
    assert any("re-oriented" in note and "beveledcube.obj" in note for note in mesh.notes)
    assert any("library 'beveledcube.mtl' not found" in note for note in mesh.notes)
    assert mesh.notes[-1].endswith("beveledcube.obj: ignored 1 line not understood: line 56 '1 14'")
    sizes = sorted(mesh.face_size(f) for f in mesh.face_ids())
    assert sizes == [3] * 8 + [4] * 18


def test_soccerballdual_crlf_and_two_2gons(topmod_samples: Path) -> None:
    data = (topmod_samples / "soccerballdual.obj").read_bytes()
    assert b"\r\n" in data and b" \r\n" in data  # CRLF, and trailing spaces before it
    mesh = read_obj(topmod_samples / "soccerballdual.obj")
    validate(mesh)
    assert [mesh.face_size(f) for f in mesh.face_ids()].count(2) == 2
    assert genus(mesh) == 0


def test_topmod_cube_with_commas() -> None:
    data = sample_bytes("cube.obj")
    assert b"v -1.0, 1.0, -1.0\n" in data
    mesh = read_obj(data)
    assert mesh.counts() == (8, 12, 6)
    assert np.array_equal(mesh.position(mesh.vertex_ids()[2]), [-1.0, 1.0, -1.0])


# what each stand-in must hold for the tests above to read what TopMod's sample holds
SAMPLE_FORMS = [
    ("tetrahedron.obj", rb"\nvt [\d.]+ [\d.]+\nvt .*\ns off\ng pCone1\nusemtl \w+\nf 1/1/1 "),
    ("dodecahedron.obj", rb"^# .*\n#\n(# .*\n)+#\n\ng dodecahedron\nv .*\n\ng\nf "),
    ("genus3hexa1.obj", rb"^# .*\n\nmtllib genus3hexa1.mtl\ng default\nv [-\d.]+ .*\nvn .*\n"
                        rb"s off\ng Mesh1\nusemtl \w+\nf \d+//1 \d+//2 "),
    ("octahedron.obj", rb"\nv [-\d.]+ [-\d.]+ [-\d.]+\n# 6 vertices\n# 8 faces\n\nf \d+ \d+ \d+\n"),
    ("beveledcube.obj", rb"\no Cube_Cube\nv [-\d.]+ .*\nusemtl \(null\)\ns off\nf .*\n1 14\n$"),
    ("soccerballdual.obj", rb"\nv [-\d.]+e-0\d\d .*\r\n.*\r\nvn .*\r\nf \d+//\d+ \d+//\d+ \r\n"),
]


@pytest.mark.parametrize(("name", "form"), SAMPLE_FORMS)
def test_the_stand_ins_spell_obj_as_the_samples_do(name: str, form: bytes) -> None:
    assert re.search(form, sample_bytes(name), re.DOTALL)


# ------------------------------------------------------------- edge cases


def test_ids_follow_file_order() -> None:
    mesh = read_obj(CUBE)
    assert list(mesh.face_ids()) == list(range(6))
    assert mesh.face_vertices(mesh.face_ids()[0]) == [0, 1, 2, 3]
    assert mesh.face_vertices(mesh.face_ids()[5]) == [7, 6, 5, 4]


@pytest.mark.parametrize("form", ["{}", "{}/{}", "{}//{}", "{}/{}/{}"])
def test_vertex_texture_normal_forms(form: str) -> None:
    faces = []
    for line in CUBE.decode().splitlines():
        if line.startswith("f "):
            idx = line.split()[1:]
            faces.append("f " + " ".join(form.format(i, 1, 1) for i in idx))
    text = [ln for ln in CUBE.decode().splitlines() if not ln.startswith("f ")]
    text += ["vt 0 0", "vn 0 0 1"] + faces
    mesh = read_obj("\n".join(text).encode())
    assert mesh.counts() == (8, 12, 6)
    assert mesh.face_vertices(0) == [0, 1, 2, 3]


def test_negative_indices_count_back_from_the_last_vertex() -> None:
    text = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 0 0 1\nf 1 -1 2\n"
    mesh = read_obj(text)
    assert mesh.face_vertices(0) == [0, 1, 2]
    assert mesh.face_vertices(1) == [0, 3, 1]


def test_ignored_statements_comments_and_whitespace() -> None:
    text = (
        b"\xef\xbb\xbf# header\r\nmtllib x.mtl\r\no thing\r\ng group\r\ns off\r\n"
        b"usemtl red\r\nvn 0 0 1\r\nvt 0 0\r\nvp 1\r\nl 1 2\r\ncstype bezier\r\n"
        b"v\t0 0 0   \r\n  v 1 0 0 # indented, with a comment\r\nv 1,1,0 1.0 0.5 0.5 0.5\r\n"
        b"\r\n\r\nf 1 2 3   \r\nf\t3\t2\t1 # back\r\nunknown words here"
    )
    with pytest.warns(DLFLSkippedLinesWarning, match="line 19 'unknown words here'"):
        mesh = read_obj(text)
    validate(mesh)
    assert mesh.counts() == (3, 3, 2)
    assert np.array_equal(mesh.position(2), [1.0, 1.0, 0.0])
    assert mesh.face_vertices(1) == [2, 1, 0]


def test_number_forms() -> None:
    text = b"v -0.5 .25 5.\nv 1e-3 -2E+2 +3\nv 12345678901234567890.5 0.1 -0\nf 1 2 3\n"
    soup = parse_obj(text)
    assert soup.positions.tolist() == [[-0.5, 0.25, 5.0], [0.001, -200.0, 3.0],
                                       [12345678901234567890.5, 0.1, 0.0]]


def test_numbers_without_integer_part_only() -> None:
    # no number with an integer run at all once sent the fast path out of bounds
    soup = parse_obj(b"v .5 .25 -.75\nv .1 .2 .3\nv .0 .0 .0\nf 1 2 3\n")
    assert soup.positions.tolist() == [[0.5, 0.25, -0.75], [0.1, 0.2, 0.3], [0.0, 0.0, 0.0]]
    with pytest.raises(FileFormatError, match="<obj>:1: a v line needs 3 coordinates, got 1"):
        read_obj(b"v .0")


def test_open_mesh_gets_a_hole_and_unused_vertices_become_point_spheres() -> None:
    text = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nf 1 2 3 4\n"
    mesh = read_obj(text)
    validate(mesh)
    assert mesh.counts() == (5, 4, 3)
    assert [mesh.is_hole(f) for f in mesh.face_ids()] == [False, True, False]
    assert mesh.is_point_sphere(4)


@pytest.mark.parametrize(
    ("text", "message"),
    [
        (b"v 0 0 0\nv 1 x 0\n", r"<obj>:2: bad number 'x'"),
        (b"v 0 0\n", r"<obj>:1: a v line needs 3 coordinates, got 2"),
        (b"v 0 0 nan\n", r"<obj>:1: coordinate 'nan' is not finite"),
        (b"v 0 0 0\nv 0 1e999 0\n", r"<obj>:2: coordinate '1e999' is not finite"),
        (b"v 0 0 0\nf\n", r"<obj>:2: empty face"),
        (b"v 0 0 0\nf \r\n", r"<obj>:2: empty face"),
        (b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", r"<obj>:4: vertex index 4 is out of range"),
        (b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2 0\n", r"<obj>:5: vertex index 0"),
        (b"v 0 0 0\nf 1 -2 1\n", r"<obj>:2: vertex index -2 is out of range"),
        (b"v 0 0 0\nf 1 a 1\n", r"<obj>:2: bad vertex index 'a'"),
        (b"v 0 0 0\nf 1 /2 1\n", r"<obj>:2: bad vertex index '/2'"),
        (b"v 0 0 0\nf 1 1.5 1\n", r"<obj>:2: bad vertex index '1.5'"),
        (b"v 0 0 0\nf 1 99999999999999999999999 1\n", r"<obj>:2: vertex index '9+' is out"),
        (b"v 0 0 0\nf 1 -99999999999999999999999\n", r"<obj>:2: vertex index '-9+' is out"),
        (b"v 0 0 0\nf 1 9999999999999999999 1\n", r"<obj>:2: vertex index '9+' is out"),
        (b"v 0 0 0\nf 1 999999999999999999 1\n", r"<obj>:2: vertex index 9+ is out of range"),
        # a file of another kind is refused, not read as an empty mesh
        (b"hello world\nthis is not obj\n", r"<obj>:1: not an OBJ file: no vertex, .* 'hello'"),
        (b"# a comment\n\nsolid cube\nendsolid\n", r"<obj>:3: not an OBJ file: .* 'solid'"),
        (b"ply\nformat ascii 1.0\n", r"<obj>:1: not an OBJ file: .* 'ply'"),
        (b"\x00\x01binary", r"<obj>: not an OBJ file: it holds binary data"),
    ],
)
def test_errors_name_file_and_line(text: bytes, message: str) -> None:
    with pytest.raises(FileFormatError, match=message):
        read_obj(text)


@pytest.mark.parametrize("text", [b"", b"\n\n", b"# only a comment\n", b"o empty\ng group\n",
                                  b"mtllib a.mtl\nusemtl red\n",
                                  b"\xef\xbb\xbf# comments after a byte order mark\n"])
def test_a_blank_or_vertexless_obj_file_is_an_empty_mesh(text: bytes) -> None:
    assert read_obj(text).counts() == (0, 0, 0)


def test_error_names_the_path(tmp_path: Path) -> None:
    path = tmp_path / "broken.obj"
    path.write_bytes(b"v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 2 3\n")
    with pytest.raises(NonManifoldError, match=r"broken\.obj:\d+: .*edge"):
        read_obj(path)


def test_non_manifold_error_names_the_line(tmp_path: Path) -> None:
    path = tmp_path / "fin.obj"
    path.write_bytes(b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                     b"f 1 2 3\nf 2 1 4\nf 1 2 5\n")
    # vertices as the f lines number them (from 1), not livemod's indices
    with pytest.raises(NonManifoldError, match=r"fin\.obj:6: edge \(1, 2\) is used by 3"):
        read_obj(path)


def test_errors_number_vertices_as_the_obj_file_does(tmp_path: Path) -> None:
    path = tmp_path / "twice.obj"
    path.write_bytes(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 2 3\n")
    with pytest.raises(InvalidArgumentError, match=r"line 5 visits vertex 2 twice in a row"):
        read_obj(path)
    path.write_bytes(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 0 0 2\n"
                     b"f 1 2 3\nf 1 3 4\nf 1 5 6\n")  # two fans meet at vertex 1
    with pytest.raises(NonManifoldError, match=r"vertex 1 is non-manifold"):
        read_obj(path)


# ------------------------------------------------------------ round trips


def round_trip(mesh: Mesh, tmp_path: Path) -> Mesh:
    path = tmp_path / "m.obj"
    write_obj(mesh, path)
    again = load_quietly(path)
    validate(again)
    return again


def assert_same_mesh(a: Mesh, b: Mesh) -> None:
    assert a.counts() == b.counts()
    assert genus(a) == genus(b)
    assert np.array_equal(a.positions_view(), b.positions_view())
    assert [a.face_vertices(f) for f in a.face_ids()] == [b.face_vertices(f) for f in b.face_ids()]
    assert [a.is_hole(f) for f in a.face_ids()] == [b.is_hole(f) for f in b.face_ids()]


@pytest.mark.parametrize("name", ["cube.obj", "soccerballdual.obj", "genus3hexa1.obj",
                                  "beveledcube.obj", "donuthexa1.obj"])
def test_sample_round_trip(name: str, tmp_path: Path, topmod_samples: Path) -> None:
    mesh = load_quietly(topmod_samples / name)
    assert_same_mesh(mesh, round_trip(mesh, tmp_path))


def test_round_trip_keeps_holes_as_boundaries_and_point_spheres(tmp_path: Path) -> None:
    mesh = read_obj(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.1 0.2 0.3\nf 1 2 3 4\n")
    text = obj_bytes(mesh).decode()
    assert text.count("\nf ") == 1
    assert_same_mesh(mesh, round_trip(mesh, tmp_path))


def test_round_trip_of_random_positions_is_exact(tmp_path: Path) -> None:
    rng = np.random.default_rng(7)
    positions = rng.standard_normal((40, 3)) * 10.0 ** rng.integers(-9, 17, (40, 3))
    positions[0] = [0.0, -0.0, 1e-300]
    positions[1] = [np.pi, -1e15, 5e-324]
    mesh = from_polygons(positions, [[0, 1, 2], [0, 2, 1]])
    again = round_trip(mesh, tmp_path)
    assert np.array_equal(again.positions_view(), positions)
    assert np.array_equal(np.signbit(again.positions_view()), np.signbit(positions))


def test_a_file_of_many_pieces_is_written_whole_and_reads_back(tmp_path: Path) -> None:
    from livemod.dlfl.io.obj import _LINES_PER_PASS

    # a strip of quads longer than one writer piece, so write_obj streams several
    n = _LINES_PER_PASS // 2 + 7
    x = np.arange(n + 1, dtype=np.float64) / 3.0
    positions = np.concatenate([np.stack([x, 0 * x, -x], 1), np.stack([x, 1 + 0 * x, x], 1)])
    k = np.arange(n)
    mesh = from_polygons(positions, np.stack([k, k + 1, k + n + 2, k + n + 1], 1))
    path = tmp_path / "strip.obj"
    write_obj(mesh, path)
    assert path.read_bytes() == obj_bytes(mesh)
    again = read_obj(path)
    validate(again)
    assert again.counts() == mesh.counts()
    assert np.array_equal(again.positions_view(), positions)


def test_thesis_load_and_save_commands_use_io(tmp_path: Path) -> None:
    from livemod.dlfl import commands
    from livemod.dlfl.scene import Scene, use_scene

    path = tmp_path / "cube.obj"
    path.write_bytes(CUBE)
    with use_scene(Scene()):
        commands.load(str(path))
        assert commands.save(str(tmp_path / "out.dlfl"))
    assert load_mesh(tmp_path / "out.dlfl").counts() == (8, 12, 6)


# -------------------------------------------------------------- numbers


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(allow_nan=False, allow_infinity=False), min_size=1, max_size=50))
def test_float_text_parses_back_to_the_same_bits(values: list[float]) -> None:
    x = np.array(values, dtype=np.float64)
    cells = format_floats(x)
    texts = [bytes(row[row != 0]) for row in cells]
    back = np.array([float(t) for t in texts])
    assert np.array_equal(back.view(np.int64), x.view(np.int64))
    assert all(b"e" not in t for t, v in zip(texts, x, strict=True) if 1e-6 <= abs(v) < 1e15)
    for text, value in zip(texts, x.tolist(), strict=True):
        ours, shortest = _significant(text), _significant(repr(value).encode())
        # 15 digits whenever some 15 suffice: then they are the shortest's
        assert ours == shortest if len(shortest) <= 15 else len(ours) <= 17


def _significant(text: bytes) -> bytes:
    """The significant digits of a decimal (no sign, point, exponent or outer zeros)."""
    mantissa = text.lower().split(b"e")[0].lstrip(b"-")
    return mantissa.replace(b".", b"").strip(b"0")


def test_chunk_tables_hold_the_text_of_every_chunk() -> None:
    def table(text_of) -> list[bytes]:
        return [text_of(i).ljust(4, b"\0") for i in range(10000)]

    def lead(i: int) -> bytes:
        return str(i).rjust(4, "\0").encode() if i else b""

    def as_text(chunks: np.ndarray) -> list[bytes]:
        return [bytes(row) for row in chunks.view(np.uint8).reshape(-1, 4)]

    assert as_text(_numtext._FULL) == table(lambda i: f"{i:04d}".encode())
    assert as_text(_numtext._LEAD) == table(lead)
    assert as_text(_numtext._UNITS) == table(lambda i: lead(i) or b"\0\0\0" b"0")
    assert as_text(_numtext._TRAIL) == table(lambda i: f"{i:04d}".rstrip("0").encode())


def test_float_text_forms() -> None:
    x = np.array([0.0, -0.0, 1.0, -2.5, 0.1, 1e-6, 1.5e-6, 123456.0, 1e15, 1e-7, 2**0.5, -1e14])
    texts = [bytes(row[row != 0]) for row in format_floats(x)]
    assert texts == [b"0", b"-0.0", b"1", b"-2.5", b"0.1", b"0.000001", b"0.0000015",
                     b"123456", b"1000000000000000.0", b"1e-07", b"1.4142135623730951", b"-100000000000000"]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 2**62 - 1), st.integers(0, 18)), min_size=1, max_size=50))
def test_decimal_to_float_is_correctly_rounded(pairs: list[tuple[int, int]]) -> None:
    mantissa = np.array([m for m, _ in pairs], dtype=np.int64)
    frac = np.array([k for _, k in pairs], dtype=np.int64)
    values, decided = decimal_to_float(mantissa, frac)
    expected = np.array([float(f"{m}e-{k}") for m, k in pairs])
    assert np.array_equal(values[decided], expected[decided])


def test_uint_text() -> None:
    cells = format_uints(np.array([0, 7, 10, 99999, 1234567890123]))
    assert [bytes(r[r != 0]) for r in cells] == [b"0", b"7", b"10", b"99999", b"1234567890123"]


# -- face colours as materials ----------------------------------------------------

def test_colours_round_trip_through_the_material_library(tmp_path: Path) -> None:
    mesh = coloured_cube()
    write_obj(mesh, tmp_path / "c.obj")
    text = (tmp_path / "c.obj").read_text()
    assert text.splitlines()[1] == "mtllib c.mtl"
    assert text.count("usemtl") == 5  # red, green, blue-ish, red again, the default run
    back = read_obj(tmp_path / "c.obj")
    validate(back)
    np.testing.assert_array_equal(back.face_colors(), expected_written_colors(mesh))


def test_trimesh_reads_the_materials_colours(tmp_path: Path) -> None:
    import trimesh

    mesh = coloured_cube()
    write_obj(mesh, tmp_path / "c.obj")
    peer = trimesh.load(tmp_path / "c.obj", process=False, group_material=False)
    kd = {tuple(np.round(np.asarray(g.visual.material.diffuse[:3]) / 255, 3))
          for g in peer.geometry.values()}
    expected = {tuple(np.round(row, 3)) for row in expected_written_colors(mesh).tolist()}
    assert kd == expected


def test_a_missing_library_is_a_warning_and_leaves_no_colour(tmp_path: Path) -> None:
    write_obj(coloured_cube(), tmp_path / "c.obj")
    (tmp_path / "c.mtl").unlink()
    with pytest.warns(DLFLRepairWarning, match="material library 'c.mtl' not found"):
        back = read_obj(tmp_path / "c.obj")
    assert back.face_colors() is None and back.counts() == (8, 12, 6)
    assert any("c.mtl" in note for note in back.notes)


def test_the_library_is_found_beside_the_obj_not_in_the_working_folder(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    (tmp_path / "sub").mkdir()
    write_obj(coloured_cube(), tmp_path / "sub" / "c.obj")
    monkeypatch.chdir(tmp_path)
    assert read_obj(Path("sub") / "c.obj").face_color(2) == CUBE_FACE_COLORS[2]


def test_an_obj_without_colours_names_no_library(tmp_path: Path) -> None:
    write_obj(cube(), tmp_path / "c.obj")
    assert not (tmp_path / "c.mtl").exists()
    assert b"mtllib" not in (tmp_path / "c.obj").read_bytes()


# -- a lone CR ends a line, also a continued one, and counts in line numbers


@pytest.mark.parametrize("fast", [True, False])
@pytest.mark.parametrize("line", [2, 8, 9, 13])  # after v, the last v, an f, the last but one f
def test_obj_lone_cr_ends_a_line(fast, line):
    data = lone_cr_after_line(UNIT_CUBE_OBJ, line)
    soup = parse_obj(data, fast=fast)
    reference = parse_obj(UNIT_CUBE_OBJ, fast=fast)
    np.testing.assert_array_equal(soup.positions, reference.positions)
    np.testing.assert_array_equal(soup.indices, reference.indices)
    mesh = read_obj(data)
    validate(mesh)
    assert mesh.counts() == (8, 12, 6)


def test_obj_lone_cr_counts_in_line_numbers():
    data = lone_cr_after_line(UNIT_CUBE_OBJ, 2).replace(b"f 2 3 7 6", b"f 2 3 7 x")
    with pytest.raises(FileFormatError, match=r"^<obj>:12: bad vertex index 'x'"):
        read_obj(data)


def test_obj_lone_cr_ends_a_continued_line():
    data = b"v 0 0 0\nv 1 0 0\rv 0 1 0\nf 1 \\\r2 3\n"
    mesh = read_obj(data)
    assert mesh.counts() == (3, 3, 2)


# -- a backslash continues a line; CR-only line endings

UNIT_CUBE_VERTICES = UNIT_CUBE_OBJ[: UNIT_CUBE_OBJ.index(b"f ")]  # its eight "v" lines

@pytest.mark.parametrize("fast", [True, False])
@pytest.mark.parametrize("newline", [b"\n", b"\r\n"])
def test_obj_backslash_continues_a_line(fast: bool, newline: bytes) -> None:
    data = (UNIT_CUBE_VERTICES + b"f 1 4 \\\n    3 2\nv 0 0 \\\n 2\nf 1 2 -1\n").replace(b"\n", newline)
    soup = parse_obj(data, "c.obj", fast=fast)
    assert soup.offsets.tolist() == [0, 4, 7]
    assert soup.indices.tolist() == [0, 3, 2, 1, 0, 1, 8]
    assert soup.positions[8].tolist() == [0.0, 0.0, 2.0]
    assert soup.face_lines.tolist() == [9, 13]  # a joined line keeps its first line's number


def test_obj_continued_lines_keep_later_line_numbers() -> None:
    data = UNIT_CUBE_VERTICES + b"f 1 2 \\\n 3\nf 1 2 x\n"
    with pytest.raises(FileFormatError, match=r"^c\.obj:11: bad vertex index 'x'"):
        parse_obj(data, "c.obj")


@pytest.mark.parametrize("fast", [True, False])
def test_obj_with_cr_line_endings_reads_every_line(fast: bool) -> None:
    soup = parse_obj(UNIT_CUBE_OBJ.replace(b"\n", b"\r"), "mac.obj", fast=fast)
    assert len(soup.positions) == 8 and len(soup.offsets) == 7
