"""Output names and image/animation files of ``livemod render`` (no GL needed)."""

from __future__ import annotations

import sys
from pathlib import Path

import av
import numpy as np
import pytest
from PIL import Image

from livemod.viewer.imagefiles import (
    check_output,
    gif_delays,
    gif_rate_note,
    output_paths,
    save_new_png,
    save_numbered_png,
    save_png,
    write_images,
)
from tests.images import read_image


def moving_square(frames: int, size: tuple[int, int] = (64, 48), alpha: bool = False,
                  ) -> list[np.ndarray]:
    """``frames`` images ``(H, W, 3 or 4)``: a white square walking over a red ramp
    (alpha: the ramp half transparent, the square opaque)."""
    width, height = size
    images = []
    for k in range(frames):
        image = np.zeros((height, width, 4 if alpha else 3), np.uint8)
        image[..., 0] = 30 * k + 20
        if alpha:
            image[..., 3] = 128
        image[10:26, 4 + 6 * k:20 + 6 * k] = 255
        images.append(image)
    return images


def test_output_paths_of_patterns_folders_and_single_files() -> None:
    assert [p.name for p in output_paths("out/t_{frame:02d}.png", 2)] == ["t_00.png", "t_01.png"]
    assert [p.name for p in output_paths("t_%03d.png", 2)] == ["t_000.png", "t_001.png"]
    assert output_paths("folder", 2)[1].as_posix() == "folder/frame_001.png"
    for name in ("turn.gif", "turn.webp", "turn.MP4"):
        assert output_paths(name, 36) == [Path(name)]
    assert output_paths("one.PNG", 1) == [Path("one.PNG")]


@pytest.mark.parametrize(("out", "frames", "wrong"), [
    ("x.foo", 1, "give a .png, .gif, .webp or .mp4 name, a folder, or a name with {frame} "
                 "or %03d"),
    ("tt.png", 3, "3 frames cannot go to one PNG \\(tt.png\\); use .gif, .webp, .mp4"),
    ("100%.png", 1, "takes only {frame} or one %d field .*write %% for a percent sign"),
    ("f_{frame}_{x}.png", 2, "takes only {frame} or one %d field \\(KeyError: 'x'\\)"),
    ("same.png{}", 2, "takes only {frame}"),
    ("fixed_{frame:.0s}.png", 2, "takes only {frame}|names two frames alike"),
])
def test_output_paths_refuse_what_cannot_be_written(out: str, frames: int, wrong: str) -> None:
    with pytest.raises(ValueError, match=wrong):
        output_paths(out, frames)


@pytest.mark.parametrize(("out", "size", "transparent", "fps", "wrong"), [
    ("t.gif", (64, 48), True, 25.0, "needs PNG or WebP output, not 't.gif' \\(a GIF cannot "
                                    "hold soft edges\\)"),
    ("t.mp4", (64, 48), True, 25.0, "not 't.mp4' \\(MP4 has no alpha\\)"),
    ("t.mp4", (63, 48), False, 25.0, "MP4 needs an even width and height, got 63x48; try 64x48"),
    ("t.mp4", (64, 47), False, 25.0, "got 64x47; try 64x48"),
    ("t.gif", (64, 48), False, 0.0, "frames per second must be a positive number, got 0.0"),
    ("t.webp", (64, 48), False, float("nan"), "positive number, got nan"),
])
def test_check_output_refuses_what_the_format_cannot_hold(
        out: str, size: tuple[int, int], transparent: bool, fps: float, wrong: str) -> None:
    with pytest.raises(ValueError, match=wrong):
        check_output(out, 4, size, transparent=transparent, fps=fps)


def test_check_output_takes_what_the_formats_hold() -> None:
    assert check_output("t.webp", 4, (63, 47), transparent=True) == [Path("t.webp")]
    assert check_output("seq", 2, (63, 47), transparent=True)[1] == Path("seq/frame_001.png")
    assert check_output("t.mp4", 4, (64, 48), fps=30.0) == [Path("t.mp4")]


