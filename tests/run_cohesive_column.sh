#!/bin/bash
# A cohesive interface with damage (parameters/cohesive_column.prm): a
# column in uniaxial strain bonded to a rigid base, its top pulled to
# U = 0.03, pushed back to 0 and pulled to 0.06. The column carries
# P = K (U - delta), K = M / H, delta the opening; the interface the
# tension T(delta) on the secant T(m) delta / m below the largest opening m
# of the steps before, on the envelope (K_c delta up to T_c, then linear
# softening to 0 at delta_f = 2 G_c / T_c) beyond it. In every step:
#   delta_n = K U_n / (K + s), s = T(m) / m (K_c while m <= delta_0), if
#             that is at most max(m, delta_0); else on the softening piece,
#             (K U_n - T_c delta_f / (delta_f - delta_0))
#             / (K - T_c / (delta_f - delta_0)), if at most delta_f; else U_n;
#   P_n = K (U_n - delta_n), m = max(m, delta_n), damage 1 - T(m) / (K_c m).
# This is what the discrete solution satisfies to round-off (the
# displacement is linear, in the space of every element; the damage is
# rate-independent, so there is no error in k): the contact force -P_n, the
# reaction of the top P_n, and in every profile u_nu = -delta_n, the
# pressure -P_n and the damage at every node, in each variant:
#  - quadrilaterals, plane strain, condensed, 1 rank (the shipped file);
#  - triangles, plane stress (M = E / (1 - nu^2)), full space, 2 ranks;
#  - hexahedra, matrix-free, 1 rank; tetrahedra, condensed, 2 ranks;
#  - adaptive time steps (each step's own U_n), quadrilaterals, full space;
#  - an adaptive mesh (quadrilaterals, condensed, 2 ranks): the reached
#    openings are carried to the refined and coarsened cells;
#  - two bodies (a pad on a base, non-matching meshes) held by the
#    interface, with the opposite side's profiles.
#  - Cohesive damage = explicit (quadrilaterals, matrix-free): beyond
#    m* = max(m, delta_0) the step's law is the plateau T(m*), so
#    delta_n = K U_n / (K + T(m*) / m*) if that is at most m*, else
#    U_n - T(m*) / K.
# Then the damage never decreases, the unloading passes through the origin
# (the force at U = 0 is 0) and the interface is broken at the end.
# With "quick" as second argument (the Debug build): the first two.
#   run_cohesive_column.sh EXECUTABLE [quick]
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 quick=${2:-}
prm=$here/../parameters/cohesive_column.prm

