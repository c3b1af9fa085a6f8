"""STL and PLY export (livemod.dlfl.io.stl, .ply) and atomic writes (.atomic)."""

from __future__ import annotations

import os
import struct
from pathlib import Path

import numpy as np
import pytest

from livemod.dlfl import Mesh, from_polygons, validate
from livemod.dlfl.io import (
    atomic_write,
    load_mesh,
    save_mesh,
    write_atomically,
    write_ply,
    write_stl,
)
from livemod.dlfl.io import read_ply as load_ply
from livemod.dlfl.io.ply import ply_bytes
from livemod.dlfl.shapes import cube, soccer_ball
from tests.meshes import coloured_cube, expected_written_colors


def open_box() -> Mesh:
    """A cube without its top: 5 quads, one hole, plus a point-sphere."""
    mesh = cube()  # TopMod's cube.obj: face 0 is the top (+y)
    top = mesh.face_ids()[0]
    mesh.set_hole(top)
    mesh.create_vertex((4.0, 5.0, 6.0))
    return mesh


def read_stl(path: Path) -> tuple[bytes, np.ndarray]:
    data = path.read_bytes()
    (count,) = struct.unpack_from("<I", data, 80)
    dtype = np.dtype([("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    assert len(data) == 84 + 50 * count
    return data[:80], np.frombuffer(data, dtype=dtype, offset=84)


def test_stl_has_fans_of_the_drawn_faces_with_face_normals(tmp_path: Path) -> None:
    path = tmp_path / "box.stl"
    write_stl(open_box(), path)
    header, triangles = read_stl(path)
    assert header.startswith(b"livemod")
    assert len(triangles) == 5 * 2  # five quads, the hole and the point-sphere skipped
    corners = triangles["corners"].astype(np.float64)
    cross = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    assert np.allclose(cross / np.linalg.norm(cross, axis=1)[:, None], triangles["normal"])
    assert not np.any(np.all(triangles["normal"] == [0, 1, 0], axis=1))  # the top is a hole


def test_stl_of_pentagons_and_hexagons(tmp_path: Path) -> None:
    path = tmp_path / "ball.stl"
    save_mesh(soccer_ball(), path)
    _, triangles = read_stl(path)
    assert len(triangles) == 12 * 3 + 20 * 4


def read_ply(path: Path) -> tuple[list[str], np.ndarray, list[list[int]]]:
    data = path.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().splitlines()
    num_v = int(next(h for h in header if h.startswith("element vertex")).split()[2])
    num_f = int(next(h for h in header if h.startswith("element face")).split()[2])
    positions = np.frombuffer(data, dtype="<f8", count=3 * num_v, offset=end).reshape(-1, 3)
    pos = end + 24 * num_v
    faces = []
    for _ in range(num_f):
        size = data[pos]
        faces.append(list(struct.unpack_from(f"<{size}i", data, pos + 1)))
        pos += 1 + 4 * size
    assert pos == len(data)
    return header, positions, faces


def test_ply_binary_polygons_without_holes(tmp_path: Path) -> None:
    mesh = open_box()
    path = tmp_path / "box.ply"
    write_ply(mesh, path)
    header, positions, faces = read_ply(path)
    assert header[:2] == ["ply", "format binary_little_endian 1.0"]
    assert "property list uchar int vertex_indices" in header
    assert np.array_equal(positions, mesh.positions_view())
    assert faces == [mesh.face_vertices(f) for f in mesh.face_ids()[1:6]]


def test_ply_with_a_huge_face_uses_uint_counts(tmp_path: Path) -> None:
    angles = np.linspace(0, 2 * np.pi, 300, endpoint=False)
    ring = np.stack([np.cos(angles), np.sin(angles), 0 * angles], axis=1)
    mesh = from_polygons(ring, [list(range(300)), list(range(299, -1, -1))])
    path = tmp_path / "disk.ply"
    write_ply(mesh, path)
    data = path.read_bytes()
    assert b"property list uint int vertex_indices" in data
    end = data.index(b"end_header\n") + len(b"end_header\n") + 24 * 300
    assert struct.unpack_from("<I", data, end)[0] == 300
    assert len(data) == end + 2 * (4 + 4 * 300)


# ------------------------------------------------------------ atomic writes


def test_saving_through_a_symlink_replaces_its_target_and_keeps_the_link(
        tmp_path: Path) -> None:
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "model.obj"
    target.write_bytes(b"old")
    link, dangling = tmp_path / "model.obj", tmp_path / "new.obj"
    link.symlink_to(target)
    dangling.symlink_to(tmp_path / "real" / "new.obj")
    save_mesh(cube(), link)
    save_mesh(cube(), dangling)
    assert link.is_symlink() and dangling.is_symlink()
    assert load_mesh(target).counts() == (8, 12, 6)
    assert load_mesh(tmp_path / "real" / "new.obj").counts() == (8, 12, 6)
    assert sorted(p.name for p in (tmp_path / "real").iterdir()) == ["model.obj", "new.obj"]


def test_atomic_write_replaces_only_on_success(tmp_path: Path) -> None:
    path = tmp_path / "a.bin"
    path.write_bytes(b"old")
    with pytest.raises(RuntimeError), atomic_write(path) as handle:
        handle.write(b"half")
        raise RuntimeError("disk on fire")
    assert path.read_bytes() == b"old"
    assert os.listdir(tmp_path) == ["a.bin"]
    with atomic_write(path) as handle:
        handle.write(b"new")
    assert path.read_bytes() == b"new"
    assert os.listdir(tmp_path) == ["a.bin"]


def test_pieces_are_written_in_order_and_a_failing_piece_keeps_the_old_file(
    tmp_path: Path,
) -> None:
    path = tmp_path / "a.bin"
    write_atomically(path, iter([b"one ", b"two ", b"three"]))
    assert path.read_bytes() == b"one two three"

    def pieces():  # type: ignore[no-untyped-def]
        yield b"half a file"
        raise ValueError("the mesh went away")

    with pytest.raises(ValueError, match="went away"):
        write_atomically(path, pieces())
    assert path.read_bytes() == b"one two three"
    assert os.listdir(tmp_path) == ["a.bin"]


def test_new_files_get_ordinary_permissions(tmp_path: Path) -> None:
    path = tmp_path / "fresh.obj"
    save_mesh(open_box(), path)
    assert path.stat().st_mode & 0o777 == 0o644


@pytest.mark.parametrize("ext", ["obj", "dlfl", "stl", "ply"])
def test_a_save_that_fails_midway_leaves_the_old_file(
    ext: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = tmp_path / f"mesh.{ext}"
    save_mesh(open_box(), path)
    before = path.read_bytes()

    class Exploding:
        def __init__(self, real: object) -> None:
            self.real = real

        def write(self, data: bytes) -> int:
            self.real.write(data[: len(data) // 2])  # type: ignore[attr-defined]
            raise OSError("no space left on device")

        def __getattr__(self, name: str) -> object:
            return getattr(self.real, name)

    real_atomic = atomic_write

    def failing(target: str, **options):  # type: ignore[no-untyped-def]
        import contextlib

        @contextlib.contextmanager
        def wrapped():  # type: ignore[no-untyped-def]
            with real_atomic(target, **options) as handle:
                yield Exploding(handle)

        return wrapped()

    # every writer goes through write_atomically, which opens atomic_write
    monkeypatch.setattr("livemod.dlfl.io.atomic.atomic_write", failing)
    with pytest.raises(OSError, match="no space"):
        save_mesh(soccer_ball(), path)
    assert path.read_bytes() == before
    assert os.listdir(tmp_path) == [path.name]


@pytest.mark.parametrize("points", [0, 1, 3])
def test_every_format_writes_point_clouds_and_empty_meshes(points: int, tmp_path: Path) -> None:
    from livemod.dlfl import validate
    from livemod.dlfl.io import load_mesh

    mesh = Mesh()
    for i in range(points):
        mesh.create_vertex((i, 0.5, -i))
    for ext in ("obj", "dlfl", "stl", "ply"):
        save_mesh(mesh, tmp_path / f"cloud.{ext}")
    for ext in ("obj", "dlfl"):
        again = load_mesh(tmp_path / f"cloud.{ext}")
        validate(again)
        assert again.counts() == (points, 0, points)
        assert np.array_equal(again.positions_view(), mesh.positions_view())
    _, triangles = read_stl(tmp_path / "cloud.stl")
    assert len(triangles) == 0
    header, positions, faces = read_ply(tmp_path / "cloud.ply")
    assert len(positions) == points and faces == []


def test_a_killed_writer_can_remove_its_unfinished_temporary_file(tmp_path: Path) -> None:
    from livemod.dlfl.io.atomic import remove_unfinished

    target = tmp_path / "mesh.obj"
    target.write_bytes(b"old")
    with pytest.raises(FileNotFoundError), atomic_write(target) as handle:
        handle.write(b"half of a new mesh")
        remove_unfinished()  # what a batch worker does on SIGTERM, before it exits
        assert sorted(p.name for p in tmp_path.iterdir()) == ["mesh.obj"]
    assert target.read_bytes() == b"old"
    remove_unfinished()  # nothing under way: nothing to do


def test_ply_face_colours_are_read_back_by_livemod_and_trimesh(tmp_path: Path) -> None:
    import trimesh

    mesh = coloured_cube()
    write_ply(mesh, tmp_path / "c.ply")
    expected = np.rint(expected_written_colors(mesh) * 255).astype(np.uint8)
    back = load_ply(tmp_path / "c.ply")
    validate(back)
    np.testing.assert_array_equal(np.rint(back.face_colors() * 255), expected)
    peer = trimesh.load(tmp_path / "c.ply", process=False)
    # trimesh 5.2 keeps one colour per face row of the file (its quads cut in two)
    assert len(peer.faces) == 12
    np.testing.assert_array_equal(peer.visual.face_colors[:, :3], expected)


def test_a_ply_without_colours_writes_no_colour_properties() -> None:
    assert b"red" not in ply_bytes(cube())
    assert load_ply(ply_bytes(cube())).face_colors() is None


def test_ply_colours_of_any_declared_type_scale_to_unit_range() -> None:
    header = (b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              b"property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              b"property %s red\nproperty %s green\nproperty %s blue\nend_header\n"
              b"0 0 0\n1 0 0\n0 1 0\n3 0 1 2 %s\n")
    cases = [(b"uchar", b"255 51 0", [1.0, 0.2, 0.0]), (b"ushort", b"65535 0 13107", [1.0, 0.0, 0.2]),
             (b"float", b"0.5 2.0 -1", [0.5, 1.0, 0.0])]
    for kind, values, expected in cases:
        mesh = load_ply(header % (kind, kind, kind, values))
        np.testing.assert_allclose(mesh.face_colors()[0], expected, rtol=1e-6)
