"""Every example in scripts/ runs headless with the counts its operations imply, and
matches its stored snapshot (the livemod_snapshot fixture of livemod's pytest plugin).

Expected counts are derived from the rules of the operations the script uses (so
a wrong operation fails here), e.g. a cubical extrusion of a quad adds 4 vertices,
8 edges and 4 faces; Catmull-Clark maps (V, E, F) with C = 2E corners to
(V + E + F, 2E + C, C) and Doo-Sabin to (2E, 4E, F + E + V).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np
import pytest

from livemod.dlfl import genus, mesh_arrays, validate
from livemod.dlfl.analysis import component_genera
from livemod.dlfl.shapes import cube
from livemod.dlfl.subdivision import subdivide
from livemod.runner.execute import execute
from tests.images import read_image

SCRIPTS = Path(__file__).resolve().parents[1] / "scripts"


def run(name: str, **parameters: object):
    outcome = execute(SCRIPTS / name, parameters=parameters or None)
    assert outcome.error is None, outcome.error
    mesh = outcome.scene.mesh
    validate(mesh)
    return outcome, mesh


def catmull_clark(v: int, e: int, f: int) -> tuple[int, int, int]:
    corners = 2 * e
    return v + e + f, 2 * e + corners, corners


def doo_sabin(v: int, e: int, f: int) -> tuple[int, int, int]:
    # one vertex per corner (C = 2E), each of valence 4; one face per face, edge, vertex
    return 2 * e, 4 * e, f + e + v


def extrude_quads(counts: tuple[int, int, int], times: int, sides: int = 4) -> tuple[int, int, int]:
    v, e, f = counts
    return v + sides * times, e + 2 * sides * times, f + sides * times


def test_triangle_is_three_vertices_three_edges_two_faces() -> None:
    _, mesh = run("triangle.py")
    assert mesh.counts() == (3, 3, 2)
    assert genus(mesh) == 0


def test_doo_sabin_by_hand_matches_the_built_in_scheme() -> None:
    _, by_hand = run("doo_sabin_by_hand.py")
    builtin = cube()
    first = builtin.edge_ids()[0]
    c0, _ = builtin.edge_corners(first)
    builtin.insert_edge(c0, builtin.corner_next(c0))  # the same overlapping edge
    subdivide(builtin, "doo-sabin")
    assert by_hand.counts() == builtin.counts() == doo_sabin(8, 13, 7)
    a, b = mesh_arrays(by_hand), mesh_arrays(builtin)
    assert sorted(a.face_sizes.tolist()) == sorted(b.face_sizes.tolist())
    pa = np.array(sorted(map(tuple, a.positions)))
    pb = np.array(sorted(map(tuple, b.positions)))
    np.testing.assert_allclose(pa, pb, rtol=0, atol=1e-12)


@pytest.mark.parametrize("storeys", [36, 3])
def test_tower_counts_follow_from_its_extrusions(storeys: int) -> None:
    _, mesh = run("tower.py", storeys=storeys)
    v, e, f = extrude_quads((8, 12, 6), storeys)
    # two duals give the same counts back; then Doo-Sabin
    assert mesh.counts() == doo_sabin(v, e, f)
    assert genus(mesh) == 0


def test_two_towers_wireframe_has_one_handle_per_independent_cycle() -> None:
    _, mesh = run("two_towers.py", levels=5, time=1.0)
    # the cube's top is split in two: two edge subdivisions (+1 V, +1 E each) and an edge
    v, e, _ = extrude_quads((8 + 2, 12 + 2 + 1, 6 + 1), 2 * 5)
    assert mesh.counts()[:2] == (4 * e, 10 * e)
    assert genus(mesh) == e - v + 1


def test_organic_dodecahedron_counts() -> None:
    _, mesh = run("organic_dodecahedron.py")
    counts = extrude_quads((20, 30, 12), 2 * 12, sides=5)
    assert mesh.counts() == catmull_clark(*counts)
    assert genus(mesh) == 0


def test_rind_soccerball_punches_faces_into_a_crust() -> None:
    outcome, mesh = run("rind_soccerball.py")
    label = next(s.label for s in outcome.steps if s.label.endswith("faces to punch"))
    punched = int(label.split()[0])
    assert punched > 0
    # the punched quads come in threes around each 3-valent vertex; rind's cleanup
    # (TopMod's default) merges each three into one triangular hole (thesis fig. 30)
    assert component_genera(mesh) == [punched // 3 - 1]


def test_wireframe_soccerball_genus_is_its_cycle_rank() -> None:
    _, mesh = run("wireframe_soccerball.py", thickness=0.05)
    assert mesh.counts()[:2] == (4 * 90, 10 * 90)
    assert genus(mesh) == 90 - 60 + 1


def test_thirty_soccerballs_are_thirty_objects() -> None:
    outcome, _ = run("wireframe_soccerballs.py", count=4)
    scene = outcome.scene
    assert len(scene.objects) == 4
    for obj in scene.objects.values():
        validate(obj.mesh)
        assert genus(obj.mesh) == 31
    origins = [tuple(obj.origin) for obj in scene.objects.values()]
    assert origins == [(0.0, 0.0, 0.0), (3.0, 0.0, 0.0), (6.0, 0.0, 0.0), (9.0, 0.0, 0.0)]


def test_handle_adds_a_genus() -> None:
    _, mesh = run("handle.py", segments=10)
    assert mesh.counts() == catmull_clark(44, 88, 44)
    assert genus(mesh) == 1


def test_connect_faces_makes_a_torus_of_the_cube() -> None:
    _, mesh = run("connect_faces.py", segments=3)
    # two insets (+4 V, +8 E, +4 F each); a 3-segment tube adds two rings of 4
    # vertices, 8 ring edges and 12 side edges, and 12 quads for the 2 faces it opens
    v, e, f = extrude_quads((8, 12, 6), 2)
    assert mesh.counts() == doo_sabin(v + 8, e + 20, f + 10)
    assert genus(mesh) == 1


def test_steps_demo_records_labelled_steps() -> None:
    outcome = execute(SCRIPTS / "steps_demo.py")
    labels = [s.label for s in outcome.steps]
    assert labels[:2] == ["load cube", "the cube"]
    assert "storey 4" in labels and labels[-1] == "smoothed"
    assert outcome.scene.mesh.counts() == catmull_clark(*extrude_quads((8, 12, 6), 4))


def test_user_mesh_starts_from_the_given_mesh() -> None:
    _, mesh = run("user_mesh.py")
    counts = extrude_quads((100, 150, 50), 50, sides=6)
    assert mesh.counts() == catmull_clark(*counts)
    assert genus(mesh) == 1


SCRIPT_NAMES = sorted(p.name for p in SCRIPTS.glob("*.py"))
SNAPSHOTS = Path(__file__).resolve().parent / "__snapshots__" / "test_scripts"
SNAPSHOT_PARAMETERS = {"wireframe_soccerballs.py": {"count": 2}}


@pytest.mark.parametrize("name", SCRIPT_NAMES)
def test_every_script_matches_its_snapshot(name: str, livemod_snapshot: Any) -> None:
    # counts, genus per component, face sizes, box and picture, stored in
    # tests/__snapshots__/test_scripts/ (pytest --livemod-update after a meant change)
    livemod_snapshot.assert_script(SCRIPTS / name, parameters=SNAPSHOT_PARAMETERS.get(name))


@pytest.mark.parametrize("name", SCRIPT_NAMES)
def test_every_stored_snapshot_picture_shows_its_model(name: str) -> None:
    image = read_image(SNAPSHOTS / f"test_every_script_matches_its_snapshot[{name}].png", "RGB")
    covered = np.any(np.abs(image.astype(int) - image[0, 0]) > 12, axis=2).mean()
    assert image.shape == (180, 240, 3) and 0.02 < covered < 0.95


def test_relative_file_names_are_read_and_written_next_to_the_script(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    folder = tmp_path / "project"
    folder.mkdir()
    (folder / "model.py").write_text(
        "from livemod.dlfl import *\n"
        "load('cube')\n"
        "save('out/cube.obj')\n"
        "load('out/cube.obj')\n"
    )
    (folder / "out").mkdir()
    monkeypatch.chdir(tmp_path)  # the working directory is elsewhere
    outcome = execute(folder / "model.py")
    assert outcome.error is None, outcome.error
    assert (folder / "out" / "cube.obj").exists()
    assert outcome.scene.mesh.counts() == (8, 12, 6)
    assert [s.label for s in outcome.steps] == ["load cube", "load out/cube.obj"]
