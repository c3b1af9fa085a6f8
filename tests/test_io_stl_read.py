"""STL import (livemod.dlfl.io.stl.read_stl): binary and ASCII, welding, errors."""

from __future__ import annotations

import re
import struct
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from livemod import cli
from livemod.dlfl import DLFLRepairWarning, FileFormatError, Mesh, NonManifoldError, genus, validate
from livemod.dlfl.arrays import mesh_arrays
from livemod.dlfl.io import load_mesh, read_obj, read_stl, save_mesh
from livemod.dlfl.io import stl as stl_module
from livemod.dlfl.io.stl import drop_collapsed, parse_stl, stl_bytes, weld_positions
from livemod.dlfl.shapes import cube, soccer_ball, torus
from tests.io_inputs import lone_cr_after_line

from .test_io_fuzz import FUZZ, only_dlfl_errors
from .test_io_stl_ply import open_box

SQUARE = b"""solid square
facet normal 0 0 1
 outer loop
  vertex 0 0 0
  vertex 1 0 0
  vertex 1 1 0
  vertex 0 1 0
 endloop
endfacet
endsolid square
"""


def ascii_stl(triangles: np.ndarray, name: str = "t") -> bytes:
    """``triangles`` (``(T, 3, 3)``) as ASCII STL, numbers written by repr."""
    facets = "".join(
        "facet normal 0 0 0\n outer loop\n"
        + "".join(f"  vertex {x!r} {y!r} {z!r}\n" for x, y, z in triangle)
        + " endloop\nendfacet\n"
        for triangle in np.asarray(triangles, dtype=float).tolist())
    return f"solid {name}\n{facets}endsolid {name}\n".encode()


def binary_stl(triangles: np.ndarray, header: bytes = b"test") -> bytes:
    """``triangles`` (``(T, 3, 3)``) as binary STL with zero normals."""
    records = b"".join(struct.pack("<12fH", 0, 0, 0, *np.ravel(t), 0) for t in triangles)
    return header.ljust(80, b" ") + struct.pack("<I", len(triangles)) + records


def tetra_triangles() -> np.ndarray:
    """A tetrahedron's four outward triangles, ``(4, 3, 3)``."""
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=float)
    return p[[[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]]]


def triangle_normals(mesh: Mesh) -> np.ndarray:
    """``(F, 3)`` unit normal of every drawn triangle, from its corner order."""
    a = mesh_arrays(mesh)
    sizes, indices = a.surface_polygons()
    assert np.all(sizes == 3)
    p = a.positions[indices.reshape(-1, 3)]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    return n / np.linalg.norm(n, axis=1)[:, None]


@pytest.mark.parametrize(("mesh", "counts", "handles"), [
    (cube(), (8, 18, 12), 0),
    (soccer_ball(), (60, 174, 116), 0),
    (torus(12, 8), (96, 288, 192), 1),
])
def test_binary_round_trip_welds_the_fans_back_into_one_manifold(mesh, counts, handles) -> None:
    back = read_stl(stl_bytes(mesh))
    validate(back)
    assert back.counts() == counts and genus(back) == handles
    assert not back.notes
    f32 = mesh_arrays(mesh).positions.astype(np.float32).astype(np.float64)
    assert {tuple(p) for p in mesh_arrays(back).positions} == {tuple(p) for p in f32}
    records = np.frombuffer(stl_bytes(mesh), stl_module._TRIANGLE, offset=84)
    assert np.allclose(triangle_normals(back), records["normal"], atol=1e-5)


def test_an_open_mesh_comes_back_with_its_hole_and_without_point_spheres() -> None:
    back = read_stl(stl_bytes(open_box()))
    validate(back)
    holes = [f for f in back.face_ids() if back.is_hole(int(f))]
    assert back.counts() == (8, 17, 11) and len(holes) == 1
    assert len(back.face_vertices(int(holes[0]))) == 4


def test_vertices_are_numbered_in_the_order_they_first_appear() -> None:
    corners = np.array([[2, 0, 0], [0, 0, 0], [2, 0, 0], [1, 0, 0], [0, 0, 0]], dtype=float)
    positions, vertex_of_corner = weld_positions(corners)
    assert positions.tolist() == [[2, 0, 0], [0, 0, 0], [1, 0, 0]]
    assert vertex_of_corner.tolist() == [0, 1, 0, 2, 1]


def test_minus_zero_welds_with_zero() -> None:
    positions, vertex_of_corner = weld_positions(np.array([[0.0, -0.0, 1.0], [-0.0, 0.0, 1.0]]))
    assert vertex_of_corner.tolist() == [0, 0]
    assert not np.signbit(positions).any()


