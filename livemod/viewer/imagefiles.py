"""Writing rendered frames to files: PNG, PNG sequences, GIF, animated WebP, MP4.

Every name is checked by :func:`check_output` before anything is rendered, so a
long turntable never ends in a bad file name, and every file is written
atomically (encoded in full, then renamed over the target).

PNG, GIF and WebP need only Pillow. MP4 (H.264, the format video sites and slide
decks take) needs PyAV, an optional dependency: ``pip install "livemod[video]"``.
"""

from __future__ import annotations

import functools
import importlib.util
import io
import tempfile
from collections.abc import Callable, Sequence
from fractions import Fraction
from pathlib import Path

import numpy as np

# suffixes that hold every frame in one file, by what can go in them
ANIMATIONS = (".gif", ".webp", ".mp4")
IMAGE_SUFFIXES = (".png", *ANIMATIONS)
# what cannot hold a transparent background: GIF's alpha is on/off (soft edges
# turn into fringes); H.264 has none
OPAQUE_ONLY = (".gif", ".mp4")
VIDEO_EXTRA = 'pip install "livemod[video]"'
# x264's quality: 18 is visually lossless for flat-shaded renders, at ~1/5 of crf 0's size
MP4_QUALITY = "18"


def output_paths(out: str, frames: int) -> list[Path]:
    """The files rendering ``frames`` frames to ``out`` writes: ``x.gif``, ``x.webp``
    or ``x.mp4`` (all frames in one), ``x.png`` (one frame), or a PNG sequence: a
    name with ``{frame}`` (format spec allowed) or one ``%d``-style field, or a
    folder (``frame_000.png``, ...).

    Raises:
        ValueError: another suffix, a pattern with other fields, several frames
            for one PNG, or a pattern that names two frames alike.
    """
    target = Path(out)
    if "{" not in out and "%" not in out and target.suffix:
        if target.suffix.lower() not in IMAGE_SUFFIXES:
            raise ValueError(f"cannot write images to {out!r}: give a .png, .gif, .webp or "
                             ".mp4 name, a folder, or a name with {frame} or %03d")
        if target.suffix.lower() == ".png" and frames > 1:
            raise ValueError(f"{frames} frames cannot go to one PNG ({out}); use .gif, .webp, "
                             ".mp4, a folder, or a name with {frame}, e.g. turn_{frame:03d}.png")
        return [target]
    paths = _sequence(out, frames)
    if len(set(paths)) < len(paths):
        raise ValueError(f"the pattern {out!r} names two frames alike; put {{frame}} in it")
    return paths


def _sequence(out: str, frames: int) -> list[Path]:
    """The PNG sequence of a pattern or folder ``out`` (see :func:`output_paths`)."""
    width = max(3, len(str(frames - 1)))
    try:
        if "{" in out:
            return [Path(out.format(frame=index)) for index in range(frames)]
        if "%" in out:
            return [Path(out % index) for index in range(frames)]
    except (KeyError, IndexError, ValueError, TypeError) as exc:
        percent = "; write %% for a percent sign" if "%" in out else ""
        raise ValueError(f"the output pattern {out!r} takes only {{frame}} or one %d "
                         f"field ({type(exc).__name__}: {exc}){percent}") from None
    return [Path(out) / f"frame_{index:0{width}d}.png" for index in range(frames)]


def check_output(out: str, frames: int, size: tuple[int, int], *,
                 transparent: bool = False, fps: float = 25.0) -> list[Path]:
    """:func:`output_paths`, and whether its format can take these frames: call it
    before rendering. ``size`` is ``(width, height)`` in pixels.

    Raises:
        ValueError: what :func:`output_paths` raises; a transparent background
            for GIF or MP4; an MP4 of odd width or height (H.264's 4:2:0 colour
            needs even ones) or without PyAV installed; ``fps`` not positive.
    """
    paths = output_paths(out, frames)
    suffix = paths[0].suffix.lower() if len(paths) == 1 else ".png"
    if not np.isfinite(fps) or fps <= 0:
        raise ValueError(f"frames per second must be a positive number, got {fps}")
    if transparent and suffix in OPAQUE_ONLY:
        why = "a GIF cannot hold soft edges" if suffix == ".gif" else "MP4 has no alpha"
        raise ValueError(f"a transparent background needs PNG or WebP output, not {out!r} "
                         f"({why})")
    if suffix == ".mp4":
        if size[0] % 2 or size[1] % 2:
            raise ValueError(f"MP4 needs an even width and height, got {size[0]}x{size[1]}; "
                             f"try {size[0] + size[0] % 2}x{size[1] + size[1] % 2}")
        if importlib.util.find_spec("av") is None:
            raise ValueError(f"writing {out} needs PyAV: {VIDEO_EXTRA} (or write .gif or .webp)")
    return paths


