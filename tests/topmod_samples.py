"""Stand-ins for TopMod's fifteen sample OBJ files, made by the tests (not a test module).

livemod's readers were first checked on the sample meshes TopMod ships (``cube.obj`` ...
``soccerballdual.obj``). Those files are TopMod's, so they are not in this repository.
What the tests need from them is their shapes and the ways they spell OBJ, and both are
made here. Each stand-in is a built-in shape of :mod:`livemod.dlfl.shapes` (they have the
samples' counts and genus) written the way its sample writes: the same statements around
the records (comments with counts, ``mtllib``, ``g``, ``o``, ``s``, ``usemtl``, a stray
line of two numbers), ``vt``/``vn`` records and ``f v/t/n`` or ``f v//n`` corners where
the sample has them, commas between coordinates, CRLF line ends, three-digit exponents
(``6.1e-017``, as Windows' ``%g`` prints them), faces that disagree with their
neighbours on orientation, and 2-gons; also trailing spaces, which no sample has but
other writers leave. The lines are formatted here, not by livemod's writers, so a reader
test reads text its writer did not make.

Two samples are not built-in shapes: ``beveledcube.obj`` stands in as the Doo-Sabin
refinement of the cube (TopMod's counts, 24/48/26: a cube with bevelled edges and
corners) with four faces written backwards, and ``soccerballdual.obj`` (TopMod's is a
309/500/193 sphere) as the buckminster sphere turned a quarter turn, so float round-off
stands where its zeros were, with two of its edges doubled into 2-gons: 540/812/274.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import cache
from pathlib import Path

import numpy as np

from livemod.dlfl import Mesh, mesh_arrays
from livemod.dlfl.shapes import SHAPES, buckminster, cube
from livemod.dlfl.subdivision import subdivide

# name -> (V, E, F, genus) of each stand-in: TopMod's own counts but for soccerballdual
SAMPLE_COUNTS: dict[str, tuple[int, int, int, int]] = {
    "cube.obj": (8, 12, 6, 0),
    "tetrahedron.obj": (4, 6, 4, 0),
    "octahedron.obj": (6, 12, 8, 0),
    "dodecahedron.obj": (20, 30, 12, 0),
    "icosahedron.obj": (12, 30, 20, 0),
    "soccerball.obj": (60, 90, 32, 0),
    "geodesicdome.obj": (272, 810, 540, 0),
    "buckminister.obj": (540, 810, 272, 0),
    "sphericalcube.obj": (98, 192, 96, 0),
    "donuthexa1.obj": (100, 150, 50, 1),
    "donuthexa3.obj": (1600, 2400, 800, 1),
    "genus3hexa1.obj": (161, 247, 82, 3),
    "genus3hexa3.obj": (2631, 3952, 1317, 3),
    "beveledcube.obj": (24, 48, 26, 0),
    "soccerballdual.obj": (540, 812, 274, 0),
}
# the faces (by file order) the beveledcube stand-in writes backwards: the cube's top,
# a bevel quad and two corner triangles, no two of them beside each other
BEVELED_REVERSED = (0, 10, 20, 25)


@dataclass(frozen=True)
class Layout:
    """How one sample spells its mesh: the text around the records and their forms.

    ``head``, ``middle`` (between the vertex records and the faces) and ``tail`` are
    whole lines; ``{vertices}``/``{faces}`` in them become the counts.
    """

    head: str = ""
    middle: str = ""
    tail: str = ""
    number: str = "g"  # format spec of a coordinate
    comma: bool = False  # "v x, y, z"
    corner: str = "{v}"  # a face corner: "{v}", "{v}//{n}" or "{v}/{t}/{n}"
    line_end: str = "\n"
    face_end: str = ""  # after the last corner of an f line: " " leaves a trailing space
    windows_exponent: bool = False  # "1e-017" as Windows' C library prints %g


COUNTED = Layout(middle="# {vertices} vertices\n# {faces} faces\n\n")
MAYA = Layout(
    head="# This file uses centimeters as units for non-parametric coordinates.\n\n"
         "mtllib {stem}.mtl\ng default\n",
    middle="s off\ng Mesh1\nusemtl initialShadingGroup\n", number=".6f", corner="{v}//{n}",
)
LAYOUTS: dict[str, Layout] = {
    "cube.obj": Layout(head="#\n", middle="#\n", number=".1f", comma=True),
    "tetrahedron.obj": Layout(
        head="# The units used in this file are inches.\ng default\n",
        middle="s off\ng pCone1\nusemtl initialShadingGroup\n", number=".6f",
        corner="{v}/{t}/{n}"),
    "octahedron.obj": COUNTED,
    "dodecahedron.obj": Layout(
        head="# a regular dodecahedron\n#\n# {vertices} vertices\n# {faces} elements\n#\n\n"
             "g dodecahedron\n", middle="\ng\n", number=".6f"),
    "icosahedron.obj": COUNTED,
    "soccerball.obj": Layout(),
    "geodesicdome.obj": COUNTED,
    "buckminister.obj": COUNTED,
    "sphericalcube.obj": COUNTED,
    "donuthexa1.obj": COUNTED,
    "donuthexa3.obj": MAYA,
    "genus3hexa1.obj": MAYA,
    "genus3hexa3.obj": COUNTED,
    "beveledcube.obj": Layout(
        head="# exported by a modeler\nmtllib beveledcube.mtl\no Cube_Cube\n",
        middle="usemtl (null)\ns off\n", tail="1 14\n", number=".6f"),
    "soccerballdual.obj": Layout(middle="# {vertices} vertices\n# {faces} faces\n\n",
                                 corner="{v}//{n}", face_end=" ", line_end="\r\n",
                                 windows_exponent=True),
}


def polygons(mesh: Mesh) -> tuple[np.ndarray, list[list[int]]]:
    """``(V, 3)`` positions and the faces (no holes) of ``mesh`` as dense vertex indices."""
    a = mesh_arrays(mesh)
    ring = a.corner_vertex.tolist()
    offsets = a.face_offsets.tolist()
    faces = [ring[offsets[f]:offsets[f + 1]] for f in range(len(a.face_ids)) if not a.face_hole[f]]
    return np.array(a.positions), faces


def beveled_cube() -> tuple[np.ndarray, list[list[int]]]:
    """The cube refined once by Doo-Sabin (24/48/26), four faces of it reversed."""
    mesh = cube()
    subdivide(mesh, "doo-sabin")
    positions, faces = polygons(mesh)
    return positions, [f[::-1] if i in BEVELED_REVERSED else f for i, f in enumerate(faces)]


def sphere_with_2gons() -> tuple[np.ndarray, list[list[int]]]:
    """The buckminster sphere turned a quarter turn about y, with 2-gons on two edges.

    A 2-gon ``[b, a]`` on the edge a -> b of one face sits between that face and the
    face across the edge, as TopMod writes one: its line comes before the face's.
    """
    positions, faces = polygons(buckminster())
    turn = np.pi / 2
    rotation = np.array([[np.cos(turn), 0.0, np.sin(turn)], [0.0, 1.0, 0.0],
                         [-np.sin(turn), 0.0, np.cos(turn)]])
    with_2gons: list[list[int]] = []
    for i, face in enumerate(faces):
        if i in (40, len(faces) - 3):
            with_2gons.append([face[1], face[0]])
        with_2gons.append(face)
    return positions @ rotation.T, with_2gons


def _mesh_of(name: str) -> tuple[np.ndarray, list[list[int]]]:
    if name == "beveledcube.obj":
        return beveled_cube()
    if name == "soccerballdual.obj":
        return sphere_with_2gons()
    return polygons(SHAPES[name.removesuffix(".obj")]())


def _numbers(values: np.ndarray, layout: Layout) -> list[str]:
    text = [format(float(x), layout.number) for x in values.ravel()]
    if layout.windows_exponent:
        text = [re.sub(r"e([+-])(\d\d)$", r"e\g<1>0\2", t) for t in text]
    return text


def _records(positions: np.ndarray, faces: list[list[int]], layout: Layout) -> list[str]:
    """The v (and vt, vn) lines, then the middle, then the f lines of the sample."""
    numbers = _numbers(positions, layout)
    glue = ", " if layout.comma else " "
    lines = ["v " + glue.join(numbers[3 * i:3 * i + 3]) for i in range(len(positions))]
    corners = sum(len(face) for face in faces)
    if "{t}" in layout.corner:
        lines += [f"vt {k / corners:.6f} 0.500000" for k in range(corners)]
    if "{n}" in layout.corner:
        lines += ["vn " + " ".join(_numbers(normal, layout)) for normal in _normals(positions, faces)]
    lines += layout.middle.format(vertices=len(positions), faces=len(faces)).splitlines()
    k = 0  # corners before this face: its vt/vn records follow theirs
    for face in faces:
        spelled = [layout.corner.format(v=v + 1, t=k + i, n=k + i) for i, v in enumerate(face, 1)]
        k += len(face)
        lines.append("f " + " ".join(spelled) + layout.face_end)
    return lines


def _normals(positions: np.ndarray, faces: list[list[int]]) -> list[np.ndarray]:
    """A unit normal per corner: its face's (Newell's), as modelers write them."""
    out = []
    for face in faces:
        p = positions[face]
        normal = np.cross(p, np.roll(p, -1, axis=0)).sum(axis=0)
        length = np.linalg.norm(normal)
        out += [normal / length if length else normal] * len(face)
    return out


@cache
def sample_bytes(name: str) -> bytes:
    """The stand-in for TopMod's sample ``name`` (``"cube.obj"``, ...), as file bytes."""
    layout = LAYOUTS[name]
    positions, faces = _mesh_of(name)
    fill = {"vertices": len(positions), "faces": len(faces), "stem": name.removesuffix(".obj")}
    lines = layout.head.format(**fill).splitlines() + _records(positions, faces, layout)
    lines += layout.tail.splitlines()
    return "".join(line + layout.line_end for line in lines).encode()


def write_samples(directory: Path) -> Path:
    """Write every stand-in into ``directory`` under its sample's name; return it."""
    for name in LAYOUTS:
        (directory / name).write_bytes(sample_bytes(name))
    return directory
