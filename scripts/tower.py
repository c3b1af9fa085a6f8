"""A twisted tower of extrusions whose width follows a sine (thesis figure 26).

Each extrusion works on the end face the previous one returned, turning it a few
degrees and scaling it by 1 + 0.12 sin(t), so the tower swells and narrows as it
rises. Two duals and a Doo-Sabin subdivision then round it off, as in the thesis.

    livemod run scripts/tower.py -o tower.obj
    livemod view scripts/tower.py
    livemod render scripts/tower.py -o tower.gif --turntable 36
"""

from math import pi, sin

from livemod.dlfl import *

storeys = param("storeys", 36, min=1, max=200, doc="number of extrusions")
height = param("height", 0.35, min=0.05, max=2.0, doc="height of each storey")
twist = param("twist", 5.0, min=-45.0, max=45.0, doc="turn of each storey, degrees")
swell = param("swell", 0.12, min=0.0, max=0.5, doc="amplitude of the sine on the scale")

load("cube")
face = faces()[0]
for i in range(storeys):
    t = 2 * pi * i / storeys
    face = extrude("cubical", face, height, 1, twist, 1.0 + swell * sin(t))
    step(f"storey {i}")
dual()
dual()
subdivide("doo-sabin")
