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
  class CohesiveDamage : public NodeValueHistory
  {
  public:
    // m = max(m, -r) at the nodes of a cohesive zone (NodeValueHistory::
    // reinit(): whether each zone has a cohesive interface; no node has
    // opened at the start).
    void
    accept_step(const ContactNodes &nodes) override;

  private:
    // The reached openings cut the nodes' laws.
    void
    apply(ContactNodes &nodes) const override;
  };
} // namespace ViscoContact

#endif