# check_recurrence K AREA T_C G_C TOLERANCE NAME [explicit]: K the
# column's stiffness M / H (modulus: "stress" plane stress, "strain" 3D and
# plane strain, or a number), AREA the contact area, T_C and G_C the
# interface's strength and fracture energy (its stiffness K_c = 1000).
check_recurrence() {
  awk -F, -v model="$1" -v area="$2" -v Tc="$3" -v Gc="$4" -v tol="$5" -v name="$6" \
      -v update="${7:-implicit}" '
    function near(a, b) { d = a - b; if (d < 0) d = -d
                          m_ = b < 0 ? -b : b; return d <= tol * (m_ > 1 ? m_ : 1) }
    function T(x) { return x <= d0 ? Kc * x : (x < df ? Tc * (df - x) / (df - d0) : 0) }
    function max(a, b) { return a > b ? a : b }
    function min(a, b) { return a < b ? a : b }
    BEGIN { E = 1000; nu = 0.3; Kc = 1000; d0 = Tc / Kc; df = 2 * Gc / Tc
            K = model == "stress" ? E / (1 - nu * nu) \
              : model == "strain" ? E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) : model + 0
            m = 0 }
    FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    FILENAME ~ /time_series/ {
      t = $col["time"]
      U = 0.03 * max(min(t, 3 - 2 * t), 0) + 0.06 * max(t - 1.5, 0)
      s = m > d0 ? T(m) / m : Kc
      d = K * U / (K + s)
      if (update == "explicit" && d > max(m, d0)) d = U - T(max(m, d0)) / K
      else if (d > max(m, d0)) {
        d = (K * U - Tc * df / (df - d0)) / (K - Tc / (df - d0))
        if (d > df) d = U }
      P = K * (U - d); m = max(m, d)
      opening[t] = d; force[t] = P; damage[t] = m > d0 ? 1 - T(m) / (Kc * m) : 0
      if (!near($col["total_contact_force"], -P * area) \
          || !near($col["reaction_prescribed_1_y"], P * area)) {
        print name ": at t = " t " force " $col["total_contact_force"] ", reaction " \
              $col["reaction_prescribed_1_y"] "; expected a tension of " P " per unit area"; exit 1 }
      next }
    FILENAME ~ /profile/ {
      t = $col["time"]
      if (!(t in opening)) { print name ": profile time " t " is no step"; exit 1 }
      if (!near($col["damage"], damage[t]) || !near($col["u_nu"] * 1000, -opening[t] * 1000) \
          || !near($col["contact_pressure"], -force[t])) {
        print name ": at t = " t " in " FILENAME " damage " $col["damage"] ", u_nu " $col["u_nu"] \
              ", pressure " $col["contact_pressure"] "; expected " damage[t] ", " -opening[t] \
              ", " -force[t]; exit 1 }
      # A node that carries a tension is held by the interface (status 1),
      # also where explicit damage lags: the tension from the opening of
      # the last step at a node that has opened beyond delta_f.
      if ($col["contact_pressure"] < 0 && $col["status"] == 0) {
        print name ": at t = " t " in " FILENAME " a tension " $col["contact_pressure"] \
              " at a node of status 0"; exit 1 }
      ++rows }
    END { if (rows == 0) { print name ": no profile rows"; exit 1 } }
    ' results/time_series.csv results/contact_profile_*.csv || exit 1
}
source "$here/column_variants.sh"

variant hypercube condensed > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, condensed"
check_recurrence strain 1 10 0.2 1e-9 "2D quadrilaterals, condensed"
grep -q "damage" results/solution_0003.0.vtu \
  || fail "2D quadrilaterals: no damage field in the VTU file"
# Irreversible: the damage of every node never falls from profile to
# profile; unloaded at t = 1.5 the column carries nothing (the secant ends
# at the origin); at t = 2.5 the interface is broken (damage 1, no force).
awk -F, 'FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
         { key = $1 "," $2; D = $col["damage"]
           if (key in last && D < last[key]) { print "the damage fell at " key; exit 1 }
           if ($col["time"] == 1.5 && $col["contact_pressure"] != 0) { print "a force at U = 0"; exit 1 }
           last[key] = D; final = D }
         END { if (final != 1) { print "not broken at the end: damage " final; exit 1 } }' \
  results/contact_profile_0016.csv results/contact_profile_0024.csv results/contact_profile_0032.csv \
  results/contact_profile_0040.csv || fail "2D quadrilaterals: damage"
variant simplex "full space" | plane_stress > variant.prm
run_scene variant.prm 2 "2D triangles, plane stress, full space, 2 ranks"
check_recurrence stress 1 10 0.2 1e-8 "2D triangles, plane stress, full space, 2 ranks"
if [ "$quick" = quick ]; then
  echo "The cohesive column follows the closed form on quadrilaterals (condensed) and triangles (full space, 2 ranks)."
  exit 0
fi

variant hypercube "matrix free" | three_d > variant.prm
run_scene variant.prm 1 "3D hexahedra, matrix-free"
check_recurrence strain 1 10 0.2 1e-8 "3D hexahedra, matrix-free"
variant simplex condensed | three_d > variant.prm
run_scene variant.prm 2 "3D tetrahedra, condensed, 2 ranks"
check_recurrence strain 1 10 0.2 1e-9 "3D tetrahedra, condensed, 2 ranks"
# Adaptive steps: the elastic column has no history error, so the steps
# grow to the Maximum time step, each with its own U_n.
variant hypercube "full space" \
  | sed -e 's/^\(subsection Time\)$/\1\n  set Time step control = adaptive\n  set Maximum time step = 0.25/' \
  | set_entry "Time step" 0.03125 | set_entry "Profile times" "1, 2" > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, adaptive time steps"
