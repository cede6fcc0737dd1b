"""The Gmsh 2.2 ASCII text of a 2D quadrilateral mesh, shared by the mesh
scripts of this folder: nodes (number, x, y), boundary lines (physical tag,
node, node), quadrilaterals (four nodes, counterclockwise; physical tag 10
"body") and the names of the boundary tags."""


def gmsh_text(nodes, lines, quads, boundary_names):
    out = ["$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$PhysicalNames",
           str(len(boundary_names) + 1)]
    out += ['1 %d "%s"' % (tag, name) for tag, name in boundary_names]
    out += ['2 10 "body"', "$EndPhysicalNames", "$Nodes", str(len(nodes))]
    out += ["%d %.17g %.17g 0" % node for node in nodes]
    out += ["$EndNodes", "$Elements", str(len(lines) + len(quads))]
    number = 0
    for tag, a, b in lines:
        number += 1
        out.append("%d 1 2 %d %d %d %d" % (number, tag, tag, a, b))
    for quad in quads:
        number += 1
        out.append("%d 3 2 10 10 %d %d %d %d" % ((number,) + quad))
    out.append("$EndElements")
    return "\n".join(out) + "\n"
