#!/bin/bash
# The command line never destroys a file, and what it prints is complete:
#  - --print-parameters FILE writes the documented defaults (exit 0), and
#    the file states the ranges the program enforces (Subdivisions in
#    [1, 100000]); the printed file is a valid scene;
#  - a second --print-parameters FILE refuses (exit 1, a message naming the
#    file) and leaves the file as it was; with --force it replaces it;
#  - the printed defaults run, print the timing table and spend no solves
#    on the cost ratios, which Measure cost ratios = true adds;
#  - a parameter file without a single entry runs with a warning that every
#    value is the default.
#   run_command_line.sh EXECUTABLE
set -u
executable=$1
fail() { echo "$*"; exit 1; }
rm -rf work && mkdir work && cd work || exit 1

"$executable" --print-parameters scene.prm > out.txt 2> err.txt
[ $? -eq 0 ] || fail "--print-parameters scene.prm failed: $(cat err.txt)"
grep -q "in \[1, 100000\]" scene.prm \
  || fail "The printed parameters do not state the range of Subdivisions."
grep -q "Each in \[0, End" scene.prm \
  || fail "The printed parameters do not state the range of Profile times."
"$executable" --print-parameters > stdout.prm 2> err.txt
cmp -s scene.prm stdout.prm || fail "The file and standard output differ."

# The printed defaults are a valid scene (on a coarse mesh, two steps).
sed -e 's/^\( *set Subdivisions *=\).*/\1 2/' \
    -e 's/^\( *set Time step *=\).*/\1 0.5/' \
    -e 's/^\( *set Profile times *=\).*/\1 1/' \
    -e 's/^\( *set Output directory *=\).*/\1 coarse/' scene.prm > coarse.prm
"$executable" coarse.prm > out.txt 2> err.txt \
  || fail "The printed defaults are not accepted: $(cat err.txt)"
# By default the run prints its timing table but spends no solves on the
# cost ratios; Measure cost ratios = true adds them.
grep -q "Total wallclock time" out.txt \
  || fail "The default run printed no timing table."
grep -q "Cost measurement" out.txt \
  && fail "The default run measured the cost ratios."
sed -e 's/^\( *set Measure cost ratios *=\).*/\1 true/' \
    -e 's/^\( *set Output directory *=\).*/\1 measured/' coarse.prm \
  > measured.prm
"$executable" measured.prm > out.txt 2> err.txt \
  || fail "Measure cost ratios = true failed: $(cat err.txt)"
grep -q "ratio step / solve: [0-9]" out.txt \
  || fail "Measure cost ratios = true printed no ratio step / solve."

# An existing file is not overwritten.
echo "# my own scene" >> scene.prm
cp scene.prm before.prm
"$executable" --print-parameters scene.prm > out.txt 2> err.txt
status=$?
[ $status -eq 1 ] || fail "Overwriting scene.prm: exit status $status, not 1."
grep -q "<scene.prm> exists" err.txt \
  || fail "The refusal does not name the file: $(cat err.txt)"
cmp -s scene.prm before.prm || fail "The refused command changed scene.prm."
[ -z "$(ls scene.prm.* 2>/dev/null)" ] || fail "A temporary file was left."

# --force replaces it (before or after the file name).
"$executable" --print-parameters --force scene.prm > out.txt 2> err.txt \
  || fail "--force failed: $(cat err.txt)"
cmp -s scene.prm stdout.prm || fail "--force did not write the defaults."

# An entry-less file: a warning, then the defaults.
printf '# nothing set here\n\n' > empty.prm
"$executable" empty.prm > out.txt 2> err.txt \
  || fail "The entry-less file failed: $(cat err.txt)"
grep -q "sets no entry; every value is the default" err.txt \
  || fail "No warning for the entry-less file: $(cat err.txt)"
echo "--print-parameters refuses to overwrite, --force replaces, ranges are printed, an entry-less file is warned about."
