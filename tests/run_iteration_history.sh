#!/bin/bash
# Print iteration history (subsection Output) prints each step's line, even
# with Verbose = false, and under it one line per active-set iteration. The
# scene runs with it on and Verbose off; for every step the lines must
# agree with the step's row of time_series.csv: as many lines as
# active_set_iterations, numbered 1, 2, ..., their Krylov iterations summing
# to krylov_iterations, the last one with no node that changed its piece and
# with unilateral_nodes nodes at the rigid limit. At least one step must
# take several iterations, so that the check covers a history with changes.
# With CYCLES > 0 the scene solves step 1 on CYCLES coarser meshes first
# (Initial cycles): each "Initial cycle" line must be followed by as many
# numbered lines as the iterations it states, the last one moving no node.
#   run_iteration_history.sh EXECUTABLE PRM [CYCLES]
set -u
here=$(dirname "$0")
executable=$1 prm=$2 cycles=${3:-0}

edit="s/^\( *subsection Output\)/\1\n  set Print iteration history = true/;s/^\( *set Verbose *=\).*/\1 false/"
if [ "$cycles" -gt 0 ]; then
  edit="$edit;\$a subsection Mesh adaptation\n  set Initial cycles = $cycles\nend"
fi
"$here/run_scene_variant.sh" history "$executable" "$prm" "$edit" || exit 1
grep -q "^ *set Print iteration history = true" history/scene.prm || {
  echo "$prm has no subsection <Output> to switch the history on in."
  exit 1
}
grep -q "^ *set Verbose *= false" history/scene.prm || {
  echo "$prm has no Verbose entry in subsection <Output> to switch off."
  exit 1
}

# One line per step from the terminal: step, lines, last number, sum of
# Krylov iterations, changed nodes and nodes at the rigid limit of the last.
# The initial cycles' histories are checked here and counted in cycles.txt.
awk -v cycles_file=history/cycles.txt '
  function flush() {
    if (cycle != "" && (lines != expected || changed != 0)) {
      print "Initial cycle " cycle ": " lines " history lines for " expected \
            " iterations, the last moving " changed " nodes"
      exit 1
    }
    if (cycle != "")
      print cycle > cycles_file
    if (step != "")
      print step, lines, last, krylov, changed, rigid
    cycle = ""; step = ""
  }
  /^Initial cycle [0-9]+: / {
    flush(); cycle = $3; sub(":", "", cycle); lines = 0; changed = -1
    for (i = 1; i < NF; i++) if ($(i + 1) == "active-set") expected = $i
    next
  }
  /^Step +[0-9]+ +t = / {
    flush(); step = $2; lines = 0; last = 0; krylov = 0; changed = -1; next
  }
  /^    iteration [0-9]+: / {
    if (step == "" && cycle == "") { print "a history line under no step"; exit 1 }
    lines++
    number = $2; sub(":", "", number)
    if (number != lines) { print "bad numbering in step " step cycle; exit 1 }
    last = number; changed = $3; rigid = $8
    if (match($0, /after [0-9]+ Krylov/))
      krylov += substr($0, RSTART + 6, RLENGTH - 13)
    next
  }
  /^(Step|Initial cycles done)/ { flush() }
  END { flush() }' history/output.txt > history/terminal.txt || {
  cat history/terminal.txt
  exit 1
}
printed_cycles=$(cat history/cycles.txt 2> /dev/null | wc -l)
[ "$printed_cycles" -eq "$cycles" ] || {
  echo "The run printed the history of $printed_cycles initial cycles, $cycles were asked for."
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
echo "The iteration history of $steps steps agrees with the time series ($cycles initial cycles)."
