#!/usr/bin/python3
"""Writes the Gmsh meshes (format 2.2, ASCII) of the 2D Hertz benchmark:
the right half (x >= 0) of the lower half of a cylinder of radius R = 1
whose lowest point touches the plane y = 0, i.e. the quarter disk
x >= 0, y <= 1, x^2 + (y - 1)^2 <= 1 (the half model of a half cylinder
pressed onto a rigid plane by its flat top, with the symmetry line x = 0).

hertz_cylinder_N.msh: N x N quadrilaterals, the unit square mapped onto the
quarter disk by transfinite (Coons) interpolation of its sides: the left
side x = 0, the top y = 1, and the arc in two halves (from the contact point
(0, 0) to the point at 45 degrees, and on to (1, 1)). The square's
coordinates are graded as (i/N)^2 toward the contact point, so that about a
third of the arc's nodes lie within a contact half-width of 0.1. All arc
nodes lie on the circle. Physical groups (the boundary ids of the parameter
file):
  1  the symmetry line x = 0
  2  the top y = 1 (its displacement is prescribed)
  3  the arc (contact with the plane y = 0)

quarter_disk(n, fitted=a) (not shipped; benchmarks/run_hertz_cylinder.py
--fitted A): the same patch with a grading fitted to a contact half-width
a: the first n/4 arc nodes lie at x = a k / (n/4), uniformly, the last of
them at x = a, and beyond it the spacing grows quadratically to the 45
degree point; the vertical coordinate is graded alike. The meshes of n and
2n are nested, and the contact edge sits at the same node for every n, so
that the error at the square-root edge falls regularly.

Run from anywhere: python3 meshes/make_hertz_meshes.py
"""
import math
import os

from gmsh_format import gmsh_elements_text, gmsh_text

R = 1.0


def arc(theta):
    return (R * math.cos(theta), R + R * math.sin(theta))


def point(xi, eta):
    """The Coons patch of the quarter disk at (xi, eta) in [0, 1]^2."""
    bottom = arc(-math.pi / 2 + xi * math.pi / 4)      # (0, 0) .. 45 degrees
    right = arc(-math.pi / 4 + eta * math.pi / 4)      # 45 degrees .. (1, 1)
    top = (xi * R, R)                                  # (0, 1) .. (1, 1)
    left = (0.0, eta * R)                              # (0, 0) .. (0, 1)
    p00, p10, p01, p11 = arc(-math.pi / 2), arc(-math.pi / 4), (0.0, R), (R, R)
    return tuple((1 - eta) * bottom[c] + eta * top[c] + (1 - xi) * left[c]
                 + xi * right[c]
                 - ((1 - xi) * (1 - eta) * p00[c] + xi * (1 - eta) * p10[c]
                    + (1 - xi) * eta * p01[c] + xi * eta * p11[c])
                 for c in range(2))


def fitted_grading(n, a):
    """The Coons coordinates xi_0..xi_n of the arc nodes: x = a k / m for
    k <= m = n / 4, then xi quadratic in k up to xi_n = 1 with the spacing
    of the uniform part at k = m."""
    m = n // 4
    xi = [math.asin(a * k / m / R) / (math.pi / 4) for k in range(m + 1)]
    h = xi[m] - xi[m - 1]
    c = 1 - xi[m] - h * (n - m)
    if c < 0:
        raise ValueError("a = %g is too large for the fitted grading" % a)
    for k in range(m + 1, n + 1):
        s = (k - m) / (n - m)
        xi.append(xi[m] + h * (n - m) * s + c * s * s)
    return xi


def patch_nodes(n, fitted=None):
    """The (N + 1)^2 nodes (i, j, x, y) of the quarter disk's patch, graded
    as (i/N)^2 or fitted to the half-width fitted, row by row."""
    graded = (fitted_grading(n, fitted) if fitted
              else [(k / n) ** 2 for k in range(n + 1)])
    return [(i, j) + point(graded[i], graded[j])
            for j in range(n + 1) for i in range(n + 1)]


