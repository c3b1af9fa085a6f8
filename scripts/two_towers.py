"""Two towers driven by the sine of the time, then a solid wireframe (thesis figures 27-28).

The cube's top face is split in two (two edge subdivisions and an inserted
edge); each half grows a tower whose storeys swell and turn with sin(time + ...).
The thesis read the clock (time.time()) so that every run grew different towers.
Here the time is a parameter: `livemod run two_towers.py --set time=3.2` gives a
repeatable result, and dragging its slider in the window animates it.
"""

from math import sin

from livemod.dlfl import *

time = param("time", 0.0, min=0.0, max=60.0, doc="seconds; the thesis used time.time()")
levels = param("levels", 12, min=1, max=40, doc="storeys per tower")
thickness = param("thickness", 0.06, min=0.01, max=0.3, doc="wireframe rod thickness")

load("cube")
top = faces()[0]
_, edge_ids = walk(top)
a = subdivideEdge(edge_ids[0])[0]  # midpoints of two opposite sides of the top
b = subdivideEdge(edge_ids[2])[0]
edge, left, right, _, _ = insertEdge((top, a), (top, b))
towers = [left[0], right[0]]
for i in range(levels):
    for k, face in enumerate(towers):
        phase = time + 0.5 * i + 2.0 * k
        towers[k] = extrude("cubical", face, 0.5, 1, 12 * sin(phase), 1.0 + 0.08 * sin(phase))
    step(f"storey {i}")
wireframe(thickness)
