// The tangential laws of the contact zones (tangential_law.h).

#include "tangential_law.h"

#include "parameters.h"

#include <algorithm>

namespace ViscoContact
{
  std::shared_ptr<const TangentialLaw>
  TangentialLaw::from_parameters(const Parameters::Contact &contact)
  {
    std::shared_ptr<TangentialLaw> law;
    switch (contact.tangential_law)
      {
        case Parameters::TangentialLawType::tresca:
          law = std::make_shared<TrescaFriction>();
          break;
        case Parameters::TangentialLawType::coulomb:
          law = std::make_shared<CoulombFriction>(contact.friction_coefficient);
          break;
        default:
          law = std::make_shared<Frictionless>();
      }
    const bool of_rate = !contact.weakening_rates.empty();
    law->weakening
      = {of_rate ? contact.weakening_rates : contact.weakening_slips,
         contact.weakening_factors,
         of_rate};
    return law;
  }



  // f(x): the first factor up to the first point, linear between the
  // points, the last factor beyond the last.
  double
  SlipWeakening::factor(const double variable) const
  {
    if (points.empty())
      return 1;
    if (variable <= points.front())
      return factors.front();
    for (unsigned int k = 1; k < points.size(); ++k)
      if (variable <= points[k])
        return factors[k - 1]
               + (factors[k] - factors[k - 1]) * (variable - points[k - 1])
                   / (points[k] - points[k - 1]);
    return factors.back();
  }



  bool
  Frictionless::has_friction() const
  {
    return false;
  }



  bool
  Frictionless::uses_node_bounds() const
  {
    return false;
  }



  double
  Frictionless::bound(const double, const double) const
  {
    return 0;
  }



  TangentialLaw::SlipForce
  Frictionless::slip_force(const double) const
  {
    return {0, 0};
  }



  bool
  TrescaFriction::has_friction() const
  {
    return true;
  }



  bool
  TrescaFriction::uses_node_bounds() const
  {
    return true;
  }



  double
  TrescaFriction::bound(const double, const double node_bound) const
  {
    return node_bound;
  }



  TangentialLaw::SlipForce
  TrescaFriction::slip_force(const double bound) const
  {
    return {bound, 0};
  }



  CoulombFriction::CoulombFriction(const double coefficient)
    : mu(coefficient)
  {}



  bool
  CoulombFriction::has_friction() const
  {
    return true;
  }



  bool
  CoulombFriction::uses_node_bounds() const
  {
    return false;
  }



  double
  CoulombFriction::bound(const double z, const double) const
  {
    return mu * std::max(z, 0.);
  }



  TangentialLaw::SlipForce
  CoulombFriction::slip_force(const double) const
  {
    return {0, mu};
  }



  double
  CoulombFriction::coefficient() const
  {
    return mu;
  }
} // namespace ViscoContact