def reference_weld(corners: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """weld_positions the slow, obvious way: a dict in file order."""
    seen: dict[tuple[float, ...], int] = {}
    vertex_of_corner = [seen.setdefault(tuple(p + 0.0), len(seen)) for p in corners]
    return np.array(list(seen), dtype=float).reshape(-1, 3), np.array(vertex_of_corner)


@pytest.mark.parametrize("fake_mix", [
    lambda bits: np.zeros(len(bits), dtype=np.uint64),       # every row collides
    lambda bits: (bits[:, 0] >> np.uint64(62)) << np.uint64(62),  # a few tangled runs
    None,                                                      # the real hash
])
def test_welding_is_right_even_when_hashes_collide(monkeypatch, fake_mix) -> None:
    rng = np.random.default_rng(5)
    corners = rng.integers(-3, 4, size=(500, 3)).astype(float) * 0.5
    if fake_mix is not None:
        monkeypatch.setattr(stl_module, "_mix", fake_mix)
    positions, vertex_of_corner = weld_positions(corners)
    expected_positions, expected_vertices = reference_weld(corners)
    assert np.array_equal(positions, expected_positions)
    assert np.array_equal(vertex_of_corner, expected_vertices)


def test_drop_collapsed_removes_repeats_then_faces_under_three_corners() -> None:
    indices = np.array([0, 1, 1, 2, 3, 3, 4, 5, 6, 7, 6, 8, 9, 10, 8])
    offsets = np.array([0, 4, 7, 10, 15])
    kept_indices, kept_offsets, kept = drop_collapsed(indices, offsets)
    # (0 1 1 2) -> 0 1 2; (3 3 4) -> 2 corners, dropped; (5 6 7) kept; (6 8 9 10 8)
    # has no consecutive repeat (the 8s are not neighbours), kept as it is
    assert kept.tolist() == [True, False, True, True]
    assert kept_indices.tolist() == [0, 1, 2, 5, 6, 7, 6, 8, 9, 10, 8]
    assert kept_offsets.tolist() == [0, 3, 6, 11]


def test_degenerate_facets_are_dropped_with_a_note() -> None:
    triangles = np.concatenate([tetra_triangles(), [[[1, 0, 0], [1, 0, 0], [0, 1, 0]],
                                                    [[5, 5, 5], [5, 5, 5], [6, 6, 6]]]])
    with pytest.warns(DLFLRepairWarning, match="2 degenerate facets"):
        mesh = read_stl(binary_stl(triangles), name="sliver.stl")
    validate(mesh)
    assert mesh.counts() == (4, 6, 4)  # (5,5,5) and (6,6,6) are not left as point-spheres
    assert mesh.notes == ["sliver.stl: 2 degenerate facets (two corners at the same point) "
                          "left out"]


def test_only_degenerate_facets_give_an_empty_mesh() -> None:
    with pytest.warns(DLFLRepairWarning, match="1 degenerate facet "):
        mesh = read_stl(binary_stl(np.zeros((1, 3, 3))))
    assert mesh.counts() == (0, 0, 0)


def test_a_binary_header_starting_with_solid_is_still_binary() -> None:
    mesh = read_stl(binary_stl(tetra_triangles(), header=b"solid exported by a CAD tool"))
    validate(mesh)
    assert mesh.counts() == (4, 6, 4)


def test_ascii_and_binary_give_the_same_mesh() -> None:
    triangles = np.frombuffer(stl_bytes(torus(6, 5)), stl_module._TRIANGLE, offset=84)["corners"]
    from_ascii = read_stl(ascii_stl(triangles))
    from_binary = read_stl(stl_bytes(torus(6, 5)))
    validate(from_ascii)
    assert np.array_equal(mesh_arrays(from_ascii).positions, mesh_arrays(from_binary).positions)
    assert [from_ascii.face_vertices(int(f)) for f in from_ascii.face_ids()] == [
        from_binary.face_vertices(int(f)) for f in from_binary.face_ids()]


def test_ascii_loops_of_four_are_quads_and_layout_does_not_matter() -> None:
    square = read_stl(SQUARE)
    assert square.counts() == (4, 4, 2)  # the quad and its hole
    assert square.face_vertices(0) == [0, 1, 2, 3]
    squashed = SQUARE.replace(b"\n  vertex 1 0 0", b" vertex 1e0 0 0")  # two on a line
    spaced = SQUARE.replace(b"\n", b"\r\n").replace(b"vertex 1 1 0", b"vertex\t+1.0  1 0.0e1")
    shouted = SQUARE.upper()  # some old exporters write the keywords in capitals
    for text in (squashed, spaced, SQUARE.rstrip(b"\n"), shouted):
        again = read_stl(text)
        assert np.array_equal(mesh_arrays(again).positions, mesh_arrays(square).positions)
    assert read_stl(b"solid empty\nendsolid empty\n").counts() == (0, 0, 0)


def test_an_ascii_file_may_hold_several_solids() -> None:
    tetra = tetra_triangles()
    mesh = read_stl(ascii_stl(tetra[:2], "a") + ascii_stl(tetra[2:], "b"))
    validate(mesh)
    assert mesh.counts() == (4, 6, 4) and genus(mesh) == 0


def test_ascii_numbers_read_exactly() -> None:
    values = np.array([[[0.1, -2.5e-7, 1e300], [3.141592653589793, 2.0, -0.0],
                        [7.0, 123456789.123456789, 5e-324]]])
    corners, offsets, lines = parse_stl(ascii_stl(values))
    assert np.array_equal(corners, values[0]) and offsets.tolist() == [0, 3]
    assert lines.tolist() == [2]


@pytest.mark.parametrize(("data", "message"), [
    (b"hello", "t.stl: not an STL file: 5 bytes, too short for binary STL"),
    (b"\0" * 80 + struct.pack("<I", 2) + b"\0" * 50,
     r"t.stl: not an STL file: as binary STL its header counts 2 triangles \(184 bytes\), "
     r"but the file has 134 bytes"),
    (SQUARE.replace(b"endloop", b"endlop"), "t.stl:2: facet 0 is not 'facet normal NX NY NZ, "
                                            "outer loop, vertex X Y Z"),
    (SQUARE.replace(b"normal", b"norml"), "t.stl:2: facet 0 is not"),
    (SQUARE.replace(b"  vertex 1 1 0\n  vertex 0 1 0\n", b""), "t.stl:2: facet 0 is not"),
    (SQUARE + SQUARE[SQUARE.index(b"facet"):SQUARE.index(b"endloop")],
     "t.stl:11: facet 1 is not"),
    (SQUARE + b"endloop\n", r"t.stl:11: after facet 0 \(the file may be cut short\) is not"),
    (SQUARE.replace(b"1 1 0", b"1 x 0"), "t.stl:6: bad number 'x'"),
    (SQUARE.replace(b"1 1 0", b"1 1"), "t.stl:2: facet 0 is not"),
    (SQUARE.replace(b"1 1 0", b"1 inf 0"), r"t.stl:6: a vertex coordinate is not finite: "
                                           r"\[1.0, inf, 0.0\]"),
    (binary_stl(np.full((1, 3, 3), np.nan)), "t.stl: triangle 0: a vertex coordinate is not "
                                             "finite"),
])
def test_bad_files_are_refused_naming_what_is_wrong(data: bytes, message: str) -> None:
    with pytest.raises(FileFormatError, match=message):
        read_stl(data, name="t.stl")


def test_a_non_manifold_stl_names_the_facet_line() -> None:
    fin = np.concatenate([tetra_triangles(), [[[0, 0, 0], [1, 0, 0], [0.5, -1, 0.5]]]])
    with pytest.raises(NonManifoldError, match=r"^fin.stl:"):
        read_stl(ascii_stl(fin), name="fin.stl")
    with pytest.raises(NonManifoldError, match=r"^fin.stl: "):
        read_stl(binary_stl(fin), name="fin.stl")


def test_load_mesh_and_the_cli_read_stl(tmp_path: Path, capsys) -> None:
    path = tmp_path / "ball.stl"
    save_mesh(soccer_ball(), path)
    assert load_mesh(path).counts() == (60, 174, 116)
    assert cli.main(["info", str(path)]) == 0
    assert "Genus : 0" in capsys.readouterr().out
    assert cli.main(["convert", str(path), str(tmp_path / "ball.obj")]) == 0
    assert read_obj(tmp_path / "ball.obj").counts() == (60, 174, 116)


@FUZZ
@given(st.binary(max_size=400))
def test_stl_random_bytes(data: bytes) -> None:
    only_dlfl_errors(read_stl, data)
    only_dlfl_errors(read_stl, b"solid x\n" + data)


@FUZZ
@given(st.sampled_from([SQUARE, ascii_stl(tetra_triangles()), binary_stl(tetra_triangles())]),
       st.integers(0, 400), st.lists(st.tuples(st.integers(0, 2), st.integers(0, 10**6),
                                               st.integers(0, 255)), max_size=6))
def test_stl_truncated_and_mutated(base: bytes, cut: int, edits) -> None:
    from .test_io_fuzz import mutate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DLFLRepairWarning)
        only_dlfl_errors(read_stl, base[:cut])
        only_dlfl_errors(read_stl, mutate(base, edits))


