#!/usr/bin/python3
"""Writes the Gmsh meshes (format 2.2, ASCII) of the bad_input tests that a
run must refuse, each with one defect, and one good mesh of each kind that a
run must accept (the tests run it too, so a check that refuses good meshes
fails):

  good_2d.msh            2 x 2 squares cut into triangles, boundary ids
                         0 (x = 0), 1 (x = 1), 2 (y = 0), 3 (y = 1)
  good_hexahedra.msh     2 x 2 x 2 hexahedra, ids 0 (x = 0), 1 (x = 1),
                         4 (z = 0), 5 (z = 1)
  repeated_vertex.msh    a triangle that uses a node twice
  duplicate_node_id.msh  node id 5 defined twice
  collinear.msh          all nodes on the line y = 0
  degenerate_cell.msh    a triangle with its three nodes on a line
  huge.msh, tiny.msh     the good mesh scaled by 1e300 and 1e-300
  hanging_vertex.msh     a node on the edge of a larger triangle
  coincident_nodes.msh   two squares with separate nodes on x = 1 (a crack)
  hanging_face_3d.msh    a hexahedron next to 2 x 2 x 2 smaller ones
  twisted_hexahedron.msh a hexahedron with two nodes of its top swapped
  wedge.msh              the unit cube as two wedges (prisms), a cell type
                         the program does not support
  negative_node_count.msh      the good 2D mesh announcing -5 nodes
  huge_element_count.msh       the good 2D mesh announcing 1e12 elements

Run from anywhere: python3 tests/bad_input/meshes/make_bad_meshes.py
"""
import os


