"""The PLY reader (livemod.dlfl.io.ply.read_ply): round trips, the formats and
types it accepts, skipped elements, the row-by-row fallback, errors, fuzzing."""

from __future__ import annotations

import struct
import tracemalloc
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from livemod.dlfl import (
    DLFLError,
    DLFLRepairWarning,
    FileFormatError,
    InvalidArgumentError,
    Mesh,
    NonManifoldError,
    from_polygons,
    genus,
    validate,
)
from livemod.dlfl.io.ply import parse_ply, ply_bytes, read_ply
from tests.io_inputs import lone_cr_after_line
from tests.meshes import CUBE_FACES, CUBE_POSITIONS, cube, torus, torus_polygons
from tests.test_io_fuzz import edit_lists, mutate, only_dlfl_errors


def faces_of(mesh: Mesh) -> list[list[int]]:
    return [mesh.face_vertices(f) for f in mesh.face_ids()]


def assert_same_mesh(a: Mesh, b: Mesh) -> None:
    validate(b)
    assert a.counts() == b.counts()
    assert genus(a) == genus(b)
    assert a.positions_view().tobytes() == b.positions_view().tobytes()  # bit for bit
    assert faces_of(a) == faces_of(b)
    assert [a.is_hole(f) for f in a.face_ids()] == [b.is_hole(f) for f in b.face_ids()]


def open_box() -> Mesh:
    """The cube without its top (one hole)."""
    return from_polygons(CUBE_POSITIONS, [f for i, f in enumerate(CUBE_FACES) if i != 1])


def cube_and_a_point() -> Mesh:
    """The cube plus an unused vertex, which becomes a point-sphere."""
    positions = np.concatenate([CUBE_POSITIONS, [[0.1, 0.2, 1e-300]]])
    return from_polygons(positions, CUBE_FACES)


def disk(corners: int = 300) -> Mesh:
    """Two faces of ``corners`` corners glued along their rim."""
    angles = np.linspace(0, 2 * np.pi, corners, endpoint=False)
    ring = np.stack([np.cos(angles), np.sin(angles), 0 * angles], axis=1)
    return from_polygons(ring, [list(range(corners)), list(range(corners - 1, -1, -1))])


def binary_ply(header: str, order: str, rows: list[tuple[str, tuple[float, ...]]]) -> bytes:
    """A binary PLY: ``header`` (element and property lines) and rows packed by
    struct formats (without the byte order mark, which is ``order``)."""
    encoding = "binary_little_endian" if order == "<" else "binary_big_endian"
    text = f"ply\nformat {encoding} 1.0\n{header.strip()}\nend_header\n".encode()
    return text + b"".join(struct.pack(order + fmt, *values) for fmt, values in rows)


def ascii_ply(header: str, rows: list[str], newline: str = "\n") -> bytes:
    lines = ["ply", "format ascii 1.0", *header.strip().splitlines(), "end_header", *rows]
    return (newline.join(lines) + newline).encode()


def quiet_read(data: bytes) -> Mesh:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DLFLRepairWarning)
        return read_ply(data)


XYZ = "property double x\nproperty double y\nproperty double z\n"
TRIANGLE_FACES = "property list uchar int vertex_indices\n"
# a cube cut into a triangle and a quad... no: two triangles and four quads
MIXED_FACES = [[0, 3, 2], [0, 2, 1], *CUBE_FACES[1:]]


def cube_binary(order: str = "<") -> bytes:
    header = f"element vertex 8\n{XYZ}element face 6\n{TRIANGLE_FACES}"
    rows = [("ddd", tuple(p)) for p in CUBE_POSITIONS.tolist()]
    rows += [("B4i", (4, *f)) for f in CUBE_FACES]
    return binary_ply(header, order, rows)


def mixed_binary() -> bytes:
    header = f"element vertex 8\n{XYZ}element face 7\n{TRIANGLE_FACES}"
    rows = [("ddd", tuple(p)) for p in CUBE_POSITIONS.tolist()]
    rows += [(f"B{len(f)}i", (len(f), *f)) for f in MIXED_FACES]
    return binary_ply(header, "<", rows)


def ascii_of(mesh: Mesh) -> bytes:
    """``mesh`` as ASCII PLY, coordinates as ``repr`` (which parses back exactly)."""
    soup = parse_ply(ply_bytes(mesh))
    rows = [" ".join(map(repr, p)) for p in soup.positions.tolist()]
    faces = [f.tolist() for f in np.split(soup.indices, soup.offsets[1:-1])]
    rows += [" ".join(map(str, [len(f), *f])) for f in faces]
    header = f"element vertex {len(soup.positions)}\n{XYZ}element face {len(soup.offsets) - 1}\n"
    return ascii_ply(header + TRIANGLE_FACES, rows)


def mixed_ascii() -> bytes:
    rows = [" ".join(map(repr, p)) for p in CUBE_POSITIONS.tolist()]
    rows += [" ".join(map(str, [len(f), *f])) for f in MIXED_FACES]
    return ascii_ply(f"element vertex 8\n{XYZ}element face 7\n{TRIANGLE_FACES}", rows)


# ------------------------------------------------------------------ round trips


@pytest.mark.parametrize("make", [cube, lambda: torus(5, 4), open_box, cube_and_a_point, disk],
                         ids=["cube", "torus", "open box", "point-sphere", "300-gon"])
