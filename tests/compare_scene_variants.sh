#!/bin/bash
# For the tests that compare two runs of the same scene: each FILE (a path
# relative to both directories) must agree between DIRECTORY1 and
# DIRECTORY2 by numdiff with the given tolerances; the first that does not
# is shown (the differences, after "FILE differs WHAT") and the exit status
# is 1. With --profiles, every contact profile DIRECTORY1/results holds is
# compared as well.
#   compare_scene_variants.sh [--profiles] DIRECTORY1 DIRECTORY2 WHAT ABSOLUTE RELATIVE FILE...
set -u
profiles=false
if [ "$1" = --profiles ]; then
  profiles=true
  shift
fi
first=$1 second=$2 what=$3 absolute=$4 relative=$5
shift 5
files=("$@")
if $profiles; then
  for profile in "$first"/results/contact_profile_*.csv; do
    files+=("results/$(basename "$profile")")
  done
fi
for file in "${files[@]}"; do
  if ! numdiff -q -a "$absolute" -r "$relative" -s ' \t\n=,:;' \
       "$first/$file" "$second/$file" > /dev/null; then
    echo "$file differs $what beyond -a $absolute -r $relative:"
    numdiff -a "$absolute" -r "$relative" -s ' \t\n=,:;' "$first/$file" "$second/$file" | head -30
    exit 1
  fi
done
