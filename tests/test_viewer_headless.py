"""Framing of headless renders (livemod.viewer.headless.Framing, ``livemod render
--margin/--zoom/--refit``), measured in pixels: the rows and columns a box
covers on a transparent background, seen orthographically from the side."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from livemod.dlfl import from_polygons, mesh_arrays
from livemod.viewer.cli import main
from livemod.viewer.headless import Framing, Offscreen, render_arrays
from livemod.viewer.renderer import BACKGROUNDS, Style

from .conftest import OFFSCREEN_SIZE
from .images import read_image
from .meshes import CUBE_FACES, CUBE_POSITIONS

WIDTH, HEIGHT = OFFSCREEN_SIZE  # 160 x 120: the height is the tighter side of a tower


def _box(size: tuple[float, float, float]):  # noqa: ANN202
    return mesh_arrays(from_polygons((CUBE_POSITIONS - 0.5) * size, CUBE_FACES))


def _extent(path: Path) -> tuple[int, int]:
    """(columns, rows) of the picture the drawing covers (alpha above 0)."""
    covered = read_image(path)[:, :, 3] > 0
    columns, rows = np.flatnonzero(covered.any(axis=0)), np.flatnonzero(covered.any(axis=1))
    return int(columns[-1] - columns[0] + 1), int(rows[-1] - rows[0] + 1)


def _render(offscreen: Offscreen, arrays, out: Path, framing: Framing | None,  # noqa: ANN001
            turntable: int = 0) -> list[Path]:
    style = Style(background=BACKGROUNDS["transparent"])
    return render_arrays(arrays, str(out), turntable=turntable, elevation=0.0, yaw=0.0,
                         style=style, ortho=True, offscreen=offscreen, framing=framing)


@pytest.mark.parametrize(("framing", "rows"), [
    (None, HEIGHT / 1.06),  # the thin border of before
    (Framing(margin=0.0), HEIGHT),
    (Framing(margin=0.1), 0.8 * HEIGHT),
    (Framing(margin=0.25), 0.5 * HEIGHT),
    (Framing(margin=0.25, zoom=1.5), 0.75 * HEIGHT),
])
def test_a_tower_fills_the_share_of_the_frame_the_margin_and_zoom_leave(
        offscreen, tmp_path, framing, rows):
    [path] = _render(offscreen, _box((1.0, 4.0, 1.0)), tmp_path / "tower.png", framing)
    columns, covered = _extent(path)
    assert abs(covered - rows) <= 2, (covered, rows)
    assert abs(columns - covered / 4) <= 2  # the side keeps its proportions


def test_refit_frames_each_turntable_frame_at_its_own_angle(offscreen, tmp_path):
    """A 4 x 1 x 1 bar: from its long side it is framed by its width; turned by
    90 degrees, one framing for the orbit draws it small, a refit fills the height."""
    bar = _box((4.0, 1.0, 1.0))
    shared = _render(offscreen, bar, tmp_path / "shared_{frame}.png", Framing(margin=0.1), 4)
    refit = _render(offscreen, bar, tmp_path / "refit_{frame}.png",
                    Framing(margin=0.1, refit=True), 4)
    long_side = 0.8 * WIDTH
    assert [abs(c - long_side) <= 2 for c, _ in map(_extent, shared[::2])] == [True, True]
    assert [abs(r - long_side / 4) <= 2 for _, r in map(_extent, shared[1::2])] == [True, True]
    assert abs(_extent(refit[0])[0] - long_side) <= 2
    assert [abs(r - 0.8 * HEIGHT) <= 2 for _, r in map(_extent, refit[1::2])] == [True, True]


@pytest.mark.parametrize(("option", "message"), [
    (["--margin", "0.5"], "the margin is a share of the frame from 0 to below 0.5 (or 0% to "
                          "below 50%), not '0.5'"),
    (["--zoom", "0"], "the zoom must be a number above 0 (2 draws the mesh twice as large), "
                      "not '0'"),
    (["--refit"], "--refit frames each turntable frame at its own angle: give --turntable N "
                  "(a single frame is framed at its angle already)"),
])
def test_render_refuses_framing_it_cannot_do(tmp_path, capsys, option, message):
    try:
        code = main(["render", "cube", "-o", str(tmp_path / "x.png"), *option])
    except SystemExit as stopped:  # argparse's own refusal
        code = stopped.code
    assert code == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "x.png").exists()


def test_render_command_takes_a_margin(tmp_path, capsys):
    out = tmp_path / "cube.png"
    assert main(["render", "cube", "-o", str(out), "--size", "120x120", "--ortho",
                 "--elevation", "0", "--yaw", "0", "--background", "transparent",
                 "--margin", "25%", "--samples", "0"]) == 0
    assert _extent(out) == (60, 60)


def _reddish(path: Path) -> int:
    """Pixels drawn in a red (red well above green and blue)."""
    rgb = read_image(path)[:, :, :3].astype(int)
    return int(((rgb[:, :, 0] > 90) & (rgb[:, :, 1] < 40) & (rgb[:, :, 2] < 40)).sum())


def test_the_colour_mode_draws_the_faces_own_colours(offscreen, tmp_path):
    mesh = from_polygons(CUBE_POSITIONS - 0.5, CUBE_FACES)
    for face in range(6):
        mesh.set_face_color(face, (1.0, 0.0, 0.0))
    arrays = mesh_arrays(mesh)
    on, off = tmp_path / "on.png", tmp_path / "off.png"
    for out, colors in ((on, True), (off, False)):
        render_arrays(arrays, str(out), style=Style(colors=colors), offscreen=offscreen)
    # lit red faces where the mesh covers the picture; none in the modelling colour
    covered = int((read_image(on)[:, :, :3] != read_image(off)[:, :, :3]).any(axis=2).sum())
    assert _reddish(on) > 0.9 * covered > 1000
    assert _reddish(off) == 0


@pytest.mark.parametrize("preview", [[], ["--preview"]], ids=["faces", "preview"])
def test_render_draws_the_colours_unless_told_not_to(tmp_path, preview):
    script = tmp_path / "s.py"
    script.write_text("from livemod.dlfl import *\nload('cube')\nsetFaceColor(faces(), (1, 0, 0))\n")
    assert main(["render", str(script), "-o", str(tmp_path / "a.png"), "--size", "160x120",
                 *preview]) == 0
    assert main(["render", str(script), "-o", str(tmp_path / "b.png"), "--size", "160x120",
                 "--no-colors", *preview]) == 0
    assert _reddish(tmp_path / "a.png") > 1000 and _reddish(tmp_path / "b.png") == 0
