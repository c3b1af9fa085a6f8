"""Start from your own mesh: `livemod run user_mesh.py --mesh model.obj`.

With --mesh the script works on that mesh; without it, it loads the `mesh`
parameter (a file or a built-in shape name) and gives every face a short
Doo-Sabin extrusion before smoothing.
"""

from livemod.dlfl import *

mesh = param("mesh", "donuthexa1", doc="a .obj/.dlfl file or a built-in shape name")
height = param("height", 0.2, min=0.0, max=1.0, doc="extrusion length")

if not faces():
    load(mesh)
for face in faces():
    extrude("doo-sabin", face, height, 1, 0, 0.7)
step("faces extruded")
subdivide("catmull-clark")
