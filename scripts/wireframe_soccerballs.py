"""Thirty wireframe soccer balls of increasing thickness on a grid (thesis figure 31).

Each ball is its own object in the scene, placed on a 6 by 5 grid; with `out`
set, each is saved as it is made. The last one stays current.
"""

from livemod.dlfl import *

count = param("count", 30, min=1, max=60, doc="number of balls")
out = param("out", "", doc="folder to save every ball into (empty: do not save)")

for i in range(count):
    load("soccerball")
    wireframe(0.01 + 0.005 * i)
    translate(3.0 * (i % 6), 0.0, 3.0 * (i // 6))
    if out:
        save(f"{out}/soccerball_{i:02d}.obj")
    step(f"ball {i}")
