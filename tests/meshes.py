"""Small meshes and mesh comparisons shared by the DLFL test modules."""

from __future__ import annotations

import random
import warnings
from collections import Counter
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from livemod.dlfl import DLFLError, Mesh, Scene, from_polygons, mesh_arrays, shapes, validate
from livemod.dlfl.analysis import component_genera

CUBE_POSITIONS = np.array(
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
    dtype=np.float64,
)
# counter-clockwise seen from outside: bottom (-z), top (+z), -y, +x, +y, -x
CUBE_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
CUBE_OUTWARD = [(0, 0, -1), (0, 0, 1), (0, -1, 0), (1, 0, 0), (0, 1, 0), (-1, 0, 0)]

TETRA_POSITIONS = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float64)
TETRA_FACES = [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]]


def cube(offset: tuple[float, float, float] = (0.0, 0.0, 0.0)) -> Mesh:
    """The unit cube, 8/12/6; face ``i`` has corners ``4i..4i+3`` at ``CUBE_FACES[i]``."""
    return from_polygons(CUBE_POSITIONS + np.asarray(offset), CUBE_FACES)


def two_cubes() -> Mesh:
    """Two disjoint unit cubes, 16/24/12, the second shifted by 3 along x."""
    pos = np.concatenate([CUBE_POSITIONS, CUBE_POSITIONS + [3.0, 0.0, 0.0]])
    faces = CUBE_FACES + [[v + 8 for v in f] for f in CUBE_FACES]
    return from_polygons(pos, faces)


def tetrahedron() -> Mesh:
    """A tetrahedron, 4/6/4."""
    return from_polygons(TETRA_POSITIONS, TETRA_FACES)


def triangle() -> Mesh:
    """An open triangle: its face plus one hole face, 3/3/2."""
    return from_polygons([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]])


def point_sphere() -> Mesh:
    """One isolated vertex, 1/0/1."""
    m = Mesh()
    m.create_vertex((0.0, 0.0, 0.0))
    return m


def path_face() -> Mesh:
    """A path 0-1-2 as one face that visits vertex 1 twice, 3/2/1."""
    return from_polygons([[0, 0, 0], [1, 0, 0], [2, 0, 0]], [[0, 1, 2, 1]])


def torus_polygons(n: int, m: int, *, radii: tuple[float, float] = (3.0, 1.0)) -> tuple[np.ndarray, np.ndarray]:
    """Positions ``(n*m, 3)`` and quads ``(n*m, 4)`` of an n x m quad torus."""
    i, j = np.meshgrid(np.arange(n), np.arange(m), indexing="ij")
    u, v = 2 * np.pi * i.ravel() / n, 2 * np.pi * j.ravel() / m
    big, small = radii
    ring = big + small * np.cos(v)
    pos = np.stack([ring * np.cos(u), ring * np.sin(u), small * np.sin(v)], axis=1)
    a = i * m + j
    b = ((i + 1) % n) * m + j
    c = ((i + 1) % n) * m + (j + 1) % m
    d = i * m + (j + 1) % m
    quads = np.stack([a.ravel(), b.ravel(), c.ravel(), d.ravel()], axis=1)
    return pos, quads


def torus(n: int = 4, m: int = 3) -> Mesh:
    """An n x m quad torus, nm / 2nm / nm, genus 1."""
    pos, quads = torus_polygons(n, m)
    return from_polygons(pos, quads)


def snapshot(mesh: Mesh) -> tuple[Any, ...]:
    """Everything observable about ``mesh``: its dense arrays and id counters."""
    a = mesh_arrays(mesh)
    # bytes, not lists: a face without colour is a row of NaN, and NaN != NaN
    fields = [None if getattr(a, name) is None else (getattr(a, name).dtype.str,
              getattr(a, name).shape, getattr(a, name).tobytes())
              for name in a.__dataclass_fields__]
    return (*fields, mesh.next_ids())


def assert_refused(mesh: Mesh, call: Callable[[Mesh], object], message: str,
                   error: type[Exception] = DLFLError) -> None:
    """Assert that ``call(mesh)`` raises ``error`` matching ``message`` and leaves
    ``mesh`` exactly as it was (:func:`snapshot`)."""
    before = snapshot(mesh)
    with pytest.raises(error, match=message):
        call(mesh)
    assert snapshot(mesh) == before


