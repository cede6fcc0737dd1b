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
# iteration), 1 + steps / iterations when it stops and solves again. The
# scene sets its Method; on the ranks of its line "# ranks: N" (default 1).
#   run_krylov_iterations.sh EXECUTABLE PRM
set -u
here=$(dirname "$0")
executable=$1 prm=$2
most=$(sed -n 's/^# Krylov iterations per step at most: *//p' "$prm")
most_solves=$(sed -n 's/^# solves per active-set iteration at most: *//p' "$prm")
ranks=$(sed -n 's/^# ranks: //p' "$prm")
export RANKS=${ranks:-1}
if [ -z "$most" ]; then
  echo "$prm has no line '# Krylov iterations per step at most: F'."
  exit 1
fi
"$here/run_scene_variant.sh" run "$executable" "$prm" \
  "s|^\( *set Output directory *=\).*|\1 results|;s|^\( *set Write vtu *=\).*|\1 false|" \
  || exit 1
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
if [ -n "$most_solves" ]; then
  awk -v s="$solves" -v i="$iterations" -v most="$most_solves" 'BEGIN {
    printf "%d solves in %d active-set iterations: %.2f per iteration (at most %s)\n", s, i, s / i, most
    exit !(i > 0 && s / i <= most)
  }' || { echo "More solves per active-set iteration than the scene allows."; exit 1; }
fi
