# ruff: noqa: F821  (the runner injects the thesis commands and the parameters)
"""A polygon of ``count`` corners and radius ``radius`` (batch-test parameters)."""
import math

points = [(radius * math.cos(2 * math.pi * i / count), radius * math.sin(2 * math.pi * i / count), 0.0)
          for i in range(count)]
createFace(points)