def test_round_trip_through_ply_bytes(make) -> None:  # type: ignore[no-untyped-def]
    mesh = make()
    assert_same_mesh(mesh, read_ply(ply_bytes(mesh)))


def test_round_trip_counts_and_genus_of_the_samples() -> None:
    assert genus(read_ply(ply_bytes(torus(5, 4)))) == 1
    again = read_ply(ply_bytes(open_box()))
    assert again.counts() == (8, 12, 6)
    assert [again.is_hole(f) for f in again.face_ids()] == [False] * 5 + [True]
    assert read_ply(ply_bytes(cube_and_a_point())).is_point_sphere(8)
    assert b"list uint int" in ply_bytes(disk())


def test_round_trip_of_random_positions_is_exact() -> None:
    rng = np.random.default_rng(5)
    positions = rng.standard_normal((30, 3)) * 10.0 ** rng.integers(-300, 300, (30, 3))
    positions[0] = [-0.0, 5e-324, np.pi]
    mesh = from_polygons(positions, [[0, 1, 2], [0, 2, 1]])
    again = read_ply(ply_bytes(mesh))
    assert np.array_equal(again.positions_view(), positions)
    assert np.array_equal(np.signbit(again.positions_view()), np.signbit(positions))


def test_a_path_and_a_name_are_used_in_messages(tmp_path: Path) -> None:
    path = tmp_path / "model.ply"
    path.write_bytes(ply_bytes(cube()))
    assert read_ply(path).counts() == (8, 12, 6)
    path.write_bytes(b"ply\nformat ascii 1.0\nend_header\n")
    with pytest.raises(FileFormatError, match=r"model\.ply:3: no 'vertex' element"):
        read_ply(path)
    with pytest.raises(FileFormatError, match=r"^other\.ply:3: no 'vertex'"):
        read_ply(path, name="other.ply")
    with pytest.raises(OSError):
        read_ply(tmp_path / "missing.ply")


# ------------------------------------------------------------ what is accepted


def test_ascii_cube_with_colors_normals_face_properties_and_edges() -> None:
    header = """comment made by hand
obj_info anything at all
element vertex 8
property float x
property float nx
property float y
property float ny
property float z
property float nz
property uchar red
property uchar green
property uchar blue
element face 6
property uchar intensity
property list uchar int vertex_indices
property float quality
element edge 3
property int vertex1
property int vertex2
property list uchar float weights
"""
    rows = [f"{x} 0.5 {y} -1 {z} 1e3 255 0 {i}" for i, (x, y, z) in
            enumerate(CUBE_POSITIONS.tolist())]
    rows += [f"7 4 {' '.join(map(str, f))} 0.25" for f in CUBE_FACES]
    rows += ["0 1 2 0.5 0.5", "1 2 0", "2 3 3 1 2 3"]
    for newline in ("\n", "\r\n"):
        mesh = read_ply(ascii_ply(header, rows, newline))
        assert_same_mesh(cube(), mesh)


def test_ascii_rows_need_not_be_lines() -> None:
    body = " ".join(" ".join(map(str, p)) for p in CUBE_POSITIONS.tolist())
    body += "\n\n" + "\t".join(" ".join(map(str, [4, *f])) for f in CUBE_FACES)
    data = ascii_ply(f"element vertex 8\n{XYZ}element face 6\n{TRIANGLE_FACES}", [body])
    assert_same_mesh(cube(), read_ply(data))


def test_big_endian_float32_uchar_and_ushort_types() -> None:
    header = """element vertex 8
property uchar flags
property float x
property float y
property float z
property ushort id
element material 2
property list ushort uchar name
property short shininess
element face 6
property list ushort ushort vertex_index
"""
    rows = [("BfffH", (1, *p, i)) for i, p in enumerate(CUBE_POSITIONS.tolist())]
    rows += [("H3Bh", (3, 65, 66, 67, -5)), ("H1Bh", (1, 68, 7))]  # lists of two lengths
    rows += [("H4H", (4, *f)) for f in CUBE_FACES]
    for order in "<>":
        assert_same_mesh(cube(), read_ply(binary_ply(header, order, rows)))


def test_big_endian_doubles_and_every_integer_type_for_positions() -> None:
    assert_same_mesh(cube(), read_ply(cube_binary(">")))
    for ply_type, fmt in [("char", "b"), ("uchar", "B"), ("short", "h"), ("ushort", "H"),
                          ("int32", "i"), ("uint32", "I"), ("float64", "d"), ("int8", "b")]:
        header = (f"element vertex 8\nproperty {ply_type} x\nproperty {ply_type} y\n"
                  f"property {ply_type} z\nelement face 6\nproperty list uint8 uint vertex_indices\n")
        rows = [(3 * fmt, tuple(int(c) for c in p)) for p in CUBE_POSITIONS.tolist()]
        rows += [("B4I", (4, *f)) for f in CUBE_FACES]
        assert_same_mesh(cube(), read_ply(binary_ply(header, ">", rows)))


@pytest.mark.parametrize("data", [mixed_binary(), mixed_ascii()], ids=["binary", "ascii"])
def test_mixed_face_sizes_go_row_by_row(data: bytes) -> None:
    mesh = read_ply(data)
    validate(mesh)
    assert faces_of(mesh) == MIXED_FACES
    assert mesh.counts() == (8, 13, 7)


