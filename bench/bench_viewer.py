"""Viewer and rendering benchmarks (plain python; prints medians of several runs).

    python bench/bench_viewer.py [--quick | --preview [--colors]]

1. Upload of a 1,000,000-face mesh (a 1000x1000 quad torus) to GPU buffers over
   EGL: the numpy part (:func:`build_geometry`) and the whole ``set_mesh``
   (numpy + buffer and table uploads, ``ctx.finish()``). Targets: 0.3 s and 0.5 s.
2. A 36-frame 512x512 turntable of a 100,000-face mesh (316x316 torus) on the
   software renderer, with read-back, without MSAA (the turntable default) and
   with 4x MSAA; plus writing it as a GIF. Target: at most 20 s for the frames.
3. Frame times of the live window (headless backend, 640x480) while a 5-second
   pure-Python script runs in the runner, back to back and paced at 60 Hz as vsync
   would: median, 75th and 90th percentile, max. Target: under 50 ms.

``--preview`` takes the figures of issue 29 instead, at 1280x800 (they run on an
older tree too, given by PYTHONPATH, for figures side by side):

4. The first frame with the smooth preview of a 10,000- and a 99,856-face torus,
   from the result's arrays (targets 0.3 s and 2 s).
5. Frame times with the preview of the 99,856-face torus on screen, the view
   turning, drawn by the renderer (MSAA 0 and 4; whole, and as the window's
   quick pictures while the view moves: no edges, no multisampling), and in the
   live window, idle and turning (quick pictures, and every picture whole)
   (target: median 50 ms).
6. Save -> first whole frame of a 1,000,000-face result in the live window, face
   labels on, and the longest frame meanwhile (targets 1.0 s and 100 ms).
7. The patches evaluated by numpy against GL 4.5 tessellation shaders on llvmpipe
   (this tree only).

``--preview --colors`` takes figures 4 and 5 of tori with every other face
coloured (the preview drawn in the faces' colours).
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

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


def bench_frames_during_run(seconds: float, rate: float | None = None) -> None:
    """Frame times of the window while a pure-Python script runs: back to back, or with
    ``rate`` paced as vsync would (sleeping to the next 1/rate tick), which is what the
    user feels (the frame-time test of test_viewer_window.py measured that way)."""
    from livemod.viewer.window import ViewOptions, close_viewer, create_viewer, run_frames

    with tempfile.TemporaryDirectory() as folder:
        script = Path(folder) / "busy.py"
        script.write_text(BUSY)
        viewer = create_viewer(ViewOptions(str(script), backend="headless", size=(640, 480),
                                           samples=0, vsync=False))
        times = []
        tick = 0.0 if rate is None else 1.0 / rate
        started = next_frame = time.perf_counter()
        while time.perf_counter() - started < seconds:
            time.sleep(max(next_frame - time.perf_counter(), 0.0))
            frame_start = time.perf_counter()
            run_frames(viewer, 1)
            times.append(time.perf_counter() - frame_start)
            next_frame = max(next_frame + tick, time.perf_counter())
        still_running = viewer.waiting
        close_viewer(viewer)
    times.sort()
    paced = "back to back" if rate is None else f"paced at {rate:g} Hz"
    shown = ", ".join(f"{name} {1000 * times[int(q * (len(times) - 1))]:.1f} ms"
                      for name, q in (("median", 0.5), ("p75", 0.75), ("p90", 0.9), ("max", 1.0)))
    print(f"window frames during a 5 s script, {paced} ({len(times)} frames, run still "
          f"going: {still_running}): {shown}  target < 50 ms")


# -- the smoothed preview and the swap of a big result (issue 29) -------------------------
#
# These run on this tree's code and on an older one alike (PYTHONPATH picks the
# tree), so that figures can be taken side by side: code without the patch
# preview (livemod.runner.preview.make_preview) gets the Catmull-Clark preview it
# had, drawn the way it drew it.

PREVIEW_SIZE = (1280, 800)
COLORED = [False]  # --colors: the preview's tori have every other face coloured


def _preview_torus(size: int):  # noqa: ANN202
    """The arrays of a ``size`` x ``size`` torus, every other face coloured with
    ``--colors``."""
    mesh = torus(size, size)
    if COLORED[0]:
        from livemod.dlfl.colors import set_face_colors

        set_face_colors(mesh, [int(f) for f in mesh.face_ids()[::2]], (0.2, 0.5, 0.9))
    return mesh_arrays(mesh)


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
    arrays = _preview_torus(size)
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


def _quick_pictures() -> bool:
    """This tree's window draws quick pictures while the view moves."""
    import livemod.viewer.renderer as renderer

    return hasattr(renderer, "QUICK_PRIMITIVES")