def test_mp4_without_pyav_names_the_extra_to_install(monkeypatch) -> None:
    monkeypatch.setitem(sys.modules, "av", None)  # find_spec then raises ValueError
    monkeypatch.setattr("importlib.util.find_spec", lambda name: None)
    with pytest.raises(ValueError, match='writing t.mp4 needs PyAV: pip install "livemod'
                                         '\\[video\\]" \\(or write .gif or .webp\\)'):
        check_output("t.mp4", 4, (64, 48))


def test_mp4_holds_every_frame_at_the_rate_asked(tmp_path: Path) -> None:
    images = moving_square(7)
    out = tmp_path / "turn.mp4"
    assert write_images(str(out), images, fps=30.0) == [out]
    with av.open(str(out)) as container:
        stream = container.streams.video[0]
        assert stream.codec_context.name == "h264"
        assert (stream.codec_context.width, stream.codec_context.height) == (64, 48)
        assert stream.average_rate == 30
        decoded = [frame.to_ndarray(format="rgb24") for frame in container.decode(stream)]
    assert len(decoded) == 7
    for made, back in zip(images, decoded, strict=True):
        # lossy, but close, and the square is where it was in that frame
        assert np.abs(made.astype(int) - back).mean() < 4.0
    assert out.read_bytes().find(b"moov") < out.read_bytes().find(b"mdat")  # index first


def test_mp4_is_encoded_once_into_the_temporary_file_beside_the_target(tmp_path: Path,
                                                                      monkeypatch) -> None:
    """No copy in memory or in a private folder first: while frames are encoded, the
    atomic write's temporary file beside the target is what grows."""
    out = tmp_path / "turn.mp4"
    encode = av.VideoFrame.from_ndarray
    seen: list[list[str]] = []

    def watching(*args, **kwargs):
        seen.append([p.name for p in tmp_path.iterdir()])
        return encode(*args, **kwargs)

    monkeypatch.setattr(av.VideoFrame, "from_ndarray", watching)
    write_images(str(out), moving_square(3))
    assert len(seen) == 3
    assert all(len(names) == 1 and names[0].startswith(".turn.mp4.") for names in seen)
    assert [p.name for p in tmp_path.iterdir()] == ["turn.mp4"]


def test_mp4_is_the_same_bytes_every_time(tmp_path: Path) -> None:
    first, second = tmp_path / "a.mp4", tmp_path / "b.mp4"
    write_images(str(first), moving_square(4))
    write_images(str(second), moving_square(4))
    assert first.read_bytes() == second.read_bytes()


def test_webp_is_lossless_with_alpha_and_loops(tmp_path: Path) -> None:
    images = moving_square(5, alpha=True)
    out = tmp_path / "turn.webp"
    write_images(str(out), images, fps=20.0)
    with Image.open(out) as webp:
        assert webp.n_frames == 5 and webp.info["loop"] == 0
        for k, made in enumerate(images):
            webp.seek(k)
            frame = np.asarray(webp.convert("RGBA"))  # loads the frame and its info
            assert webp.info["duration"] == 50
            assert np.array_equal(frame, made)


def _gif_durations(path: Path) -> list[int]:
    with Image.open(path) as gif:
        assert gif.info["loop"] == 0
        durations = []
        for k in range(gif.n_frames):
            gif.seek(k)
            durations.append(gif.info["duration"])
        return durations


@pytest.mark.parametrize(("fps", "durations"), [
    (25.0, [40, 40, 40]),
    (30.0, [30, 40, 30]),    # 100 ms for three frames: the rate kept over the loop
    (40.0, [20, 30, 30]),    # Pillow alone would store 25 ms as 20: 50 fps
    (50.0, [20, 20, 20]),
    (60.0, [20, 20, 20]),    # 17 ms would play as 100 ms in most viewers: 50 fps
    (1000.0, [20, 20, 20]),
])
def test_gif_delays_are_whole_hundredths_and_at_most_50_fps(tmp_path: Path, fps: float,
                                                            durations: list[int]) -> None:
    out = tmp_path / "turn.gif"
    write_images(str(out), moving_square(3), fps=fps)
    assert _gif_durations(out) == durations == gif_delays(3, fps)


