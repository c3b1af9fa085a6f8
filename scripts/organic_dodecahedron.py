"""A dodecahedron extruded face by face into an organic shape (thesis figure 29).

Every face of the dodecahedron is pushed out twice with Doo-Sabin extrusions whose
length and twist depend on the face's position, then the whole shape is smoothed
with Catmull-Clark.
"""

from math import cos, sin

from livemod.dlfl import *

length = param("length", 0.6, min=0.1, max=2.0, doc="first extrusion length")
twist = param("twist", 0.2, min=-1.0, max=1.0, doc="Doo-Sabin twist, a fraction of an edge")

load("dodecahedron")
for face in faces():
    x, y, z = faceInfo(face)["centroid"]
    wobble = 0.5 + 0.5 * sin(3 * x + 2 * y) * cos(2 * z)
    end = extrude("doo-sabin", face, length * (0.5 + wobble), 1, twist * wobble, 0.7)
    extrude("doo-sabin", end, 0.5 * length, 1, -twist, 0.6)
    step(f"face {face}")
subdivide("catmull-clark")
