"""glTF 2.0 (.glb, .gltf + .bin): read back by trimesh and checked by pygltflib."""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pygltflib
import pytest
import trimesh

from livemod.dlfl import Mesh, from_polygons, mesh_arrays
from livemod.dlfl.analysis import face_areas, face_normals
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.io import save_mesh, save_objects
from livemod.dlfl.io.gltf import glb_bytes, write_gltf
from livemod.dlfl.shapes import load_shape
from tests.meshes import coloured_cube, expected_written_colors, torus, triangle


def triangle_count(mesh) -> int:  # type: ignore[no-untyped-def]
    a = mesh_arrays(mesh)
    drawn = ~a.face_hole & (a.face_sizes >= 3)
    return int((a.face_sizes[drawn] - 2).sum())


def accessor(doc: pygltflib.GLTF2, index: int) -> np.ndarray:
    """The array of accessor ``index`` of a loaded GLB (pygltflib's own reading)."""
    acc = doc.accessors[index]
    view = doc.bufferViews[acc.bufferView]
    blob = doc.binary_blob()
    dtype = {5126: "<f4", 5121: "u1", 5125: "<u4"}[acc.componentType]
    width = {"SCALAR": 1, "VEC3": 3, "VEC4": 4}[acc.type]
    data = np.frombuffer(blob, dtype, acc.count * width, view.byteOffset + (acc.byteOffset or 0))
    return data.reshape(acc.count, width) if width > 1 else data


@pytest.mark.parametrize("shape", ["soccerball", "cube", "genus3hexa1"])
def test_trimesh_loads_the_glb_with_the_same_surface(shape: str, tmp_path: Path) -> None:
    mesh = load_shape(shape)
    save_mesh(mesh, tmp_path / "m.glb")
    peer = trimesh.load(tmp_path / "m.glb", force="mesh", process=False)
    assert len(peer.faces) == triangle_count(mesh)
    merged = trimesh.Trimesh(peer.vertices, peer.faces)  # welded as trimesh does
    a = mesh_arrays(mesh)
    assert len(merged.vertices) == len(a.positions)
    assert merged.is_watertight and merged.is_winding_consistent
    assert merged.volume > 0  # the faces point outward
    assert np.isclose(merged.area, peer.area)


def _house() -> Mesh:
    """A triangle-capped pentagonal prism on a quad: faces of 3, 4 and 5 corners."""
    angles = 2 * np.pi * np.arange(5) / 5
    ring = np.stack([np.cos(angles), np.sin(angles), np.zeros(5)], axis=1)
    positions = np.concatenate([ring, ring + (0, 0, 2), [(0, 0, 3)]])
    sides = [[k, (k + 1) % 5, 5 + (k + 1) % 5, 5 + k] for k in range(5)]
    roof = [[5 + k, 5 + (k + 1) % 5, 10] for k in range(5)]
    return from_polygons(positions, [[4, 3, 2, 1, 0], *sides, *roof])


@pytest.mark.parametrize("make", [lambda: load_shape("cube"), lambda: load_shape("soccerball"),
                                  _house], ids=["quads", "pentagons-hexagons", "mixed"])
def test_flat_normals_are_each_faces_and_smooth_ones_each_vertexs(make: Callable[[], Mesh],
                                                                  tmp_path: Path) -> None:
    mesh = make()
    a = mesh_arrays(mesh)
    vector_area = face_normals(a) * face_areas(a)[:, None]  # normal times area
    around = np.stack([np.bincount(a.corner_vertex, vector_area[a.corner_face, k]) for k in range(3)], 1)
    around /= np.linalg.norm(around, axis=1, keepdims=True)
    for smooth, expected in [(False, face_normals(a)[a.corner_face]),
                             (True, around[a.corner_vertex])]:
        write_gltf(mesh, tmp_path / "m.glb", smooth=smooth)
        doc = pygltflib.GLTF2().load(str(tmp_path / "m.glb"))
        attributes = doc.meshes[0].primitives[0].attributes
        assert attributes.TEXCOORD_0 is None and attributes.COLOR_0 is None
        normals = accessor(doc, attributes.NORMAL)
        assert np.allclose(normals, expected.astype(np.float32))
        assert np.allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-6)
        position = doc.accessors[attributes.POSITION]  # bounds exactly those written
        written = accessor(doc, attributes.POSITION)
        assert position.min == written.min(axis=0).tolist()
        assert position.max == written.max(axis=0).tolist()
        assert np.allclose(position.min, a.positions.min(axis=0))


