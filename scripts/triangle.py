"""A triangle from nothing but createVertex and insertEdge (thesis figure 24).

Three point-spheres, then three edges: the first joins two point-spheres into a
two-sided sliver, the second brings in the third vertex, the third closes the
triangle and splits the face into its front and back. insertEdge returns the new
edge and its four corners, because the faces the corners belong to change.

Result: 3 vertices, 3 edges, 2 faces (front and back), genus 0.
"""

from livemod.dlfl import *

a, obj = createVertex((0.0, 0.0, 0.0))
b, _ = createVertex((2.0, 0.0, 0.0))
c, _ = createVertex((1.0, 1.7, 0.0))

edge, a, b, after_a, after_b = insertEdge(a, b)  # one face now visits a and b
step("a-b")
edge, c, b, after_c, after_b = insertEdge(c, b)  # c joins that face
step("c-b")
face = c[0]
insertEdge((face, c[1]), (face, a[1]))  # split it: front and back triangles
step("c-a")
printObject()