def test_skipped_elements_with_lists_of_varying_length_before_and_after_faces() -> None:
    header = f"""element vertex 8
{XYZ}element texture 3
property list uchar float uv
property list int char tag
element face 7
property list uchar float texcoord
{TRIANGLE_FACES}element tail 2
property list uint double stuff
"""
    rows = [("ddd", tuple(p)) for p in CUBE_POSITIONS.tolist()]
    rows += [("B2fi1b", (2, 0.5, 0.5, 1, 9)), ("B0fi0b", (0, 0)), ("B1fi3b", (1, 1.0, 3, 1, 2, 3))]
    rows += [(f"B2fB{len(f)}i", (2, 0.0, 1.0, len(f), *f)) for f in MIXED_FACES]
    rows += [("I1d", (1, 2.0)), ("I", (0,))]
    mesh = read_ply(binary_ply(header, ">", rows))
    assert faces_of(mesh) == MIXED_FACES
    text_rows = [" ".join(map(str, p)) for p in CUBE_POSITIONS.tolist()]
    text_rows += ["2 0.5 0.5 1 9", "0 0", "1 1 3 1 2 3"]
    text_rows += [f"2 0 1 {len(f)} {' '.join(map(str, f))}" for f in MIXED_FACES]
    text_rows += ["1 2.0", "0"]
    assert faces_of(read_ply(ascii_ply(header, text_rows))) == MIXED_FACES


def test_face_list_names_and_float_indices() -> None:
    rows = [("ddd", tuple(p)) for p in CUBE_POSITIONS.tolist()]
    first_list = "property list uchar int corners\n"
    header = f"element vertex 8\n{XYZ}element face 6\nproperty int id\n{first_list}"
    data = binary_ply(header, "<", rows + [("iB4i", (9, 4, *f)) for f in CUBE_FACES])
    assert_same_mesh(cube(), read_ply(data))
    header = (f"element vertex 8\n{XYZ}element face 6\nproperty list uchar int other\n"
              "property list uchar double vertex_indices\n")
    data = binary_ply(header, "<", rows + [("B1iB4d", (1, 0, 4, *f)) for f in CUBE_FACES])
    assert_same_mesh(cube(), read_ply(data))


def test_point_clouds_and_empty_files() -> None:
    rows = [("ddd", tuple(p)) for p in CUBE_POSITIONS.tolist()]
    no_faces = binary_ply(f"element vertex 8\n{XYZ}", "<", rows)
    no_rows = binary_ply(f"element vertex 8\n{XYZ}element face 0\n{TRIANGLE_FACES}", "<", rows)
    for data in (no_faces, no_rows, ply_bytes(Mesh()) + b"trailing bytes are ignored"):
        mesh = read_ply(data)
        validate(mesh)
        assert all(mesh.is_point_sphere(v) for v in mesh.vertex_ids())
        assert np.array_equal(mesh.positions_view(), CUBE_POSITIONS[: len(mesh.vertex_ids())])
    assert read_ply(ply_bytes(Mesh())).counts() == (0, 0, 0)
    assert parse_ply(no_faces).offsets.tolist() == [0]


def walked(self, element, wanted):  # type: ignore[no-untyped-def]
    """:meth:`_BinaryBody.element` without its one-layout path."""
    self._check_room(element)
    starts, counts, self.pos = self._walk(element, element.count)
    return self._walked_table(element, starts, counts, wanted)


@pytest.mark.parametrize("make", [lambda: ply_bytes(torus(6, 5)), lambda: cube_binary(">"),
                                  mixed_binary, lambda: ascii_of(torus(6, 5)), mixed_ascii],
                         ids=["binary torus", "big-endian cube", "binary mixed", "ascii torus",
                              "ascii mixed"])
def test_the_one_layout_and_the_row_by_row_paths_agree(
    make, monkeypatch: pytest.MonkeyPatch  # type: ignore[no-untyped-def]
) -> None:
    from livemod.dlfl.io import _ply_ascii, ply

    monkeypatch.setattr(_ply_ascii, "_LINE_PATH_MIN_BYTES", 0)  # small files too
    data = make()
    fast = parse_ply(data)  # ASCII: the line path
    monkeypatch.setattr(ply._AsciiBody, "_line_table", lambda *args: None)
    tokens = parse_ply(data)  # ASCII: the token path's one layout
    monkeypatch.setattr(ply._BinaryBody, "element", walked)
    monkeypatch.setattr(ply._AsciiBody, "_uniform", lambda *args: False)
    slow = parse_ply(data)
    for other in (tokens, slow):
        assert fast.positions.tobytes() == other.positions.tobytes()
        assert np.array_equal(fast.indices, other.indices)
        assert np.array_equal(fast.offsets, other.offsets)


def test_ascii_and_binary_files_of_one_mesh_read_the_same() -> None:
    mesh = torus(6, 5)
    assert_same_mesh(read_ply(ply_bytes(mesh)), read_ply(ascii_of(mesh)))


# ------------------------------------------------------------------ errors

V8 = f"element vertex 8\n{XYZ}"
CUBE_ROWS = [" ".join(map(str, p)) for p in CUBE_POSITIONS.tolist()]
FACE_ROWS = [" ".join(map(str, [4, *f])) for f in CUBE_FACES]
ASCII_CUBE = ascii_ply(f"{V8}element face 6\n{TRIANGLE_FACES}", CUBE_ROWS + FACE_ROWS)