def test_face_colours_become_each_corners_colour(tmp_path: Path) -> None:
    mesh = load_shape("cube")
    colours = np.arange(24, dtype=np.uint8).reshape(6, 4) * 10
    write_gltf(mesh, tmp_path / "m.glb", face_colors=colours)
    doc = pygltflib.GLTF2().load(str(tmp_path / "m.glb"))
    attributes = doc.meshes[0].primitives[0].attributes
    assert doc.accessors[attributes.COLOR_0].normalized
    a = mesh_arrays(mesh)
    assert np.array_equal(accessor(doc, attributes.COLOR_0), colours[a.corner_face])
    peer = trimesh.load(tmp_path / "m.glb", force="mesh", process=False)
    assert np.array_equal(peer.visual.vertex_colors, colours[a.corner_face])
    with pytest.raises(InvalidArgumentError, match="must lie in"):
        write_gltf(mesh, tmp_path / "m.glb", face_colors=np.full((6, 3), 2.0))


def test_gltf_writes_a_bin_beside_it_and_names_it(tmp_path: Path) -> None:
    mesh = torus(5, 4)
    save_mesh(mesh, tmp_path / "t.gltf")
    document = json.loads((tmp_path / "t.gltf").read_text())
    assert document["buffers"] == [{"byteLength": (tmp_path / "t.bin").stat().st_size,
                                    "uri": "t.bin"}]
    peer = trimesh.load(tmp_path / "t.gltf", force="mesh", process=False)
    assert len(peer.faces) == 2 * 20
    assert (tmp_path / "t.bin").read_bytes() in glb_bytes(mesh)


def test_one_node_per_object_with_its_name(tmp_path: Path) -> None:
    objects = [("cube", load_shape("cube")), ("ball", load_shape("soccerball")),
               ("hole only", triangle())]
    save_objects(objects, tmp_path / "s.glb")
    doc = pygltflib.GLTF2().load(str(tmp_path / "s.glb"))
    assert [node.name for node in doc.nodes] == ["cube", "ball", "hole only"]
    assert doc.scenes[0].nodes == [0, 1, 2]
    scene = trimesh.load(tmp_path / "s.glb", process=False)
    counts = sorted(len(g.faces) for g in scene.geometry.values())
    assert counts == sorted(triangle_count(m) for _, m in objects)


def test_a_mesh_with_no_face_to_draw_is_a_node_without_a_mesh(tmp_path: Path) -> None:
    from tests.meshes import point_sphere

    write_gltf(point_sphere(), tmp_path / "p.glb")
    doc = pygltflib.GLTF2().load(str(tmp_path / "p.glb"))
    assert doc.nodes[0].mesh is None and doc.meshes == []


def test_the_glb_layout_is_aligned_and_sized(tmp_path: Path) -> None:
    data = glb_bytes(load_shape("soccerball"))
    magic, version, length = np.frombuffer(data[:12], "<u4")
    assert data[:4] == b"glTF" and version == 2 and length == len(data)
    json_length = int(np.frombuffer(data[12:16], "<u4")[0])
    assert json_length % 4 == 0 and data[16:20] == b"JSON"
    assert data[20 + json_length + 4 : 20 + json_length + 8] == b"BIN\0"


def test_glb_named_by_format_is_binary_whatever_the_file_s_name(tmp_path: Path) -> None:
    mesh = torus(5, 4)
    save_mesh(mesh, tmp_path / "staged.tmp", format="glb")  # as a batch stages it
    assert (tmp_path / "staged.tmp").read_bytes() == glb_bytes(mesh)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["staged.tmp"]  # no .bin


def test_the_meshs_own_colours_are_written_unless_others_are_given(tmp_path: Path) -> None:
    mesh = coloured_cube()
    save_mesh(mesh, tmp_path / "c.glb")
    doc = pygltflib.GLTF2().load(str(tmp_path / "c.glb"))
    attributes = doc.meshes[0].primitives[0].attributes
    a = mesh_arrays(mesh)
    expected = np.rint(expected_written_colors(mesh) * 255).astype(np.uint8)[a.corner_face]
    assert np.array_equal(accessor(doc, attributes.COLOR_0)[:, :3], expected)
    peer = trimesh.load(tmp_path / "c.glb", force="mesh", process=False)
    assert np.array_equal(peer.visual.vertex_colors[:, :3], expected)
