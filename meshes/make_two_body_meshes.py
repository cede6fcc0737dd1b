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

two_blocks_{hexahedron,tetrahedron}_A_B.msh: the same in 3D, blocks of
depth 1: the base [0, 2] x [0, 1] x [0, 1] with A x A/2 x 2 cubes' cells,
the pad [0, 2] x [0, 1] x [1, 2] with B x B/2 x 2 (tetrahedra: Kuhn's six
per cell). Boundary tags as in 2D with y -> z, and 7 the front sides
y = 0, 8 the back sides y = 1 of both blocks.

two_blocks_quadrilateral_6_8_turned.msh: the quadrilaterals 6:8 turned by
45 degrees about the origin (oblique planes of symmetry).

two_blocks_mixed_6_8.msh: the 2D blocks 6:8, the base of triangles, the
pad of quadrilaterals; two_blocks_mixed_3d_4_10.msh: the 3D blocks 4:10,
the base of hexahedra, the pad of tetrahedra (Cell type = mixed).

three_blocks.msh: a base and two pads, see three_blocks().

layered_strip.msh: a thin layer on a base, non-matching, see
layered_strip().

Run from anywhere: python3 meshes/make_two_body_meshes.py
"""
import math
import os

from gmsh_format import box_cell_elements, box_face_elements, gmsh_elements_text


def per_block(simplex):
    """simplex: one value for both blocks, or (base's, pad's)."""
    return tuple(simplex) if isinstance(simplex, tuple) else (simplex, simplex)


def blocks(a, b, simplex, angle=0.0):
    """angle: the whole mesh turned by that many degrees about the origin."""
    nodes, boundary, cells = [], [], []
    for block, (n, y0, material, bottom, top) in enumerate(((a, 0.0, 1, 2, 3), (b, 1.0, 2, 4, 5))):
        block_simplex = per_block(simplex)[block]
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
                cells += ([(2, material, p, q, r), (2, material, p, r, s)] if block_simplex
                          else [(3, material, p, q, r, s)])
    names = [(1, "left_sides"), (2, "base_bottom"), (3, "base_top"), (4, "pad_bottom"),
             (5, "pad_top"), (6, "right_sides")]
    if angle != 0.0:
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        nodes = [(n, c * x - s * y, s * x + c * y, z) for n, x, y, z in nodes]
    return gmsh_elements_text(nodes, boundary, cells, names, [(1, "base"), (2, "pad")])


def blocks_3d(a, b, simplex, separation=0.0):
    """separation: the base moved down by that much (a gap between the
    blocks; benchmarks/run_two_body_cost.py)."""
    nodes, boundary, cells = [], [], []
    for block, (n, z0, material, bottom, top) in enumerate(((a, -separation, 1, 2, 3),
                                                            (b, 1.0, 2, 4, 5))):
        block_simplex = per_block(simplex)[block]
        first = len(nodes) + 1
        size = (n, n // 2, 2)
        v = lambda i, j, k: first + (k * (size[1] + 1) + j) * (size[0] + 1) + i
        for k in range(size[2] + 1):
            for j in range(size[1] + 1):
                for i in range(size[0] + 1):
                    nodes.append((v(i, j, k), 2.0 * i / size[0], j / size[1], z0 + k / size[2]))
        # The faces of the block's surface: (tag, fixed axis, fixed index).
        for tag, axis, fixed in ((1, 0, 0), (6, 0, size[0]), (7, 1, 0), (8, 1, size[1]),
                                 (bottom, 2, 0), (top, 2, size[2])):
            others = [d for d in range(3) if d != axis]
            for p in range(size[others[0]]):
                for q in range(size[others[1]]):
                    corners = []
                    for dp, dq in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        ijk = [0, 0, 0]
                        ijk[axis], ijk[others[0]], ijk[others[1]] = fixed, p + dp, q + dq
                        corners.append(v(*ijk))
                    boundary += box_face_elements(tag, corners, block_simplex)
        for k in range(size[2]):
            for j in range(size[1]):
                for i in range(size[0]):
                    cells += box_cell_elements(v, i, j, k, block_simplex, material)
    names = [(1, "left_sides"), (2, "base_bottom"), (3, "base_top"), (4, "pad_bottom"),
             (5, "pad_top"), (6, "right_sides"), (7, "front_sides"), (8, "back_sides")]
    return gmsh_elements_text(nodes, boundary, cells, names, [(1, "base"), (2, "pad")])


def layered_strip(nb=16, nl=22):
    """A base [0, 4] x [0, 0.5] (nb x 2 squares' cells, material id 1) and a
    layer [0, 4] x [0.5, 0.75] on it (nl x 2 cells, material id 2), two
    bodies (parameters/softening_interface.prm). Boundary tags: 1 x = 0 of
    both, 2 the base's bottom, 3 the base's top, 4 the layer's bottom, 5 the
    layer's top, 6 x = 4 of both."""
    nodes, boundary, cells = [], [], []
    for n, y0, height, material, bottom, top in ((nb, 0.0, 0.5, 1, 2, 3),
                                                  (nl, 0.5, 0.25, 2, 4, 5)):
        first = len(nodes) + 1
        v = lambda i, j: first + j * (n + 1) + i
        for j in range(3):
            for i in range(n + 1):
                nodes.append((v(i, j), 4.0 * i / n, y0 + height * j / 2, 0.0))
        for i in range(n):
            boundary += [(1, bottom, v(i, 0), v(i + 1, 0)), (1, top, v(i, 2), v(i + 1, 2))]
        for j in range(2):
            boundary += [(1, 1, v(0, j), v(0, j + 1)), (1, 6, v(n, j), v(n, j + 1))]
            for i in range(n):
                cells.append((3, material, v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)))
    names = [(1, "left_sides"), (2, "base_bottom"), (3, "base_top"), (4, "layer_bottom"),
             (5, "layer_top"), (6, "right_sides")]
    return gmsh_elements_text(nodes, boundary, cells, names, [(1, "base"), (2, "layer")])


