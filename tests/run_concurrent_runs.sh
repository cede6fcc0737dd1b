#!/bin/bash
# One run per output folder (doc/robustness.md, "Output folders"):
#  - while a run goes on, a second run into its folder (another Young's
#    modulus; also with Overwrite = true, and with Resume = true) is
#    refused at once with exit status 1, naming the folder and the process
#    of the first run, which ends normally with a time series of its own
#    steps only, in order;
#  - two runs started together into a folder that does not exist yet: one
#    runs, the other is refused, and the folder holds the results of one of
#    them.
#   run_concurrent_runs.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
steps_in_order() { # time series, number of steps
  tail -n +2 "$1" | cut -d, -f1 | tr '\n' ' ' | grep -qx "$(seq -s ' ' 1 "$2") "
}
rm -rf results work && mkdir -p work
# Runs that overlap keep Open MPI's session files apart (one-rank runs
# started without mpirun all take the same job name); env execs the
# program, so $! is the run's process.
session="env OMPI_MCA_orte_tmpdir_base=work/mpi"

# A long run, and a second run into its folder while it goes on. The first
# run's standard output goes into a pipe that is read only after the others
# have tried: its 1024 steps print about 130 kB, more than a pipe holds, so
# it blocks while it holds the folder's lock, however fast the machine is
# or however late this script gets a core.
set_entry "Time step" 0.0009765625 < "$base" | set_entry "Checkpoint interval" 16 \
  | set_entry "Profile times" 1 | set_entry "Write vtu" false > work/first.prm
set_entry "Young's modulus" 2000 < work/first.prm > work/second.prm
sed -e "s/^\( *set Write vtu *=.*\)/\1\n  set Overwrite = true/" work/second.prm > work/overwrite.prm
set_entry "Resume" true < work/first.prm > work/resume.prm
rm -f first.pipe && mkfifo first.pipe
$session.first "$executable" work/first.prm > first.pipe 2> first_err.txt &
first=$!
exec 3< first.pipe
for i in $(seq 1 600); do
  grep -q "^process $first on " results/.viscoplastic_contact.lock 2> /dev/null && break
  kill -0 $first 2> /dev/null || break
  sleep 0.05
done
grep -q "^process $first on " results/.viscoplastic_contact.lock 2> /dev/null \
  || fail "The first run did not take the folder's lock: $(cat first_err.txt)"
for prm in second overwrite resume; do
  start=$(date +%s)
  $session.$prm "$executable" work/$prm.prm > second.txt 2> second_err.txt
  status=$?
  [ $status -eq 1 ] || fail "The $prm run into the used folder: exit status $status, not 1."
  [ $(( $(date +%s) - start )) -le 10 ] || fail "The $prm run took more than 10 s to be refused."
  grep -q "value <results>; another run is writing into it (process $first on " second_err.txt \
    || fail "The refusal of the $prm run does not name the folder and process $first: $(cat second_err.txt)"
done
kill -0 $first 2> /dev/null || fail "The first run ended before the second runs were refused."
cat <&3 > first.txt
exec 3<&-
wait $first
status=$?
[ $status -eq 0 ] || fail "The first run failed: $(cat first_err.txt)"
steps_in_order results/time_series.csv 1024 \
  || fail "The time series of the first run is not steps 1 to 1024 in order."
grep -q "set Young's modulus *= 1000" results/parameters.prm \
  || fail "parameters.prm is not that of the first run."

# Two runs started together into a new folder.
rm -rf results
set_entry "Time step" 0.0625 < work/first.prm > work/a.prm
set_entry "Young's modulus" 2000 < work/a.prm > work/b.prm
$session.a "$executable" work/a.prm > a.txt 2> a_err.txt &
a=$!
$session.b "$executable" work/b.prm > b.txt 2> b_err.txt &
b=$!
wait $a
status_a=$?
wait $b
status_b=$?
[ $((status_a + status_b)) -eq 1 ] \
  || fail "Two runs into one new folder: exit statuses $status_a and $status_b, not 0 and 1 ($(cat a_err.txt b_err.txt))."
refused=$([ $status_a -eq 1 ] && echo a_err.txt || echo b_err.txt)
# Refused by the lock, or (if the other run was over by then) by its files.
grep -q "another run is writing into it\|holds the files of another run" $refused \
  || fail "The refused run does not say why: $(cat $refused)"
steps_in_order results/time_series.csv 16 \
  || fail "The time series of the two runs is not steps 1 to 16 of one run."
echo "A second run into a used folder is refused at once, naming the process; of two runs started together, one runs."
