// Archard's wear (archard_wear.h).

#include <deal.II/base/exceptions.h>

#include "archard_wear.h"
#include "contact_nodes.h"

#include <algorithm>
#include <cmath>

namespace ViscoContact
{
  using namespace dealii;

  void
  ArchardWear::reinit(const std::vector<double>       &zone_coefficients,
                      const std::vector<unsigned int> &node_zones)
  {
    coefficients = zone_coefficients;
    std::vector<bool> worn;
    for (const double k_w : coefficients)
      worn.push_back(k_w > 0);
    NodeValueHistory::reinit(worn, node_zones);
  }



  void
  ArchardWear::accept_step(const ContactNodes &nodes)
  {
    AssertDimension(nodes.size(), values.size());
    for (unsigned int i = 0; i < values.size(); ++i)
      if (has_law(i) && nodes.n_tangential(i) > 0)
        {
          const ContactNodes::Tangential slip = nodes.step_slip(i);
          values[i] += coefficients[zone(i)]
                       * std::max(nodes.contact_pressure(i), 0.)
                       * std::hypot(slip[0], slip[1]);
        }
  }



  void
  ArchardWear::apply(ContactNodes &nodes) const
  {
    nodes.set_wear(values);
  }
} // namespace ViscoContact
