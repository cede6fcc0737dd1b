#ifndef viscoplastic_contact_cohesive_damage_h
#define viscoplastic_contact_cohesive_damage_h

#include "contact_history.h"

#include <vector>

namespace ViscoContact
{
  // @sect3{The damage of a cohesive interface}
  //
  // A cohesive interface (doc/model.md, section 12; contact_law.h,
  // CohesiveBranch) remembers the largest opening m = max(-r) each node has
  // reached: below it the node's tension is on the secant T(m) delta / m.
  // The step takes m from the accepted steps before it, as the paper's
  // scheme takes its histories. Beyond m the step's law is either the
  // envelope itself (implicit damage: an opening that grows within the step
  // softens within it, the step problem is a hemivariational inequality,
  // unique while the body's stiffness dominates the envelope's softening,
  // the start-up check, and every step is exact, without an error in k) or
  // a plateau at the tension reached (explicit damage: a monotone law,
  // first order in k; ContactLaw::piece()). After the step,
  // m = max(m, -r); an initial gap s counts as an opening already reached.
  class CohesiveDamage : public ContactHistory
  {
  public:
    // Whether each zone has a cohesive interface, and the zone of every
    // contact node of this rank; no node has opened at the start.
    void
    reinit(const std::vector<bool>         &zone_cohesion,
           const std::vector<unsigned int> &node_zones);

    bool
    active() const override;
    // Per node: the largest opening reached.
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

    // The reached openings on the nodes (the step's length does not enter:
    // the damage is rate-independent).
    void
    start_step(const double k, ContactNodes &nodes) override;
    // m = max(m, -r) with r of the accepted step.
    void
    accept_step(const ContactNodes &nodes) override;
    void
    apply_accepted(ContactNodes &nodes) const override;

  private:
    std::vector<bool>         cohesion;
    std::vector<unsigned int> zones;
    bool                      any_cohesion = false;
    std::vector<double>       openings;
  };
} // namespace ViscoContact

#endif
