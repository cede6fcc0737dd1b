// The memory term of the normal law (normal_memory.h).

#include <deal.II/base/exceptions.h>

#include "contact_nodes.h"
#include "normal_memory.h"
#include "parameters.h"

#include <algorithm>
#include <cmath>

namespace ViscoContact
{
  using namespace dealii;

  namespace
  {
    // int_0^k exp(-lambda s) ds = (1 - exp(-lambda k)) / lambda, k for
    // lambda = 0 (expm1 keeps the digits of a small lambda k).
    double
    decayed_length(const double lambda, const double k)
    {
      return lambda == 0 ? k : -std::expm1(-lambda * k) / lambda;
    }
  } // namespace



  NormalMemory::Kernel
  NormalMemory::Kernel::from_parameters(const Parameters::Contact &contact)
  {
    return {contact.memory_weights, contact.memory_rates};
  }



  double
  NormalMemory::Kernel::integral(const double t) const
  {
    double sum = 0;
    for (unsigned int k = 0; k < weights.size(); ++k)
      sum += weights[k] * decayed_length(rates[k], t);
    return sum;
  }



  void
  NormalMemory::reinit(const std::vector<Kernel>       &zone_kernels,
                       const std::vector<unsigned int> &node_zones)
  {
    kernels = zone_kernels;
    zones   = node_zones;
    n_terms = 0;
    for (const Kernel &kernel : kernels)
      {
        AssertDimension(kernel.weights.size(), kernel.rates.size());
        n_terms = std::max<unsigned int>(n_terms, kernel.weights.size());
      }
    history.assign(zones.size() * n_terms, 0.);
    step_history = history;
    penetrations.assign(zones.size(), 0.);
    pressures.assign(zones.size(), 0.);
  }



  bool
  NormalMemory::active() const
  {
    return n_terms > 0;
  }



  unsigned int
  NormalMemory::n_variables() const
  {
    return n_terms + 1;
  }



  const std::vector<double> &
  NormalMemory::start_step(const double k)
  {
    for (unsigned int i = 0; i < zones.size(); ++i)
      {
        const Kernel &kernel      = kernels[zones[i]];
        const double  penetration = penetrations[i];
        pressures[i]              = 0;
        for (unsigned int term = 0; term < kernel.weights.size(); ++term)
          {
            const double lambda = kernel.rates[term];
            const double h = std::exp(-lambda * k) * history[i * n_terms + term]
                             + kernel.weights[term] * decayed_length(lambda, k)
                                 * penetration;
            step_history[i * n_terms + term] = h;
            pressures[i] += h;
          }
      }
    return pressures;
  }



  void
  NormalMemory::accept_step(const std::vector<double> &r)
  {
    AssertDimension(r.size(), zones.size());
    history = step_history;
    for (unsigned int i = 0; i < zones.size(); ++i)
      penetrations[i] = std::max(r[i], 0.);
  }



  double
  NormalMemory::pressure(const unsigned int i) const
  {
    return pressures[i];
  }



  std::vector<double>
  NormalMemory::accepted_pressures() const
  {
    std::vector<double> result(zones.size(), 0.);
    for (unsigned int i = 0; i < zones.size(); ++i)
      for (unsigned int term = 0; term < n_terms; ++term)
        result[i] += history[i * n_terms + term];
    return result;
  }



  double
  NormalMemory::variable(const unsigned int i, const unsigned int k) const
  {
    return k < n_terms ? history[i * n_terms + k] : penetrations[i];
  }



  void
  NormalMemory::set_variable(const unsigned int i,
                             const unsigned int k,
                             const double       h)
  {
    if (k < n_terms)
      history[i * n_terms + k] = step_history[i * n_terms + k] = h;
    else
      penetrations[i] = h;
  }



  unsigned int
  NormalMemory::n_nodes() const
  {
    return zones.size();
  }



  void
  NormalMemory::start_step(const double k, ContactNodes &nodes)
  {
    nodes.set_history_pressure(start_step(k));
  }



  void
  NormalMemory::apply_accepted(ContactNodes &nodes) const
  {
    nodes.set_history_pressure(accepted_pressures());
  }



  void
  NormalMemory::accept_step(const ContactNodes &nodes)
  {
    accept_step(nodes.r);
  }
} // namespace ViscoContact
