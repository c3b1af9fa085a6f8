"""TopMod's .dlfl format (livemod.dlfl.io.dlflfile)."""

from __future__ import annotations

import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from livemod.dlfl import (
    DLFLError,
    DLFLSkippedLinesWarning,
    FileFormatError,
    Mesh,
    from_polygons,
    genus,
    mesh_arrays,
    validate,
)
from livemod.dlfl.analysis import face_normals
from livemod.dlfl.io import dlflfile, read_dlfl, read_obj, write_dlfl
from livemod.dlfl.io._dlfl_build import DlflRecords, build_dlfl
from livemod.dlfl.io._lines import leading_uints
from livemod.dlfl.io._numtext import format_floats, format_rounded
from livemod.dlfl.io.dlflfile import dlfl_bytes, parse_dlfl
from livemod.dlfl.shapes import donut_hexa
from tests.io_inputs import lone_cr_after_line
from tests.meshes import coloured_cube, expected_written_colors, torus, two_cubes
from tests.meshes import cube as unit_cube
from tests.topmod_samples import sample_bytes

# TOPMOD.md section 6, verbatim: TopMod's own writer output for its cube
TOPMOD_CUBE = b"""DLFL
mtllib cube.mtl
#
v 1 1 1
v 1 1 -1
v -1 1 -1
v -1 1 1
v 1 -1 1
v 1 -1 -1
v -1 -1 -1
v -1 -1 1
#
fv 0 [0 1 0] [0 0]
fv 1 [0 1 0] [0 0]
fv 2 [0 1 0] [0 0]
fv 3 [0 1 0] [0 0]
fv 4 [1 0 0] [0 0]
fv 5 [1 0 0] [0 0]
fv 1 [1 0 0] [0 0]
fv 0 [1 0 0] [0 0]
fv 5 [0 0 -1] [0 0]
fv 6 [0 0 -1] [0 0]
fv 2 [0 0 -1] [0 0]
fv 1 [0 0 -1] [0 0]
fv 6 [-1 0 0] [0 0]
fv 7 [-1 0 0] [0 0]
fv 3 [-1 0 0] [0 0]
fv 2 [-1 0 0] [0 0]
fv 7 [0 0 1] [0 0]
fv 4 [0 0 1] [0 0]
fv 0 [0 0 1] [0 0]
fv 3 [0 0 1] [0 0]
fv 7 [0 -1 0] [0 0]
fv 6 [0 -1 0] [0 0]
fv 5 [0 -1 0] [0 0]
fv 4 [0 -1 0] [0 0]
#
e 0 6
e 1 10
e 2 14
e 3 18
e 4 22
e 5 11
e 7 17
e 8 21
e 9 15
e 12 20
e 13 19
e 16 23
#
usemtl default
f 0 1 2 3
f 4 5 6 7
f 8 9 10 11
f 12 13 14 15
f 16 17 18 19
f 20 21 22 23
#
"""


def cube() -> Mesh:
    return read_dlfl(TOPMOD_CUBE)


def test_topmod_cube_example_loads_as_8_12_6() -> None:
    mesh = cube()
    validate(mesh)
    assert mesh.counts() == (8, 12, 6)
    assert genus(mesh) == 0
    assert mesh.face_vertices(0) == [0, 1, 2, 3]
    assert np.array_equal(mesh.position(6), [-1.0, -1.0, -1.0])


def test_bare_fv_lines_without_normals_load() -> None:
    bare = b"\n".join(
        line.split(b" [")[0] if line.startswith(b"fv") else line
        for line in TOPMOD_CUBE.split(b"\n")
    )
    assert b"fv 0\n" in bare
    mesh = read_dlfl(bare)
    validate(mesh)
    assert mesh.counts() == (8, 12, 6)


def test_writer_output_matches_topmod_layout(tmp_path: Path) -> None:
    path = tmp_path / "box.dlfl"
    write_dlfl(cube(), path)
    text = path.read_text()
    lines = text.split("\n")
    assert lines[:4] == ["DLFL", "mtllib box.mtl", "#", "v 1 1 1"]
    assert "fv 0 [0 1 0] [0 0] " in lines
    assert "e 0 6" in lines and "e 16 23" in lines
    assert "usemtl default" in lines and "f 20 21 22 23" in lines
    assert text.endswith("#\n")
    assert text.count("\n#\n") == 5  # after the header and each of the 4 sections


