"""The smoothed preview and smooth shading against golden pictures.

Each scene is rendered offscreen (Mesa llvmpipe over EGL, 4x MSAA) and compared
with its picture in ``tests/golden`` by :func:`livemod.viewer.compare.image_difference`
(the comparison ``livemod render --reference`` makes): at most 1 % of the pixels
may differ by more than a tenth of a channel's range. After a change that is
meant to change a picture, look at the new one and write it with::

    LIVEMOD_UPDATE_GOLDEN=1 python -m pytest tests/test_viewer_golden.py
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterator
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from livemod.dlfl import Mesh, mesh_arrays
from livemod.dlfl.arrays import MeshArrays, concatenate_arrays
from livemod.dlfl.shapes import cube, genus_torus, soccer_ball, torus
from livemod.dlfl.subdivision import subdivide
from livemod.runner.preview import PreviewRequest, PreviewSettings, make_preview
from livemod.viewer.compare import image_difference, read_picture
from livemod.viewer.headless import Offscreen, framed_camera
from livemod.viewer.renderer import Style

GOLDEN = Path(__file__).parent / "golden"
SIZE = (200, 150)
UPDATE = os.environ.get("LIVEMOD_UPDATE_GOLDEN") == "1"


@pytest.fixture(scope="module")
def target() -> Iterator[Offscreen]:
    made = Offscreen(SIZE, samples=4)
    yield made
    made.release()


def _moved(mesh: Mesh, by: tuple[float, float, float]) -> Mesh:
    mesh.set_positions(mesh.vertex_ids(), mesh_arrays(mesh).positions + np.asarray(by))
    return mesh


def _subdivided(mesh: Mesh) -> Mesh:
    subdivide(mesh, "catmull-clark")
    return mesh


def _scene(target: Offscreen, objects: list[MeshArrays], style: Style,
           settings: PreviewSettings | None) -> np.ndarray:
    """Draw ``objects`` (the first the current one) framed together."""
    made = None if settings is None else make_preview(PreviewRequest(tuple(objects), settings))
    others = concatenate_arrays(objects[1:]) if len(objects) > 1 else None
    target.activate()
    target.renderer.set_mesh(objects[0], made, others)
    camera = framed_camera(concatenate_arrays(objects), elevation=25.0, yaw=30.0,
                           aspect=SIZE[0] / SIZE[1])
    return target.render(camera, style)


SCENES: dict[str, Callable[[], tuple[list[Mesh], Style, PreviewSettings | None]]] = {
    "patches_cube": lambda: ([cube()], Style(preview=True), PreviewSettings()),
    "patches_genus3": lambda: ([genus_torus(3)], Style(preview=True, edges=False),
                               PreviewSettings(density=3)),
    "patches_two_objects": lambda: ([torus(8, 6), _moved(cube(), (4.0, 0.0, 0.0))],
                                    Style(preview=True), PreviewSettings()),
    "catmull_clark_cube": lambda: ([cube()], Style(preview=True),
                                   PreviewSettings(mode="catmull-clark")),
    "smooth_creased": lambda: ([_subdivided(soccer_ball()), _moved(cube(), (3.0, 0.0, 0.0))],
                               Style(smooth=True, edges=False), None),
}


@pytest.mark.parametrize("name", sorted(SCENES))
def test_the_picture_matches_its_golden_one(target: Offscreen, name: str) -> None:
    meshes, style, settings = SCENES[name]()
    picture = _scene(target, [mesh_arrays(m) for m in meshes], style, settings)
    path = GOLDEN / f"{name}.png"
    if UPDATE:
        GOLDEN.mkdir(exist_ok=True)
        Image.fromarray(picture).save(path)
    difference = image_difference(picture, read_picture(path, "golden picture"))
    assert difference.matches(), (
        f"{name}: {difference.share:.2%} of the pixels differ from {path.name} "
        f"(largest difference {difference.largest:.0%})")
