#!/bin/bash
# Values at the ends of the doubles' range that the entries accept:
#  - a Friction coefficient (Coulomb) or Slip bound (Tresca) of 1e-200 or
#    1e-320 holds nothing the arithmetic resolves: the sliding block
#    (parameters/sliding_block.prm, 2D, and sliding_block_3d.prm) on both
#    back ends must end with exit status 0 and the contact states, forces
#    and reactions of the frictionless block (numdiff -a 1e-12 -r 1e-9);
#  - a Gap direction of (0, -1e300) or (0, -1e-300) is the direction
#    (0, -1): the 2D block with each must end as with (0, -1) (the same
#    numbers, numdiff -a 1e-14 -r 1e-12).
#   run_extreme_values.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
parameters=$here/../parameters
rm -rf runs && mkdir -p runs

# The block of FILE with the sed EDIT on Method into runs/NAME/; prints the
# columns of its time series that must agree (no wall time, no Krylov
# iterations) into runs/NAME.csv.
block() { # FILE NAME METHOD EDIT
  local prm=runs/$2.prm
  sed -e "$4" -e "s|^\( *set Output directory *=\).*|\1 runs/$2|" \
    "$parameters/$1" > "$prm"
  printf 'subsection Linear solver\n  set Method = %s\nend\n' "$3" >> "$prm"
  printf 'subsection Output\n  set Write vtu = false\nend\n' >> "$prm"
  "$executable" "$prm" > "runs/$2.txt" 2> "runs/$2.err"
  local status=$?
  [ $status -eq 0 ] || fail "$2: exit status $status: $(grep -v '^ *iteration' "runs/$2.err" | head -4)"
  ! grep -qi "nan\|inf" "runs/$2/time_series.csv" \
    || fail "$2: nan or inf in the time series."
  # step, time, iterations and counts, force, von Mises; the columns after
  # wall_time and krylov_iterations (contact area, peak pressure, the
  # reactions), without the friction columns, which only frictional runs
  # have.
  local columns
  columns=$(head -1 "runs/$2/time_series.csv" | tr ',' '\n' \
    | grep -n -v -E '^(wall_time|krylov_iterations|stick_nodes|slip_nodes|tangential_force.*)$' \
    | cut -d: -f1 | paste -sd,)
  cut -d, -f"$columns" "runs/$2/time_series.csv" > "runs/$2.csv"
}
same() { # NAME REFERENCE ABSOLUTE RELATIVE
  numdiff -q -a "$3" -r "$4" -s ' \t\n,' "runs/$2.csv" "runs/$1.csv" > /dev/null \
    || fail "$1 differs from $2: $(numdiff -a "$3" -r "$4" -s ' \t\n,' "runs/$2.csv" "runs/$1.csv" | head -6)"
}

frictionless='s/^\( *set Tangential law *=\).*/\1 frictionless/;/Friction coefficient/d'
tresca='s/^\( *set Tangential law *=\).*/\1 Tresca\n  set Slip bound = VALUE/'
for file in sliding_block.prm sliding_block_3d.prm; do
  for method in condensed "full space"; do
    stem=$(basename "$file" .prm)_$(echo "$method" | tr ' ' '_')
    block "$file" "${stem}_frictionless" "$method" "$frictionless"
    for value in 1e-200 1e-320; do
      block "$file" "${stem}_coulomb_$value" "$method" \
        "s/^\( *set Friction coefficient *=\).*/\1 $value/"
      same "${stem}_coulomb_$value" "${stem}_frictionless" 1e-12 1e-9
      block "$file" "${stem}_tresca_$value" "$method" \
        "$(echo "$tresca" | sed "s/VALUE/$value/");/Friction coefficient/d"
      same "${stem}_tresca_$value" "${stem}_frictionless" 1e-12 1e-9
    done
  done
done

direction='/^subsection Contact$/a\  set Gap direction = VALUE'
block sliding_block.prm direction_unit condensed "$(echo "$direction" | sed 's/VALUE/0, -1/')"
for value in "0, -1e300" "0, -1e-300" "0, -1.7e308"; do
  name=direction_$(echo "$value" | tr -d ' ,')
  block sliding_block.prm "$name" condensed "$(echo "$direction" | sed "s/VALUE/$value/")"
  same "$name" direction_unit 1e-14 1e-12
done
echo "A Friction coefficient or Slip bound of 1e-200 and 1e-320 (2D, 3D, both back ends) ends as the frictionless block; a Gap direction of (0, -1e300), (0, -1e-300) and (0, -1.7e308) as (0, -1)."
