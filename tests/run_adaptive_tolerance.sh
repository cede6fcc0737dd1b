#!/bin/bash
# The adaptive time steps respect their tolerance (doc/adaptivity.md). The
# scene PRM (adaptive steps) runs with the Error tolerance TOL and TOL/2, and
# with fixed steps k = 1/2048 as the reference. Asserted:
#   - every accepted step's estimate (time_series.csv, error_estimate) is at
#     most its tolerance, unless the step is at Minimum time step;
#   - the steps land on the profile time 0.5 and on End time;
#   - the error against the reference, the largest relative difference of
#     the total contact force at t = 0.5 and t = 1 and of ||eps(u)||_L2 and
#     ||sigma||_L2 at t = 1, is at most FACTOR times the tolerance;
#   - halving the tolerance takes more steps and reduces that error.
#   run_adaptive_tolerance.sh EXECUTABLE PRM TOL FACTOR
set -u
here=$(dirname "$0")
executable=$1 prm=$2 tolerance=$3 factor=$4
half=$(awk -v t="$tolerance" 'BEGIN { printf "%.6g", t / 2 }')

run() { # directory, control, time step, tolerance
  rm -rf "$1" && mkdir -p "$1"
  sed -e "s/^\( *set Time step control *=\).*/\1 $2/" \
      -e "s/^\( *set Time step *=\).*/\1 $3/" \
      -e "s/^\( *set Error tolerance *=\).*/\1 $4/" "$prm" > "$1/scene.prm"
  (cd "$1" && "$here/run_mpi.sh" 1 "$executable" scene.prm > output.txt 2> error.txt)
  local status=$?
  if [ $status -ne 0 ]; then
    echo "The run in $1 failed with exit status $status:"; cat "$1/error.txt"; exit 1
  fi
}
# The compared quantities of a run: force at t = 0.5 and t = 1, ||eps(u)||,
# ||sigma||.
quantities() {
  awk -F, '$2 == 0.5 { f05 = $7 } $2 == 1 { f1 = $7 } END { print f05, f1 }' \
    "$1/results/time_series.csv"
  sed -n 's/.*||eps(u)||_L2 = \([^,]*\), ||sigma||_L2 = \([^,]*\),.*/\1 \2/p' \
    "$1/output.txt"
}
run reference fixed 0.00048828125 "$tolerance"
run coarse adaptive 0.0625 "$tolerance"
run fine adaptive 0.0625 "$half"
quantities reference | tr '\n' ' ' > reference/q.txt
errors=()
for dir in coarse fine; do
  tol=$(sed -n 's/^ *set Error tolerance *= *//p' "$dir/scene.prm")
  minimum=$(sed -n 's/^ *set Minimum time step *= *//p' "$dir/scene.prm")
  # Every accepted step within the tolerance (or at the minimum step).
  if ! awk -F, -v tol="$tol" -v minimum="${minimum:-1e-6}" '
       NR > 1 && $12 > tol && $11 > minimum * (1 + 1e-12) { print "step " $1 ": estimate " $12 " > " tol; bad = 1 }
       END { exit bad }' "$dir/results/time_series.csv"; then
    echo "Error tolerance = $tol: a step above the tolerance was accepted."; exit 1
  fi
  # Landing on the profile time and on End time.
  for t in 0.5 1; do
    awk -F, -v t="$t" '$2 == t { found = 1 } END { exit !found }' "$dir/results/time_series.csv" \
      || { echo "Error tolerance = $tol: no step ends at t = $t."; exit 1; }
  done
  quantities "$dir" | tr '\n' ' ' > "$dir/q.txt"
  error=$(paste -d' ' reference/q.txt "$dir/q.txt" | awk '{
    e = 0; for (i = 1; i <= 4; ++i) { d = ($i - $(i + 4)) / $i; if (d < 0) d = -d; if (d > e) e = d }
    printf "%.6g", e }')
  steps=$(($(wc -l < "$dir/results/time_series.csv") - 1))
  echo "Error tolerance = $tol: $steps steps, error $error against k = 1/2048"
  if ! awk -v e="$error" -v t="$tol" -v f="$factor" 'BEGIN { exit !(e <= f * t) }'; then
    echo "The error $error exceeds $factor x the tolerance $tol."; exit 1
  fi
  errors+=("$error $steps")
done
read -r e1 s1 <<< "${errors[0]}"
read -r e2 s2 <<< "${errors[1]}"
awk -v a="$e1" -v b="$e2" 'BEGIN { exit !(b < a) }' \
  || { echo "Halving the tolerance did not reduce the error ($e1 -> $e2)."; exit 1; }
[ "$s2" -gt "$s1" ] || { echo "Halving the tolerance did not add steps ($s1 -> $s2)."; exit 1; }
echo "Every step within its tolerance, landing on t = 0.5 and 1; errors $e1 (tolerance $tolerance, $s1 steps) and $e2 (tolerance $half, $s2 steps), each <= $factor x tolerance, and decreasing."
