#!/bin/bash
# The contact patch test (parameters/patch_test.prm, patch_test_3d.prm): a
# block on a flat rigid support, its top pushed down by the prescribed
# displacement D(t) = 0.01 min(t, 2 - t) (H = 1, E = 1000), rollers on the
# sides. The exact state is uniaxial stress, p = E D / H on the whole
# support, which the discrete solution reproduces to round-off:
#  - elastic, on triangles, quadrilaterals, tetrahedra and hexahedra, with
#    both back ends and on 1 and 2 ranks: in every step the contact force is
#    p A (A = 2 in 2D, 3 in 3D), the contact area A, the peak pressure p,
#    the reaction of the top -p A, no reaction on the rollers (the contact
#    force of the nodes where they meet the support is not theirs; relative
#    error 1e-9 with the condensed
#    back end, 1e-7 with the full space back end's Krylov tolerance), every
#    node of the profiles at t = 1 and 1.5 has p, and the condensed back
#    end factorises once per run;
#  - unloaded again (t = 2): no contact area, force or peak pressure;
#  - with the support at a distance s = 0.002 (Initial gap, Gap direction),
#    and with the top held and the support moving up (s = 0.002 - D(t)):
#    p = E (D - s) / H, exactly as above;
#  - with hanging nodes on the roller, the support and a second prescribed
#    part (the right side, given the exact u_x = nu D x / H): the same, and
#    no reaction on the right side;
#  - on the tilted block (parameters/tilted_patch_test*.prm: the block
#    rotated so that its rollers and the support are oblique, the contact
#    nodes on the rollers constrained to move in them), on all four cell
#    types, both back ends, 1 and 2 ranks: the same;
#  - in plane strain (E = 910, so that E / (1 - nu^2) = 1000): the same;
#  - with plasticity (explicit and implicit update): the state is still
#    uniform and uniaxial, so every node of a profile has the same pressure
#    (to 1e-9 relative), the force is p A, the reaction -p A and the largest
#    von Mises stress p.
# With "quick" as second argument (the Debug build): two elastic variants.
#   run_patch_test.sh EXECUTABLE [quick]
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 quick=${2:-}
parameters=$here/../parameters

# check_elastic AREA TOLERANCE NAME [OFFSET [UP]]: p = 10 min(t, 2 - t) -
# OFFSET, the top's reaction -p AREA UP (UP the support's inner normal,
# "x y" or "x y z"; default the y axis with AREA 2, the z axis with AREA 3).
check_elastic() {
  local offset=${4:-0} up=${5:-}
  [ -n "$up" ] || { up="0 1"; [ "$1" = 3 ] && up="0 0 1"; }
  awk -F, -v area="$1" -v tol="$2" -v name="$3" -v offset="$offset" -v up="$up" '
    function near(a, b) { d = a - b; if (d < 0) d = -d
                          m = b < 0 ? -b : b; return d <= tol * (m > 1 ? m : 1) }
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i
              dim = split(up, direction, " "); next }
    { t = $col["time"]; p = 10 * (t < 2 - t ? t : 2 - t) - offset
      top = 0
      for (c = 1; c <= dim; ++c)
        top += direction[c] * $col["reaction_prescribed_1_" substr("xyz", c, 1)]
      if (!near($col["total_contact_force"], p * area) || !near($col["contact_area"], area) \
          || !near($col["peak_pressure"], p) || !near(top, -p * area) || $col["no_contact_nodes"] != 0) {
        print name ": at t = " t " force " $col["total_contact_force"] ", area " $col["contact_area"] \
              ", peak " $col["peak_pressure"] ", reaction of the top " $top "; expected p = " p ", force " p * area
        exit 1 }
      # The rollers carry nothing (the stress is uniaxial, normal to the
      # support): the contact force of the nodes on them is not theirs.
      for (c in col)
        if (c ~ /^reaction_symmetry_/ && !near(p * area + $col[c], p * area)) {
          print name ": at t = " t " the roller reaction " c " is " $col[c] ", not 0"; exit 1 } }' \
    results/time_series.csv || exit 1
  for profile in results/contact_profile_*.csv; do
    awk -F, -v tol="$2" -v name="$3" -v offset="$offset" '
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
      { t = $col["time"]; p = 10 * (t < 2 - t ? t : 2 - t) - offset; d = $col["contact_pressure"] - p
        if (d < 0) d = -d
        if (d > tol * p) { print name ": pressure " $col["contact_pressure"] " at t = " t ", not " p; exit 1 } }' \
      "$profile" || exit 1
  done
  # One factorisation per run on the condensed back end (the full space
  # back end rebuilds its AMG when the contact set changes).
  case "$3" in *condensed*)
    grep -q "set up by the back end 1x" out.txt \
      || fail "$3: the operator was set up more than once: $(grep 'operator:' out.txt)" ;;
  esac
}

