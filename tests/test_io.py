"""Choosing a format and writing a scene's objects (livemod.dlfl.io)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
import trimesh

from livemod.dlfl import InvalidArgumentError, genus, mesh_arrays, validate
from livemod.dlfl.io import (
    READERS,
    WRITERS,
    companion_paths,
    keeps_objects,
    load_mesh,
    save_mesh,
    save_objects,
    scene_objects,
)
from livemod.dlfl.scene import Scene
from livemod.dlfl.shapes import cube, torus

from .meshes import coloured_cube


def _scene() -> tuple[Scene, int]:
    scene = Scene()
    scene.add(cube(), "base")
    ring = scene.add(torus(4, 3))  # unnamed
    return scene, ring


def test_a_scene_s_objects_are_named_and_in_creation_order():
    scene, ring = _scene()
    assert [name for name, _ in scene_objects(scene)] == ["base", f"object {ring}"]
    assert scene_objects(scene, all_objects=False) == \
        [(f"object {ring}", scene.objects[ring].mesh)]  # the current one
    scene.kill(ring)
    scene.current = ring  # a script may leave current on an object it killed
    assert scene_objects(scene, all_objects=False) == [] and len(scene_objects(scene)) == 1
    assert scene_objects(Scene()) == []


def test_a_scene_is_written_an_object_each_or_joined(tmp_path: Path):
    scene, ring = _scene()
    save_objects(scene, tmp_path / "s.glb")
    read = trimesh.load(tmp_path / "s.glb", process=False)
    assert sorted(len(g.faces) for g in read.geometry.values()) == [12, 2 * 12]
    save_objects(scene, tmp_path / "s.obj")
    joined = trimesh.load(tmp_path / "s.obj", process=False)
    assert len(joined.vertices) == 8 + 12 and len(joined.faces) == 12 + 2 * 12
    assert [keeps_objects(name) for name in ("a.GLB", "a.gltf", "a.3mf", "a.obj", "a.ply")] \
        == [True, True, True, False, False]
    assert keeps_objects("a.tmp", format="3mf")


def test_one_object_is_written_as_it_is_its_ids_kept(tmp_path: Path):
    mesh = cube()
    mesh.delete_edge(mesh.edge_ids()[0])  # a face gone: the ids are no longer dense
    (tmp_path / "one").mkdir()
    save_objects([("base", mesh)], tmp_path / "one" / "m.dlfl")
    save_mesh(mesh, tmp_path / "m.dlfl")
    assert (tmp_path / "one" / "m.dlfl").read_bytes() == (tmp_path / "m.dlfl").read_bytes()


# -- choosing the format -----------------------------------------------------------------

def test_load_and_save_dispatch_by_extension(tmp_path: Path) -> None:
    mesh = cube()
    for ext in ("obj", "dlfl"):
        save_mesh(mesh, tmp_path / f"c.{ext}")
        assert load_mesh(tmp_path / f"c.{ext}").counts() == (8, 12, 6)
    save_mesh(mesh, tmp_path / "c.txt", format="obj")
    assert load_mesh(tmp_path / "c.txt", format="OBJ").counts() == (8, 12, 6)


@pytest.mark.parametrize(("verb", "table"), [("write", WRITERS), ("read", READERS)])
def test_an_unknown_extension_is_refused_listing_the_registered_ones(verb, table, tmp_path):
    path = tmp_path / "c.nomesh"  # no format will take this extension
    valid = ", ".join(f".{key}" for key in table)
    message = re.escape(f"cannot {verb} ") + ".*" + re.escape(
        f"c.nomesh: unknown extension '.nomesh'; use one of {valid}") + "$"
    with pytest.raises(InvalidArgumentError, match=message):
        save_mesh(cube(), path) if verb == "write" else load_mesh(path)


# -- the format registries: every format is whole -------------------------------------

FORMATS_DOC = (Path(__file__).resolve().parents[1] / "docs" / "formats.md").read_text()


@pytest.mark.parametrize("key", sorted(set(READERS) | set(WRITERS)))
def test_every_format_is_documented_and_named_where_it_is_chosen(key: str):
    sections = [line for line in FORMATS_DOC.splitlines() if line.startswith("## ")]
    functions = [f"`{table[key].__name__}`" for table in (READERS, WRITERS) if key in table]
    assert any(all(name in line for name in functions) for line in sections), (
        f"docs/formats.md has no section for .{key}: a heading "
        f"'## <name> ({', '.join(functions)})'")
    for table, chooser in ((READERS, load_mesh), (WRITERS, save_mesh)):
        if key in table:
            assert f"``.{key}``" in (chooser.__doc__ or ""), (
                f"the docstring of {chooser.__name__} (livemod/dlfl/io/__init__.py) "
                f"does not name ``.{key}``")


@pytest.mark.parametrize("key", sorted(READERS))
def test_every_format_read_is_written_too_and_comes_back(key: str, tmp_path: Path):
    mesh = torus(6, 4)  # quads: a format without polygons gives two triangles each
    path = tmp_path / f"torus.{key}"
    save_mesh(mesh, path)
    back = load_mesh(path)
    validate(back)
    v, e, f = mesh.counts()
    assert back.counts() in ((v, e, f), (v, e + f, 2 * f)), (
        f".{key} must keep a surface: the torus {mesh.counts()} came back as {back.counts()} "
        "(V, E, F); polygons or two triangles a quad are kept")
    assert genus(back) == 1


def test_every_reader_has_valid_files_for_the_fuzzers():
    """tests/test_io_adversarial.py, tests/test_io_boundaries.py and
    fuzz/fuzz_readers.py read every format through its entries there."""
    from .io_inputs import FORMATS

    covered = {read for _, read in FORMATS.values()}
    missing = [key for key, read in READERS.items() if read not in covered]
    assert not missing, (f"formats read with no maker of valid files in FORMATS of "
                         f"tests/io_inputs.py: {missing}")


@pytest.mark.parametrize("key", sorted(WRITERS))
def test_a_writer_writes_beside_its_file_exactly_the_companions_it_lists(key: str,
                                                                        tmp_path: Path):
    """What a batch relies on to stage and put in place every file of an output."""
    save_mesh(coloured_cube(), tmp_path / f"m.{key}")
    listed = [Path(p).name for p in companion_paths(tmp_path / f"m.{key}")]
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([f"m.{key}", *listed])
    assert listed == {"obj": ["m.mtl"], "dlfl": ["m.mtl"], "gltf": ["m.bin"]}.get(key, [])


# -- a round trip through a file of each format keeps the surface


@pytest.mark.parametrize("ext", ["obj", "dlfl", "ply"])
def test_round_trip_through_a_file_keeps_counts_genus_and_positions(ext: str, tmp_path) -> None:
    mesh = torus()
    save_mesh(mesh, tmp_path / f"t.{ext}")
    back = load_mesh(tmp_path / f"t.{ext}")
    assert (back.num_vertices, back.num_edges, back.num_faces) == (
        mesh.num_vertices, mesh.num_edges, mesh.num_faces)
    assert genus(back) == genus(mesh) == 1
    assert np.array_equal(mesh_arrays(back).positions, mesh_arrays(mesh).positions)


@pytest.mark.parametrize("extension", [".stl", ".glb", ".gltf"])
def test_float32_formats_refuse_coordinates_past_their_range(extension: str,
                                                             tmp_path: Path) -> None:
    from livemod.dlfl.errors import GeometryError

    target = tmp_path / f"m{extension}"
    target.write_bytes(b"an older file")
    mesh = cube()
    mesh.set_position(0, (1e39, 0.0, 0.0))  # float32 tops out near 3.4e38
    name = {".stl": "STL"}.get(extension, "glTF")
    with pytest.raises(GeometryError, match=rf"^{name} stores coordinates as float32, up to "
                                            r"about 3\.4e\+38; this mesh has one of 1e\+39$"):
        save_mesh(mesh, target)
    assert target.read_bytes() == b"an older file"
    mesh.set_position(0, (3e38, 0.0, 0.0))  # within the range: written, read back finite
    save_mesh(mesh, target)
    if extension == ".stl":  # the records as the format lays them out
        data = np.frombuffer(target.read_bytes()[84:], dtype=np.dtype(
            [("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")]))
        written = data["corners"]
    else:
        written = trimesh.load(target, force="mesh").vertices
    assert np.isfinite(written).all() and written.max() == pytest.approx(3e38)
