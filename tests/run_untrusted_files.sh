#!/bin/bash
# Every file the program reads back from its output folder is untrusted
# (doc/robustness.md, "Output folders"): something else may have planted or
# changed it. Each case below must end with exit status 1 and a message
# naming the file (or end normally where said), within 30 s (never block),
# and leave every file outside the run's own untouched:
#  - manifest lines the program never writes, obeyed by no run: a folder of
#    temporaries "../precious" (a new run), and with Overwrite: "../",
#    absolute paths, a path through a linked folder, a user's notes.txt,
#    the lock file, an empty kind;
#  - a manifest that is a named pipe, another account's file (as root
#    only), or a sparse file of 20 GB;
#  - a hard link planted as the lock file: refused, its target unchanged;
#  - a named pipe planted as checkpoint/checkpoint.info or time_series.csv
#    of a resumed run, or as the lock file;
#  - a folder locked by a running run whose lock file holds 1 MB with
#    terminal escapes: the refusal prints one line of it, printable;
#  - the folder of temporaries moved away during a run and another folder
#    put under its name: that folder keeps its files (the run, stopped by
#    SIGTERM, writes its checkpoint and ends with status 143).
#   run_untrusted_files.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
manifest=.viscoplastic_contact.manifest
lock=.viscoplastic_contact.lock
rm -rf results outside work precious && mkdir -p outside work precious
echo "a user's notes" > precious/notes.txt
echo "outside" > outside/file
(md5sum precious/notes.txt outside/file) > work/precious.md5
untouched() { # what
  md5sum -c --quiet work/precious.md5 > /dev/null 2>&1 \
    || fail "$1: a file that is not the run's was changed or removed."
}
# run PRM: the program on PRM, at most 30 s; sets status.
run() {
  timeout 30 "$executable" "$1" > out.txt 2> err.txt
  status=$?
  [ $status -ne 124 ] || fail "$1: no end within 30 s (it blocked)."
}
refused() { # what text
  [ $status -eq 1 ] || fail "$1: exit status $status, not 1: $(tail -3 err.txt)"
  grep -qF -- "$2" err.txt || fail "$1: the message does not say <$2>: $(cat err.txt)"
  untouched "$1"
}
set_entry "Stop after step" 4 < "$base" | set_entry "Write vtu" false > work/new.prm
set_entry Overwrite true < work/new.prm > work/overwrite.prm
set_entry Resume true < "$base" | set_entry "Write vtu" false > work/resume.prm
# A complete earlier run (stopped after step 4, checkpoint of step 4).
run work/new.prm
[ $status -eq 0 ] || fail "The first run failed: $(cat err.txt)"
cp -a results work/earlier

# A planted folder of temporaries outside, in a folder with nothing but
# the manifest: even a new run (Overwrite = false), which removes the
# temporaries of killed runs, refuses it.
rm -rf results && mkdir results
printf 'temporary ../precious\n' > "results/$manifest"
run work/new.prm
refused "temporary ../precious" "has the line <temporary ../precious>"

# Lines Overwrite must not obey.
ln -s "$PWD/precious" work/linked
for line in "file ../precious/notes.txt" "folder ../precious" \
            "file $PWD/precious/notes.txt" "file linked/notes.txt" \
            "file notes.txt" "file $lock" "file $manifest" "temporary .." \
            "file" "file checkpoint/../../precious/notes.txt"; do
  rm -rf results && cp -a work/earlier results
  cp precious/notes.txt results/notes.txt
  ln -s "$PWD/precious" results/linked
  echo "$line" >> "results/$manifest"
  run work/overwrite.prm
  refused "Overwrite with <$line>" "name this program never writes there"
  cmp -s precious/notes.txt results/notes.txt || fail "<$line>: the folder's notes.txt is gone."
done

# The manifest as a named pipe, as a sparse file of 20 GB, as another
# account's file.
rm -rf results && cp -a work/earlier results
rm "results/$manifest" && mkfifo "results/$manifest"
run work/overwrite.prm
refused "manifest as a named pipe" "is a named pipe"
rm "results/$manifest" && truncate -s 20G "results/$manifest"
run work/overwrite.prm
refused "manifest of 20 GB" "more than the 268435456 this program writes there"
if [ "$(id -u)" = 0 ] && id nobody > /dev/null 2>&1; then
  rm -rf results && cp -a work/earlier results
  chown nobody "results/$manifest"
  run work/overwrite.prm
  refused "another account's manifest" "belongs to another account"
  [ -e results/time_series.csv ] || fail "another account's manifest: its files were removed."
else
  echo "(not root: the case of another account's manifest is left out)"
fi

# A hard link planted as the lock file.
rm -rf results && cp -a work/earlier results
cp outside/file work/target && ln work/target "results/$lock"
run work/overwrite.prm
refused "the lock file a hard link" "a link to another file"
cmp -s work/target outside/file || fail "the lock file a hard link: its target was overwritten."

# Named pipes as files a resumed run reads, and as the lock file.
for name in checkpoint/checkpoint.info time_series.csv "$lock"; do
  rm -rf results && cp -a work/earlier results
  rm -f "results/$name" && mkfifo "results/$name"
  run work/resume.prm
  refused "$name a named pipe" "named pipe"
done

# A folder in use, whose lock file holds 1 MB of escapes: the refusal
# prints one printable line of it.
rm -rf results
set_entry "Time step" 0.0000152587890625 < "$base" | set_entry "Write vtu" false \
  | set_entry "Checkpoint interval" 0 > work/slow.prm
"$executable" work/slow.prm > work/slow.txt 2>&1 &
pid=$!
wait_for_step 2 work/slow.txt $pid
head -c 1000000 /dev/urandom | tr '\n' '\033' >> "results/$lock"
run work/slow.prm
refused "a locked folder" "another run is writing into it"
[ "$(wc -c < err.txt)" -lt 2000 ] || fail "a locked folder: $(wc -c < err.txt) bytes of message."
! grep -q $'\033' err.txt || fail "a locked folder: the message has terminal escapes."

# The folder of temporaries moved away and replaced while the run goes on:
# the replacement keeps its files.
temporary=$(ls -d results/.viscoplastic_contact.tmp.* | head -1)
[ -n "$temporary" ] || fail "No folder of temporaries in the running run's folder."
mv "$temporary" work/moved && mkdir "$temporary" && cp precious/notes.txt "$temporary/"
# Stopped by a signal (65536 steps would take long): it writes a
# checkpoint through the temporaries and removes them at its end.
kill -TERM $pid
wait $pid
status=$?
[ $status -eq 143 ] || fail "The run whose temporaries were moved: exit status $status, not 143: $(tail -3 work/slow.txt)"
cmp -s precious/notes.txt "$temporary/notes.txt" \
  || fail "The folder put under the name of the temporaries lost its files."
untouched "temporaries replaced"
echo "Untrusted files: planted manifest lines, special, foreign and huge manifests, a linked lock file, named pipes a resumed run reads, a long lock message and replaced temporaries are refused or left alone; nothing else was touched."
