#!/bin/bash
# Loads per boundary part (subsection Loads, "Surface load N"): a traction
# vector or a pressure along the inward normal on any number of parts. The
# reactions of a clamped part balance the loads exactly (the discrete
# residual sums to the discrete load, and the faces are straight), so:
#  - the block (0, 2) x (0, 1) of parameters/patch_test.prm clamped at its
#    bottom, a pressure p = 3 t on its top (Surface load 1) and a traction
#    (0.5 t, 0) on its right side (Surface load 2): the reaction of the
#    bottom is (-0.5 t, 6 t) (triangles, condensed; in 3D on hexahedra,
#    full space, 2 ranks, with the top 2 x 1.5: (-0.75 t, 0, 9 t) with the
#    traction (0.5 t, 0, 0) on a side of area 1.5);
#  - the half cylinder of parameters/hertz_cylinder.prm clamped at its flat
#    top, a pressure 2 t on its arc (a curved part: the normals of the
#    faces): on the quarter arc from (0, 0) to (1, 1) the outward normals
#    integrate to (1, -1), so the load is 2 t (-1, 1); its x part is held by
#    the roller at x = 0 too, so the y part of the top's reaction, -2 t, is
#    compared;
#  - loads on parts that are not free (a top with a prescribed u_x pressed
#    by a pressure, a pressure on a roller), and an oblique roller meeting
#    a part that prescribes one component: uniaxial stress, exact (below).
#   run_surface_loads.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
parameters=$here/../parameters

# check COLUMN SLOPE TOLERANCE NAME: the column is SLOPE t in every step.
check() {
  awk -F, -v column="$1" -v slope="$2" -v tol="$3" -v name="$4" '
    NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i
              if (!(column in col)) { print name ": no column " column; exit 1 }; next }
    { t = $col["time"]; expected = slope * t; d = $col[column] - expected; if (d < 0) d = -d
      if (d > tol * (1 + (expected < 0 ? -expected : expected))) {
        print name ": " column " = " $col[column] " at t = " t ", not " expected; exit 1 } }' \
    results/time_series.csv || exit 1
}

# The loaded block: no contact, clamped bottom, the two surface loads.
loads() { # DIM > PRM
  local traction="0.5 * t; 0" bottom=2 top=3
  [ "$1" -eq 3 ] && traction="0.5 * t; 0; 0" bottom=4 top=5
  sed -e "s/^\( *set Clamped boundary ids *=\).*/\1 $bottom/" \
      -e 's/^\( *set Contact boundary ids *=\).*/\1/' \
      -e 's/^\( *set Symmetry boundary ids *=\).*/\1/' \
      -e '/subsection Prescribed displacement 1/,/^  end/d' \
      -e "s/^\(subsection Loads\)$/\1\n  subsection Surface load 1\n    set Boundary ids = $top\n    set Type = pressure\n    set Value = 3 * t\n  end\n  subsection Surface load 2\n    set Boundary ids = 1\n    set Type = traction\n    set Value = $traction\n  end/" \
    | set_entry "Output directory" results
}
loads 2 < "$parameters/patch_test.prm" | set_entry "Cell type" simplex > variant.prm
run_scene variant.prm 1 "2D triangles, condensed"
check reaction_clamped_x -0.5 1e-9 "2D triangles, condensed"
check reaction_clamped_y 6 1e-9 "2D triangles, condensed"
loads 3 < "$parameters/patch_test_3d.prm" | set_entry "Cell type" hypercube \
  | set_entry Method "full space" | set_entry Subdivisions 2 > variant.prm
run_scene variant.prm 2 "3D hexahedra, full space, 2 ranks"
check reaction_clamped_x -0.75 1e-7 "3D hexahedra, full space, 2 ranks"
check reaction_clamped_z 9 1e-7 "3D hexahedra, full space, 2 ranks"

