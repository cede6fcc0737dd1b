#!/bin/bash
# Writes that really fail part-way (doc/robustness.md, "Write failures"),
# not only the test switch that makes a write report an error:
#  - a file size limit (ulimit -f: write() writes what fits and then fails
#    with EFBIG): 64 kB, where the .vtu pieces of h = 1/32 after the
#    initial state do not fit, nor the first checkpoint of h = 1/16 (a file
#    all ranks write together, its blocks at their offsets; no .vtu
#    output, and the parameter file the run copies fits);
#  - if this machine lets the test mount a 300 kB tmpfs (root with
#    CAP_SYS_ADMIN; skipped otherwise, and said): a full disk in the middle
#    of the run, after which the folder is copied to a larger disk and
#    resumed from its last checkpoint to the end of an uninterrupted run.
# Each run must stop with exit status 1 and a message naming the file that
# failed and the system's reason; no file under a final name may be
# truncated (every .vtu ends with </VTKFile>, the checkpoint that
# checkpoint.info names is complete: the resumed run reads it), and no
# temporary is left.
#   run_full_disk.sh EXECUTABLE [N]   (N MPI ranks, default 1)
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1 ranks=${2:-1}
no_truncated_file() { # folder
  for f in "$1"/*.vtu; do
    [ -e "$f" ] || continue
    tail -c 12 "$f" | grep -q "</VTKFile>" || fail "$f is truncated."
  done
  for d in "$1"/.viscoplastic_contact.tmp.*; do
    [ -e "$d" ] || continue
    [ -z "$(ls -A "$d")" ] || fail "Temporaries are left in $d: $(ls -A "$d")"
  done
}
rm -rf limit disk resumed full work && mkdir -p work

# A file size limit: each run in a subshell with the limit (the program
# ignores SIGXFSZ, so that a write beyond it fails with EFBIG).
# The limit applies to every file of the process, also to the shared-memory
# files of Open MPI (its PMIx data and, on several ranks, the shared-memory
# transport), which it would stop at start-up: PMIX_MCA_gds=hash and
# OMPI_MCA_btl=self,tcp keep the limit to the program's own files.
limited_run() { # kilobytes prm; sets status
  (ulimit -f "$1"; export PMIX_MCA_gds=hash OMPI_MCA_btl=self,tcp
   "$here/run_mpi.sh" "$ranks" "$executable" "$2" > out.txt 2> err.txt)
  status=$?
}
set_entry "Subdivisions" 32 < "$base" | set_entry "Output directory" limit > work/vtu.prm
limited_run 64 work/vtu.prm
[ $status -eq 1 ] || fail "A .vtu piece beyond the file size limit: exit status $status, not 1."
piece=$(sed -n 's/.*Writing the file limit\/\(solution_[0-9]*\.[0-9]*\.vtu\) failed: File too large\..*/\1/p' err.txt | head -1)
[ -n "$piece" ] || fail "The message does not name a .vtu piece and the reason: $(cat err.txt)"
[ ! -e "limit/$piece" ] || fail "The piece that failed, $piece, is under its final name."
no_truncated_file limit
rm -rf limit
set_entry "Subdivisions" 16 < "$base" | set_entry "Write vtu" false \
  | set_entry "Output directory" limit > work/checkpoint.prm
limited_run 64 work/checkpoint.prm
[ $status -eq 1 ] || fail "A checkpoint beyond the file size limit: exit status $status, not 1."
grep -q "Writing the file limit/checkpoint/step_000002.bin failed: File too large." err.txt \
  || fail "The message does not name the checkpoint and the reason: $(cat err.txt)"
[ -z "$(ls -A limit/checkpoint)" ] || fail "The failed checkpoint left $(ls -A limit/checkpoint)."
no_truncated_file limit

# A full disk, if a small file system can be mounted here.
mkdir -p disk
if ! mount -t tmpfs -o size=300k tmpfs disk 2> /dev/null; then
  echo "A file size limit stops the run cleanly on $ranks rank(s); a full disk was not tried (this machine does not let the test mount a file system)."
  exit 0
fi
trap 'umount disk 2> /dev/null' EXIT
set_entry "Output directory" disk/results < "$base" > work/disk.prm
"$here/run_mpi.sh" "$ranks" "$executable" work/disk.prm > out.txt 2> err.txt
status=$?
[ $status -eq 1 ] || fail "A run onto a full disk: exit status $status, not 1."
grep -q "Writing the file disk/results/.* failed: No space left on device." err.txt \
  || fail "The message does not name a file and the full disk: $(cat err.txt)"
no_truncated_file disk/results
[ -e disk/results/checkpoint/checkpoint.info ] \
  || fail "The disk was full before the first checkpoint; the test needs a later one."
cp -a disk/results resumed
umount disk
set_entry "Output directory" resumed < "$base" | set_entry "Resume" true > work/resume.prm
"$here/run_mpi.sh" "$ranks" "$executable" work/resume.prm > out.txt 2> err.txt
status=$?
[ $status -eq 0 ] || fail "The run resumed from the last checkpoint on the full disk failed: $(cat err.txt)"
set_entry "Output directory" full < "$base" > work/full.prm
"$here/run_mpi.sh" "$ranks" "$executable" work/full.prm > out.txt 2> err.txt
cut -d, -f1-8,11,12 full/time_series.csv > work/full.csv
cut -d, -f1-8,11,12 resumed/time_series.csv > work/resumed.csv
numdiff -q -a 1e-10 -r 1e-8 -s ' \t\n,' work/full.csv work/resumed.csv > /dev/null \
  || fail "The resumed run does not end as the uninterrupted one."
echo "A file size limit and a full disk stop the run cleanly on $ranks rank(s): no truncated file, no temporary, the last checkpoint resumes."
