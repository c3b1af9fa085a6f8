"""3MF: read back by trimesh and by lib3mf (manifold, oriented, colours, units)."""

from __future__ import annotations

import zipfile
from pathlib import Path

import lib3mf
import numpy as np
import pytest
import trimesh

from livemod.dlfl import mesh_arrays
from livemod.dlfl.errors import InvalidArgumentError
from livemod.dlfl.io import save_mesh, save_objects
from livemod.dlfl.io.threemf import write_3mf
from livemod.dlfl.shapes import load_shape
from tests.meshes import coloured_cube, expected_written_colors, point_sphere, torus


def lib3mf_model(path: Path) -> tuple[lib3mf.Model, list[lib3mf.MeshObject]]:
    model = lib3mf.get_wrapper().CreateModel()
    reader = model.QueryReader("3mf")
    reader.SetStrictModeActive(True)
    reader.ReadFromFile(str(path))
    assert reader.GetWarningCount() == 0
    objects, found = [], model.GetMeshObjects()
    while found.MoveNext():
        objects.append(found.GetCurrentMeshObject())
    return model, objects


@pytest.mark.parametrize("shape", ["soccerball", "genus3hexa1", "cube"])
def test_lib3mf_and_trimesh_read_a_printable_mesh(shape: str, tmp_path: Path) -> None:
    mesh = load_shape(shape)
    save_mesh(mesh, tmp_path / "m.3mf")
    model, (part,) = lib3mf_model(tmp_path / "m.3mf")
    a = mesh_arrays(mesh)
    sizes = a.face_sizes
    assert part.GetVertexCount() == len(a.positions)
    assert part.GetTriangleCount() == int((sizes - 2).sum())
    assert part.IsManifoldAndOriented()
    assert model.GetUnit() == lib3mf.ModelUnit.MilliMeter
    peer = trimesh.load(tmp_path / "m.3mf", force="mesh", process=False)
    assert peer.is_watertight and peer.volume > 0
    assert np.allclose(np.sort(peer.vertices, axis=0), np.sort(a.positions, axis=0))


def test_the_unit_option_and_an_unknown_unit(tmp_path: Path) -> None:
    write_3mf(torus(), tmp_path / "t.3mf", unit="inch")
    model, _ = lib3mf_model(tmp_path / "t.3mf")
    assert model.GetUnit() == lib3mf.ModelUnit.Inch
    with pytest.raises(InvalidArgumentError, match="unknown 3MF unit 'furlong'"):
        write_3mf(torus(), tmp_path / "t.3mf", unit="furlong")


def test_face_colours_are_a_colour_group(tmp_path: Path) -> None:
    mesh = load_shape("cube")
    colours = np.array([[1.0, 0, 0], [0, 1.0, 0], [1.0, 0, 0], [0, 0, 1.0], [0, 1.0, 0],
                        [1.0, 1.0, 1.0]])
    write_3mf(mesh, tmp_path / "c.3mf", face_colors=colours)
    model, (part,) = lib3mf_model(tmp_path / "c.3mf")
    groups = model.GetColorGroups()
    assert groups.MoveNext()
    group = groups.GetCurrentColorGroup()
    assert group.GetCount() == 4  # the distinct colours
    rgba = {(col.Red, col.Green, col.Blue)
            for col in (group.GetColor(i) for i in group.GetAllPropertyIDs())}
    assert rgba == {(255, 0, 0), (0, 255, 0), (0, 0, 255), (255, 255, 255)}
    a = mesh_arrays(mesh)
    properties = part.GetAllTriangleProperties()
    ids = group.GetAllPropertyIDs()
    faces = np.repeat(np.arange(6), a.face_sizes - 2)
    for face, prop in zip(faces.tolist(), properties, strict=True):
        colour = group.GetColor(prop.PropertyIDs[0])
        got = [colour.Red, colour.Green, colour.Blue]
        assert got == (colours[face] * 255).astype(int).tolist()
        assert prop.ResourceID == group.GetResourceID() and prop.PropertyIDs[0] in ids


def test_one_object_per_scene_object_under_its_name(tmp_path: Path) -> None:
    save_objects([("base", load_shape("cube")), ("ring", torus(6, 4))], tmp_path / "s.3mf")
    model, parts = lib3mf_model(tmp_path / "s.3mf")
    assert [p.GetName() for p in parts] == ["base", "ring"]
    assert [p.GetTriangleCount() for p in parts] == [12, 48]
    items = model.GetBuildItems()
    assert items.Count() == 2
    scene = trimesh.load(tmp_path / "s.3mf", process=False)
    assert sorted(scene.geometry) == ["base", "ring"]


def test_a_point_sphere_is_left_out_of_the_printable_mesh(tmp_path: Path) -> None:
    mesh = load_shape("cube")
    mesh.create_vertex((9.0, 9.0, 9.0))
    write_3mf(mesh, tmp_path / "p.3mf")
    _, (part,) = lib3mf_model(tmp_path / "p.3mf")
    assert part.GetVertexCount() == 8 and part.IsManifoldAndOriented()
    write_3mf(point_sphere(), tmp_path / "q.3mf")  # nothing printable: an empty object
    assert lib3mf_model(tmp_path / "q.3mf")[1][0].GetTriangleCount() == 0


def test_the_package_holds_the_parts_3mf_asks_for(tmp_path: Path) -> None:
    write_3mf(torus(), tmp_path / "t.3mf")
    with zipfile.ZipFile(tmp_path / "t.3mf") as package:
        assert sorted(package.namelist()) == ["3D/3dmodel.model", "[Content_Types].xml",
                                              "_rels/.rels"]
        assert package.getinfo("3D/3dmodel.model").compress_type == zipfile.ZIP_DEFLATED


def test_the_meshs_own_colours_become_its_colour_group(tmp_path: Path) -> None:
    mesh = coloured_cube()
    save_mesh(mesh, tmp_path / "c.3mf")
    model, (part,) = lib3mf_model(tmp_path / "c.3mf")
    groups = model.GetColorGroups()
    assert groups.MoveNext()
    group = groups.GetCurrentColorGroup()
    expected = np.rint(expected_written_colors(mesh) * 255).astype(int)
    assert group.GetCount() == len(np.unique(expected, axis=0))  # 4: red counts once
    for face, prop in zip(np.repeat(np.arange(6), 2).tolist(), part.GetAllTriangleProperties(),
                          strict=True):
        colour = group.GetColor(prop.PropertyIDs[0])
        assert [colour.Red, colour.Green, colour.Blue] == expected[face].tolist()
