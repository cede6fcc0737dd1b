#!/bin/bash
# A punch dragged across a slip-weakening surface
# (parameters/weakening_punch.prm, weakening_punch_3d.prm), with a contact
# profile at every step, checked by tests/check_weakening_punch.py: every
# node's traction against mu(S) p with its own accumulated slip S, in
# every step; the friction force the sum of the nodes', at the static
# value when the drag starts and between the dynamic and the static value
# after it. 2D (cylinder) with the condensed back end on 1 rank and the
# full space back end on 2; 3D (sphere, 16 x 4 x 4 cubes without the
# refinement toward the top, the first 4 steps of the drag) with the full
# space back end on 2 ranks (the matrix-free back end's slip weakening:
# tests/run_sliding_block.sh).
#   run_weakening_punch.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
# A profile at every step up to STEPS: t = 0.0625 k.
every_step() {
  awk -v n="$1" 'BEGIN { for (k = 1; k <= n; ++k) printf "%s%g", (k > 1 ? ", " : ""), 0.0625 * k }'
}

for variant in 2:condensed:1 2:full_space:2 3:full_space:2; do
  IFS=: read -r dim method ranks <<< "$variant"
  name="weakening punch ${dim}D, ${method/_/ }, $ranks rank(s)"
  tolerance=1e-9
  [ $method = condensed ] || tolerance=1e-7
  if [ $dim = 2 ]; then
    set_entry "Profile times" "$(every_step 32)" < "$here/../parameters/weakening_punch.prm"
  else
    set_entry "Contact refinement levels" 0 < "$here/../parameters/weakening_punch_3d.prm" \
      | set_entry "End time" 1.25 | set_entry "Profile times" "$(every_step 20)"
  fi | set_entry "Output directory" results > variant.prm
  printf '\nsubsection Linear solver\n  set Method = %s\nend\n' "${method/_/ }" >> variant.prm
  run_scene variant.prm $ranks "$name"
  /usr/bin/python3 "$here/check_weakening_punch.py" "$name" results $tolerance || exit 1
done
echo "A punch dragged across a slip-weakening surface: every node at mu(S) p in every step (2D and 3D, condensed and full space, 1 and 2 ranks)."
