#!/bin/bash
# The smoke tier: a shipped parameter file (parameters/NAME.prm) as a user
# runs it, cut short: a run stops after its second step (Stop after step =
# 2), a convergence study keeps its first two runs and takes its third as
# the reference. Its Output directory goes into the test's folder, a
# relative Mesh file stays relative to parameters/. The run must end with
# exit status 0, and its step lines, final state and table rows (the lines
# run_regression.sh compares across rank counts, without the progress in
# brackets and the wall time of a study's runs) must match tests/shipped/NAME.output (numdiff -a 1e-10 -r 1e-6).
# So a renamed entry, a changed default or a changed result in any shipped
# file fails here. With UPDATE=1 in the environment the reference is
# written instead.
#   run_shipped_scene.sh EXECUTABLE PRM REFERENCE
set -u
executable=$1 prm=$2 reference=$3
prm_folder=$(cd "$(dirname "$prm")" && pwd)
rm -rf results scene.prm

# The first N entries of a list entry in the Convergence study subsection.
first() { # ENTRY N
  sed -n "/^subsection Convergence study/,/^end/s/^ *set $1 *= *\([^#]*\).*/\1/p" "$prm" \
    | tr -d ' ' | cut -d, -f"$2"
}
edits=(-e "s|^\( *set Output directory *=\).*|\1 results|"
       -e "s|^\( *set Mesh file *= *\)\([^/ #][^ #]*\)|\1$prm_folder/\2|")
if sed -n '/^subsection Convergence study/,/^end/p' "$prm" | grep -q '^ *set Enabled *= *true'; then
  edits+=(-e "/^subsection Convergence study/,/^end/{
            s/^\( *set Subdivisions *=\).*/\1 $(first Subdivisions 1-2)/
            s/^\( *set Time steps *=\).*/\1 $(first 'Time steps' 1-2)/
            s/^\( *set Reference subdivisions *=\).*/\1 $(first Subdivisions 3)/
            s/^\( *set Reference time step *=\).*/\1 $(first 'Time steps' 3)/
          }")
  sed "${edits[@]}" "$prm" > scene.prm
else
  sed "${edits[@]}" "$prm" > scene.prm
  printf '\nsubsection Checkpoint\n  set Stop after step = 2\nend\n' >> scene.prm
fi

"$(dirname "$0")/run_mpi.sh" 1 "$executable" scene.prm > output.txt 2> error.txt
status=$?
if [ $status -ne 0 ]; then
  echo "$prm, cut short, failed with exit status $status:"
  cat error.txt
  exit 1
fi
pattern='^Step +[0-9]+  t =|^  final (state|contact):|^Final displacement|^ +1/[0-9]+ '
# The wall time of a study's runs (column 5 of its rows) is left out.
grep -E "$pattern" output.txt | sed -e 's/  \[[^]]*\]$//' \
  | awk '/^ +1\// { $5 = "-" } { print }' > observed.txt
if [ ! -s observed.txt ]; then
  echo "$prm, cut short, printed no step, final state or table row:"
  cat output.txt
  exit 1
fi
if [ "${UPDATE:-0}" = 1 ]; then
  cp observed.txt "$reference"
  echo "Wrote $reference."
  exit 0
fi
if ! numdiff -q -a 1e-10 -r 1e-6 -s ' \t\n=,:;<>[](){}^' "$reference" observed.txt > /dev/null; then
  echo "$prm, cut short, differs from $reference beyond -a 1e-10 -r 1e-6:"
  numdiff -a 1e-10 -r 1e-6 -s ' \t\n=,:;<>[](){}^' "$reference" observed.txt | head -30
  exit 1
fi
echo "$prm, cut short, matches $reference ($(wc -l < observed.txt) lines)."
