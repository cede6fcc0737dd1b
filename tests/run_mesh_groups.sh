#!/bin/bash
# Simplex meshes are built once per group of ranks (Mesh group size,
# source/mesh/mesh.cc): the group root reads, refines and partitions the whole
# mesh and hands each member its part.
#  1. The two columns on a Gmsh mesh of triangles, 3 ranks in groups of 2:
#     exactly two processes (the roots, ranks 0 and 2) open the mesh file
#     (strace); the member's peak memory is reported (Print timing
#     summary); time_series.csv is that of one rank (numdiff relative
#     1e-6, absolute 1e-9).
#  2. The generated box of tetrahedra (cube_3d_tetrahedra.prm, coarser, two
#     steps), 3 ranks in groups of 2, and 3 ranks each building the mesh
#     itself (groups of 1): both give the one-rank results.
# (A root that cannot read the mesh stops every rank with its message:
# bad_input/mesh_group_root_fails.prm.)
#   run_mesh_groups.sh EXECUTABLE
set -u
here=$(cd "$(dirname "$0")" && pwd)
source "$here/robustness/helpers.sh"
executable=$1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

# results_only FILE: a time_series.csv without the wall times and the
# Krylov iterations (which depend on the partition).
results_only() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; ++i) skip[i] = ($i == "wall_time" || $i == "krylov_iterations") }
           { line = ""; for (i = 1; i <= NF; ++i) if (!skip[i]) line = line $i ","; print line }' "$1"
}
# same_results NAME: results/time_series.csv against one_rank.csv.
same_results() {
  results_only one_rank.csv > expected.csv
  results_only results/time_series.csv > obtained.csv
  numdiff -q -r 1e-6 -a 1e-9 -s ', \n' expected.csv obtained.csv > /dev/null \
    || fail "$1: time_series.csv differs from the one-rank run's"
}

mesh=two_columns_triangle_4.msh
sed -e "s|^\( *set Mesh file *=\).*|\1 $here/../meshes/$mesh|" \
  "$here/../parameters/two_columns.prm" | set_entry "Cell type" simplex \
  | set_entry Method "full space" | set_entry "Output directory" results \
  | sed -e 's/^\(subsection Geometry\)$/\1\n  set Mesh group size = 2/' \
        -e 's/^\(subsection Output\)$/\1\n  set Print timing summary = true/' \
  > columns.prm
run_scene columns.prm 1 "Triangles on one rank"
cp results/time_series.csv one_rank.csv
rm -rf results trace.*
mpirun -np 3 --oversubscribe strace -f -qq -e trace=open,openat -o trace \
  -ff "$executable" columns.prm > out.txt 2> err.txt \
  || fail "Triangles on 3 ranks in groups of 2: the run failed: $(cat err.txt)"
openers=$(grep -l "\"[^\"]*/$mesh\"" trace.* | wc -l)
[ "$openers" -eq 2 ] \
  || fail "$openers processes opened $mesh, not 2 (the roots of the groups {0, 1} and {2})"
grep -q "largest member [0-9]" out.txt \
  || fail "No peak memory of a member: $(grep 'peak memory' out.txt)"
same_results "Triangles on 3 ranks in groups of 2"
rm -f trace.*

sed -e 's/^\(subsection Geometry\)$/\1\n  set Mesh group size = 2/' \
  "$here/../parameters/cube_3d_tetrahedra.prm" | set_entry Subdivisions 6 \
  | set_entry "End time" 0.0625 \
  | sed -e 's/^\(subsection Output\)$/\1\n  set Profile times = 0.0625/' \
  | set_entry "Write vtu" false | set_entry "Output directory" results \
  | set_entry Method "full space" > cube.prm
run_scene cube.prm 1 "Tetrahedra on one rank"
cp results/time_series.csv one_rank.csv
run_scene cube.prm 3 "Tetrahedra on 3 ranks in groups of 2"
same_results "Tetrahedra on 3 ranks in groups of 2"
set_entry "Mesh group size" 1 < cube.prm > cube_alone.prm
run_scene cube_alone.prm 3 "Tetrahedra on 3 ranks, each building the mesh"
same_results "Tetrahedra on 3 ranks, each building the mesh"

echo "Only the group roots open the mesh file; groups of 1 and 2 give the one-rank results."
