#!/bin/bash
# Adhesion with a bonding field (parameters/adhesion_column.prm): a column
# in uniaxial strain glued to a rigid base, its top pulled up by V t. The
# column carries P = K (V t - s), K = M / H, s = -r the separation; the glue
# gamma beta^2 min(s, L). In every step the scheme takes
#   beta_n = (beta_n-1 + k_n kappa epsilon) / (1 + k_n kappa gamma min(s_n-1, L)^2)
#   where beta_n-1 gamma min(s_n-1, L)^2 > epsilon (else beta_n-1),
# beta_0 = 1, s_0 = 0, and
#   s_n = K V t_n / (K + gamma beta_n^2), or V t_n - gamma beta_n^2 L / K
#   where the first exceeds L;  P_n = K (V t_n - s_n).
# This recurrence is what the discrete solution satisfies to round-off (the
# displacement is linear, in the space of every element), with each step's
# own k_n: the contact force -P_n, the reaction of the top P_n, and in every profile u_nu = -s_n, bonding = beta_n and the
# pressure -P_n at every node, in each variant:
#  - quadrilaterals, plane strain, condensed, 1 rank (the shipped file);
#  - triangles, plane stress (M = E / (1 - nu^2)), full space, 2 ranks;
#  - hexahedra, matrix-free, 1 rank; tetrahedra, condensed, 2 ranks;
#  - adaptive time steps (each step's own k_n), quadrilaterals, full space;
#  - an adaptive mesh (quadrilaterals, condensed, 2 ranks): the bonding is
#    carried to the refined and coarsened cells;
#  - two bodies (a pad on a base, non-matching meshes) held by the glue.
# Then the bonding only decreases (irreversible) in the profiles, and
# Initial bonding = 0 leaves the column free (no force at all).
# With "quick" as second argument (the Debug build): the first two.
#   run_adhesion_column.sh EXECUTABLE [quick]
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 quick=${2:-}
prm=$here/../parameters/adhesion_column.prm

# check_recurrence K AREA TOLERANCE NAME [PROFILES]: K the column's
# stiffness M / H (modulus: "stress" plane stress, "strain" 3D and plane
# strain, or a number), AREA the contact area.
check_recurrence() {
  awk -F, -v model="$1" -v area="$2" -v tol="$3" -v name="$4" '
    function near(a, b) { d = a - b; if (d < 0) d = -d
                          m = b < 0 ? -b : b; return d <= tol * (m > 1 ? m : 1) }
    BEGIN { E = 1000; nu = 0.3; V = 0.02; gamma = 1000; L = 0.01; eps = 0.001; kappa = 10
            K = model == "stress" ? E / (1 - nu * nu) \
              : model == "strain" ? E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) : model + 0
            beta = 1; s = 0 }
    FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    FILENAME ~ /time_series/ {
      k = $col["time_step"]; t = $col["time"]
      R = s < L ? s : L
      if (beta * gamma * R * R > eps) beta = (beta + k * kappa * eps) / (1 + k * kappa * gamma * R * R)
      a = gamma * beta * beta; s = K * V * t / (K + a)
      if (s > L) s = V * t - a * L / K
      P = K * (V * t - s)
      bonding[t] = beta; separation[t] = s
      if (!near($col["total_contact_force"], -P * area) \
          || !near($col["reaction_prescribed_1_y"], P * area)) {
        print name ": at t = " t " force " $col["total_contact_force"] ", reaction " \
              $col["reaction_prescribed_1_y"] "; expected a tension of " P " per unit area"; exit 1 }
      next }
    FILENAME ~ /profile/ {
      t = $col["time"]
      if (!(t in bonding)) { print name ": profile time " t " is no step"; exit 1 }
      if (!near($col["bonding"], bonding[t]) || !near($col["u_nu"] * 1000, -separation[t] * 1000) \
          || !near($col["contact_pressure"], -K * (V * t - separation[t]))) {
        print name ": at t = " t " in " FILENAME " bonding " $col["bonding"] ", u_nu " $col["u_nu"] \
              ", pressure " $col["contact_pressure"] "; expected " bonding[t] ", " -separation[t]; exit 1 }
      ++rows }
    END { if (rows == 0) { print name ": no profile rows"; exit 1 } }
    ' results/time_series.csv results/contact_profile_*.csv || exit 1
}
source "$here/column_variants.sh"

variant hypercube condensed > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, condensed"
check_recurrence strain 1 1e-9 "2D quadrilaterals, condensed"
grep -q "bonding" results/solution_0003.0.vtu \
  || fail "2D quadrilaterals: no bonding field in the VTU file"
