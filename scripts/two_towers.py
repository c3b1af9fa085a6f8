"""Two towers driven by the sine of the time, then a solid wireframe (thesis figures 27-28).

The thesis read the clock (time.time()) so that every run grew a different pair
of towers. Here the time is a parameter: `livemod run two_towers.py --set time=3.2`
gives a repeatable result, and dragging its slider in the window animates it.
"""

from math import sin

from livemod.dlfl import *

time = param("time", 0.0, min=0.0, max=60.0, doc="seconds; the thesis used time.time()")
levels = param("levels", 12, min=1, max=40, doc="extrusions per tower")
thickness = param("thickness", 0.08, min=0.01, max=0.3, doc="wireframe rod thickness")

load("cube")
top, bottom = faces()[0], faces()[5]
for i in range(levels):
    phase = time + 0.4 * i
    top = extrude("cubical", top, 0.6 + 0.3 * sin(phase), 1, 8 * sin(phase), 0.92)
    bottom = extrude("cubical", bottom, 0.6 + 0.3 * sin(phase + 1.5), 1,
                     -8 * sin(phase), 0.92)
    step(f"level {i}")
wireframe(thickness)