def quarter_disk(n, fitted=None):
    index = lambda i, j: j * (n + 1) + i + 1
    nodes = [(index(i, j), x, y) for i, j, x, y in patch_nodes(n, fitted)]
    lines = []
    for k in range(n):
        lines.append((1, index(0, k), index(0, k + 1)))          # x = 0
        lines.append((2, index(k, n), index(k + 1, n)))          # y = 1
        lines.append((3, index(k, 0), index(k + 1, 0)))          # arc, bottom
        lines.append((3, index(n, k), index(n, k + 1)))          # arc, right
    quads = [(index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1))
             for j in range(n) for i in range(n)]
    return gmsh_text(nodes, lines, quads, [(1, "symmetry"), (2, "top"), (3, "contact")])


def half_disk(n, fitted=None):
    """The whole lower half of the cylinder, -1 <= x <= 1 (for loads that
    break the symmetry, benchmarks/run_cattaneo_mindlin.py): the quarter
    disk of quarter_disk(n, fitted) and its mirror image x -> -x, sharing
    the nodes on x = 0. Physical groups: 2 the top y = 1, 3 the arc."""
    index = lambda i, j: j * (n + 1) + i + 1
    mirrored = lambda i, j: index(i, j) if i == 0 else (n + 1) ** 2 + j * n + i
    patch = patch_nodes(n, fitted)
    nodes = ([(index(i, j), x, y) for i, j, x, y in patch]
             + [(mirrored(i, j), -x, y) for i, j, x, y in patch if i > 0])
    lines = []
    for number in (index, mirrored):
        for k in range(n):
            lines.append((2, number(k, n), number(k + 1, n)))      # y = 1
            lines.append((3, number(k, 0), number(k + 1, 0)))      # arc
            lines.append((3, number(n, k), number(n, k + 1)))      # arc
    quads = [(index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1))
             for j in range(n) for i in range(n)]
    # The mirror image reverses the orientation: list its nodes clockwise
    # in the mirrored numbering, which is counterclockwise in the plane.
    quads += [(mirrored(i, j), mirrored(i, j + 1), mirrored(i + 1, j + 1),
               mirrored(i + 1, j)) for j in range(n) for i in range(n)]
    return gmsh_text(nodes, lines, quads, [(2, "top"), (3, "contact")])


def two_cylinders(n1, n2, r1=1.0, r2=2.0):
    """Two cylinders touching at the origin, the half model x >= 0 (not
    shipped; benchmarks/run_hertz_two_cylinders.py): above, the lower
    quarter of a cylinder of radius r1 (the patch of quarter_disk(n1)
    scaled by r1, material id 1); below, the mirror image y -> -y of the
    patch of quarter_disk(n2) scaled by r2 (the upper quarter of a cylinder
    of radius r2, material id 2). The two arcs have 2 n1 and 2 n2 segments,
    both graded toward the contact point; their nodes differ but for the
    one at the origin of each. Physical groups: 1 x = 0 (both), 2 the top
    y = r1, 3 the upper arc, 4 the bottom y = -r2, 5 the lower arc."""
    nodes, boundary, cells = [], [], []
    for n, scale, flip, top, arc_tag, material in ((n1, r1 / R, 1, 2, 3, 1),
                                                   (n2, r2 / R, -1, 4, 5, 2)):
        first = len(nodes) + 1
        index = lambda i, j: first + j * (n + 1) + i
        for i, j, x, y in patch_nodes(n):
            nodes.append((index(i, j), scale * x, flip * scale * y, 0.0))
        for k in range(n):
            boundary += [(1, 1, index(0, k), index(0, k + 1)),
                         (1, top, index(k, n), index(k + 1, n)),
                         (1, arc_tag, index(k, 0), index(k + 1, 0)),
                         (1, arc_tag, index(n, k), index(n, k + 1))]
        for j in range(n):
            for i in range(n):
                quad = [index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)]
                # The mirror image reverses the orientation.
                cells.append((3, material) + tuple(quad if flip > 0 else quad[::-1]))
    names = [(1, "symmetry"), (2, "top"), (3, "upper_arc"), (4, "bottom"), (5, "lower_arc")]
    return gmsh_elements_text(nodes, boundary, cells, names, [(1, "upper"), (2, "lower")])


if __name__ == "__main__":
    folder = os.path.dirname(os.path.abspath(__file__))
    for n in (16, 32, 64):
        with open(os.path.join(folder, "hertz_cylinder_%d.msh" % n), "w") as f:
            f.write(quarter_disk(n))
