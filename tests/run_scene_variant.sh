#!/bin/bash
# One run of a variant of a scene, for the tests that compare two runs of
# the same scene: DIRECTORY is made afresh, gets the parameter file PRM
# (through the sed expression EDIT, if given) as scene.prm, a relative Mesh
# file made relative to PRM's folder as the program reads it, and the program
# runs there on RANKS ranks (environment, default 1), its output in
# output.txt and error.txt. A failed run prints why and exits with 1.
#   run_scene_variant.sh DIRECTORY EXECUTABLE PRM [EDIT]
set -u
directory=$1 executable=$2 prm=$3 edit=${4:-}
rm -rf "$directory"
mkdir -p "$directory"
prm_folder=$(cd "$(dirname "$prm")" && pwd)
sed -e "$edit" \
  -e "s|^\( *set Mesh file *= *\)\([^/ #][^ #]*\)|\1$prm_folder/\2|" \
  "$prm" > "$directory/scene.prm"
(cd "$directory" && "$(dirname "$0")/run_mpi.sh" "${RANKS:-1}" "$executable" scene.prm > output.txt 2> error.txt)
status=$?
if [ $status -ne 0 ]; then
  echo "The $directory run failed with exit status $status:"
  cat "$directory/error.txt"
  exit 1
fi
