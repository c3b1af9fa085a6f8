# ruff: noqa: F821  (the runner injects the thesis commands)
"""A polygon of ``count`` corners and radius ``radius`` (batch-test parameters)."""
import math

count = param("count", 4, min=1, max=64, doc="corners of the polygon")
radius = param("radius", 1.0, min=0.1, max=10.0, doc="distance of the corners from the centre")
points = [(radius * math.cos(2 * math.pi * i / count), radius * math.sin(2 * math.pi * i / count), 0.0)
          for i in range(count)]
createFace(points)
