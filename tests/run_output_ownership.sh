#!/bin/bash
# The program deletes and replaces only what it wrote (doc/robustness.md,
# "Output folders"):
#  - a folder with files under the program's names that no manifest lists
#    (a user's runs/ and checkpoint/ folders with their data, parameters.prm,
#    time_series.csv, solution.pvd, a solution_1.vtu of another program) is
#    refused with Overwrite = true, naming them, and left exactly as it was;
#    so is the same folder reached as "sub/..";
#  - Output directory = . with the scene file named parameters.prm there:
#    refused, the scene file unchanged;
#  - Overwrite = true over an earlier run removes exactly the files its
#    manifest lists: a user's notes.txt and a backup inside the run's
#    checkpoint/ stay, the earlier steps' files go, and the folder has no
#    temporaries and no lock file after the run;
#  - running the parameters.prm an earlier run wrote, with Overwrite = true
#    into that run's folder, is refused (it would remove the file being run).
#   run_output_ownership.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
run() { # prm [directory to run in]; sets status
  (cd "${2:-.}" && "$executable" "$1" > "$OLDPWD/out.txt" 2> "$OLDPWD/err.txt")
  status=$?
}
snapshot() { # folder: every file and folder with its content
  (cd "$1" && find . | sort && find . -type f | sort | xargs md5sum)
}
rm -rf user work results && mkdir -p work
set_entry "End time" 0.25 < "$base" | set_entry "Checkpoint interval" 2 | set_entry "Profile times" 0.25 \
  | set_entry "Overwrite" true > work/short.prm
grep -q "set Overwrite" work/short.prm \
  || sed -i -e "s/^\( *set Write vtu *=.*\)/\1\n  set Overwrite = true/" work/short.prm

# A user's folder with files under the program's names.
mkdir -p user/runs user/checkpoint
echo "thesis data" > user/runs/thesis.dat
echo "backup" > user/checkpoint/backup.tar
echo "# my commented scene" > user/parameters.prm
echo "step,my,own,series" > user/time_series.csv
echo "<VTKFile/>" > user/solution.pvd
echo "<VTKFile/>" > user/solution_1.vtu
echo "notes" > user/notes.txt
snapshot user > work/user_before.txt
set_entry "Output directory" "$PWD/user" < work/short.prm > work/into_user.prm
run "$PWD/work/into_user.prm"
[ $status -eq 1 ] || fail "Overwrite into a user's folder: exit status $status, not 1."
grep -q "holds files with the names of this program's output that no manifest of this program lists, or links under them (checkpoint, parameters.prm, runs, solution.pvd and 2 more)" err.txt \
  || fail "The refusal does not list the files in the way: $(cat err.txt)"
snapshot user | cmp -s - work/user_before.txt || fail "The refused run changed the user's folder."
mkdir -p user/sub
snapshot user > work/user_before.txt
set_entry "Output directory" "$PWD/user/sub/.." < work/short.prm > work/into_parent.prm
run "$PWD/work/into_parent.prm"
[ $status -eq 1 ] || fail "Overwrite into sub/..: exit status $status, not 1."
snapshot user | cmp -s - work/user_before.txt || fail "The refused run changed the user's folder (sub/..)."

# Output directory = . with the scene file named parameters.prm in it.
mkdir -p work/scene
set_entry "Output directory" . < work/short.prm > work/scene/parameters.prm
cp work/scene/parameters.prm work/scene_copy.prm
run parameters.prm work/scene
[ $status -eq 1 ] || fail "Output directory = . next to parameters.prm: exit status $status, not 1."
grep -q "no manifest of this program lists, or links under them (parameters.prm)" err.txt \
  || fail "The refusal does not name parameters.prm: $(cat err.txt)"
cmp -s work/scene/parameters.prm work/scene_copy.prm || fail "The scene file was changed."
[ "$(ls -A work/scene)" = parameters.prm ] || fail "The refused run left files: $(ls -A work/scene)"

# An earlier run of 8 steps, a user's notes and a backup in its checkpoint/.
set_entry "End time" 0.5 < work/short.prm | set_entry "Overwrite" false > work/earlier.prm
run "$PWD/work/earlier.prm"
[ $status -eq 0 ] || fail "The earlier run failed: $(cat err.txt)"
echo "notes" > results/notes.txt
echo "backup" > results/checkpoint/backup.tar
run "$PWD/work/short.prm"
[ $status -eq 0 ] || fail "Overwrite = true over an earlier run failed: $(cat err.txt)"
[ -e results/notes.txt ] && [ -e results/checkpoint/backup.tar ] \
  || fail "Overwrite removed a file that no run wrote."
for f in results/solution_0008.pvtu results/solution_0008.0.vtu results/checkpoint/step_000008.bin; do
  [ ! -e "$f" ] || fail "$f of the earlier run is still there."
done
[ "$(tail -n +2 results/time_series.csv | wc -l)" -eq 4 ] \
  || fail "The new time series does not have 4 rows."
leftovers=$(cd results && ls -A | grep '^\.viscoplastic_contact\.\(tmp\|lock\)')
[ -z "$leftovers" ] || fail "The run left $leftovers behind."
grep -q "^file checkpoint/step_000004.bin$" results/.viscoplastic_contact.manifest \
  || fail "The manifest does not list the checkpoint of step 4."

# The parameters.prm the run wrote (Overwrite = true, Output directory =
# results), run again as it is.
grep -q "set Overwrite *= true" results/parameters.prm \
  || fail "The listing of the run does not have Overwrite = true."
snapshot results > work/before.txt
run "$PWD/results/parameters.prm"
[ $status -eq 1 ] || fail "Running the run's own parameters.prm with Overwrite: exit status $status, not 1."
grep -q "which is the parameter file being run" err.txt \
  || fail "The refusal does not say that the parameter file would be removed: $(cat err.txt)"
snapshot results | cmp -s - work/before.txt || fail "The refused run changed the folder."
echo "Foreign files in the way are refused untouched, Overwrite removes exactly what the manifest lists, the parameter file being run is never removed."
