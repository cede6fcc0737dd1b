#ifndef viscoplastic_contact_matrix_free_elasticity_h
#define viscoplastic_contact_matrix_free_elasticity_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/symmetric_tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <deal.II/lac/affine_constraints.h>

#include "back_ends/constrained_smoothing.h"
#include "back_ends/linear_algebra.h"

#include <functional>
#include <memory>
#include <string>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{The elastic operator without a matrix}
  //
  // What the matrix-free back end needs to apply the elastic operator K of a
  // mesh and to build the levels of its multigrid: the displacement's dofs
  // with their (homogeneous) constraints, the elasticity tensor of a
  // material id, and how the constraints of a coarser mesh are made (the
  // same Dirichlet parts, planes of symmetry and hanging nodes, on the
  // coarser mesh's dofs). The references must outlive the operator.
  template <int dim>
  struct ElasticOperatorData
  {
    const Mapping<dim>              &mapping;
    const DoFHandler<dim>           &dof_handler;
    const AffineConstraints<double> &constraints;
    std::function<const SymmetricTensor<4, dim> &(types::material_id)>
      elasticity;
    std::function<void(const DoFHandler<dim> &,
                       const IndexSet &,
                       AffineConstraints<double> &)>
      make_constraints;
    // The Chebyshev smoother: degree 4 and a smoothing range of 15 were
    // the fastest settings benchmarks/preconditioner_comparison.cc measured
    // for K (it varies them).
    unsigned int smoother_degree = 4;
    double       smoothing_range = 15.;
  };

  // K applied cell by cell (deal.II's MatrixFree, as in step-37, with the
  // isotropic stress of every cell's material at the 2^dim Gauss points the
  // program's stress points are), and one V-cycle of a geometric multigrid
  // on the meshes that global coarsening of the p4est mesh gives (step-75):
  // Chebyshev smoothing on every level, in single precision, and ML's AMG
  // on the coarse mesh. Quadrilaterals and hexahedra only. Both act on the
  // program's displacement vectors; a constrained dof is an identity row of
  // both, as in the assembled K (whose constrained rows are decoupled).
  template <int dim>
  class MatrixFreeElasticity
  {
  public:
    MatrixFreeElasticity(const ElasticOperatorData<dim> &data,
                         const VectorType               &layout);
    ~MatrixFreeElasticity();

    // dst = K src.
    void
    vmult(VectorType &dst, const VectorType &src) const;
    // dst = M^{-1} src, one V-cycle.
    void
    precondition(VectorType &dst, const VectorType &src) const;

    // Sets the projected step operator of a set of pieces
    // (constrained_smoothing.h) that precondition_constrained() smooths on
    // the finest level; its functions must stay valid while it is used.
    void
    constrain(const ConstrainedOperator &constrained);
    // dst = M^{-1} src, one V-cycle whose finest level smooths the
    // constrained operator instead of K (Chebyshev around its Jacobi step,
    // with K's eigenvalue bound), and whose coarser levels are K's. A V-cycle
    // of K alone treats the fixed directions as free: CG then needs about three
    // times the iterations of an elastic solve (doc/performance.md). The
    // coarser levels neither get nor return the fixed directions and the
    // stiff ones (ConstrainedOperator::remove_stiff).
    void
    precondition_constrained(VectorType &dst, const VectorType &src) const;
    // The diagonal of K (locally owned entries).
    const VectorType &
    diagonal() const;

    // The number of meshes of the multigrid and their dofs, for the
    // header.
    std::string
    description() const;

  private:
    struct Implementation;
    std::unique_ptr<Implementation> implementation;
  };
} // namespace ViscoContact

#endif
