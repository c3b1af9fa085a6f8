"""Viewer and rendering benchmarks (plain python; prints medians of several runs).

    python bench/bench_viewer.py [--quick]

1. Upload of a 1,000,000-face mesh (a 1000x1000 quad torus) to GPU buffers over
   EGL: the numpy part (:func:`build_geometry`) and the whole ``set_mesh``
   (numpy + buffer and table uploads, ``ctx.finish()``). Targets: 0.3 s and 0.5 s.
2. A 36-frame 512x512 turntable of a 100,000-face mesh (316x316 torus) on the
   software renderer, with read-back, without MSAA (the turntable default) and
   with 4x MSAA; plus writing it as a GIF. Target: at most 20 s for the frames.
3. Frame times of the live window (headless backend, 640x480) while a 5-second
   pure-Python script runs in the runner: median and 90th percentile.
   Target: under 50 ms.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

from livemod.dlfl import mesh_arrays
from livemod.dlfl.shapes import torus
from livemod.viewer.geometry import build_geometry
from livemod.viewer.headless import Offscreen, framed_camera, render_turntable, write_images
from livemod.viewer.renderer import Style


def _median(times: list[float]) -> str:
    return f"median {statistics.median(times):.3f} s  (runs: {', '.join(f'{t:.3f}' for t in times)})"


def bench_upload(runs: int, size: int) -> None:
    arrays = mesh_arrays(torus(size, size))
    faces = arrays.counts[2]
    numpy_times, total_times, numpy_cpu, total_cpu = [], [], [], []
    offscreen = Offscreen((64, 64), samples=0)
    for _ in range(runs):
        start, cpu = time.perf_counter(), time.process_time()
        build_geometry(arrays)
        numpy_times.append(time.perf_counter() - start)
        numpy_cpu.append(time.process_time() - cpu)
        start, cpu = time.perf_counter(), time.process_time()
        offscreen.renderer.set_mesh(arrays)
        offscreen.ctx.finish()
        total_times.append(time.perf_counter() - start)
        total_cpu.append(time.process_time() - cpu)
    offscreen.release()
    print(f"upload {faces:,} faces, numpy part: wall {_median(numpy_times)}  target 0.3 s")
    print(f"  CPU: {_median(numpy_cpu)}; least wall {min(numpy_times):.3f} s")
    print(f"upload {faces:,} faces, total:      wall {_median(total_times)}  target 0.5 s")
    print(f"  CPU: {_median(total_cpu)}; least wall {min(total_times):.3f} s")


def bench_turntable(runs: int, size: int, frames: int, samples: int) -> None:
    arrays = mesh_arrays(torus(size, size))
    faces = arrays.counts[2]
    times, cpu_times, gif_times = [], [], []
    for _ in range(runs):
        offscreen = Offscreen((512, 512), samples=samples)
        offscreen.renderer.set_mesh(arrays)
        camera = framed_camera(arrays, elevation=25.0, frames=frames)
        start, cpu_start = time.perf_counter(), time.process_time()
        images = render_turntable(offscreen, camera, Style(), frames)
        times.append(time.perf_counter() - start)
        cpu_times.append(time.process_time() - cpu_start)
        offscreen.release()
        with tempfile.TemporaryDirectory() as folder:
            start = time.perf_counter()
            write_images(str(Path(folder) / "turn.gif"), images)
            gif_times.append(time.perf_counter() - start)
    print(f"turntable {frames} frames 512x512, MSAA {samples}, {faces:,} faces: "
          f"wall {_median(times)}  target 20 s")
    print(f"  CPU time of those frames (all threads): {_median(cpu_times)}")
    print(f"  writing the GIF: {_median(gif_times)}")


BUSY = (
    "import time\n"
    "start = time.perf_counter()\n"
    "while time.perf_counter() - start < 5.0:\n"
    "    total = sum(i * i for i in range(2000))\n"
)


def bench_frames_during_run(seconds: float) -> None:
    from livemod.viewer.window import ViewOptions, close_viewer, create_viewer, run_frames

    with tempfile.TemporaryDirectory() as folder:
        script = Path(folder) / "busy.py"
        script.write_text(BUSY)
        viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(640, 480),
                                           samples=0, vsync=False))
        times = []
        started = time.perf_counter()
        while time.perf_counter() - started < seconds:
            frame_start = time.perf_counter()
            run_frames(viewer, 1)
            times.append(time.perf_counter() - frame_start)
        still_running = viewer.waiting
        close_viewer(viewer)
    times.sort()
    print(f"window frames during a 5 s script ({len(times)} frames, run still going: "
          f"{still_running}): median {1000 * times[len(times) // 2]:.1f} ms, "
          f"p90 {1000 * times[int(0.9 * len(times))]:.1f} ms, max {1000 * times[-1]:.1f} ms"
          "  target < 50 ms")


# -- the smoothed preview and the swap of a big result (issue 29) -------------------------
#
# These run on this tree's code and on an older one alike (PYTHONPATH picks the
# tree), so that figures can be taken side by side: code without the patch
# preview (livemod.runner.preview.make_preview) gets the Catmull-Clark preview it
# had, drawn the way it drew it.

PREVIEW_SIZE = (1280, 800)


def _has_patches() -> bool:
    import livemod.runner.preview as preview

    return hasattr(preview, "make_preview")


def _make_preview(arrays):  # noqa: ANN001, ANN202
    """The preview of ``arrays`` as this tree's window makes it."""
    if _has_patches():
        from livemod.runner.preview import PreviewRequest, make_preview

        return make_preview(PreviewRequest((arrays,)))
    from livemod.dlfl.build import from_corner_arrays
    from livemod.runner.preview import preview_arrays

    return preview_arrays(from_corner_arrays(arrays.positions, arrays.face_offsets,
                                             arrays.corner_vertex, arrays.corner_mate,
                                             arrays.face_hole))


