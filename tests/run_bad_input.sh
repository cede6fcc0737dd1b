#!/bin/bash
# Runs the program on a parameter file that must be rejected: the run must
# fail (non-zero exit status), write nothing into its output directory, and
# print the message given on the file's first line as "# expect: MESSAGE".
#   run_bad_input.sh EXECUTABLE PRM
set -u
executable=$1 prm=$2
expected=$(sed -n '1s/^# expect: //p' "$prm")
rm -rf results

"$executable" "$prm" > stdout.txt 2> stderr.txt
status=$?
if [ $status -eq 0 ]; then
  echo "The program accepted $prm; it must reject it."
  exit 1
fi
if ! grep -qF -- "$expected" stderr.txt; then
  echo "The error message does not contain <$expected>:"
  cat stderr.txt
  exit 1
fi
if [ -e results ]; then
  echo "The rejected run wrote into its output directory."
  exit 1
fi
echo "Rejected with exit status $status and the expected message."
