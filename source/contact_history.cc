// The variables of a contact law's history as nodal fields
// (contact_history.h).

#include "contact_history.h"
#include "contact_set.h"

#include <algorithm>

namespace ViscoContact
{
  using namespace dealii;

  void
  NodeValueHistory::reinit(const std::vector<bool>         &zone_has_law,
                           const std::vector<unsigned int> &node_zones)
  {
    this->zone_has_law = zone_has_law;
    zones              = node_zones;
    any = std::find(zone_has_law.begin(), zone_has_law.end(), true)
          != zone_has_law.end();
    values.assign(zones.size(), 0.);
  }



  bool
  NodeValueHistory::active() const
  {
    return any;
  }



  unsigned int
  NodeValueHistory::n_variables() const
  {
    return 1;
  }



  unsigned int
  NodeValueHistory::n_nodes() const
  {
    return zones.size();
  }



  double
  NodeValueHistory::variable(const unsigned int i, const unsigned int) const
  {
    return values[i];
  }



  void
  NodeValueHistory::set_variable(const unsigned int i,
                                 const unsigned int,
                                 const double x)
  {
    values[i] = x;
  }



  void
  NodeValueHistory::start_step(const double, ContactNodes &nodes)
  {
    apply(nodes);
  }



  void
  NodeValueHistory::apply_accepted(ContactNodes &nodes) const
  {
    apply(nodes);
  }



  bool
  NodeValueHistory::has_law(const unsigned int i) const
  {
    return zone_has_law[zones[i]];
  }



  unsigned int
  NodeValueHistory::zone(const unsigned int i) const
  {
    return zones[i];
  }



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