def ascii_cube_with(row: int, text: str) -> bytes:
    rows = CUBE_ROWS + FACE_ROWS
    rows[row] = text
    return ascii_ply(f"{V8}element face 6\n{TRIANGLE_FACES}", rows)


def twenty_triangles_cut_in_row_12() -> bytes:
    header = f"{V8}element face 20\n{TRIANGLE_FACES}"
    rows = [("ddd", tuple(p)) for p in CUBE_POSITIONS.tolist()]
    data = binary_ply(header, "<", rows + [("B3i", (3, 0, 1, 2))] * 20)
    return data[: len(data) - 8 * 13 - 5]


def binary_cube_with(fmt: str, values: tuple[float, ...], list_type: str = "uchar int") -> bytes:
    rows = [("ddd", tuple(p)) for p in CUBE_POSITIONS.tolist()]
    rows[3] = (fmt, values) if fmt.startswith("d") else rows[3]
    faces = [(fmt, values)] if not fmt.startswith("d") else []
    faces += [("B4i", (4, *f)) for f in CUBE_FACES[len(faces):]]
    header = f"{V8}element face 6\nproperty list {list_type} vertex_indices\n"
    return binary_ply(header, "<", rows + faces)


@pytest.mark.parametrize(("data", "message"), [
    (b"", r"^model\.ply:1: not a PLY file \(the first line is not 'ply'\)$"),
    (b"PLY\nformat ascii 1.0\n", r"not a PLY file"),
    (b"ply\n", r"^model\.ply:1: header: no end_header line$"),
    (b"ply\nelement vertex 0\nend_header\n", r"^model\.ply:3: header: no format line$"),
    (b"ply\nformat ascii 2.0\nend_header\n", r"header: unsupported format 'ascii 2\.0'"),
    (b"ply\nformat binary 1.0\nend_header\n", r"header: unsupported format 'binary 1\.0'"),
    (b"ply\nformat ascii 1.0\nformat ascii 1.0\nend_header\n", r"header: a second format line"),
    (b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float128 x\nend_header\n",
     r"^model\.ply:4: header: unknown property type 'float128'$"),
    (b"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int128 v\nend_header\n",
     r"header: unknown property type 'int128'"),
    (b"ply\nformat ascii 1.0\nelement face 1\nproperty list float int v\nend_header\n",
     r"header: list count type 'float' is not an integer type"),
    (b"ply\nformat ascii 1.0\nelement face 1\nproperty list uchar int\nend_header\n",
     r"header: bad property line 'property list uchar int'"),
    (b"ply\nformat ascii 1.0\nproperty float x\nend_header\n",
     r"header: a property line before any element line"),
    (b"ply\nformat ascii 1.0\nelement vertex -1\nend_header\n",
     r"header: bad element line 'element vertex -1'"),
    (b"ply\nformat ascii 1.0\nelement vertex 1e3\nend_header\n", r"header: bad element line"),
    (b"ply\nformat ascii 1.0\nelement vertex 0\nelement vertex 0\nend_header\n",
     r"header: a second element 'vertex'"),
    (b"ply\nformat ascii 1.0\nelemnt vertex 0\nend_header\n",
     r"header: unknown line 'elemnt vertex 0'"),
    (b"ply\r\nformat ascii 1.0\r\nelement face 0\r\nend_header\r\n",
     r"^model\.ply:4: no 'vertex' element before end_header$"),
    (ascii_ply("element vertex 0\nproperty float x\nproperty float y\n", []),
     r"^model\.ply:3: element 'vertex' has no property 'z'$"),
    (ascii_ply("element vertex 0\nproperty list uchar float x\nproperty float y\n"
               "property float z\n", []), r"element 'vertex' has no property 'x'"),
    (ascii_ply(f"{V8}element face 0\nproperty int vertex_indices\n", CUBE_ROWS),
     r"^model\.ply:7: element 'face' has no list property \(vertex_indices\)$"),
    (twenty_triangles_cut_in_row_12(),
     r"^model\.ply: the file ends inside element 'face' \(row 12 of 20\)$"),
    (ply_bytes(cube())[:-10], r"the file ends inside element 'face' \(row 6 of 6\)"),
    (ply_bytes(cube())[: ply_bytes(cube()).index(b"end_header\n") + 11 + 34], r"the file ends inside element 'vertex' \(row 2 of 8\)"),
    (ASCII_CUBE[:-4], r"the file ends inside element 'face' \(row 6 of 6\)"),
    (ascii_ply(f"{V8}", CUBE_ROWS[:7] + ["1 1"]),
     r"the file ends inside element 'vertex' \(row 8 of 8\)"),
    (binary_ply(f"element vertex 99999999999\n{XYZ}", "<", [("ddd", (0, 0, 0))] * 5),
     r"the file ends inside element 'vertex' \(row 6 of 99999999999\)"),
    (binary_ply(f"element vertex 0\n{XYZ}element face 99999999999\n{TRIANGLE_FACES}", "<",
                [("B3i", (3, 0, 1, 2))] * 2),
     r"^model\.ply:7: element 'face' has 99999999999 rows, more than the 26 bytes left in "
     r"the file can hold$"),
    (ascii_ply(f"element vertex 99999999999\n{XYZ}", ["0 0 0"]),
     r"the file ends inside element 'vertex' \(row 2 of 99999999999\)"),
    (ascii_ply(f"{V8}element face 99999999999\n{TRIANGLE_FACES}", CUBE_ROWS + FACE_ROWS),
     r"element 'face' has 99999999999 rows, more than the 30 numbers left in the file"),
    (ascii_cube_with(8 + 5, "4 0 1 99 4"),
     r"^model\.ply:23: face 5: vertex index 99 is out of range \(8 vertices\)$"),
    (ascii_cube_with(8 + 4, "4 0 1 -1 4"), r"face 4: vertex index -1 is out of range"),
    (ascii_cube_with(8 + 2, "4 0 1 2.5 4"), r"face 2: vertex index 2.5 is not a whole number"),
    (ascii_cube_with(8 + 2, "4 0 1 nan 4"), r"face 2: vertex index nan is not a whole number"),
    (ascii_cube_with(8 + 2, "4 0 1 inf 4"), r"face 2: vertex index inf is not a whole number"),
    (ascii_cube_with(3, "0 nan 0"), r"^model\.ply:13: vertex 3: coordinate nan is not finite$"),
    (ascii_cube_with(7, "0 0 -1e999"), r"vertex 7: coordinate -inf is not finite"),
    (ascii_cube_with(3, "0 abc 0"), r"^model\.ply:13: element 'vertex': bad number 'abc'$"),
    (ascii_cube_with(3, "0 1_0 0"), r"element 'vertex': bad number '1_0'"),
    (ascii_cube_with(3, "0 \xd9\xa1 0"), r"element 'vertex': bad number"),
    (ascii_cube_with(8 + 1, "four 0 1 2 3"), r"^model\.ply:19: face 1: bad number 'four'$"),
    (ascii_cube_with(8 + 1, "4 0 1 2 x"), r"element 'face': bad number 'x'"),
    (ascii_cube_with(8 + 0, "-1 0 1 2 3"),
     r"^model\.ply:18: face 0: list 'vertex_indices' has a negative count \(-1\)$"),
    (ascii_cube_with(8 + 4, "2.5 0 1 2 3"),
     r"^model\.ply:22: face 4: list 'vertex_indices' has count 2\.5, not a whole number$"),
    (binary_cube_with("ddd", (0.0, float("nan"), 0.0)), r"vertex 3: coordinate nan is not"),
    (binary_cube_with("ddd", (float("inf"), 0.0, 0.0)), r"vertex 3: coordinate inf is not"),
    (binary_cube_with("b4i", (-3, 0, 1, 2, 3), "char int"),
     r"^model\.ply: face 0: list 'vertex_indices' has a negative count \(-3\)$"),
    (binary_cube_with("B4i", (4, 0, 1, 2, 8)), r"face 0: vertex index 8 is out of range"),
    (binary_cube_with("B4f", (4, 0, 1, 2, 0.5), "uchar float"),
     r"face 0: vertex index 0\.5 is not a whole number"),
], ids=lambda value: "" if isinstance(value, bytes) else value.strip("^$")[:50])
def test_errors_name_the_file_and_what_is_wrong(data: bytes, message: str) -> None:
    with pytest.raises(FileFormatError, match=message):
        read_ply(data, name="model.ply")