def bench_preview_frames(size: int, frames: int, samples: int, quick: bool = False) -> None:
    """Frame time at 1280x800 while the preview of the mesh is on screen and the view
    turns (every frame drawn whole, or ``quick`` as the window draws it while the
    view moves; an unchanging view is a kept frame, copied)."""
    if quick and not _quick_pictures():
        return
    arrays = _preview_torus(size)
    offscreen = Offscreen(PREVIEW_SIZE, samples=samples)
    made = _make_preview(arrays)
    offscreen.renderer.set_mesh(arrays, made)
    camera = framed_camera(arrays, elevation=25.0, aspect=1.6)
    style = Style(preview=True)
    offscreen.renderer.draw(offscreen.target, camera, style)
    walls, cpus = [], []
    drawn = {"quick": True} if quick else {}
    for _ in range(frames):
        camera.yaw += 2.0
        start, cpu = time.perf_counter(), time.process_time()
        offscreen.renderer.draw(offscreen.target, camera, style, **drawn)
        offscreen.ctx.finish()
        walls.append(time.perf_counter() - start)
        cpus.append(time.process_time() - cpu)
    offscreen.release()
    triangles = len(getattr(made, "surface", None).triangles) if _has_patches() \
        else 2 * made.counts[2]
    how = "quick pictures" if quick else "every picture whole"
    print(f"preview frames, {size * size:,} faces ({triangles:,} triangles), MSAA {samples}, "
          f"turning, {how}: wall {_median(walls)}; CPU {_median(cpus)}")


def bench_window_preview_frames(rings: int, samples: int) -> None:
    """Frame times of the live window (headless, 1280x800) with the preview of a
    torus of ``rings`` x ``rings`` faces on screen: idle (the picture unchanged:
    the kept frame) and while the view turns (drawn every frame: as the window
    draws it, quick pictures while the view moves, and every picture whole),
    paced at 60 Hz."""
    import livemod.viewer.renderer as renderer
    from livemod.viewer.window import ViewOptions, close_viewer, create_viewer, run_frames

    with tempfile.TemporaryDirectory() as folder:
        script = Path(folder) / "torus.py"
        script.write_text(SWAP_SCRIPT.format(rings=rings, major=2.0).replace(
            ", 1000,", f", {rings},"))
        viewer = create_viewer(ViewOptions(str(script), backend="headless", size=PREVIEW_SIZE,
                                           samples=samples, vsync=False,
                                           echo=open(os.devnull, "w")))  # noqa: SIM115
        try:
            _frames_until(viewer, lambda: viewer.renderer.arrays is not None, run_frames)
            viewer.handle_key("P")
            _frames_until(viewer, lambda: viewer.renderer.preview is not None
                          and not getattr(viewer.renderer, "uploading", False), run_frames)
            run_frames(viewer, 3)
            figures = {"idle": _paced_frames(viewer, run_frames, 60, lambda: None)}
            if _quick_pictures():
                figures["turning, quick pictures"] = _paced_frames(
                    viewer, run_frames, 15, lambda: viewer.camera.orbit(2.0, 0.0))
                renderer.QUICK_PRIMITIVES = float("inf")  # type: ignore[attr-defined]
            figures["turning, every picture whole"] = _paced_frames(
                viewer, run_frames, 15, lambda: viewer.camera.orbit(2.0, 0.0))
        finally:
            close_viewer(viewer)
    for name, (walls, cpus) in figures.items():
        print(f"window frames, {rings * rings:,}-face preview on screen, MSAA {samples}, "
              f"{name}: median {statistics.median(walls) * 1000:.1f} ms "
              f"(CPU {statistics.median(cpus) * 1000:.1f} ms), "
              f"max {max(walls) * 1000:.1f} ms ({len(walls)} frames)")


