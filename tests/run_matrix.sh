#!/bin/bash
# One row of the test matrix: the scene PRM with every back end that runs
# it (Method = condensed and full space; matrix free too on hypercube cells
# with the explicit update) on N MPI ranks. Each run must match the stored
# reference REFERENCE (the condensed back end on one rank) step by step, and
# the runs must match each other:
#   - per step: step, time, nodes at the rigid limit, in compliance
#     contact, out of contact (exactly), total contact force;
#   - the final state: ||eps(u)||, ||sigma||, max von Mises, the final
#     contact counts and force, the l2 and max norms of u;
#   numdiff -a ABSOLUTE -r RELATIVE;
#   - the contact profiles of the two back ends (rows sorted: on several
#     ranks each rank writes its own block), the same tolerances;
#   - the last .vtu record holds the displacement, the stresses and the
#     contact fields (pressure, its layer and foundation parts, status).
#   run_matrix.sh EXECUTABLE PRM REFERENCE N ABSOLUTE RELATIVE
set -u
here=$(dirname "$0")
executable=$1 prm=$2 reference=$3 n=$4 absolute=$5 relative=$6

steps() {
  grep -E '^Step +[0-9]+  t =' "$1" | awk '{print $2, $5, $10, $12, $15, $18}'
}
final_state() {
  grep -E '^  final (state|contact):|^Final displacement' "$1"
}
compare() { # what, file a, file b
  if [ ! -s "$2" ] || [ "$(wc -l < "$2")" -ne "$(wc -l < "$3")" ]; then
    echo "$1: $2 has $(wc -l < "$2") lines, $3 has $(wc -l < "$3")."
    exit 1
  fi
  if ! numdiff -q -a "$absolute" -r "$relative" -s ' \t\n=,:;' "$2" "$3" > /dev/null; then
    echo "$1 differ beyond -a $absolute -r $relative ($2 against $3):"
    numdiff -a "$absolute" -r "$relative" -s ' \t\n=,:;' "$2" "$3" | head -30
    exit 1
  fi
}

steps "$reference" > reference_steps.txt
final_state "$reference" > reference_final.txt
methods=(condensed "full space")
if grep -qE '^ *set Cell type *= *hypercube' "$prm" \
  && grep -qE '^ *set Stress update *= *explicit' "$prm"; then
  methods+=("matrix free")
fi
for method in "${methods[@]}"; do
  dir=${method// /_}
  rm -rf "$dir"
  mkdir -p "$dir"
  sed -e "s/^\( *set Method *=\).*/\1 $method/" "$prm" > "$dir/scene.prm"
  (cd "$dir" && "$here/run_mpi.sh" "$n" "$executable" scene.prm > output.txt 2> error.txt)
  status=$?
  if [ $status -ne 0 ]; then
    echo "Method = $method failed on $n rank(s) with exit status $status:"
    cat "$dir/error.txt"
    exit 1
  fi
  steps "$dir/output.txt" > "$dir/steps.txt"
  final_state "$dir/output.txt" > "$dir/final.txt"
  compare "Steps of Method = $method" reference_steps.txt "$dir/steps.txt"
  compare "Final state of Method = $method" reference_final.txt "$dir/final.txt"

  vtu=$(ls "$dir"/results/solution_*.vtu 2>/dev/null | tail -1)
  for field in displacement stress_xx viscoplastic_stress_xx von_mises_stress \
               contact_pressure compliance_pressure foundation_pressure contact_status; do
    if [ -z "$vtu" ] || ! grep -q "Name=\"$field\"" "$vtu"; then
      echo "Method = $method: the field $field is missing in ${vtu:-the .vtu output}."
      exit 1
    fi
  done
  profiles=$(ls "$dir"/results/contact_profile_*.csv 2>/dev/null | wc -l)
  if [ "$profiles" -eq 0 ]; then
    echo "Method = $method wrote no contact profile."
    exit 1
  fi
  for profile in "$dir"/results/contact_profile_*.csv; do
    tail -n +2 "$profile" | sort > "$profile.sorted"
  done
done
for method in "${methods[@]:1}"; do
  dir=${method// /_}
  compare "Steps of Method = condensed and $method" condensed/steps.txt \
    "$dir/steps.txt"
  for profile in condensed/results/contact_profile_*.csv; do
    compare "Contact profiles of Method = condensed and $method" \
      "$profile.sorted" "$dir/results/$(basename "$profile").sorted"
  done
done
echo "The ${#methods[@]} back ends on $n rank(s) match $(basename "$reference") and each other: $(wc -l < reference_steps.txt) steps, final state, profiles; .vtu fields present."
