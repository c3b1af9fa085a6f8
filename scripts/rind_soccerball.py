"""Rind modeling (thesis figure 30).

A soccer ball is remeshed with the dual checkerboard scheme, then made into a
crust of the given thickness with every four-sided face that touches a
three-valent vertex punched out: a printable lattice shell.
"""

from livemod.dlfl import *

thickness = param("thickness", 0.05, min=0.005, max=0.3, doc="crust thickness")

load("soccerball")
subdivide("dual-checkerboard")
punched = [
    f for f in faces()
    if faceInfo(f)["size"] == 4 and any(vertexInfo(v)["valence"] == 3 for v in walk(f)[0])
]
step(f"{len(punched)} faces to punch")
rind(punched, False, thickness)
