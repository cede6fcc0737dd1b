// The memory term of the normal law (normal_memory.h).

#include <deal.II/base/exceptions.h>

#include "contact_set.h"
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
  NormalMemory::n_nodal_fields(const unsigned int dim) const
  {
    return active() ? (n_variables() + dim - 1) / dim : 0;
  }



  template <int dim>
  std::vector<VectorType>
  NormalMemory::nodal_fields(
    const ContactSet<dim>           &contact,
    const VectorType                &layout,
    const AffineConstraints<double> &hanging_constraints) const
  {
    std::vector<VectorType> fields(n_nodal_fields(dim), VectorType(layout));
    for (VectorType &field : fields)
      field = 0;
    for (unsigned int i = 0; i < zones.size(); ++i)
      for (unsigned int v = 0; v < n_variables(); ++v)
        fields[v / dim].local_element(contact.node(i).local_dofs[v % dim])
          = variable(i, v);
    for (VectorType &field : fields)
      {
        field.zero_out_ghost_values();
        hanging_constraints.distribute(field);
        field.update_ghost_values();
      }
    return fields;
  }



  template <int dim>
  void
  NormalMemory::set_from_nodal_fields(const ContactSet<dim>         &contact,
                                      const std::vector<VectorType> &fields)
  {
    AssertDimension(fields.size(), n_nodal_fields(dim));
    for (unsigned int i = 0; i < zones.size(); ++i)
      for (unsigned int v = 0; v < n_variables(); ++v)
        set_variable(i,
                     v,
                     fields[v / dim].local_element(
                       contact.node(i).local_dofs[v % dim]));
  }



  template std::vector<VectorType>
  NormalMemory::nodal_fields(const ContactSet<2> &,
                             const VectorType &,
                             const AffineConstraints<double> &) const;
  template std::vector<VectorType>
  NormalMemory::nodal_fields(const ContactSet<3> &,
                             const VectorType &,
                             const AffineConstraints<double> &) const;
  template void
  NormalMemory::set_from_nodal_fields(const ContactSet<2> &,
                                      const std::vector<VectorType> &);
  template void
  NormalMemory::set_from_nodal_fields(const ContactSet<3> &,
                                      const std::vector<VectorType> &);
} // namespace ViscoContact
