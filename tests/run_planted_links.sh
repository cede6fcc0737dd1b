#!/bin/bash
# Files are created, not followed (doc/robustness.md, "Output folders"):
# symbolic links planted in the output folder never make a run write
# outside it.
#  - links under every temporary name a writer could use (NAME.tmp of every
#    kind of file, the manifest's .new) before a fresh run and before a
#    resumed one: the runs succeed, the files outside are unchanged;
#  - a link under a final name that a resumed run would write: the resume is
#    refused, naming it; a file of the run replaced by a link: Overwrite is
#    refused, naming it;
#  - a link under a final name planted while a run goes on: the run stops
#    with exit status 1 when it gets there, naming the file;
# and in every case the files the links point to are unchanged.
#   run_planted_links.sh EXECUTABLE [N]   (N MPI ranks, default 1)
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 ranks=${2:-1}
run() { # prm; sets status
  "$here/run_mpi.sh" "$ranks" "$executable" "$1" > out.txt 2> err.txt
  status=$?
}
rm -rf results outside work && mkdir -p outside work
for f in a b c d e f g h i j k; do echo "outside file $f" > outside/$f; done
(cd outside && md5sum ?) > work/outside.md5
outside_unchanged() {
  (cd outside && md5sum -c --quiet ../work/outside.md5 > /dev/null 2>&1) \
    || fail "$1: a file outside the output folder was overwritten."
}
plant() { # name target
  ln -sfn "$PWD/outside/$2" "results/$1"
}

# A fresh run with links under the temporary names.
mkdir -p results
plant solution.pvd.tmp a
plant solution_0009.0.vtu.tmp b
plant solution_0009.1.vtu.tmp c
plant parameters.prm.tmp d
plant time_series.csv.tmp e
plant contact_profile_0008.csv.tmp f
plant solution_0009.pvtu.tmp g
plant .viscoplastic_contact.manifest.new h
set_entry "Stop after step" 6 < "$base" > work/stop.prm
run work/stop.prm
[ $status -eq 0 ] || fail "The run with links under temporary names failed: $(cat err.txt)"
outside_unchanged "Fresh run"

# Resumed, with links under the temporary names of the checkpoint too.
plant checkpoint/step_000008.bin.tmp i
plant checkpoint/checkpoint.info.tmp j
plant checkpoint/step_000008.bin.tmp.new k
set_entry "Resume" true < "$base" | set_entry "End time" 0.75 > work/resume.prm
cp -a results work/stopped
run work/resume.prm
[ $status -eq 0 ] || fail "The resumed run with links under temporary names failed: $(cat err.txt)"
outside_unchanged "Resumed run"

# A link under a final name the resumed run would write: refused.
rm -rf results && cp -a work/stopped results
plant solution_0010.0.vtu a
run work/resume.prm
[ $status -eq 1 ] || fail "Resume with a link under solution_0010.0.vtu: exit status $status, not 1."
grep -q "no manifest of this program lists, or links under them (solution_0010.0.vtu)" err.txt \
  || fail "The refused resume does not name the link: $(cat err.txt)"
outside_unchanged "Refused resume"

# A file of the run replaced by a link: Overwrite refuses the folder,
# naming it (it neither removes the link nor writes through it).
rm -rf results && cp -a work/stopped results
rm results/solution_0003.0.vtu
plant solution_0003.0.vtu c
sed -e "s/^\( *set Write vtu *=.*\)/\1\n  set Overwrite = true/" "$base" > work/overwrite.prm
run work/overwrite.prm
[ $status -eq 1 ] || fail "Overwrite with a link in place of a file of the run: exit status $status, not 1."
grep -q "or links under them (solution_0003.0.vtu)" err.txt \
  || fail "The refused Overwrite does not name the link: $(cat err.txt)"
[ -L results/solution_0003.0.vtu ] || fail "The link was removed."
outside_unchanged "Overwrite with a link in place of a file of the run"

# A link planted while the run goes on, under the name of a step about 2000
# steps later (several seconds of margin).
rm -rf results
set_entry "Time step" 0.00048828125 < "$base" | set_entry "Checkpoint interval" 0 \
  | set_entry "Profile times" 1 | set_entry "Output interval" 16 > work/long.prm
"$here/run_mpi.sh" "$ranks" "$executable" work/long.prm > out.txt 2> err.txt &
job=$!
wait_for_step 20 out.txt $job
plant solution_2000.0.vtu b
wait $job
status=$?
[ $status -eq 1 ] || fail "The run with a link planted under solution_2000.0.vtu: exit status $status, not 1."
grep -q "The file results/solution_2000.0.vtu is in the way" err.txt \
  || fail "The run does not name the file in the way: $(cat err.txt)"
[ -L results/solution_2000.0.vtu ] || fail "The planted link was replaced."
outside_unchanged "Link planted during the run"
echo "No planted link was followed on $ranks rank(s): temporary names are never used, final names are never replaced."
