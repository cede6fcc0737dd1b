#!/bin/bash
# The predicted start of a step (Predicted start, doc/algorithm.md) changes
# the iterations, not the results. The scene runs as it is (Predicted
# start = true, the default) and with Predicted start = false.
#   unique:   the step problem has one solution. Both runs must give the
#             same time series (all columns but the active-set iterations,
#             the wall time and the Krylov iterations), the same contact
#             profiles and final norms, by numdiff absolute 1e-8, relative
#             1e-8, and the predicted run must take fewer active-set
#             iterations in all (Newton iterations with the implicit
#             update) and no more Krylov iterations.
#   several:  the uniqueness check warns that the step problem may have
#             several solutions, so the contact nodes keep the previous
#             step's pieces: with the condensed back end (which does not use
#             the displacement as a start) the two runs must agree in
#             everything but the wall time, iteration counts included.
#   run_predicted_start.sh EXECUTABLE PRM unique|several
set -u
here=$(dirname "$0")
executable=$1 prm=$2 expect=$3
absolute=1e-8 relative=1e-8

"$here/run_scene_variant.sh" predicted "$executable" "$prm" || exit 1
"$here/run_scene_variant.sh" previous "$executable" "$prm" \
  "s/^\( *subsection Active set solver\)/\1\n  set Predicted start = false/" || exit 1
if ! grep -q "^ *set Predicted start = false" previous/scene.prm; then
  echo "$prm has no subsection <Active set solver> to switch the predicted start off in."
  exit 1
fi
if [ "$expect" = several ]; then
  columns=1-8,10-
  grep -q '^WARNING: the contact law softens more' predicted/output.txt || {
    echo "$prm was to be a scene whose step problem may have several solutions, but the program did not warn."
    exit 1
  }
else
  columns=1,2,4-8,11-
fi
for dir in predicted previous; do
  cut -d, -f$columns "$dir/results/time_series.csv" | tr ',' ' ' > "$dir/series.txt"
  grep '^  final state:\|^  final contact:\|^Final displacement:' "$dir/output.txt" > "$dir/final.txt"
done
"$here/compare_scene_variants.sh" --profiles predicted previous \
  "with and without the predicted start" $absolute $relative \
  series.txt final.txt || exit 1

# The totals of the run summary: active-set (or Newton) and Krylov iterations.
total() { # directory, pattern of the summary line
  sed -n "s/^  $2: \([0-9]*\).*/\1/p" "$1/output.txt" | head -1
}
krylov() { sed -n 's/^  back end: .* \([0-9]*\) Krylov iterations.*/\1/p' "$1/output.txt"; }
counter='active-set iterations'
grep -q '^  Newton iterations' predicted/output.txt && counter='Newton iterations (implicit scheme)'
with=$(total predicted "$counter") without=$(total previous "$counter")
if [ -z "$with" ] || [ -z "$without" ]; then
  echo "The run summary has no line '$counter'."
  exit 1
fi
if [ "$expect" = unique ]; then
  if [ "$with" -ge "$without" ] || [ "$(krylov predicted)" -gt "$(krylov previous)" ]; then
    echo "The predicted start took $with $counter and $(krylov predicted) Krylov iterations, against $without and $(krylov previous) without it."
    exit 1
  fi
elif [ "$with" -ne "$without" ]; then
  echo "With several solutions possible, the predicted start changed the $counter: $with against $without."
  exit 1
fi
echo "Predicted start: the same results (time series, contact profiles, final norms; numdiff -a $absolute -r $relative); $counter $with against $without, Krylov iterations $(krylov predicted) against $(krylov previous)."
