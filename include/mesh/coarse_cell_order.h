#ifndef viscoplastic_contact_coarse_cell_order_h
#define viscoplastic_contact_coarse_cell_order_h

#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The order of the coarse cells}
  //
  // p4est numbers its trees (the coarse cells of a quadrilateral or
  // hexahedral mesh) in the order deal.II's
  // SparsityTools::reorder_hierarchical() gives the graph of cells that
  // share a vertex. The program numbers the coarse cells in that order
  // before the mesh goes to p4est (coarse_cell_order.cc says why).

  // The new number of each row of a symmetric graph: the same numbers as
  // SparsityTools::reorder_hierarchical() of deal.II 9.4 gives, in time
  // O(entries log rows) rather than O(rows * front), where the front is the
  // set of candidate rows next to the rows numbered so far (on a graded
  // hexahedral mesh of 314k cells: 0.5 s per call against 2.5 to 4.6 s).
  std::vector<types::global_dof_index>
  hierarchical_order(const DynamicSparsityPattern &graph);

  // Renumbers the coarse cells of an unrefined mesh in p4est's tree order,
  // with their vertices, material and manifold ids and the boundary and
  // manifold ids of their faces (and, in 3D, edges).
  template <int dim>
  void
  number_coarse_cells_as_p4est_trees(Triangulation<dim> &coarse_mesh);
} // namespace ViscoContact

#endif
