#ifndef viscoplastic_contact_contact_solver_h
#define viscoplastic_contact_contact_solver_h

#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <deal.II/hp/mapping_collection.h>

#include <deal.II/lac/affine_constraints.h>

#include <deal.II/lac/vector.h>

#include "back_ends/cost_model.h"
#include "back_ends/linear_algebra.h"
#include "back_ends/matrix_free_elasticity.h"
#include "contact_nodes.h"
#include "contact_set.h"
#include "parameters.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // @sect3{Back ends: how the linear problem of fixed pieces is solved}
  //
  // A step problem (doc/model.md, section 2) is, for fixed pieces of the
  // contact law, a linear problem with the operator A of the step (the
  // elastic operator K, or the implicit update's tangent) and the contact
  // nodes' equations. ViscoplasticContact runs one active-set iteration
  // (ContactNodes::solve) and asks its back end, through this interface,
  // for the solutions of these linear problems:
  //  - set_operator(): factorise or precondition A (once per run for K, once
  //    per Newton iteration for a tangent);
  //  - set_right_hand_side(): the right-hand side b of a step problem;
  //  - solve_for_pieces(): for the current pieces and friction states,
  //    hand each contact node's displacements along its directions and its
  //    forces along the fixed ones to ContactNodes::store_solution(), which
  //    sets r, z, s and t (and u, if the back end has it anyway), to the
  //    accuracy the iteration asks for;
  //  - finish(): the displacement u of the final pieces;
  //  - solve_without_contact(), apply_compliance(): A^{-1} b for the cost
  //    measurements, and N A^{-1} N^T for the uniqueness margin.
  // Two back ends implement it:
  //  - CondensedContactSolver: A factorised by a sparse direct solver, the
  //    contact problem condensed to the contact nodes (the compliance
  //    S = N A^{-1} N^T read off the factor, or one solve per contact node);
  //  - FullSpaceContactSolver: a Krylov method in the full space on the
  //    projected operator, preconditioned by AMG or a factorisation of A;
  //    or, for Method = matrix free, with K applied cell by cell and
  //    preconditioned by geometric multigrid (matrix_free_elasticity.h), no
  //    matrix stored at all (set_operator() then ignores its argument).
  //
  // All calls but description() and statistics() are collective over the
  // communicator of the displacement vectors: ContactNodes::solve() makes
  // every rank call solve_for_pieces() the same number of times, and the
  // back ends rely on it (a factorised solve with MUMPS, a Krylov method's
  // inner products, the gathers of the condensed back end). In one step
  // problem the calls come in this order: set_right_hand_side() once,
  // solve_for_pieces() once per active-set iteration, finish() once after
  // the iteration has converged.
  template <int dim>
  class ContactSolver
  {
  public:
    // What the run summary reports about the linear algebra of a run; each
    // back end counts into it.
    struct Statistics
    {
      unsigned int operator_setups  = 0; // factorisations or AMG set-ups
      unsigned int solves           = 0; // solves with A (or the Krylov method)
      unsigned int inner_iterations = 0; // Krylov iterations of all solves
    };

    virtual ~ContactSolver() = default;

    // One line for the run's header: the method and its solver.
    virtual std::string
    description() const = 0;

    // A becomes the operator of every following step problem, until the next
    // call: K once per run, the tangent once per Newton iteration of the
    // implicit update. symmetric is true for K and false for a tangent
    // (which is unsymmetric in 2D plane stress, doc/model.md, section 3); it
    // selects Cholesky or LU, CG or GMRES. A back end may keep a reference
    // to A, so A must not change until the next call. contact gives the
    // contact nodes (numbering, normals, weights, law) whose compliance the
    // condensed back end computes.
    virtual void
    set_operator(const MatrixType      &A,
                 const bool             symmetric,
                 const ContactSet<dim> &contact)
      = 0;

    // The right-hand side b of the next step problem: the condensed back end
    // solves with it here, once per step problem; the full space back end
    // keeps it for its Krylov solves.
    virtual void
    set_right_hand_side(const VectorType &b, const ContactSet<dim> &contact)
      = 0;

    // For the current pieces and friction states of the contact nodes
    // (ContactNodes::directions()), the displacements and forces of this
    // rank's nodes, through ContactNodes::store_solution() (without
    // friction the condensed back end writes contact.r and contact.z
    // directly), with the relative accuracy the active-set iteration asks
    // for (a Krylov method may stop there, or go on as the request allows;
    // a direct solve is exact anyway). The report says whether the linear
    // solve met it; if it did not, the active-set iteration stops with the
    // report's failure. u holds the previous iterate on entry (the full
    // space back end starts from it) and, for the full space back end, the
    // solution on exit.
    virtual LinearSolveReport
    solve_for_pieces(ContactSet<dim>          &contact,
                     VectorType               &u,
                     const LinearSolveRequest &request)
      = 0;

    // After the active-set iteration has converged: the displacement of the
    // final pieces, in the locally owned entries of u (the caller
    // distributes the constraints and updates the ghosts).
    virtual void
    finish(const ContactSet<dim> &contact, VectorType &u)
      = 0;

    // dst = A src, with the operator of the last set_operator() (the
    // matrix-free back end has no matrix of it).
    virtual void
    apply_operator(VectorType &dst, const VectorType &src) const = 0;

    // u = A^{-1} b without any contact: the step problem of a scene without
    // contact, and the reference solve of the run summary's cost
    // measurements.
    virtual LinearSolveReport
    solve_without_contact(const VectorType &b, VectorType &u)
      = 0;

    // y = N A^{-1} N^T x, x and y indexed by this rank's contact nodes: the
    // product with the contact compliance S that the Lanczos iteration of
    // the uniqueness test needs (doc/model.md, section 4). Collective.
    virtual void
    apply_compliance(const ContactSet<dim> &contact,
                     const Vector<double>  &x,
                     Vector<double>        &y)
      = 0;

    // After a checkpoint: forget what the back end keeps from earlier solves
    // of the run and a checkpoint does not store (the condensed back end's
    // dense factorisation, corrected for the rows that changed since; the
    // full space back end's AMG of an earlier step operator), so that the
    // run goes on with the arithmetic of a run resumed from that checkpoint,
    // bit for bit.
    virtual void
    forget_kept_state()
    {}

    // Contact pairs (dual_mortar_basis.h): work in the basis u = T w, i.e.
    // with the operator T^T A T, which a back end that only applies A has
    // to apply itself, and whose near-null space is T^{-1} times A's. Only
    // the full space and matrix-free back ends do.
    virtual void
    work_in_basis(const MatrixType &)
    {
      AssertThrow(false, ExcInternalError());
    }

    // The counts so far, for the run summary.
    const Statistics &
    statistics() const
    {
      return counts;
    }

  protected:
    Statistics counts;
  };



  // The back end of the given method (not automatic). layout is a
  // displacement vector with the run's partition; the AMG needs the
  // support points of the dofs for the rigid-body modes, the matrix-free
  // back end what its operator is built from. With contact pairs the full
  // space back end works in the dual mortar basis (dual_mortar_basis.h),
  // which needs the displacement's constraints.
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_contact_solver(const Parameters::Method          method,
                        const Parameters::AllParameters  &parameters,
                        const hp::MappingCollection<dim> &mapping,
                        const DoFHandler<dim>            &dof_handler,
                        const VectorType                 &layout,
                        const ElasticOperatorData<dim>   &operator_data,
                        const AffineConstraints<double>  &constraints);

  // The constructors of the two back ends (condensed_contact_solver.cc,
  // full_space_contact_solver.cc), for create_contact_solver().
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_condensed_contact_solver(const Parameters::AllParameters &parameters,
                                  const VectorType                &layout);
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_full_space_contact_solver(
    const Parameters::AllParameters  &parameters,
    const hp::MappingCollection<dim> &mapping,
    const DoFHandler<dim>            &dof_handler,
    const VectorType                 &layout,
    const ElasticOperatorData<dim>   *matrix_free_data);
} // namespace ViscoContact

#endif