check_recurrence strain 1 10 0.2 1e-8 "2D quadrilaterals, adaptive time steps"
[ "$(awk -F, 'NR > 1 { print $11 }' results/time_series.csv | sort -u | wc -l)" -ge 3 ] \
  || fail "adaptive time steps: fewer than 3 different step lengths"
# An adaptive mesh: refined every 12 steps, the reached openings travel
# with the cells (the new contact nodes get them interpolated).
variant hypercube condensed \
  | sed -e 's/^\(subsection Output\)$/subsection Mesh adaptation\n  set Adaptive refinement = true\n  set Refinement interval = 12\n  set Refine fraction = 0.5\nend\n\n\1/' > variant.prm
run_scene variant.prm 2 "2D quadrilaterals, adaptive mesh, 2 ranks"
check_recurrence strain 1 10 0.2 1e-9 "2D quadrilaterals, adaptive mesh, 2 ranks"
grep -q "Mesh adapted" out.txt || fail "adaptive mesh: the mesh was never adapted"

# The damage from the last step: the plateau in the step.
# (A profile at t = 2.1875 too: the step in which the column opens beyond
# delta_f still carries the tension of the last step's opening.)
variant hypercube "matrix free" | sed -e 's/^\(  set Fracture energy.*\)$/\1\n  set Cohesive damage = explicit/' \
  | set_entry "Profile times" "1, 1.5, 2, 2.1875, 2.5" > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, explicit damage, matrix-free"
check_recurrence strain 1 10 0.2 1e-8 "2D quadrilaterals, explicit damage, matrix-free" explicit

# Two bodies: the cohesive interface between a pad (E = 500) and a base
# (E = 1000), each 1 high and 2 wide, on non-matching meshes
# (parameters/two_block_patch_test.prm, the right sides free: uniaxial
# stress), K = 1 / (1 / 1000 + 1 / 500) per unit area; T_c = 5, so that
# the softening 5 / 0.075 stays below K.
sed -e "s|^\( *set Mesh file *= *\)\.\./|\1$here/../|" "$here/../parameters/two_block_patch_test.prm" \
  | set_entry Displacement "0.03 * max(min(t, 3 - 2 * t), 0) + 0.06 * max(t - 1.5, 0)" \
  | sed -e 's/^\(  set Layer thickness.*\)$/\1\n  set Cohesive strength = 5\n  set Cohesive stiffness = 1000\n  set Fracture energy = 0.2/' \
  | set_entry "End time" 2.5 | set_entry "Time step" 0.0625 | set_entry "Profile times" "1, 2.5" \
  | set_entry "Output directory" results > variant.prm
run_scene variant.prm 2 "two bodies, condensed, 2 ranks"
check_recurrence 333.3333333333333 2 5 0.2 1e-9 "two bodies, condensed, 2 ranks"
# The opposite side's profiles: a row for every header column, the
# tension of the interface on the base at t = 1.
awk -F, 'FNR == 1 { n = NF; for (i = 1; i <= NF; ++i) col[$i] = i; next }
         NF != n { print FILENAME ": " NF " values under " n " columns"; exit 1 }
         $col["time"] == 1 && $col["contact_pressure"] >= 0 { print FILENAME ": no tension at x = " $1; exit 1 }
         { ++rows } END { if (rows == 0) { print "no opposite profile rows"; exit 1 } }' \
  results/opposite_profile_*.csv || fail "two bodies: opposite profiles"

echo "The cohesive column follows the closed form exactly in 7 variants (all cell types, three back ends, 1 and 2 ranks, plane strain and stress, adaptive steps and meshes, two bodies) and the explicit update's recurrence; the damage only grows."
