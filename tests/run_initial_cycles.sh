#!/bin/bash
# Nested iteration on the first step does not change the results: the
# parameter file (Initial cycles = L, Initial refinement = global) describes
# the last mesh of the cycles; it runs as it is and with Initial cycles = 0,
# on the same mesh. The step problem has a unique solution, so the warm start
# from the coarser meshes must not change it: both runs must give the same
# time series (all columns but the active-set iterations, the wall time and
# the Krylov iterations), the same contact profiles and the same final norms,
# by numdiff absolute 1e-8, relative 1e-8 (or those of a line "# tolerance:
# ABSOLUTE RELATIVE", for an iterative back end's solver tolerance). The
# cycled run must have printed
# L cycles, and its step 1 on the last mesh must take fewer active-set
# iterations than the cold start. With Initial cycles = auto, the file names
# the L the program must choose ("# expect cycles: L"), and the header must
# say why.
# The runs take the ranks of the file's "# ranks: N" line (1 if none).
#   run_initial_cycles.sh EXECUTABLE PRM
set -u
here=$(dirname "$0")
executable=$1 prm=$2
read -r absolute relative < <(sed -n 's/^# tolerance: *//p' "$prm")
absolute=${absolute:-1e-8} relative=${relative:-1e-8}
cycles=$(sed -n 's/^ *set Initial cycles *= *\([0-9a-z]*\).*/\1/p' "$prm")
# The ranks of "# ranks: N" (1 if none).
RANKS=$(sed -n 's/^# ranks: *\([0-9]*\).*/\1/p' "$prm" | head -1)
export RANKS=${RANKS:-1}
automatic=false
if [ "$cycles" = auto ]; then
  automatic=true
  cycles=$(sed -n 's/^# expect cycles: *\([0-9]*\).*/\1/p' "$prm")
fi

"$here/run_scene_variant.sh" cycles "$executable" "$prm" || exit 1
"$here/run_scene_variant.sh" direct "$executable" "$prm" \
  "s/^\( *set Initial cycles *=\).*/\1 0/" || exit 1
for dir in cycles direct; do
  cut -d, -f1,2,4-8,11,12 "$dir/results/time_series.csv" | tr ',' ' ' > "$dir/series.txt"
  { grep '^  final state:\|^  final contact:\|^Final displacement:' "$dir/output.txt"; } > "$dir/final.txt"
done

n_cycles=$(grep -c '^Initial cycle [0-9]' cycles/output.txt)
if [ "$n_cycles" -ne "$cycles" ] || grep -q '^Initial cycle' direct/output.txt; then
  echo "The cycled run printed $n_cycles initial cycles, not $cycles (or the direct one printed some)."
  exit 1
fi
if $automatic && ! grep -q "^Initial cycles: step 1 on $cycles coarser meshes .*(Initial cycles = auto: " cycles/output.txt; then
  echo "The header does not say that Initial cycles = auto chose $cycles cycles, and why."
  exit 1
fi
if ! grep -q "^  initial cycles: .* on $cycles coarser meshes" cycles/output.txt; then
  echo "The run summary does not count the initial cycles apart."
  exit 1
fi
"$here/compare_scene_variants.sh" --profiles cycles direct \
  "with and without initial cycles" $absolute $relative \
  series.txt final.txt || exit 1
# Step 1's active-set iterations on the last mesh (column 3 of its row).
warm=$(awk -F, 'NR == 2 {print $3}' cycles/results/time_series.csv)
cold=$(awk -F, 'NR == 2 {print $3}' direct/results/time_series.csv)
if [ -z "$warm" ] || [ -z "$cold" ] || [ "$warm" -ge "$cold" ]; then
  echo "Step 1 on the last mesh took $warm active-set iterations after the initial cycles, not fewer than the $cold of the cold start: the warm start carried nothing over."
  exit 1
fi
echo "$cycles initial cycles ($(grep '^Initial cycle [0-9]' cycles/output.txt | sed 's/^Initial cycle [0-9]*: //' | tr '\n' ';')) leave the results unchanged (time series, contact profiles, final norms; numdiff -a $absolute -r $relative); step 1 on the last mesh: $warm active-set iterations against $cold cold."
