# ruff: noqa: F821  (the runner injects the thesis commands)
from livemod.dlfl import current_run, current_scene, from_polygons

points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
quads = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
current_scene().add(from_polygons(points, quads))
current_run().parameters["all"] = faces()
current_run().parameters["picked"] = faces(True)
