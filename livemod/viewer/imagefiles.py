"""Writing rendered frames to files: PNG, PNG sequences, GIF, animated WebP, MP4.

Every name is checked by :func:`check_output` before anything is rendered, so a
long turntable never ends in a bad file name, and every file is written
atomically (encoded into a temporary file beside it, then renamed over it).

PNG, GIF and WebP need only Pillow. MP4 (H.264, the format video sites and slide
decks take) needs PyAV, an optional dependency: ``pip install "livemod[video]"``.
"""

from __future__ import annotations

import functools
import importlib.util
from collections.abc import Callable, Sequence
from fractions import Fraction
from pathlib import Path
from typing import BinaryIO

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
# a GIF's delays are whole hundredths of a second, and browsers and most viewers
# play a delay under 2 of them as 10: 50 fps is the fastest a GIF plays at
GIF_FASTEST = 50.0
# room kept at the front of an MP4 for its index (see _mp4): measured 773 bytes for
# one frame and ~12 more per frame; at most 32 per frame (every sample table
# holding a full entry for each), so the room always suffices
MP4_INDEX_ROOM = (2048, 32)


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


def gif_rate_note(paths: Sequence[Path], fps: float) -> str | None:
    """What to tell whoever asked for ``fps`` when ``paths`` (see
    :func:`check_output`) is one GIF faster than :data:`GIF_FASTEST`, which
    :func:`write_images` writes at that rate; None for anything else."""
    if len(paths) != 1 or paths[0].suffix.lower() != ".gif" or fps <= GIF_FASTEST:
        return None
    return (f"a GIF plays at most {GIF_FASTEST:g} frames per second (its delays are whole "
            f"hundredths of a second, and viewers slow shorter ones to a tenth); writing "
            f"{paths[0]} at {GIF_FASTEST:g} fps, not {fps:g} (.webp or .mp4 play at {fps:g})")


