"""Property-based stateful tests: random operator sequences on a corpus of meshes.

After every step the mesh must pass :func:`validate` and satisfy
``V - E + F == 2 (components - genus)``. Inserting an edge and deleting it again
restores the mesh; deleting an edge and inserting it again between its old side
corners gives an isomorphic mesh.
"""

from __future__ import annotations

import os
from collections.abc import Callable

import numpy as np
from hypothesis import HealthCheck, Phase, settings
from hypothesis import strategies as st
from hypothesis.stateful import RuleBasedStateMachine, initialize, invariant, precondition, rule

from livemod.dlfl import DLFLError, Mesh, from_polygons, mesh_arrays, validate
from livemod.dlfl.geometry import (
    cleanup_2gons,
    cleanup_winged_vertices,
    edge_cleanup,
    splice_corners,
    split_valence2_vertices,
)
from livemod.dlfl.io import read_dlfl
from livemod.dlfl.io.dlflfile import dlfl_bytes
from tests.meshes import (
    canonical,
    corner_structure,
    cube,
    euler_ok,
    path_face,
    point_sphere,
    snapshot,
    tetrahedron,
    torus,
    triangle,
    two_cubes,
)

CORPUS: list[Callable[[], Mesh]] = [
    point_sphere, triangle, cube, tetrahedron, lambda: torus(4, 3), two_cubes, path_face,
]

index = st.integers(min_value=0, max_value=2**16)
coordinate = st.floats(min_value=-10, max_value=10, allow_nan=False)
point = st.tuples(coordinate, coordinate, coordinate)


def pick(ids: list[int], i: int) -> int:
    return ids[i % len(ids)]


