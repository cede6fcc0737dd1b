#!/bin/bash
# Output paths (doc/robustness.md, "Output folders"):
#  - a folder path of more than 300 characters (six components of 50) on 2
#    ranks: the run ends normally with its files there, and nothing on
#    standard error (no abort in an MPI-I/O component, no error noise);
#  - a component of 300 characters: exit status 1 and the system's "File
#    name too long", naming the entry;
#  - a '#' inside the value of Output directory: a warning that the value
#    ends there, and the run writes into the cut path.
#   run_paths.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
component=$(printf 'd%.0s' $(seq 1 50))
deep=deep/$component/$component/$component/$component/$component/$component
rm -rf deep work long cut "cut#2" && mkdir -p work
[ ${#deep} -gt 300 ] || fail "The test path is too short."

set_entry "Output directory" "$deep" < "$base" | set_entry "End time" 0.25 \
  | set_entry "Profile times" 0.25 > work/deep.prm
"$here/run_mpi.sh" 2 "$executable" work/deep.prm > out.txt 2> err.txt
status=$?
[ $status -eq 0 ] || fail "The run into a path of ${#deep} characters: exit status $status: $(cat err.txt)"
[ -e "$deep/solution_0004.pvtu" ] && [ -e "$deep/checkpoint/checkpoint.info" ] \
  || fail "The run into the long path did not write its files."
[ ! -s err.txt ] || fail "The run into the long path printed on standard error: $(head -5 err.txt)"

long=long/$(printf 'x%.0s' $(seq 1 300))
set_entry "Output directory" "$long" < work/deep.prm > work/long.prm
"$executable" work/long.prm > out.txt 2> err.txt
status=$?
[ $status -eq 1 ] || fail "A path component of 300 characters: exit status $status, not 1."
grep -q "Invalid parameter <Output directory> in subsection <Output>: .*File name too long" err.txt \
  || fail "The message does not name the entry and the reason: $(cat err.txt)"

set_entry "Output directory" "cut#2" < work/deep.prm > work/cut.prm
"$executable" work/cut.prm > out.txt 2> err.txt
status=$?
[ $status -eq 0 ] || fail "The run with '#' in its Output directory failed: $(cat err.txt)"
grep -q "the value of <Output directory> ends at the '#' .* the run uses <cut>" err.txt \
  || fail "No warning about the '#' in the path: $(cat err.txt)"
[ -e cut/time_series.csv ] || fail "The run did not write into the cut path."
echo "Long output paths work on 2 ranks without noise, a too long component is refused by name, a '#' in a path is warned about."
