"""A cube with a hole through it: inset the top and the bottom, then connect them.

Two planar-offset extrusions (insets) leave a smaller face in the middle of the
top and of the bottom; connectFaces joins them with a tube of `segments` rings
through the inside, which adds a handle (genus 1). Doo-Sabin rounds it off.
"""

from livemod.dlfl import *

segments = param("segments", 3, min=1, max=20, doc="rings of the tube")
inset = param("inset", 0.25, min=0.05, max=0.45, doc="inset of the two faces")

load("cube")
top = extrude("planar-offset", faces()[0], 0.0, 0.0, inset)
bottom = extrude("planar-offset", faces()[5], 0.0, 0.0, inset)
step("insets")
connectFaces(top, bottom, segments)
step("tube")
subdivide("doo-sabin")
