"""A script made to be stepped through: press the arrow keys in `livemod view`.

Every modeling command is a step; step("...") adds a labelled checkpoint of its
own. `livemod run steps_demo.py --steps` prints the same list headless.
"""

from livemod.dlfl import *

load("cube")
step("the cube")
face = faces()[0]
for i in range(4):
    face = extrude("cubical", face, 0.8, 1, 15, 0.85)
    step(f"storey {i + 1}")
subdivide("catmull-clark")
step("smoothed")
