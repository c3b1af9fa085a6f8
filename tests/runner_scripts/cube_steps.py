"""A cube built with the library, then edited step by step with core commands."""
# ruff: noqa: F821  (the runner injects the thesis commands)
import random

from livemod.dlfl import current_scene, from_polygons

CUBE_POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
CUBE_FACES = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]

current_scene().add(from_polygons(CUBE_POINTS, CUBE_FACES))
step("cube")
for _ in range(6):
    edge = random.choice(edges())
    subdivideEdge(edge)
    move(verts()[-1:], (0.0, 0.0, random.random()))
step("done")
