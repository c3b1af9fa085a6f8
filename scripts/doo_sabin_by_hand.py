"""Doo-Sabin subdivision written with the core commands only (thesis figure 25).

Every face becomes a two-sided polygon of Doo-Sabin points (createFace). The old
mesh is deleted edge by edge. Then the back sides of the polygons of two faces
that shared an old edge are stitched with two insertEdge calls (TopMod's
connectEdges); what is left of the back sides becomes the vertex faces. As in the
thesis, the cube first gets an extra edge laid over an existing one (a 2-gon),
which leaves a slit in the result. tests/test_scripts.py checks that this gives
the same counts and positions as the built-in subdivide("doo-sabin").
"""

from math import cos, pi

from livemod.dlfl import *


def doo_sabin_points(points):
    """The Doo-Sabin polygon of a face from its corner positions (TOPMOD.md §3)."""
    n = len(points)
    polygon = []
    for i in range(n):
        point = [0.0, 0.0, 0.0]
        for j, p in enumerate(points):
            if i == j:
                weight = 0.25 + 5.0 / (4 * n)
            else:
                weight = (3 + 2 * cos(2 * pi * (i - j) / n)) / (4 * n)
            for k in range(3):
                point[k] += weight * p[k]
        polygon.append(tuple(point))
    return polygon


def back_side(edge, front):
    """The corner of a polygon edge that lies on the polygon's back, not its front."""
    info = edgeInfo(edge)
    return info["cornerA"] if info["cornerA"][0] != front else info["cornerB"]


def adjacent(c1, c2):
    return c1[0] == c2[0] and (next(c1) == c2 or next(c2) == c1)


def connect(c1, c2):
    """insertEdge unless the corners are already neighbours (TopMod's loop check)."""
    if not adjacent(c1, c2):
        insertEdge(c1, c2)


def subdivide_by_hand():
    polygon_edge, front_of = {}, {}
    for f in faces():
        ring = cornerWalk(f)
        points = [vertexInfo(v)["coords"] for _, v in ring]
        front, _back = createFace(doo_sabin_points(points))
        _, new_edges = walk(front)
        for corner, new_edge in zip(ring, new_edges, strict=True):
            polygon_edge[corner] = new_edge
            front_of[corner] = front
    old_edges = [e for e in edges() if e not in polygon_edge.values()]
    sides = [(edgeInfo(e)["cornerA"], edgeInfo(e)["cornerB"]) for e in old_edges]
    for e in old_edges:
        deleteEdge(e)  # with cleanup: the old vertices go with their last edge
    step("old mesh deleted")
    for a, b in sides:
        ea, eb = polygon_edge[a], polygon_edge[b]
        connect(back_side(ea, front_of[a]), next(back_side(eb, front_of[b])))
        connect(next(back_side(ea, front_of[a])), back_side(eb, front_of[b]))
        step("edge stitched")


load("cube")
first = edgeInfo(edges()[0])
insertEdge(first["cornerA"], first["cornerC"])  # a second edge over the first: a 2-gon
step("extra edge")
subdivide_by_hand()
