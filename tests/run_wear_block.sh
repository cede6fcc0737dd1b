#!/bin/bash
# Archard's wear (parameters/wear_block.prm): an elastic block pressed onto
# a rigid support that moves sideways under it with Coulomb friction; its
# surface wears away at w' = k_w p |slip rate| and the worn depth moves the
# support away for the next step. The scheme's recurrence, node by node and
# step by step (a profile at every step):
#   w_n = w_n-1 + k_w p_n |slip_n|,   w_0 = 0,
# with the node's own contact pressure p_n and slip of the step (relative to
# the support) from the profile (relative 1e-9 of the step's wear; 1e-7 on
# the iterative back ends); every node on the support (u_nu = 0 against the
# worn gap) and slipping; the worn volume sum_i w_i weight_i grows by
# k_w sum_i z_i |slip_i| per step, and the contact force falls as the
# block wears (the top is held). Variants: quadrilaterals, condensed, 1 rank
# (the shipped file); triangles, full space, 2 ranks; hexahedra,
# matrix-free; tetrahedra, condensed, 2 ranks; and an adaptive mesh
# (quadrilaterals, condensed, 2 ranks: the worn depth travels to the new
# nodes). With "quick" (the Debug build): the first two.
#   run_wear_block.sh EXECUTABLE [quick]
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 quick=${2:-}
prm=$here/../parameters/wear_block.prm

# check_wear TOLERANCE NAME: every profile against the one of the step
# before (the first against w = 0), matched by the node's coordinates.
check_wear() {
  ls results/contact_profile_*.csv | sort | awk -F, -v tol="$1" -v name="$2" -v kw=0.001 '
    function fail(text) { print name ": " text; bad = 1; exit 1 }
    # The wear of the node before this step: its own, or for a node the
    # mesh adaptation made (2D: a midpoint on the bottom edge) the linear
    # interpolation between its neighbours of the last profile.
    function previous(key, x,    k, left, right, xl, xr) {
      if (f == 1) return 0
      if (key in wear) return wear[key]
      xl = -1e300; xr = 1e300
      for (k in wear) { split(k, c, ","); c[1] += 0
        if (c[1] < x && c[1] > xl) { xl = c[1]; left = wear[k] }
        if (c[1] > x && c[1] < xr) { xr = c[1]; right = wear[k] } }
      if (xl == -1e300 || xr == 1e300) fail(files[f] " at " key ": a new node outside the old ones")
      return left + (right - left) * (x - xl) / (xr - xl)
    }
    { files[++n] = $0 }
    END {
      if (n < 16) fail("only " n " profiles")
      for (f = 1; f <= n; ++f) {
        delete col; delete current; row = 0
        while ((getline line < files[f]) > 0) {
          m = split(line, v, ",")
          if (++row == 1) { for (i = 1; i <= m; ++i) col[v[i]] = i; continue }
          key = v[1] "," v[2] (("z" in col) ? "," v[3] : "")
          slip = sqrt(v[col["slip_x"]]^2 + v[col["slip_y"]]^2 + (("slip_z" in col) ? v[col["slip_z"]]^2 : 0))
          expected = previous(key, v[1]) + kw * v[col["contact_pressure"]] * slip
          d = v[col["wear"]] - expected; if (d < 0) d = -d
          if (d > tol * (expected > 1e-12 ? expected : 1e-12))
            fail(files[f] " at " key ": wear " v[col["wear"]] ", expected " expected)
          if (v[col["friction_state"]] != 2) fail(files[f] " at " key ": not slipping")
          if (v[col["u_nu"]] > 1e-12 || v[col["u_nu"]] < -1e-12) fail(files[f] " at " key ": u_nu " v[col["u_nu"]])
          worn[f] += v[col["wear"]] * v[col["weight"]]
          gain[f] += kw * v[col["nodal_force"]] * slip
          current[key] = v[col["wear"]]
        }
        delete wear
        for (key in current) wear[key] = current[key]
        d = worn[f] - worn[f - 1] - gain[f]; if (d < 0) d = -d
        if (d > tol * gain[f]) fail(files[f] ": worn volume " worn[f] ", expected " worn[f - 1] + gain[f])
      }
      if (!(worn[n] > 0)) fail("nothing worn")
    }' || exit 1
  # The force falls as the block wears away under the held top.
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) col[$i] = i; next }
           NR > 2 && $col["total_contact_force"] >= last { print "the force grew at t = " $col["time"]; exit 1 }
           { last = $col["total_contact_force"] }' results/time_series.csv || fail "$2: force"
}
variant() { # CELL_TYPE METHOD > variant.prm
  set_entry "Cell type" "$1" < "$prm" | set_entry Method "$2" \
    | set_entry "Output directory" results
}
three_d() {
  sed -e "/^set Plane model/d" | set_entry Dimension 3 | set_entry Lengths "2, 1, 1" | set_entry Subdivisions 4 \
    | set_entry Components "x, y, z" | set_entry Displacement "0; -0.01; 0" \
    | set_entry "Obstacle motion" "0.5 * t; 0; 0" \
    | set_entry "Body force" "0; 0; 0" | set_entry "Surface traction" "0; 0; 0"
}

variant hypercube condensed > variant.prm
run_scene variant.prm 1 "2D quadrilaterals, condensed"
check_wear 1e-9 "2D quadrilaterals, condensed"
grep -q '"wear"' results/solution_0003.0.vtu || fail "2D quadrilaterals: no wear field in the VTU file"
variant simplex "full space" > variant.prm
run_scene variant.prm 2 "2D triangles, full space, 2 ranks"
check_wear 1e-7 "2D triangles, full space, 2 ranks"
if [ "$quick" = quick ]; then
  echo "The worn block follows the scheme's recurrence node by node on quadrilaterals (condensed) and triangles (full space, 2 ranks)."
  exit 0
fi

variant hypercube "matrix free" | three_d > variant.prm
run_scene variant.prm 1 "3D hexahedra, matrix-free"
check_wear 1e-7 "3D hexahedra, matrix-free"
variant simplex condensed | three_d > variant.prm
run_scene variant.prm 2 "3D tetrahedra, condensed, 2 ranks"
check_wear 1e-9 "3D tetrahedra, condensed, 2 ranks"
# An adaptive mesh: refined every 4 steps, the worn depths travel with the
# cells (a new node's interpolated depth is its wear before its first
# step).
variant hypercube condensed \
  | sed -e 's/^\(subsection Output\)$/subsection Mesh adaptation\n  set Adaptive refinement = true\n  set Refinement interval = 4\n  set Refine fraction = 0.3\nend\n\n\1/' > variant.prm
run_scene variant.prm 2 "2D quadrilaterals, adaptive mesh, 2 ranks"
grep -q "Mesh adapted" out.txt || fail "adaptive mesh: the mesh was never adapted"
check_wear 1e-9 "2D quadrilaterals, adaptive mesh, 2 ranks"

echo "The worn block follows the scheme's recurrence node by node in 5 variants (all cell types, three back ends, 1 and 2 ranks, an adaptive mesh)."
