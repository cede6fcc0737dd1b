// The damage of a cohesive interface (cohesive_damage.h).

#include <deal.II/base/exceptions.h>

#include "cohesive_damage.h"
#include "contact_nodes.h"

#include <algorithm>

namespace ViscoContact
{
  using namespace dealii;

  void
  CohesiveDamage::accept_step(const ContactNodes &nodes)
  {
    AssertDimension(nodes.size(), values.size());
    for (unsigned int i = 0; i < values.size(); ++i)
      if (has_law(i))
        values[i] = std::max(values[i], -nodes.r[i]);
  }



  void
  CohesiveDamage::apply(ContactNodes &nodes) const
  {
    nodes.set_reached_openings(values);
  }
} // namespace ViscoContact
