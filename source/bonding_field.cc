// The bonding field of adhesion (bonding_field.h).

#include <deal.II/base/exceptions.h>

#include "bonding_field.h"
#include "contact_nodes.h"
#include "parameters.h"

#include <algorithm>

namespace ViscoContact
{
  using namespace dealii;

  BondingField::Law
  BondingField::Law::from_parameters(const Parameters::Contact &contact)
  {
    return {contact.adhesion_stiffness,
            contact.adhesion_length,
            contact.adhesion_energy,
            contact.debonding_rate};
  }



  // The explicit Euler step of beta' = -kappa (beta gamma R(r)^2 - eps)+. The
  // bracket is never negative, so beta never grows; a step that would take
  // it below 0 ends the bond (a step longer than 1 / (kappa gamma R^2)).
  double
  BondingField::Law::evolve(const double beta,
                            const double r,
                            const double k) const
  {
    const double R = std::max(-length, std::min(r, 0.));
    return std::max(0.,
                    beta
                      - k * rate
                          * std::max(0., beta * stiffness * R * R - energy));
  }



  void
  BondingField::reinit(const std::vector<Law>          &zone_laws,
                       const std::vector<unsigned int> &node_zones,
                       const std::vector<double>       &initial_bonding)
  {
    AssertDimension(node_zones.size(), initial_bonding.size());
    laws         = zone_laws;
    zones        = node_zones;
    any_adhesion = std::any_of(laws.begin(), laws.end(), [](const Law &law) {
      return law.stiffness > 0;
    });
    accepted_bonding.assign(zones.size(), 1.);
    for (unsigned int i = 0; i < zones.size(); ++i)
      if (laws[zones[i]].stiffness > 0)
        accepted_bonding[i] = initial_bonding[i];
    step_bonding = accepted_bonding;
    separations.assign(zones.size(), 0.);
  }



  bool
  BondingField::active() const
  {
    return any_adhesion;
  }



  unsigned int
  BondingField::n_variables() const
  {
    return 2;
  }



  unsigned int
  BondingField::n_nodes() const
  {
    return zones.size();
  }



  double
  BondingField::variable(const unsigned int i, const unsigned int v) const
  {
    return v == 0 ? accepted_bonding[i] : separations[i];
  }



  void
  BondingField::set_variable(const unsigned int i,
                             const unsigned int v,
                             const double       x)
  {
    if (v == 0)
      accepted_bonding[i] = step_bonding[i] = x;
    else
      separations[i] = x;
  }



  void
  BondingField::start_step(const double k, ContactNodes &nodes)
  {
    for (unsigned int i = 0; i < zones.size(); ++i)
      step_bonding[i]
        = laws[zones[i]].stiffness > 0
            ? laws[zones[i]].evolve(accepted_bonding[i], separations[i], k)
            : 1.;
    nodes.set_bonding(step_bonding);
  }



  void
  BondingField::accept_step(const std::vector<double> &r)
  {
    AssertDimension(r.size(), zones.size());
    accepted_bonding = step_bonding;
    separations      = r;
  }



  void
  BondingField::apply_accepted(ContactNodes &nodes) const
  {
    nodes.set_bonding(accepted_bonding);
  }



  double
  BondingField::bonding(const unsigned int i) const
  {
    return step_bonding[i];
  }
} // namespace ViscoContact
