"""The mesh passes: their programs, and each element's draw call (EGL, pixels)."""

from __future__ import annotations

from collections.abc import Iterator
from types import SimpleNamespace
from typing import Any

import moderngl
import numpy as np
import pytest

from livemod.dlfl import from_polygons, mesh_arrays
from livemod.dlfl.shapes import cube
from livemod.viewer.framebuffers import release_framebuffer
from livemod.viewer.geometry import build_geometry
from livemod.viewer.mesh_passes import (
    EDGE_COLOR,
    POINT_COLOR,
    PROGRAMS,
    TEXTURE_UNITS,
    MeshPasses,
    compile_programs,
    matrix_bytes,
)
from livemod.viewer.uploads import MeshGPU

SIZE = (64, 64)
RED = (1.0, 0.0, 0.0)
# one quad in the plane z = 0 over the middle half of the clip square (an identity
# view: each of its two triangles covers a half of it)
QUAD = from_polygons([(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (0.5, 0.5, 0.0),
                      (-0.5, 0.5, 0.0)], [(0, 1, 2, 3)])
# the pixels (row, column) of its corners
CORNERS = [(SIZE[1] // 4, SIZE[0] // 4), (SIZE[1] // 4, 3 * SIZE[0] // 4),
           (3 * SIZE[1] // 4, SIZE[0] // 4), (3 * SIZE[1] // 4, 3 * SIZE[0] // 4)]


class Cap:
    """A section cap that records what it is asked to draw."""

    def __init__(self) -> None:
        self.drawn: list[tuple[object, tuple[float, float, float], bool]] = []

    def draw(self, mesh: object, color: tuple[float, float, float], current: bool) -> None:
        self.drawn.append((mesh, color, current))


@pytest.fixture(scope="module")
def programs(shared_offscreen: Any) -> Iterator[dict[str, moderngl.Program]]:
    """The programs compiled afresh (the tests set their uniforms at will)."""
    shared_offscreen.activate()
    made = compile_programs(shared_offscreen.ctx)
    yield made
    for program in made.values():
        program.release()


@pytest.fixture
def target(offscreen: Any) -> Iterator[moderngl.Framebuffer]:
    """A ``SIZE`` colour and depth target, bound and cleared to black, with the
    depth test on."""
    ctx = offscreen.ctx
    fbo = ctx.framebuffer([ctx.renderbuffer(SIZE, 4)], ctx.depth_renderbuffer(SIZE))
    fbo.use()
    ctx.viewport = (0, 0, *SIZE)
    ctx.enable(moderngl.DEPTH_TEST | moderngl.PROGRAM_POINT_SIZE)
    ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
    fbo.clear(0.0, 0.0, 0.0, 1.0)
    yield fbo
    release_framebuffer(fbo)


def _passes(offscreen: Any, programs: dict[str, moderngl.Program],
            cap: Cap | None = None) -> MeshPasses:
    passes = MeshPasses(offscreen.ctx, programs, cap or Cap())  # type: ignore[arg-type]
    passes.set_view(np.eye(4), np.eye(4))
    return passes


def _upload(offscreen: Any, programs: dict[str, moderngl.Program], mesh: Any) -> MeshGPU:
    return MeshGPU.made(offscreen.ctx, programs, build_geometry(mesh_arrays(mesh)))


def _pixels(fbo: moderngl.Framebuffer) -> np.ndarray:
    """``(H, W, 3)`` uint8, row 0 at the bottom (GL's order)."""
    return np.frombuffer(fbo.read(components=3), dtype=np.uint8).reshape(SIZE[1], SIZE[0], 3)


def _drawn(fbo: moderngl.Framebuffer) -> np.ndarray:
    """``(H, W)`` bool: the pixels drawn on the black clear colour."""
    return np.asarray(_pixels(fbo).any(axis=2))


def test_every_program_compiles_with_its_samplers_on_their_units(programs) -> None:
    assert set(programs) == set(PROGRAMS)
    bound = {(name, sampler): programs[name][sampler].value
             for name in programs for sampler in TEXTURE_UNITS if sampler in programs[name]}
    assert bound == {key: TEXTURE_UNITS[key[1]] for key in bound}
    assert {sampler for _, sampler in bound} == set(TEXTURE_UNITS)  # every unit is used
    assert all("mvp" in program for program in programs.values())


def test_set_view_gives_every_program_the_matrices_column_major(offscreen, programs) -> None:
    projection_view = np.arange(16, dtype=float).reshape(4, 4)
    view = np.arange(16, 32, dtype=float).reshape(4, 4)
    MeshPasses(offscreen.ctx, programs, Cap()).set_view(projection_view,  # type: ignore[arg-type]
                                                        view)
    # GL's order is column-major: the first four floats are the first column
    assert np.frombuffer(matrix_bytes(projection_view), np.float32)[:4].tolist() == \
        [0.0, 4.0, 8.0, 12.0]
    for program in programs.values():
        assert program["mvp"].read() == matrix_bytes(projection_view)
        if "view" in program:
            assert program["view"].read() == matrix_bytes(view)
    assert "view" in programs["face_smooth"] and "view" in programs["surface"]


def test_faces_draw_the_range_of_triangles_asked(offscreen, programs, target) -> None:
    passes, mesh = _passes(offscreen, programs), _upload(offscreen, programs, QUAD)
    drawn = {}
    for first, count in ((0, None), (0, 1), (1, 1), (2, None), (0, 0)):
        target.clear(0.0, 0.0, 0.0, 1.0)
        passes.faces(mesh, RED, True, first=first, count=count)
        drawn[first, count] = _drawn(target)
    whole = drawn[0, None]
    assert whole.sum() == pytest.approx((SIZE[0] // 2) * (SIZE[1] // 2), abs=2 * SIZE[0])
    assert not whole[0, 0] and whole[SIZE[1] // 2, SIZE[0] // 2]
    halves = drawn[0, 1], drawn[1, 1]
    assert halves[0].any() and halves[1].any() and not (halves[0] & halves[1]).any()
    assert np.array_equal(halves[0] | halves[1], whole)
    assert not drawn[2, None].any() and not drawn[0, 0].any()  # past the end: nothing


def test_faces_are_lit_in_the_colour_given(offscreen, programs, target) -> None:
    passes, mesh = _passes(offscreen, programs), _upload(offscreen, programs, QUAD)
    passes.faces(mesh, RED, True)
    middle = _pixels(target)[SIZE[1] // 2, SIZE[0] // 2].astype(int)
    assert middle[0] > 60 and middle[1] == middle[2] == 0


def test_a_closed_mesh_cut_by_the_section_gets_its_cap(offscreen, programs, target) -> None:
    cap = Cap()
    passes = _passes(offscreen, programs, cap)
    closed, open_quad = (_upload(offscreen, programs, mesh) for mesh in (cube(), QUAD))
    passes.faces(closed, RED, True)
    passes.faces(open_quad, RED, True)
    assert cap.drawn == []  # no section
    passes.section = (0, 0.0)
    passes.faces(open_quad, RED, True)
    assert cap.drawn == []  # an open mesh shows its inside: no cap
    passes.faces(closed, RED, False)
    assert cap.drawn == [(closed, RED, True)]


def test_the_surface_draws_its_part_with_the_quick_variant_when_quick(offscreen,
                                                                      programs) -> None:
    rendered: list[tuple[bool, bool, int, int]] = []

    def vao(quick: bool, colors: bool) -> SimpleNamespace:
        name = ("surface_quick" if quick else "surface") + ("_colors" if colors else "")
        return SimpleNamespace(program=programs[name], render=lambda mode, vertices, first:
                               rendered.append((quick, colors, vertices, first)))

    surface = SimpleNamespace(closed=True, vao=vao,
                              part=lambda current: (10, 30) if current else (0, 10))
    cap = Cap()
    passes = _passes(offscreen, programs, cap)
    passes.surface(surface, RED, True)  # type: ignore[arg-type]
    passes.quick = True
    passes.surface(surface, RED, False, first=2, count=3,  # type: ignore[arg-type]
                   own_colors=True)
    passes.surface(surface, RED, True, first=30)  # type: ignore[arg-type]  # none left
    passes.section = (1, 0.5)
    passes.surface(surface, RED, True, first=5, count=1)  # type: ignore[arg-type]
    assert rendered == [(False, False, 90, 30), (True, True, 9, 6), (True, False, 3, 45)]
    assert cap.drawn == [(surface, RED, True)]


def test_edges_draw_the_range_asked_in_the_edge_colour(offscreen, programs, target) -> None:
    passes, mesh = _passes(offscreen, programs), _upload(offscreen, programs, QUAD)
    passes.edges(mesh)
    pixels = _pixels(target)
    all_edges = _drawn(target)
    assert set(map(tuple, pixels[all_edges])) == {tuple(round(c * 255) for c in EDGE_COLOR)}
    target.clear(0.0, 0.0, 0.0, 1.0)
    passes.edges(mesh, first=1, count=2)
    two = _drawn(target)
    assert two.any() and (two & ~all_edges).sum() == 0 and two.sum() < all_edges.sum()


def test_points_draw_every_vertex_in_the_point_colour(offscreen, programs, target) -> None:
    passes, mesh = _passes(offscreen, programs), _upload(offscreen, programs, QUAD)
    passes.points(mesh, 5.0)
    pixels, drawn = _pixels(target), _drawn(target)
    assert set(map(tuple, pixels[drawn])) == {tuple(round(c * 255) for c in POINT_COLOR)}
    assert all(drawn[corner] for corner in CORNERS)
    assert 4 * 16 <= drawn.sum() <= 4 * 36  # four points of about 5 x 5 pixels


def test_point_spheres_alone_are_drawn_however_few(offscreen, programs, target) -> None:
    mesh = from_polygons([(-0.5, -0.5, 0.0), (0.5, -0.5, 0.0), (0.5, 0.5, 0.0),
                          (-0.5, 0.5, 0.0)], [(0, 1, 2, 3)])
    mesh.create_vertex((0.0, 0.0, 0.0))  # one point-sphere, in the middle
    passes, uploaded = _passes(offscreen, programs), _upload(offscreen, programs, mesh)
    assert len(uploaded.geometry.point_spheres) == 1
    passes.points(uploaded, 5.0, point_spheres=True)
    drawn = _drawn(target)
    # (its index buffer has room for four: drawing all of it drew vertex 0, a corner)
    assert drawn[SIZE[1] // 2, SIZE[0] // 2] and not any(drawn[corner] for corner in CORNERS)
    assert 16 <= drawn.sum() <= 36  # one point of about 5 x 5 pixels
