// The damage of a cohesive interface (cohesive_damage.h).

#include <deal.II/base/exceptions.h>

#include "cohesive_damage.h"
#include "contact_nodes.h"

#include <algorithm>

namespace ViscoContact
{
  using namespace dealii;

  void
  CohesiveDamage::reinit(const std::vector<bool>         &zone_cohesion,
                         const std::vector<unsigned int> &node_zones)
  {
    cohesion = zone_cohesion;
    zones    = node_zones;
    any_cohesion
      = std::find(cohesion.begin(), cohesion.end(), true) != cohesion.end();
    openings.assign(zones.size(), 0.);
  }



  bool
  CohesiveDamage::active() const
  {
    return any_cohesion;
  }



  unsigned int
  CohesiveDamage::n_variables() const
  {
    return 1;
  }



  unsigned int
  CohesiveDamage::n_nodes() const
  {
    return zones.size();
  }



  double
  CohesiveDamage::variable(const unsigned int i, const unsigned int) const
  {
    return openings[i];
  }



  void
  CohesiveDamage::set_variable(const unsigned int i,
                               const unsigned int,
                               const double x)
  {
    openings[i] = x;
  }



  void
  CohesiveDamage::start_step(const double, ContactNodes &nodes)
  {
    nodes.set_reached_openings(openings);
  }



  void
  CohesiveDamage::accept_step(const ContactNodes &nodes)
  {
    AssertDimension(nodes.size(), zones.size());
    for (unsigned int i = 0; i < zones.size(); ++i)
      if (cohesion[zones[i]])
        openings[i] = std::max(openings[i], -nodes.r[i]);
  }



  void
  CohesiveDamage::apply_accepted(ContactNodes &nodes) const
  {
    nodes.set_reached_openings(openings);
  }
} // namespace ViscoContact
