#!/bin/bash
# Normal compliance with memory (parameters/memory_column.prm): a column in
# uniaxial strain, its top pushed down by D = 0.01 and held, on a layer
# p = c1 r + m, m = h1 + h2 the memory of the kernel
# b(t) = a1 exp(-lambda1 t) + a2. The column carries K (D - r),
# K = M / L; in every step the scheme takes
#   h_k,n = exp(-lambda_k k_n) h_k,n-1 + a_k (1 - exp(-lambda_k k_n)) / lambda_k r_n-1
# (a_k k_n r_n-1 for lambda_k = 0), r_0 = 0, and
#   r_n = (K D - m_n) / (K + c1),  P_n = K (D - r_n).
# This recurrence is what the discrete solution satisfies to round-off (the
# displacement is linear, in the space of every element), with each step's
# own k_n: the contact force P_n, the peak pressure, the reaction of the top
# -P_n, and in every profile u_nu = r_n and memory_pressure = m_n at every
# node, in each variant:
#  - quadrilaterals, plane strain, condensed, 1 rank (the shipped file);
#  - triangles, plane stress (M = E / (1 - nu^2)), full space, 2 ranks;
#  - hexahedra, matrix-free, 1 rank; tetrahedra, condensed, 2 ranks;
#  - adaptive time steps (each step's own k_n), quadrilaterals, full space;
#  - an adaptive mesh (quadrilaterals, condensed, 2 ranks): the memory is
#    carried to the refined and coarsened cells;
#  - two bodies (a pad on a base, non-matching meshes) joined by the layer
#    with memory: both sides' profiles.
# With "quick" as second argument (the Debug build): the first two.
#   run_memory_column.sh EXECUTABLE [quick]
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 quick=${2:-}
prm=$here/../parameters/memory_column.prm

# check_recurrence K AREA TOLERANCE NAME: K the column's stiffness M / L
# (modulus: "stress" plane stress, "strain" 3D and plane strain, or a
# number), AREA the contact area; every contact and opposite profile.
check_recurrence() {
  awk -F, -v model="$1" -v area="$2" -v tol="$3" -v name="$4" '
    function near(a, b) { d = a - b; if (d < 0) d = -d
                          m = b < 0 ? -b : b; return d <= tol * (m > 1 ? m : 1) }
    BEGIN { E = 1000; nu = 0.3; D = 0.01; c1 = 1000
            a1 = 500; l1 = 2; a2 = 100
            K = model == "stress" ? E / (1 - nu * nu) \
              : model == "strain" ? E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) : model + 0
            h1 = 0; h2 = 0; r = 0 }
    FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    FILENAME ~ /time_series/ {
      k = $col["time_step"]
      h1 = exp(-l1 * k) * h1 + a1 * (1 - exp(-l1 * k)) / l1 * r
      h2 = h2 + a2 * k * r
      m = h1 + h2; r = (K * D - m) / (K + c1); P = K * (D - r)
      memory[$col["time"]] = m; penetration[$col["time"]] = r
      if (!near($col["total_contact_force"], P * area) || !near($col["peak_pressure"], P) \
          || !near($col["reaction_prescribed_1_y"], -P * area)) {
        print name ": at t = " $col["time"] " force " $col["total_contact_force"] ", peak " \
              $col["peak_pressure"] ", reaction " $col["reaction_prescribed_1_y"] "; expected " P " per unit area"; exit 1 }
      next }
    FILENAME ~ /profile/ {
      t = $col["time"]
      if (!(t in memory)) { print name ": profile time " t " is no step"; exit 1 }
      if (!near($col["memory_pressure"], memory[t]) || !near($col["u_nu"] * 1000, penetration[t] * 1000) \
          || !near($col["contact_pressure"], K * (D - penetration[t]))) {
        print name ": at t = " t " in " FILENAME " memory " $col["memory_pressure"] ", u_nu " $col["u_nu"] \
              ", pressure " $col["contact_pressure"] "; expected " memory[t] ", " penetration[t]; exit 1 }
      ++rows }
    END { if (rows == 0) { print name ": no profile rows"; exit 1 } }
    ' results/time_series.csv results/*profile_*.csv || exit 1
}
source "$here/column_variants.sh"

