// The choice of the back end.

#include <deal.II/base/exceptions.h>

#include "contact_solver.h"

#include <sstream>

namespace ViscoContact
{
  // @sect4{choose_method}
  //
  // The condensed back end costs a factorisation of the operator, one solve
  // per contact node at set-up and m^2 doubles on every rank; afterwards a
  // step is one solve. The full space back end costs an AMG set-up and a
  // Krylov solve per active-set iteration. On one rank and in 2D the direct
  // factorisation is cheap and the contact boundary is a line with few
  // nodes, so the condensed one wins by far (doc/performance.md); in 3D
  // the factorisation's fill and the m solves grow quickly, and on several
  // ranks the replicated compliance does not scale. The limits below are
  // where the measured costs of the two cross (benchmarks/).
  MethodChoice
  choose_method(const Parameters::AllParameters &parameters,
                const unsigned int               dim,
                const unsigned int               n_ranks,
                const types::global_dof_index    n_dofs,
                const types::global_dof_index    n_contact_nodes)
  {
    if (parameters.method != Parameters::Method::automatic)
      return {parameters.method, "set in the parameter file"};

    const types::global_dof_index max_nodes = (dim == 2 ? 4000 : 2000);
    const types::global_dof_index max_dofs  = (dim == 2 ? 4000000 : 60000);
    std::ostringstream            reason;
    reason << "Method = auto: " << n_ranks << " rank(s), " << n_dofs
           << " dofs, " << n_contact_nodes << " contact nodes; ";
    if (n_ranks == 1 && n_contact_nodes <= max_nodes && n_dofs <= max_dofs)
      {
        reason << "condensed on one rank up to " << max_nodes
               << " contact nodes and " << max_dofs << " dofs in " << dim
               << "D";
        return {Parameters::Method::condensed, reason.str()};
      }
    reason << "full space beyond one rank, " << max_nodes
           << " contact nodes or " << max_dofs << " dofs in " << dim << "D";
    return {Parameters::Method::full_space, reason.str()};
  }



  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_contact_solver(const Parameters::Method         method,
                        const Parameters::AllParameters &parameters,
                        const Mapping<dim>              &mapping,
                        const DoFHandler<dim>           &dof_handler,
                        const VectorType                &layout)
  {
    Assert(method != Parameters::Method::automatic, ExcInternalError());
    if (method == Parameters::Method::condensed)
      return create_condensed_contact_solver<dim>(parameters, layout);
    return create_full_space_contact_solver<dim>(parameters,
                                                 mapping,
                                                 dof_handler,
                                                 layout);
  }



  template std::unique_ptr<ContactSolver<2>>
  create_contact_solver(const Parameters::Method,
                        const Parameters::AllParameters &,
                        const Mapping<2> &,
                        const DoFHandler<2> &,
                        const VectorType &);
  template std::unique_ptr<ContactSolver<3>>
  create_contact_solver(const Parameters::Method,
                        const Parameters::AllParameters &,
                        const Mapping<3> &,
                        const DoFHandler<3> &,
                        const VectorType &);
} // namespace ViscoContact