def write_images(out: str, images: Sequence[np.ndarray], fps: float = 25.0) -> list[Path]:
    """Write ``images`` (each ``(H, W, 3)`` or, with a transparent background,
    ``(H, W, 4)`` uint8, all one size) where :func:`output_paths` says, each file
    atomically, and return the paths written.

    Animations loop and play at ``fps``. GIF frame delays are whole centiseconds,
    so 25 fps (40 ms) is exact; WebP is lossless; MP4 is H.264 (``yuv420p``, the
    index at the front so browsers play it while loading).

    Raises:
        ValueError: see :func:`check_output`.
        OSError: a file cannot be written; an old file of that name is left intact.
    """
    if not images:
        raise ValueError(f"no frames to write to {out}")
    height, width = images[0].shape[:2]
    transparent = images[0].shape[2] == 4
    paths = check_output(out, len(images), (width, height), transparent=transparent, fps=fps)
    writer = _ANIMATION_WRITERS.get(paths[0].suffix.lower()) if len(paths) == 1 else None
    if writer is not None:
        _save(paths[0], functools.partial(writer, images, fps))
        return paths
    for path, image in zip(paths, images, strict=True):
        save_png(path, image)
    return paths


def _pillow_animation(images: Sequence[np.ndarray], fps: float, data: io.BytesIO, *,
                      format: str, **options: object) -> None:  # noqa: A002 (Pillow's name)
    """Encode ``images`` as one looping Pillow animation of ``format`` into ``data``."""
    from PIL import Image

    pictures = [Image.fromarray(image) for image in images]
    pictures[0].save(data, format=format, save_all=True, append_images=pictures[1:],
                     duration=round(1000.0 / fps), loop=0, **options)


def _mp4(images: Sequence[np.ndarray], fps: float, data: io.BytesIO) -> None:
    import av

    height, width = images[0].shape[:2]
    # the muxer's second pass (index to the front) reopens the file by name, so it
    # cannot write to memory: encode into a private folder, then read back
    with tempfile.TemporaryDirectory(prefix="livemod-mp4-") as folder:
        name = str(Path(folder) / "out.mp4")
        with av.open(name, mode="w", options={"movflags": "faststart"}) as container:
            stream = container.add_stream("libx264", rate=Fraction(fps).limit_denominator(1001))
            stream.width, stream.height, stream.pix_fmt = width, height, "yuv420p"
            stream.options = {"crf": MP4_QUALITY}
            for image in images:
                container.mux(stream.encode(av.VideoFrame.from_ndarray(image, format="rgb24")))
            container.mux(stream.encode())  # flush the frames the encoder holds back
        data.write(Path(name).read_bytes())


_ANIMATION_WRITERS: dict[str, Callable[[Sequence[np.ndarray], float, io.BytesIO], None]] = {
    ".gif": functools.partial(_pillow_animation, format="GIF", optimize=False),
    # exact: keep the colour under alpha 0 too, the PNG's pixels
    ".webp": functools.partial(_pillow_animation, format="WEBP", lossless=True, exact=True),
    ".mp4": _mp4}


def _save(path: Path, write: Callable[[io.BytesIO], None]) -> None:
    """Encode with ``write`` in memory, then replace ``path`` atomically."""
    from livemod.dlfl.io.atomic import write_atomically

    data = io.BytesIO()
    write(data)
    path.parent.mkdir(parents=True, exist_ok=True)
    write_atomically(path, data.getvalue())


def save_png(path: Path, image: np.ndarray) -> None:
    """Write one ``(H, W, 3 or 4)`` uint8 image to ``path`` as PNG, atomically."""
    from PIL import Image

    _save(path, functools.partial(Image.fromarray(image).save, format="PNG"))
