#!/usr/bin/python3
"""Writes the two-body meshes of this folder (Gmsh 2.2, ASCII).

two_blocks_{quadrilateral,triangle}_A_B.msh: two blocks stacked, not
connected (their interface nodes are separate nodes of each block, at
different places: non-matching meshes), each of width 2 and height 1:
the base [0, 2] x [0, 1] with A x A/2 squares (material id 1), the pad
[0, 2] x [1, 2] with B x B/2 squares (material id 2); triangles cut each
square by its diagonal from (x_i, y_j) to (x_i+1, y_j+1). Boundary tags:
  1  the left sides x = 0 of both blocks
  2  the bottom of the base, y = 0
  3  the top of the base, y = 1 (the opposite side of the pair)
  4  the bottom of the pad, y = 1 (the contact zone)
  5  the top of the pad, y = 2
  6  the right sides x = 2 of both blocks
parameters/two_block_patch_test.prm and tests/run_two_bodies.sh use them.

Run from anywhere: python3 meshes/make_two_body_meshes.py
"""
import os

from gmsh_format import gmsh_elements_text


def blocks(a, b, simplex):
    nodes, boundary, cells = [], [], []
    for block, (n, y0, material, bottom, top) in enumerate(((a, 0.0, 1, 2, 3), (b, 1.0, 2, 4, 5))):
        first = len(nodes) + 1
        rows = n // 2
        v = lambda i, j: first + j * (n + 1) + i
        for j in range(rows + 1):
            for i in range(n + 1):
                nodes.append((v(i, j), 2.0 * i / n, y0 + j / rows, 0.0))
        for i in range(n):
            boundary += [(1, bottom, v(i, 0), v(i + 1, 0)), (1, top, v(i, rows), v(i + 1, rows))]
        for j in range(rows):
            boundary += [(1, 1, v(0, j), v(0, j + 1)), (1, 6, v(n, j), v(n, j + 1))]
            for i in range(n):
                p, q, r, s = v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)
                cells += ([(2, material, p, q, r), (2, material, p, r, s)] if simplex
                          else [(3, material, p, q, r, s)])
    names = [(1, "left_sides"), (2, "base_bottom"), (3, "base_top"), (4, "pad_bottom"),
             (5, "pad_top"), (6, "right_sides")]
    return gmsh_elements_text(nodes, boundary, cells, names, [(1, "base"), (2, "pad")])


if __name__ == "__main__":
    folder = os.path.dirname(os.path.abspath(__file__))
    for name, simplex in (("quadrilateral", False), ("triangle", True)):
        for a, b in ((6, 8), (4, 10)):
            with open(os.path.join(folder, "two_blocks_%s_%d_%d.msh" % (name, a, b)), "w") as f:
                f.write(blocks(a, b, simplex))