# check_uniform AREA NAME
check_uniform() {
  for profile in results/contact_profile_*.csv; do
    awk -F, -v name="$2" '
      NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
      NR == 2 { p = $col["contact_pressure"] }
      { d = $col["contact_pressure"] - p; if (d < 0) d = -d
        if (d > 1e-9 * p) { print name ": pressures " p " and " $col["contact_pressure"] " in one profile"; exit 1 } }' \
      "$profile" || exit 1
  done
  awk -F, -v area="$1" -v name="$2" '
    function near(a, b) { d = a - b; if (d < 0) d = -d; m = b < 0 ? -b : b; return d <= 1e-9 * (m > 1 ? m : 1) }
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i
              top = col["reaction_prescribed_1_" (area == 3 ? "z" : "y")]; next }
    { p = $col["peak_pressure"]
      if (!near($col["total_contact_force"], p * area) || !near($top, -p * area) \
          || !near($col["max_von_mises"], p)) {
        print name ": at t = " $col["time"] " force " $col["total_contact_force"] ", reaction " $top \
              ", von Mises " $col["max_von_mises"] " for the pressure " p; exit 1 } }' \
    results/time_series.csv || exit 1
}

variant() { # PRM CELL_TYPE METHOD > variant.prm
  set_entry "Cell type" "$2" < "$1" | set_entry "Method" "$3" \
    | set_entry "Output directory" results
}

if [ "$quick" = quick ]; then
  variant "$parameters/patch_test.prm" simplex condensed | set_entry Subdivisions 3 > variant.prm
  run_scene variant.prm 1 "2D simplex, condensed"
  check_elastic 2 1e-9 "2D simplex, condensed"
  variant "$parameters/patch_test_3d.prm" hypercube "full space" | set_entry Subdivisions 2 > variant.prm
  run_scene variant.prm 1 "3D hypercube, full space"
  check_elastic 3 1e-7 "3D hypercube, full space"
  echo "The patch test is exact on triangles (condensed) and hexahedra (full space)."
  exit 0
fi

n=0
for dim in 2 3; do
  prm=$parameters/patch_test.prm area=2
  [ $dim -eq 3 ] && prm=$parameters/patch_test_3d.prm area=3
  for cell in simplex hypercube; do
    for method in condensed "full space"; do
      tolerance=1e-9
      [ "$method" = condensed ] || tolerance=1e-7
      variant "$prm" $cell "$method" | set_entry Subdivisions 3 > variant.prm
      run_scene variant.prm 1 "${dim}D $cell, $method"
      check_elastic $area $tolerance "${dim}D $cell, $method"
      n=$((n + 1))
    done
  done
done

variant "$parameters/patch_test.prm" hypercube "full space" > variant.prm
run_scene variant.prm 2 "2D hypercube, full space, 2 ranks"
check_elastic 2 1e-7 "2D hypercube, full space, 2 ranks"
variant "$parameters/patch_test_3d.prm" simplex condensed | set_entry Subdivisions 3 > variant.prm
run_scene variant.prm 2 "3D simplex, condensed, 2 ranks"
check_elastic 3 1e-9 "3D simplex, condensed, 2 ranks"

# Unloaded again at t = 2 (D = 0): every node touches the support, none is
# pressed, so the contact area is 0 (only nodes with a pressure count), as
# are the force and the peak pressure; both back ends.
for method in condensed "full space"; do
  variant "$parameters/patch_test.prm" hypercube "$method" | set_entry "End time" 2 > variant.prm
  run_scene variant.prm 1 "2D hypercube, $method, unloaded"
  tail -1 results/time_series.csv | awk -F, -v name="2D hypercube, $method, unloaded" '
    { if ($2 != 2 || $7 > 1e-9 || $7 < -1e-9 || $13 != 0 || $14 > 1e-9) {
        print name ": at t = " $2 " force " $7 ", area " $13 ", peak " $14 "; expected 0"; exit 1 } }' \
    || exit 1
done

