"""The Gmsh 2.2 ASCII text of a 2D quadrilateral mesh, shared by the mesh
scripts of this folder: nodes (number, x, y), boundary lines (physical tag,
node, node), quadrilaterals (four nodes, counterclockwise), the names of the
boundary tags, and the physical tag of each quadrilateral (its material id)
with the names of those tags (default: all tag 10 "body")."""


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
