#!/bin/bash
# What the preconditioners of the iterative back ends achieve with contact
# (doc/performance.md): over a run of the scene, the Krylov iterations per
# time step stay within F elastic solves, F from the parameter file's line
# "# Krylov iterations per step at most: F", an elastic solve being the
# iterations of one solve with K from zero to the same Tolerance (the run
# summary's cost measurement). F is the observed value with a margin; a
# preconditioner that treats the contact nodes' fixed directions as free
# (a V-cycle or AMG of K alone) takes two to three times the iterations,
# far above it. With the line "# solves per active-set iteration at
# most: S" the run's linear solves per active-set iteration stay within S:
# 1 when CG goes on past an early solve whose pieces stay (one solve per
# iteration), 1 + steps / iterations when it stops and solves again. With
# "# back end set-ups: A to B" the back end sets its preconditioner up A to
# B times over the run (the full space back end's rule for rebuilding its
# AMG). With "# Hertz sphere mesh: N" the scene's Mesh file is the graded
# block of N cells per edge of meshes/make_hertz_sphere_meshes.py, written
# here. The scene sets its Method; on the ranks of its line "# ranks: N"
# (default 1).
#   run_krylov_iterations.sh EXECUTABLE PRM
set -u
here=$(dirname "$0")
executable=$1 prm=$2
most=$(sed -n 's/^# Krylov iterations per step at most: *//p' "$prm")
most_solves=$(sed -n 's/^# solves per active-set iteration at most: *//p' "$prm")
ranks=$(sed -n 's/^# ranks: //p' "$prm")
setups_range=$(sed -n 's/^# back end set-ups: *//p' "$prm")
hertz_mesh=$(sed -n 's/^# Hertz sphere mesh: *//p' "$prm")
export RANKS=${ranks:-1}
if [ -z "$most" ]; then
  echo "$prm has no line '# Krylov iterations per step at most: F'."
  exit 1
fi
edit="s|^\( *set Output directory *=\).*|\1 results|;s|^\( *set Write vtu *=\).*|\1 false|"
if [ -n "$hertz_mesh" ]; then
  mesh=$PWD/hertz_sphere_hexahedron_$hertz_mesh.msh
  /usr/bin/python3 "$here/../meshes/make_hertz_sphere_meshes.py" "$hertz_mesh" "$mesh" \
    || { echo "Could not write the Hertz sphere mesh $mesh."; exit 1; }
  edit="$edit;s|^\( *set Mesh file *=\).*|\1 $mesh|"
fi
"$here/run_scene_variant.sh" run "$executable" "$prm" "$edit" || exit 1
read -r steps krylov < <(sed -n 's/^  back end: [0-9]* solves, \([0-9]*\) Krylov iterations.*/\1/p' run/output.txt \
  | paste - <(sed -n 's/^  active-set iterations: [0-9]* in \([0-9]*\) steps.*/\1/p' run/output.txt) \
  | awk '{print $2, $1}')
solves=$(sed -n 's/^  back end: \([0-9]*\) solves, .*/\1/p' run/output.txt)
iterations=$(sed -n 's/^  active-set iterations: \([0-9]*\) in .*/\1/p' run/output.txt)
solve=$(sed -n 's/^  one solve with the step operator, no contact: .*(\([0-9]*\) Krylov iterations)/\1/p' run/output.txt)
if [ -z "${steps:-}" ] || [ -z "${krylov:-}" ] || [ -z "$solve" ]; then
  echo "The run printed no Krylov iterations, steps or cost measurement."
  exit 1
fi
awk -v k="$krylov" -v n="$steps" -v s="$solve" -v most="$most" 'BEGIN {
  ratio = k / n / s
  printf "%d Krylov iterations in %d steps: %.2f per step, %.2f elastic solves of %d iterations (at most %s)\n", k, n, k / n, ratio, s, most
  exit !(ratio <= most)
}' || { echo "More Krylov iterations per step than the scene allows."; exit 1; }
if [ -n "$setups_range" ]; then
  setups=$(sed -n 's/^  operator: .*set up by the back end \([0-9]*\)x.*/\1/p' run/output.txt)
  read -r fewest most_setups <<< "${setups_range/ to / }"
  echo "The back end set up its preconditioner ${setups:-?} times (from $fewest to $most_setups)."
  [ -n "$setups" ] && [ "$setups" -ge "$fewest" ] && [ "$setups" -le "$most_setups" ] \
    || { echo "Not the set-ups the scene expects."; exit 1; }
fi
if [ -n "$most_solves" ]; then
  awk -v s="$solves" -v i="$iterations" -v most="$most_solves" 'BEGIN {
    printf "%d solves in %d active-set iterations: %.2f per iteration (at most %s)\n", s, i, s / i, most
    exit !(i > 0 && s / i <= most)
  }' || { echo "More solves per active-set iteration than the scene allows."; exit 1; }
fi