def _paced_frames(viewer, run_frames, count: int,  # noqa: ANN001
                  before) -> tuple[list[float], list[float]]:  # noqa: ANN001
    """Wall and CPU times of ``count`` frames run at most 60 a second, ``before()``
    each."""
    walls, cpus = [], []
    for _ in range(count):
        before()
        start, cpu = time.perf_counter(), time.process_time()
        run_frames(viewer, 1)
        walls.append(time.perf_counter() - start)
        cpus.append(time.process_time() - cpu)
        time.sleep(max(1 / 60 - walls[-1], 0.0))
    return walls, cpus


# GPU evaluation of the patches: tessellation shaders (GL 4.0+; Mesa's llvmpipe
# has them in its GL 4.5 core context), 16 control points and normals a patch
_TESS = {
    "vertex_shader": """#version 450
in vec3 in_position; in vec3 in_normal; out vec3 c_pos; out vec3 c_nrm;
void main() { c_pos = in_position; c_nrm = in_normal; }""",
    "tess_control_shader": """#version 450
layout(vertices = 16) out;
in vec3 c_pos[]; in vec3 c_nrm[]; out vec3 e_pos[]; out vec3 e_nrm[];
uniform float level;
void main() {
    e_pos[gl_InvocationID] = c_pos[gl_InvocationID];
    e_nrm[gl_InvocationID] = c_nrm[gl_InvocationID];
    if (gl_InvocationID == 0) {
        for (int k = 0; k < 4; ++k) gl_TessLevelOuter[k] = level;
        gl_TessLevelInner[0] = level; gl_TessLevelInner[1] = level;
    }
}""",
    "tess_evaluation_shader": """#version 450
layout(quads, equal_spacing, ccw) in;
in vec3 e_pos[]; in vec3 e_nrm[]; out vec3 v_normal; uniform mat4 mvp;
vec4 bernstein(float t) { float s = 1.0 - t; return vec4(s*s*s, 3.0*t*s*s, 3.0*t*t*s, t*t*t); }
void main() {
    vec4 bu = bernstein(gl_TessCoord.x), bv = bernstein(gl_TessCoord.y);
    vec3 p = vec3(0.0), n = vec3(0.0);
    for (int i = 0; i < 4; ++i) for (int j = 0; j < 4; ++j) {
        float w = bu[i] * bv[j]; p += w * e_pos[4 * i + j]; n += w * e_nrm[4 * i + j];
    }
    v_normal = n; gl_Position = mvp * vec4(p, 1.0);
}""",
    "fragment_shader": """#version 450
in vec3 v_normal; out vec4 color;
void main() {
    float lit = 0.2 + 0.8 * max(dot(normalize(v_normal), normalize(vec3(-0.45, 0.55, 0.7))), 0.0);
    color = vec4(lit * vec3(0.62, 0.78, 0.95), 1.0);
}""",
}
_NUMPY_VERTEX = """#version 450
in vec3 in_position; in vec3 in_normal; out vec3 v_normal; uniform mat4 mvp;
void main() { v_normal = in_normal; gl_Position = mvp * vec4(in_position, 1.0); }"""


