#!/usr/bin/python3
"""Writes the Gmsh meshes (format 2.2, ASCII) of the 3D Hertz benchmark: a
rigid sphere pressed into an elastic block, whose quarter model is the cube
[0, L]^3 (y up) with the contact point at the corner (0, L, 0) of its top
face and the planes of symmetry x = 0 and z = 0 (parameters/hertz_sphere.prm).

hertz_sphere_hexahedron_8.msh (and hertz_sphere_block(N, simplex) for
other N, and tetrahedra): N cells along each edge, the
coordinates graded as L (k/N)^2 toward the contact corner (x and z from 0,
y from the top), so that about a third of the edge's cells lie within a
contact radius of L/10; tetrahedra: each hexahedron cut into the six
around its diagonal from its lowest to its highest corner (Kuhn's
subdivision, conforming across faces). Physical groups (the boundary ids of
the parameter file):
  1  the plane of symmetry x = 0       2  the plane of symmetry z = 0
  3  the bottom y = 0                  4  the top y = L (contact)
  5  the side x = L                    6  the side z = L

Run from anywhere: python3 meshes/make_hertz_sphere_meshes.py
(or with N FILE: the hexahedral block of N cells along each edge to FILE)
"""
import itertools
import math
import os
import sys

from gmsh_format import gmsh_elements_text

L = 1.0
NAMES = [(1, "symmetry_x"), (2, "symmetry_z"), (3, "bottom"), (4, "top"),
         (5, "side_x"), (6, "side_z")]


def signed_volume(points):
    a, b, c, d = points
    u = [b[i] - a[i] for i in range(3)]
    v = [c[i] - a[i] for i in range(3)]
    w = [d[i] - a[i] for i in range(3)]
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
            + u[2] * (v[0] * w[1] - v[1] * w[0]))


def hertz_sphere_block(n, simplex=False, length=L, mirrored=False):
    """mirrored: the tetrahedra around the other diagonal in x of each
    hexahedron (from its corner (1, 0, 0) to (0, 1, 1)), the faces cut to
    match: the same mesh reflected in its cells' x index, a second
    conforming split to compare with."""
    nodes, boundary, cells = graded_cube(n, simplex, length, mirrored)
    return gmsh_elements_text(nodes, boundary, cells, NAMES, [(10, "block")])


def graded_cube(n, simplex=False, length=L, mirrored=False, first=1, material=10,
                tags=(1, 2, 3, 4, 5, 6), point_map=None, y_graded_down=False):
    """The nodes, boundary faces and cells of the graded cube (node numbers
    from first, the cells' material id, the tags of the faces x = 0, z = 0,
    y = 0, y = L, x = L, z = L), y graded toward y = L (or toward y = 0 if
    y_graded_down), its points moved by point_map if given."""
    graded = [length * (k / n) ** 2 for k in range(n + 1)]
    coordinate = (lambda i: graded[i],
                  (lambda j: graded[j]) if y_graded_down else (lambda j: length - graded[n - j]),
                  lambda k: graded[k])
    index = lambda i, j, k: (k * (n + 1) + j) * (n + 1) + i + first
    nodes, where = [], {}
    for k in range(n + 1):
        for j in range(n + 1):
            for i in range(n + 1):
                point = (coordinate[0](i), coordinate[1](j), coordinate[2](k))
                if point_map:
                    point = point_map(*point)
                nodes.append((index(i, j, k),) + point)
                where[index(i, j, k)] = point
    boundary, cells = [], []
    # The faces on the surface: (tag, axis, index of the plane).
    for tag, axis, fixed in zip(tags, (0, 2, 1, 1, 0, 2), (0, 0, 0, n, n, n)):
        others = [a for a in range(3) if a != axis]
        for p in range(n):
            for q in range(n):
                corners = {}
                for dp, dq in itertools.product((0, 1), repeat=2):
                    ijk = [0, 0, 0]
                    ijk[axis], ijk[others[0]], ijk[others[1]] = fixed, p + dp, q + dq
                    corners[(dp, dq)] = index(*ijk)
                if simplex and mirrored and axis != 0:
                    # x is the face's first direction: the diagonal from
                    # (1, 0) to (0, 1).
                    for middle in ((0, 0), (1, 1)):
                        boundary.append((2, tag, corners[(1, 0)], corners[middle], corners[(0, 1)]))
                elif simplex:
                    # Kuhn's diagonal of the face: lowest to highest corner.
                    for middle in ((1, 0), (0, 1)):
                        boundary.append((2, tag, corners[(0, 0)], corners[middle], corners[(1, 1)]))
                else:
                    boundary.append((3, tag, corners[(0, 0)], corners[(1, 0)],
                                     corners[(1, 1)], corners[(0, 1)]))
    for k in range(n):
        for j in range(n):
            for i in range(n):
                v = lambda a, b, c: index(i + a, j + b, k + c)
                if simplex and mirrored:
                    v = lambda a, b, c: index(i + 1 - a, j + b, k + c)
                if not simplex:
                    cells.append((5, material, v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0),
                                  v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1)))
                    continue
                for order in itertools.permutations(range(3)):
                    step, path = [0, 0, 0], [v(0, 0, 0)]
                    for axis in order:
                        step[axis] = 1
                        path.append(v(*step))
                    if signed_volume([where[p] for p in path]) < 0:
                        path[1], path[2] = path[2], path[1]
                    cells.append((4, material) + tuple(path))
    return nodes, boundary, cells