def write_images(out: str, images: Sequence[np.ndarray], fps: float = 25.0) -> list[Path]:
    """Write ``images`` (each ``(H, W, 3)`` or, with a transparent background,
    ``(H, W, 4)`` uint8, all one size) where :func:`output_paths` says, each file
    atomically, and return the paths written.

    Animations loop and play at ``fps``. A GIF plays at most at 50 fps (see
    :data:`GIF_FASTEST`): it is written at 50 when asked for more. Its delays are
    whole hundredths of a second, so where ``fps`` does not divide 100 they
    alternate (30 fps: 30, 40, 30 ms, ...) to keep the rate over the loop. WebP is
    lossless; MP4 is H.264 (``yuv420p``, the index at the front so browsers play
    it while loading).

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


def _pillow_animation(images: Sequence[np.ndarray], durations: list[int], data: BinaryIO,
                      *, format: str, **options: object) -> None:  # noqa: A002 (Pillow's name)
    """Encode ``images`` as one looping Pillow animation of ``format`` into ``data``,
    frame ``k`` shown for ``durations[k]`` milliseconds."""
    from PIL import Image

    pictures = [Image.fromarray(image) for image in images]
    pictures[0].save(data, format=format, save_all=True, append_images=pictures[1:],
                     duration=durations, loop=0, **options)


def _gif(images: Sequence[np.ndarray], fps: float, data: BinaryIO) -> None:
    """A looping GIF at ``fps`` (at most :data:`GIF_FASTEST`) into ``data``."""
    _pillow_animation(images, gif_delays(len(images), fps), data, format="GIF",
                      optimize=False)


def gif_delays(frames: int, fps: float) -> list[int]:
    """Each of ``frames`` GIF frames' delay in milliseconds at ``fps`` (at most
    :data:`GIF_FASTEST`): whole hundredths of a second, each the rounded running
    total less the one before, so the loop keeps the rate (30 fps: 30, 40, 30)."""
    ends = [round(100.0 * (k + 1) / min(fps, GIF_FASTEST)) for k in range(frames)]
    return [10 * (end - start) for start, end in zip([0, *ends], ends, strict=False)]


def _webp(images: Sequence[np.ndarray], fps: float, data: BinaryIO) -> None:
    """A looping, lossless animated WebP at ``fps`` into ``data`` (``exact``: the
    colour under alpha 0 kept too, the PNG's pixels)."""
    _pillow_animation(images, [round(1000.0 / fps)] * len(images), data, format="WEBP",
                      lossless=True, exact=True)


def _mp4(images: Sequence[np.ndarray], fps: float, data: BinaryIO) -> None:
    """An H.264 MP4 at ``fps`` into ``data`` (a seekable file), its index first.

    The muxer's ``faststart`` moves the index to the front in a second pass that
    reopens the file by name, which the atomic write's temporary file has not:
    room for the index is kept at the front instead (``moov_size``, see
    :data:`MP4_INDEX_ROOM`), and the muxer seeks back to write it there.
    """
    import av

    height, width = images[0].shape[:2]
    room = MP4_INDEX_ROOM[0] + MP4_INDEX_ROOM[1] * len(images)
    with av.open(data, mode="w", format="mp4", options={"moov_size": str(room)}) as container:
        stream = container.add_stream("libx264", rate=Fraction(fps).limit_denominator(1001))
        stream.width, stream.height, stream.pix_fmt = width, height, "yuv420p"
        stream.options = {"crf": MP4_QUALITY}
        for image in images:
            container.mux(stream.encode(av.VideoFrame.from_ndarray(image, format="rgb24")))
        container.mux(stream.encode())  # flush the frames the encoder holds back


_ANIMATION_WRITERS: dict[str, Callable[[Sequence[np.ndarray], float, BinaryIO], None]] = {
    ".gif": _gif, ".webp": _webp, ".mp4": _mp4}


def _save(path: Path, write: Callable[[BinaryIO], None]) -> None:
    """Encode with ``write`` straight into the temporary file of an atomic write,
    which then replaces ``path`` (its folder made if missing).

    Raises:
        OSError: the file cannot be written; an old ``path`` is left intact.
    """
    from livemod.dlfl.io.atomic import atomic_write

    path.parent.mkdir(parents=True, exist_ok=True)
    with atomic_write(path) as handle:
        write(handle)


def save_new_png(path: Path, image: np.ndarray) -> None:
    """Write one ``(H, W, 3 or 4)`` uint8 image to ``path`` as PNG, only if no file
    has that name: the check and the write are one step, so a file another
    process makes meanwhile is never written over. The PNG is encoded into a
    temporary file beside ``path`` and then hard-linked to its name (a link never
    replaces a file), so ``path`` appears whole; where the file system has no hard
    links, ``path`` is created exclusively and written.

    Raises:
        FileExistsError: ``path`` exists (it is left as it was).
        OSError: the file cannot be written (no partial ``path`` is left).
    """
    import os

    from PIL import Image

    from livemod.dlfl.io.atomic import temporary_path

    path.parent.mkdir(parents=True, exist_ok=True)
    # named as atomic saves name theirs, so a later save removes it if this
    # process is killed before it is unlinked
    temp = Path(temporary_path(os.path.abspath(path)))
    _write_exclusive(temp, functools.partial(Image.fromarray(image).save, format="PNG"))
    try:
        try:
            os.link(temp, path)
        except FileExistsError:
            raise
        except OSError:  # no hard links here (FAT, some network shares)
            _write_exclusive(path, lambda handle: handle.write(temp.read_bytes()))
    finally:
        temp.unlink(missing_ok=True)


def _write_exclusive(path: Path, write: Callable[[BinaryIO], object]) -> None:
    """Create ``path`` (FileExistsError if it exists) and fill it with ``write``;
    a failed write removes it again."""
    import os

    fd = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0),
                 0o666)
    try:
        with os.fdopen(fd, "wb") as handle:
            write(handle)
    except BaseException:
        path.unlink(missing_ok=True)
        raise


def save_png(path: Path, image: np.ndarray) -> None:
    """Write one ``(H, W, 3 or 4)`` uint8 image to ``path`` as PNG, atomically."""
    from PIL import Image

    _save(path, functools.partial(Image.fromarray(image).save, format="PNG"))


def save_numbered_png(stem: str, first: int, image: np.ndarray) -> Path:
    """Write ``image`` (as :func:`save_new_png`) to ``<stem>_NNN.png`` in the
    working directory, NNN the first number from ``first`` whose name is free
    at the moment the file is made; return that path.

    Raises:
        OSError: the file cannot be written.
    """
    index = first
    while True:
        path = Path(f"{stem}_{index:03d}.png")
        try:
            save_new_png(path, image)
            return path
        except FileExistsError:
            index += 1

