// The constraints of the displacement: hanging nodes and the clamped parts
// Gamma_1 (u = 0). The program's set-up and the preconditioner benchmark use
// the same function, so that the benchmark solves the program's K.

#ifndef viscoplastic_contact_constraints_h
#define viscoplastic_contact_constraints_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/types.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/mapping.h>

#include <deal.II/lac/affine_constraints.h>

#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  // Fills constraints (reinitialised on locally_relevant_dofs) with the
  // hanging-node constraints and u = 0 on the boundary ids clamped_ids, and
  // closes it.
  template <int dim>
  void
  make_displacement_constraints(
    const Mapping<dim>                    &mapping,
    const DoFHandler<dim>                 &dof_handler,
    const std::vector<types::boundary_id> &clamped_ids,
    const IndexSet                        &locally_relevant_dofs,
    AffineConstraints<double>             &constraints);
} // namespace ViscoContact

#endif
