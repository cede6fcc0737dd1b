#!/bin/bash
# The two-body patch test (parameters/two_block_patch_test.prm): a pad
# (E2 = 500) pressed by D(t) = 0.01 min(t, 2 - t) onto a base (E1 = 1000),
# both of height 1 and width 2, meshed separately with non-matching nodes
# at their interface, in contact along a pair (Opposite boundary ids). Each
# block is in uniaxial stress with the closed form
#   p = max(0, D - s) / (1 / E1 + 1 / E2 + 1 / c),
# s the zone's Initial gap (a clearance; negative: an interference) and c
# the stiffness of a compliant layer between the bodies (none: 1 / c = 0).
# The mortar coupling reproduces it to round-off (relative 1e-9) in every
# step: the force 2 p on the pad's side, the forces 2 p up on the pad's
# side and 2 p down on the base's side of the pair, the pair's contact
# area 2 and peak pressure p (time_series.csv), the
# reaction -2 p of its top, +2 p at the base's support (action equals
# reaction: all the pad's force reaches the base), the largest von Mises stress p, the contact area 2,
# and p at every node of the contact profiles; the operator is factorised
# once. Variants: quadrilaterals and triangles, cell-size ratios 6:8 and
# 4:10, on 1, 2 and 3 ranks (the opposite side of a node on another rank),
# the coarse side as the zone, a clearance, an interference, a compliant
# layer (2 ranks), and Coulomb friction between the bodies (below); then
# on the full space back end (1e-7: its Krylov tolerance) two meshes, the
# clearance, the layer and the friction, on 1 and 2 ranks; and on the
# matrix-free back end (quadrilaterals) a mesh, an interference and the
# friction, on 1 and 2 ranks; the 3D variants; and simplices on one side,
# hypercubes on the other (Cell type = mixed), 2D and 3D, condensed and
# full space. With "quick" as second argument (the Debug build): the
# quadrilaterals 6:8 on 1 rank, the triangles 4:10 and the mixed mesh on 2;
# with "core": the default tier's variants, not those marked "extended"
# (robustness/helpers.sh).
#   run_two_bodies.sh EXECUTABLE [quick|core]
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
read_part "${2:-}"
meshes=$here/../meshes

# check NAME GAP INVERSE_LAYER_STIFFNESS [UP]: UP = -1 where the zone is
# the base's top (the force on the zone's side then points down). The
# relative tolerance is $tolerance: 1e-9 on the condensed back end, 1e-7 on
# the full space back end (its Krylov tolerance).
tolerance=1e-9 axis=y
# The contact pressure at time t: linear, the pad's top pushed down by
# D = 0.01 min(t, 2 - t); softening, by D = 0.02 min(t, 2 - t) onto a
# layer with the law p(r) = 2000 r up to r = 0.002, then 4 - 100 (r - 0.002)
# (softening) up to the rigid limit r = 0.006, where p = 3.6. With
# C = 1 / E1 + 1 / E2 = 0.003 the columns in series give D = r + C p(r):
# r = D / 7 up to D = 0.014, r = (D - 0.0126) / 0.7 up to D = 0.0168, then
# r = 0.006 and p = (D - 0.006) / C.
closed_form='
  function penetration(t,   D) {
    if (law == "softening") {
      D = 0.02 * (t < 2 - t ? t : 2 - t)
      if (D <= 0.014) return D / 7
      if (D <= 0.0168) return (D - 0.0126) / 0.7
      return 0.006 }
    return pressure(t) * inverse_c }
  function pressure(t,   D, p, r) {
    if (law == "softening") {
      D = 0.02 * (t < 2 - t ? t : 2 - t)
      if (D <= 0.014) return 2000 * D / 7
      if (D <= 0.0168) { r = (D - 0.0126) / 0.7; return 4 - 100 * (r - 0.002) }
      return (D - 0.006) / 0.003 }
    D = 0.01 * (t < 2 - t ? t : 2 - t)
    p = D - s; if (p < 0) p = 0
    return p / (1 / 1000 + 1 / 500 + inverse_c) }'
