#!/bin/bash
# A failed write (a full disk, simulated by the test switch
# VISCOPLASTIC_CONTACT_FAIL_WRITE=PATTERN[:N], see include/robustness/file_output.h)
# must stop the run on every rank within seconds with exit status 1 and a
# message that names the file and the reason ("No space left on device"),
# leave no temporary or truncated file behind, and keep the last complete
# checkpoint usable: resumed from it, the run ends with the time series of
# an uninterrupted run. On 2 ranks every solver choice is tried, among them
# the full space back end with Preconditioner = direct (MUMPS), which used
# to hang in a collective call of its destructor.
#   run_write_failure.sh EXECUTABLE RANKS
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 ranks=$2

scene() { # method preconditioner write_vtu > scene.prm
  sed -e "s/^\( *set Method *=\).*/\1 $1/" \
      -e "s/^\( *set Preconditioner *=\).*/\1 $2/" \
      -e "s/^\( *set Write vtu *=\).*/\1 $3/" "$base"
}

# One run that must fail on the writes of PATTERN[:N].
expect_failure() { # label pattern file
  rm -rf results
  local start=$SECONDS
  VISCOPLASTIC_CONTACT_FAIL_WRITE=$2 timeout 60 \
    "$here/run_mpi.sh" "$ranks" "$executable" scene.prm > out.txt 2> err.txt
  local status=$?
  [ $status -eq 1 ] || fail "$1, failing $2: exit status $status, not 1 (124: hang)."
  [ $((SECONDS - start)) -le 20 ] || fail "$1, failing $2: took $((SECONDS - start)) s."
  grep -aq "Writing the file results/$3 failed: No space left on device" err.txt \
    || fail "$1, failing $2: no message naming results/$3 and the reason: $(cat err.txt)"
  [ -z "$(find results -name '*.tmp')" ] || fail "$1, failing $2: a temporary file was left."
  # A file written once must not exist; the time series (appended) must end
  # in a complete row; the .pvd record (rewritten) must be the complete
  # previous one.
  case $3 in
    time_series.csv) awk -F, 'NR == 1 { n = NF } NF != n { exit 1 }' "results/$3" \
           || fail "$1, failing $2: results/$3 has an incomplete row." ;;
    solution.pvd) tail -1 "results/$3" | grep -q "</VTKFile>" \
           || fail "$1, failing $2: results/$3 is not complete." ;;
    *) [ ! -e "results/$3" ] || fail "$1, failing $2: results/$3 was left behind." ;;
  esac
}

configurations="auto:amg"
[ "$ranks" -gt 1 ] && configurations="condensed:amg full_space:amg full_space:direct"
n=0
for configuration in $configurations; do
  method=${configuration%%:*} preconditioner=${configuration##*:}
  method=${method/_/ }
  label="$ranks rank(s), Method = $method, Preconditioner = $preconditioner"
  scene "$method" "$preconditioner" true > scene.prm
  expect_failure "$label" time_series.csv:5 time_series.csv
  expect_failure "$label" "solution_0003.$((ranks - 1)).vtu" "solution_0003.$((ranks - 1)).vtu"
  n=$((n + 2))
  # The other files once per rank count (their writers do not depend on
  # the solver): with the last configuration, the one that used to hang.
  if [ "$configuration" = "${configurations##* }" ]; then
    expect_failure "$label" contact_profile contact_profile_0008.csv
    expect_failure "$label" solution.pvd:3 solution.pvd
    n=$((n + 2))
  fi
  if [ "$ranks" -eq 1 ]; then
    expect_failure "$label" parameters.prm parameters.prm
    expect_failure "$label" solution_0003.pvtu solution_0003.pvtu
    scene "$method" "$preconditioner" false > scene.prm
    expect_failure "$label, Write vtu = false" time_series.csv:5 time_series.csv
    scene "$method" "$preconditioner" true > scene.prm
    n=$((n + 3))
  fi
done

# The checkpoint of step 6 fails: the one of step 4 stays, and a run resumed
# from it ends as the uninterrupted run.
rm -rf full && mkdir -p full
(cd full && "$here/run_mpi.sh" "$ranks" "$executable" ../scene.prm > out.txt 2> err.txt) \
  || fail "The uninterrupted run failed: $(cat full/err.txt)"
expect_failure "$label" step_000006 checkpoint/step_000006.bin
grep -q "^step 4$" results/checkpoint/checkpoint.info \
  || fail "checkpoint.info does not name step 4 after the failed checkpoint."
sed -e "s/^\( *set Resume *=\).*/\1 true/" scene.prm > resume.prm
"$here/run_mpi.sh" "$ranks" "$executable" resume.prm > out.txt 2> err.txt \
  || fail "Resuming after the failed checkpoint failed: $(cat err.txt)"
grep -q "^Resuming from the checkpoint of step 4 " out.txt || fail "Not resumed from step 4."
# Identical on one rank; on two, MUMPS and the parallel sums are not
# bit-reproducible from run to run, so numdiff with the tolerances of
# run_resume_check.sh for other rank counts (the CSV has 10 digits).
cut -d, -f1-8 full/results/time_series.csv > full.txt
cut -d, -f1-8 results/time_series.csv > resumed.txt
if [ "$ranks" -eq 1 ]; then
  cmp -s full.txt resumed.txt
else
  numdiff -q -a 1e-10 -r 1e-8 -s ' \t\n,' full.txt resumed.txt > /dev/null
fi || fail "The resumed run's time series differs from the uninterrupted run's."
echo "$((n + 1)) simulated write failures on $ranks rank(s) ended every rank with status 1 and the file and reason; the last complete checkpoint resumed to the uninterrupted result."
