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
    zones        = node_zones;
    any_wear     = std::any_of(coefficients.begin(),
                           coefficients.end(),
                           [](const double k_w) { return k_w > 0; });
    depths.assign(zones.size(), 0.);
  }



  bool
  ArchardWear::active() const
  {
    return any_wear;
  }



  unsigned int
  ArchardWear::n_variables() const
  {
    return 1;
  }



  unsigned int
  ArchardWear::n_nodes() const
  {
    return zones.size();
  }



  double
  ArchardWear::variable(const unsigned int i, const unsigned int) const
  {
    return depths[i];
  }



  void
  ArchardWear::set_variable(const unsigned int i,
                            const unsigned int,
                            const double x)
  {
    depths[i] = x;
  }



  void
  ArchardWear::start_step(const double, ContactNodes &nodes)
  {
    nodes.set_wear(depths);
  }



  void
  ArchardWear::accept_step(const ContactNodes &nodes)
  {
    AssertDimension(nodes.size(), zones.size());
    for (unsigned int i = 0; i < zones.size(); ++i)
      if (coefficients[zones[i]] > 0 && nodes.n_tangential(i) > 0)
        {
          const ContactNodes::Tangential slip = nodes.step_slip(i);
          depths[i] += coefficients[zones[i]]
                       * std::max(nodes.contact_pressure(i), 0.)
                       * std::hypot(slip[0], slip[1]);
        }
  }



  void
  ArchardWear::apply_accepted(ContactNodes &nodes) const
  {
    nodes.set_wear(depths);
  }
} // namespace ViscoContact