def bench_gpu_tessellation(size: int, density: int, frames: int) -> None:
    """The patches evaluated by numpy (once, then drawn as triangles) against the GPU's
    tessellation shaders (evaluated in every frame), on llvmpipe at 1280x800: the
    first frame from the arrays, then frames of a turning view."""
    import moderngl

    from livemod.dlfl.patches import CornerPatches

    arrays = mesh_arrays(torus(size, size))
    ctx = moderngl.create_standalone_context(backend="egl", require=450)
    fbo = ctx.framebuffer([ctx.renderbuffer(PREVIEW_SIZE, 4)],
                          ctx.depth_renderbuffer(PREVIEW_SIZE))
    camera = framed_camera(arrays, elevation=25.0, aspect=1.6)

    def frame(program, vao, mode) -> None:  # noqa: ANN001
        camera.yaw += 2.0
        program["mvp"].write(camera.view_projection(1.6).T.astype("f4").tobytes())
        fbo.use()
        fbo.clear()
        ctx.enable(moderngl.DEPTH_TEST)
        vao.render(mode)
        ctx.finish()

    def by_numpy():  # noqa: ANN202
        tessellation = CornerPatches(arrays).tessellate(density)
        program = ctx.program(vertex_shader=_NUMPY_VERTEX,
                              fragment_shader=_TESS["fragment_shader"])
        rows = np.hstack([tessellation.positions, tessellation.normals])
        vao = ctx.vertex_array(program, [(ctx.buffer(rows.tobytes()), "3f 3f", "in_position",
                                          "in_normal")], ctx.buffer(tessellation.triangles))
        frame(program, vao, moderngl.TRIANGLES)
        return program, vao, moderngl.TRIANGLES

    def by_gpu():  # noqa: ANN202
        net = CornerPatches(arrays).nets()
        rows = np.hstack([net.columns.transpose(2, 0, 1).reshape(-1, 3),
                          net.normal_columns.transpose(2, 0, 1).reshape(-1, 3)]).astype("f4")
        program = ctx.program(**_TESS)
        program["level"].value = float(density)
        vao = ctx.vertex_array(program, [(ctx.buffer(rows.tobytes()), "3f 3f", "in_position",
                                          "in_normal")])
        ctx.patch_vertices = 16
        frame(program, vao, moderngl.PATCHES)
        return program, vao, moderngl.PATCHES

    for name, make in (("numpy", by_numpy), ("GPU tessellation", by_gpu)):
        start, cpu = time.perf_counter(), time.process_time()
        program, vao, mode = make()
        first = (time.perf_counter() - start, time.process_time() - cpu)
        walls, cpus = [], []
        for _ in range(frames):
            start, cpu = time.perf_counter(), time.process_time()
            frame(program, vao, mode)
            walls.append(time.perf_counter() - start)
            cpus.append(time.process_time() - cpu)
        print(f"patches of {size * size:,} faces at density {density} by {name}: first frame "
              f"wall {first[0]:.3f} s (CPU {first[1]:.3f} s); frames {_median(walls)}; "
              f"CPU {_median(cpus)}")
    ctx.release()


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
            arrived, cpu = time.perf_counter(), time.process_time()
            while not _shown_whole(viewer, first):
                start = time.perf_counter()
                run_frames(viewer, 1)
                times.append(time.perf_counter() - start)
                # paced at 60 Hz, as vsync would (a loop that never waits starves the
                # threads that prepare the result of the interpreter)
                time.sleep(max(1 / 60 - times[-1], 0.0))
            total, cpu = time.perf_counter() - arrived, time.process_time() - cpu
        finally:
            close_viewer(viewer)
    faces = rings * 1000
    print(f"swap to a {faces:,}-face result, labels {'on' if labels else 'off'}, MSAA "
          f"{samples}: first whole frame {total:.3f} s after it arrived (CPU of the process, "
          f"all threads: {cpu:.3f} s), {len(times)} frames, longest {max(times) * 1000:.0f} ms, "
          f"median {statistics.median(times) * 1000:.0f} ms")


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
    parser.add_argument("--colors", action="store_true",
                        help="with --preview: the preview's figures of coloured tori only")
    args = parser.parse_args(argv)
    print("load average before: {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))
    if args.preview and args.colors:
        COLORED[0] = True
        bench_preview_first_frame(100, 3, 0)
        bench_preview_first_frame(316, 3, 0)
        bench_preview_frames(316, 9, 0)
        bench_preview_frames(316, 9, 0, quick=True)
    elif args.preview:
        bench_preview_first_frame(100, 3, 0)
        bench_preview_first_frame(316, 3, 0)
        for samples in (0, 4):
            bench_preview_frames(316, 9, samples)
            bench_preview_frames(316, 9, samples, quick=True)
        bench_window_preview_frames(316, 4)
        bench_gpu_tessellation(100, 3, 5)
        bench_gpu_tessellation(316, 1, 3)
        bench_swap(1000, 4)
    elif args.quick:
        bench_upload(1, 100)
        bench_turntable(1, 60, 4, 0)
        bench_frames_during_run(1.0)
        bench_frames_during_run(1.0, rate=60.0)
    else:
        bench_upload(5, 1000)
        bench_turntable(3, 316, 36, 0)   # the default of ``livemod render --turntable``
        bench_turntable(3, 316, 36, 4)
        bench_frames_during_run(4.0)
        bench_frames_during_run(2.5, rate=60.0)
    print("load average after: {:.2f} {:.2f} {:.2f}".format(*os.getloadavg()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
