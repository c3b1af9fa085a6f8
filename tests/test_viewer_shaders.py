"""The GLSL sources' variants, compiled on the headless context."""

from __future__ import annotations

import pytest

from livemod.viewer import shaders
from livemod.viewer.headless import Offscreen


def test_a_variant_defines_its_names_after_the_version_line() -> None:
    source = "\n#version 330\nvoid main() {}\n"
    made = shaders.variant(source, "WIRE", "PLAIN")
    assert made.splitlines() == ["#version 330", "#define WIRE 1", "#define PLAIN 1",
                                 "void main() {}"]
    assert shaders.variant(source).splitlines() == ["#version 330", "void main() {}"]


@pytest.mark.parametrize(("source", "define", "uniform", "in_variant"), [
    # the face pass reads the triangles' corners only for the wire
    (shaders.FACE_FRAGMENT, "WIRE", "triangle_index", True),
    # the plain edges read no flags
    (shaders.EDGE_FRAGMENT, "PLAIN", "edge_flags", False),
])
def test_a_variant_leaves_out_what_it_does_not_draw(offscreen: Offscreen, source: str,
                                                    define: str, uniform: str,
                                                    in_variant: bool) -> None:
    ctx = offscreen.ctx
    variant = ctx.program(vertex_shader=shaders.MESH_VERTEX,
                          fragment_shader=shaders.variant(source, define))
    base = ctx.program(vertex_shader=shaders.MESH_VERTEX, fragment_shader=source)
    assert (uniform in variant, uniform in base) == (in_variant, not in_variant)
    variant.release()
    base.release()
