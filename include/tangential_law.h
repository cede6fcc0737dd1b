#ifndef viscoplastic_contact_tangential_law_h
#define viscoplastic_contact_tangential_law_h

#include <memory>
#include <vector>

namespace ViscoContact
{
  namespace Parameters
  {
    struct Contact;
  }

  // @sect3{Tangential laws}
  //
  // Friction acts on the slip increment of a time step, s - s_{n-1} (the
  // tangential displacement since the last accepted step), with exact stick:
  // a sticking node has no slip increment and a tangential force of at most
  // its bound g, a slipping node carries the force g along its slip
  // (doc/model.md, section 7). What a law decides is the bound of a node,
  // and how the force of a slipping node enters the step problem, whose
  // unknowns include the node's normal force z: value + coupling z along the
  // slip direction (the Newton linearisation of t = g(z) d). The stick/slip
  // update, the slip directions and the back ends are the same for every
  // law (ContactNodes).
  //
  // The laws of the program: frictionless; Tresca, g = w_i times the zone's
  // Slip bound at the node (the given friction of the variational
  // literature, a convex term, on every node of the zone whether it touches
  // or not); Coulomb, g = mu z_i with the node's normal force of the step. A
  // new law is a class implementing this interface (one file) and a value
  // of the Tangential law entry (TangentialLaw::from_parameters()).
  //
  // Any of them may weaken with the slip or with the slip rate
  // (doc/model.md, section 7): the bound and the coupling times f(x), x the
  // node's accumulated slip up to the last accepted step, or the rate of
  // its slip in that step (explicit, as the paper's history), f piecewise
  // linear through the points (x_k, f_k) and constant beyond them.
  struct SlipWeakening
  {
    std::vector<double> points;          // x_1 < ... < x_K (empty: f = 1)
    std::vector<double> factors;         // f_k >= 0
    bool                of_rate = false; // x the slip rate, not the slip

    double
    factor(const double variable) const;
  };

  class TangentialLaw
  {
  public:
    virtual ~TangentialLaw() = default;

    // The law of a contact zone's subsection (Tangential law, Friction
    // coefficient).
    static std::shared_ptr<const TangentialLaw>
    from_parameters(const Parameters::Contact &contact);

    // Frictionless zones have no tangential unknowns.
    virtual bool
    has_friction() const = 0;
    // Whether the law takes a bound per node from the zone's Slip bound
    // function (node_bound below; 0 otherwise).
    virtual bool
    uses_node_bounds() const = 0;
    // The bound g of a node with normal force z (>= 0 in contact) and bound
    // node_bound.
    virtual double
    bound(const double z, const double node_bound) const = 0;

    // A slipping node's force along its slip direction, value + coupling z,
    // given the node's bound at its last update.
    struct SlipForce
    {
      double value;
      double coupling;
    };
    virtual SlipForce
    slip_force(const double bound) const = 0;

    // The weakening of the zone's law (f = 1 without one).
    SlipWeakening weakening;
  };

  // No tangential force: the zone's nodes slide freely.
  class Frictionless : public TangentialLaw
  {
  public:
    bool
    has_friction() const override;
    bool
    uses_node_bounds() const override;
    double
    bound(const double z, const double node_bound) const override;
    SlipForce
    slip_force(const double bound) const override;
  };

  // Tresca: the bound is the node's share of the Slip bound, whatever the
  // normal force.
  class TrescaFriction : public TangentialLaw
  {
  public:
    bool
    has_friction() const override;
    bool
    uses_node_bounds() const override;
    double
    bound(const double z, const double node_bound) const override;
    SlipForce
    slip_force(const double bound) const override;
  };

  // Coulomb: the bound is mu z, and a slipping node's force mu z is
  // coupled to the normal force of the same solve.
  class CoulombFriction : public TangentialLaw
  {
  public:
    explicit CoulombFriction(const double coefficient);
    bool
    has_friction() const override;
    bool
    uses_node_bounds() const override;
    double
    bound(const double z, const double node_bound) const override;
    SlipForce
    slip_force(const double bound) const override;
    double
    coefficient() const;

  private:
    double mu;
  };
} // namespace ViscoContact

#endif
