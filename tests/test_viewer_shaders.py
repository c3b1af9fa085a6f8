"""The GLSL sources' variants, compiled on the headless context."""

from __future__ import annotations

import moderngl
import pytest

from livemod.viewer import shaders
from livemod.viewer.headless import Offscreen


def test_a_variant_defines_its_names_after_the_version_line() -> None:
    source = "\n#version 330\nvoid main() {}\n"
    made = shaders.variant(source, "WIRE", "PLAIN")
    assert made.splitlines() == ["#version 330", "#define WIRE 1", "#define PLAIN 1",
                                 "void main() {}"]
    assert shaders.variant(source).splitlines() == ["#version 330", "void main() {}"]


@pytest.mark.parametrize(("source", "base", "define", "uniform", "in_variant"), [
    # the smooth face pass reads the triangles' corners only for the wire
    (shaders.FACE_FRAGMENT, ("SMOOTH",), "WIRE", "triangle_index", True),
    # the plain edges read no flags
    (shaders.EDGE_FRAGMENT, (), "PLAIN", "edge_flags", False),
], ids=["the wire of smooth faces", "plain edges"])
def test_a_variant_leaves_out_what_it_does_not_draw(offscreen: Offscreen, source: str,
                                                    base: tuple[str, ...], define: str,
                                                    uniform: str, in_variant: bool) -> None:
    ctx = offscreen.ctx
    with_it = ctx.program(vertex_shader=shaders.MESH_VERTEX,
                          fragment_shader=shaders.variant(source, *base, define))
    without = ctx.program(vertex_shader=shaders.MESH_VERTEX,
                          fragment_shader=shaders.variant(source, *base))
    assert (uniform in with_it, uniform in without) == (in_variant, not in_variant)
    with_it.release()
    without.release()


def test_the_flat_face_pass_pulls_its_corners_from_the_tables(offscreen: Offscreen) -> None:
    # no attributes, and no primitive_base: the triangle is gl_VertexID / 3, not
    # gl_PrimitiveID (llvmpipe copies every primitive's vertices to hand that over)
    program = offscreen.ctx.program(vertex_shader=shaders.FACE_VERTEX,
                                    fragment_shader=shaders.variant(shaders.FACE_FRAGMENT,
                                                                    "WIRE"))
    assert "triangle_face" in program and "primitive_base" not in program
    attributes = [name for name, member in program._members.items()
                  if isinstance(member, moderngl.Attribute)]
    assert attributes == ["gl_VertexID"]
    program.release()
