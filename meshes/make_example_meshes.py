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

two_columns_{quadrilateral,triangle}_N.msh,
two_columns_{hexahedron,tetrahedron}_N.msh:
two unit columns side by side, [0, 1] and [2, 3] in x, 0 <= y <= 1 (and
0 <= z <= 1 in 3D), not connected, N cells along each edge (triangles: each
square cut by its diagonal from (x_i, y_j) to (x_i+1, y_j+1); tetrahedra:
each cube cut into the six around its diagonal from its lowest to its
highest corner). Boundary
tags: 1 the sides x = 0 and x = 2, 2 the sides x = 1 and x = 3, 6 the sides
z = 0 and 7 z = 1 (3D), 3 the bottom of the first column, 5 the bottom of
the second, 4 both tops; parameters/two_columns.prm (contact zones).

tilted_block_{quadrilateral,triangle}_N.msh,
tilted_block_{hexahedron,tetrahedron}_N.msh: the first of the two columns
alone, rotated about the origin by 30 degrees about z and then, in 3D, by
20 degrees about x (x = R X, R in rotation()), so that no face is parallel
to a coordinate plane; the same tags (without 5). The tilted patch tests
(parameters/tilted_patch_test*.prm) put their planes of symmetry and the
support on these oblique faces.

peeling_strip.msh, peeling_strip_3d.msh: a strip of cells as square as
the strip allows, 8 long (x) and 0.5 thick (y), in 3D 1 wide (z, half of
the strip: z = 0 is a plane of symmetry): 64 x 4 quadrilaterals, 32 x 2 x 4
hexahedra. Boundary tags: 1 the end x = 0, 2 the end x = 8, 3 the bottom
y = 0 (glued), 4 the top, 6 z = 0 and 7 z = 1 (3D);
parameters/peeling_strip*.prm (adhesion).

precracked_strip.msh, precracked_strip_3d.msh: the same strips, the
bottom cut in two: 5 the pre-crack x < 2 (free), 3 the rest (bonded);
parameters/cohesive_peel*.prm (a cohesive interface).