def test_write_then_read_is_the_cube_again(tmp_path: Path) -> None:
    write_dlfl(cube(), tmp_path / "c.dlfl")
    assert_same_mesh(cube(), read_dlfl(tmp_path / "c.dlfl"))


def assert_same_mesh(a: Mesh, b: Mesh) -> None:
    validate(b)
    assert a.counts() == b.counts()
    assert genus(a) == genus(b)
    assert np.array_equal(a.positions_view(), b.positions_view())
    assert [a.face_vertices(f) for f in a.face_ids()] == [b.face_vertices(f) for f in b.face_ids()]
    assert [a.is_hole(f) for f in a.face_ids()] == [b.is_hole(f) for f in b.face_ids()]
    pairs_a = sorted(tuple(sorted(a.edge_vertices(e))) for e in a.edge_ids())
    pairs_b = sorted(tuple(sorted(b.edge_vertices(e))) for e in b.edge_ids())
    assert pairs_a == pairs_b


def round_trip(mesh: Mesh) -> Mesh:
    return read_dlfl(dlfl_bytes(mesh))


def test_round_trip_of_samples() -> None:
    for name in ("soccerballdual.obj", "genus3hexa1.obj", "donuthexa1.obj"):
        mesh = read_obj(sample_bytes(name))
        assert_same_mesh(mesh, round_trip(mesh))


def square_sheet() -> tuple[Mesh, int, int]:
    """A two-sided square: front face 0-1-2-3 and its back face."""
    mesh = Mesh()
    front, back = mesh.create_face([(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)])
    return mesh, front, back


def test_round_trip_of_a_2gon_and_multi_edge() -> None:
    mesh, front, _ = square_sheet()
    c = mesh.face_corners(front)
    mesh.insert_edge(c[0], c[1])  # a second edge between vertices 0 and 1
    validate(mesh)
    sizes = [mesh.face_size(f) for f in mesh.face_ids()]
    assert 2 in sizes
    again = round_trip(mesh)
    assert_same_mesh(mesh, again)
    assert [again.face_size(f) for f in again.face_ids()] == sizes


def test_round_trip_of_a_face_visiting_a_vertex_twice_and_a_self_loop() -> None:
    mesh, front, _ = square_sheet()
    p = mesh.create_vertex((0.5, 0.5, 0.0))
    mesh.insert_edge(mesh.face_corners(front)[0], mesh.vertex_corner(p))  # dangling edge
    validate(mesh)
    face = mesh.corner_face(mesh.vertex_corner(p))
    verts = mesh.face_vertices(face)
    assert verts.count(0) == 2
    assert_same_mesh(mesh, round_trip(mesh))
    at_zero = [c for c in mesh.face_corners(face) if mesh.corner_vertex(c) == 0]
    mesh.insert_edge(at_zero[0], at_zero[1])  # a self-loop at vertex 0
    validate(mesh)
    assert any(len(set(mesh.edge_vertices(e))) == 1 for e in mesh.edge_ids())
    assert_same_mesh(mesh, round_trip(mesh))


