#!/bin/bash
# Runs the program on N MPI ranks and compares, step by step, the contact
# states and the total contact force it prints with a reference output of
# another run (another solver, or the same scene axis-aligned):
#   columns compared: step, time, nodes at the rigid limit, in compliance
#   contact, out of contact (exactly), total contact force (numdiff with
#   the given tolerances).
#   run_cross_check.sh EXECUTABLE PRM REFERENCE N ABSOLUTE RELATIVE
set -u
here=$(dirname "$0")
executable=$1 prm=$2 reference=$3 n=$4 absolute=$5 relative=$6

# The program refuses an output directory with an earlier run's files:
# start from a clean one, as a repeated ctest run finds the last one's.
rm -rf results output
"$here/run_mpi.sh" "$n" "$executable" "$prm" > output.txt 2> error.txt
status=$?
if [ $status -ne 0 ]; then
  echo "The program failed with exit status $status on $n rank(s):"
  cat error.txt
  exit 1
fi
extract() {
  grep -E '^Step +[0-9]+  t =' "$1" | awk '{print $2, $5, $10, $12, $15, $18}'
}
extract "$reference" > expected.txt
extract output.txt > observed.txt
if [ ! -s observed.txt ] || \
   [ "$(wc -l < expected.txt)" -ne "$(wc -l < observed.txt)" ]; then
  echo "The run printed $(wc -l < observed.txt) steps, the reference $(wc -l < expected.txt)."
  exit 1
fi
if ! numdiff -q -a "$absolute" -r "$relative" expected.txt observed.txt > /dev/null; then
  echo "Contact states or forces differ from $reference beyond -a $absolute -r $relative"
  echo "(step, t, rigid, compliance, no contact, force):"
  numdiff -a "$absolute" -r "$relative" expected.txt observed.txt | head -40
  exit 1
fi
echo "$(wc -l < observed.txt) steps on $n rank(s) match $reference (numdiff -a $absolute -r $relative)."

# A header line "# Krylov iterations per solve at most: X" bounds the
# back end's Krylov iterations per solve (its run summary, "back end: S
# solves, K Krylov iterations").
bound=$(sed -n 's/^# Krylov iterations per solve at most: *//p' "$prm")
if [ -n "$bound" ]; then
  counts=$(sed -n 's/^ *back end: \([0-9]*\) solves, \([0-9]*\) Krylov iterations.*/\1 \2/p' output.txt)
  if [ -z "$counts" ]; then
    echo "The run printed no line \"back end: S solves, K Krylov iterations\"."
    exit 1
  fi
  read -r solves iterations <<< "$counts"
  if ! awk -v s="$solves" -v k="$iterations" -v b="$bound" 'BEGIN { exit !(k <= b * s) }'; then
    echo "$iterations Krylov iterations in $solves solves: more than $bound per solve."
    exit 1
  fi
  echo "$iterations Krylov iterations in $solves solves (at most $bound per solve)."
fi