Run from anywhere: python3 meshes/make_example_meshes.py
"""
import math
import os

from gmsh_format import box_cell_elements, box_face_elements, gmsh_elements_text, gmsh_text

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


def rotation(dim):
    """The rotation of the tilted blocks: by 30 degrees about z, then in 3D
    by 20 degrees about x, so that no face is parallel to a coordinate
    plane. Rows of the matrix R, x = R X."""
    c, s = math.cos(ANGLE), math.sin(ANGLE)
    if dim == 2:
        return ((c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0))
    a, b = math.cos(math.radians(20.0)), math.sin(math.radians(20.0))
    return ((c, -s, 0.0), (a * s, a * c, -b), (b * s, b * c, a))


def columns(n, dim, simplex=False, count=2, rotate=None):
    """Unit columns side by side, [2 b, 2 b + 1] in x for b < count, rotated
    by the matrix rotate (rows) if given (see the top of the file)."""
    nz = n if dim == 3 else 0
    index = lambda b, i, j, k: ((b * (nz + 1) + k) * (n + 1) + j) * (n + 1) + i + 1
    nodes = []
    for b in range(count):
        for k in range(nz + 1):
            for j in range(n + 1):
                for i in range(n + 1):
                    point = (2 * b + i / n, j / n, k / n if dim == 3 else 0.0)
                    if rotate:
                        point = tuple(sum(r * p for r, p in zip(row, point)) for row in rotate)
                    nodes.append((index(b, i, j, k),) + point)
    boundary, cells = [], []
    for b in range(count):
        bottom = 3 if b == 0 else 5
        if dim == 2:
            v = lambda i, j: index(b, i, j, 0)
            for k in range(n):
                boundary += [(1, 1, v(0, k), v(0, k + 1)), (1, 2, v(n, k), v(n, k + 1)),
                             (1, bottom, v(k, 0), v(k + 1, 0)), (1, 4, v(k, n), v(k + 1, n))]
            for j in range(n):
                for i in range(n):
                    a, b_, c, d = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
                    cells += ([(2, 10, a, b_, c), (2, 10, a, c, d)] if simplex
                              else [(3, 10, a, b_, c, d)])
        else:
            v = lambda i, j, k: index(b, i, j, k)
            # The faces of the cube surface: (tag, fixed axis, fixed index).
            for tag, axis, fixed in ((1, 0, 0), (2, 0, n), (bottom, 1, 0), (4, 1, n), (6, 2, 0), (7, 2, n)):
                for p in range(n):
                    for q in range(n):
                        corners = []
                        for dp, dq in ((0, 0), (1, 0), (1, 1), (0, 1)):
                            ijk = [0, 0, 0]
                            others = [a for a in range(3) if a != axis]
                            ijk[axis], ijk[others[0]], ijk[others[1]] = fixed, p + dp, q + dq
                            corners.append(v(*ijk))
                        boundary += box_face_elements(tag, corners, simplex)
            for k in range(n):
                for j in range(n):
                    for i in range(n):
                        cells += box_cell_elements(v, i, j, k, simplex, 10)
    names = [(1, "left_sides"), (2, "right_sides"), (3, "support_1"), (4, "tops")]
    if count > 1:
        names.append((5, "support_2"))
    if dim == 3:
        names += [(6, "front_sides"), (7, "back_sides")]
    return gmsh_elements_text(nodes, boundary, cells, names, [(10, "columns")])


def strip(lengths, counts, precrack=0.0):
    """A box of lengths[a] cut into counts[a] cells along each axis a (2 or
    3 axes), tagged as described at the top of the file; the bottom's faces
    with x < precrack tagged 5 instead of 3."""
    dim = len(lengths)
    n = list(counts) + [0] * (3 - dim)
    index = lambda i, j, k: (k * (n[1] + 1) + j) * (n[0] + 1) + i + 1
    nodes = [(index(i, j, k), lengths[0] * i / n[0], lengths[1] * j / n[1],
              lengths[2] * k / n[2] if dim == 3 else 0.0)
             for k in range(n[2] + 1) for j in range(n[1] + 1) for i in range(n[0] + 1)]
    boundary, cells = [], []
    if dim == 2:
        v = lambda i, j: index(i, j, 0)
        for j in range(n[1]):
            boundary += [(1, 1, v(0, j), v(0, j + 1)), (1, 2, v(n[0], j), v(n[0], j + 1))]
        for i in range(n[0]):
            bottom = 5 if lengths[0] * (i + 1) / n[0] <= precrack else 3
            boundary += [(1, bottom, v(i, 0), v(i + 1, 0)), (1, 4, v(i, n[1]), v(i + 1, n[1]))]
        cells = [(3, 10, v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1))
                 for j in range(n[1]) for i in range(n[0])]
        names = [(1, "lifted_end"), (2, "far_end"), (3, "glued_bottom"), (4, "top")]
        names += [(5, "precrack")] if precrack > 0 else []
    else:
        for tag, axis, fixed in ((1, 0, 0), (2, 0, n[0]), (3, 1, 0), (4, 1, n[1]),
                                 (6, 2, 0), (7, 2, n[2])):
            others = [a for a in range(3) if a != axis]
            for p in range(n[others[0]]):
                for q in range(n[others[1]]):
                    corners = []
                    for dp, dq in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        ijk = [0, 0, 0]
                        ijk[axis], ijk[others[0]], ijk[others[1]] = fixed, p + dp, q + dq
                        corners.append(index(*ijk))
                    cracked = tag == 3 and lengths[0] * (p + 1) / n[0] <= precrack
                    boundary += box_face_elements(5 if cracked else tag, corners, False)
        cells = [cell for k in range(n[2]) for j in range(n[1]) for i in range(n[0])
                 for cell in box_cell_elements(index, i, j, k, False, 10)]
        names = [(1, "lifted_end"), (2, "far_end"), (3, "glued_bottom"), (4, "top"),
                 (6, "symmetry_plane"), (7, "side")]
        names += [(5, "precrack")] if precrack > 0 else []
    return gmsh_elements_text(nodes, boundary, cells, names, [(10, "strip")])


if __name__ == "__main__":
    folder = os.path.dirname(os.path.abspath(__file__))
    for n in (8, 16):
        with open(os.path.join(folder, "rotated_square_%d.msh" % n), "w") as f:
            f.write(rotated_square(n))
    with open(os.path.join(folder, "two_layer_column_4.msh"), "w") as f:
        f.write(two_layer_column(4))
    for name, dim, simplex, n in (("quadrilateral", 2, False, 4), ("triangle", 2, True, 4),
                                  ("hexahedron", 3, False, 2), ("tetrahedron", 3, True, 2)):
        with open(os.path.join(folder, "two_columns_%s_%d.msh" % (name, n)), "w") as f:
            f.write(columns(n, dim, simplex))
        with open(os.path.join(folder, "tilted_block_%s_%d.msh" % (name, n)), "w") as f:
            f.write(columns(n, dim, simplex, count=1, rotate=rotation(dim)))
    with open(os.path.join(folder, "peeling_strip.msh"), "w") as f:
        f.write(strip((8.0, 0.5), (64, 4)))
    with open(os.path.join(folder, "peeling_strip_3d.msh"), "w") as f:
        f.write(strip((8.0, 0.5, 1.0), (32, 2, 4)))
    with open(os.path.join(folder, "precracked_strip.msh"), "w") as f:
        f.write(strip((8.0, 0.5), (64, 4), precrack=2.0))
    with open(os.path.join(folder, "precracked_strip_3d.msh"), "w") as f:
        f.write(strip((8.0, 0.5, 1.0), (32, 2, 4), precrack=2.0))