def bench_preview_first_frame(size: int, runs: int, samples: int) -> None:
    """From a result's arrays to the first frame drawn with its smooth preview, at
    1280x800 (the preview made, uploaded and drawn; what the window does off and on
    its thread, here in one)."""
    arrays = mesh_arrays(torus(size, size))
    offscreen = Offscreen(PREVIEW_SIZE, samples=samples)
    offscreen.renderer.set_mesh(arrays)
    camera = framed_camera(arrays, elevation=25.0, aspect=1.6)
    style = Style(preview=True)
    walls, cpus, described = [], [], ""
    for _ in range(runs):
        start, cpu = time.perf_counter(), time.process_time()
        made = _make_preview(arrays)
        offscreen.renderer.set_preview(made)
        offscreen.renderer.draw(offscreen.target, camera, style)
        offscreen.ctx.finish()
        walls.append(time.perf_counter() - start)
        cpus.append(time.process_time() - cpu)
        described = getattr(made, "description", "Catmull-Clark, 2 levels (old code)")
    offscreen.release()
    print(f"preview first frame, {size * size:,} faces ({described}), MSAA {samples}: "
          f"wall {_median(walls)}; CPU {_median(cpus)}")


def bench_preview_frames(size: int, frames: int, samples: int) -> None:
    """Frame time at 1280x800 while the preview of the mesh is on screen and the view
    turns (every frame drawn whole; an unchanging view is a kept frame, copied)."""
    arrays = mesh_arrays(torus(size, size))
    offscreen = Offscreen(PREVIEW_SIZE, samples=samples)
    made = _make_preview(arrays)
    offscreen.renderer.set_mesh(arrays, made)
    camera = framed_camera(arrays, elevation=25.0, aspect=1.6)
    style = Style(preview=True)
    offscreen.renderer.draw(offscreen.target, camera, style)
    walls, cpus = [], []
    for _ in range(frames):
        camera.yaw += 2.0
        start, cpu = time.perf_counter(), time.process_time()
        offscreen.renderer.draw(offscreen.target, camera, style)
        offscreen.ctx.finish()
        walls.append(time.perf_counter() - start)
        cpus.append(time.process_time() - cpu)
    offscreen.release()
    triangles = len(getattr(made, "surface", None).triangles) if _has_patches() \
        else 2 * made.counts[2]
    print(f"preview frames, {size * size:,} faces ({triangles:,} triangles), MSAA {samples}, "
          f"turning: wall {_median(walls)}; CPU {_median(cpus)}")


