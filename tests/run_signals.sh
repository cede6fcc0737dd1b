#!/bin/bash
# Scheduler signals, sent for real while the run is in its time loop:
#  - SIGTERM, SIGINT or SIGUSR1: the run finishes the step, writes a
#    checkpoint (none is due: Checkpoint interval = 0), says at which step it
#    stopped and how to resume, and exits with status 128 + signal; resumed
#    from that checkpoint, it ends with the time series of an uninterrupted
#    run (identical on 1 rank; numdiff -a 1e-10 -r 1e-8 on 2, where MUMPS
#    and the parallel sums are not bit-reproducible);
#  - on 2 ranks: SIGTERM to rank 1 alone (both ranks must agree on the step)
#    and SIGUSR1 to mpirun (which forwards it); SIGINT and SIGTERM to
#    mpirun, which ends the job at once itself (doc/robustness.md): one note
#    from rank 0 that says so, and the next run into the folder works;
#  - two signals in a row (1 rank): the run ends at once, without the
#    orderly stop;
#  - a signal during the set-up (1 rank): the run stops after the phase it
#    is in, before anything is written, with status 128 + signal.
# The signal is sent as soon as the log shows step 20 while the run is still
# going, which also shows that progress lines reach a log file as they
# happen.
#   run_signals.sh EXECUTABLE RANKS
set -u
here=$(cd "$(dirname "$0")" && pwd)
executable=$1 ranks=$2
fail() { echo "$*"; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
rm -rf full stopped && mkdir -p full stopped
# 256 steps on a 16 x 16 mesh, about a second per run.
sed -e 's/^\( *set Subdivisions *=\).*/\1 16/' \
    -e 's/^\( *set Time step *=\).*/\1 0.00390625/' \
    -e 's/^\( *set Write vtu *=\).*/\1 false/' \
    -e 's/^\( *set Checkpoint interval *=\).*/\1 0/' \
    "$here/robustness/small.prm" > scene.prm
sed -e "s/^\( *set Resume *=\).*/\1 true/" scene.prm > resume.prm
(cd full && "$here/run_mpi.sh" "$ranks" "$executable" ../scene.prm > out.txt 2> err.txt) \
  || fail "The uninterrupted run failed: $(cat full/err.txt)"
cut -d, -f1-8 full/results/time_series.csv > full/series.txt

# The PID of rank 1 among the children of mpirun.
rank_pid() { # mpirun_pid rank
  local pid
  for pid in $(pgrep -P "$1"); do
    if tr '\0' '\n' < "/proc/$pid/environ" 2>/dev/null | grep -qx "OMPI_COMM_WORLD_RANK=$2"; then
      echo "$pid"; return
    fi
  done
}

# Starts the run in stopped/, waits for step 20 in its log, sends the
# signal(s) to the target (run: the process started; rank1: rank 1 alone),
# and waits for the end; sets status and log.
interrupt() { # target signal [signal]
  # The log of the last case must not be mistaken for this one's.
  rm -rf stopped/results stopped/out.txt stopped/err.txt
  (cd stopped && exec "$here/run_mpi.sh" "$ranks" "$executable" ../scene.prm > out.txt 2> err.txt) &
  local pid=$! start=$SECONDS
  until grep -q "^Step   20 " stopped/out.txt 2>/dev/null; do
    kill -0 $pid 2> /dev/null || fail "The run ended before step 20 was logged: $(cat stopped/err.txt)"
    [ $((SECONDS - start)) -lt 60 ] || { kill -KILL $pid; fail "No step 20 in the log after 60 s."; }
    sleep 0.01
  done
  kill -0 $pid 2> /dev/null || fail "Step 20 reached the log only after the run ended."
  local target=$pid
  if [ "$1" = rank1 ]; then
    target=$(rank_pid $pid 1)
    [ -n "$target" ] || fail "Rank 1 not found."
  fi
  shift
  for signal in "$@"; do kill -s "$signal" "$target"; done
  local waited=0
  while kill -0 $pid 2> /dev/null; do
    sleep 0.1; waited=$((waited + 1))
    [ $waited -lt 300 ] || { kill -KILL $pid; fail "The run did not end within 30 s of the signal."; }
  done
  wait $pid
  status=$?
}

# An orderly stop on the signal, and a resumed run that ends as the
# uninterrupted one.
check_stop_and_resume() { # label signal_number
  [ $status -eq $((128 + $2)) ] || fail "$1: exit status $status, not $((128 + $2)): $(cat stopped/err.txt)"
  local step
  step=$(sed -n 's/^Stopped after step \([0-9]*\) (t = .*) on SIG.*; the checkpoint of step .*/\1/p' stopped/out.txt)
  [ -n "$step" ] || fail "$1: no message saying where the run stopped: $(cat stopped/out.txt | tail -3)"
  grep -q "set Resume = true in subsection <Checkpoint>" stopped/out.txt || fail "$1: no word on how to resume."
  [ "$step" -lt 256 ] || fail "$1: stopped only at the end."
  grep -qx "step $step" stopped/results/checkpoint/checkpoint.info \
    || fail "$1: the checkpoint of step $step was not written."
  (cd stopped && "$here/run_mpi.sh" "$ranks" "$executable" ../resume.prm > resumed.txt 2> err.txt) \
    || fail "$1: resuming failed: $(cat stopped/err.txt)"
  grep -q "^Resuming from the checkpoint of step $step " stopped/resumed.txt || fail "$1: not resumed from step $step."
  cut -d, -f1-8 stopped/results/time_series.csv > stopped/series.txt
  if [ "$ranks" -eq 1 ]; then
    cmp -s full/series.txt stopped/series.txt
  else
    numdiff -q -a 1e-10 -r 1e-8 -s ' \t\n,' full/series.txt stopped/series.txt > /dev/null
  fi || fail "$1: the resumed run differs from the uninterrupted one."
  echo "$1: stopped after step $step, resumed to the uninterrupted result."
}

if [ "$ranks" -eq 1 ]; then
  interrupt run TERM; check_stop_and_resume "SIGTERM" 15
  interrupt run INT;  check_stop_and_resume "SIGINT" 2
  interrupt run USR1; check_stop_and_resume "SIGUSR1" 10
  # Two SIGTERMs. The second must reach the process after its handler took
  # the first (two signals of one kind that are pending together count as
  # one): /proc/PID/status shows in SigCgt which signals the process
  # catches; SIGTERM's bit (1 << 14) is set once the handler is installed and
  # clear again once it has taken the first signal, when the default action
  # is back. A slower scene (about 4 s), so that this all happens long before
  # the run could end by itself.
  caught_term() { # pid: SIGTERM is caught (0) or not (1)
    local mask
    mask=$(awk '/^SigCgt/ { print $2 }' "/proc/$1/status" 2> /dev/null) || return 1
    [ -n "$mask" ] && [ $((0x$mask & 0x4000)) -ne 0 ]
  }
  start_once_handled() { # prm: runs it in stopped/; sets pid and start
    rm -rf stopped/results stopped/out.txt stopped/err.txt
    (cd stopped && exec "$executable" "../$1" > out.txt 2> err.txt) &
    pid=$!
    start=$SECONDS
    until caught_term $pid; do
      [ $((SECONDS - start)) -lt 30 ] || { kill -KILL $pid; fail "The handler was not installed within 30 s."; }
      sleep 0.01
    done
  }
  sed -e 's/^\( *set Subdivisions *=\).*/\1 96/' \
      -e 's/^\( *set Time step *=\).*/\1 0.0625/' \
      -e 's/^\( *set Method *=\).*/\1 full space/' scene.prm > slow.prm
  start_once_handled slow.prm
  kill -TERM $pid
  while caught_term $pid; do sleep 0.01; done
  kill -TERM $pid 2> /dev/null
  wait $pid
  status=$?
  [ $status -eq 143 ] || fail "Two SIGTERMs: exit status $status, not 143."
  grep -q "^Signal received: the run stops at the end of the current time step" stopped/err.txt \
    || fail "Two SIGTERMs: the first was not taken by the handler."
  ! grep -q "^Stopped after step\|^Run summary" stopped/out.txt \
    || fail "Two SIGTERMs: the run did not end at once."
  echo "Two SIGTERMs: ended at once ($((SECONDS - start)) s after the start)."
  # A SIGTERM during the set-up (a mesh of 256 x 256 squares, a second or so
  # of set-up), as soon as the handler is installed: the run stops after the
  # phase it is in, with status 143 and a word on where, before anything is
  # written (its Output directory does not exist).
  sed -e 's/^\( *set Subdivisions *=\).*/\1 256/' scene.prm > large.prm
  start_once_handled large.prm
  kill -TERM $pid
  wait $pid
  status=$?
  [ $status -eq 143 ] || fail "SIGTERM during the set-up: exit status $status, not 143: $(cat stopped/err.txt)"
  grep -q "^Stopped during the set-up (.*) on SIGTERM; no time step was computed" stopped/out.txt \
    || fail "SIGTERM during the set-up: no word on where the run stopped: $(tail -3 stopped/out.txt)"
  [ ! -e stopped/results ] || fail "SIGTERM during the set-up: the run wrote into its Output directory."
  echo "SIGTERM during the set-up: $(sed -n 's/^Stopped during the set-up (\(.*\)) on.*/stopped \1/p' stopped/out.txt), $((SECONDS - start)) s after the start."
else
  interrupt rank1 TERM; check_stop_and_resume "SIGTERM to rank 1 of $ranks" 15
  interrupt run USR1;   check_stop_and_resume "SIGUSR1 to mpirun" 10
  # SIGINT or SIGTERM to mpirun: Open MPI kills the ranks right after
  # passing a SIGTERM on (its exit status is its own). Rank 0 says so
  # once, and how to stop with a checkpoint; the next run into the folder
  # (Overwrite) works and leaves no folder of temporaries behind.
  for signal in INT TERM; do
    interrupt run $signal
    [ $status -ne 0 ] || fail "SIG$signal to mpirun: exit status 0."
    [ "$(grep -c '^Signal received' stopped/err.txt)" -eq 1 ] \
      || fail "SIG$signal to mpirun: not one note: $(cat stopped/err.txt)"
    grep -q "If it was sent to mpirun, Open MPI ends the job at once.*send SIGUSR1 to mpirun" stopped/err.txt \
      || fail "SIG$signal to mpirun: the note does not say what mpirun does: $(cat stopped/err.txt)"
    sed -e 's/^\( *set Overwrite *=\).*/\1 true/' scene.prm > overwrite.prm
    grep -q "Overwrite *= *true" overwrite.prm || sed -i 's/^\(subsection Output\)$/\1\n  set Overwrite = true/' overwrite.prm
    (cd stopped && "$here/run_mpi.sh" "$ranks" "$executable" ../overwrite.prm > again.txt 2> err.txt) \
      || fail "SIG$signal to mpirun: the next run into the folder failed: $(cat stopped/err.txt)"
    ! ls -d stopped/results/.viscoplastic_contact.tmp.* > /dev/null 2>&1 \
      || fail "SIG$signal to mpirun: a folder of temporaries was left behind."
    echo "SIG$signal to mpirun: the job ended (status $status) with one note on what mpirun does; the next run works."
  done
fi
