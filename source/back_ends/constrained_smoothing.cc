// Smoothing of the projected step operator of a set of pieces: the Jacobi
// step and a Chebyshev two-level cycle around a preconditioner of A.

#include "back_ends/constrained_smoothing.h"

namespace ViscoContact
{
  void
  ConstrainedJacobi::reinit(const VectorType          &diagonal,
                            const ConstrainedOperator &constrained)
  {
    this->constrained = constrained;
    inverse_diagonal.reinit(diagonal, true);
    inverse_diagonal.copy_locally_owned_data_from(diagonal);
    if (constrained.add_stiffness)
      constrained.add_stiffness(inverse_diagonal);
    // A softening slope cannot make a diagonal entry vanish where the
    // uniqueness condition holds; A's entry is kept if it would. A zero
    // entry of A (a hanging dof's row) gets 1: nothing reads its value.
    for (unsigned int i = 0; i < inverse_diagonal.locally_owned_size(); ++i)
      {
        const double d = inverse_diagonal.local_element(i);
        const double a = diagonal.local_element(i);
        inverse_diagonal.local_element(i)
          = (d > 0 ? 1. / d : (a != 0 ? 1. / a : 1.));
      }
    fixed_part.reinit(diagonal, true);
  }



  void
  ConstrainedJacobi::vmult(VectorType &dst, const VectorType &src) const
  {
    dst.copy_locally_owned_data_from(src);
    if (!constrained.project)
      {
        dst.scale(inverse_diagonal);
        return;
      }
    constrained.project(dst);
    fixed_part.copy_locally_owned_data_from(src);
    fixed_part -= dst; // (I - P) src
    dst.scale(inverse_diagonal);
    constrained.project(dst);
    dst += fixed_part;
  }



  ConstrainedSmoothing::ConstrainedSmoothing(const unsigned int degree,
                                             const double       smoothing_range)
    : degree(degree)
    , smoothing_range(smoothing_range)
    , jacobi(std::make_shared<ConstrainedJacobi>())
  {}



  // The eigenvalue bound of D^{-1} A by deal.II's Lanczos estimate (10 CG
  // iterations), then the smoother of A_P with that bound; constrain()
  // only changes what its operator and Jacobi step refer to.
  void
  ConstrainedSmoothing::initialize(
    const std::function<void(VectorType &, const VectorType &)> &apply_A,
    const VectorType                                            &diagonal)
  {
    this->diagonal.reinit(diagonal, true);
    this->diagonal.copy_locally_owned_data_from(diagonal);
    residual.reinit(diagonal, true);
    correction.reinit(diagonal, true);

    constrained_operator.apply = apply_A;
    jacobi->reinit(diagonal, {apply_A, {}, {}, {}});
    typename Smoother::AdditionalData data;
    data.degree              = degree;
    data.smoothing_range     = smoothing_range;
    data.eig_cg_n_iterations = 10;
    data.preconditioner      = jacobi;
    {
      Smoother estimator;
      estimator.initialize(constrained_operator, data);
      max_eigenvalue
        = estimator.estimate_eigenvalues(residual).max_eigenvalue_estimate;
    }
    data.eig_cg_n_iterations = 0;
    data.max_eigenvalue      = max_eigenvalue;
    smoother.initialize(constrained_operator, data);
  }



  void
  ConstrainedSmoothing::constrain(const ConstrainedOperator &constrained)
  {
    constrained_operator.apply = constrained.apply;
    remove_stiff               = constrained.remove_stiff;
    jacobi->reinit(diagonal, constrained);
  }



  void
  ConstrainedSmoothing::vmult(
    VectorType                                                  &dst,
    const VectorType                                            &src,
    const std::function<void(VectorType &, const VectorType &)> &coarse) const
  {
    smoother.vmult(dst, src);
    constrained_operator.vmult(residual, dst);
    residual.sadd(-1., 1., src);
    if (remove_stiff)
      remove_stiff(residual);
    coarse(correction, residual);
    if (remove_stiff)
      remove_stiff(correction);
    dst += correction;
    constrained_operator.vmult(residual, dst);
    residual.sadd(-1., 1., src);
    smoother.vmult(correction, residual);
    dst += correction;
  }
} // namespace ViscoContact
