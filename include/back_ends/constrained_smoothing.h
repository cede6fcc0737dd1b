#ifndef viscoplastic_contact_constrained_smoothing_h
#define viscoplastic_contact_constrained_smoothing_h

#include <deal.II/base/subscriptor.h>

#include <deal.II/lac/precondition.h>

#include "back_ends/linear_algebra.h"

#include <functional>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Smoothing the projected step operator}
  //
  // The iterative back ends solve a set of pieces with the projected step
  // operator A_P = P (A + sum k v v^T) P + (I - P)
  // (full_space_contact_solver.cc): P removes the fixed directions of the
  // contact nodes (a vertical piece's normal, a sticking node's tangents), the
  // free directions add their stiffness. A preconditioner of A alone treats the
  // fixed directions as free; these classes smooth A_P itself, so that a
  // preconditioner of A (a multigrid V-cycle, an AMG built for other pieces)
  // only has to do the coarse part, and nothing is rebuilt when nodes change
  // piece.

  // A_P of one set of pieces: apply is its product, project applies P in
  // place, add_stiffness adds the free directions' stiffness k v_j^2 to a
  // vector holding A's diagonal, and remove_stiff removes in place the free
  // directions that are stiffer than A along them, which a coarse
  // correction that does not know them must leave to the smoothing
  // (FullSpaceContactSolver::collect_stiff_rows()).
  struct ConstrainedOperator
  {
    std::function<void(VectorType &, const VectorType &)> apply;
    std::function<void(VectorType &)>                     project;
    std::function<void(VectorType &)>                     add_stiffness;
    std::function<void(VectorType &)>                     remove_stiff;
  };

  // The Jacobi step of A_P: P D^{-1} P + (I - P), D the diagonal of A plus
  // the free directions' stiffness (a stiff sloped piece would otherwise lie
  // outside a smoother's eigenvalue range). The identity along the fixed
  // directions matches A_P's rows there.
  class ConstrainedJacobi
  {
  public:
    // The diagonal of A (locally owned entries) and the operator, whose
    // functions must stay valid while vmult() is used.
    void
    reinit(const VectorType &diagonal, const ConstrainedOperator &constrained);
    void
    vmult(VectorType &dst, const VectorType &src) const;

  private:
    ConstrainedOperator constrained;
    VectorType          inverse_diagonal;
    mutable VectorType  fixed_part;
  };

  // Chebyshev smoothing of A_P around its Jacobi step, before and after a
  // coarse correction C (P Q C Q P with the projections P and the removal Q
  // of the stiff free directions): one symmetric two-level cycle. deal.II's
  // PreconditionChebyshev does the smoothing; its eigenvalue bound is that of
  // D^{-1} A, estimated once per operator (initialize()): removing directions
  // and adding a stiffness that D includes do not raise it much, and the
  // estimate has a safety factor of 1.2.
  class ConstrainedSmoothing
  {
  public:
    ConstrainedSmoothing(const unsigned int degree,
                         const double       smoothing_range);

    // A, its diagonal, and a vector of the layout.
    void
    initialize(
      const std::function<void(VectorType &, const VectorType &)> &apply_A,
      const VectorType                                            &diagonal);
    // The operator of the next cycles.
    void
    constrain(const ConstrainedOperator &constrained);
    // dst = S r + C (r - A_P S r) and the same smoothing after it, for the
    // projected residual r = src.
    void
    vmult(VectorType                                                  &dst,
          const VectorType                                            &src,
          const std::function<void(VectorType &, const VectorType &)> &coarse)
      const;

  private:
    struct Operator : public Subscriptor
    {
      std::function<void(VectorType &, const VectorType &)> apply;
      void
      vmult(VectorType &dst, const VectorType &src) const
      {
        apply(dst, src);
      }
    };
    using Smoother
      = PreconditionChebyshev<Operator, VectorType, ConstrainedJacobi>;

    const unsigned int                 degree;
    const double                       smoothing_range;
    double                             max_eigenvalue = 0;
    VectorType                         diagonal;
    Operator                           constrained_operator;
    std::shared_ptr<ConstrainedJacobi> jacobi;
    std::function<void(VectorType &)>  remove_stiff;
    Smoother                           smoother;
    mutable VectorType                 residual, correction;
  };
} // namespace ViscoContact

#endif
