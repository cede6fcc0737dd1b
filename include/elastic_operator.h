#ifndef viscoplastic_contact_elastic_operator_h
#define viscoplastic_contact_elastic_operator_h

#include <deal.II/base/quadrature.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <array>
#include <functional>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // K_ij = (E eps(phi_j), eps(phi_i)) on the locally owned cells of
  // dof_handler, integrated with quadrature (the program's stress points;
  // the collections have an entry per element of dof_handler),
  // the constrained rows and columns condensed as the cell matrices are
  // added, and compressed: the elastic operator of the program
  // (ViscoplasticContact::assemble_elastic_operator()), for the benchmark
  // programs too. The matrix must have its sparsity pattern. E is the
  // elasticity tensor of each cell (of its material).
  template <int dim>
  using ElasticityOfCell = std::function<const SymmetricTensor<4, dim> &(
    const typename DoFHandler<dim>::active_cell_iterator &)>;

  template <int dim>
  void
  assemble_elastic_operator(const hp::MappingCollection<dim> &mapping,
                            const DoFHandler<dim>            &dof_handler,
                            const hp::QCollection<dim>       &quadrature,
                            const ElasticityOfCell<dim>      &elasticity,
                            const AffineConstraints<double>  &constraints,
                            TrilinosWrappers::SparseMatrix   &matrix);

  // Without a matrix: the dim x dim blocks K_ii of the given vertices (the
  // dofs of each, by component), from the cells around them, owned and
  // ghost (all of a locally owned vertex's cells are one or the other).
  // These are K's blocks where no hanging node depends on the vertex; the
  // contact set only scales its parameters by them.
  template <int dim>
  std::vector<Tensor<2, dim>>
  elastic_node_blocks(
    const hp::MappingCollection<dim>                            &mapping,
    const DoFHandler<dim>                                       &dof_handler,
    const hp::QCollection<dim>                                  &quadrature,
    const ElasticityOfCell<dim>                                 &elasticity,
    const std::vector<std::array<types::global_dof_index, dim>> &node_dofs);
} // namespace ViscoContact

#endif