# A pressure on the curved arc of the half cylinder (no contact).
sed -e 's/^\( *set Clamped boundary ids *=\).*/\1 2/' \
    -e 's/^\( *set Contact boundary ids *=\).*/\1/' \
    -e '/subsection Prescribed displacement 1/,/^  end/d' \
    -e 's|^\( *set Mesh file *=\).*|\1 '"$here"'/../meshes/hertz_cylinder_16.msh|' \
    -e 's/^\(subsection Loads\)$/\1\n  subsection Surface load 1\n    set Boundary ids = 3\n    set Value = 2 * t\n  end/' \
    "$parameters/hertz_cylinder.prm" | set_entry "Output directory" results > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, pressure on an arc"
check reaction_clamped_y -2 1e-9 "2D quadrilaterals, pressure on an arc"

# Loads on parts that are not free: the block held at its bottom by u_y = 0
# (Prescribed displacement 1), a roller at x = 0, its top given u_x = nu p x
# / E (Prescribed displacement 2, component x only) and pressed by the
# pressure p = 3 t (Surface load 1 on the same top), and a pressure 7 t on
# the roller (Surface load 2, which the roller takes whole). Uniaxial stress
# sigma_yy = -p, exact: the bottom's reaction is 2 p = 6 t, the largest von
# Mises stress p, and the top's x reaction is no shear but the roller's
# pressure on the half face at the corner (0, 1), whose x component the
# top prescribes: -7 t h / 2 = -7 t / 16 (h = 1/8).
partly_prescribed() {
  set_entry "Contact boundary ids" "" | set_entry "Boundary ids" 2 | set_entry Displacement 0 \
    | sed -e 's/^\(subsection Boundary\)$/\1\n  subsection Prescribed displacement 2\n    set Boundary ids = 3\n    set Components = x\n    set Displacement = 0.0009 * t * x\n  end/' \
          -e 's/^\(subsection Loads\)$/\1\n  subsection Surface load 1\n    set Boundary ids = 3\n    set Value = 3 * t\n  end\n  subsection Surface load 2\n    set Boundary ids = 0\n    set Value = 7 * t\n  end/' \
    | set_entry "Output directory" results
}
for variant in "simplex condensed 1" "hypercube full_space 2"; do
  set -- $variant
  partly_prescribed < "$parameters/patch_test.prm" | set_entry "Cell type" $1 \
    | set_entry Method "${2/_/ }" > variant.prm
  tolerance=1e-9
  [ $2 = condensed ] || tolerance=1e-7
  run_scene variant.prm $3 "loads on a prescribed top and a roller, $1, ${2/_/ }"
  check reaction_prescribed_1_y 6 $tolerance "loads on a prescribed top and a roller, $1"
  check reaction_prescribed_2_x -0.4375 $tolerance "loads on a prescribed top and a roller, $1"
  check max_von_mises 3 $tolerance "loads on a prescribed top and a roller, $1"
done

# An oblique roller that meets a part prescribing the component it would
# constrain: the tilted block of parameters/tilted_patch_test.prm without
# contact, the roller X = 0, its bottom given u_x of the exact state only
# (Prescribed displacement 1, component x), a pressure p = 3 t on its side
# X = 1. Uniaxial stress along e_X, u = -(p/E) X e_X + nu (p/E) Y e_Y: the
# roller carries p, also at the corner (0, 0), where it must constrain u_y
# since u_x is prescribed; the largest von Mises stress is p (1e-9).
# (The file's Displacement continues on a second line, which goes.)
sed -e "s|\.\./meshes/|$here/../meshes/|" -e '/^ *set Displacement/{n;d}' \
    "$parameters/tilted_patch_test.prm" \
  | set_entry "Contact boundary ids" "" | set_entry "Boundary ids" 3 | set_entry Components x \
  | set_entry Displacement "-0.003 * t * (x * cos(pi/6) + y * sin(pi/6)) * cos(pi/6)" \
  | sed -e 's/^\(subsection Loads\)$/\1\n  subsection Surface load 1\n    set Boundary ids = 2\n    set Value = 3 * t\n  end/' \
  | set_entry "Output directory" results > variant.prm
run_scene variant.prm 1 "oblique roller meeting a prescribed part"
check max_von_mises 3 1e-9 "oblique roller meeting a prescribed part"

echo "Surface loads: the reactions balance a pressure and a traction on the block (2D triangles, 3D hexahedra on 2 ranks), a pressure on a curved arc, and loads on a partly prescribed top and on a roller."
