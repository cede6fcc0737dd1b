"""The Gmsh 2.2 ASCII text of a mesh, shared by the mesh scripts of this
folder.

gmsh_text: a 2D quadrilateral mesh: nodes (number, x, y), boundary lines
(physical tag, node, node), quadrilaterals (four nodes, counterclockwise),
the names of the boundary tags, and the physical tag of each quadrilateral
(its material id) with the names of those tags (default: all tag 10
"body").

gmsh_elements_text: any mesh: nodes (number, x, y, z), boundary elements
and cells as (Gmsh element type, physical tag, nodes...), and the names of
the boundary tags and of the cell tags (the dimension of the boundary
elements is dim - 1).

box_face_elements, box_cell_elements: the boundary elements and cells of a
structured box of cubes, hexahedra or Kuhn's tetrahedra."""

import itertools

# Gmsh element types: 1 line, 2 triangle, 3 quadrilateral, 4 tetrahedron,
# 5 hexahedron.
ELEMENT_DIMENSION = {1: 1, 2: 2, 3: 2, 4: 3, 5: 3}


def gmsh_text(nodes, lines, quads, boundary_names, cell_tags=None,
              cell_names=((10, "body"),)):
    if cell_tags is None:
        cell_tags = [10] * len(quads)
    out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames",
           str(len(boundary_names) + len(cell_names))]
    out += ['1 %d "%s"' % (tag, name) for tag, name in boundary_names]
    out += ['2 %d "%s"' % (tag, name) for tag, name in cell_names]
    out += ["$EndPhysicalNames", "$Nodes", str(len(nodes))]
    out += ["%d %.17g %.17g 0" % node for node in nodes]
    out += ["$EndNodes", "$Elements", str(len(lines) + len(quads))]
    number = 0
    for tag, a, b in lines:
        number += 1
        out.append("%d 1 2 %d %d %d %d" % (number, tag, tag, a, b))
    for quad, tag in zip(quads, cell_tags):
        number += 1
        out.append("%d 3 2 %d %d %d %d %d %d" % ((number, tag, tag) + quad))
    out.append("$EndElements")
    return "\n".join(out) + "\n"


def gmsh_elements_text(nodes, boundary, cells, boundary_names, cell_names):
    dim = ELEMENT_DIMENSION[cells[0][0]]
    out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames",
           str(len(boundary_names) + len(cell_names))]
    out += ['%d %d "%s"' % (dim - 1, tag, name) for tag, name in boundary_names]
    out += ['%d %d "%s"' % (dim, tag, name) for tag, name in cell_names]
    out += ["$EndPhysicalNames", "$Nodes", str(len(nodes))]
    out += ["%d %.17g %.17g %.17g" % node for node in nodes]
    out += ["$EndNodes", "$Elements", str(len(boundary) + len(cells))]
    for number, (kind, tag, *vertices) in enumerate(boundary + cells, 1):
        out.append(" ".join(str(v) for v in [number, kind, 2, tag, tag] + vertices))
    out.append("$EndElements")
    return "\n".join(out) + "\n"


def permutation_sign(order):
    """+1 for an even permutation of (0, 1, 2), -1 for an odd one: the sign
    of the volume of Kuhn's tetrahedron along that order of the axes."""
    inversions = sum(1 for a in range(3) for b in range(a + 1, 3) if order[a] > order[b])
    return -1 if inversions % 2 else 1


def box_face_elements(tag, corners, simplex):
    """A square face of a box of cubes, its corners in cyclic order from the
    lowest: one quadrilateral, or the two triangles of Kuhn's diagonal from
    the lowest to the highest corner (conforming with box_cell_elements)."""
    if simplex:
        return [(2, tag, corners[0], corners[1], corners[2]),
                (2, tag, corners[0], corners[2], corners[3])]
    return [(3, tag) + tuple(corners)]


def box_cell_elements(v, i, j, k, simplex, material):
    """Cube (i, j, k) of a box, v(i, j, k) the node numbers: one hexahedron,
    or Kuhn's six tetrahedra around its diagonal from the lowest to the
    highest corner, positively oriented."""
    if not simplex:
        return [(5, material, v(i, j, k), v(i + 1, j, k), v(i + 1, j + 1, k), v(i, j + 1, k),
                 v(i, j, k + 1), v(i + 1, j, k + 1), v(i + 1, j + 1, k + 1),
                 v(i, j + 1, k + 1))]
    cells = []
    for order in itertools.permutations(range(3)):
        step, path = [0, 0, 0], [(i, j, k)]
        for axis in order:
            step[axis] = 1
            path.append((i + step[0], j + step[1], k + step[2]))
        if permutation_sign(order) < 0:
            path[1], path[2] = path[2], path[1]
        cells.append((4, material) + tuple(v(*corner) for corner in path))
    return cells
