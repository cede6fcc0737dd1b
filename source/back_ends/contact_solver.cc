// The one place where the program turns a method (Method = auto resolved by
// cost_model.cc) into a back-end object.

#include <deal.II/base/exceptions.h>

#include "back_ends/contact_solver.h"
#include "contact_pairs/dual_mortar_basis.h"

#include <algorithm>


namespace ViscoContact
{
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
  create_contact_solver(const Parameters::Method          method,
                        const Parameters::AllParameters  &parameters,
                        const hp::MappingCollection<dim> &mapping,
                        const DoFHandler<dim>            &dof_handler,
                        const VectorType                 &layout,
                        const ElasticOperatorData<dim>   &operator_data,
                        const AffineConstraints<double>  &constraints)
  {
    Assert(method != Parameters::Method::automatic, ExcInternalError());
    if (method == Parameters::Method::condensed)
      return create_condensed_contact_solver<dim>(parameters, layout);
    auto back_end = create_full_space_contact_solver<dim>(
      parameters,
      mapping,
      dof_handler,
      layout,
      method == Parameters::Method::matrix_free ? &operator_data : nullptr);
    const auto zones = parameters.used_contact_zones();
    if (std::any_of(zones.begin(), zones.end(), [](const auto &zone) {
          return !zone.contact->opposite_ids.empty();
        }))
      return std::make_unique<DualMortarBasis<dim>>(
        std::move(back_end),
        constraints,
        layout,
        method == Parameters::Method::matrix_free);
    return back_end;
  }



  // The program runs in 2D and 3D; both instances are compiled here.
  template std::unique_ptr<ContactSolver<2>>
  create_contact_solver(const Parameters::Method,
                        const Parameters::AllParameters &,
                        const hp::MappingCollection<2> &,
                        const DoFHandler<2> &,
                        const VectorType &,
                        const ElasticOperatorData<2> &,
                        const AffineConstraints<double> &);
  template std::unique_ptr<ContactSolver<3>>
  create_contact_solver(const Parameters::Method,
                        const Parameters::AllParameters &,
                        const hp::MappingCollection<3> &,
                        const DoFHandler<3> &,
                        const VectorType &,
                        const ElasticOperatorData<3> &,
                        const AffineConstraints<double> &);
} // namespace ViscoContact
