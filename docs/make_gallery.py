"""Render the README's pictures with livemod itself.

    python docs/make_gallery.py

writes docs/images/tower.gif (a turntable of scripts/tower.py),
docs/images/build.gif (a film of the tower's build, a frame per step, as
``livemod render scripts/tower.py --set storeys=12 --steps --turn 4 --captions``
draws it), docs/images/gallery.png (one thumbnail per script in scripts/, labelled)
and docs/images/section.png (scripts/rind_soccerball.py whole and cut open at x = 0,
as ``livemod render --section x`` draws it), through the same headless renderer as
``livemod render``.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

from PIL import Image, ImageDraw

from livemod.dlfl import mesh_arrays
from livemod.runner.execute import execute
from livemod.runner.results import snapshot_others
from livemod.viewer.film import film
from livemod.viewer.headless import render_arrays
from livemod.viewer.renderer import Style

ROOT = Path(__file__).resolve().parents[1]
IMAGES = ROOT / "docs" / "images"
THUMB = 200
COLUMNS = 4
# twelve of the thirty balls (two rows) still read at thumbnail size
PARAMETERS = {"wireframe_soccerballs.py": {"count": 12}}


def script_arrays(path: Path):  # noqa: ANN201  ((MeshArrays, MeshArrays or None))
    """The current object's arrays and the other objects' (as ``livemod render`` draws)."""
    outcome = execute(path, parameters=PARAMETERS.get(path.name))
    if outcome.error is not None:
        raise SystemExit(f"{path.name}: {outcome.error}")
    return mesh_arrays(outcome.scene.mesh), snapshot_others(outcome.scene)


def thumbnail(path: Path, folder: Path) -> Image.Image:
    out = folder / f"{path.stem}.png"
    arrays, others = script_arrays(path)
    render_arrays(arrays, str(out), size=(THUMB, THUMB), elevation=25.0, others=others)
    image = Image.open(out).convert("RGB")
    ImageDraw.Draw(image).text((6, THUMB - 16), path.stem, fill=(230, 230, 230))
    return image


def gallery(scripts: list[Path]) -> Image.Image:
    rows = (len(scripts) + COLUMNS - 1) // COLUMNS
    sheet = Image.new("RGB", (COLUMNS * THUMB, rows * THUMB), (40, 40, 44))
    with tempfile.TemporaryDirectory() as tmp:
        for i, path in enumerate(scripts):
            sheet.paste(thumbnail(path, Path(tmp)), ((i % COLUMNS) * THUMB, (i // COLUMNS) * THUMB))
    return sheet


def section_pair(path: Path, folder: Path) -> Image.Image:
    """``path``'s result whole (left) and cut open by a section at x = 0 (right)."""
    arrays, others = script_arrays(path)
    pictures = []
    for name, style in (("whole", Style()), ("cut", Style(section=(0, 0.0)))):
        out = folder / f"{name}.png"
        render_arrays(arrays, str(out), size=(360, 300), elevation=20.0, style=style,
                      others=others)
        pictures.append(Image.open(out).convert("RGB"))
    sheet = Image.new("RGB", (720, 300))
    for i, picture in enumerate(pictures):
        sheet.paste(picture, (360 * i, 0))
    return sheet


def main() -> int:
    IMAGES.mkdir(parents=True, exist_ok=True)
    scripts = sorted((ROOT / "scripts").glob("*.py"))
    gallery(scripts).save(IMAGES / "gallery.png", optimize=True)
    arrays, others = script_arrays(ROOT / "scripts" / "tower.py")
    render_arrays(arrays, str(IMAGES / "tower.gif"), size=(360, 360), turntable=36,
                  elevation=20.0, samples=0, others=others)
    film(ROOT / "scripts" / "tower.py", parameters={"storeys": 12}, turn=4.0, captions=True,
         size=(320, 320), fps=6.0).save(IMAGES / "build.gif")
    with tempfile.TemporaryDirectory() as tmp:
        section_pair(ROOT / "scripts" / "rind_soccerball.py", Path(tmp)).save(
            IMAGES / "section.png", optimize=True)
    print(f"wrote {IMAGES / 'gallery.png'}, {IMAGES / 'tower.gif'}, {IMAGES / 'build.gif'} "
          f"and {IMAGES / 'section.png'}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