def three_blocks():
    """A base [0, 2] x [0, 1] (4 x 2 squares, material id 1) and two pads
    on it, [0, 0.9] x [1, 2] and [1.1, 2] x [1, 2] (3 x 3 squares each,
    material id 2), three bodies. Boundary tags: 1 x = 0, 2 the base's
    bottom, 3 the base's top for x < 1, 7 for x > 1, 4 the first pad's
    bottom, 8 the second pad's, 5 the pads' tops, 6 x = 2, 9 the pads'
    inner sides. The base's vertex (1, 1) ends both parts of its top
    (tests/bad_input/pair_pairs_meet.prm)."""
    nodes, boundary, cells = [], [], []

    def block(x0, x1, y0, y1, nx, ny, material, tags):
        """tags: left, right, bottom (a function of x), top."""
        first = len(nodes) + 1
        v = lambda i, j: first + j * (nx + 1) + i
        for j in range(ny + 1):
            for i in range(nx + 1):
                nodes.append((v(i, j), x0 + (x1 - x0) * i / nx, y0 + (y1 - y0) * j / ny, 0.0))
        for j in range(ny):
            boundary.extend([(1, tags[0], v(0, j), v(0, j + 1)), (1, tags[1], v(nx, j), v(nx, j + 1))])
        for i in range(nx):
            x = x0 + (x1 - x0) * (i + 0.5) / nx
            boundary.extend([(1, tags[2], v(i, 0), v(i + 1, 0)), (1, tags[3](x), v(i, ny), v(i + 1, ny))])
            for j in range(ny):
                cells.append((3, material, v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1)))

    block(0.0, 2.0, 0.0, 1.0, 4, 2, 1, (1, 6, 2, lambda x: 3 if x < 1 else 7))
    block(0.0, 0.9, 1.0, 2.0, 3, 3, 2, (1, 9, 4, lambda x: 5))
    block(1.1, 2.0, 1.0, 2.0, 3, 3, 2, (9, 6, 8, lambda x: 5))
    names = [(1, "x_0"), (2, "base_bottom"), (3, "base_top_left"), (4, "pad_1_bottom"),
             (5, "pad_tops"), (6, "x_2"), (7, "base_top_right"), (8, "pad_2_bottom"),
             (9, "pad_inner_sides")]
    return gmsh_elements_text(nodes, boundary, cells, names, [(1, "base"), (2, "pads")])


if __name__ == "__main__":
    folder = os.path.dirname(os.path.abspath(__file__))
    for name, simplex in (("quadrilateral", False), ("triangle", True)):
        for a, b in ((6, 8), (4, 10)):
            with open(os.path.join(folder, "two_blocks_%s_%d_%d.msh" % (name, a, b)), "w") as f:
                f.write(blocks(a, b, simplex))
    for name, simplex in (("hexahedron", False), ("tetrahedron", True)):
        for a, b in ((6, 8), (4, 10)):
            with open(os.path.join(folder, "two_blocks_%s_%d_%d.msh" % (name, a, b)), "w") as f:
                f.write(blocks_3d(a, b, simplex))
    # Turned by 45 degrees: the planes of symmetry x = 0 and y = 0 of the
    # patch test become oblique.
    with open(os.path.join(folder, "two_blocks_quadrilateral_6_8_turned.msh"), "w") as f:
        f.write(blocks(6, 8, False, 45.0))
    # Mixed: simplices on one side, hypercubes on the other.
    with open(os.path.join(folder, "two_blocks_mixed_6_8.msh"), "w") as f:
        f.write(blocks(6, 8, (True, False)))
    with open(os.path.join(folder, "two_blocks_mixed_3d_4_10.msh"), "w") as f:
        f.write(blocks_3d(4, 10, (False, True)))
    with open(os.path.join(folder, "three_blocks.msh"), "w") as f:
        f.write(three_blocks())
    with open(os.path.join(folder, "layered_strip.msh"), "w") as f:
        f.write(layered_strip())