# -- a binary STL whose header counts 0 triangles reads the triangles its size shows


def _zero_count(data: bytes) -> bytes:
    return data[:80] + b"\0\0\0\0" + data[84:]


def test_binary_stl_with_a_zero_count_reads_the_triangles_its_size_shows():
    original = stl_bytes(cube())
    assert original[80:84] != b"\0\0\0\0"
    mesh = read_stl(_zero_count(original))
    validate(mesh)
    assert mesh.counts() == read_stl(original).counts() == (8, 18, 12)
    np.testing.assert_array_equal(mesh.positions_view(), read_stl(original).positions_view())


def test_binary_stl_with_a_zero_count_under_a_solid_header_reads_too():
    data = _zero_count(stl_bytes(cube()))
    data = b"solid exported".ljust(80, b" ") + data[80:]
    assert read_stl(data).counts() == (8, 18, 12)


def test_binary_stl_with_a_zero_count_and_no_triangles_is_empty():
    assert read_stl(_zero_count(stl_bytes(cube()))[:84]).counts() == (0, 0, 0)


@pytest.mark.parametrize("extra", [1, 7, 49])
def test_binary_stl_with_a_zero_count_and_part_of_a_triangle_is_refused(extra):
    data = _zero_count(stl_bytes(cube()))[: 84 + 50 + extra]
    message = (f"<stl>: not an STL file: as binary STL its header counts 0 triangles, and the "
               f"{50 + extra} bytes after the 84-byte header are not whole 50-byte triangles "
               f"({134 + extra} bytes in all); and it does not start with 'solid'")
    with pytest.raises(FileFormatError, match=re.escape(message)):
        read_stl(data)


