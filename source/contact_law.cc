// The contact law as a graph made of pieces (contact_law.h, doc/model.md,
// sections 2 and 5): its construction from the parameters, and the two
// queries of the active-set method, the piece that q = p + c r names and the
// update rule that keeps a node at a breakpoint from flipping back and
// forth.
#include <deal.II/base/exceptions.h>

#include "contact_law.h"
#include "parameters.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace ViscoContact
{
  using namespace dealii;

  // @sect4{ContactLawPiece}
  //
  // An adhesive piece at a node of bonding beta: its pressures times
  // a = beta^2, the interval in r unchanged.
  ContactLawPiece
  ContactLawPiece::scaled(const double a) const
  {
    if (!adhesive || a == 1)
      return *this;
    ContactLawPiece result = *this;
    result.slope *= a;
    result.intercept *= a;
    result.p_lower *= a;
    result.p_upper *= a;
    return result;
  }



  bool
  ContactLawPiece::operator==(const ContactLawPiece &other) const
  {
    return vertical == other.vertical && rigid == other.rigid
           && r_lower == other.r_lower && r_upper == other.r_upper
           && p_lower == other.p_lower && p_upper == other.p_upper
           && slope == other.slope && intercept == other.intercept
           && adhesive == other.adhesive && cohesive == other.cohesive;
  }



  // @sect4{The envelope of a cohesive interface}
  //
  // Linear softening: three points. Exponential softening: the tail
  // T_c exp(-x / lambda), x = delta - delta_0, at exponential_pieces - 1
  // equal steps down to T_c / 1000, then 0 one more step on; its openings
  // are then stretched by the factor that makes the area under the
  // polygon G_c (the polygon lies above the convex exponential, and the
  // truncation takes a little off: the factor is close to 1).
  std::vector<std::array<double, 2>>
  cohesive_envelope(const CohesiveBranch &cohesion)
  {
    const double tension     = cohesion.strength;
    const double delta_0     = tension / cohesion.stiffness;
    const double tail_energy = cohesion.fracture_energy - tension * delta_0 / 2;
    AssertThrow(cohesion.stiffness > 0 && tail_energy > 0
                  && std::isfinite(tail_energy / tension),
                ExcMessage("A cohesive branch needs a stiffness > 0 and a "
                           "fracture energy > strength^2 / (2 stiffness)."));
    if (!cohesion.exponential)
      return {{{0., 0.}},
              {{delta_0, tension}},
              {{2 * cohesion.fracture_energy / tension, 0.}}};
    const unsigned int n      = CohesiveBranch::exponential_pieces;
    const double       length = tail_energy / tension; // lambda
    const double       step   = length * std::log(1000.) / (n - 1);
    std::vector<std::array<double, 2>> tail;
    for (unsigned int j = 0; j < n; ++j)
      tail.push_back({{j * step, tension * std::exp(-(j * step) / length)}});
    tail.push_back({{n * step, 0.}});
    double area = 0;
    for (unsigned int j = 0; j + 1 < tail.size(); ++j)
      area += (tail[j + 1][0] - tail[j][0]) * (tail[j][1] + tail[j + 1][1]) / 2;
    std::vector<std::array<double, 2>> envelope{{{0., 0.}}};
    for (const auto &[x, T] : tail)
      envelope.push_back({{delta_0 + x * tail_energy / area, T}});
    return envelope;
  }



  // @sect4{ContactLaw::ContactLaw}
  //
  // Walk along r from -infinity: a sloped piece up to each breakpoint, then
  // (if the law jumps there) a vertical piece, and so on. The rigid limit
  // cuts the graph at r = g and closes it with the vertical piece
  // [p(g-), +infinity); breakpoints at or beyond g are then irrelevant.
  ContactLaw::ContactLaw(const std::vector<double> &breakpoints,
                         const std::vector<double> &slopes,
                         const std::vector<double> &jumps_in,
                         const bool                 unilateral_constraint,
                         const double               gap,
                         const AdhesiveBranch      &adhesion,
                         const CohesiveBranch      &cohesion)
    : gap_value(gap)
    , length_scale(std::abs(gap))
  {
    // The data must describe a law: one slope per interval, one jump per
    // breakpoint (no jumps given means none).
    AssertThrow(slopes.size() == breakpoints.size() + 1,
                ExcMessage("A contact law needs one more slope than "
                           "breakpoints."));
    const std::vector<double> jumps
      = (jumps_in.empty() ? std::vector<double>(breakpoints.size(), 0.)
                          : jumps_in);
    AssertThrow(jumps.size() == breakpoints.size(),
                ExcMessage("A contact law needs one jump per breakpoint."));

    // With the rigid foundation, the graph ends at r = g; without it, it
    // goes on to +infinity.
    const double infinity = std::numeric_limits<double>::infinity();
    const double limit    = (unilateral_constraint ? gap : infinity);

    // Start left of b_1 with p(b_1-) = 0 (or with p = 0 if there is no
    // breakpoint at all).
    double left_point = (breakpoints.empty() ? 0. : breakpoints[0]);
    double left_value = 0;
    for (unsigned int k = 0; k <= breakpoints.size(); ++k)
      {
        // The interval (b_k, b_{k+1}) of sloped piece k, cut at the limit; a
        // piece that would start at or beyond g is not part of the graph.
        const double r_lower = (k == 0 ? -infinity : breakpoints[k - 1]);
        double r_upper = (k == breakpoints.size() ? infinity : breakpoints[k]);
        if (r_lower >= limit)
          break;
        r_upper = std::min(r_upper, limit);

        // The sloped piece through (left_point, left_value) with the
        // interval's slope, so that p is continuous from the right at every
        // breakpoint.
        ContactLawPiece sloped;
        sloped.r_lower   = r_lower;
        sloped.r_upper   = r_upper;
        sloped.slope     = slopes[k];
        sloped.intercept = left_value - slopes[k] * left_point;
        pieces.push_back(sloped);

        // At a breakpoint below the limit: the value of p just before it, a
        // vertical piece if p jumps there (upward jumps only, doc/model.md,
        // section 5), and the point the next sloped piece starts from.
        if (k < breakpoints.size() && breakpoints[k] < limit)
          {
            const double value_before
              = sloped.intercept + sloped.slope * breakpoints[k];
            AssertThrow(jumps[k] >= 0,
                        ExcMessage("Jumps of a contact law must be >= 0."));
            if (jumps[k] > 0)
              {
                ContactLawPiece vertical;
                vertical.vertical = true;
                vertical.r_lower = vertical.r_upper = breakpoints[k];
                vertical.p_lower                    = value_before;
                vertical.p_upper                    = value_before + jumps[k];
                pieces.push_back(vertical);
              }
            left_point = breakpoints[k];
            left_value = value_before + jumps[k];
          }
      }

    // An adhesive or a cohesive branch replaces the law's zero pressure
    // below r = 0. The law's first piece then starts at r = 0, or is gone
    // if it ended there.
    AssertThrow(adhesion.stiffness == 0 || cohesion.strength == 0,
                ExcMessage("A contact law has an adhesive or a cohesive "
                           "branch, not both."));
    const auto tension_below_zero = [&](const char *branch) {
      ContactLawPiece &first = pieces.front();
      AssertThrow(!first.vertical && first.slope == 0 && first.intercept == 0
                    && first.r_upper >= 0 && gap >= 0,
                  ExcMessage(std::string("A ") + branch
                             + " branch needs a law that is zero for r < 0 "
                               "and a gap >= 0."));
      first.r_lower = 0;
      if (first.r_upper == 0)
        pieces.erase(pieces.begin());
    };
    // Adhesion: the constant tension -stiffness length below -length, the
    // slope stiffness up to 0 (continuous, nondecreasing: it adds no
    // softening).
    if (adhesion.stiffness > 0)
      {
        tension_below_zero("adhesive");
        AssertThrow(adhesion.length > 0,
                    ExcMessage("An adhesive branch needs a length > 0."));
        ContactLawPiece tension, bond;
        tension.adhesive = bond.adhesive = true;
        tension.r_upper = bond.r_lower = -adhesion.length;
        tension.intercept              = -adhesion.stiffness * adhesion.length;
        bond.r_upper                   = 0;
        bond.slope                     = adhesion.stiffness;
        pieces.insert(pieces.begin(), {tension, bond});
        length_scale = std::max(length_scale, adhesion.length);
      }
    // A cohesive interface: no tension beyond delta_f, then the pieces of
    // the envelope from delta_f in to 0 (p = -T, r = -delta: a segment from
    // (delta_k, T_k) to (delta_k+1, T_k+1) has the slope dT / d delta; the
    // softening ones are what the uniqueness condition must dominate), the
    // last one the stiffness K up to r = 0.
    if (cohesion.strength > 0)
      {
        tension_below_zero("cohesive");
        const std::vector<std::array<double, 2>> envelope
          = cohesive_envelope(cohesion);
        std::vector<ContactLawPiece> branch(1);
        branch[0].r_upper = -envelope.back()[0];
        for (unsigned int k = envelope.size() - 1; k > 0; --k)
          {
            const auto &[outer_opening, outer_tension] = envelope[k];
            const auto &[inner_opening, inner_tension] = envelope[k - 1];
            ContactLawPiece segment;
            segment.r_lower = -outer_opening;
            segment.r_upper = -inner_opening;
            segment.slope   = k == 1 ? cohesion.stiffness
                                     : (outer_tension - inner_tension)
                                       / (outer_opening - inner_opening);
            // The elastic piece through the origin exactly.
            segment.intercept
              = k == 1 ? 0. : -outer_tension + segment.slope * outer_opening;
            branch.push_back(segment);
          }
        for (ContactLawPiece &piece : branch)
          piece.cohesive = true;
        pieces.insert(pieces.begin(), branch.begin(), branch.end());
        n_cohesive_pieces = branch.size();
        explicit_damage   = cohesion.explicit_damage;
        length_scale      = std::max(length_scale, envelope.back()[0]);
      }

    // The rigid foundation: the vertical piece at r = g from p(g-), the
    // layer's pressure when it is crushed, to +infinity.
    if (unilateral_constraint)
      {
        const ContactLawPiece &last = pieces.back();
        ContactLawPiece        rigid;
        rigid.vertical = rigid.rigid = true;
        // At g = 0 behind an adhesive branch the layer's pressure is
        // p(0-) = 0 at every bonding.
        rigid.r_lower = rigid.r_upper = gap;
        rigid.p_lower                 = last.intercept + last.slope * gap;
        rigid.p_upper                 = infinity;
        pieces.push_back(rigid);
      }
  }



  // @sect4{ContactLaw::from_parameters}
  //
  // The three ways subsection Contact describes a law, as breakpoints,
  // slopes and jumps: no normal compliance (p = 0, Signorini's condition if
  // the rigid limit is on); the benchmark's nonmonotone law, slope c1 on
  // [0, u1] and c2 beyond (just c2 from 0 on if u1 = 0); or a general
  // piecewise-linear law given as it is.
  ContactLaw
  ContactLaw::from_parameters(const Parameters::Contact &contact)
  {
    const AdhesiveBranch adhesion{contact.adhesion_stiffness,
                                  contact.adhesion_length};
    const CohesiveBranch cohesion{contact.cohesive_stiffness,
                                  contact.cohesive_strength,
                                  contact.fracture_energy,
                                  contact.cohesive_damage == "explicit",
                                  contact.cohesive_softening == "exponential"};
    const auto           law = [&](const std::vector<double> &breakpoints,
                         const std::vector<double> &slopes,
                         const std::vector<double> &jumps) {
      return ContactLaw(breakpoints,
                        slopes,
                        jumps,
                        contact.unilateral_constraint,
                        contact.gap,
                        adhesion,
                        cohesion);
    };
    if (!contact.normal_compliance)
      return law({}, {0.}, {});
    if (contact.law_type == Parameters::ContactLawType::nonmonotone
        && contact.u1 == 0)
      return law({0.}, {0., contact.c2}, {0.});
    if (contact.law_type == Parameters::ContactLawType::nonmonotone)
      return law({0., contact.u1}, {0., contact.c1, contact.c2}, {0., 0.});
    return law(contact.breakpoints, contact.slopes, contact.jumps);
  }



  // The pieces, in order from r = -infinity.
  unsigned int
  ContactLaw::n_pieces() const
  {
    return pieces.size();
  }



  const ContactLawPiece &
  ContactLaw::piece(const unsigned int i) const
  {
    AssertIndexRange(i, pieces.size());
    return pieces[i];
  }



  // @sect4{ContactLaw::piece at a node}
  //
  // Adhesive pieces scaled by the node's bonding. A cohesive piece that
  // reaches into the opened range (-m, 0] is cut at r = -m; the one that
  // ends at r = 0 becomes the secant p = (T(m) / m) r on [-m, 0] once m
  // passes its own range (before that it is the secant), and pieces within
  // the range shrink to the point r = -m of the secant, so that the graph
  // stays one monotone chain in q = p + c r.
  //
  // With the damage from the last step, the node's law is the secant up to
  // m* = max(m, delta_0) and the plateau at its tension T(m*) beyond: the
  // broken piece becomes the plateau, the elastic one the secant, and the
  // softening pieces the point r = -m* between the two.
  ContactLawPiece
  ContactLaw::piece(const unsigned int i, const NodeLawState &node) const
  {
    ContactLawPiece result = piece(i).scaled(node.adhesion_scale);
    if (result.cohesive && explicit_damage)
      {
        const unsigned int last = n_cohesive_pieces - 1; // the elastic one
        const double m = std::max(node.reached_opening, -pieces[last].r_lower);
        const double tension = envelope_tension(m);
        result.r_lower       = (i == 0 ? result.r_lower : -m);
        result.r_upper       = (i == last ? 0. : -m);
        result.slope         = (i == 0 ? 0. : tension / m);
        result.intercept     = (i == 0 ? -tension : 0.);
        return result;
      }
    const double m = node.reached_opening;
    if (!result.cohesive || !(result.r_upper > -m))
      return result;
    if (result.r_lower < -m)
      {
        if (result.r_upper < 0)
          result.r_upper = -m;
        return result;
      }
    result.r_lower   = -m;
    result.r_upper   = (result.r_upper == 0 ? 0. : -m);
    result.slope     = envelope_tension(m) / m;
    result.intercept = 0;
    return result;
  }



  // The tension -p of the original cohesive piece that contains r = -m.
  double
  ContactLaw::envelope_tension(const double opening) const
  {
    for (const ContactLawPiece &piece : pieces)
      if (piece.cohesive && -opening <= piece.r_upper)
        return -(piece.intercept - piece.slope * opening);
    return 0;
  }



  // @sect4{ContactLaw::find_piece}
  //
  // The upper end of each piece in the monotone parameter q = p + c r; the
  // first piece whose upper end is not below q contains the point. Ties go
  // to the left piece, so a node exactly at a breakpoint stays on the piece
  // it came from when it moves right. The last piece extends to
  // q = +infinity, so every q names a piece.
  unsigned int
  ContactLaw::find_piece(const double        q,
                         const double        c,
                         const NodeLawState &node) const
  {
    Assert(c > steepest_softening(),
           ExcMessage("The active-set parameter c must exceed the steepest "
                      "softening of the contact law."));
    for (unsigned int i = 0; i + 1 < pieces.size(); ++i)
      {
        const ContactLawPiece piece = this->piece(i, node);
        const double          q_upper
          = (piece.vertical
               ? piece.p_upper + c * piece.r_upper
               : piece.intercept + (piece.slope + c) * piece.r_upper);
        if (q <= q_upper)
          return i;
      }
    return pieces.size() - 1;
  }



  // @sect4{ContactLaw::next_piece}
  //
  // The update rule of one node: stay on the current piece if q lies in its
  // range [q_lower, q_upper] up to a small slack, else find the piece q
  // names. The slack is relative to q and to c times a length: the law's
  // own (the gap g, the size of q at the rigid limit, or the length of an
  // adhesive or cohesive branch) or the displacements of the solve, whose
  // rounding enters q as c r. It only absorbs rounding: without it a node
  // that sits exactly at a breakpoint could jump between the two pieces
  // that meet there from one iteration to the next, and the active set
  // would never settle. (A bonded node far from the load sits at r = 0
  // with a displacement of round-off, 1e-15 where the lift is 0.1; with
  // g = 0 a slack relative to q alone let it flip between the bond and the
  // base forever.)
  unsigned int
  ContactLaw::next_piece(const unsigned int  current,
                         const double        q,
                         const double        c,
                         const NodeLawState &node,
                         const double        displacement_scale) const
  {
    const ContactLawPiece piece = this->piece(current, node);
    const double          q_lower
      = (piece.vertical ? piece.p_lower + c * piece.r_lower
                        : piece.intercept + (piece.slope + c) * piece.r_lower);
    const double q_upper
      = (piece.vertical ? piece.p_upper + c * piece.r_upper
                        : piece.intercept + (piece.slope + c) * piece.r_upper);
    const double slack
      = 1e-12 * (std::abs(q) + c * std::max(length_scale, displacement_scale))
        + 1e-300;
    if (q < q_lower - slack || q > q_upper + slack)
      return find_piece(q, c, node);
    return current;
  }



  // @sect4{ContactLaw::compliance_pressure}
  //
  // p(r) of the layer from the sloped pieces: the first whose interval
  // reaches r. Vertical pieces are skipped, so at a breakpoint this is the
  // left limit.
  double
  ContactLaw::compliance_pressure(const double r) const
  {
    for (const ContactLawPiece &piece : pieces)
      if (!piece.vertical && r <= piece.r_upper)
        return piece.intercept + piece.slope * r;
    // Beyond the last sloped piece (only reachable at the rigid limit).
    for (auto piece = pieces.rbegin(); piece != pieces.rend(); ++piece)
      if (!piece->vertical)
        return piece->intercept + piece->slope * piece->r_upper;
    return 0;
  }



  // @sect4{Properties of the law}
  //
  // The steepest softening max(0, -smallest slope), which the parameters c_i
  // and the uniqueness margin must exceed; whether the law does nothing at
  // all (one flat piece p = 0 and no rigid limit, so contact is skipped);
  // whether it has the rigid limit; and the gap g.
  //
  // A cohesive envelope whose damage is taken from the last step does not
  // soften within the step: its nodes' laws are monotone.
  double
  ContactLaw::steepest_softening() const
  {
    double softening = 0;
    for (const ContactLawPiece &piece : pieces)
      if (!piece.vertical && !(piece.cohesive && explicit_damage))
        softening = std::max(softening, -piece.slope);
    return softening;
  }



  bool
  ContactLaw::is_void() const
  {
    return pieces.size() == 1 && pieces[0].slope == 0
           && pieces[0].intercept == 0;
  }



  bool
  ContactLaw::has_adhesion() const
  {
    return pieces.front().adhesive;
  }



  bool
  ContactLaw::has_cohesion() const
  {
    return pieces.front().cohesive;
  }



  // 1 - T(m) / (K m), K the slope of the envelope's first piece from r = 0.
  double
  ContactLaw::damage(const double reached_opening) const
  {
    if (!has_cohesion() || !(reached_opening > 0))
      return 0;
    const double stiffness = pieces[n_cohesive_pieces - 1].slope;
    return std::clamp(1
                        - envelope_tension(reached_opening)
                            / (stiffness * reached_opening),
                      0.,
                      1.);
  }



  bool
  ContactLaw::has_rigid_limit() const
  {
    return pieces.back().rigid;
  }



  double
  ContactLaw::gap() const
  {
    return gap_value;
  }


  // @sect4{ContactLaws}
  //
  // The table of the pieces of all zones: zone z's pieces are the indices
  // first_piece[z], ..., first_piece[z + 1] - 1.
  ContactLaws::ContactLaws(const std::vector<ContactLaw> &zone_laws)
    : laws(zone_laws)
    , first_piece{0}
  {
    for (const ContactLaw &law : laws)
      first_piece.push_back(first_piece.back() + law.n_pieces());
  }



  ContactLaws::ContactLaws(const ContactLaw &law)
    : ContactLaws(std::vector<ContactLaw>{law})
  {}



  unsigned int
  ContactLaws::n_zones() const
  {
    return laws.size();
  }



  const ContactLaw &
  ContactLaws::zone_law(const unsigned int zone) const
  {
    AssertIndexRange(zone, laws.size());
    return laws[zone];
  }



  unsigned int
  ContactLaws::n_pieces() const
  {
    return first_piece.back();
  }



  const ContactLawPiece &
  ContactLaws::piece(const unsigned int index) const
  {
    const unsigned int zone = zone_of_piece(index);
    return laws[zone].piece(index - first_piece[zone]);
  }



  unsigned int
  ContactLaws::zone_of_piece(const unsigned int index) const
  {
    AssertIndexRange(index, n_pieces());
    return std::upper_bound(first_piece.begin(), first_piece.end(), index)
           - first_piece.begin() - 1;
  }



  ContactLawPiece
  ContactLaws::piece(const unsigned int index, const NodeLawState &node) const
  {
    const unsigned int zone = zone_of_piece(index);
    return laws[zone].piece(index - first_piece[zone], node);
  }



  unsigned int
  ContactLaws::find_piece(const unsigned int  zone,
                          const double        q,
                          const double        c,
                          const NodeLawState &node) const
  {
    return first_piece[zone] + zone_law(zone).find_piece(q, c, node);
  }



  unsigned int
  ContactLaws::next_piece(const unsigned int  zone,
                          const unsigned int  current,
                          const double        q,
                          const double        c,
                          const NodeLawState &node,
                          const double        displacement_scale) const
  {
    Assert(zone_of_piece(current) == zone, ExcInternalError());
    return first_piece[zone]
           + zone_law(zone).next_piece(current - first_piece[zone],
                                       q,
                                       c,
                                       node,
                                       displacement_scale);
  }



  double
  ContactLaws::steepest_softening() const
  {
    double softening = 0;
    for (const ContactLaw &law : laws)
      softening = std::max(softening, law.steepest_softening());
    return softening;
  }



  double
  ContactLaws::largest_gap() const
  {
    double gap = 0;
    for (const ContactLaw &law : laws)
      gap = std::max(gap, law.gap());
    return gap;
  }
} // namespace ViscoContact