def write(name, nodes, cells, faces, cell_type, face_type):
    """nodes: (id, x, y, z); cells: node id tuples; faces: (tag, ids)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), name)
    with open(path, "w") as f:
        f.write("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n")
        f.write("$Nodes\n%d\n" % len(nodes))
        for (i, x, y, z) in nodes:
            f.write("%d %.17g %.17g %.17g\n" % (i, x, y, z))
        f.write("$EndNodes\n$Elements\n%d\n" % (len(cells) + len(faces)))
        k = 1
        for (tag, ids) in faces:
            f.write("%d %d 2 %d %d %s\n"
                    % (k, face_type, tag, tag, " ".join(map(str, ids))))
            k += 1
        for ids in cells:
            f.write("%d %d 2 10 10 %s\n"
                    % (k, cell_type, " ".join(map(str, ids))))
            k += 1
        f.write("$EndElements\n")


def recount(source, name, section, count):
    """The file source with the count at the head of section replaced."""
    folder = os.path.dirname(os.path.abspath(__file__))
    with open(os.path.join(folder, source)) as f:
        lines = f.read().split("\n")
    lines[lines.index(section) + 1] = count
    with open(os.path.join(folder, name), "w") as f:
        f.write("\n".join(lines))


def triangles(n, scale=1.0, squash=False):
    index = lambda i, j: j * (n + 1) + i + 1
    nodes = [(index(i, j), scale * i / n, 0.0 if squash else scale * j / n, 0.0)
             for j in range(n + 1) for i in range(n + 1)]
    cells = []
    for j in range(n):
        for i in range(n):
            a, b = index(i, j), index(i + 1, j)
            c, d = index(i + 1, j + 1), index(i, j + 1)
            cells += [(a, b, c), (a, c, d)]
    lines = []
    for k in range(n):
        lines += [(0, (index(0, k), index(0, k + 1))),
                  (1, (index(n, k), index(n, k + 1))),
                  (2, (index(k, 0), index(k + 1, 0))),
                  (3, (index(k, n), index(k + 1, n)))]
    return nodes, cells, lines


def hexahedra(n, origin=0.0, size=1.0, first_id=1):
    m = n + 1
    index = lambda i, j, k: (k * m + j) * m + i + first_id
    h = size / n
    nodes = [(index(i, j, k), origin + i * h, j * h, k * h)
             for k in range(m) for j in range(m) for i in range(m)]
    cells = []
    for k in range(n):
        for j in range(n):
            for i in range(n):
                cells.append((index(i, j, k), index(i + 1, j, k),
                              index(i + 1, j + 1, k), index(i, j + 1, k),
                              index(i, j, k + 1), index(i + 1, j, k + 1),
                              index(i + 1, j + 1, k + 1), index(i, j + 1, k + 1)))
    faces = []
    for a in range(n):
        for b in range(n):
            faces += [(0, (index(0, a, b), index(0, a + 1, b),
                           index(0, a + 1, b + 1), index(0, a, b + 1))),
                      (1, (index(n, a, b), index(n, a + 1, b),
                           index(n, a + 1, b + 1), index(n, a, b + 1))),
                      (4, (index(a, b, 0), index(a + 1, b, 0),
                           index(a + 1, b + 1, 0), index(a, b + 1, 0))),
                      (5, (index(a, b, n), index(a + 1, b, n),
                           index(a + 1, b + 1, n), index(a, b + 1, n)))]
    return nodes, cells, faces


TRIANGLE, QUADRILATERAL, HEXAHEDRON, LINE, WEDGE = 2, 3, 5, 1, 6

nodes, cells, lines = triangles(2)
write("good_2d.msh", nodes, cells, lines, TRIANGLE, LINE)
recount("good_2d.msh", "negative_node_count.msh", "$Nodes", "-5")
recount("good_2d.msh", "huge_element_count.msh", "$Elements", "1000000000000")
write("repeated_vertex.msh", nodes,
      [(cells[0][0], cells[0][0], cells[0][2])] + cells[1:], lines,
      TRIANGLE, LINE)
write("duplicate_node_id.msh", nodes + [(5, 0.7, 0.3, 0.0)], cells, lines,
      TRIANGLE, LINE)
write("degenerate_cell.msh",
      [(i, x, y, z) if i != 5 else (i, 1.0, 0.0, 0.0) for (i, x, y, z) in nodes],
      cells, lines, TRIANGLE, LINE)
write("collinear.msh", *triangles(2, squash=True), TRIANGLE, LINE)
write("huge.msh", *triangles(2, scale=1e300), TRIANGLE, LINE)
write("tiny.msh", *triangles(2, scale=1e-300), TRIANGLE, LINE)
# [0,1]^2 as two triangles, [1,2]x[0,1] as four with a node at (1, 0.5).
write("hanging_vertex.msh",
      [(1, 0, 0, 0), (2, 1, 0, 0), (3, 2, 0, 0), (4, 0, 1, 0), (5, 1, 1, 0),
       (6, 2, 1, 0), (7, 1, 0.5, 0), (8, 2, 0.5, 0)],
      [(1, 2, 5), (1, 5, 4), (2, 3, 8), (2, 8, 7), (7, 8, 6), (7, 6, 5)],
      [(0, (1, 4)), (1, (3, 8)), (1, (8, 6)), (2, (1, 2)), (2, (2, 3)),
       (3, (4, 5)), (3, (5, 6))], TRIANGLE, LINE)
# Two unit squares side by side, each with its own nodes on x = 1.
write("coincident_nodes.msh",
      [(1, 0, 0, 0), (2, 1, 0, 0), (3, 0, 1, 0), (4, 1, 1, 0), (5, 1, 0, 0),
       (6, 2, 0, 0), (7, 1, 1, 0), (8, 2, 1, 0)],
      [(1, 2, 4), (1, 4, 3), (5, 6, 8), (5, 8, 7)],
      [(0, (1, 3)), (1, (6, 8)), (2, (1, 2)), (2, (5, 6)), (3, (3, 4)),
       (3, (7, 8))], TRIANGLE, LINE)

nodes, cells, faces = hexahedra(2)
write("good_hexahedra.msh", nodes, cells, faces, HEXAHEDRON, QUADRILATERAL)
top = cells[0]
write("twisted_hexahedron.msh", nodes,
      [top[:4] + (top[5], top[4], top[6], top[7])] + cells[1:], faces,
      HEXAHEDRON, QUADRILATERAL)
# [0,1]^3 as one hexahedron, [1,2]x[0,1]^2 as 2 x 2 x 2 (ids from 100).
big_nodes, big_cells, big_faces = hexahedra(1)
small_nodes, small_cells, small_faces = hexahedra(2, origin=1.0, first_id=100)
# The small block's nodes on x = 1 that coincide with the big one's corners
# are the big one's.
corner = {(round(x, 9), round(y, 9), round(z, 9)): i
          for (i, x, y, z) in big_nodes}
rename = {}
for (i, x, y, z) in small_nodes:
    key = (round(x, 9), round(y, 9), round(z, 9))
    if key in corner:
        rename[i] = corner[key]
small_nodes = [n for n in small_nodes if n[0] not in rename]
small_cells = [tuple(rename.get(i, i) for i in c) for c in small_cells]
small_faces = [(t, tuple(rename.get(i, i) for i in ids))
               for (t, ids) in small_faces if t != 0]
write("hanging_face_3d.msh", big_nodes + small_nodes, big_cells + small_cells,
      [f for f in big_faces if f[0] != 1] + small_faces, HEXAHEDRON,
      QUADRILATERAL)
# The unit cube cut along its diagonal plane x = y into two wedges (Gmsh's
# node order: the bottom triangle, then the top one); no boundary faces
# (the cell type is refused before they are looked at).
cube = [(1, 0, 0, 0), (2, 1, 0, 0), (3, 1, 1, 0), (4, 0, 1, 0),
        (5, 0, 0, 1), (6, 1, 0, 1), (7, 1, 1, 1), (8, 0, 1, 1)]
write("wedge.msh", cube, [(1, 2, 3, 5, 6, 7), (1, 3, 4, 5, 7, 8)], [],
      WEDGE, QUADRILATERAL)
