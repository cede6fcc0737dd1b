#!/bin/bash
# Print iteration history (subsection Output) prints, after each step's
# line, one line per active-set iteration. The scene runs with it on; for
# every step the lines must agree with the step's row of time_series.csv:
# as many lines as active_set_iterations, numbered 1, 2, ..., their Krylov
# iterations summing to krylov_iterations, the last one with no node that
# changed its piece and with unilateral_nodes nodes at the rigid limit.
# At least one step must take several iterations, so that the check covers
# a history with changes.
#   run_iteration_history.sh EXECUTABLE PRM
set -u
here=$(dirname "$0")
executable=$1 prm=$2

"$here/run_scene_variant.sh" history "$executable" "$prm" \
  "s/^\( *subsection Output\)/\1\n  set Print iteration history = true\n  set Verbose = true/" || exit 1
grep -q "^ *set Print iteration history = true" history/scene.prm || {
  echo "$prm has no subsection <Output> to switch the history on in."
  exit 1
}

# One line per step from the terminal: step, lines, last number, sum of
# Krylov iterations, changed nodes and nodes at the rigid limit of the last.
awk '
  function flush() {
    if (step != "")
      print step, lines, last, krylov, changed, rigid
  }
  /^Step +[0-9]+ / { flush(); step = $2; lines = 0; last = 0; krylov = 0; next }
  /^    iteration [0-9]+: / {
    if (step == "") next   # the initial cycles print theirs before step 1
    lines++
    number = $2; sub(":", "", number)
    if (number != lines) { print "bad numbering in step " step; exit 1 }
    last = number; changed = $3; rigid = $8
    if (match($0, /after [0-9]+ Krylov/))
      krylov += substr($0, RSTART + 6, RLENGTH - 13)
  }
  END { flush() }' history/output.txt > history/terminal.txt || {
  cat history/terminal.txt
  exit 1
}
# The same from the time series: step, iterations, Krylov, unilateral.
awk -F, 'NR > 1 { print $1, $3, $10, $4 }' history/results/time_series.csv \
  > history/series.txt

steps=$(wc -l < history/series.txt)
[ "$steps" -gt 0 ] || { echo "The run wrote no steps."; exit 1; }
[ "$(wc -l < history/terminal.txt)" -eq "$steps" ] || {
  echo "The terminal has $(wc -l < history/terminal.txt) steps with a history, the time series $steps."
  exit 1
}
several=0
while read -r step lines last krylov changed rigid && read -r s iterations series_krylov unilateral <&3; do
  [ "$step" = "$s" ] || { echo "Step $step of the terminal is step $s of the time series."; exit 1; }
  [ "$lines" -eq "$iterations" ] || {
    echo "Step $step: $lines history lines, but $iterations active-set iterations in the time series."
    exit 1
  }
  [ "$krylov" -eq "$series_krylov" ] || {
    echo "Step $step: the history's Krylov iterations sum to $krylov, the time series has $series_krylov."
    exit 1
  }
  [ "$changed" -eq 0 ] || { echo "Step $step: its last iteration moved $changed nodes."; exit 1; }
  [ "$rigid" -eq "$unilateral" ] || {
    echo "Step $step: $rigid nodes at the rigid limit in the last iteration, $unilateral in the time series."
    exit 1
  }
  [ "$lines" -gt 1 ] && several=1
done < history/terminal.txt 3< history/series.txt
[ "$several" -eq 1 ] || { echo "No step of $prm took more than one iteration."; exit 1; }
echo "The iteration history of $steps steps agrees with the time series."
