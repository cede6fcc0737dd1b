#!/bin/bash
# Two materials (parameters/two_layer_column.prm): a stiff lower half
# (E1 = 1000) and a soft upper half (E2 = 100, nu = 0.3) of a unit column on
# a flat rigid support, rollers on the sides, the top pushed down by
# D(t) = 0.01 min(t, 2 - t). The exact state is uniaxial strain with
#   p = D / (h1/M1 + h2/M2),  h1 = h2 = 1/2,
#   M = E/(1 - nu^2) (plane stress), E(1-nu)/((1+nu)(1-2nu)) (3D),
# which the discrete solution reproduces to round-off: in every step the
# contact force is p A (A = 1), the peak pressure p, the reaction of the top
# -p A, that of each roller (a side of area 1) sigma_xx = nu p (plane
# stress) or nu / (1 - nu) p (3D, plane strain) into the body, and every
# node of the profiles has p, in each variant:
#  - the materials as regions of a function of the cell centre, on triangles
#    (condensed, 1 rank), quadrilaterals (full space, 2 ranks, one global
#    refinement: the children inherit the ids), tetrahedra and hexahedra;
#  - the materials as the physical groups of a Gmsh mesh (ids 10 and 20);
#  - plane strain (triangles, full space), where M is that of 3D;
#  - an adaptive mesh (quadrilaterals, plane strain, condensed, 2 ranks,
#    the soft layer viscoplastic): refined and coarsened cells keep their
#    material and their out-of-plane state, the state stays uniform in each
#    layer (checked as below);
#  - the soft layer viscoplastic (explicit and implicit update): the state
#    is still uniform in each layer, so every node of a profile has the same
#    pressure and the reaction is minus the contact force.
# With "quick" as second argument (the Debug build): two variants.
#   run_two_layer_column.sh EXECUTABLE [quick]
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 quick=${2:-}
prm=$here/../parameters/two_layer_column.prm

# check_exact MODEL TOLERANCE NAME: the closed form in every step and
# profile; MODEL is "stress" (2D plane stress) or "strain" (3D, plane strain).
check_exact() {
  awk -F, -v model="$1" -v tol="$2" -v name="$3" '
    function modulus(E, nu) { return model == "stress" ? E / (1 - nu * nu) : E * (1 - nu) / ((1 + nu) * (1 - 2 * nu)) }
    function near(a, b) { d = a - b; if (d < 0) d = -d
                          m = b < 0 ? -b : b; return d <= tol * (m > 1 ? m : 1) }
    BEGIN { c = 0.5 / modulus(1000, 0.3) + 0.5 / modulus(100, 0.3)
            ratio = model == "stress" ? 0.3 : 0.3 / 0.7 }
    FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    { t = $col["time"]; p = 0.01 * (t < 2 - t ? t : 2 - t) / c }
    FILENAME ~ /time_series/ {
      if (!near($col["total_contact_force"], p) || !near($col["peak_pressure"], p) \
          || !near($col["reaction_prescribed_1_y"], -p) || $col["no_contact_nodes"] != 0) {
        print name ": at t = " t " force " $col["total_contact_force"] ", peak " $col["peak_pressure"] \
              ", reaction of the top " $col["reaction_prescribed_1_y"] "; expected p = " p; exit 1 }
      # Each roller (a side of area 1) holds sigma_xx = ratio sigma_yy,
      # pushing into the body: its normal component is ratio p, every
      # other 0; two rollers per direction balance.
      pushing = 0
      for (c in col)
        if (c ~ /^reaction_symmetry_/) {
          r = $col[c] < 0 ? -$col[c] : $col[c]
          if (near(r + p, p)) continue
          if (!near(r, ratio * p)) {
            print name ": at t = " t " the roller reaction " c " is " $col[c] ", not 0 or " ratio * p " in magnitude"; exit 1 }
          pushing += $col[c] }
      if (!near(pushing + p, p)) { print name ": at t = " t " the rollers do not balance (" pushing ")"; exit 1 } }
    FILENAME ~ /profile/ {
      if (!near($col["contact_pressure"], p)) {
        print name ": pressure " $col["contact_pressure"] " at t = " t " in " FILENAME ", not " p; exit 1 } }
    ' results/time_series.csv results/contact_profile_*.csv || exit 1
}

# check_uniform NAME: one pressure per profile, the reaction minus the force.
check_uniform() {
  awk -F, -v name="$1" '
    function near(a, b) { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; return d <= 1e-9 * (m > 1 ? m : 1) }
    FNR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; p = ""; next }
    FILENAME ~ /time_series/ {
      if (!near($col["reaction_prescribed_1_y"], -$col["total_contact_force"])) {
        print name ": reaction " $col["reaction_prescribed_1_y"] " for the force " $col["total_contact_force"]; exit 1 } }
    FILENAME ~ /profile/ {
      if (p == "") p = $col["contact_pressure"]
      else if (!near($col["contact_pressure"], p)) {
        print name ": pressures " p " and " $col["contact_pressure"] " in " FILENAME; exit 1 } }
    ' results/time_series.csv results/contact_profile_*.csv || exit 1
}