def test_binary_stl_with_a_nonzero_count_that_disagrees_stays_refused():
    data = stl_bytes(cube())[:-50]  # the header still counts 12
    with pytest.raises(FileFormatError, match=re.escape(
            f"its header counts 12 triangles (684 bytes), but the file has {len(data)} bytes")):
        read_stl(data)


# -- a lone CR ends an ASCII STL line and counts in line numbers

LONE_CR_STL = (b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
               b"vertex 0 1 0\nendloop\nendfacet\nfacet normal 0 0 1\nouter loop\n"
               b"vertex 1 0 0\nvertex 1 1 0\nvertex x 1 0\nendloop\nendfacet\nendsolid t\n")


def test_ascii_stl_lone_cr_counts_in_line_numbers():
    with pytest.raises(FileFormatError, match=r"^<stl>:13: bad number 'x'"):
        read_stl(LONE_CR_STL)
    with pytest.raises(FileFormatError, match=r"^<stl>:13: bad number 'x'"):
        read_stl(lone_cr_after_line(LONE_CR_STL, 8))


def test_ascii_stl_lone_cr_reads_the_same_mesh():
    data = LONE_CR_STL.replace(b"vertex x", b"vertex 0")
    mesh = read_stl(lone_cr_after_line(lone_cr_after_line(data, 1), 8))
    assert mesh.counts() == read_stl(data).counts() == (4, 5, 3)


# -- binary STL under a solid header, ASCII numbers and solid names

ONE_TRIANGLE_STL = (b"solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"
                    b"vertex 0 1 0\nendloop\nendfacet\nendsolid t\n")


def test_binary_stl_with_solid_header_and_trailing_bytes_is_not_empty() -> None:
    data = b"solid exported" + stl_bytes(torus())[14:] + b"\n"
    with pytest.raises(FileFormatError, match=r"binary STL"):
        read_stl(data, name="t.stl")


def test_ascii_stl_refuses_digit_underscores_like_obj() -> None:
    with pytest.raises(FileFormatError, match=r"t\.stl:5: bad number '1_0'"):
        read_stl(ONE_TRIANGLE_STL.replace(b"vertex 1 0 0", b"vertex 1_0 0 0"), name="t.stl")


@pytest.mark.parametrize("name", [b"facet", b"vertex 1 2 3", b"outer loop", b"endloop"])
def test_ascii_stl_solid_name_may_hold_keywords(name: bytes) -> None:
    data = ONE_TRIANGLE_STL.replace(b"solid t\n", b"solid " + name + b"\n").replace(
        b"endsolid t", b"endsolid " + name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mesh = read_stl(data, name="t.stl")
    validate(mesh)
    assert mesh.num_vertices == 3
