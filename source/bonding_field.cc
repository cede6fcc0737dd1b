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



  // One step of beta' = -kappa (beta gamma R^2 - eps)+ with R from the last
  // step and beta taken at the end of the step where the bond weakens:
  // beta_n = (beta + k kappa eps) / (1 + k kappa gamma R^2) when
  // beta gamma R^2 > eps, else beta. The explicit Euler step would overshoot
  // for k kappa gamma R^2 > 1 (and end the bond at 0, where the ODE levels
  // off at eps / (gamma R^2)); this one lies between beta and that level for
  // every k, and is first order like it.
  double
  BondingField::Law::evolve(const double beta,
                            const double r,
                            const double k) const
  {
    const double R = std::max(-length, std::min(r, 0.));
    const double a = stiffness * R * R;
    if (!(beta * a > energy))
      return beta;
    return (beta + k * rate * energy) / (1 + k * rate * a);
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



  void
  BondingField::accept_step(const ContactNodes &nodes)
  {
    accept_step(nodes.r);
  }
} // namespace ViscoContact
