#ifndef viscoplastic_contact_normal_memory_h
#define viscoplastic_contact_normal_memory_h

#include "contact_history.h"

#include <vector>

namespace ViscoContact
{
  using namespace dealii;

  namespace Parameters
  {
    struct Contact;
  }
  // @sect3{The memory term of the normal law}
  //
  // Normal compliance with memory (doc/model.md, section 9): the pressure on
  // the body is p(r(t)) + int_0^t b(t - s) r+(s) ds, the integral over the
  // penetrations of the past weighted by a kernel b. With b a sum of
  // exponentials, b(t) = sum_k a_k exp(-lambda_k t), the integral is a sum of
  // terms h_k(t) with h_k' = a_k r+ - lambda_k h_k, a few numbers per node
  // instead of the whole history. The step from t_{n-1} to t_n takes r+ of
  // the last accepted step, as the paper's scheme takes the stresses of the
  // last step into the viscoplastic history (explicit, first order in k):
  //   h_k(t_n) = exp(-lambda_k k_n) h_k(t_{n-1})
  //              + a_k (1 - exp(-lambda_k k_n)) / lambda_k r+_{n-1}
  // (a_k k_n r+_{n-1} for lambda_k = 0), exact for a penetration that is
  // constant over the step. Within the step the memory pressure
  // m_i = sum_k h_k(t_n) is a constant of node i: the graph of the law moved
  // up by m_i (ContactNodes::set_history_pressure()), so that the step
  // problem keeps the structure, the uniqueness condition and the active set
  // of the law without memory.
  class NormalMemory : public ContactHistory
  {
  public:
    struct Kernel
    {
      std::vector<double> weights; // a_k
      std::vector<double> rates;   // lambda_k >= 0

      // The kernel of a contact zone's subsection (Memory weights, Memory
      // rates).
      static Kernel
      from_parameters(const Parameters::Contact &contact);
      // int_0^t b(s) ds.
      double
      integral(const double t) const;
    };

    // The kernels of the zones and the zone of every contact node of this
    // rank; every node starts without history.
    void
    reinit(const std::vector<Kernel>       &zone_kernels,
           const std::vector<unsigned int> &node_zones);

    // Whether any zone has a memory term.
    bool
    active() const override;
    // The history variables per node: the terms h_k (the most terms of any
    // zone; a node of a zone with fewer has zeros in the others), then r+
    // of the last accepted step.
    unsigned int
    n_variables() const override;
    unsigned int
    n_nodes() const override;
    double
    variable(const unsigned int i, const unsigned int k) const override;
    void
    set_variable(const unsigned int i,
                 const unsigned int k,
                 const double       h) override;

    // The memory pressures m_i of a step of length k from the history at the
    // start of the step, and the nodes' laws moved up by them.
    const std::vector<double> &
    start_step(const double k);
    void
    start_step(const double k, ContactNodes &nodes) override;
    void
    accept_step(const std::vector<double> &r);
    void
    accept_step(const ContactNodes &nodes) override;
    // The memory pressures of the last accepted step from its history
    // (sum_k h_k(t_n)), on the nodes.
    void
    apply_accepted(ContactNodes &nodes) const override;

    // The memory pressure of node i in the current step, and those of the
    // last accepted step.
    double
    pressure(const unsigned int i) const;
    std::vector<double>
    accepted_pressures() const;

  private:
    std::vector<Kernel>       kernels;
    std::vector<unsigned int> zones;
    unsigned int              n_terms = 0;
    // Per node: n_terms values at the last accepted step, and those of the
    // step being solved; r+ of the last accepted step; the memory pressure
    // of the step being solved.
    std::vector<double> history, step_history;
    std::vector<double> penetrations;
    std::vector<double> pressures;
  };
} // namespace ViscoContact

#endif