def sphere_on_block(n_block, n_sphere, simplex=False, radius=2.0, top=2.5):
    """Two elastic bodies (benchmarks/run_hertz_sphere_on_block.py): below,
    the block of hertz_sphere_block(n_block) (material id 1, its tags); on
    it, the quarter of a body whose bottom is the sphere of the given radius
    touching the block's top at the corner (0, L, 0), and whose top is the
    plane y = top: the graded cube of n_sphere cells, x and z as the
    block's, each vertical line of nodes spread from the sphere to the top
    graded toward the sphere (material id 2). Tags of the upper body: 1
    x = 0 and 2 z = 0 (as the block's), 7 its spherical bottom, 8 its top,
    9 its sides x = L and z = L."""
    nodes, boundary, cells = graded_cube(n_block, simplex, material=1)

    def on_sphere(x, y, z):
        bottom = L + radius - math.sqrt(radius ** 2 - x ** 2 - z ** 2)
        return (x, bottom + y / L * (top - bottom), z)

    upper = graded_cube(n_sphere, simplex, first=len(nodes) + 1, material=2,
                        tags=(1, 2, 7, 8, 9, 9), point_map=on_sphere, y_graded_down=True)
    names = NAMES[:4] + [(5, "side_x"), (6, "side_z"), (7, "sphere"), (8, "sphere_top"),
                         (9, "sphere_sides")]
    return gmsh_elements_text(nodes + upper[0], boundary + upper[1], cells + upper[2],
                              names, [(1, "block"), (2, "sphere")])


if __name__ == "__main__" and len(sys.argv) == 3:
    with open(sys.argv[2], "w") as f:
        f.write(hertz_sphere_block(int(sys.argv[1])))
elif __name__ == "__main__" and len(sys.argv) != 1:
    sys.exit("usage: make_hertz_sphere_meshes.py [N FILE]")
elif __name__ == "__main__":
    folder = os.path.dirname(os.path.abspath(__file__))
    # The mesh of parameters/hertz_sphere.prm; benchmarks/run_hertz_sphere.py
    # writes the others where it needs them.
    with open(os.path.join(folder, "hertz_sphere_hexahedron_8.msh"), "w") as f:
        f.write(hertz_sphere_block(8))
    # The mesh of parameters/hertz_sphere_on_block.prm.
    with open(os.path.join(folder, "hertz_sphere_on_block_6_9.msh"), "w") as f:
        f.write(sphere_on_block(6, 9))
