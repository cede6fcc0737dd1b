// The contact zones of a scene (contact_zones.h), built from the
// parameters.

#include <deal.II/base/tensor.h>

#include "scene/contact_zones.h"
#include "scene/loads.h"

namespace ViscoContact
{
  template <int dim>
  ContactZones<dim>::ContactZones(const Parameters::AllParameters &parameters)
  {
    for (const Parameters::ContactZone &zone : parameters.used_contact_zones())
      {
        const Parameters::Contact  &entries = *zone.contact;
        ContactZoneDescription<dim> description{
          zone.number,
          zone.subsection,
          ContactLaw::from_parameters(entries),
          zone.boundary_ids,
          {},
          TangentialLaw::from_parameters(entries),
          entries.opposite_ids,
          entries.search_distance == "auto"
            ? 0.
            : Utilities::string_to_double(entries.search_distance),
          entries.geometric_gap == "measured"};
        if (description.law.is_void())
          continue;
        if (entries.gap_direction != "normal")
          {
            const std::vector<double> d = entries.direction_vector();
            Tensor<1, dim>            direction;
            for (unsigned int c = 0; c < dim; ++c)
              direction[c] = d[c];
            description.direction = direction;
          }
        std::unique_ptr<FunctionParser<dim>> gap;
        if (!is_zero_expression(entries.initial_gap))
          {
            gap = std::make_unique<FunctionParser<dim>>(1);
            initialize_load(*gap,
                            zone.subsection,
                            "Initial gap",
                            entries.initial_gap,
                            parameters.lengths);
            any_gap = true;
            time_dependent_gap
              = time_dependent_gap || mentions_time(entries.initial_gap);
          }
        std::unique_ptr<FunctionParser<dim>> slip_bound;
        if (description.friction->uses_node_bounds())
          {
            slip_bound = std::make_unique<FunctionParser<dim>>(1);
            initialize_load(*slip_bound,
                            zone.subsection,
                            "Slip bound",
                            entries.slip_bound,
                            parameters.lengths);
          }
        zones.push_back(std::move(description));
        gap_functions.push_back(std::move(gap));
        slip_bound_functions.push_back(std::move(slip_bound));
      }
  }



  template <int dim>
  bool
  ContactZones<dim>::empty() const
  {
    return zones.empty();
  }



  template <int dim>
  const std::vector<ContactZoneDescription<dim>> &
  ContactZones<dim>::descriptions() const
  {
    return zones;
  }



  template <int dim>
  std::vector<unsigned int>
  ContactZones<dim>::numbers() const
  {
    std::vector<unsigned int> result;
    for (const auto &zone : zones)
      result.push_back(zone.number);
    return result;
  }



  template <int dim>
  std::vector<unsigned int>
  ContactZones<dim>::frictional_numbers() const
  {
    std::vector<unsigned int> result;
    for (const auto &zone : zones)
      if (zone.friction->has_friction())
        result.push_back(zone.number);
    return result;
  }



  template <int dim>
  std::vector<unsigned int>
  ContactZones<dim>::pair_numbers() const
  {
    std::vector<unsigned int> result;
    for (const auto &zone : zones)
      if (!zone.opposite_ids.empty())
        result.push_back(zone.number);
    return result;
  }



  template <int dim>
  std::vector<Function<dim> *>
  ContactZones<dim>::gaps() const
  {
    std::vector<Function<dim> *> result;
    for (const auto &gap : gap_functions)
      result.push_back(gap.get());
    return result;
  }



  template <int dim>
  std::vector<const Function<dim> *>
  ContactZones<dim>::slip_bounds() const
  {
    std::vector<const Function<dim> *> result;
    for (const auto &bound : slip_bound_functions)
      result.push_back(bound.get());
    return result;
  }



  template <int dim>
  bool
  ContactZones<dim>::has_gap() const
  {
    return any_gap;
  }



  template <int dim>
  bool
  ContactZones<dim>::gap_depends_on_time() const
  {
    return time_dependent_gap;
  }



  template class ContactZones<2>;
  template class ContactZones<3>;
} // namespace ViscoContact
