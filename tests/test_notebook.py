"""The example notebook (examples/notebook.ipynb), executed headless as Jupyter runs it."""

from __future__ import annotations

import base64
import io
from pathlib import Path

import nbclient
import nbformat
import numpy as np
import pytest
from PIL import Image

from livemod.dlfl.extrusion import extrude
from livemod.dlfl.shapes import cube
from livemod.dlfl.subdivision import subdivide
from livemod.runner import run_script
from livemod.viewer.compare import image_difference
from livemod.viewer.pictures import PICTURE_SIZE, TURNTABLE_SIZE, picture

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
SCRIPTS = EXAMPLES.parent / "scripts"


def _executed() -> list[nbformat.NotebookNode]:
    """The notebook's code cells after a run in a fresh kernel, in examples/."""
    notebook = nbformat.read(EXAMPLES / "notebook.ipynb", as_version=4)
    nbclient.NotebookClient(notebook, timeout=300, kernel_name="python3",
                            resources={"metadata": {"path": str(EXAMPLES)}}).execute()
    return [cell for cell in notebook.cells if cell.cell_type == "code"]


@pytest.mark.timeout(600)
def test_the_notebook_shows_a_mesh_a_turntable_a_film_and_a_result():
    # one kernel for all the checks: starting one is the slow part
    executed = _executed()
    _shows_the_mesh(executed[0])
    _shows_a_turntable_and_a_film(executed[1], executed[2])
    _shows_a_result_and_trimesh(executed[3], executed[4])
    assert not [out for cell in executed for out in cell.outputs
                if out.output_type == "error"]


def _text(cell: nbformat.NotebookNode) -> str:
    return "".join(out.text for out in cell.outputs if out.output_type == "stream")


def _image(cell: nbformat.NotebookNode) -> Image.Image:
    (shown,) = [out for out in cell.outputs if out.output_type == "execute_result"]
    return Image.open(io.BytesIO(base64.b64decode(shown.data["image/png"])))


def _shows_the_mesh(cell: nbformat.NotebookNode) -> None:
    # 3 cubical extrusions add 4 V, 8 E, 4 F each; Catmull-Clark maps (V, E, F)
    # to (V + E + F, 4E, 2E)
    v, e, f = 8 + 3 * 4, 12 + 3 * 8, 6 + 3 * 4
    assert _text(cell) == f"<Mesh V={v + e + f} E={4 * e} F={2 * e}> genus 0\n"
    mesh = cube()
    end = mesh.face_ids()[0]
    for _ in range(3):
        end = extrude(mesh, end, kind="cubical", distance=0.8, rotation=15, scale=0.8)
    subdivide(mesh, "catmull-clark")
    shown = _image(cell)
    assert shown.size == PICTURE_SIZE and not getattr(shown, "is_animated", False)
    assert image_difference(np.asarray(shown.convert("RGB")), picture(mesh).image).matches()


def _shows_a_turntable_and_a_film(turntable: nbformat.NotebookNode,
                                  film: nbformat.NotebookNode) -> None:
    turn = _image(turntable)
    assert turn.is_animated and turn.n_frames == 36 and turn.size == TURNTABLE_SIZE
    steps = len(run_script(SCRIPTS / "steps_demo.py").steps)
    assert _text(film) == f"{steps} frames\n"
    build = _image(film)
    assert build.is_animated and build.n_frames == steps


def _shows_a_result_and_trimesh(result_cell: nbformat.NotebookNode,
                                trimesh_cell: nbformat.NotebookNode) -> None:
    result = run_script(SCRIPTS / "wireframe_soccerballs.py", parameters={"count": 3})
    assert _text(result_cell) == f"ok {len(result.steps)} steps\n"
    assert _image(result_cell).size == PICTURE_SIZE
    assert _text(trimesh_cell).endswith(", watertight True\n")
