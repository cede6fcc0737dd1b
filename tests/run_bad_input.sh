#!/bin/bash
# Runs the program on a parameter file that must be rejected: the run must
# fail (non-zero exit status), write nothing into its output directory, and
# print the message given on the file's first line as "# expect: MESSAGE"
# (and the text of any further line "# expect also: TEXT", which deal.II's
# messages on several lines need), once, without MPI_Abort on several ranks.
# A line "# ranks: N" runs it on N MPI ranks.
# With a third argument "failing-solve" the run may have written output
# before it stopped (a solve that fails during the time loop), and it must
# have written the last accepted state as results/failed_step_*.vtu.
#   run_bad_input.sh EXECUTABLE PRM [failing-solve]
set -u
executable=$1 prm=$2 kind=${3:-bad-input}
expected=$(sed -n '1s/^# expect: //p' "$prm")
mapfile -t also < <(sed -n 's/^# expect also: //p' "$prm")
ranks=$(sed -n 's/^# ranks: //p' "$prm")
rm -rf results

"$(dirname "$0")/run_mpi.sh" "${ranks:-1}" "$executable" "$prm" > stdout.txt 2> stderr.txt
status=$?
if [ $status -eq 0 ]; then
  echo "The program accepted $prm; it must reject it."
  exit 1
fi
# Exactly 1: a crash, an abort or a sanitizer's report has another status.
if [ $status -ne 1 ]; then
  echo "The program stopped with exit status $status, not 1:"
  cat stderr.txt
  exit 1
fi
for text in "$expected" "${also[@]}"; do
  if ! grep -qF -- "$text" stderr.txt; then
    echo "The error message does not contain <$text>:"
    cat stderr.txt
    exit 1
  fi
done
if [ "$kind" = bad-input ] && [ -e results ]; then
  echo "The rejected run wrote into its output directory."
  exit 1
fi
# All ranks stop on the error in order: the message once, no MPI_Abort
# (Open MPI's banner).
if [ "$(grep -c '^Error:' stderr.txt)" -ne 1 ] || grep -q MPI_ABORT stderr.txt; then
  echo "The error is not reported once, or the ranks were aborted:"
  cat stderr.txt
  exit 1
fi
# A failed solve writes the last accepted state for inspection.
if [ "$kind" = failing-solve ]; then
  state=$(find results -name 'failed_step_*.vtu' 2>/dev/null | head -1)
  if [ -z "$state" ]; then
    echo "The failed solve wrote no failed_step_*.vtu."
    exit 1
  fi
fi
echo "Stopped with exit status $status and the expected message."