# well-formed files whose polygons the builder refuses: not format errors, but
# the file's name still leads the message
@pytest.mark.parametrize(("data", "error", "message"), [
    (binary_cube_with("B0i", (0,)), InvalidArgumentError,
     r"^model\.ply: face 0 has no vertices$"),
    (ascii_ply(f"{V8}element face 3\n{TRIANGLE_FACES}", CUBE_ROWS + ["3 0 1 2"] * 3),
     NonManifoldError, r"^model\.ply: edge \(0, 1\) is used by 3 face sides"),
    (ascii_ply(f"{V8}element face 1\n{TRIANGLE_FACES}", CUBE_ROWS + ["3 0 0 1"]),
     InvalidArgumentError, r"face 0 visits vertex 0 twice in a row"),
], ids=["no vertices", "three sides", "twice in a row"])
def test_polygons_the_builder_refuses_name_the_file(data: bytes, error: type[Exception],
                                                    message: str) -> None:
    with pytest.raises(error, match=message):
        read_ply(data, name="model.ply")


def test_a_huge_declared_count_fails_before_anything_is_allocated() -> None:
    tracemalloc.start()  # numpy reports its buffers to tracemalloc too
    for count in (99999999999, 10**30 - 1):
        data = binary_ply(f"element vertex {count}\n{XYZ}", "<", [("ddd", (0, 0, 0))])
        with pytest.raises(FileFormatError, match="ends inside"):
            read_ply(data)
        data = binary_ply(f"element vertex 1\n{XYZ}element face {count}\n{TRIANGLE_FACES}",
                          "<", [("ddd", (0, 0, 0)), ("B3i", (3, 0, 0, 0))])
        with pytest.raises(FileFormatError, match="rows, more than"):
            read_ply(data)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert peak < 1_000_000


def test_elements_without_properties_take_no_room() -> None:
    data = cube_binary().replace(b"element face", b"element nothing 99999999999\nelement face")
    assert_same_mesh(cube(), read_ply(data))


# ------------------------------------------------------------------ fuzzing