check() {
  awk -F, -v name="$1" -v s="$2" -v inverse_c="$3" -v up="${4:-1}" -v law="${5:-linear}" \
    -v tol=$tolerance -v axis=$axis "$closed_form"'
    function near(a, b) { d = a - b; if (d < 0) d = -d
                          m = b < 0 ? -b : b; return d <= tol * (m > 1 ? m : 1) }
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i
              pair = "pair_force_zone_1_"; opposite = "opposite_force_zone_1_"; next }
    { t = $col["time"]; p = pressure(t)
      if (!((pair axis) in col)) { print name ": no column " pair axis; exit 1 }
      if (!near($col["total_contact_force"], 2 * p) \
          || !near($col["reaction_prescribed_1_" axis], -2 * p) \
          || !near($col["reaction_symmetry_2_" axis], 2 * p) \
          || !near($col[pair axis], 2 * up * p) || !near($col[opposite axis], -2 * up * p) \
          || !near($col["peak_pressure_zone_1"], p) \
          || (p > 0 && !near($col["contact_area_zone_1"], 2)) \
          || !near($col["max_von_mises"], p) || !near($col["peak_pressure"], p) \
          || (p > 0 && !near($col["contact_area"], 2))) {
        print name ": at t = " t " force " $col["total_contact_force"] ", reactions of the top " \
              $col["reaction_prescribed_1_" axis] " and of the base " $col["reaction_symmetry_2_" axis] \
              ", forces on the two sides " $col[pair axis] " and " $col[opposite axis] \
              ", von Mises " $col["max_von_mises"] ", peak " $col["peak_pressure"] ", area " \
              $col["contact_area"] "; expected p = " p ", force " 2 * p
        exit 1 } }' results/time_series.csv || exit 1
  # Both sides' profiles: the pressure p and, where p > 0, the
  # penetration r (the average of the zone's on the opposite side).
  ls results/opposite_profile_*.csv > /dev/null 2>&1 || fail "$1: no opposite_profile_*.csv"
  for profile in results/contact_profile_*.csv results/opposite_profile_*.csv; do
    awk -F, -v name="$1" -v s="$2" -v inverse_c="$3" -v law="${5:-linear}" -v tol=$tolerance \
      "$closed_form"'
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
      { t = $col["time"]; p = pressure(t)
        d = $col["contact_pressure"] - p; if (d < 0) d = -d
        if (d > tol * (p > 1 ? p : 1)) {
          print name ": pressure " $col["contact_pressure"] " at x = " $col["x"] ", t = " t \
                " in " FILENAME ", not " p; exit 1 }
        r = penetration(t); d = $col["u_nu"] - r; if (d < 0) d = -d
        if (p > 0 && d > tol) {
          print name ": penetration " $col["u_nu"] " at x = " $col["x"] ", t = " t \
                " in " FILENAME ", not " r; exit 1 } }' \
      "$profile" || exit 1
  done
  [ $tolerance != 1e-9 ] || grep -q "set up by the back end 1x" out.txt \
    || fail "$1: the operator was set up more than once: $(grep 'operator:' out.txt)"
}
# check_both_sides NAME: in the last .vtu record (every piece), each point
# of the interface (the coordinate along $axis equal to 1) of either body
# has the contact pressure of the last step (peak_pressure_zone_1, which
# check() compares with p), to the 1e-6 of Float32: the zone's nodes
# theirs, the opposite side's the force the zone exerts on them over their
# lumped weights; and the contact status 2 (on the unilateral limit) with
# a zero penetration.
check_both_sides() {
  local last p
  last=$(ls results/solution_*.pvtu | tail -1)
  p=$(awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
               { p = $col["peak_pressure_zone_1"] } END { print p }' results/time_series.csv)
  for piece in "${last%.pvtu}".*.vtu; do
    /usr/bin/python3 "$here/vtu_points.py" "$piece" contact_pressure contact_status penetration \
      || exit 1
  done | awk -v name="$1" -v p="$p" -v k=$([ $axis = y ] && echo 2 || echo 3) '
    $k > 1 - 1e-6 && $k < 1 + 1e-6 { ++n; d = $4 - p; if (d < 0) d = -d
      if (d > 1e-6 * p || $5 != 2 || $6 > 1e-9 || $6 < -1e-9) {
        print name ": contact_pressure " $4 ", status " $5 ", penetration " $6 " at (" $1 ", " $2 ", " $3 \
              ") in the .vtu, not " p ", 2, 0"; bad = 1; exit 1 } }
    END { if (!bad && n == 0) { print name ": no interface point in the .vtu"; exit 1 } }' || exit 1
}
full_space() { cat; printf '\nsubsection Linear solver\n  set Method = full space\nend\n'; }
matrix_free() { cat; printf '\nsubsection Linear solver\n  set Method = matrix free\nend\n'; }
condensed() { cat; printf '\nsubsection Linear solver\n  set Method = condensed\nend\n'; }

variant() { # MESH > variant.prm
  sed -e "s|\.\./meshes/two_blocks_quadrilateral_6_8|$meshes/$1|" \
    "$here/../parameters/two_block_patch_test.prm" | set_entry "Output directory" results
}
contact_entries() { sed -e "s/^\(subsection Contact\)$/\1\n$1/"; }

n=0
meshes_to_run="quadrilateral_6_8:1 triangle_6_8:3"
extended && meshes_to_run+=" quadrilateral_4_10:2 triangle_4_10:1"
[ "$quick" = quick ] && meshes_to_run="quadrilateral_6_8:1 triangle_4_10:2"
for mesh_ranks in $meshes_to_run; do
  mesh=${mesh_ranks%:*} ranks=${mesh_ranks#*:}
  cell=hypercube
  case $mesh in triangle*) cell=simplex ;; esac
  variant two_blocks_$mesh | set_entry "Cell type" $cell > variant.prm
  run_scene variant.prm $ranks "$mesh, $ranks rank(s)"
  check "$mesh, $ranks rank(s)" 0 0
  check_both_sides "$mesh, $ranks rank(s)"
  n=$((n + 1))
done
# Simplices on one side, hypercubes on the other (Cell type = mixed): a
# base of triangles under a pad of quadrilaterals.
variant two_blocks_mixed_6_8 | set_entry "Cell type" mixed > variant.prm
run_scene variant.prm 2 "mixed 6:8, 2 ranks"
check "mixed 6:8, 2 ranks" 0 0
check_both_sides "mixed 6:8, 2 ranks"
n=$((n + 1))
if [ "$quick" = quick ]; then
  axis=z
  sed -e "s|\.\./meshes/two_blocks_hexahedron_6_8|$meshes/two_blocks_tetrahedron_4_10|" \
    "$here/../parameters/two_block_patch_test_3d.prm" | set_entry "Output directory" results \
    | set_entry "Cell type" simplex > variant.prm
  run_scene variant.prm 2 "3D, tetrahedra 4:10, 2 ranks"
  check "3D, tetrahedra 4:10, 2 ranks" 0 0
  echo "The two-body patch test is exact on $((n + 1)) meshes."
  exit 0
fi

# The blocks turned by 45 degrees (nu = 0, the pad's top moved along the
# turned axis): the planes of symmetry are oblique, and the vertices on
# them have constrained components. Both profiles list every vertex of
# their side (9 and 7) with the pressure p and a zero penetration.
variant two_blocks_quadrilateral_6_8_turned | set_entry "Poisson ratio" 0 \
  | set_entry Components "x, y" \
  | set_entry Displacement "0.01 * min(t, 2 - t) * sin(pi / 4); -0.01 * min(t, 2 - t) * cos(pi / 4)" \
  > variant.prm
run_scene variant.prm 2 "turned by 45 degrees, 2 ranks"
for side_lines in contact:9 opposite:7; do
  for profile in results/${side_lines%:*}_profile_*.csv; do
    awk -F, -v name="turned by 45 degrees" -v lines=${side_lines#*:} -v law=linear -v s=0 \
      -v inverse_c=0 "$closed_form"'
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
      { ++n; p = pressure($col["time"]); d = $col["contact_pressure"] - p; if (d < 0) d = -d
        r = $col["u_nu"]; if (r < 0) r = -r
        if (d > 1e-9 * p || r > 1e-12) {
          print name ": pressure " $col["contact_pressure"] ", penetration " $col["u_nu"] \
                " at (" $col["x"] ", " $col["y"] ") in " FILENAME ", not " p ", 0"; exit 1 } }
      END { if (n != lines) { print name ": " n " lines in " FILENAME ", not " lines; exit 1 } }' \
      "$profile" || exit 1
  done
done

# The coarse side as the zone: the base's top meets the pad's bottom.
variant two_blocks_quadrilateral_4_10 | set_entry "Contact boundary ids" 3 \
  | set_entry "Opposite boundary ids" 4 > variant.prm
run_scene variant.prm 1 "coarse side as the zone"
check "coarse side as the zone" 0 0 -1

# A clearance s = 0.002 and an interference s = -0.002 (Initial gap adds to
# the distance of the sides).
gaps="-0.002"
extended && gaps+=" 0.002"
for s in $gaps; do
  variant two_blocks_triangle_6_8 | set_entry "Cell type" simplex \
    | contact_entries "  set Initial gap = $s" > variant.prm
  run_scene variant.prm 1 "Initial gap $s"
  check "Initial gap $s" $s 0
done

# A compliant layer between the bodies, p = c r with c = 2000, no rigid
# limit.
variant two_blocks_quadrilateral_6_8 | set_entry "Unilateral constraint" false \
  | set_entry "Normal compliance" true | set_entry "Layer thickness" 1 \
  | contact_entries "  set Law = piecewise linear\n  set Breakpoints = 0\n  set Slopes = 0, 2000" \
  > variant.prm
run_scene variant.prm 2 "compliant layer, 2 ranks"
check "compliant layer, 2 ranks" 0 0.0005

# A softening layer between the bodies with its rigid limit (the paper's
# law as an interface: the closed form of the columns in series, above),
# pressed to D = 0.02 through the rising branch, the softening one and the
# rigid limit, and back.
softening() { # MESH > variant.prm
  variant $1 | set_entry "Normal compliance" true | set_entry "Layer thickness" 0.006 \
    | set_entry Displacement "-0.02 * min(t, 2 - t)" | set_entry "Time step" 0.0625 \
    | contact_entries "  set Law = piecewise linear\n  set Breakpoints = 0, 0.002\n  set Slopes = 0, 2000, -100"
}
softening two_blocks_triangle_4_10 | set_entry "Cell type" simplex > variant.prm
run_scene variant.prm 1 "softening layer"
check "softening layer" 0 0 1 softening

# Coulomb friction between the bodies (mu = 0.3, nu = 0): the base clamped
# at its bottom, the pad's top pressed down by 0.01 min(t, 1), then moved
# sideways by 0.02 max(t - 1, 0). Once it slides (t >= 1.625) every node
# slips, the tangential force of the pair is mu N to round-off, the
# pair's forces on the two sides are -mu N and mu N along x, and the
# reactions of the pad's top and of the base's bottom balance them: the
# friction force reaches the other body whole.
sliding() { # > variant.prm
  variant two_blocks_quadrilateral_6_8 | set_entry "Symmetry boundary ids" "" \
    | set_entry "Clamped boundary ids" 2 | set_entry Components "x, y" \
    | set_entry Displacement "0.02 * max(t - 1, 0); -0.01 * min(t, 1)" \
    | set_entry "Poisson ratio" 0 | set_entry "End time" 2 | set_entry "Time step" 0.125 \
    | set_entry "Profile times" "1, 2" \
    | contact_entries "  set Tangential law = Coulomb\n  set Friction coefficient = 0.3"
}
check_sliding() { # NAME [SLIPPING_NODES]
  awk -F, -v name="$1" -v tol=$tolerance -v axis=$axis -v slipping=${2:-9} '
    function near(a, b) { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; return d <= tol * (m > 1 ? m : 1) }
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
    $col["time"] >= 1.625 {
      N = $col["total_contact_force"]; F = $col["tangential_force_zone_1_x"]
      if (N < 1 || $col["slip_nodes"] != slipping || !near(F, 0.3 * N) \
          || !near($col["reaction_prescribed_1_x"], F) || !near($col["reaction_clamped_x"], -F) \
          || !near($col["pair_force_zone_1_x"], -F) || !near($col["opposite_force_zone_1_x"], F) \
          || !near($col["reaction_clamped_" axis], N) || !near($col["reaction_prescribed_1_" axis], -N)) {
        print name ": at t = " $col["time"] " N = " N ", F = " F ", slipping nodes " \
              $col["slip_nodes"] ", reactions of the top (" $col["reaction_prescribed_1_x"] ", " \
              $col["reaction_prescribed_1_" axis] ") and of the base (" $col["reaction_clamped_x"] ", " \
              $col["reaction_clamped_" axis] "); expected F = 0.3 N, all " slipping " nodes slipping"
        exit 1 } }' results/time_series.csv || exit 1
  # At t = 2 every node of both sides slips (state 2) by the step's
  # 0.0025 along x (the opposite side's relative to the zone: -0.0025),
  # and the tangential traction that each side exerts on the other is
  # mu p along x, with the sign of its slip.
  for side in contact:1 opposite:-1; do
    awk -F, -v name="$1" -v tol=$tolerance -v side=${side%:*} -v sign=${side#*:} '
      function near(a, b) { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; return d <= tol * (m > 1 ? m : 1) }
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
      { ++n; p = $col["contact_pressure"]
        if ($col["friction_state"] != 2 || !near($col["slip_x"], sign * 0.0025) \
            || !near($col["tangential_traction_x"], sign * 0.3 * p) || p <= 0) {
          print name ": on the " side " side at x = " $col["x"] ": state " $col["friction_state"] \
                ", slip " $col["slip_x"] ", traction " $col["tangential_traction_x"] ", pressure " p \
                "; expected 2, " sign * 0.0025 ", " sign * 0.3 * p; exit 1 } }
      END { if (n == 0) { print name ": no line in the " side " profile at t = 2"; exit 1 } }' \
      results/${side%:*}_profile_0016.csv || exit 1
  done
}
sliding > variant.prm
run_scene variant.prm 2 "Coulomb friction, 2 ranks"
check_sliding "Coulomb friction, 2 ranks"

# The full space back end (in the dual mortar basis of the pairs): the
# same closed forms to its Krylov tolerance, 1 and 2 ranks.
tolerance=1e-7
if extended; then
  variant two_blocks_quadrilateral_4_10 | full_space > variant.prm
  run_scene variant.prm 1 "full space, quadrilaterals 4:10"
  check "full space, quadrilaterals 4:10" 0 0
fi
variant two_blocks_triangle_6_8 | set_entry "Cell type" simplex \
  | contact_entries "  set Initial gap = 0.002" | full_space > variant.prm
run_scene variant.prm 2 "full space, triangles 6:8, clearance, 2 ranks"
check "full space, triangles 6:8, clearance, 2 ranks" 0.002 0
if extended; then
  variant two_blocks_quadrilateral_6_8 | set_entry "Unilateral constraint" false \
    | set_entry "Normal compliance" true | set_entry "Layer thickness" 1 \
    | contact_entries "  set Law = piecewise linear\n  set Breakpoints = 0\n  set Slopes = 0, 2000" \
    | full_space > variant.prm
  run_scene variant.prm 1 "full space, compliant layer"
  check "full space, compliant layer" 0 0.0005
fi
sliding | full_space > variant.prm
run_scene variant.prm 2 "full space, Coulomb friction, 2 ranks"
check_sliding "full space, Coulomb friction, 2 ranks"

# The matrix-free back end (quadrilaterals; the operator T^T A T applied
# without a matrix): the same, to its Krylov tolerance.
if extended; then
  variant two_blocks_quadrilateral_4_10 | matrix_free > variant.prm
  run_scene variant.prm 1 "matrix free, quadrilaterals 4:10"
  check "matrix free, quadrilaterals 4:10" 0 0
fi
variant two_blocks_quadrilateral_6_8 | contact_entries "  set Initial gap = -0.002" \
  | matrix_free > variant.prm
run_scene variant.prm 2 "matrix free, interference, 2 ranks"
check "matrix free, interference, 2 ranks" -0.002 0
sliding | matrix_free > variant.prm
run_scene variant.prm 2 "matrix free, Coulomb friction, 2 ranks"
check_sliding "matrix free, Coulomb friction, 2 ranks"

# 3D (parameters/two_block_patch_test_3d.prm, blocks of depth 1: the same
# closed forms along z): hexahedra and tetrahedra, cell-size ratios 6:8 and
# 4:10, 1 to 3 ranks, a clearance, the compliant layer and Coulomb
# friction (45 nodes slipping) on the condensed back end; hexahedra and
# tetrahedra on the full space back end, hexahedra on the matrix-free one,
# 1 and 2 ranks.
axis=z tolerance=1e-9
variant_3d() { # MESH > variant.prm
  sed -e "s|\.\./meshes/two_blocks_hexahedron_6_8|$meshes/$1|" \
    "$here/../parameters/two_block_patch_test_3d.prm" | set_entry "Output directory" results
}
sliding_3d() { # > variant.prm
  variant_3d two_blocks_hexahedron_6_8 | set_entry "Symmetry boundary ids" "" \
    | set_entry "Clamped boundary ids" 2 | set_entry Components "x, y, z" \
    | set_entry Displacement "0.02 * max(t - 1, 0); 0; -0.01 * min(t, 1)" \
    | set_entry "Poisson ratio" 0 | set_entry "End time" 2 | set_entry "Time step" 0.125 \
    | set_entry "Profile times" "1, 2" \
    | contact_entries "  set Tangential law = Coulomb\n  set Friction coefficient = 0.3"
}
meshes_to_run="hexahedron_6_8:1 tetrahedron_6_8:2"
extended && meshes_to_run+=" hexahedron_4_10:3 tetrahedron_4_10:1"
for mesh_ranks in $meshes_to_run; do
  mesh=${mesh_ranks%:*} ranks=${mesh_ranks#*:}
  cell=hypercube
  case $mesh in tetrahedron*) cell=simplex ;; esac
  variant_3d two_blocks_$mesh | set_entry "Cell type" $cell > variant.prm
  run_scene variant.prm $ranks "3D, $mesh, $ranks rank(s)"
  check "3D, $mesh, $ranks rank(s)" 0 0
  check_both_sides "3D, $mesh, $ranks rank(s)"
  n=$((n + 1))
done
if extended; then
  variant_3d two_blocks_tetrahedron_4_10 | set_entry "Cell type" simplex \
    | contact_entries "  set Initial gap = 0.002" > variant.prm
  run_scene variant.prm 2 "3D, Initial gap 0.002, 2 ranks"
  check "3D, Initial gap 0.002, 2 ranks" 0.002 0
  variant_3d two_blocks_hexahedron_6_8 | set_entry "Unilateral constraint" false \
    | set_entry "Normal compliance" true | set_entry "Layer thickness" 1 \
    | contact_entries "  set Law = piecewise linear\n  set Breakpoints = 0\n  set Slopes = 0, 2000" \
    > variant.prm
  run_scene variant.prm 1 "3D, compliant layer"
  check "3D, compliant layer" 0 0.0005
fi
sliding_3d > variant.prm
run_scene variant.prm 2 "3D, Coulomb friction, 2 ranks"
check_sliding "3D, Coulomb friction, 2 ranks" 45

tolerance=1e-7
variant_3d two_blocks_hexahedron_4_10 | full_space > variant.prm
run_scene variant.prm 2 "3D, full space, hexahedra 4:10, 2 ranks"
check "3D, full space, hexahedra 4:10, 2 ranks" 0 0
if extended; then
  variant_3d two_blocks_tetrahedron_6_8 | set_entry "Cell type" simplex | full_space > variant.prm
  run_scene variant.prm 1 "3D, full space, tetrahedra 6:8"
  check "3D, full space, tetrahedra 6:8" 0 0
fi
sliding_3d | full_space > variant.prm
run_scene variant.prm 1 "3D, full space, Coulomb friction"
check_sliding "3D, full space, Coulomb friction" 45
variant_3d two_blocks_hexahedron_6_8 | matrix_free > variant.prm
run_scene variant.prm 2 "3D, matrix free, hexahedra 6:8, 2 ranks"
check "3D, matrix free, hexahedra 6:8, 2 ranks" 0 0
if extended; then
  sliding_3d | matrix_free > variant.prm
  run_scene variant.prm 1 "3D, matrix free, Coulomb friction"
  check_sliding "3D, matrix free, Coulomb friction" 45
fi

# Mixed meshes on the full space back end, and in 3D: a base of hexahedra
# under a pad of tetrahedra.
axis=y tolerance=1e-7
if extended; then
  variant two_blocks_mixed_6_8 | set_entry "Cell type" mixed | full_space > variant.prm
  run_scene variant.prm 1 "full space, mixed 6:8"
  check "full space, mixed 6:8" 0 0
fi
axis=z tolerance=1e-9
variant_3d two_blocks_mixed_3d_4_10 | set_entry "Cell type" mixed > variant.prm
run_scene variant.prm 1 "3D, mixed 4:10"
check "3D, mixed 4:10" 0 0
check_both_sides "3D, mixed 4:10"
n=$((n + 1))
# Refined once (the fully distributed mesh refines both kinds of cells).
variant_3d two_blocks_mixed_3d_4_10 \
  | sed -e 's/^\( *set Cell type *=\).*/\1 mixed\n  set Global refinements = 1/' | condensed > variant.prm
run_scene variant.prm 2 "3D, mixed 4:10 refined once, 2 ranks"
grep -q "4928 Hex and Tet cells" out.txt || fail "3D, mixed 4:10 refined once: not the refined mesh: $(grep Mesh: out.txt)"
check "3D, mixed 4:10 refined once, 2 ranks" 0 0
n=$((n + 1))
tolerance=1e-7
if extended; then
  variant_3d two_blocks_mixed_3d_4_10 | set_entry "Cell type" mixed | full_space > variant.prm
  run_scene variant.prm 2 "3D, full space, mixed 4:10, 2 ranks"
  check "3D, full space, mixed 4:10, 2 ranks" 0 0
fi

echo "The two-body patch test is exact on $n meshes (2D and 3D, simplices, hypercubes and both), with the coarse side as the zone, a clearance, an interference and a compliant layer; Coulomb friction between the bodies slides at mu N; the full space and matrix-free back ends agree."
