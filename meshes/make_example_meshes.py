#!/usr/bin/python3
"""Writes the example Gmsh meshes of this folder (format 2.2, ASCII).

rotated_square_N.msh: the unit square of the reference benchmark, cut into
N x N quadrilaterals and rotated by 30 degrees counterclockwise about the
origin, so that no boundary part is axis-aligned. Physical groups of the
boundary lines (the boundary ids of the parameter file):
  1  the side that was x = 0   (clamped, Gamma_1)
  2  the side that was x = 1   (traction-free)
  3  the side that was y = 0   (contact, Gamma_3)
  4  the side that was y = 1   (loaded)
Rotated with its loads, the scene is the benchmark itself: the contact
forces and contact states must be those of the axis-aligned run (the
tests compare them).

two_layer_column_N.msh: the unit square cut into N x N quadrilaterals, two
materials: physical group 10 "stiff" below y = 1/2, 20 "soft" above (the
material ids of the parameter file). Boundary lines: 1 x = 0, 2 x = 1,
3 y = 0 (the support), 4 y = 1 (the top); parameters/two_layer_column.prm.

Run from anywhere: python3 meshes/make_example_meshes.py
"""
import math
import os

from gmsh_format import gmsh_text

ANGLE = math.radians(30.0)


def square_sides(n, index):
    """The boundary lines of an n x n grid of nodes index(i, j): tag 1 on
    i = 0, 2 on i = n, 3 on j = 0, 4 on j = n."""
    lines = []
    for k in range(n):
        lines.append((1, index(0, k), index(0, k + 1)))
        lines.append((2, index(n, k), index(n, k + 1)))
        lines.append((3, index(k, 0), index(k + 1, 0)))
        lines.append((4, index(k, n), index(k + 1, n)))
    return lines


def rotated_square(n):
    c, s = math.cos(ANGLE), math.sin(ANGLE)
    index = lambda i, j: j * (n + 1) + i + 1
    nodes = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i / n, j / n
            nodes.append((index(i, j), c * x - s * y, s * x + c * y))
    lines = square_sides(n, index)
    quads = [(index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1))
             for j in range(n) for i in range(n)]
    return gmsh_text(nodes, lines, quads, [(1, "clamped"), (2, "free"), (3, "contact"), (4, "loaded")])


def two_layer_column(n):
    index = lambda i, j: j * (n + 1) + i + 1
    nodes = [(index(i, j), i / n, j / n) for j in range(n + 1) for i in range(n + 1)]
    lines = square_sides(n, index)
    quads, tags = [], []
    for j in range(n):
        for i in range(n):
            quads.append((index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)))
            tags.append(10 if 2 * j < n else 20)
    return gmsh_text(nodes, lines, quads, [(1, "left"), (2, "right"), (3, "support"), (4, "top")],
                     tags, [(10, "stiff"), (20, "soft")])


if __name__ == "__main__":
    folder = os.path.dirname(os.path.abspath(__file__))
    for n in (8, 16):
        with open(os.path.join(folder, "rotated_square_%d.msh" % n), "w") as f:
            f.write(rotated_square(n))
    with open(os.path.join(folder, "two_layer_column_4.msh"), "w") as f:
        f.write(two_layer_column(4))