def assert_refused_quietly(mesh: Mesh, call: Callable[[Mesh], object], message: str) -> None:
    """:func:`assert_refused`, with any warning on the way an error: numpy's
    ``RuntimeWarning: overflow encountered`` before a DLFLError that says the
    same is noise on the user's stderr."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert_refused(mesh, call, message)



def assert_scales(make: Callable[[], Mesh], op: Callable[[Mesh, float], object],
                  scale: float = 1e100, rtol: float = 1e-9) -> Mesh:
    """``op(mesh, s)`` on ``make()`` scaled by ``scale`` (with ``s = scale``: its
    lengths scale too) gives the result on the unit mesh (``s = 1``) scaled, with
    no warning on the way (raw products of huge coordinates overflow); returns
    the scaled mesh, for further checks."""
    small, big = make(), make()
    big.set_positions(big.vertex_ids(), big.positions_view() * scale)
    op(small, 1.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        op(big, scale)
    assert big.counts() == small.counts()
    np.testing.assert_allclose(big.positions_view() / scale, small.positions_view(),
                               rtol=rtol, atol=1e-12)
    return big

def same_up_to_ids(mesh: Mesh) -> tuple[Any, ...]:
    """The dense arrays without the id counters (ids of live elements kept)."""
    return snapshot(mesh)[:-1]


def canonical(mesh: Mesh) -> tuple[Any, ...]:
    """An isomorphism invariant: counts, face sizes, valences and positions."""
    a = mesh_arrays(mesh)
    valence = np.bincount(a.corner_vertex[a.corner_edge >= 0], minlength=len(a.vertex_ids))
    positions = sorted(map(tuple, np.round(a.positions, 9).tolist()))
    return (
        a.counts,
        sorted(a.face_sizes.tolist()),
        sorted(Counter(valence.tolist()).items()),
        positions,
    )


def euler_ok(mesh: Mesh) -> bool:
    """``V - E + F == 2 (components - genus)``, genus summed per component."""
    a = mesh_arrays(mesh)
    genera = component_genera(a)  # one entry per component
    v, e, f = a.counts
    return v - e + f == 2 * (len(genera) - sum(genera))


def checked(mesh: Mesh) -> tuple[int, int, int]:
    """Validate ``mesh`` and its Euler relation; return its counts."""
    validate(mesh)
    assert euler_ok(mesh)
    return mesh.counts()


def three_point_spheres() -> tuple[Mesh, list[int]]:
    """An empty mesh given three point-spheres at x = 0, 1, 2, and their ids."""
    m = Mesh()
    return m, [m.create_vertex((float(i), 0.0, 0.0)) for i in range(3)]


def corner_structure(mesh: Mesh, *, face_ids: bool = False) -> tuple[Any, ...]:
    """The mesh keyed by corner, edge and vertex id, with faces as corner sets.

    Equal for two meshes that differ only in face ids, face head corners and
    hole flags: what deleting an edge that merged two faces cannot restore (the
    second face's id is gone for good, and the merged face kept one flag).
    With ``face_ids`` the face ids and hole flags are compared too, so only the
    head corners (where face walks start) may differ.
    """
    a = mesh_arrays(mesh)
    cid = a.corner_ids
    has = a.corner_edge >= 0
    nxt = cid[a.corner_next].tolist()
    mate = np.full(len(cid), -1, dtype=np.int64)
    mate[has] = cid[a.corner_mate[has]]
    edge = np.full(len(cid), -1, dtype=np.int64)
    edge[has] = a.edge_ids[a.corner_edge[has]]
    vert = a.vertex_ids[a.corner_vertex].tolist()
    corners = sorted(zip(cid.tolist(), nxt, mate.tolist(), edge.tolist(), vert, strict=True))
    faces = sorted(
        (
            tuple(sorted(cid[a.face_offsets[i]:a.face_offsets[i + 1]].tolist())),
            (int(a.face_ids[i]), bool(a.face_hole[i])) if face_ids else None,
        )
        for i in range(len(a.face_ids))
    )
    return corners, faces, a.vertex_ids.tolist(), a.positions.tolist(), a.edge_ids.tolist()


def counts(scene: Scene) -> tuple[int, int, int]:
    """``(V, E, F)`` of the scene's current mesh, after checking it is valid."""
    validate(scene.mesh)
    return scene.mesh.counts()


# (r, g, b) of faces 0..3 of :func:`coloured_cube`; faces 4 and 5 have none
CUBE_FACE_COLORS = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.2, 0.4, 1.0), (1.0, 0.0, 0.0)]


