#!/bin/bash
# Runs the program on a parameter file and compares its terminal output with
# a stored reference using numdiff with the stated tolerances.
#   run_regression.sh EXECUTABLE PRM REFERENCE ABSOLUTE_TOLERANCE RELATIVE_TOLERANCE
set -u
executable=$1 prm=$2 reference=$3 absolute=$4 relative=$5

"$executable" "$prm" > output.txt 2> error.txt
status=$?
if [ $status -ne 0 ]; then
  echo "The program failed with exit status $status:"
  cat error.txt
  exit 1
fi
if ! numdiff -q -a "$absolute" -r "$relative" -s ' \t\n=,:;<>[](){}^' \
     "$reference" output.txt > /dev/null; then
  echo "Output differs from $reference beyond -a $absolute -r $relative:"
  numdiff -a "$absolute" -r "$relative" -s ' \t\n=,:;<>[](){}^' \
    "$reference" output.txt | head -40
  exit 1
fi
echo "Output matches $reference (numdiff -a $absolute -r $relative)."
