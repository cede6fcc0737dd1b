// The Dirichlet parts of a scene (dirichlet_parts.h), built from the
// parameters.

#include <deal.II/fe/component_mask.h>

#include "scene/dirichlet_parts.h"
#include "scene/loads.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ViscoContact
{
  template <int dim>
  DirichletParts<dim>::DirichletParts(
    const Parameters::AllParameters &parameters)
  {
    if (!parameters.clamped_ids.empty())
      {
        boundary_parts.push_back({parameters.clamped_ids, ComponentMask()});
        names.emplace_back("clamped");
        std::vector<unsigned int> all(dim);
        for (unsigned int c = 0; c < dim; ++c)
          all[c] = c;
        part_components.push_back(all);
        functions.emplace_back();
      }
    for (const auto &[number, entry] :
         parameters.used_prescribed_displacements())
      {
        std::vector<bool> mask(dim, false);
        for (const unsigned int c : entry->component_indices())
          mask[c] = true;
        boundary_parts.push_back({entry->boundary_ids, ComponentMask(mask)});
        names.push_back("prescribed_" + std::to_string(number));
        part_components.push_back(entry->component_indices());
        functions.push_back(
          std::make_unique<FunctionParser<dim>>(entry->components.size()));
        initialize_load(*functions.back(),
                        "Boundary/Prescribed displacement "
                          + std::to_string(number),
                        "Displacement",
                        entry->displacement,
                        parameters.lengths);
        nonzero_values
          = nonzero_values || !is_zero_expression(entry->displacement);
        time_dependent = time_dependent || mentions_time(entry->displacement);
      }
  }



  template <int dim>
  unsigned int
  DirichletParts<dim>::size() const
  {
    return boundary_parts.size();
  }



  template <int dim>
  const std::vector<DirichletPart> &
  DirichletParts<dim>::parts() const
  {
    return boundary_parts;
  }



  template <int dim>
  const std::string &
  DirichletParts<dim>::name(const unsigned int part) const
  {
    return names[part];
  }



  template <int dim>
  const std::vector<unsigned int> &
  DirichletParts<dim>::components(const unsigned int part) const
  {
    return part_components[part];
  }



  template <int dim>
  bool
  DirichletParts<dim>::prescribes_function(const unsigned int part) const
  {
    return functions[part] != nullptr;
  }



  template <int dim>
  bool
  DirichletParts<dim>::has_values() const
  {
    return nonzero_values;
  }



  template <int dim>
  bool
  DirichletParts<dim>::depend_on_time() const
  {
    return time_dependent;
  }



  // The function's components are the part's components, in their order.
  template <int dim>
  std::pair<double, std::string>
  DirichletParts<dim>::value(const unsigned int part,
                             const unsigned int component,
                             const Point<dim>  &point,
                             const double       time) const
  {
    FunctionParser<dim> &function   = *functions[part];
    const auto          &components = part_components[part];
    function.set_time(time);
    const double value = function.value(point,
                                        std::find(components.begin(),
                                                  components.end(),
                                                  component)
                                          - components.begin());
    if (std::isfinite(value))
      return {value, ""};
    std::ostringstream message;
    message << "Invalid parameter <Displacement> in subsection "
            << "<Boundary/Prescribed displacement " << names[part].substr(11)
            << ">: its component "
            << "xyz"[component] << " is not finite at the point (" << point
            << ") at t = " << time
            << "; accepted: expressions with a finite value at every point "
               "of the part and every time of the run.";
    return {value, message.str()};
  }



  template class DirichletParts<2>;
  template class DirichletParts<3>;
} // namespace ViscoContact
