#!/bin/bash
# The matrix-free back end on the shipped hypercube scenes: each PRM runs
# with Method = full space and matrix free (no .vtu output), and the time
# series (without wall time, active-set and Krylov iterations), the contact profiles
# and the final norms must agree by numdiff, absolute 1e-7 (forces that
# vanish come out as 1e-9 to 1e-8 beside loads of 10 to 20), relative 1e-6:
# both solve each step problem to the Tolerance of the parameter file, one
# with K assembled, the other applied cell by cell. The
# scenes cover friction, oblique planes of symmetry, Gmsh meshes, two
# materials, prescribed displacements and 3D.
#   run_matrix_free_scenes.sh EXECUTABLE PRM...
set -u
here=$(dirname "$0")
executable=$1
shift
for prm in "$@"; do
  name=$(basename "$prm" .prm)
  # Gmsh files are named relative to the parameter file's directory.
  meshes=$(cd "$(dirname "$prm")/../meshes" 2> /dev/null && pwd)
  for method in "full space" "matrix free"; do
    # The Method is set by a subsection added at the end (the last value
    # of an entry counts).
    "$here/run_scene_variant.sh" "$name/${method// /_}" "$executable" \
      <(cat "$prm"; printf 'subsection Linear solver\n  set Method = %s\nend\n' "$method") \
      "s|^\( *set Write vtu *=\).*|\1 false|;s|^\( *set Output directory *=\).*|\1 results|;s|\.\./meshes/|$meshes/|" \
      || exit 1
    if ! grep -q "^Back end: ${method}:" "$name/${method// /_}/output.txt"; then
      echo "$name did not run with Method = $method."
      exit 1
    fi
    grep -E '^  final (state|contact):|^Final displacement' \
      "$name/${method// /_}/output.txt" > "$name/${method// /_}/final.txt"
    # Without the columns that differ by design: wall time, Krylov
    # iterations, and active-set iterations (the early solves stop at
    # sqrt(Tolerance), and where their preconditioners differ the pieces
    # may settle one iteration earlier or later).
    cut -d, -f1,2,4-8,11- "$name/${method// /_}/results/time_series.csv" \
      > "$name/${method// /_}/series.csv"
  done
  "$here/compare_scene_variants.sh" --profiles "$name/full_space" \
    "$name/matrix_free" "between the full space and matrix-free back ends ($name)" \
    1e-7 1e-6 series.csv final.txt || exit 1
done
echo "The matrix-free and full space back ends agree on $# scenes: time series, contact profiles, final state."
