#!/bin/bash
# Runs the program on a parameter file and compares its terminal output with
# a stored reference using numdiff with the stated tolerances. On N > 1
# ranks the header names other solvers and partitions, so only the lines
# that must not depend on the partition are compared: the steps, the final
# state and norms, and the rows of a convergence table.
#   run_regression.sh EXECUTABLE PRM REFERENCE ABSOLUTE_TOLERANCE RELATIVE_TOLERANCE [N]
set -u
executable=$1 prm=$2 reference=$3 absolute=$4 relative=$5 n=${6:-1}

# The program refuses an output directory with an earlier run's files:
# start from a clean one, as a repeated ctest run finds the last one's.
rm -rf results output
"$(dirname "$0")/run_mpi.sh" "$n" "$executable" "$prm" > output.txt 2> error.txt
status=$?
if [ $status -ne 0 ]; then
  echo "The program failed with exit status $status on $n rank(s):"
  cat error.txt
  exit 1
fi
# The step lines end with the progress of the run in brackets (its wall
# times differ from run to run), which the comparison leaves out.
sed -i -e 's/  \[[^]]*\]$//' output.txt
if [ "$n" -gt 1 ]; then
  pattern='^Step +[0-9]+  t =|^  final (state|contact):|^Final displacement|^ +1/[0-9]+ '
  grep -E "$pattern" "$reference" > expected.txt
  grep -E "$pattern" output.txt > observed.txt
  if [ ! -s observed.txt ] || \
     [ "$(wc -l < expected.txt)" -ne "$(wc -l < observed.txt)" ]; then
    echo "The run printed $(wc -l < observed.txt) comparable lines, $reference $(wc -l < expected.txt)."
    exit 1
  fi
else
  # Method = auto's reason names its cost estimates and this machine's
  # memory, which the unit tests check (CostModel): here the back end it
  # chose is compared, not the estimates.
  estimates='s/\(Method = auto: .*\)$/(Method = auto)/'
  sed -E "$estimates" "$reference" > expected.txt
  sed -E "$estimates" output.txt > observed.txt
fi
if ! numdiff -q -a "$absolute" -r "$relative" -s ' \t\n=,:;<>[](){}^' \
     expected.txt observed.txt > /dev/null; then
  echo "Output differs from $reference beyond -a $absolute -r $relative on $n rank(s):"
  numdiff -a "$absolute" -r "$relative" -s ' \t\n=,:;<>[](){}^' \
    expected.txt observed.txt | head -40
  exit 1
fi
echo "Output matches $reference on $n rank(s) (numdiff -a $absolute -r $relative)."
