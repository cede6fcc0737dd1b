#!/bin/bash
# Runs a convergence study and checks the observed order of the total error
# between the two finest runs of its convergence.csv (and that the errors
# decrease from run to run).
#   run_order_check.sh EXECUTABLE PRM MINIMUM_ORDER
set -u
executable=$1 prm=$2 minimum=$3
rm -rf results
if ! "$executable" "$prm" > stdout.txt 2> stderr.txt; then
  echo "The study failed:"; cat stderr.txt; exit 1
fi
awk -F, -v minimum="$minimum" '
  NR == 1 { for (i = 1; i <= NF; ++i) column[$i] = i; next }
  { error[NR] = $column["error"]; order[NR] = $column["order"]; last = NR }
  END {
    for (i = 3; i <= last; ++i)
      if (!(error[i] < error[i - 1])) { print "error does not decrease at row " i; exit 1 }
    if (!(order[last] >= minimum)) { print "order " order[last] " < " minimum; exit 1 }
    print "errors decrease; finest observed order " order[last] " >= " minimum
  }' results/convergence.csv