# The support 0.002 below the block (Initial gap, along the direction
# 0, -1): p = E (D - 0.002) / H once D > 0.002. Then the top held and the
# support moving up instead (a gap 0.002 - D(t)): the same pressures.
gap() { sed -e "s/^\(subsection Contact\)$/\1\n  set Initial gap = $1\n  set Gap direction = $2/"; }
variant "$parameters/patch_test.prm" simplex condensed | gap 0.002 "0, -1" > variant.prm
run_scene variant.prm 1 "2D simplex, support at a distance"
check_elastic 2 1e-9 "2D simplex, support at a distance" 2
variant "$parameters/patch_test_3d.prm" hypercube "full space" | set_entry Subdivisions 2 \
  | gap "0.002 - 0.01 * min(t, 2 - t)" "0, 0, -1" | set_entry Displacement 0 > variant.prm
run_scene variant.prm 1 "3D hexahedra, moving support"
check_elastic 3 1e-7 "3D hexahedra, moving support" 2

# Hanging nodes (Contact refinement levels) on the roller, the support and
# a second prescribed part, the right side, given the exact u_x = nu D x / H:
# the same pressures, and no reaction on the right side.
variant "$parameters/patch_test.prm" hypercube condensed | set_entry Subdivisions 4 \
  | sed -e 's/^\(subsection Geometry\)$/\1\n  set Contact refinement levels = 2/' \
        -e '0,/^  end$/s//  end\n  subsection Prescribed displacement 2\n    set Boundary ids = 1\n    set Components = x\n    set Displacement = 0.003 * min(t, 2 - t) * x\n  end/' \
  > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, hanging nodes, two prescribed parts"
check_elastic 2 1e-9 "2D quadrilaterals, hanging nodes, two prescribed parts"
awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
  { r = $col["reaction_prescribed_2_x"]; if (r > 1e-9 || r < -1e-9) { print "reaction of the right side " r; exit 1 } }' \
  results/time_series.csv || fail "2D quadrilaterals, hanging nodes: the right side carries a force."

# The tilted block (parameters/tilted_patch_test*.prm): oblique rollers and
# an oblique support, the contact nodes on a roller constrained to move in
# it (along the edge of the two planes in 3D). The same pressures on every
# cell type, both back ends, 1 and 2 ranks; UP = e_Y of the meshes' rotation.
up2="-0.5 0.8660254037844387" up3="-0.5 0.8137976813493738 0.29619813272602386"
tilted() { # PRM MESH CELL_TYPE METHOD > variant.prm
  sed -e "s|\.\./meshes/tilted_block_[a-z]*_\([0-9]\)|$here/../meshes/tilted_block_$2_\1|" "$1" \
    | set_entry "Cell type" "$3" | set_entry Method "$4" | set_entry "Output directory" results
}
for variant in "quadrilateral hypercube condensed 1" "triangle simplex full_space 2" \
               "hexahedron hypercube full_space 1" "hexahedron hypercube condensed 2" \
               "tetrahedron simplex condensed 1" "tetrahedron simplex full_space 2"; do
  set -- $variant
  prm=$parameters/tilted_patch_test.prm up=$up2
  case $1 in hexahedron|tetrahedron) prm=$parameters/tilted_patch_test_3d.prm up=$up3 ;; esac
  tolerance=1e-9
  [ "$3" = condensed ] || tolerance=1e-7
  tilted "$prm" $1 $2 "${3/_/ }" > variant.prm
  run_scene variant.prm $4 "tilted block, $1, ${3/_/ }, $4 rank(s)"
  check_elastic 1 $tolerance "tilted block, $1, ${3/_/ }, $4 rank(s)" 0 "$up"
done

# Plane strain: p = E D / ((1 - nu^2) H), the same pressures with
# E = 1000 (1 - 0.3^2) = 910.
variant "$parameters/patch_test.prm" hypercube condensed | set_entry "Young's modulus" 910 \
  | sed -e 's/^\(set Dimension = 2\)$/\1\nset Plane model = plane strain/' > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, plane strain"
check_elastic 2 1e-9 "2D quadrilaterals, plane strain"

variant "$parameters/patch_test.prm" hypercube condensed \
  | set_entry Plasticity true > variant.prm
run_scene variant.prm 1 "2D hypercube, explicit plasticity"
check_uniform 2 "2D hypercube, explicit plasticity"
variant "$parameters/patch_test_3d.prm" simplex "full space" | set_entry Subdivisions 3 \
  | set_entry Plasticity true | sed -e 's/^\(subsection Time\)$/\1\n  set Stress update = implicit/' > variant.prm
run_scene variant.prm 1 "3D simplex, implicit plasticity"
check_uniform 3 "3D simplex, implicit plasticity"

echo "The patch test is exact in $((n + 12)) elastic variants (both back ends, all cell types, 1 and 2 ranks, a support at a distance and a moving one, hanging nodes on prescribed parts, a tilted block on oblique rollers, plane strain), has no contact area when unloaded, and is uniform with plasticity."