class MeshOperators(RuleBasedStateMachine):
    """Applies the minimal operators at random and checks the mesh after each."""

    mesh: Mesh

    @initialize(which=st.integers(min_value=0, max_value=len(CORPUS) - 1))
    def start(self, which: int) -> None:
        self.mesh = CORPUS[which]()

    # -- helpers -----------------------------------------------------------------

    def corners(self) -> list[int]:
        return self.mesh.corner_ids().tolist()

    def edges(self) -> list[int]:
        return self.mesh.edge_ids().tolist()

    def point_spheres(self) -> list[int]:
        m = self.mesh
        return [v for v in m.vertex_ids().tolist() if m.is_point_sphere(v)]

    def has_edges(self) -> bool:
        return self.mesh.num_edges > 0

    def has_corners(self) -> bool:
        return self.mesh.num_corners > 0

    # -- operators -----------------------------------------------------------------

    @precondition(has_corners)
    @rule(i=index, j=index)
    def insert_cofacial(self, i: int, j: int) -> None:
        m = self.mesh
        face = m.corner_face(pick(self.corners(), i))
        ring = m.face_corners(face)
        if len(ring) < 2:
            return
        c1 = pick(ring, j)
        c2 = pick([c for c in ring if c != c1], j // 7)
        counts = m.counts()
        e = m.insert_edge(c1, c2)
        assert m.counts() == (counts[0], counts[1] + 1, counts[2] + 1)
        assert m.edge_corners(e) == (c1, c2)

    @precondition(has_corners)
    @rule(i=index, j=index)
    def insert_merging(self, i: int, j: int) -> None:
        m = self.mesh
        c1 = pick(self.corners(), i)
        others = [c for c in self.corners() if m.corner_face(c) != m.corner_face(c1)]
        if not others:
            return
        counts = m.counts()
        m.insert_edge(c1, pick(others, j))
        assert m.counts() == (counts[0], counts[1] + 1, counts[2] - 1)

    @precondition(has_edges)
    @rule(i=index, cleanup=st.booleans())
    def delete(self, i: int, cleanup: bool) -> None:
        m = self.mesh
        e = pick(self.edges(), i)
        faces = m.delete_edge(e, cleanup)
        assert not m.has_edge(e)
        assert all(m.has_face(f) for f in faces)

    @precondition(has_edges)
    @rule(i=index, divisions=st.integers(min_value=1, max_value=4))
    def subdivide(self, i: int, divisions: int) -> None:
        m = self.mesh
        v, e, f = m.counts()
        new = m.subdivide_edge(pick(self.edges(), i), divisions)
        assert len(new) == divisions - 1
        assert m.counts() == (v + divisions - 1, e + divisions - 1, f)

    @precondition(has_edges)
    @rule(i=index, cleanup=st.booleans())
    def collapse(self, i: int, cleanup: bool) -> None:
        survivor = self.mesh.collapse_edge(pick(self.edges(), i), cleanup)
        assert self.mesh.has_vertex(survivor)

    @rule(position=point)
    def create_vertex(self, position: tuple[float, float, float]) -> None:
        v = self.mesh.create_vertex(position)
        assert self.mesh.is_point_sphere(v)

    @rule(i=index)
    def remove_point_sphere(self, i: int) -> None:
        spheres = self.point_spheres()
        if spheres:
            self.mesh.remove_vertex(pick(spheres, i))

    @rule(points=st.lists(point, min_size=2, max_size=5))
    def create_face(self, points: list[tuple[float, float, float]]) -> None:
        v, e, f = self.mesh.counts()
        self.mesh.create_face(points)
        n = len(points)
        assert self.mesh.counts() == (v + n, e + n, f + 2)

    @rule(i=index, j=index, which=st.integers(min_value=0, max_value=4))
    def cleanup_helper(self, i: int, j: int, which: int) -> None:
        """TopMod's cleanup helpers and spliceCorners, built on the operators."""
        m = self.mesh
        if which == 4:
            corners = self.corners()
            if len(corners) < 2:
                return
            c1 = pick(corners, i)
            c2 = pick([c for c in corners if c != c1], j)
            if m.corner_vertex(c1) != m.corner_vertex(c2):
                assert m.has_vertex(splice_corners(m, c1, c2))
            return
        helpers = (cleanup_2gons, cleanup_winged_vertices, edge_cleanup, split_valence2_vertices)
        helpers[which](m)

    # -- inverses ----------------------------------------------------------------

    @precondition(has_corners)
    @rule(i=index, j=index)
    def insert_then_delete(self, i: int, j: int) -> None:
        m = self.mesh
        c1 = pick(self.corners(), i)
        c2 = pick([c for c in self.corners() if c != c1] or [c1], j)
        if c1 == c2:
            return
        cofacial = m.corner_face(c1) == m.corner_face(c2)
        # cleanup would remove a point-sphere side that the insert joined
        cleanup = m.corner_edge(c1) >= 0 and m.corner_edge(c2) >= 0
        # a co-facial insert may move the face's head corner; a merging one
        # drops the second face's id for good
        before = corner_structure(m, face_ids=cofacial)
        m.delete_edge(m.insert_edge(c1, c2), cleanup)
        validate(m)
        assert corner_structure(m, face_ids=cofacial) == before

    @precondition(has_edges)
    @rule(i=index)
    def delete_then_insert(self, i: int) -> None:
        m = self.mesh
        e = pick(self.edges(), i)
        c0, c1 = m.edge_corners(e)
        f0, f1 = m.edge_faces(e)
        if f0 != f1 and 1 in (m.face_size(f0), m.face_size(f1)):
            return  # a loop closing a one-corner face takes a side corner with it
        before = canonical(m)
        m.delete_edge(e, cleanup=False)
        validate(m)
        m.insert_edge(c0, c1)
        assert canonical(m) == before

    @rule()
    def round_trip_through_polygons(self) -> None:
        """Export the faces as a polygon soup and build it again: an isomorphic mesh.

        A self-loop cannot be written as a polygon (it is a zero-length side), so
        meshes with one are skipped; every other legal state round-trips.
        """
        m = self.mesh
        a = mesh_arrays(m)
        ends = a.edge_vertices
        if (ends[:, 0] == ends[:, 1]).any():
            return
        faces = np.split(a.corner_vertex, a.face_offsets[1:-1]) if len(a.face_ids) else []
        rebuilt = from_polygons(a.positions, faces)
        validate(rebuilt)
        assert canonical(rebuilt) == canonical(m)
        assert euler_ok(rebuilt)

    @rule()
    def round_trip_through_dlfl(self) -> None:
        """Write the mesh as .dlfl and read it back: the same corners, faces, holes,
        pairing and positions in the same dense order, self-loops included
        (test_io_dlflfile covers ``reverse``)."""
        m = self.mesh
        back = read_dlfl(dlfl_bytes(m))
        validate(back)
        a, b = mesh_arrays(m), mesh_arrays(back)
        for name in ("positions", "corner_vertex", "face_offsets", "face_hole", "corner_mate"):
            assert np.array_equal(getattr(a, name), getattr(b, name)), name
        assert sorted(map(sorted, a.edge_corners.tolist())) == sorted(
            map(sorted, b.edge_corners.tolist()))

    @rule(i=index)
    def bad_input_changes_nothing(self, i: int) -> None:
        m = self.mesh
        before = snapshot(m)
        dead = m.next_ids()[1] + i
        for attempt in (
            lambda: m.delete_edge(dead),
            lambda: m.collapse_edge(dead),
            lambda: m.subdivide_edge(dead),
            lambda: m.insert_edge(m.next_ids()[3] + i, m.next_ids()[3] + i + 1),
        ):
            try:
                attempt()
            except DLFLError:
                pass
            else:
                raise AssertionError("a dead id was accepted")
        assert snapshot(m) == before

    # -- checks ------------------------------------------------------------------

    @invariant()
    def valid(self) -> None:
        if hasattr(self, "mesh"):
            validate(self.mesh)
            assert euler_ok(self.mesh)


# LIVEMOD_PROPERTY_EXAMPLES and LIVEMOD_PROPERTY_STEPS scale the hunt; NOSHRINK=1 skips
# shrinking when hunting bugs with many examples
PHASES = [Phase.explicit, Phase.reuse, Phase.generate]
EXAMPLES = int(os.environ.get("LIVEMOD_PROPERTY_EXAMPLES", "800"))
MeshOperators.TestCase.settings = settings(
    max_examples=max(1, EXAMPLES // 4),
    stateful_step_count=int(os.environ.get("LIVEMOD_PROPERTY_STEPS", "10")),
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
    phases=PHASES if os.environ.get("NOSHRINK") else [*PHASES, Phase.shrink],
)


# The hunt runs as four test cases of a quarter of the examples each, every one
# drawing its own: the same search, but pytest-xdist spreads it over the workers and no
# one test comes near pytest's timeout on a loaded machine.
class TestMeshOperators1(MeshOperators.TestCase):
    """The first quarter of the examples."""


class TestMeshOperators2(MeshOperators.TestCase):
    """The second quarter of the examples."""


class TestMeshOperators3(MeshOperators.TestCase):
    """The third quarter of the examples."""


class TestMeshOperators4(MeshOperators.TestCase):
    """The fourth quarter of the examples."""