SWAP_SCRIPT = (
    "from livemod.dlfl.shapes import torus\n"
    "from livemod.dlfl import current_scene\n"
    "current_scene().add(torus({rings}, 1000, major={major}))\n"
)


def bench_swap(rings: int, samples: int, labels: bool = True) -> None:
    """Save -> first frame of a big result in the live window (headless, 1280x800):
    from the frame the result arrives in (the script's own run excluded) to the
    first frame that shows it whole, and the longest frame in between; with face
    labels on."""
    from livemod.viewer.window import ViewOptions, close_viewer, create_viewer, run_frames

    with tempfile.TemporaryDirectory() as folder:
        script = Path(folder) / "big.py"
        script.write_text(SWAP_SCRIPT.format(rings=rings, major=2.0))
        viewer = create_viewer(ViewOptions(str(script), backend="headless", size=PREVIEW_SIZE,
                                           samples=samples, vsync=False,
                                           echo=open(os.devnull, "w")))  # noqa: SIM115
        try:
            if labels:
                viewer.handle_key("F", ctrl=True)
            _frames_until(viewer, lambda: _shown_whole(viewer, None), run_frames)
            first = viewer.renderer.arrays
            script.write_text(SWAP_SCRIPT.format(rings=rings, major=2.5))
            viewer.session.reload()
            _until_posted(viewer, run_frames)
            times = []
            arrived = time.perf_counter()
            while not _shown_whole(viewer, first):
                start = time.perf_counter()
                run_frames(viewer, 1)
                times.append(time.perf_counter() - start)
                # paced at 60 Hz, as vsync would (a loop that never waits starves the
                # threads that prepare the result of the interpreter)
                time.sleep(max(1 / 60 - times[-1], 0.0))
            total = time.perf_counter() - arrived
        finally:
            close_viewer(viewer)
    faces = rings * 1000
    print(f"swap to a {faces:,}-face result, labels {'on' if labels else 'off'}, MSAA "
          f"{samples}: first whole frame {total:.3f} s after it arrived, {len(times)} frames, "
          f"longest {max(times) * 1000:.0f} ms, median {statistics.median(times) * 1000:.0f} ms")


def _shown_whole(viewer, before) -> bool:  # noqa: ANN001
    """The window shows a mesh other than ``before``, wholly drawn."""
    shown = viewer.renderer.arrays
    if shown is None or shown is before:
        return False
    display = getattr(viewer, "display", None)
    return not (getattr(viewer.renderer, "unfinished", False)
                or (display is not None and getattr(display, "pending", False)))


def _frames_until(viewer, done, run_frames) -> None:  # noqa: ANN001
    """Run frames until ``done()`` (at most 10 minutes)."""
    deadline = time.monotonic() + 600
    while not done() and time.monotonic() < deadline:
        run_frames(viewer, 1)
        time.sleep(0.002)


def _until_posted(viewer, run_frames) -> None:  # noqa: ANN001
    """Run frames until the session has posted a result the window has not taken
    (the next frame takes it)."""
    deadline = time.monotonic() + 600
    while viewer.session.results.qsize() == 0 and time.monotonic() < deadline:
        run_frames(viewer, 1)
        time.sleep(0.002)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes, one run")
    parser.add_argument("--preview", action="store_true",
                        help="only the figures of the smoothed preview and of a big swap")
    args = parser.parse_args(argv)
    print("load average before: {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))
    if args.preview:
        bench_preview_first_frame(100, 3, 0)
        bench_preview_first_frame(316, 3, 0)
        bench_preview_frames(316, 9, 0)
        bench_preview_frames(316, 9, 4)
        bench_swap(1000, 4)
    elif args.quick:
        bench_upload(1, 100)
        bench_turntable(1, 60, 4, 0)
        bench_frames_during_run(1.0)
    else:
        bench_upload(5, 1000)
        bench_turntable(3, 316, 36, 0)   # the default of ``livemod render --turntable``
        bench_turntable(3, 316, 36, 4)
        bench_frames_during_run(4.0)
    print("load average after: {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