# The soft layer viscoplastic (yield stress below the stress it reaches).
plastic_soft_layer() {
  sed -e '/^subsection Material 2/,/^end/{s/Plasticity *= false/Plasticity = true\n  set Yield stress = 0.5\n  set Viscosity = 10/}'
}
variant() { # CELL_TYPE METHOD > variant.prm
  set_entry "Cell type" "$1" < "$prm" | set_entry Method "$2" \
    | set_entry "Output directory" results
}
# The 3D column: rollers on x = 0, L1 and z = 0, L3.
three_d() {
  set_entry Dimension 3 | set_entry Lengths "1, 1, 1" \
    | set_entry "Symmetry boundary ids" "0, 1, 4, 5" \
    | set_entry "Body force" "0; 0; 0" | set_entry "Surface traction" "0; 0; 0"
}

variant simplex condensed > variant.prm
run_scene variant.prm 1 "2D triangles, condensed"
check_exact stress 1e-9 "2D triangles, condensed"
variant hypercube "full space" | three_d | set_entry Subdivisions 2 > variant.prm
run_scene variant.prm 1 "3D hexahedra, full space"
check_exact strain 1e-7 "3D hexahedra, full space"
if [ "$quick" = quick ]; then
  echo "The two-layer column is exact on triangles (condensed) and hexahedra (full space)."
  exit 0
fi

variant hypercube "full space" | set_entry "Global refinements" 1 > variant.prm
run_scene variant.prm 2 "2D quadrilaterals, full space, refined, 2 ranks"
check_exact stress 1e-7 "2D quadrilaterals, full space, refined, 2 ranks"
# Adaptive meshes: the cells refined and coarsened during the run keep
# their material (the interface stays a mesh line, hanging nodes on it).
variant hypercube condensed | plastic_soft_layer \
  | sed -e 's/^\(subsection Output\)$/subsection Mesh adaptation\n  set Adaptive refinement = true\n  set Refinement interval = 1\n  set Refine fraction = 0.5\nend\n\n\1/' \
        -e 's/^\(set Dimension = 2\)$/\1\nset Plane model = plane strain/' > variant.prm
run_scene variant.prm 2 "2D quadrilaterals, plane strain, adaptive mesh, 2 ranks"
check_uniform "2D quadrilaterals, plane strain, adaptive mesh, 2 ranks"
variant simplex condensed | three_d | set_entry Subdivisions 2 > variant.prm
run_scene variant.prm 1 "3D tetrahedra, condensed"
check_exact strain 1e-9 "3D tetrahedra, condensed"
# Plane strain: the modulus of uniaxial strain is that of 3D.
variant simplex "full space" | sed -e 's/^\(set Dimension = 2\)$/\1\nset Plane model = plane strain/' > variant.prm
run_scene variant.prm 1 "2D triangles, plane strain, full space"
check_exact strain 1e-7 "2D triangles, plane strain, full space"
variant hypercube condensed | set_entry "Material id function" "" \
  | sed -e "s|^\(subsection Geometry\)$|\1\n  set Mesh file = $here/../meshes/two_layer_column_4.msh|" \
  | set_entry "Boundary ids" 4 | set_entry "Contact boundary ids" 3 \
  | set_entry "Symmetry boundary ids" "1, 2" \
  | sed -e '0,/Material ids .*/s//Material ids = 10/' -e 's/Material ids *= 2$/Material ids = 20/' > variant.prm
run_scene variant.prm 1 "2D Gmsh mesh, condensed"
check_exact stress 1e-9 "2D Gmsh mesh, condensed"
grep -q "Model: elastic (2 materials" out.txt || fail "Gmsh mesh: not two materials: $(grep Model: out.txt)"

variant hypercube condensed | plastic_soft_layer > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, viscoplastic soft layer, explicit"
check_uniform "2D quadrilaterals, viscoplastic soft layer, explicit"
grep -q "Model: viscoplastic (2 materials, 1 viscoplastic)" out.txt \
  || fail "viscoplastic soft layer: $(grep Model: out.txt)"
variant simplex "full space" | three_d | set_entry Subdivisions 2 | plastic_soft_layer \
  | sed -e 's/^\(subsection Time\)$/\1\n  set Stress update = implicit/' > variant.prm
run_scene variant.prm 1 "3D tetrahedra, viscoplastic soft layer, implicit"
check_uniform "3D tetrahedra, viscoplastic soft layer, implicit"

echo "The two-layer column is exact in 6 elastic variants (all cell types, both back ends, 1 and 2 ranks, regions of a function and of a Gmsh mesh, plane strain) and uniform with a viscoplastic layer."
