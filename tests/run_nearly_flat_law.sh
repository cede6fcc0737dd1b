#!/bin/bash
# Every monotone law the entries accept converges, down to nearly flat
# branches (doc/algorithm.md, "The dense contact problem"): the benchmark at
# h = 1/8 with c2 = 1e-6 and 1e-300 (after the layer's first branch the
# pressure barely grows) on both back ends must end with exit status 0, no
# nan or inf in the time series, and the contact states and forces of
# c2 = 0 with the condensed back end (numdiff relative 1e-6: the force w c2 r that c2 adds is below
# 1e-8 of the forces).
#   run_nearly_flat_law.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
rm -rf runs && mkdir -p runs
for method in condensed "full space"; do
  for c2 in 0 1e-6 1e-300; do
    name=$(echo "${method}_$c2" | tr ' ' '_')
    set_entry c2 "$c2" < "$base" | set_entry "Output directory" "runs/$name" \
      | set_entry "Write vtu" false | set_entry "Checkpoint interval" 0 > "runs/$name.prm"
    printf 'subsection Linear solver\n  set Method = %s\nend\n' "$method" >> "runs/$name.prm"
    "$executable" "runs/$name.prm" > "runs/$name.txt" 2> "runs/$name.err"
    status=$?
    [ $status -eq 0 ] || fail "c2 = $c2 with $method: exit status $status: $(tail -5 "runs/$name.err")"
    ! grep -qi "nan\|inf" "runs/$name/time_series.csv" \
      || fail "c2 = $c2 with $method: nan or inf in the time series."
    cut -d, -f1,2,4-8 "runs/$name/time_series.csv" > "runs/$name.csv"
    reference=runs/condensed_0.csv
    [ "runs/$name.csv" = "$reference" ] && continue
    numdiff -q -a 1e-12 -r 1e-6 -s ' \t\n,' "$reference" "runs/$name.csv" > /dev/null \
      || fail "c2 = $c2 with $method differs from c2 = 0: $(numdiff -a 1e-12 -r 1e-6 -s ' \t\n,' "$reference" "runs/$name.csv" | head -5)"
  done
done
echo "Nearly flat branches (c2 = 1e-6, 1e-300) converge on both back ends, as c2 = 0."
