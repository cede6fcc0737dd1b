#!/bin/bash
# Step cycles (nested iteration in every step, doc/algorithm.md) change where
# each step's active-set iteration starts, not the results. The scene runs
# as it is (with its Step cycles = L > 0) and with Step cycles = 0, on the
# ranks of its line "# ranks: N" (default 1). Both runs must give the same
# time series (all columns but the active-set iterations, the wall time and
# the Krylov iterations), the same contact profiles and final norms, by
# numdiff absolute 1e-8, relative 1e-8 (or those of a line "# tolerance:
# ABSOLUTE RELATIVE", for an iterative back end's solver tolerance). The run with step cycles must say so
# in its header, count active-set iterations on its coarser meshes in its
# summary, and take fewer active-set iterations than the run without them
# (the scenes are chosen so that the front of the rigid zone crosses several
# rows of nodes per step). A scene with Step cycles = auto names the number
# auto must choose in a line "# auto chooses: L", and its header must give
# auto's reason. A line "# iterations at most: N" bounds the active-set
# iterations of the run with step cycles (the observed count with a margin:
# where the coarser meshes miss a law's state, the start they give is off
# and the count grows). With a line "# pieces tied at u_n = 0" the time
# series counts the unilateral and the compliance nodes together: where a
# cohesive law meets the unilateral constraint at u_n = 0 both pieces give
# r = 0, and a node that sits there within the solver's tolerance goes to
# either. The contact profiles and the final line still name each node's
# piece: a scene with such a node at a profile time or at the end would
# fail.
#   run_step_cycles.sh EXECUTABLE PRM
set -u
here=$(dirname "$0")
executable=$1 prm=$2
read -r absolute relative < <(sed -n 's/^# tolerance: *//p' "$prm")
absolute=${absolute:-1e-8} relative=${relative:-1e-8}
ranks=$(sed -n 's/^# ranks: //p' "$prm")
most=$(sed -n 's/^# iterations at most: //p' "$prm")
tied=$(grep -c '^# pieces tied at u_n = 0' "$prm")
export RANKS=${ranks:-1}

cycles=$(sed -n 's/^ *set Step cycles *= *\([0-9a-z]*\).*/\1/p' "$prm")
reason=
if [ "$cycles" = auto ]; then
  cycles=$(sed -n 's/^# auto chooses: //p' "$prm")
  reason=".*(Step cycles = auto: "
fi
if [ -z "$cycles" ] || [ "$cycles" -eq 0 ]; then
  echo "$prm sets no Step cycles > 0 (nor auto with '# auto chooses: L')."
  exit 1
fi
"$here/run_scene_variant.sh" cycles "$executable" "$prm" || exit 1
"$here/run_scene_variant.sh" none "$executable" "$prm" \
  "s/^\( *set Step cycles *=\).*/\1 0/" || exit 1

header="Step cycles: every step.* solved on $cycles coarser mesh$reason"
grep -q "^$header" cycles/output.txt || {
  echo "The run with Step cycles = ${reason:+auto choosing }$cycles does not print '$header' in its header."
  exit 1
}
coarse=$(sed -n 's/^  step cycles: \([0-9]*\) active-set iterations.*/\1/p' cycles/output.txt)
if [ -z "$coarse" ] || [ "$coarse" -eq 0 ]; then
  echo "The run summary counts no active-set iterations on the coarser meshes."
  exit 1
fi
if grep -q "^  step cycles:" none/output.txt; then
  echo "The run with Step cycles = 0 reports step cycles in its summary."
  exit 1
fi

for dir in cycles none; do
  cut -d, -f1,2,4-8,11- "$dir/results/time_series.csv" | tr ',' ' ' \
    | awk -v tied="$tied" '{ if (tied > 0) { $3 = (NR == 1 ? "in_contact" : $3 + $4); $4 = "" } print }' \
    > "$dir/series.txt"
  grep '^  final state:\|^  final contact:\|^Final displacement:' "$dir/output.txt" > "$dir/final.txt"
  if [ "$(wc -l < "$dir/final.txt")" -ne 3 ] || [ "$(wc -l < "$dir/series.txt")" -lt 2 ]; then
    echo "The $dir run printed no final state or wrote no time series to compare."
    exit 1
  fi
done
"$here/compare_scene_variants.sh" --profiles cycles none \
  "with and without step cycles" $absolute $relative \
  series.txt final.txt || exit 1

total() { sed -n 's/^  active-set iterations: \([0-9]*\).*/\1/p' "$1/output.txt"; }
with=$(total cycles) without=$(total none)
if [ -z "$with" ] || [ -z "$without" ] || [ "$with" -ge "$without" ]; then
  echo "With Step cycles = $cycles the run took ${with:-?} active-set iterations, against ${without:-?} without them."
  exit 1
fi
if [ -n "$most" ] && [ "$with" -gt "$most" ]; then
  echo "With Step cycles = $cycles the run took $with active-set iterations, more than the $most its scene allows."
  exit 1
fi
echo "Step cycles = $cycles: the same results (time series, contact profiles, final norms; numdiff -a $absolute -r $relative); $with active-set iterations on the mesh of the run (and $coarse on the coarser meshes) against $without without them."
