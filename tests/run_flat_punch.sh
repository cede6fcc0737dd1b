#!/bin/bash
# A rigid flat punch (parameters/flat_punch.prm): half-width b = 0.25 (its
# edge on a node), pressed into an elastic block by d(t) = 0.01 t. Checked
# against Sadowsky's pressure under a flat punch on a half-plane,
#   p(x) = P / (pi sqrt(b^2 - x^2)),   P = twice the half model's force:
#  - every node under the punch's face (x <= b) is at the rigid limit and
#    none beside it;
#  - away from the edges (x <= b / 2) the pressure has Sadowsky's shape,
#    p(x) pi sqrt(b^2 - x^2) / P within 1.5 times the observed deviation
#    from 1: 2.0% on quadrilaterals, 3.1% on triangles (observed 1.36% and
#    2.04%, which the finite block and the lumped edge node, carrying the
#    singular part, make);
#  - elastic, so P(t = 1) = 2 P(t = 0.5) to 1e-9;
# on quadrilaterals (condensed, 1 rank) and triangles (full space, 2 ranks).
#   run_flat_punch.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1

# The last field: 1.5 times the largest observed deviation from
# Sadowsky's shape at x <= b / 2.
for variant in "hypercube condensed 1 0.0204" "simplex full_space 2 0.0306"; do
  set -- $variant
  name="flat punch, $1, ${2/_/ }, $3 rank(s)"
  # Triangles have no hanging nodes in deal.II 9.4: a uniform mesh of h =
  # 1/64 instead of h = 1/32 refined twice toward the top.
  mesh="set_entry Subdivisions 32"
  [ $1 = simplex ] && mesh="set_entry Subdivisions 64"
  set_entry "Cell type" $1 < "$here/../parameters/flat_punch.prm" | $mesh \
    | set_entry "Contact refinement levels" $([ $1 = simplex ] && echo 0 || echo 2) \
    | set_entry Method "${2/_/ }" | set_entry "Output directory" results > variant.prm
  run_scene variant.prm $3 "$name"
  force=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    { f[NR - 1] = $col["total_contact_force"] }
    END { d = f[2] - 2 * f[1]; if (d < 0) d = -d; if (d > 1e-9 * f[2]) print "bad"; else print 2 * f[2] }' \
    results/time_series.csv)
  [ "$force" != bad ] || fail "$name: the force is not linear in d: $(cat results/time_series.csv)"
  awk -F, -v P="$force" -v name="$name" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    { x = $col["x"]; p = $col["contact_pressure"]; s = $col["status"]
      if (x <= 0.25 + 1e-9 && s != 2) { print name ": the node at x = " x " is not at the punch"; exit 1 }
      if (x > 0.25 + 1e-9 && s != 0) { print name ": the node at x = " x " touches beside the punch"; exit 1 }
      if (x <= 0.125 + 1e-9) {
        shape = p * 3.141592653589793 * sqrt(0.0625 - x * x) / P
        deviation = shape > 1 ? shape - 1 : 1 - shape
        if (deviation > largest) largest = deviation
        if (deviation > bound) { print name ": p pi sqrt(b^2 - x^2) / P = " shape " at x = " x ", more than " bound " from 1"; exit 1 }
        ++n } }
    END { if (n < 8) { print name ": only " n " nodes with x <= b / 2"; exit 1 }
          printf "%s: the shape within %.4f of 1 (bound %.4f).\n", name, largest, bound }' \
    bound=$4 results/contact_profile_*.csv || exit 1
done
echo "Flat punch: the contact is the punch face, the pressure has Sadowsky's shape away from the edges (within 1.5 times the observed 1.4% and 2.0%), the force is linear in d (quadrilaterals condensed, triangles full space on 2 ranks)."
