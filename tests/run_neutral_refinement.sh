#!/bin/bash
# A refinement that changes nothing physical leaves the results unchanged:
# the parameter file (Adaptive refinement = true) describes a scene whose
# exact solution the mesh reproduces (a linear displacement, uniform
# stresses and history: neutral_refinement/*.prm). It runs as it is and with
# Adaptive refinement = false; the adapted run must have changed its mesh,
# and both must give the same time series (all columns but the wall time and
# the Krylov iterations), the same final norms of eps(u) and sigma and the
# same maximum of u (the l2 norm of the dof vector depends on the number of
# dofs and is not compared), by numdiff absolute 1e-12, relative 1e-10.
#   run_neutral_refinement.sh EXECUTABLE PRM
set -u
here=$(dirname "$0")
executable=$1 prm=$2
absolute=1e-12 relative=1e-10

"$here/run_scene_variant.sh" adapted "$executable" "$prm" || exit 1
"$here/run_scene_variant.sh" fixed "$executable" "$prm" \
  "s/^\( *set Adaptive refinement *=\).*/\1 false/" || exit 1
for dir in adapted fixed; do
  cut -d, -f1-8 "$dir/results/time_series.csv" | tr ',' ' ' > "$dir/series.txt"
  { grep '^  final state:' "$dir/output.txt"
    sed -n 's/^Final displacement: .*\(max norm .*\)/\1/p' "$dir/output.txt"; } > "$dir/final.txt"
done
n_adaptations=$(grep -c '^Mesh adapted at' adapted/output.txt)
if [ "$n_adaptations" -lt 1 ] || grep -q '^Mesh adapted at' fixed/output.txt; then
  echo "The adapted run did not change its mesh (or the fixed one did)."
  exit 1
fi
"$here/compare_scene_variants.sh" adapted fixed \
  "between the adapted and the fixed mesh" $absolute $relative \
  series.txt final.txt || exit 1
echo "$n_adaptations adaptations ($(grep '^Mesh adapted at' adapted/output.txt | tail -1 | sed 's/.*: //')) leave the results unchanged: $(($(wc -l < adapted/series.txt) - 1)) steps of time_series.csv and $(cat adapted/final.txt | tr '\n' ' ')(numdiff -a $absolute -r $relative)."
