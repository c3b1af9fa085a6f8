"""A Hermite handle between two faces of a cube: one operation adds a genus.

The handle leaves the top face and lands on the front face, bending along a
Hermite curve whose tangents follow the two face normals.
"""

from livemod.dlfl import *

segments = param("segments", 10, min=1, max=40, doc="rings along the handle")
weight = param("weight", 5.0, min=0.5, max=30.0, doc="tangent weight at both ends")
twists = param("twists", 0, min=0, max=3, doc="full turns along the handle")

load("cube")
top, front = faces()[0], faces()[1]
addHandle("hermite", cornerWalk(top)[0], cornerWalk(front)[0], segments, weight, weight,
          -1, twists)
step("handle")
subdivide("catmull-clark")
