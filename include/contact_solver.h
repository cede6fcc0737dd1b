#ifndef viscoplastic_contact_contact_solver_h
#define viscoplastic_contact_contact_solver_h

#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <deal.II/lac/vector.h>

#include "active_set.h"
#include "contact_set.h"
#include "linear_algebra.h"
#include "parameters.h"

#include <memory>
#include <string>

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
  //  - solve_for_pieces(): for the current pieces, write r = u.nu and the
  //    nodal forces z of every contact node (and u, if the back end has it
  //    anyway);
  //  - finish(): the displacement u of the final pieces;
  //  - solve_without_contact(), apply_compliance(): A^{-1} b for the cost
  //    measurements, and N A^{-1} N^T for the uniqueness margin.
  // Two back ends implement it:
  //  - CondensedContactSolver: A factorised by a sparse direct solver, the
  //    contact problem condensed to the contact nodes (the compliance
  //    S = N A^{-1} N^T computed with one solve per contact node);
  //  - FullSpaceContactSolver: a Krylov method in the full space on the
  //    projected operator, preconditioned by AMG or a factorisation of A.
  template <int dim>
  class ContactSolver
  {
  public:
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

    virtual void
    set_operator(const MatrixType      &A,
                 const bool             symmetric,
                 const ContactSet<dim> &contact)
      = 0;

    virtual void
    set_right_hand_side(const VectorType &b, const ContactSet<dim> &contact)
      = 0;

    // u holds the previous iterate on entry (the full space back end starts
    // from it) and, for the full space back end, the solution on exit.
    virtual LinearSolveReport
    solve_for_pieces(ContactSet<dim> &contact, VectorType &u)
      = 0;

    virtual void
    finish(const ContactSet<dim> &contact, VectorType &u)
      = 0;

    virtual LinearSolveReport
    solve_without_contact(const VectorType &b, VectorType &u)
      = 0;

    // y = N A^{-1} N^T x, x and y indexed by this rank's contact nodes.
    // Collective.
    virtual void
    apply_compliance(const ContactSet<dim> &contact,
                     const Vector<double>  &x,
                     Vector<double>        &y)
      = 0;

    const Statistics &
    statistics() const
    {
      return counts;
    }

  protected:
    Statistics counts;
  };



  // What Method = auto picks, and why (printed at start-up).
  struct MethodChoice
  {
    Parameters::Method method;
    std::string        reason;
  };

  MethodChoice
  choose_method(const Parameters::AllParameters &parameters,
                const unsigned int               dim,
                const unsigned int               n_ranks,
                const types::global_dof_index    n_dofs,
                const types::global_dof_index    n_contact_nodes);

  // The back end of the given method (not automatic). layout is a
  // displacement vector with the run's partition; the AMG needs the
  // support points of the dofs for the rigid-body modes.
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_contact_solver(const Parameters::Method         method,
                        const Parameters::AllParameters &parameters,
                        const Mapping<dim>              &mapping,
                        const DoFHandler<dim>           &dof_handler,
                        const VectorType                &layout);

  // The constructors of the two back ends (condensed_contact_solver.cc,
  // full_space_contact_solver.cc), for create_contact_solver().
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_condensed_contact_solver(const Parameters::AllParameters &parameters,
                                  const VectorType                &layout);
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_full_space_contact_solver(const Parameters::AllParameters &parameters,
                                   const Mapping<dim>              &mapping,
                                   const DoFHandler<dim>           &dof_handler,
                                   const VectorType                &layout);
} // namespace ViscoContact

#endif
