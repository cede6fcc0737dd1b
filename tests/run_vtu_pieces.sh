#!/bin/bash
# A rank's cells go into its .vtu file in pieces of at most 2^18 cells
# (robustness/vtu_record.cc, write_vtu_record()). On one rank and more cells than that:
#  - the last .vtu file has more than one <Piece>;
#  - read by meshio (Debian's python3-meshio), the pieces together have
#    4 points per quadrilateral of the "Mesh:" line (every cell written
#    once), and the largest displacement component is the "max norm" of
#    the program's "Final displacement" line (relative 1e-6: the .vtu
#    stores single precision).
#   run_vtu_pieces.sh EXECUTABLE PRM
set -u
executable=$1 prm=$2
fail() { echo "$*"; exit 1; }
rm -rf results
"$executable" "$prm" > output.txt 2>&1 || { cat output.txt; fail "The run failed."; }
cells=$(sed -n 's/^Mesh: \([0-9]*\) Quad cells.*/\1/p' output.txt)
max_norm=$(sed -n 's/^Final displacement: .*max norm \(.*\)$/\1/p' output.txt)
vtu=$(ls results/solution_*.vtu | tail -1)
[ -n "$cells" ] && [ -n "$max_norm" ] && [ -n "$vtu" ] ||
  fail "No Mesh line, Final displacement line or .vtu file in the run."
pieces=$(grep -a -c "<Piece " "$vtu")
[ "$pieces" -ge 2 ] || fail "$vtu has $pieces piece(s), expected 2 or more."
/usr/bin/python3 - "$vtu" "$cells" "$max_norm" <<'PYTHON' || exit 1
import sys
import meshio
import numpy as np
vtu, cells, max_norm = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
mesh = meshio.read(vtu)
largest = np.abs(mesh.point_data["displacement"]).max()
print(f"{vtu}: {len(mesh.points)} points for {cells} cells; largest "
      f"displacement component {largest:.9g}, the run's max norm {max_norm:.9g}")
if len(mesh.points) != 4 * cells:
    sys.exit("Expected 4 points per cell.")
if abs(largest - max_norm) > 1e-6 * max_norm:
    sys.exit("The largest displacement differs from the run's.")
PYTHON
echo "$vtu: $pieces pieces, every cell once, the run's displacement."
