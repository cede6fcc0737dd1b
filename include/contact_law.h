#ifndef viscoplastic_contact_contact_law_h
#define viscoplastic_contact_contact_law_h

#include "tangential_law.h"

#include <array>
#include <limits>
#include <memory>
#include <vector>

namespace ViscoContact
{
  namespace Parameters
  {
    struct Contact;
  }

  // @sect3{The normal contact law as a graph made of pieces}
  //
  // The contact condition at a node relates the normal displacement
  // r = u_nu (positive = penetration into the layer) and the normal pressure
  // p the foundation exerts. Normal compliance p in dj(r) (Clarke
  // subdifferential of a piecewise-quadratic potential j) and the rigid limit
  // r <= g together form one graph in the (r, p) plane, made of
  //  - sloped pieces: p = intercept + slope * r for r in [r_lower, r_upper];
  //  - vertical pieces: r = breakpoint, p in [p_lower, p_upper]; the rigid
  //    foundation is the last one, [p(g-), +infinity) at r = g.
  // The active-set method (doc/model.md, section 5) assigns every contact node
  // to one piece; Signorini's condition, the benchmark's nonmonotone law and
  // laws with jumps are then one mechanism.
  //
  // For any c > max(0, -smallest slope) the quantity q = p + c r increases
  // strictly along the graph, so q names a unique point of it: find_piece()
  // is the generalisation of the primal-dual active set criterion
  // "lambda + c (u_nu - g) > 0".
  struct ContactLawPiece
  {
    bool   vertical  = false;
    bool   rigid     = false; // the foundation below the layer (r = g)
    double r_lower   = -std::numeric_limits<double>::infinity();
    double r_upper   = std::numeric_limits<double>::infinity();
    double p_lower   = 0; // vertical pieces only
    double p_upper   = 0;
    double slope     = 0; // sloped pieces only
    double intercept = 0;
    // A piece of the adhesive branch (r < 0): its pressures scale with the
    // node's bonding, beta^2 (scaled()).
    bool adhesive = false;
    // A piece of a cohesive interface's envelope (r < 0): below the opening
    // a node has reached, its law is the secant instead
    // (ContactLaw::piece()).
    bool cohesive = false;

    // The piece at a node whose adhesive pressures are scaled by a (its
    // bonding beta^2; pieces that are not adhesive are returned as they are).
    ContactLawPiece
    scaled(const double a) const;
    bool
    operator==(const ContactLawPiece &other) const;
  };

  // The adhesive branch of a normal law (doc/model.md, section 10): for
  // r < 0 (the body separated from the obstacle) the tension
  // p = stiffness beta^2 R(r), R(r) = max(-length, r), with the node's
  // bonding beta in [0, 1]. Stiffness 0: no adhesion.
  struct AdhesiveBranch
  {
    double stiffness = 0;
    double length    = 0;
  };

  // A cohesive interface (doc/model.md, section 12): for r < 0 the
  // tension T(delta) of the opening delta = -r rises with the stiffness K
  // to the strength T_c at delta_0 = T_c / K and softens linearly to 0 at
  // delta_f = 2 G_c / T_c, so that the work of separation is the fracture
  // energy G_c. Below the largest opening m a node has reached, the tension
  // is on the secant T(m) delta / m: the damage 1 - T(m) / (K m) never
  // heals. Strength 0: no cohesive interface.
  //
  // With exponential softening the tension falls as
  // T_c exp(-(delta - delta_0) / lambda) instead, lambda = (G_c - T_c
  // delta_0 / 2) / T_c, interpolated linearly between exponential_pieces
  // points down to T_c / 1000 and then to 0, the openings of the tail
  // stretched so that the work of separation is G_c exactly
  // (cohesive_envelope()).
  //
  // Within a time step the opening beyond m follows either the envelope
  // itself (implicit: exact, a softening law whose step problem is unique
  // only where the body dominates the softening) or, with explicit_damage,
  // a plateau at the tension T(max(m, delta_0)) the node has reached (a
  // monotone law, unique like the law without it; the tension lags the
  // envelope by one step, first order in k).
  struct CohesiveBranch
  {
    double stiffness       = 0;
    double strength        = 0;
    double fracture_energy = 0;
    bool   explicit_damage = false;
    bool   exponential     = false;

    static constexpr unsigned int exponential_pieces = 16;
  };

  // The envelope of a cohesive branch as the points (delta_k, T_k) it
  // interpolates linearly: (0, 0), (delta_0, T_c), ..., (delta_f, 0).
  std::vector<std::array<double, 2>>
  cohesive_envelope(const CohesiveBranch &cohesion);

  // What the history of a node changes in its law (contact_history.h): the
  // scale of its adhesive pieces (its bonding beta^2) and the largest
  // opening its cohesive interface has reached.
  struct NodeLawState
  {
    double adhesion_scale  = 1;
    double reached_opening = 0;
  };

