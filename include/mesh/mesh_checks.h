#ifndef viscoplastic_contact_robustness_mesh_checks_h
#define viscoplastic_contact_robustness_mesh_checks_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>
#include <deal.II/grid/tria_description.h>

#include <string>
#include <utility>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // The checks of a Gmsh file (mesh/mesh_checks.cc), each stopping with a
  // message that names the Mesh file entry, the file and what is wrong:
  // the counts of the $Nodes and $Elements sections whole numbers within
  // what the file can hold, every node id defined once; on the cells the
  // reader hands to the
  // triangulation, before it builds anything, finite coordinates of a sane
  // extent, simplices or hypercubes only (no wedges or pyramids), distinct
  // nodes and positive, non-negligible Jacobians at every corner; and on the
  // mesh built, no coincident nodes (a crack) and conforming faces (no hanging
  // node).
  void
  check_gmsh_sections(const std::string &file);
  // The number of nodes a Gmsh file declares at the head of its $Nodes
  // section (0 if the file has none or cannot be read; the reader then says
  // why): a few lines are read, for the memory estimate before a run.
  double
  gmsh_node_count(const std::string &file);
  template <int dim>
  void
  check_mesh_cells(const std::vector<Point<dim>>    &vertices,
                   const std::vector<CellData<dim>> &cells,
                   const std::string                &file);
  // The corners of a cell, in deal.II's order.
  template <int dim>
  std::vector<Point<dim>>
  corners_of(const typename Triangulation<dim>::cell_iterator &cell);
  // The Jacobian determinant of a cell (its corners) at its vertex v, and
  // the product of the lengths of the edges it is made of: negative for an
  // inverted corner, 0 for a degenerate one.
  template <int dim>
  std::pair<double, double>
  corner_jacobian(const std::vector<Point<dim>> &corners, const unsigned int v);
  template <int dim>
  void
  check_mesh_conformity(const Triangulation<dim>              &triangulation,
                        const std::string                     &file,
                        const std::vector<types::boundary_id> &pair_ids);
} // namespace ViscoContact

#endif