FUZZ = settings(max_examples=80, deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
EMPTY_PLY = ply_bytes(Mesh()).replace(b"vertex 0", b"vertex 3")


def header_of(data: bytes) -> bytes:
    return data[: data.index(b"end_header\n") + len(b"end_header\n")]


HEADERS = [
    EMPTY_PLY.replace(b"face 0", b"face 2"),
    header_of(cube_binary(">")),
    header_of(ASCII_CUBE),
    EMPTY_PLY.replace(b"element face 0", b"element edge 2\nproperty list char short x\n"
                      b"property uchar y\nelement face 1"),
]
ASCII_ALPHABET = b"0123456789 -.\n\r\tenaif"
BASES = [cube_binary(), cube_binary(">"), mixed_binary(), mixed_ascii(), ASCII_CUBE,
         ply_bytes(torus(4, 3))]


@pytest.mark.timeout(60)
@FUZZ
@given(st.sampled_from(HEADERS), st.binary(max_size=300))
def test_random_bytes_after_a_valid_header(header: bytes, body: bytes) -> None:
    only_dlfl_errors(read_ply, header + body)


@pytest.mark.timeout(60)
@FUZZ
@given(st.sampled_from(HEADERS[1:3]),
       st.lists(st.sampled_from(list(ASCII_ALPHABET)), max_size=200).map(bytes))
def test_random_number_like_text_after_a_valid_header(header: bytes, body: bytes) -> None:
    only_dlfl_errors(read_ply, header + body)
    only_dlfl_errors(read_ply, header.replace(b"binary_big_endian", b"ascii") + body)


@pytest.mark.timeout(60)
@FUZZ
@given(st.sampled_from(BASES), st.integers(0, 2000), edit_lists)
def test_truncated_and_mutated_files(base: bytes, cut: int, edits: list[tuple[int, int, int]],
                                     ) -> None:
    only_dlfl_errors(read_ply, base[:cut])
    only_dlfl_errors(read_ply, mutate(base, edits))
    only_dlfl_errors(read_ply, mutate(base[:cut], edits))


def test_every_truncation_of_a_binary_and_an_ascii_file_is_refused_cleanly() -> None:
    for base in (mixed_binary(), ASCII_CUBE):
        for cut in range(len(base) - 1):
            with pytest.raises(FileFormatError):
                quiet_read(base[:cut])


# ------------------------------------------------------------- the ASCII line path
#
# An ASCII element laid out one row per line is parsed in blocks of lines (the
# line path); anything else, and every error, goes token by token (the token
# path). The two must agree bit for bit, errors included.


def outcome(data: bytes) -> tuple[bytes, bytes, bytes] | str:
    """What :func:`parse_ply` gives: the soup's bytes, or the error's message."""
    try:
        soup = parse_ply(data, "f.ply")
    except DLFLError as error:
        return str(error)
    return soup.positions.tobytes(), soup.indices.tobytes(), soup.offsets.tobytes()


def token_path_outcome(data: bytes) -> tuple[bytes, bytes, bytes] | str:
    """:func:`outcome` with the line path switched off."""
    from livemod.dlfl.io import _ply_ascii as ply

    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(ply._AsciiBody, "_line_table", lambda *args: None)
        return outcome(data)


def number_text(rng: np.random.Generator) -> str:
    """A coordinate in one of the forms writers use, or float() takes."""
    value = float(rng.standard_normal() * 10.0 ** rng.integers(-6, 7))
    style = int(rng.integers(12))
    texts = [
        repr(value), f"{value:.3f}", f"{value:.6E}", f"{value:+.5g}",  # 17 digits, +, E
        f"{value:.4f}".replace("0.", ".", 1),  # ".5", "-.5"
        f"{round(value)}.", str(round(value)),  # "5.", "5"
        f"{value:.25f}", str(rng.choice(["-0", "-0.0", "0", "+0"])),  # 25 digits, signed zeros
        repr(value * 1e300 if abs(value) < 1e6 else 5e-324), f"{value:.17e}", repr(value),
    ]
    return texts[style]


def index_text(rng: np.random.Generator, index: int) -> str:
    """A list count or vertex index, now and then in a form float() takes too."""
    forms = [str(index)] * 20 + [f"{index}.0", f"+{index}", f"0{index}", f"{index}e0"]
    return forms[int(rng.integers(len(forms)))]


def random_element(rng: np.random.Generator, name: str, vertices: int,
                   ) -> tuple[list[str], list[list[str]]]:
    """The header lines and rows (as tokens) of an element: ``vertex`` (x, y, z
    and extras in any order, maybe a list), ``face`` (maybe scalars around the
    list of indices below ``vertices``), ``edge`` (integers) or ``material`` (a
    list of floats)."""
    count = int(rng.integers(1, 30)) if name == "vertex" else int(rng.integers(0, 30))
    if name == "vertex":
        extras = ["float nx", "uchar red", "int flags"][: int(rng.integers(4))]
        props = [str(p) for p in rng.permutation(["double x", "float y", "double z", *extras])]
        if rng.random() < 0.2:
            props.insert(int(rng.integers(len(props) + 1)), "list uchar float uv")
    elif name == "face":
        props = ["uchar intensity"] * int(rng.random() < 0.3) + ["list uchar int vertex_indices"]
        props += ["float quality"] * int(rng.random() < 0.3)
    else:
        props = ["int a", "int b"] if name == "edge" else ["list uchar float values"]
    rows = [random_row(rng, props, vertices) for _ in range(count)]
    return [f"element {name} {count}", *(f"property {p}" for p in props)], rows


def random_row(rng: np.random.Generator, props: list[str], vertices: int) -> list[str]:
    row = []
    for prop in props:
        if prop.startswith("list"):
            size = int(rng.choice([3, 3, 3, 4, 4, 5, 6, 0, 1, 12]))
            row.append(index_text(rng, size))
            if prop.split()[2] == "int":
                row += [index_text(rng, int(i)) for i in rng.integers(0, vertices, size)]
            else:
                row += [number_text(rng) for _ in range(size)]
        elif prop.split()[0] in ("uchar", "int"):
            row.append(index_text(rng, int(rng.integers(0, 30))))
        else:
            row.append(number_text(rng))
    return row


def random_ascii_ply(seed: int) -> bytes:
    """A random ASCII PLY: mixed number forms and face sizes, extra properties and
    elements, CRLF, blank lines, odd blanks, and now and then rows not one per line."""
    rng = np.random.default_rng(seed)
    vertex = random_element(rng, "vertex", 0)
    elements = [vertex] + [random_element(rng, str(name), len(vertex[1])) for name in
                           ["face", *rng.choice(["edge", "material"], int(rng.integers(3)))]]
    elements = [elements[i] for i in rng.permutation(len(elements))]
    text = ["ply", "format ascii 1.0", *(line for e in elements for line in e[0]), "end_header"]
    for row in (row for e in elements for row in e[1]):
        blanks = rng.choice([" ", "  ", "\t", " \t "], len(row))
        line = "".join(b + t for b, t in zip(blanks, row, strict=True))
        text.append(line if rng.random() < 0.3 else line.lstrip())
        if rng.random() < 0.05:
            text.append(str(rng.choice(["", " \t", " "])))
    newline = "\r\n" if rng.random() < 0.4 else "\n"
    body = text.index("end_header") + 1
    if rng.random() < 0.15 and len(text) > body + 1:  # a row over two lines, or two on one
        k = int(rng.integers(body, len(text) - 1))
        if rng.random() < 0.5:
            text[k] = text[k].strip().replace(" ", newline, 1).replace("\t", newline, 1)
        else:
            text[k : k + 2] = [text[k] + " " + text[k + 1]]
    return (newline.join(text) + (newline if rng.random() < 0.8 else "")).encode()


def counting_line_tables(patch: pytest.MonkeyPatch) -> list[bool]:
    """Record, for every element the line path is asked for, whether it read it."""
    from livemod.dlfl.io import _ply_ascii as ply

    taken: list[bool] = []
    line_table = ply._AsciiBody._line_table

    def spy(self, element, wanted):  # type: ignore[no-untyped-def]
        table = line_table(self, element, wanted)
        taken.append(table is not None)
        return table

    patch.setattr(ply._AsciiBody, "_line_table", spy)
    return taken


def line_path_for_small_files(patch: pytest.MonkeyPatch, small_passes: bool = False) -> None:
    """Take the line path whatever the body's size; with ``small_passes``, in
    passes of 3 lines and scan slices of 16 bytes (many passes, on threads)."""
    from livemod.dlfl.io import _ply_ascii as ply

    patch.setattr(ply, "_LINE_PATH_MIN_BYTES", 0)
    if small_passes:
        patch.setattr(ply, "_LINES_PER_PASS", 3)
        patch.setattr(ply, "_BYTES_PER_SCAN", 16)


@pytest.mark.parametrize("passes", ["whole", "small"])
def test_the_line_and_token_paths_agree_on_random_files(
    passes: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    line_path_for_small_files(monkeypatch, passes == "small")
    taken = counting_line_tables(monkeypatch)
    for seed in range(60 if passes == "small" else 100):  # the small passes are slow
        data = random_ascii_ply(seed)
        fast = outcome(data)
        assert fast == token_path_outcome(data), seed
        assert not isinstance(fast, str), (seed, fast)  # the files are valid
    assert sum(taken) > 0.9 * len(taken)  # rows over two lines decline the rest


MUTATIONS = list(b"0123456789 -+.eE\n\r\t\v\x1c,_/xn#") + [0xD9, 0xA1]


@pytest.mark.timeout(60)
@FUZZ
@given(st.integers(0, 10**6), st.booleans(),
       st.lists(st.tuples(st.integers(0, 2), st.integers(0, 10**6), st.sampled_from(MUTATIONS)),
                min_size=1, max_size=4))
def test_the_line_and_token_paths_agree_on_mutated_files(
    seed: int, small: bool, edits: list[tuple[int, int, int]]
) -> None:
    data = random_ascii_ply(seed)
    body = data.index(b"end_header") + len(b"end_header")
    data = data[:body] + mutate(data[body:], edits)
    with pytest.MonkeyPatch.context() as patch:
        line_path_for_small_files(patch, small)
        assert outcome(data) == token_path_outcome(data)


def test_exporter_layouts_never_need_the_token_path(monkeypatch: pytest.MonkeyPatch) -> None:
    from livemod.dlfl.io import _ply_ascii as ply

    def refuse(*args):  # type: ignore[no-untyped-def]
        raise AssertionError("the token path ran")

    big = ascii_of(torus(60, 60))
    assert len(big) - len(header_of(big)) > ply._LINE_PATH_MIN_BYTES
    assert_same_mesh(cube(), read_ply(ASCII_CUBE))  # a small file: the token path
    monkeypatch.setattr(ply._AsciiBody, "_token_table", refuse)
    assert_same_mesh(torus(60, 60), read_ply(big))
    line_path_for_small_files(monkeypatch)
    ones, zeros = ["1", "+1", "1.", "1.0", "1e0", "10E-1", ".1e1"], ["0", "0.", ".0", "0e5", "+0"]
    header = f"element tag 2\nproperty int t\n{V8}property uchar red\nelement face 6\n" \
             f"property uchar intensity\n{TRIANGLE_FACES}property float quality\n"
    rows = ["abc", "x,y"]  # nobody wants the tags: they are not converted
    rows += [" ".join(ones[k % 7] if c else zeros[k % 5] for c in p) + "\t255 "
             for k, p in enumerate(CUBE_POSITIONS.tolist())]
    counts = ["4", "4.0", "+4", "04", "4e0", "4"]
    rows += [f" 7 {counts[k]} {' '.join(map(str, f))} 0.25" for k, f in enumerate(CUBE_FACES)]
    for newline in ("\n", "\r\n"):
        for blank in ("", " \t"):
            lines = [r for row in rows for r in (row, blank) if r or row is rows[3]]
            assert_same_mesh(cube(), read_ply(ascii_ply(header, lines, newline)))
    assert faces_of(read_ply(mixed_ascii().replace(b"\n", b"\r\n"))) == MIXED_FACES
    assert_same_mesh(torus(6, 5), read_ply(ascii_of(torus(6, 5))))


@pytest.mark.parametrize(("row", "text", "message"), [
    (3, "0, 1, 0", r"element 'vertex': bad number '0,'"),
    (3, "0,1,0", r"element 'vertex': bad number '0,1,0'"),
    (8 + 1, "4 0 1/1 2 3", r"element 'face': bad number '1/1'"),
    (8 + 1, "4, 0 1 2 3", r"face 1: bad number '4,'"),
    (8 + 5, "4 0 1 2 0x7", r"element 'face': bad number '0x7'"),
    (3, "0 1e999 0", r"vertex 3: coordinate inf is not finite"),
    (3, "0 -nan 0", r"vertex 3: coordinate nan is not finite"),
    (3, "0 0 1_0", r"element 'vertex': bad number '1_0'"),
])
def test_the_line_path_leaves_refusals_to_the_token_path(
    row: int, text: str, message: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    line_path_for_small_files(monkeypatch)
    data = ascii_cube_with(row, text)
    assert outcome(data) == token_path_outcome(data)
    with pytest.raises(FileFormatError, match=message):
        read_ply(data)


def test_integer_coordinates_keep_the_sign_of_minus_zero(monkeypatch: pytest.MonkeyPatch) -> None:
    line_path_for_small_files(monkeypatch)
    header = "element vertex 3\nproperty int x\nproperty int y\nproperty int z\n"
    data = ascii_ply(header, ["-0 1 2", "3 -4 -0", "5 6 7"])
    positions = parse_ply(data).positions
    assert positions.tolist() == [[0, 1, 2], [3, -4, 0], [5, 6, 7]]
    assert np.signbit(positions).tolist() == [[True, False, False], [False, True, True],
                                              [False] * 3]
    assert outcome(data) == token_path_outcome(data)


def test_faces_of_many_sizes_few_of_each(monkeypatch: pytest.MonkeyPatch) -> None:
    line_path_for_small_files(monkeypatch)
    rng = np.random.default_rng(3)
    sizes = np.where(rng.random(3000) < 0.995, 3, rng.integers(4, 200, 3000))
    rows = ["0 0 0"] * 200
    rows += [" ".join(map(str, [n, *rng.integers(0, 200, n)])) for n in sizes]
    data = ascii_ply(f"element vertex 200\n{XYZ}element face 3000\n{TRIANGLE_FACES}", rows)
    soup = parse_ply(data)
    assert np.diff(soup.offsets).tolist() == sizes.tolist()
    assert outcome(data) == token_path_outcome(data)


@pytest.mark.parametrize("count", [2**63, 2**64 + 5, 10**30])
def test_a_list_count_past_any_integer_type_ends_inside_the_element(count: int) -> None:
    data = ascii_ply(f"element vertex 3\n{XYZ}element face 1\n{TRIANGLE_FACES}",
                     ["0 0 0", "1 0 0", "0 1 0", f"{count} 0 1 2"])
    with pytest.raises(FileFormatError, match=r"the file ends inside element 'face' \(row 1 of 1\)"):
        read_ply(data)


# -- a lone CR ends a header line, the header, and an ASCII body row


@pytest.mark.parametrize("line", [1, 2, 4, 9])  # after ply, format, element, end_header-1
def test_ply_header_lone_cr_ends_a_line(line):
    data = ply_bytes(cube())
    assert data.split(b"\n")[line - 1] != b"end_header"
    mesh = read_ply(lone_cr_after_line(data, line))
    validate(mesh)
    assert mesh.counts() == (8, 12, 6)
    np.testing.assert_array_equal(mesh.positions_view(), cube().positions_view())


def test_ply_header_lone_cr_after_end_header_starts_the_body():
    data = ply_bytes(cube())
    end = data.index(b"end_header\n") + len(b"end_header")
    mesh = read_ply(data[:end] + b"\r" + data[end + 1 :])
    assert mesh.counts() == (8, 12, 6)


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
    read = read_ply(lone_cr_after_line(data, 500))
    assert read.counts() == (14400, 28800, 14400)
    np.testing.assert_array_equal(read.positions_view(), positions)
