"""A tower of Doo-Sabin extrusions whose size follows a sine (thesis figure 26).

Each extrusion works on the end face the previous one returned; the distance
and scale swing with sin(t), so the tower bulges and narrows as it rises. Two
duals and a Doo-Sabin subdivision then round it off.

    livemod run scripts/tower.py -o tower.obj
    livemod view scripts/tower.py
"""

from math import pi, sin

from livemod.dlfl import *

load("cube")
face = faces()[0]
for i in range(36):
    t = 2 * pi * i / 36
    face = extrude("doo-sabin", face, 0.5 + 0.3 * sin(t), 1, 0, 0.9 + 0.1 * sin(t))
    step(f"extrusion {i}")
dual()
dual()
subdivide("doo-sabin")