variant hypercube condensed > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, condensed"
check_recurrence strain 1 1e-9 "2D quadrilaterals, condensed"
grep -q "memory_pressure" results/solution_0003.0.vtu \
  || fail "2D quadrilaterals: no memory_pressure field in the VTU file"
variant simplex "full space" | plane_stress > variant.prm
run_scene variant.prm 2 "2D triangles, plane stress, full space, 2 ranks"
check_recurrence stress 1 1e-8 "2D triangles, plane stress, full space, 2 ranks"
if [ "$quick" = quick ]; then
  echo "The memory column follows the scheme's recurrence on quadrilaterals (condensed) and triangles (full space, 2 ranks)."
  exit 0
fi

variant hypercube "matrix free" | three_d > variant.prm
run_scene variant.prm 1 "3D hexahedra, matrix-free"
check_recurrence strain 1 1e-8 "3D hexahedra, matrix-free"
variant simplex condensed | three_d > variant.prm
run_scene variant.prm 2 "3D tetrahedra, condensed, 2 ranks"
check_recurrence strain 1 1e-9 "3D tetrahedra, condensed, 2 ranks"
# Adaptive steps: the elastic column has no history error, so the steps
# grow from 0.0625 to the Maximum time step, each with its own k_n.
variant hypercube "full space" \
  | sed -e 's/^\(subsection Time\)$/\1\n  set Time step control = adaptive\n  set Maximum time step = 0.5/' \
  | set_entry "Time step" 0.03125 | set_entry "Profile times" "1, 2" > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, adaptive time steps"
check_recurrence strain 1 1e-8 "2D quadrilaterals, adaptive time steps"
[ "$(awk -F, 'NR > 1 { print $11 }' results/time_series.csv | sort -u | wc -l)" -ge 3 ] \
  || fail "adaptive time steps: fewer than 3 different step lengths"
# An adaptive mesh: refined every 8 steps, the memory travels with the
# cells (the new contact nodes get it interpolated).
variant hypercube condensed \
  | sed -e 's/^\(subsection Output\)$/subsection Mesh adaptation\n  set Adaptive refinement = true\n  set Refinement interval = 8\n  set Refine fraction = 0.5\nend\n\n\1/' > variant.prm
run_scene variant.prm 2 "2D quadrilaterals, adaptive mesh, 2 ranks"
check_recurrence strain 1 1e-9 "2D quadrilaterals, adaptive mesh, 2 ranks"
grep -q "Mesh adapted\|adapted" out.txt || fail "adaptive mesh: the mesh was never adapted"

# Two bodies: the layer with memory as the interface of a pad (E = 500) on
# a base (E = 1000), each 1 high and 2 wide, on non-matching meshes
# (parameters/two_block_patch_test.prm, the right sides free: uniaxial
# stress), K = 1 / (1 / 1000 + 1 / 500) per unit area, on both sides of
# the pair (the opposite profile averages the memory by the mortar
# weights).
sed -e "s|^\( *set Mesh file *= *\)\.\./|\1$here/../|" "$here/../parameters/two_block_patch_test.prm" \
  | set_entry "Normal compliance" true | set_entry "Unilateral constraint" false \
  | set_entry "Layer thickness" 0.1 | set_entry Displacement -0.01 \
  | sed -e 's/^\(  set Layer thickness.*\)$/\1\n  set Law = piecewise linear\n  set Breakpoints = 0\n  set Slopes = 0, 1000\n  set Memory weights = 500, 100\n  set Memory rates = 2, 0/' \
  | set_entry "End time" 1 | set_entry "Time step" 0.0625 | set_entry "Profile times" "0.5, 1" \
  | set_entry "Output directory" results > variant.prm
run_scene variant.prm 2 "two bodies, condensed, 2 ranks"
check_recurrence 333.3333333333333 2 1e-9 "two bodies, condensed, 2 ranks"
[ -e results/opposite_profile_0016.csv ] || fail "two bodies: no opposite profile"

echo "The memory column follows the scheme's recurrence exactly in 7 variants (all cell types, three back ends, 1 and 2 ranks, plane strain and stress, adaptive steps and meshes, two bodies)."
