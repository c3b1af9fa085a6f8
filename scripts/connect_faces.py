"""Connecting two faces of a cube through its inside: a torus (genus 1) from a cube.

connectFaces joins the top and the bottom face with a tube of `segments` rings.
"""

from livemod.dlfl import *

segments = param("segments", 3, min=1, max=20, doc="rings of the tube")

load("cube")
top, bottom = faces()[0], faces()[5]
connectFaces(top, bottom, segments)
step("tube")
subdivide("doo-sabin")
