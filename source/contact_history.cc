// The variables of a contact law's history as nodal fields
// (contact_history.h).

#include "contact_history.h"
#include "contact_set.h"

namespace ViscoContact
{
  using namespace dealii;

  unsigned int
  ContactHistory::n_nodal_fields(const unsigned int dim) const
  {
    return active() ? (n_variables() + dim - 1) / dim : 0;
  }



  template <int dim>
  std::vector<VectorType>
  ContactHistory::nodal_fields(
    const ContactSet<dim>           &contact,
    const VectorType                &layout,
    const AffineConstraints<double> &hanging_constraints) const
  {
    std::vector<VectorType> fields(n_nodal_fields(dim), VectorType(layout));
    for (VectorType &field : fields)
      field = 0;
    for (unsigned int i = 0; i < n_nodes() && !fields.empty(); ++i)
      for (unsigned int v = 0; v < n_variables(); ++v)
        fields[v / dim].local_element(contact.node(i).local_dofs[v % dim])
          = variable(i, v);
    for (VectorType &field : fields)
      {
        field.zero_out_ghost_values();
        hanging_constraints.distribute(field);
        field.update_ghost_values();
      }
    return fields;
  }



  template <int dim>
  void
  ContactHistory::set_from_nodal_fields(
    const ContactSet<dim>             &contact,
    const ArrayView<const VectorType> &fields)
  {
    AssertDimension(fields.size(), n_nodal_fields(dim));
    for (unsigned int i = 0; i < n_nodes() && fields.size() > 0; ++i)
      for (unsigned int v = 0; v < n_variables(); ++v)
        set_variable(i,
                     v,
                     fields[v / dim].local_element(
                       contact.node(i).local_dofs[v % dim]));
  }



  template std::vector<VectorType>
  ContactHistory::nodal_fields(const ContactSet<2> &,
                               const VectorType &,
                               const AffineConstraints<double> &) const;
  template std::vector<VectorType>
  ContactHistory::nodal_fields(const ContactSet<3> &,
                               const VectorType &,
                               const AffineConstraints<double> &) const;
  template void
  ContactHistory::set_from_nodal_fields(const ContactSet<2> &,
                                        const ArrayView<const VectorType> &);
  template void
  ContactHistory::set_from_nodal_fields(const ContactSet<3> &,
                                        const ArrayView<const VectorType> &);
} // namespace ViscoContact