  class ContactLaw
  {
  public:
    // A law defined by breakpoints b_1 < ... < b_K, the K+1 slopes on the
    // intervals between them, the K jumps p(b_k+) - p(b_k-) >= 0 and
    // p(b_1-) = 0, optionally cut off by the rigid foundation at r = g;
    // with an adhesive or a cohesive branch, the law for r < 0 is that
    // branch (the law given must then be zero there; not both).
    ContactLaw(const std::vector<double> &breakpoints,
               const std::vector<double> &slopes,
               const std::vector<double> &jumps,
               const bool                 unilateral_constraint,
               const double               gap,
               const AdhesiveBranch      &adhesion = {},
               const CohesiveBranch      &cohesion = {});

    // The law the parameter file describes (subsection Contact).
    static ContactLaw
    from_parameters(const Parameters::Contact &contact);

    unsigned int
    n_pieces() const;
    const ContactLawPiece &
    piece(const unsigned int i) const;
    // Piece i as it acts at a node of the given history: adhesive pieces
    // scaled by its bonding; a cohesive envelope below the reached opening m
    // replaced by the secant through (-m, -T(m)), the pieces there shrunk to
    // the point r = -m on it.
    ContactLawPiece
    piece(const unsigned int i, const NodeLawState &node) const;

    // The piece that contains the graph point with p + c r = q, at a node
    // of the given history.
    unsigned int
    find_piece(const double        q,
               const double        c,
               const NodeLawState &node = {}) const;

    // The active-set update of one node: the piece that q = p + c r names,
    // except that a node whose q lies within rounding of the ends of its
    // current piece stays there, so that roundoff cannot make a node at a
    // breakpoint flip back and forth.
    // The displacement scale (the largest |r| of the solve) sets the
    // rounding of q along with the law's own length.
    unsigned int
    next_piece(const unsigned int  current,
               const double        q,
               const double        c,
               const NodeLawState &node               = {},
               const double        displacement_scale = 0) const;

    // The single-valued part of the compliance law: p(r) for r below the
    // rigid limit (the left limit at breakpoints).
    double
    compliance_pressure(const double r) const;

    // Whether the law has an adhesive branch, a cohesive one.
    bool
    has_adhesion() const;
    bool
    has_cohesion() const;
    // The damage 1 - T(m) / (K m) of a cohesive interface that has reached
    // the opening m (0 without one).
    double
    damage(const double reached_opening) const;

    // max(0, -smallest slope): the softening the uniqueness condition and
    // the active-set parameter c have to dominate.
    double
    steepest_softening() const;

    // True if the law is zero everywhere and has no rigid limit: contact
    // can then be skipped altogether.
    bool
    is_void() const;

    bool
    has_rigid_limit() const;
    double
    gap() const;

  private:
    std::vector<ContactLawPiece> pieces;
    double                       gap_value;
    // The pieces of a cohesive branch (the first ones; the last of them the
    // elastic piece up to r = 0), and whether its damage is taken from the
    // last step (CohesiveBranch::explicit_damage).
    unsigned int n_cohesive_pieces = 0;
    bool         explicit_damage   = false;
    // The length over which the law acts: the gap, or the length of an
    // adhesive or a cohesive branch (the scale of next_piece()'s slack).
    double length_scale = 0;

    // The tension of the cohesive envelope at the opening m.
    double
    envelope_tension(const double opening) const;
  };

  // The tangential law of a contact zone (tangential_law.h), shared by the
  // zone's description and the contact nodes.
  using FrictionLaw = std::shared_ptr<const TangentialLaw>;



  // @sect3{The laws of several contact zones}
  //
  // Each contact zone has its own law. The active-set method and the back
  // ends see one table of pieces: the pieces of zone 0, then those of zone
  // 1, and so on, so that a piece index names a piece of one zone's law,
  // and a back end reads a node's piece without knowing its zone. Finding
  // a node's next piece needs its zone.
  class ContactLaws
  {
  public:
    ContactLaws() = default;
    explicit ContactLaws(const std::vector<ContactLaw> &zone_laws);
    // One zone.
    ContactLaws(const ContactLaw &law);

    unsigned int
    n_zones() const;
    const ContactLaw &
    zone_law(const unsigned int zone) const;

    // The pieces of all zones, zone by zone, and the zone of a piece.
    unsigned int
    n_pieces() const;
    const ContactLawPiece &
    piece(const unsigned int index) const;
    unsigned int
    zone_of_piece(const unsigned int index) const;

    // A piece as it acts at a node of the given history
    // (ContactLaw::piece()).
    ContactLawPiece
    piece(const unsigned int index, const NodeLawState &node) const;

    // ContactLaw::find_piece and next_piece of the zone's law, in the
    // indices of the table.
    unsigned int
    find_piece(const unsigned int  zone,
               const double        q,
               const double        c,
               const NodeLawState &node = {}) const;
    unsigned int
    next_piece(const unsigned int  zone,
               const unsigned int  current,
               const double        q,
               const double        c,
               const NodeLawState &node               = {},
               const double        displacement_scale = 0) const;

    // Over all zones: the steepest softening and the largest gap.
    double
    steepest_softening() const;
    double
    largest_gap() const;

  private:
    std::vector<ContactLaw>   laws;
    std::vector<unsigned int> first_piece; // of each zone, and the total
  };
} // namespace ViscoContact

#endif