def test_round_trip_of_point_spheres_and_holes() -> None:
    mesh = read_obj(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 3 3 3\nf 1 2 3 4\n")
    mesh.create_vertex((7.0, 8.0, 9.0))
    assert [mesh.is_hole(f) for f in mesh.face_ids()] == [False, True, False, False]
    text = dlfl_bytes(mesh)
    assert b"usemtl hole\nf " in text
    assert_same_mesh(mesh, round_trip(mesh))


def test_reverse_flips_every_face() -> None:
    mesh = donut_hexa(1)
    flipped = read_dlfl(dlfl_bytes(mesh, reverse=True))
    validate(flipped)
    assert flipped.counts() == mesh.counts()
    assert genus(flipped) == 1
    for f in mesh.face_ids():
        original = mesh.face_vertices(f)
        assert flipped.face_vertices(f) == [original[0], *original[:0:-1]]


def test_vertex_without_corners_becomes_a_point_sphere() -> None:
    text = TOPMOD_CUBE.replace(b"v -1 -1 1\n#", b"v -1 -1 1\nv 9 9 9\n#")
    mesh = read_dlfl(text)
    validate(mesh)
    assert mesh.counts() == (9, 12, 7)
    assert mesh.is_point_sphere(8)


def test_empty_file_body() -> None:
    assert read_dlfl(b"DLFL\nmtllib x.mtl\n#\n#\n#\n#\n#\n").counts() == (0, 0, 0)


@pytest.mark.parametrize(
    ("old", "new", "message"),
    [
        (b"DLFL", b"DLFX", r"<dlfl>:1: not a \.dlfl file"),
        (b"v 1 1 -1\n", b"v 1 x -1\n", r"<dlfl>:5: bad number 'x'"),
        (b"v 1 1 -1\n", b"v 1 1\n", r"<dlfl>:5: a v line needs 3 coordinates"),
        (b"fv 5 [0 -1 0]", b"fv 8 [0 -1 0]", r"<dlfl>:\d+: vertex index 8 is out of range"),
        (b"e 0 6\n", b"e 0 24\n", r"<dlfl>:\d+: corner index 24 is out of range"),
        (b"e 0 6\n", b"e 0 0\n", r"<dlfl>:\d+: an edge needs two different corners"),
        (b"e 1 10\n", b"e 0 10\n", r"<dlfl>:\d+: corner 0 is already on an edge"),
        (b"e 0 6\ne 1 10\n", b"e 0 10\ne 1 6\n",
         r"<dlfl>:\d+: corners 0 and 10 are not at opposite ends"),
        (b"e 0 6\n", b"", r"<dlfl>:\d+: corner 0 is on no edge"),
        (b"f 4 5 6 7\n", b"f 4 5 6 0\n", r"<dlfl>:\d+: corner 0 is already used by the face"),
        (b"f 4 5 6 7\n", b"f 4 5 6\n", r"<dlfl>:\d+: corner 7 belongs to no face"),
        (b"f 4 5 6 7\n", b"f\n", r"<dlfl>:\d+: empty face"),
        (b"f 4 5 6 7\n", b"f 4 5 six 7\n", r"<dlfl>:\d+: bad index 'six'"),
        (b"fv 6 [0 0 -1]", b"fv 99999999999999999999999 [0 0 -1]",
         r"<dlfl>:\d+: index '9+' is out of range"),
    ],
)
def test_errors_name_file_and_line(old: bytes, new: bytes, message: str) -> None:
    assert old in TOPMOD_CUBE
    with pytest.raises(FileFormatError, match=message):
        read_dlfl(TOPMOD_CUBE.replace(old, new, 1))


def test_non_manifold_result_is_refused_with_the_file_name(tmp_path: Path) -> None:
    # two separate two-sided triangles; then let the second one's vertex 3 be
    # vertex 0: vertex 0's corners form two fans, a bow-tie
    two = from_polygons([(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 0), (-1, 0, 0), (0, -1, 0)],
                        [[0, 1, 2], [0, 2, 1], [3, 4, 5], [3, 5, 4]])
    lines = dlfl_bytes(two).split(b"\n")
    fixed = [b"fv 0" + ln[4:] if ln.startswith(b"fv 3") else ln for ln in lines]
    path = tmp_path / "bowtie.dlfl"
    path.write_bytes(b"\n".join(fixed))
    with pytest.raises(FileFormatError, match=r"bowtie\.dlfl"):
        read_dlfl(path)


# ---------------------------------------------------------------------------
# the numpy reader and writer against the record-by-record reference

def reference_read(data: bytes, label: str = "<dlfl>") -> Mesh:
    """The record-by-record reader: every line parsed in Python, every check a loop
    over the records in file order (what read_dlfl did before its numpy paths)."""
    records = parse_dlfl(data, label, fast=False)
    reference_checks(records)
    return build_dlfl(records, full_check=True)


def reference_checks(r: DlflRecords) -> None:
    """The checks of a .dlfl reader, one record at a time, with their messages."""
    num_v, num_c = len(r.positions), len(r.corner_vertex)
    for v, line in zip(r.corner_vertex.tolist(), r.corner_lines.tolist(), strict=True):
        if not 0 <= v < num_v:
            raise DLFLError(f"{r.label}:{line}: vertex index {v} is out of range "
                            f"(there are {num_v} v lines)")
    rings = [r.face_corners[a:b].tolist() for a, b in zip(r.face_offsets[:-1].tolist(),
                                                          r.face_offsets[1:].tolist(), strict=True)]
    owner: dict[int, int] = {}
    for ring, line in zip(rings, r.face_lines.tolist(), strict=True):
        for c in ring:
            if not 0 <= c < num_c:
                raise DLFLError(f"{r.label}:{line}: corner index {c} is out of range "
                                f"(there are {num_c} fv lines)")
            if c in owner:
                raise DLFLError(f"{r.label}:{line}: corner {c} is already used "
                                f"by the face on line {owner[c]}")
            owner[c] = line
    for c in range(num_c):
        if c not in owner:
            raise DLFLError(f"{r.label}:{r.corner_lines[c]}: corner {c} belongs to no face "
                            "(no f line lists it)")
    reference_edge_checks(r, rings)


def reference_edge_checks(r: DlflRecords, rings: list[list[int]]) -> None:
    num_c = len(r.corner_vertex)
    mate: dict[int, int] = {}
    for (a, b), line in zip(r.edges.tolist(), r.edge_lines.tolist(), strict=True):
        for c in (a, b):
            if not 0 <= c < num_c:
                raise DLFLError(f"{r.label}:{line}: corner index {c} is out of range "
                                f"(there are {num_c} fv lines)")
            if c in mate:
                raise DLFLError(f"{r.label}:{line}: corner {c} is already on an edge")
        if a == b:
            raise DLFLError(f"{r.label}:{line}: an edge needs two different corners")
        mate[a], mate[b] = b, a
    nxt = {c: ring[(i + 1) % len(ring)] for ring in rings for i, c in enumerate(ring)}
    size = {c: len(ring) for ring in rings for c in ring}
    for c in range(num_c):
        if c not in mate and size[c] > 1:
            raise DLFLError(f"{r.label}:{r.corner_lines[c]}: corner {c} is on no edge "
                            "(only a point-sphere's single corner may lack an e line)")
    cv = r.corner_vertex.tolist()
    for (a, b), line in zip(r.edges.tolist(), r.edge_lines.tolist(), strict=True):
        if cv[a] != cv[nxt[b]] or cv[b] != cv[nxt[a]]:
            raise DLFLError(f"{r.label}:{line}: corners {a} and {b} are not at opposite ends "
                            f"of one edge (vertices {cv[a]}->{cv[nxt[a]]} and "
                            f"{cv[b]}->{cv[nxt[b]]})")


def structure(mesh: Mesh) -> tuple[object, ...]:
    """Everything a .dlfl file fixes: positions to the bit, corners face by face
    with their vertices and mates, face sizes and holes, the edges' corner pairs."""
    a = mesh_arrays(mesh)
    return (a.positions.tobytes(), a.corner_vertex.tolist(), a.face_offsets.tolist(),
            a.face_hole.tolist(), a.corner_mate.tolist(),
            sorted(map(tuple, np.sort(a.edge_corners, axis=1).tolist())))


def outcome(reader: Callable[[bytes], Mesh], data: bytes) -> object:
    """What ``reader`` makes of ``data``: the mesh's structure, or the error's
    message (the note of lines skipped is left out: both readers give it)."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DLFLSkippedLinesWarning)
            mesh = reader(data)
    except DLFLError as error:
        return str(error)
    validate(mesh)
    return structure(mesh)


def zoo() -> Mesh:
    """Every state at once: a hole, two components, a 2-gon and a multi-edge, a
    face visiting a vertex twice, a self-loop and two point-spheres."""
    mesh = read_obj(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 5 5 5\nf 1 2 3 4\n")  # + a hole
    front, _ = mesh.create_face([(3, 0, 0), (4, 0, 0), (4, 1, 0), (3, 1, 0)])
    c = mesh.face_corners(front)
    mesh.insert_edge(c[0], c[1])  # a second edge between two vertices: a 2-gon
    p = mesh.create_vertex((3.5, 0.5, 0.0))
    mesh.insert_edge(mesh.face_corners(front)[2], mesh.vertex_corner(p))  # dangling edge
    face = mesh.corner_face(mesh.vertex_corner(p))
    at = [k for k in mesh.face_corners(face) if mesh.corner_vertex(k) == mesh.corner_vertex(c[2])]
    mesh.insert_edge(at[0], at[1])  # a self-loop
    mesh.create_vertex((9.0, 9.0, 9.0))
    validate(mesh)
    return mesh


def zoo_files() -> list[bytes]:
    meshes = [zoo(), two_cubes(), torus(5, 4), donut_hexa(1)]
    files = [TOPMOD_CUBE] + [dlfl_bytes(m, reverse=r) for m in meshes for r in (False, True)]
    return files + [TOPMOD_CUBE.replace(b"\n", b"\r\n")]


def test_zoo_has_every_state() -> None:
    mesh = zoo()
    a = mesh_arrays(mesh)
    assert a.face_hole.any() and 2 in a.face_sizes and 1 in a.face_sizes
    assert (a.edge_vertices[:, 0] == a.edge_vertices[:, 1]).any()  # a self-loop
    assert any(len(set(mesh.face_vertices(f))) < mesh.face_size(f) for f in mesh.face_ids())
    assert sum(mesh.is_point_sphere(v) for v in mesh.vertex_ids()) == 2


def test_fast_reader_builds_what_the_reference_builds() -> None:
    for data in zoo_files():
        fast, slow = parse_dlfl(data), parse_dlfl(data, fast=False)
        for name in DlflRecords.__dataclass_fields__:
            assert np.array_equal(getattr(fast, name), getattr(slow, name)), name
        mesh = read_dlfl(data)
        validate(mesh)
        assert structure(mesh) == structure(reference_read(data))


def test_round_trip_keeps_every_state_and_the_layout() -> None:
    for mesh in (zoo(), two_cubes(), torus(5, 4)):
        again = round_trip(mesh)
        assert_same_mesh(mesh, again)
        assert structure(again) == structure(mesh)
        flipped = read_dlfl(dlfl_bytes(mesh, reverse=True))
        validate(flipped)
        for f, g in zip(mesh.face_ids(), flipped.face_ids(), strict=True):
            original = mesh.face_vertices(f)
            assert flipped.face_vertices(g) == [original[0], *original[:0:-1]]


def count_python_lines(monkeypatch: pytest.MonkeyPatch) -> list[int]:
    """Record the line number of every line the Python parser gets from now on."""
    seen: list[int] = []
    parse_line = dlflfile._python_record

    def counting(raw: bytes, line: int, label: str) -> object:
        seen.append(line)
        return parse_line(raw, line, label)

    monkeypatch.setattr(dlflfile, "_python_record", counting)
    return seen


def test_written_and_topmod_files_take_the_fast_path(monkeypatch: pytest.MonkeyPatch) -> None:
    files = [dlfl_bytes(zoo()), dlfl_bytes(torus(5, 4), reverse=True), TOPMOD_CUBE,
             TOPMOD_CUBE.replace(b"\n", b"\r\n")]
    seen = count_python_lines(monkeypatch)
    for data in files:
        seen.clear()
        read_dlfl(data)
        lines = data.split(b"\n")
        assert all(lines[n - 1].startswith(b"usemtl") for n in seen), seen  # only those
        assert len(seen) == sum(line.startswith(b"usemtl") for line in lines)


def test_odd_lines_among_plain_ones_go_to_python(monkeypatch: pytest.MonkeyPatch) -> None:
    odd = {b"v -1 1 1": b"v -1,1,1e0 ignored", b"fv 7 [0 0 1] [0 0]": b"fv  7[0 0 1]",
           b"e 9 15": b" e 9 15 and more", b"f 16 17 18 19": b"f 16  17 18 +19\t"}
    data = TOPMOD_CUBE
    for old, new in odd.items():
        assert old in data
        data = data.replace(old, new, 1)
    seen = count_python_lines(monkeypatch)
    mesh = read_dlfl(data)
    assert len(seen) == 1 + 4  # usemtl and the odd lines
    assert structure(mesh) == structure(cube())


def big_file() -> tuple[bytes, list[bytes]]:
    """A torus of 10,800 quads (43,200 fv lines: passes on several kinds) as text
    and lines."""
    data = dlfl_bytes(torus(120, 90))
    return data, data.split(b"\n")


def first_line(lines: list[bytes], prefix: bytes, skip: int = 0) -> int:
    """0-based index of the ``skip``-th line starting with ``prefix``."""
    return [i for i, line in enumerate(lines) if line.startswith(prefix)][skip]


def test_error_lines_from_the_fast_path_of_a_big_file() -> None:
    _, lines = big_file()
    num_c = sum(line.startswith(b"fv ") for line in lines)
    cases = [
        (b"v ", 9000, lambda ln: b"v 1 2 x", "bad number 'x'"),
        (b"fv ", 40000, lambda ln: b"fv 10800 [0 0 1] [0 0] ",
         "vertex index 10800 is out of range (there are 10800 v lines)"),
        (b"e ", 20000, lambda ln: ln.rsplit(b" ", 1)[0] + b" %d" % num_c,
         f"corner index {num_c} is out of range"),
        (b"f ", 10000, lambda ln: ln + b" 7", "corner 7 is already used by the face on line"),
        (b"f ", 10799, lambda ln: b"f 1 2 x", "bad index 'x'"),
    ]
    for prefix, skip, change, message in cases:
        edited = list(lines)
        at = first_line(edited, prefix, skip)
        edited[at] = change(edited[at])
        with pytest.raises(FileFormatError) as caught:
            read_dlfl(b"\n".join(edited))
        assert str(caught.value).startswith(f"<dlfl>:{at + 1}: {message}"), str(caught.value)


def test_the_first_bad_record_wins_and_parse_errors_come_first() -> None:
    _, lines = big_file()
    edited = list(lines)
    for skip in (300, 100):  # two bad v lines: the earlier is named
        edited[first_line(lines, b"v ", skip)] = b"v 1 2"
    with pytest.raises(FileFormatError, match=f"^<dlfl>:{first_line(lines, b'v ', 100) + 1}: a v"):
        read_dlfl(b"\n".join(edited))
    edited = list(lines)
    edited[first_line(lines, b"fv ", 5)] = b"fv 99999 [0 0 1] [0 0] "  # a topology error...
    edited[first_line(lines, b"f ", 10000)] = b"f"  # ...after which a malformed line
    with pytest.raises(FileFormatError, match=f"^<dlfl>:{first_line(lines, b'f ', 10000) + 1}: empty"):
        read_dlfl(b"\n".join(edited))


def test_big_file_loads_as_the_reference_loads() -> None:
    data, _ = big_file()
    assert structure(read_dlfl(data)) == structure(reference_read(data))


edit = st.tuples(st.integers(0, 5), st.integers(0, 10**6), st.integers(-3, 30),
                 st.sampled_from(list(b"0123456789 -[],#\tfve\r+_x")))


def edited(data: bytes, edits: list[tuple[int, int, int, int]]) -> bytes:
    """Apply line edits: set a number of a line, delete, duplicate or swap lines,
    or change, insert or delete a byte."""
    lines = data.split(b"\n")
    for kind, where, number, byte in edits:
        i, j = where % len(lines), (where // 7) % len(lines)
        if kind == 0:
            words = lines[i].split(b" ")
            k = 1 + (where // 3) % max(len(words) - 1, 1)
            if k < len(words):
                words[k] = b"%d" % number
            lines[i] = b" ".join(words)
        elif kind == 1:
            del lines[i]
        elif kind == 2:
            lines.insert(i, lines[j])
        elif kind == 3:
            lines[i], lines[j] = lines[j], lines[i]
        else:
            line = bytearray(lines[i])
            at = (where // 11) % (len(line) + 1)
            line[at : at + (kind == 5)] = bytes([byte])
            lines[i] = bytes(line)
        if not lines:
            break
    return b"\n".join(lines)


@pytest.mark.timeout(120)
@settings(max_examples=250, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(zoo_files()), st.lists(edit, min_size=1, max_size=4))
def test_fast_reader_agrees_with_the_reference_on_edited_files(
        data: bytes, edits: list[tuple[int, int, int, int]]) -> None:
    text = edited(data, edits)
    assert outcome(read_dlfl, text) == outcome(reference_read, text)


def test_writer_normals_are_the_rounded_face_normals() -> None:
    mesh = read_obj(sample_bytes("soccerballdual.obj"))  # with 2-gons
    a = mesh_arrays(mesh)
    fields = format_floats(np.round(face_normals(a), 6).ravel() + 0.0).reshape(len(a.face_ids), 3, -1)
    text = [b" ".join(bytes(f[f != 0]) for f in row) for row in fields]
    expected = [b"fv %d [%s] [0 0] " % (v, text[f])
                for v, f in zip(a.corner_vertex.tolist(), a.corner_face.tolist(), strict=True)]
    written = [ln for ln in dlfl_bytes(mesh).split(b"\n") if ln.startswith(b"fv ")]
    assert written == expected


@settings(max_examples=200, deadline=None)
@given(st.lists(st.floats(allow_nan=True, allow_infinity=True) | st.floats(-2, 2), max_size=40),
       st.integers(0, 6))
def test_format_rounded_writes_what_format_floats_writes_of_the_rounded_value(
        values: list[float], decimals: int) -> None:
    x = np.array(values, dtype=np.float64)
    with np.errstate(over="ignore", invalid="ignore"):  # np.round overflows near 1e308
        expected = format_floats(np.round(x, decimals) + 0.0)
    a, b = format_rounded(x, decimals), expected
    assert [bytes(r[r != 0]) for r in a] == [bytes(r[r != 0]) for r in b]


def test_leading_uints_reads_digit_runs() -> None:
    text = b"fv 12 [x] 0 123456789012345678 1234567890123456789 9x"
    buf = np.frombuffer(text + b" " * 20, dtype=np.uint8)
    starts = [text.index(w) for w in (b"12", b"[x]", b"0 ", b"12345678901234567", b"1234567890123456789",
                                      b"9x")]
    at = np.array([*starts, len(buf) - 2], dtype=np.int64)
    values, lengths = leading_uints(buf, at)
    assert lengths.tolist() == [2, 0, 1, 18, 0, 1, 0]
    assert values.tolist() == [12, 0, 0, 123456789012345678, 0, 9, 0]


def test_colours_go_to_the_materials_as_topmod_writes_them(tmp_path: Path) -> None:
    mesh = coloured_cube()
    mesh.set_hole(5)
    write_dlfl(mesh, tmp_path / "c.dlfl")
    text = (tmp_path / "c.dlfl").read_text()
    assert text.splitlines()[1] == "mtllib c.mtl"
    assert "usemtl hole" in text and "usemtl color_ff0000" in text
    back = read_dlfl(tmp_path / "c.dlfl")
    validate(back)
    assert back.is_hole(5) and back.face_color(5) is None  # a hole is written as one
    expected = expected_written_colors(mesh)[:5]
    np.testing.assert_array_equal(back.face_colors()[:5], expected)


def test_a_dlfl_without_colours_writes_no_library_and_reads_back_quietly(
        tmp_path: Path, recwarn: pytest.WarningsRecorder) -> None:
    write_dlfl(two_cubes(), tmp_path / "t.dlfl")
    assert not (tmp_path / "t.mtl").exists()
    back = read_dlfl(tmp_path / "t.dlfl")
    assert back.face_colors() is None and len(recwarn) == 0


# -- a lone CR ends a line and counts in line numbers; CR-only line endings


@pytest.mark.parametrize("key", [b"v ", b"fv ", b"e ", b"f "])
def test_dlfl_lone_cr_ends_a_line(key):
    data = dlfl_bytes(unit_cube())
    lines = data.split(b"\n")
    line = next(i for i, text in enumerate(lines, 1) if text.startswith(key))
    mesh = read_dlfl(lone_cr_after_line(data, line))
    validate(mesh)
    assert mesh.counts() == (8, 12, 6)
    np.testing.assert_array_equal(mesh.positions_view(), unit_cube().positions_view())


def test_dlfl_lone_cr_counts_in_line_numbers():
    data = dlfl_bytes(unit_cube())
    lines = data.split(b"\n")
    last_v = max(i for i, text in enumerate(lines, 1) if text.startswith(b"v "))
    broken = lone_cr_after_line(data, 4).replace(lines[last_v - 1], b"v 1 x 1")
    with pytest.raises(FileFormatError, match=rf"^<dlfl>:{last_v}: "):
        read_dlfl(broken)


def test_dlfl_with_cr_line_endings_reads_every_line() -> None:
    text = dlfl_bytes(unit_cube()).replace(b"\n", b"\r")
    mesh = read_dlfl(text)
    assert (mesh.num_vertices, mesh.num_edges, mesh.num_faces) == (8, 12, 6)


# -- the header's end: a missing '#' line, a file name that holds one


def test_dlfl_without_a_header_end_is_refused() -> None:
    text = dlfl_bytes(unit_cube()).replace(b"#\n", b"")
    with pytest.raises(FileFormatError, match=r"no '#' line"):
        parse_dlfl(text, "x.dlfl")


def test_dlfl_file_name_with_a_newline_still_reads_back(tmp_path) -> None:
    path = tmp_path / "a\n#\nv 0 0.dlfl"
    write_dlfl(unit_cube(), path)
    mesh = read_dlfl(path)
    assert (mesh.num_vertices, mesh.num_edges, mesh.num_faces) == (8, 12, 6)
