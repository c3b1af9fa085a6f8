"""The id tables behind a mesh (livemod/dlfl/_table.py), through the mesh's own API."""

from __future__ import annotations

import numpy as np

from livemod.dlfl import from_corner_arrays, mesh_arrays, validate
from tests.meshes import cube


def adopted_cube(vertex_ids: list[int] | None = None, corner_ids: list[int] | None = None):
    """:func:`cube` rebuilt with ``vertex_ids`` for its vertices and ``corner_ids``
    for its corners (None: the usual ids)."""
    a = mesh_arrays(cube())
    ids = (None if vertex_ids is None else np.array(vertex_ids), None, None,
           None if corner_ids is None else np.array(corner_ids))
    return from_corner_arrays(a.positions, a.face_offsets, a.corner_vertex, a.corner_mate,
                              a.face_hole, ids=ids)


def test_a_reused_slot_that_is_home_to_its_fresh_id_stays_valid():
    # ids 10..16 then 5: the next id (17) is short of base + n (18), so the
    # second created vertex lands in a reused slot that is its own home slot
    mesh = adopted_cube([10, 11, 12, 13, 14, 15, 16, 5])
    first = mesh.create_vertex((2.0, 0.0, 0.0))
    mesh.remove_vertex(first)
    second = mesh.create_vertex((3.0, 0.0, 0.0))
    validate(mesh)
    assert (first, second) == (17, 18)
    assert mesh.position(second).tolist() == [3.0, 0.0, 0.0]
    assert mesh.vertex_ids().tolist() == [5, 10, 11, 12, 13, 14, 15, 16, 18]


def test_reused_slots_taken_in_pairs_stay_valid():
    # corner ids 100..122 then 1: after one edge is inserted and deleted, the
    # next pair of corners reuses two slots, one of them its id's home slot
    mesh = adopted_cube(corner_ids=[*range(100, 123), 1])
    corners = mesh.face_corners(0)
    mesh.delete_edge(mesh.insert_edge(corners[0], corners[2]))
    corners = mesh.face_corners(0)
    mesh.insert_edge(corners[1], corners[3])
    validate(mesh)
    assert mesh.counts() == (8, 13, 7)
    assert sorted(mesh.corner_ids().tolist())[-3:] == [122, 125, 126]
