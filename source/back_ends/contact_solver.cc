// The choice of the back end, and the one place where the program turns a
// choice of method into a back-end object.

#include <deal.II/base/exceptions.h>

#include "back_ends/contact_solver.h"

#include <sstream>

namespace ViscoContact
{
  // @sect4{choose_method}
  //
  // The condensed back end costs a factorisation of the operator at set-up
  // (with MUMPS on several ranks, or UMFPACK for the implicit update's
  // unsymmetric tangent, also one solve per contact node) and m^2 doubles on
  // every rank; afterwards a step is one solve (two with MUMPS or UMFPACK).
  // The full space back end costs an AMG set-up and a Krylov solve per
  // active-set iteration. Measured on this kind of machine (2 cores,
  // benchmarks/run_back_end_comparison.py, doc/back_ends/back_ends.md; the
  // first 8 steps of a run, where the contact zone forms): in 2D the
  // factorisation is cheap and the contact boundary is a line, and the
  // condensed back end is faster at every size tried (6 times at 132k dofs,
  // 256 contact nodes; at 2.1M dofs and 1024 contact nodes it still takes
  // 114 s of set-up and 1.3 s per step, 7.8 GB); in 3D it is 4.6 times
  // faster at 47k dofs (600 contact nodes) and 6 times at 108k dofs (1056
  // contact nodes: 22 s of set-up, then 0.28 s per step, against 16 s per
  // step for the full space back end). (The set-up times were measured with S
  // computed by one solve per contact node; reading S off the factor, as
  // the back end does, is 2 to 3 times cheaper.)
  // Beyond that the fill of a 3D factorisation grows fast, and on several
  // ranks the compliance, which every rank holds, does not scale. The
  // limits below stay within what was measured.
  MethodChoice
  choose_method(const Parameters::AllParameters &parameters,
                const unsigned int               dim,
                const unsigned int               n_ranks,
                const types::global_dof_index    n_dofs,
                const types::global_dof_index    n_contact_nodes)
  {
    // A method named in the parameter file is taken as it is, on any number
    // of ranks and for any size: the user may want the condensed back end on
    // several ranks, or the full space one on a small 2D scene.
    if (parameters.method != Parameters::Method::automatic)
      return {parameters.method, "set in the parameter file"};

    // The limits of the automatic choice, by space dimension: 2000 contact
    // nodes and 2.2M dofs in 2D, 1500 contact nodes and 120k dofs in 3D.
    const types::global_dof_index max_nodes = (dim == 2 ? 2000 : 1500);
    const types::global_dof_index max_dofs  = (dim == 2 ? 2200000 : 120000);
    // The reason names the scene's numbers, so that the run's header shows
    // which limit decided.
    std::ostringstream reason;
    reason << "Method = auto: " << n_ranks << " rank(s), " << n_dofs
           << " dofs, " << n_contact_nodes << " contact nodes; ";
    // The condensed back end only on one rank: on several, its compliance S
    // would be replicated on every rank.
    if (n_ranks == 1 && n_contact_nodes <= max_nodes && n_dofs <= max_dofs)
      {
        reason << "condensed on one rank up to " << max_nodes
               << " contact nodes and " << max_dofs << " dofs in " << dim
               << "D";
        return {Parameters::Method::condensed, reason.str()};
      }
    // Anything else, the full space back end, whose cost grows with the
    // number of unknowns only.
    reason << "full space beyond one rank, " << max_nodes
           << " contact nodes or " << max_dofs << " dofs in " << dim << "D";
    return {Parameters::Method::full_space, reason.str()};
  }



  // @sect4{create_contact_solver}
  //
  // The back end of a resolved method (never automatic). The two back-end
  // classes are only known in their own files; this function reaches them
  // through their factory functions, so the rest of the program sees the
  // ContactSolver interface alone. The mapping and the dof handler are only
  // used by the full space back end, to build the rigid-body modes of its
  // AMG.
  template <int dim>
  std::unique_ptr<ContactSolver<dim>>
  create_contact_solver(const Parameters::Method         method,
                        const Parameters::AllParameters &parameters,
                        const Mapping<dim>              &mapping,
                        const DoFHandler<dim>           &dof_handler,
                        const VectorType                &layout,
                        const ElasticOperatorData<dim>  &operator_data)
  {
    Assert(method != Parameters::Method::automatic, ExcInternalError());
    if (method == Parameters::Method::condensed)
      return create_condensed_contact_solver<dim>(parameters, layout);
    return create_full_space_contact_solver<dim>(
      parameters,
      mapping,
      dof_handler,
      layout,
      method == Parameters::Method::matrix_free ? &operator_data : nullptr);
  }



  // The program runs in 2D and 3D; both instances are compiled here.
  template std::unique_ptr<ContactSolver<2>>
  create_contact_solver(const Parameters::Method,
                        const Parameters::AllParameters &,
                        const Mapping<2> &,
                        const DoFHandler<2> &,
                        const VectorType &,
                        const ElasticOperatorData<2> &);
  template std::unique_ptr<ContactSolver<3>>
  create_contact_solver(const Parameters::Method,
                        const Parameters::AllParameters &,
                        const Mapping<3> &,
                        const DoFHandler<3> &,
                        const VectorType &,
                        const ElasticOperatorData<3> &);
} // namespace ViscoContact
