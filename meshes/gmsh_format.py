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
elements is dim - 1)."""

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
