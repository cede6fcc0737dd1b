#ifndef viscoplastic_contact_bonding_field_h
#define viscoplastic_contact_bonding_field_h

#include "contact_history.h"

#include <vector>

namespace ViscoContact
{
  namespace Parameters
  {
    struct Contact;
  }

  // @sect3{The bonding field of adhesion}
  //
  // Adhesion (doc/model.md, section 10; Fremond's bonding field): a node
  // that separates from the obstacle (r < 0) is pulled back by the tension
  // gamma beta^2 R(r), R(r) = max(-L, r), where beta in [0, 1] is the
  // node's bonding, 1 for an intact bond and 0 for none. The bond weakens
  // irreversibly as
  //   beta' = -kappa (beta gamma R(r)^2 - epsilon)+,
  // epsilon the adhesion energy below which it holds. The step from
  // t_{n-1} to t_n takes r of the last accepted step (explicit in the
  // state, first order in k, as the paper takes the viscoplastic history)
  // and beta at its end where the bond weakens (stable for every k):
  //   beta_n = (beta_{n-1} + k kappa epsilon) / (1 + k kappa gamma
  //   R(r_{n-1})^2) if beta_{n-1} gamma R(r_{n-1})^2 > epsilon, else
  //   beta_{n-1},
  // and within the step the node's adhesive pieces are scaled by beta_n^2
  // (ContactNodes::set_bonding()): the step problem is the
  // piecewise-linear one of a fixed law, monotone on the adhesive branch,
  // so the uniqueness condition is that of the law without adhesion.
  class BondingField : public ContactHistory
  {
  public:
    struct Law
    {
      double stiffness = 0; // gamma; 0: no adhesion
      double length    = 0; // L
      double energy    = 0; // epsilon
      double rate      = 1; // kappa

      // The law of a contact zone's subsection (Adhesion stiffness, ...).
      static Law
      from_parameters(const Parameters::Contact &contact);
      // The bonding after a step of length k from beta with the
      // separation r of the step before it.
      double
      evolve(const double beta, const double r, const double k) const;
    };

    // The laws of the zones, the zone of every contact node of this rank
    // and its bonding at t = 0 (ignored in zones without adhesion).
    void
    reinit(const std::vector<Law>          &zone_laws,
           const std::vector<unsigned int> &node_zones,
           const std::vector<double>       &initial_bonding);

    bool
    active() const override;
    // Per node: beta, then r of the last accepted step.
    unsigned int
    n_variables() const override;
    unsigned int
    n_nodes() const override;
    double
    variable(const unsigned int i, const unsigned int v) const override;
    void
    set_variable(const unsigned int i,
                 const unsigned int v,
                 const double       x) override;

    // The bondings beta_n of a step of length k, on the nodes.
    void
    start_step(const double k, ContactNodes &nodes) override;
    void
    accept_step(const std::vector<double> &r);
    void
    accept_step(const ContactNodes &nodes) override;
    void
    apply_accepted(ContactNodes &nodes) const override;

    // The bonding of node i in the step being solved (after it is
    // accepted: in that step).
    double
    bonding(const unsigned int i) const;

  private:
    std::vector<Law>          laws;
    std::vector<unsigned int> zones;
    bool                      any_adhesion = false;
    // Per node: beta and r of the last accepted step, beta of the step
    // being solved.
    std::vector<double> accepted_bonding, separations, step_bonding;
  };
} // namespace ViscoContact

#endif
