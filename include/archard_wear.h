#ifndef viscoplastic_contact_archard_wear_h
#define viscoplastic_contact_archard_wear_h

#include "contact_history.h"

#include <vector>

namespace ViscoContact
{
  // @sect3{Wear}
  //
  // Archard's law (doc/model.md, section 11): where a node slips under a
  // pressure its surface wears away at the rate
  //   w' = k_w p |s'|,
  // k_w the zone's Wear coefficient, p the contact pressure and s the slip
  // relative to the obstacle. The worn depth w moves the node's obstacle
  // away by w: the gap of the next step is s_i + w_i, so that a node must
  // go w further to touch. Explicit as the other histories: the wear of
  // step n, w_n = w_{n-1} + k_w p_n |s_n - s_{n-1}|, enters the gap of step
  // n + 1 (exact for a constant pressure and slip rate, first order in k
  // otherwise); within a step the gap is fixed, so the step problem is that
  // of the law without wear.
  class ArchardWear : public NodeValueHistory
  {
  public:
    // The wear coefficient of every zone (0: no wear) and the zone of every
    // contact node of this rank; no node is worn at the start. The value of
    // a node is its worn depth.
    void
    reinit(const std::vector<double>       &zone_coefficients,
           const std::vector<unsigned int> &node_zones);

    // w += k_w max(p, 0) |slip| with the pressures and the slips of the
    // accepted step (ContactNodes::step_slip(), after accept_slip()).
    void
    accept_step(const ContactNodes &nodes) override;

  private:
    // The worn depths move the gaps.
    void
    apply(ContactNodes &nodes) const override;

    std::vector<double> coefficients;
  };
} // namespace ViscoContact

#endif
