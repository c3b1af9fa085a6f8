"""A notebook's picture of a 100,000-face mesh (issue 28's figure: at most 1 s after
the first).

    python bench/bench_notebook.py [--repeats N]

Times ``mesh._repr_png_()``, what IPython calls to show a Mesh: the first call (it
imports the viewer, makes the EGL context and compiles the shaders) and the median of
the later ones, in wall and CPU time (the CPU time of the whole process, Mesa's
llvmpipe render threads included). Then the parts of a later call: the arrays bridge,
the render (upload, draw with 4x MSAA, read back) and the PNG encoding. Prints the
load average before and after, since the development machines are shared.
"""

from __future__ import annotations

import argparse
import os
import time

from timing import median_times

from livemod.dlfl import mesh_arrays
from livemod.dlfl.shapes import torus


def _seconds(wall: float, cpu: float) -> str:
    return f"{wall:.3f} s wall, {cpu:.3f} s CPU"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=9)
    args = parser.parse_args()
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    mesh = torus(400, 250)  # 100,000 quads
    print(f"{mesh}")
    wall, cpu = time.perf_counter(), time.process_time()
    first = mesh._repr_png_()
    print(f"first _repr_png_: {_seconds(time.perf_counter() - wall, time.process_time() - cpu)}"
          f" ({len(first or b'')} bytes)")
    print(f"later _repr_png_, median of {args.repeats}: "
          f"{_seconds(*median_times(mesh._repr_png_, args.repeats))}")

    from livemod.viewer.pictures import picture, png_bytes

    arrays = mesh_arrays(mesh)
    shown = picture(arrays)
    print(f"  mesh_arrays: {_seconds(*median_times(lambda: mesh_arrays(mesh), args.repeats))}")
    print(f"  render (upload, draw, read back): "
          f"{_seconds(*median_times(lambda: picture(arrays), args.repeats))}")
    print(f"  PNG encoding: "
          f"{_seconds(*median_times(lambda: png_bytes([shown.image]), args.repeats))}")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
