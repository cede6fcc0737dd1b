#!/usr/bin/python3
"""Writes the Gmsh meshes (format 2.2, ASCII) of the interference fit: a
ring (inner radius B = 1, outer radius C = 2) shrunk onto a solid shaft
(radius B), the quarter model x >= 0, y >= 0, two separate bodies whose
nodes on the interface r = B do not match.

shaft_and_ring(n, ring=3, simplex=False, radii=(B, C)): the shaft is the unit square
mapped onto the quarter disk by transfinite (Coons) interpolation of its
sides (x = 0, y = 0, and the arc in two halves meeting at 45 degrees),
n x n cells, 2 n segments on its arc; the ring is a polar grid of
(ring * n) x n cells (ring * n segments on its inner arc, uniform in the
angle and the radius). All nodes of the arcs lie on the circles. With
simplex = True every quadrilateral is cut by its diagonal from its first
to its third node. Material ids: 1 the shaft, 2 the ring. Physical groups
of the boundary lines (the boundary ids of the parameter file):
  1  x = 0 (both bodies)
  2  y = 0 (both bodies)
  3  the shaft's arc r = B
  4  the ring's inner arc r = B (the contact zone)
  5  the ring's outer arc r = C
With more radii (radii = (1, 1.5, 2): a shaft and two rings, the
assembly of benchmarks/run_interference_fit.py), ring k = 1, 2, ... has
material id k + 1, its inner arc tag 2 k + 2 and its outer arc tag
2 k + 3, and its arcs have 3n (k odd) or 2n (k even) segments, so that no
two arcs that meet have the same nodes.

interference_fit_N.msh: n = N, ring = 3 (arcs of 2N and 3N segments),
quadrilaterals; parameters/interference_fit.prm,
benchmarks/run_interference_fit.py.

Run from anywhere: python3 meshes/make_interference_meshes.py
"""
import math
import os

from gmsh_format import gmsh_elements_text

B, C = 1.0, 2.0


def arc(radius, theta):
    return (radius * math.cos(theta), radius * math.sin(theta))


def shaft_point(xi, eta):
    """The Coons patch of the quarter disk at (xi, eta) in [0, 1]^2: xi
    along y = 0 and the upper half of the arc, eta along x = 0 and the
    lower half."""
    bottom = (xi * B, 0.0)
    left = (0.0, eta * B)
    right = arc(B, eta * math.pi / 4)                 # (B, 0) .. 45 degrees
    top = arc(B, math.pi / 2 - xi * math.pi / 4)      # (0, B) .. 45 degrees
    p00, p10, p01, p11 = (0.0, 0.0), (B, 0.0), (0.0, B), arc(B, math.pi / 4)
    return tuple((1 - eta) * bottom[c] + eta * top[c] + (1 - xi) * left[c]
                 + xi * right[c]
                 - ((1 - xi) * (1 - eta) * p00[c] + xi * (1 - eta) * p10[c]
                    + (1 - xi) * eta * p01[c] + xi * eta * p11[c])
                 for c in range(2))


def shaft_and_ring(n, ring=3, simplex=False, radii=(B, C)):
    """The shaft of radius radii[0] and the rings between the further radii
    (see the top of the file; with more than one ring, ring k (from 1)
    has material id k + 1, its inner arc tag 2 k + 2 and its outer arc tag
    2 k + 3)."""
    nodes, boundary, cells = [], [], []

    def add_block(points, columns, rows, material, sides):
        """points[j][i], (columns + 1) x (rows + 1); sides: tag of the
        lines i = 0, i = columns, j = 0, j = rows (None: no line)."""
        first = len(nodes) + 1
        number = lambda i, j: first + j * (columns + 1) + i
        for j in range(rows + 1):
            for i in range(columns + 1):
                nodes.append((number(i, j),) + points[j][i] + (0.0,))
        for k in range(rows):
            for i, tag in ((0, sides[0]), (columns, sides[1])):
                if tag:
                    boundary.append((1, tag, number(i, k), number(i, k + 1)))
        for k in range(columns):
            for j, tag in ((0, sides[2]), (rows, sides[3])):
                if tag:
                    boundary.append((1, tag, number(k, j), number(k + 1, j)))
        for j in range(rows):
            for i in range(columns):
                a, b, c, d = number(i, j), number(i + 1, j), number(i + 1, j + 1), number(i, j + 1)
                cells.extend([(2, material, a, b, c), (2, material, a, c, d)] if simplex
                             else [(3, material, a, b, c, d)])

    # The shaft: i along xi (x = 0 -> arc), j along eta (y = 0 -> arc).
    scale = radii[0] / B
    shaft = [[tuple(scale * c for c in shaft_point(i / n, j / n)) for i in range(n + 1)]
             for j in range(n + 1)]
    add_block(shaft, n, n, 1, (1, 3, 2, 3))
    # Each ring: i along the radius, j along the angle (0 -> 90); a ring's
    # arcs have ring * n and, on the next ring, 2 n segments, so that
    # neighbouring arcs never match.
    names = [(1, "x_0"), (2, "y_0"), (3, "shaft_arc")]
    for k, (inner, outer) in enumerate(zip(radii[:-1], radii[1:]), 1):
        m = (ring if k % 2 == 1 else 2) * n
        ring_points = [[arc(inner + (outer - inner) * i / n, math.pi / 2 * j / m)
                        for i in range(n + 1)] for j in range(m + 1)]
        add_block(ring_points, n, m, k + 1, (2 * k + 2, 2 * k + 3, 2, 1))
        names += [(2 * k + 2, "ring_%d_inner" % k), (2 * k + 3, "ring_%d_outer" % k)]
    materials = [(1, "shaft")] + [(k + 1, "ring_%d" % k) for k in range(1, len(radii) - 1)]
    return gmsh_elements_text(nodes, boundary, cells, names, materials)


if __name__ == "__main__":
    folder = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(folder, "interference_fit_8.msh"), "w") as f:
        f.write(shaft_and_ring(8))
