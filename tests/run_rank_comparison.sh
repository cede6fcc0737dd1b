#!/bin/bash
# Runs the same scene on 1 and on 2 MPI ranks and compares the results:
# time_series.csv (all columns but the wall time) and the final displacement
# norms the run prints, by numdiff with the given tolerances. The iterative
# solves stop at a relative residual; their results differ between
# partitions by about that much, far below the tolerance.
#   run_rank_comparison.sh EXECUTABLE PRM ABSOLUTE RELATIVE
set -u
here=$(dirname "$0")
executable=$1 prm=$2 absolute=$3 relative=$4

for n in 1 2; do
  rm -rf "ranks_$n"
  mkdir -p "ranks_$n"
  (cd "ranks_$n" && "$here/run_mpi.sh" "$n" "$executable" "$prm" > output.txt 2> error.txt)
  status=$?
  if [ $status -ne 0 ]; then
    echo "The program failed with exit status $status on $n rank(s):"
    cat "ranks_$n/error.txt"
    exit 1
  fi
  csv=$(find "ranks_$n" -name time_series.csv | head -1)
  if [ -z "$csv" ]; then
    echo "No time_series.csv written on $n rank(s)."
    exit 1
  fi
  cut -d, -f1-8 "$csv" | tr ',' ' ' > "ranks_$n/series.txt"
  grep '^Final displacement' "ranks_$n/output.txt" > "ranks_$n/norm.txt"
  if [ "$(wc -l < "ranks_$n/series.txt")" -lt 2 ] || [ ! -s "ranks_$n/norm.txt" ]; then
    echo "The run on $n rank(s) wrote no time series or no final norm."
    exit 1
  fi
done
for file in series.txt norm.txt; do
  if ! numdiff -q -a "$absolute" -r "$relative" -s ' \t\n=,:;' \
       ranks_1/$file ranks_2/$file > /dev/null; then
    echo "$file differs between 1 and 2 ranks beyond -a $absolute -r $relative:"
    numdiff -a "$absolute" -r "$relative" -s ' \t\n=,:;' ranks_1/$file ranks_2/$file | head -30
    exit 1
  fi
done
# Parallel output: one .pvtu record per output step, listed in solution.pvd.
if grep -q '^ *set Write vtu *= *true' "$prm"; then
  pvd=$(find ranks_2 -name solution.pvd | head -1)
  n_pvtu=$(find ranks_2 -name 'solution_*.pvtu' | wc -l)
  if [ -z "$pvd" ] || [ "$n_pvtu" -lt 2 ] || \
     [ "$(grep -c '\.pvtu' "$pvd")" -ne "$n_pvtu" ]; then
    echo "The run on 2 ranks did not write its .pvtu records and solution.pvd."
    exit 1
  fi
fi
echo "1 and 2 ranks agree: $(($(wc -l < ranks_1/series.txt) - 1)) steps of time_series.csv and $(cat ranks_1/norm.txt) (numdiff -a $absolute -r $relative)."
