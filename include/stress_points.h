#ifndef viscoplastic_contact_stress_points_h
#define viscoplastic_contact_stress_points_h

#include <deal.II/base/array_view.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/base/smartpointer.h>
#include <deal.II/base/subscriptor.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/hp/mapping_collection.h>
#include <deal.II/hp/q_collection.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>

#include "back_ends/linear_algebra.h"

#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The geometry of the stress points}
  //
  // The cell loops of the time loop (stress update, history load, lifting,
  // reactions, tangent) run over the locally owned cells and their stress
  // points without FEValues: the mesh does not move, so JxW and the
  // gradients of the scalar shape functions N_a are computed once per mesh,
  // and the strain at a stress point is sym(sum_a u_a (x) grad N_a). Cells
  // that are translates of each other (those of a box) share one copy of
  // these values, their shape.
  //
  // k numbers the locally owned cells in the order of cells(), which every
  // stress-point array (the records of the material state, the checkpoints,
  // the convergence study) follows; q numbers the stress points of a cell;
  // a cell's dofs are ordered (vertex a, component c), as indices into the
  // local storage of the displacement vectors (owned entries, then ghosts).
  template <int dim>
  class StressPointGeometry : public Subscriptor
  {
  public:
    using CellIterator = typename DoFHandler<dim>::active_cell_iterator;

    // The owned cells of dof_handler (linear elements: the scalar dofs of a
    // cell are its vertices), their dofs in the storage of vectors with
    // partitioner, and the values at the points of quadrature (an entry per
    // element of dof_handler, all with the same number of points). A cell with
    // a dof that constraints constrain adds through them (distribute()).
    void
    reinit(const hp::MappingCollection<dim>  &mapping,
           const DoFHandler<dim>             &dof_handler,
           const hp::QCollection<dim>        &quadrature,
           const Utilities::MPI::Partitioner &partitioner,
           const AffineConstraints<double>   &constraints);

    const std::vector<CellIterator> &
    cells() const
    {
      return owned_cells;
    }
    unsigned int
    n_cells() const
    {
      return owned_cells.size();
    }
    unsigned int
    n_points() const
    {
      return n_points_per_cell;
    }
    unsigned int
    n_vertices() const
    {
      return n_cell_vertices;
    }
    // The number of distinct cell geometries.
    unsigned int
    n_shapes() const
    {
      return n_points_per_cell == 0
               ? 0
               : stress_point_JxW.size() / n_points_per_cell;
    }
    // The n_vertices() * dim dofs of cell k (n_vertices() the most vertices
    // of a cell: a cell with fewer repeats its first vertex's dofs, with
    // zero gradients).
    const unsigned int *
    local_dofs(const unsigned int k) const
    {
      return &cell_local_dofs[std::size_t(k) * n_cell_vertices * dim];
    }
    double
    JxW(const unsigned int k, const unsigned int q) const
    {
      return stress_point_JxW[std::size_t(cell_shape[k]) * n_points_per_cell
                              + q];
    }
    // grad N_a at stress point q of cell k, a = 0, ..., n_vertices() - 1.
    const Tensor<1, dim> *
    shape_gradients(const unsigned int k, const unsigned int q) const
    {
      return &stress_point_gradients
        [(std::size_t(cell_shape[k]) * n_points_per_cell + q)
         * n_cell_vertices];
    }

    // grad u at stress point q of cell k, from the local storage of u (its
    // ghost values current on more than one rank).
    Tensor<2, dim>
    displacement_gradient(const VectorType  &u,
                          const unsigned int k,
                          const unsigned int q) const;
    // cell_vector += (tau, eps(v)) JxW at stress point q of cell k.
    void
    add_load(const SymmetricTensor<2, dim> &tau,
             const unsigned int             k,
             const unsigned int             q,
             const ArrayView<double>       &cell_vector) const;
    // cell_matrix += (C eps(w), eps(v)) JxW at stress point q of cell k, C
    // with the minor symmetries (the tangent of the implicit update).
    void
    add_tangent(const SymmetricTensor<4, dim> &C,
                const unsigned int             k,
                const unsigned int             q,
                FullMatrix<double>            &cell_matrix) const;
    // target += the cell vector of cell k (through the constraints where the
    // cell has a constrained dof). The caller compresses with
    // VectorOperation::add.
    void
    distribute(const unsigned int             k,
               const ArrayView<const double> &cell_vector,
               VectorType                    &target) const;

  private:
    std::vector<CellIterator>                     owned_cells;
    unsigned int                                  n_points_per_cell = 0;
    unsigned int                                  n_cell_vertices   = 0;
    std::vector<unsigned int>                     cell_local_dofs;
    std::vector<bool>                             cell_is_constrained;
    std::vector<unsigned int>                     cell_shape;
    std::vector<double>                           stress_point_JxW;
    std::vector<Tensor<1, dim>>                   stress_point_gradients;
    SmartPointer<const AffineConstraints<double>> constraints;
  };
} // namespace ViscoContact

#endif
