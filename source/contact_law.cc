#include <deal.II/base/exceptions.h>

#include "contact_law.h"
#include "parameters.h"

#include <algorithm>
#include <cmath>

namespace ViscoContact
{
  using namespace dealii;

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
                         const double               gap)
    : gap_value(gap)
  {
    AssertThrow(slopes.size() == breakpoints.size() + 1,
                ExcMessage("A contact law needs one more slope than "
                           "breakpoints."));
    const std::vector<double> jumps
      = (jumps_in.empty() ? std::vector<double>(breakpoints.size(), 0.)
                          : jumps_in);
    AssertThrow(jumps.size() == breakpoints.size(),
                ExcMessage("A contact law needs one jump per breakpoint."));

    const double infinity = std::numeric_limits<double>::infinity();
    const double limit    = (unilateral_constraint ? gap : infinity);

    // Start left of b_1 with p(b_1-) = 0 (or with p = 0 if there is no
    // breakpoint at all).
    double left_point = (breakpoints.empty() ? 0. : breakpoints[0]);
    double left_value = 0;
    for (unsigned int k = 0; k <= breakpoints.size(); ++k)
      {
        const double r_lower = (k == 0 ? -infinity : breakpoints[k - 1]);
        double r_upper = (k == breakpoints.size() ? infinity : breakpoints[k]);
        if (r_lower >= limit)
          break;
        r_upper = std::min(r_upper, limit);

        ContactLawPiece sloped;
        sloped.r_lower   = r_lower;
        sloped.r_upper   = r_upper;
        sloped.slope     = slopes[k];
        sloped.intercept = left_value - slopes[k] * left_point;
        pieces.push_back(sloped);

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

    if (unilateral_constraint)
      {
        const ContactLawPiece &last = pieces.back();
        ContactLawPiece        rigid;
        rigid.vertical = rigid.rigid = true;
        rigid.r_lower = rigid.r_upper = gap;
        rigid.p_lower                 = last.intercept + last.slope * gap;
        rigid.p_upper                 = infinity;
        pieces.push_back(rigid);
      }
  }



  ContactLaw
  ContactLaw::from_parameters(const Parameters::Contact &contact)
  {
    if (!contact.normal_compliance)
      return ContactLaw({},
                        {0.},
                        {},
                        contact.unilateral_constraint,
                        contact.gap);
    if (contact.law_type == Parameters::ContactLawType::nonmonotone
        && contact.u1 == 0)
      return ContactLaw({0.},
                        {0., contact.c2},
                        {0.},
                        contact.unilateral_constraint,
                        contact.gap);
    if (contact.law_type == Parameters::ContactLawType::nonmonotone)
      return ContactLaw({0., contact.u1},
                        {0., contact.c1, contact.c2},
                        {0., 0.},
                        contact.unilateral_constraint,
                        contact.gap);
    return ContactLaw(contact.breakpoints,
                      contact.slopes,
                      contact.jumps,
                      contact.unilateral_constraint,
                      contact.gap);
  }



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



  // @sect4{ContactLaw::find_piece}
  //
  // The upper end of each piece in the monotone parameter q = p + c r; the
  // first piece whose upper end is not below q contains the point. Ties go to
  // the left piece, so a node exactly at a breakpoint stays on the piece it
  // came from when it moves right.
  unsigned int
  ContactLaw::find_piece(const double q, const double c) const
  {
    Assert(c > steepest_softening(),
           ExcMessage("The active-set parameter c must exceed the steepest "
                      "softening of the contact law."));
    for (unsigned int i = 0; i + 1 < pieces.size(); ++i)
      {
        const ContactLawPiece &piece = pieces[i];
        const double           q_upper
          = (piece.vertical
               ? piece.p_upper + c * piece.r_upper
               : piece.intercept + (piece.slope + c) * piece.r_upper);
        if (q <= q_upper)
          return i;
      }
    return pieces.size() - 1;
  }



  unsigned int
  ContactLaw::next_piece(const unsigned int current,
                         const double       q,
                         const double       c) const
  {
    const ContactLawPiece &piece = pieces[current];
    const double           q_lower
      = (piece.vertical ? piece.p_lower + c * piece.r_lower
                        : piece.intercept + (piece.slope + c) * piece.r_lower);
    const double q_upper
      = (piece.vertical ? piece.p_upper + c * piece.r_upper
                        : piece.intercept + (piece.slope + c) * piece.r_upper);
    const double slack = 1e-12 * (std::abs(q) + c * gap_value) + 1e-300;
    if (q < q_lower - slack || q > q_upper + slack)
      return find_piece(q, c);
    return current;
  }



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



  double
  ContactLaw::steepest_softening() const
  {
    double softening = 0;
    for (const ContactLawPiece &piece : pieces)
      if (!piece.vertical)
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
  ContactLaw::has_rigid_limit() const
  {
    return pieces.back().rigid;
  }



  double
  ContactLaw::gap() const
  {
    return gap_value;
  }
} // namespace ViscoContact