# Irreversible: the bonding of every node never grows from profile to
# profile, and it has fallen below 0.3 by t = 2.
awk -F, 'FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
         { key = $1 "," $2; b = $col["bonding"]
           if (key in last && b > last[key]) { print "the bonding grew at " key; exit 1 }
           last[key] = b; final = b }
         END { if (final >= 0.3) { print "the bond did not give way: beta = " final; exit 1 } }' \
  results/contact_profile_0016.csv results/contact_profile_0032.csv results/contact_profile_0064.csv \
  || fail "2D quadrilaterals: bonding"
variant simplex "full space" | plane_stress > variant.prm
run_scene variant.prm 2 "2D triangles, plane stress, full space, 2 ranks"
check_recurrence stress 1 1e-8 "2D triangles, plane stress, full space, 2 ranks"
if [ "$quick" = quick ]; then
  echo "The adhesion column follows the scheme's recurrence on quadrilaterals (condensed) and triangles (full space, 2 ranks)."
  exit 0
fi

variant hypercube "matrix free" | three_d > variant.prm
run_scene variant.prm 1 "3D hexahedra, matrix-free"
check_recurrence strain 1 1e-8 "3D hexahedra, matrix-free"
variant simplex condensed | three_d > variant.prm
run_scene variant.prm 2 "3D tetrahedra, condensed, 2 ranks"
check_recurrence strain 1 1e-9 "3D tetrahedra, condensed, 2 ranks"
# Adaptive steps: the elastic column has no history error, so the steps
# grow to the Maximum time step, each with its own k_n.
variant hypercube "full space" \
  | sed -e 's/^\(subsection Time\)$/\1\n  set Time step control = adaptive\n  set Maximum time step = 0.25/' \
  | set_entry "Time step" 0.03125 | set_entry "Profile times" "1, 2" > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, adaptive time steps"
check_recurrence strain 1 1e-8 "2D quadrilaterals, adaptive time steps"
[ "$(awk -F, 'NR > 1 { print $11 }' results/time_series.csv | sort -u | wc -l)" -ge 3 ] \
  || fail "adaptive time steps: fewer than 3 different step lengths"
# An adaptive mesh: refined every 16 steps, the bonding travels with the
# cells (the new contact nodes get it interpolated).
variant hypercube condensed \
  | sed -e 's/^\(subsection Output\)$/subsection Mesh adaptation\n  set Adaptive refinement = true\n  set Refinement interval = 16\n  set Refine fraction = 0.5\nend\n\n\1/' > variant.prm
run_scene variant.prm 2 "2D quadrilaterals, adaptive mesh, 2 ranks"
check_recurrence strain 1 1e-9 "2D quadrilaterals, adaptive mesh, 2 ranks"
grep -q "Mesh adapted" out.txt || fail "adaptive mesh: the mesh was never adapted"

# Two bodies: the glue as the interface of a pad (E = 500) on a base
# (E = 1000), each 1 high and 2 wide, on non-matching meshes
# (parameters/two_block_patch_test.prm, the right sides free: uniaxial
# stress), K = 1 / (1 / 1000 + 1 / 500) per unit area.
sed -e "s|^\( *set Mesh file *= *\)\.\./|\1$here/../|" "$here/../parameters/two_block_patch_test.prm" \
  | set_entry Displacement "0.02 * t" \
  | sed -e 's/^\(  set Layer thickness.*\)$/\1\n  set Adhesion stiffness = 1000\n  set Adhesion length = 0.01\n  set Adhesion energy = 0.001\n  set Debonding rate = 10/' \
  | set_entry "End time" 2 | set_entry "Time step" 0.0625 | set_entry "Profile times" "1, 2" \
  | set_entry "Output directory" results > variant.prm
run_scene variant.prm 2 "two bodies, condensed, 2 ranks"
check_recurrence 333.3333333333333 2 1e-9 "two bodies, condensed, 2 ranks"
# The opposite side's profiles: a row for every header column, the
# pressure of the glue on the base.
awk -F, 'FNR == 1 { n = NF; for (i = 1; i <= NF; ++i) col[$i] = i; next }
         NF != n { print FILENAME ": " NF " values under " n " columns"; exit 1 }
         $col["contact_pressure"] >= 0 { print FILENAME ": no tension at x = " $1; exit 1 }
         { ++rows } END { if (rows == 0) { print "no opposite profile rows"; exit 1 } }' \
  results/opposite_profile_*.csv || fail "two bodies: opposite profiles"

# Nothing glued: the column comes off freely.
variant hypercube condensed | set_entry "Initial bonding" 0 > variant.prm
run_scene variant.prm 1 "not glued"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
         $col["total_contact_force"] != 0 { print "force " $col["total_contact_force"] " at t = " $col["time"]; exit 1 }' \
  results/time_series.csv || fail "not glued: the column is held"

echo "The adhesion column follows the scheme's recurrence exactly in 7 variants (all cell types, three back ends, 1 and 2 ranks, plane strain and stress, adaptive steps and meshes, two bodies); the bonding only falls."
