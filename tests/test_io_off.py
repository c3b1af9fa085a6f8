"""OFF: polygons kept both ways, read back by trimesh and by livemod's reader."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import trimesh

from livemod.dlfl import from_polygons, mesh_arrays, validate
from livemod.dlfl.analysis import genus
from livemod.dlfl.errors import FileFormatError, InvalidArgumentError
from livemod.dlfl.io import load_mesh, read_off, save_mesh
from livemod.dlfl.io.off import off_bytes
from livemod.dlfl.shapes import load_shape
from tests.meshes import coloured_cube, expected_written_colors, torus, triangle


@pytest.mark.parametrize("shape", ["soccerball", "cube", "geodesicdome", "genus3hexa1"])
def test_a_written_off_reads_back_the_same_polygons(shape: str, tmp_path: Path) -> None:
    mesh = load_shape(shape)
    save_mesh(mesh, tmp_path / "m.off")
    back = load_mesh(tmp_path / "m.off")
    validate(back)
    a, b = mesh_arrays(mesh), mesh_arrays(back)
    assert back.counts() == mesh.counts() and genus(back) == genus(mesh)
    assert a.positions.tobytes() == b.positions.tobytes()
    assert np.array_equal(a.face_sizes, b.face_sizes)
    assert np.array_equal(a.surface_polygons()[1], b.surface_polygons()[1])


@pytest.mark.parametrize("mesh", [torus(6, 5), load_shape("tetrahedron")], ids=["quads", "tris"])
def test_trimesh_reads_the_written_off(mesh, tmp_path: Path) -> None:  # type: ignore[no-untyped-def]
    # trimesh's OFF reader takes faces of one size only (it fails on mixed polygons)
    save_mesh(mesh, tmp_path / "m.off")
    peer = trimesh.load(tmp_path / "m.off", force="mesh", process=False)
    a = mesh_arrays(mesh)
    sizes, vertices = a.surface_polygons()
    assert np.allclose(peer.vertices, a.positions, rtol=0, atol=1e-9)
    assert len(peer.faces) == int((sizes - 2).sum())
    assert peer.is_watertight and peer.euler_number == 2 - 2 * genus(mesh)


def test_holes_come_back_as_boundaries_and_point_spheres_as_vertices() -> None:
    mesh = triangle()
    mesh.create_vertex((5.0, 5.0, 5.0))  # a point-sphere: a vertex no polygon uses
    back = read_off(off_bytes(mesh))
    validate(back)
    assert back.counts() == mesh.counts() == (4, 3, 3)
    assert mesh_arrays(back).face_hole.sum() == 1


def test_face_colours_follow_each_polygon() -> None:
    mesh = load_shape("cube")
    colours = np.array([[1.0, 0, 0], [0, 1.0, 0], [0, 0, 1.0], [1, 1, 0], [0, 1, 1], [1, 0, 1]])
    text = off_bytes(mesh, colours).decode()
    assert text.splitlines()[-6:][2].endswith(" 0 0 255 255")
    back = read_off(text.encode())
    assert back.counts() == (8, 12, 6)
    assert np.array_equal(back.face_colors(), colours)
    with pytest.raises(InvalidArgumentError, match=r"\(6, 3\) or \(6, 4\)"):
        off_bytes(mesh, colours[:5])


def test_comments_blank_lines_counts_on_the_header_line_and_coff() -> None:
    data = b"COFF 3 1 0\n# a comment\n\n0 0 0 255 0 0 255\n1 0 0 # x\n0 1.5e0 0\n3 0 1 2 0.5 0.5 0.5\n"
    mesh = read_off(data)
    assert mesh.counts() == (3, 3, 2)
    assert mesh_arrays(mesh).positions[2].tolist() == [0.0, 1.5, 0.0]


@pytest.mark.parametrize(("data", "line", "what"), [
    (b"OFX\n", 1, "not an OFF file: the first word is 'OFX'"),
    (b"OFF\n3 x 0\n", 2, "the counts must be 'V F E'"),
    (b"OFF\n3 1 0\n0 0 0\n1 0 0\n", 4, "the file ends after 2 of the 3 vertex and 1 face"),
    (b"OFF\n3 1 0\n0 0 0\n1 y 0\n0 1 0\n3 0 1 2\n", 4, "bad number 'y'"),
    (b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n", 6, "vertex index 5 is out of range"),
    (b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n", 6, "the face says 4 corners but lists 3"),
    (b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 " + b"9" * 30 + b"\n", 6,
     "vertex index '999999999999999999999999999999' is out of range"),
])
def test_errors_name_the_file_and_line(data: bytes, line: int, what: str) -> None:
    with pytest.raises(FileFormatError) as caught:
        read_off(data, name="m.off")
    assert (caught.value.path, caught.value.line) == ("m.off", line)
    assert str(caught.value).startswith(f"m.off:{line}: {what}")


def test_a_large_mesh_round_trips_on_the_vectorized_path() -> None:
    rows = np.arange(200)
    positions = np.stack([*np.meshgrid(rows, rows, indexing="ij"), np.zeros((200, 200))], -1)
    a = rows[:-1, None] * 200 + rows[None, :-1]
    quads = np.stack([a, a + 200, a + 201, a + 1], -1).reshape(-1, 4)
    mesh = from_polygons(positions.reshape(-1, 3).astype(float), quads)
    back = read_off(off_bytes(mesh))
    assert np.array_equal(mesh_arrays(back).surface_polygons()[1],
                          mesh_arrays(mesh).surface_polygons()[1])


def test_the_meshs_own_colours_are_written_after_each_polygon() -> None:
    mesh = coloured_cube()
    lines = off_bytes(mesh).decode().splitlines()[11:]  # header, comment, counts, 8 vertices
    expected = np.rint(expected_written_colors(mesh) * 255).astype(int)
    assert [[int(v) for v in line.split()[5:]] for line in lines] == \
        [[*row, 255] for row in expected.tolist()]


def test_the_meshs_own_colours_come_back_from_its_off() -> None:
    mesh = coloured_cube()
    back = read_off(off_bytes(mesh))
    assert np.array_equal(back.face_colors(),
                          np.rint(expected_written_colors(mesh) * 255) / np.float32(255))
    validate(back)


_TRIANGLE = b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"


@pytest.mark.parametrize(("after", "color"), [
    (b"", None),
    (b" 255 0 51", (1.0, 0.0, 0.2)),
    (b" 255 0 51 0", (1.0, 0.0, 0.2)),  # alpha is dropped
    (b" 1.0 0 0.25", (1.0, 0.0, 0.25)),  # a decimal makes the scale [0, 1]
    (b" 1 0 0.5 1", (1.0, 0.0, 0.5)),
    (b" 7", None),  # a colour-map index: no colour of its own
    (b" 256 0 0", None),
    (b" 1.5 0 0", None),
    (b" -1 0 0", None),
    (b" 255 0", None),
    (b" red green blue", None),
    (b" 255 0 0 # a comment", (1.0, 0.0, 0.0)),
])
def test_a_face_colour_is_read_when_it_is_one(after: bytes, color: tuple | None) -> None:
    mesh = read_off(_TRIANGLE + b"3 0 1 2" + after + b"\n")
    got = mesh.face_colors()
    if color is None:
        assert got is None
    else:
        assert got is not None and np.allclose(got[0], color) and np.isnan(got[1]).all()


def test_faces_with_and_without_colour_mix_on_both_paths() -> None:
    quads = "\n".join(f"4 {i} {i + 1} {i + 5} {i + 4}" + (" 0 255 0" if i % 2 else "")
                       for i in range(3))
    data = ("OFF\n8 3 0\n" + "".join(f"{x} {y} 0\n" for y in (0, 1) for x in range(4)) +
            quads + "\n").encode()
    for text in (data, data.replace(b" 0 255 0", b" 0 1.0 0")):
        got = read_off(text).face_colors()
        assert got is not None
        assert np.isnan(got[[0, 2]]).all() and got[1].tolist() == [0.0, 1.0, 0.0]
