# Shared by the column scripts (tests/run_memory_column.sh,
# run_adhesion_column.sh, run_cohesive_column.sh), sourced after they set
# "prm" to their scene (a 2D column, plane strain, on a generated box):
#   variant CELL_TYPE METHOD > PRM   the scene on that cell type and back
#                                    end, into results/;
#   three_d < PRM > PRM2             the column in 3D (2 x 2 x 2 cells,
#                                    rollers on its four sides);
#   plane_stress < PRM > PRM2        plane stress instead of plane strain.
variant() {
  set_entry "Cell type" "$1" < "$prm" | set_entry Method "$2" \
    | set_entry "Output directory" results
}
three_d() {
  sed -e "/^set Plane model/d" | set_entry Dimension 3 | set_entry Lengths "1, 1, 1" | set_entry Subdivisions 2 \
    | set_entry "Symmetry boundary ids" "0, 1, 4, 5" \
    | set_entry "Body force" "0; 0; 0" | set_entry "Surface traction" "0; 0; 0"
}
plane_stress() { sed -e '/^set Plane model/d'; }
