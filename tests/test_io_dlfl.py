"""TopMod's .dlfl format (livemod.dlfl.io.dlflfile)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from livemod.dlfl import DLFLError, Mesh, from_polygons, genus, validate
from livemod.dlfl.io import read_dlfl, read_obj, write_dlfl
from livemod.dlfl.io.dlflfile import dlfl_bytes

SAMPLES = Path(__file__).resolve().parents[2] / "shared" / "data" / "topmod-objs"

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
        mesh = read_obj(SAMPLES / name)
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
    mesh = read_obj(SAMPLES / "donuthexa1.obj")
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
    with pytest.raises(DLFLError, match=message):
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
    with pytest.raises(DLFLError, match=r"bowtie\.dlfl"):
        read_dlfl(path)
