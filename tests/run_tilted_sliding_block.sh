#!/bin/bash
# Friction on an oblique plane of symmetry (parameters/tilted_sliding_block_3d.prm):
# the unit cube rotated so that no face is axis-aligned, resting on its
# face Y = 0, its face Z = 0 a plane of symmetry, pressed and then dragged
# along e_X by its top. The contact nodes on the plane move in it: their
# normal and tangential rows on the two free dofs are neither unit vectors
# nor orthogonal, and each back end must read their forces right.
# Checked (tests/check_tilted_sliding_block.py): the closed form in every
# step (N = E D, the friction force along e_X balancing the top, below
# mu N, full slip at mu N with each node's slip the top's increment) on
# hexahedra with all three back ends, 1 and 2 ranks, and on tetrahedra;
# on hexahedra the tilted run equals the axis-aligned one (the same mesh,
# turned) node by node, in the partial slip at t = 1.375 too. A back end
# that reads the forces with the rows instead of their dual rows fails:
# N comes out as 9.96.
# With "quick" as second argument (the Debug build): two variants.
#   run_tilted_sliding_block.sh EXECUTABLE [quick]
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 quick=${2:-}
prm=$here/../parameters/tilted_sliding_block_3d.prm
check() { /usr/bin/python3 "$here/check_tilted_sliding_block.py" "$@" || exit 1; }

# The axis-aligned block: the unit cube of 2 x 2 x 2 cells (the mesh file's
# cells before the rotation), support y = 0 (id 2), plane of symmetry z = 0
# (id 4), top y = 1 (id 3).
sed -e '/set Mesh file/d' \
    -e 's|^\( *set Cell type *=.*\)|  set Lengths      = 1, 1, 1\n  set Subdivisions = 2\n\1|' \
    -e 's|^\( *set Contact boundary ids *=\).*|\1 2|' \
    -e 's|^\( *set Symmetry boundary ids *=\).*|\1 4|' \
    -e 's|^\( *set Boundary ids *=\).*|\1 3|' \
    -e '/set Displacement =/,/[^\\]$/c\    set Displacement = 0.02 * max(t - 1, 0); -0.01 * min(t, 1); 0' \
    "$prm" | set_entry "Output directory" results > aligned.prm
run_scene aligned.prm 1 "axis-aligned block"
rm -rf aligned && mv results aligned

variants="hexahedron:condensed:1 hexahedron:full_space:2 hexahedron:matrix_free:1 tetrahedron:full_space:2 tetrahedron:condensed:1"
[ "$quick" = quick ] && variants="hexahedron:full_space:1 tetrahedron:condensed:2"
for variant in $variants; do
  IFS=: read -r mesh method ranks <<< "$variant"
  cell=hypercube
  [ $mesh = tetrahedron ] && cell=simplex
  name="tilted block, $mesh, ${method/_/ }, $ranks rank(s)"
  sed -e "s|\.\./meshes/tilted_block_hexahedron_2|$here/../meshes/tilted_block_${mesh}_2|" "$prm" \
    | set_entry "Cell type" $cell | set_entry Method "${method/_/ }" \
    | set_entry "Output directory" results > variant.prm
  run_scene variant.prm $ranks "$name"
  if [ $mesh = hexahedron ]; then check "$name" results aligned; else check "$name" results --simplex; fi
done
echo "Friction on an oblique plane of symmetry: the tilted sliding block meets the closed form and the axis-aligned block's values node by node (three back ends, hexahedra and tetrahedra, 1 and 2 ranks)."