def test_gif_delays_never_go_below_two_hundredths() -> None:
    for fps in (49.0, 47.5, 33.0, 12.5, 7.0, 0.5):
        delays = gif_delays(50, fps)
        assert min(delays) >= 20 and all(d % 10 == 0 for d in delays)
        assert sum(delays) == 10 * round(100 * 50 / fps)


def test_only_a_gif_above_50_fps_gets_a_note() -> None:
    assert gif_rate_note([Path("t.gif")], 60.0) == (
        "a GIF plays at most 50 frames per second (its delays are whole hundredths of a "
        "second, and viewers slow shorter ones to a tenth); writing t.gif at 50 fps, not 60 "
        "(.webp or .mp4 play at 60)")
    assert gif_rate_note([Path("t.gif")], 50.0) is None
    assert gif_rate_note([Path("t.webp")], 60.0) is None
    assert gif_rate_note([Path("a.png"), Path("b.png")], 60.0) is None


def test_png_sequence_and_single_png(tmp_path: Path) -> None:
    images = moving_square(2)
    paths = write_images(str(tmp_path / "seq" / "f_{frame}.png"), images)
    assert [p.name for p in paths] == ["f_0.png", "f_1.png"]
    for path, made in zip(paths, images, strict=True):
        assert np.array_equal(read_image(path), made)
    clear = moving_square(1, alpha=True)[0]
    save_png(tmp_path / "one.png", clear)
    assert np.array_equal(read_image(tmp_path / "one.png"), clear)


def test_a_failed_write_leaves_the_old_file(tmp_path: Path, monkeypatch) -> None:
    out = tmp_path / "turn.mp4"
    out.write_bytes(b"old movie")

    def broken(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(av.VideoFrame, "from_ndarray", broken)
    with pytest.raises(OSError, match="disk full"):
        write_images(str(out), moving_square(2))
    assert out.read_bytes() == b"old movie"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["turn.mp4"]  # no temporary left


def test_write_images_refuses_no_frames_and_bad_names_before_writing(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="no frames to write to"):
        write_images(str(tmp_path / "t.gif"), [])
    with pytest.raises(ValueError, match="MP4 has no alpha"):
        write_images(str(tmp_path / "t.mp4"), moving_square(2, alpha=True))
    assert list(tmp_path.iterdir()) == []


def test_a_new_png_never_replaces_a_file(tmp_path: Path) -> None:
    path = tmp_path / "shot.png"
    path.write_bytes(b"someone else's")
    image = np.zeros((4, 6, 3), np.uint8)
    with pytest.raises(FileExistsError):
        save_new_png(path, image)
    assert path.read_bytes() == b"someone else's"
    fresh = tmp_path / "sub" / "new.png"
    save_new_png(fresh, image)
    assert np.asarray(Image.open(fresh)).shape == (4, 6, 3)
    assert sorted(p.name for p in tmp_path.rglob("*")) == ["new.png", "shot.png", "sub"]


def test_a_new_pngs_temporary_file_is_named_for_the_abandoned_sweep(tmp_path: Path,
                                                                    monkeypatch) -> None:
    import os

    from livemod.dlfl.io import atomic

    linked = []
    real_link = os.link

    def link(source, target):
        linked.append(Path(source).name)
        real_link(source, target)

    monkeypatch.setattr(os, "link", link)
    save_new_png(tmp_path / "shot.png", np.zeros((4, 6, 3), np.uint8))
    # the sweep of atomic saves recognises it as this process's, so it removes it
    # once this process is gone (a screenshot killed between encode and link)
    found = atomic._TEMPORARY.fullmatch(linked[0])
    assert found is not None and found["pid"] == str(os.getpid())


def test_a_numbered_png_takes_the_first_free_number(tmp_path: Path,
                                                    monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    (tmp_path / "shot_002.png").write_bytes(b"someone else's")
    image = np.full((2, 3, 3), 200, dtype=np.uint8)
    paths = [save_numbered_png("shot", 1, image) for _ in range(3)]
    assert [p.name for p in paths] == ["shot_001.png", "shot_003.png", "shot_004.png"]
    assert (tmp_path / "shot_002.png").read_bytes() == b"someone else's"
    assert np.array_equal(read_image(tmp_path / "shot_004.png"), image)
