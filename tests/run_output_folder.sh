#!/bin/bash
# A new run never mixes its files with an earlier run's, and Resume takes
# up only a checkpoint of the same scene:
#  - a run into the folder of an earlier run is refused (exit 1, the folder
#    and its files named) and the folder is left exactly as it was;
#  - with Overwrite = true but a set-up that fails, the folder is still
#    untouched; with a good set-up the earlier run's files go (files of
#    the user stay), and every .vtu in the folder is in the new solution.pvd;
#  - Resume with another Young's modulus or Time step is refused, naming
#    the entries and both values; a longer End time is accepted and the
#    resumed run ends with the time series of an uninterrupted run to it;
#  - a time series deleted before a resume starts again with its header.
#   run_output_folder.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
run() { # prm; sets status
  "$executable" "$1" > out.txt 2> err.txt
  status=$?
}
snapshot() { (cd results && find . -type f | sort | xargs md5sum); }
rm -rf results work && mkdir work

# The earlier run: 16 steps with checkpoints, and a file of the user.
run "$base"
[ $status -eq 0 ] || fail "The first run failed: $(cat err.txt)"
echo "notes of the user" > results/notes.txt
snapshot > work/before.txt

# A new run of 8 steps into the same folder is refused.
set_entry "End time" 0.5 < "$base" > work/short.prm
run work/short.prm
[ $status -eq 1 ] || fail "The run into a used folder: exit status $status, not 1."
grep -q "value <results> holds the files of another run (checkpoint, contact_profile_0008.csv" err.txt \
  || fail "The refusal does not name the folder and the files: $(cat err.txt)"
snapshot | cmp -s - work/before.txt || fail "The refused run changed the folder."

# Overwrite = true, but the set-up fails (a load that is not finite).
sed -e "s/^\( *set Write vtu *=.*\)/\1\n  set Overwrite = true/" work/short.prm > work/overwrite.prm
set_entry "Surface traction" "0; 1\/(t-0.25)" < work/overwrite.prm > work/bad.prm
run work/bad.prm
[ $status -eq 1 ] || fail "The bad run with Overwrite: exit status $status, not 1."
snapshot | cmp -s - work/before.txt || fail "A run whose set-up failed changed the folder."

# Overwrite = true with a good set-up: only the new run's files remain.
run work/overwrite.prm
[ $status -eq 0 ] || fail "The run with Overwrite = true failed: $(cat err.txt)"
[ -e results/notes.txt ] || fail "Overwrite removed a file that no run wrote."
for f in results/solution_0016.pvtu results/checkpoint/step_000016.bin; do
  [ ! -e "$f" ] || fail "$f of the earlier run is still there."
done
for f in results/solution_*.pvtu; do
  grep -q "file=\"$(basename "$f")\"" results/solution.pvd \
    || fail "$f is not in the new solution.pvd."
done
[ "$(tail -n +2 results/time_series.csv | wc -l)" -eq 8 ] \
  || fail "The new time series does not have 8 rows."

# Resume with parameters that change the result is refused.
sed -e "s/^\( *set Resume *=\).*/\1 true/" work/short.prm > work/resume.prm
snapshot > work/before.txt
set_entry "Young's modulus" 2000 < work/resume.prm | set_entry "Time step" 0.03125 > work/changed.prm
run work/changed.prm
[ $status -eq 1 ] || fail "Resume with another scene: exit status $status, not 1."
grep -q "Material/Young's modulus = 2000 (checkpoint: 1000)" err.txt \
  && grep -q "Time/Time step = 0.03125 (checkpoint: 0.0625)" err.txt \
  || fail "The refused Resume does not name the entries: $(cat err.txt)"
snapshot | cmp -s - work/before.txt || fail "The refused Resume changed the folder."

# A longer End time is accepted: the resumed run goes on to T = 1 and ends
# as a run to T = 1 from the start.
set_entry "End time" 1 < work/resume.prm > work/longer.prm
run work/longer.prm
[ $status -eq 0 ] || fail "Resume to a later End time failed: $(cat err.txt)"
mkdir -p work/full
set_entry "Output directory" "work\/full\/results" < "$base" > work/full.prm
run work/full.prm
cmp -s <(cut -d, -f1-8 work/full/results/time_series.csv) <(cut -d, -f1-8 results/time_series.csv) \
  || fail "The run resumed to a later End time differs from an uninterrupted one."
# A time series deleted before a resume starts again with its header (and
# a warning that the rows up to the checkpoint are lost).
rm -rf results
set_entry "Stop after step" 6 < "$base" > work/stop6.prm
run work/stop6.prm
[ $status -eq 0 ] || fail "The run stopped after step 6 failed: $(cat err.txt)"
rm results/time_series.csv
set_entry "Resume" true < "$base" > work/resume6.prm
run work/resume6.prm
[ $status -eq 0 ] || fail "Resume without a time series failed: $(cat err.txt)"
grep -q "time_series.csv was missing or empty; it starts again with its header, and the rows of steps 1 to 6 are lost" err.txt \
  || fail "No warning about the lost rows: $(cat err.txt)"
head -1 results/time_series.csv | grep -q "^step,time,active_set_iterations," \
  || fail "The restored time series has no header."
[ "$(sed -n '2p' results/time_series.csv | cut -d, -f1)" = 7 ] \
  || fail "The restored time series does not go on with step 7."
echo "Used folders are refused untouched, Overwrite removes only a run's files after a good set-up, Resume refuses changed entries and extends to a later End time."