def coloured_cube() -> Mesh:
    """:func:`cube` with faces 0..3 in :data:`CUBE_FACE_COLORS` and faces 4, 5 without
    colour (two faces of one colour, one colour that is no 8-bit value exactly)."""
    mesh = cube()
    for face, color in enumerate(CUBE_FACE_COLORS):
        mesh.set_face_color(face, color)
    return mesh


def expected_written_colors(mesh: Mesh) -> np.ndarray:
    """``(F, 3)`` float32 colours a format that colours every face writes for
    ``mesh``: its own, the modelling colour for a face without one."""
    from livemod.dlfl.colors import filled_colors

    colors = mesh.face_colors()
    assert colors is not None
    return filled_colors(colors)


def rainbow_cube() -> Mesh:
    """:func:`cube` with face ``f`` in the colour ``(f / 5, 1 - f / 5, 0.5)``."""
    mesh = cube()
    for face in range(6):
        mesh.set_face_color(face, (face / 5, 1 - face / 5, 0.5))
    return mesh


def colour_counts(mesh: Mesh) -> dict[int | None, int]:
    """How many faces of ``mesh`` have the colour of :func:`rainbow_cube`'s face
    ``f`` (key ``f``), and how many none (key None)."""
    colors = mesh.face_colors()
    if colors is None:
        return {None: mesh.num_faces}
    counts: dict[int | None, int] = {}
    for row in colors.tolist():
        key = None if row[0] != row[0] else round(row[0] * 5)
        counts[key] = counts.get(key, 0) + 1
    return counts


# -- parallel edges and meshes for crusts, shared by several modules

# a soup on the tetrahedron's points whose vertices 1 and 2 are joined by ten edges
PARALLEL_EDGE_SOUP = [[1, 2], [2, 1, 3], [2, 3, 1], [1, 2], [1, 2], [2, 3], [1, 2], [0, 3],
                      [1, 2], [1, 2], [1, 2], [1, 2], [1, 2], [1, 3, 0, 3]]


def stack_parallel_edges(mesh: Mesh, rng: random.Random, pairs: list[tuple[int, int]],
                         count: int) -> Mesh:
    """Insert ``count`` edges, each between the corners at two vertices of one of
    ``pairs`` in one face (a 2-gon or a split face: parallel edges)."""
    for _ in range(count):
        a, b = rng.choice(pairs)
        faces = [f for f in mesh.face_ids().tolist()
                 if {a, b} <= set(mesh.face_vertices(f))]
        f = rng.choice(faces)
        ca = rng.choice([c for c in mesh.face_corners(f) if mesh.corner_vertex(c) == a])
        cb = rng.choice([c for c in mesh.face_corners(f) if mesh.corner_vertex(c) == b])
        mesh.insert_edge(ca, cb) if rng.random() < 0.5 else mesh.insert_edge(cb, ca)
        if rng.random() < 0.2 and mesh.num_edges > 6:
            mesh.delete_edge(rng.choice(mesh.edge_ids().tolist()), cleanup=False)
        validate(mesh)
    return mesh


def scaled_cube(scale: float) -> Mesh:
    """:func:`livemod.dlfl.shapes.cube` (edge 2, about the origin) scaled by ``scale``."""
    m = shapes.cube()
    m.set_positions(m.vertex_ids(), m.positions_view() * scale)
    return m


def split_edge_cube() -> Mesh:
    """:func:`livemod.dlfl.shapes.cube` with edge 0 ((1,1,1)-(1,1,-1)) split at
    (1,1,0): vertex 8, both of whose corners are straight."""
    m = shapes.cube()
    assert m.subdivide_edge(0) == [8]
    return m
