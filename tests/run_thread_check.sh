#!/bin/bash
# Runs the same scene with DEAL_II_NUM_THREADS = 1 and 2 (one MPI rank) and
# requires identical results: the time series (all columns but the wall
# time), the contact profiles and the final state the run prints must agree
# character by character. The threads of the stress update only share the
# work at the stress points; the loads are added in cell order, so not even
# the round-off may change.
#   run_thread_check.sh EXECUTABLE PRM
set -u
executable=$1 prm=$2

for threads in 1 2; do
  rm -rf "threads_$threads"
  mkdir -p "threads_$threads"
  (cd "threads_$threads" && DEAL_II_NUM_THREADS=$threads \
     "$executable" "$prm" > output.txt 2> error.txt)
  status=$?
  if [ $status -ne 0 ]; then
    echo "The program failed with exit status $status on $threads thread(s):"
    cat "threads_$threads/error.txt"
    exit 1
  fi
  csv="threads_$threads/output/time_series.csv"
  if [ ! -s "$csv" ] || [ "$(wc -l < "$csv")" -lt 3 ]; then
    echo "No time series written with $threads thread(s)."
    exit 1
  fi
  # Every column but wall_time (the 9th).
  cut -d, -f1-8,10- "$csv" > "threads_$threads/series.txt"
  grep -E '^  final (state|contact):|^Final displacement' \
    "threads_$threads/output.txt" > "threads_$threads/final.txt"
  cat threads_"$threads"/output/contact_profile_*.csv \
    > "threads_$threads/profiles.txt" 2> /dev/null
done
for file in series.txt final.txt profiles.txt; do
  if ! cmp -s "threads_1/$file" "threads_2/$file"; then
    echo "$file differs between 1 and 2 threads:"
    diff "threads_1/$file" "threads_2/$file" | head -20
    exit 1
  fi
done
echo "1 and 2 threads give identical results ($(wc -l < threads_1/series.txt) lines of time series)."
