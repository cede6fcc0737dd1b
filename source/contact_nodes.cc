// The active-set iteration on the pieces of the contact law, and the state
// of the contact nodes it moves.
//
// This is the semismooth Newton method of doc/model.md, section 2 ("Moving
// between pieces"), written once for every back end and every number of
// ranks: the back end only solves the linear problem of the current pieces
// and writes r and z; everything this file does is local to the nodes of a
// rank, except for a few sums of counts over the ranks, which make every
// rank take the same decisions.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include "contact_nodes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <map>
#include <sstream>

namespace ViscoContact
{
  namespace
  {
    // Element-wise sums of a few counters over all ranks, in one reduction.
    // Every rank receives the same sums, so decisions based on them agree.
    template <std::size_t N>
    std::array<unsigned int, N>
    sum_over_ranks(const std::array<unsigned int, N> &local,
                   const MPI_Comm                     communicator)
    {
      std::array<unsigned int, N> sums;
      Utilities::MPI::sum(ArrayView<const unsigned int>(local.data(), N),
                          communicator,
                          ArrayView<unsigned int>(sums.data(), N));
      return sums;
    }

    // Whether the last three iterations kept their pieces and their linear
    // solves no longer improve (none of the last two halved the residual
    // and it stays above the tolerance): the accuracy of the linear
    // problem is exhausted.
    bool
    stagnates(const std::vector<ActiveSetResult::IterationRecord> &history,
              const double                                         tolerance)
    {
      const std::size_t n = history.size();
      if (n < 3)
        return false;
      bool stagnant = true;
      for (std::size_t j = n - 2; j < n; ++j)
        stagnant = stagnant && history[j].changed_nodes == 0
                   && history[j - 1].changed_nodes == 0
                   && history[j].linear_residual > tolerance
                   && history[j].linear_residual
                        > 0.5 * history[j - 1].linear_residual;
      return stagnant;
    }
  } // namespace



  // @sect4{ActiveSetResult}
  //
  // The number of iterations of a time step: those of earlier active-set
  // runs of the step (the implicit scheme runs one per Newton iteration)
  // plus those of the last run, one record each.
  unsigned int
  ActiveSetResult::iterations() const
  {
    return earlier_iterations + history.size();
  }



  // Krylov iterations, likewise (0 for the condensed back end, whose solves
  // are direct).
  unsigned int
  ActiveSetResult::inner_iterations() const
  {
    unsigned int sum = earlier_inner_iterations;
    for (const IterationRecord &record : history)
      sum += record.inner_iterations;
    return sum;
  }



  // The iteration history of the last run, one line per iteration, for the
  // report of a failed step (step_report.cc) and Print iteration history:
  // how many nodes moved, how many sit at the rigid limit, and how well the
  // linear solve did.
  std::string
  ActiveSetResult::describe() const
  {
    std::ostringstream out;
    for (unsigned int i = 0; i < history.size(); ++i)
      out << "    iteration " << i + 1 << ": " << history[i].changed_nodes
          << " nodes changed their piece, " << history[i].rigid_nodes
          << " nodes at the rigid limit, "
          << (history[i].adjusted_nodes > 0
                ? std::to_string(history[i].adjusted_nodes)
                    + " slipping nodes turned their slip direction, "
                : std::string())
          << "linear residual " << std::setprecision(3)
          << history[i].linear_residual
          << (history[i].inner_iterations > 0
                ? " after " + std::to_string(history[i].inner_iterations)
                    + " Krylov iterations"
                : std::string())
          << '\n';
    return out.str();
  }



  // @sect4{ContactNodes::reinit}
  //
  // Every node starts at r = z = 0 with no parameter yet; its piece is
  // chosen by the first set_parameters(), since finding the piece of a state
  // needs c.
  void
  ContactNodes::reinit(const ContactLaws               &laws,
                       const std::vector<unsigned int> &zones,
                       const std::vector<double>       &weights)
  {
    AssertDimension(zones.size(), weights.size());
    contact_laws = laws;
    node_zones   = zones;
    w            = weights;
    c.assign(w.size(), 0.);
    r.assign(w.size(), 0.);
    z.assign(w.size(), 0.);
    node_gaps.assign(w.size(), 0.);
    node_pieces.assign(w.size(), 0);
    placed           = false;
    memory_pressures = StepValues(0.);
    node_bonding     = StepValues(1.);
    worn_depths      = StepValues(0.);
    node_openings    = StepValues(0.);
    set_friction(std::vector<FrictionLaw>(laws.n_zones(),
                                          std::make_shared<Frictionless>()),
                 std::vector<unsigned int>(w.size(), 0),
                 std::vector<double>(w.size(), 0.));
  }



  // @sect4{ContactNodes::set_friction}
  //
  // Every frictional node starts stuck with no slip: the first solve of a
  // run then holds the contact zone tangentially, so that a body held
  // sideways by friction alone has a nonsingular first problem.
  void
  ContactNodes::set_friction(
    const std::vector<FrictionLaw>  &zone_laws,
    const std::vector<unsigned int> &tangential_directions_of_nodes,
    const std::vector<double>       &tresca_bounds)
  {
    AssertDimension(zone_laws.size(), contact_laws.n_zones());
    AssertDimension(tangential_directions_of_nodes.size(), size());
    AssertDimension(tresca_bounds.size(), size());
    zone_friction         = zone_laws;
    tangential_directions = tangential_directions_of_nodes;
    tresca_bound          = tresca_bounds;
    const Tangential zero = {{0, 0}};
    s.assign(size(), zero);
    t.assign(size(), zero);
    slip_reference.assign(size(), zero);
    slip_direction.assign(size(), zero);
    last_slip.assign(size(), zero);
    friction_states.assign(size(), free_tangential);
    weakening_state.assign(size(), 0.);
    obstacle_slip.clear();
    bounds.assign(size(), 0.);
    transverse_stiffness.assign(size(), 0.);
    for (unsigned int i = 0; i < size(); ++i)
      if (tangential_directions[i] > 0)
        friction_states[i] = stick;
  }



  // @sect4{The values of the laws with a history}
  void
  ContactNodes::set_history_pressure(const std::vector<double> &pressures)
  {
    memory_pressures.set(pressures, size());
  }



  bool
  ContactNodes::has_memory() const
  {
    return memory_pressures.given;
  }



  double
  ContactNodes::history_pressure(const unsigned int i) const
  {
    return memory_pressures(i);
  }



  const std::vector<double> &
  ContactNodes::history_pressures() const
  {
    return memory_pressures.values;
  }



  void
  ContactNodes::set_bonding(const std::vector<double> &bonding)
  {
    node_bonding.set(bonding, size());
  }



  bool
  ContactNodes::has_adhesion() const
  {
    return node_bonding.given;
  }



  double
  ContactNodes::bonding(const unsigned int i) const
  {
    return node_bonding(i);
  }



  const std::vector<double> &
  ContactNodes::bondings() const
  {
    return node_bonding.values;
  }



  void
  ContactNodes::set_reached_openings(const std::vector<double> &openings)
  {
    node_openings.set(openings, size());
  }



  bool
  ContactNodes::has_cohesion() const
  {
    return node_openings.given;
  }



  double
  ContactNodes::reached_opening(const unsigned int i) const
  {
    return node_openings(i);
  }



  const std::vector<double> &
  ContactNodes::reached_openings() const
  {
    return node_openings.values;
  }



  NodeLawState
  ContactNodes::law_state(const unsigned int i) const
  {
    return {bonding(i) * bonding(i), reached_opening(i)};
  }



  // @sect4{ContactNodes::rests_at_gaps}
  //
  // q = p + c r increases strictly along a graph, so q = c r_i - m_i names
  // the one point of node i's graph that (r_i, 0) can be (on the law's
  // graph, where the memory pressure is taken off, p = -m_i); the node
  // rests if that point is at r_i, up to rounding relative to the largest
  // gap of all ranks.
  bool
  ContactNodes::rests_at_gaps(const std::vector<double> &gaps,
                              const MPI_Comm             communicator) const
  {
    AssertDimension(gaps.size(), size());
    Assert(placed, ExcMessage("The parameters c are not set."));
    double largest_gap = 0;
    for (const double gap : gaps)
      largest_gap = std::max(largest_gap, std::abs(gap));
    largest_gap = Utilities::MPI::max(largest_gap, communicator);
    bool rests  = true;
    for (unsigned int i = 0; i < size() && rests; ++i)
      {
        const double          r     = -gaps[i];
        const double          q     = c[i] * r - history_pressure(i);
        const ContactLawPiece piece = contact_laws.piece(
          contact_laws.find_piece(node_zones[i], q, c[i], law_state(i)),
          law_state(i));
        const double r_on_graph
          = piece.vertical ? piece.r_lower
                           : (q - piece.intercept) / (piece.slope + c[i]);
        rests = std::abs(r_on_graph - r)
                <= 1e-12 * std::max({largest_gap, std::abs(r_on_graph)});
      }
    return Utilities::MPI::min(rests ? 1 : 0, communicator) == 1;
  }



  double
  ContactNodes::damage(const unsigned int i) const
  {
    return contact_laws.zone_law(node_zones[i]).damage(reached_opening(i));
  }



  void
  ContactNodes::set_wear(const std::vector<double> &depths)
  {
    worn_depths.set(depths, size());
  }



  bool
  ContactNodes::has_wear() const
  {
    return worn_depths.given;
  }



  double
  ContactNodes::wear(const unsigned int i) const
  {
    return worn_depths(i);
  }



  // @sect4{ContactNodes::set_parameters}
  //
  // The parameter c_i scales the normal displacement into a pressure; it
  // changes with the operator (the implicit scheme's tangent), the pieces do
  // not: they are the warm start of the next solve.
  //
  // c_i must exceed the steepest softening, or q = p + c r would not grow
  // strictly along the graph and the update rule could name no piece or
  // several. ContactSet::set_operator() guarantees this with its factor 2,
  // so a violation is an internal error, not a user's.
  void
  ContactNodes::set_parameters(const std::vector<double> &parameters)
  {
    AssertDimension(parameters.size(), size());
    for (unsigned int i = 0; i < size(); ++i)
      AssertThrow(parameters[i]
                    > contact_laws.zone_law(node_zones[i]).steepest_softening(),
                  ExcInternalError());
    c = parameters;
    // The first call places every node on the piece of its state r = z = 0
    // (q = 0), the state before the first load. Later calls keep the pieces.
    if (!placed)
      for (unsigned int i = 0; i < size(); ++i)
        node_pieces[i]
          = contact_laws.find_piece(node_zones[i], 0., c[i], law_state(i));
    placed = true;
  }



  // @sect4{ContactNodes::update_all_pieces}
  //
  // The update rule on every rank, after the scales of the solve are known
  // on all of them. The rounding of q = p + c r is relative to the largest
  // |r| (ContactLaw::next_piece()): a node far from the load, at r = 0 with
  // a force of round-off, must not flip between two pieces that meet there.
  // The rounding of a slip is relative to the displacements of the
  // frictional nodes, |(u.nu, s)| = |(r + gap, s)|, not to r, which holds
  // the gaps of the nodes out of contact (on a curved obstacle far larger
  // than any displacement) and is zero at every node pressed onto a flat
  // rigid obstacle, however far the nodes slip. The counts are summed over
  // the ranks.
  std::array<unsigned int, 3>
  ContactNodes::update_all_pieces(const MPI_Comm communicator)
  {
    std::vector<double> largest = {0, 0};
    for (unsigned int i = 0; i < size(); ++i)
      {
        largest[0] = std::max(largest[0], std::abs(r[i]));
        if (tangential_directions[i] > 0)
          largest[1] = std::max(largest[1],
                                std::hypot(r[i] + node_gaps[i],
                                           std::hypot(s[i][0], s[i][1])));
      }
    Utilities::MPI::max(std::vector<double>(largest), communicator, largest);
    displacement_scale = largest[0];
    slip_scale         = largest[1];
    return sum_over_ranks(update_pieces(), communicator);
  }



  // @sect4{ContactNodes::update_pieces}
  //
  // The update rule at every node of this rank: q_i = z_i / w_i + c_i r_i
  // from the last solve names the next piece (ContactLaw::next_piece), on
  // the law's graph once the memory pressure m_i is taken off. The counts
  // are this rank's only; ContactNodes::solve() sums them.
  std::array<unsigned int, 3>
  ContactNodes::update_pieces(const bool with_friction)
  {
    unsigned int changed = 0, rigid = 0, adjusted = 0;
    for (unsigned int i = 0; i < size(); ++i)
      {
        const unsigned int next
          = contact_laws.next_piece(node_zones[i],
                                    node_pieces[i],
                                    z[i] / w[i] - history_pressure(i)
                                      + c[i] * r[i],
                                    c[i],
                                    law_state(i),
                                    displacement_scale);
        if (next != node_pieces[i])
          {
            node_pieces[i] = next;
            ++changed;
          }
        // After the move: the nodes now at the rigid limit, for the
        // iteration history.
        if (current_piece(i).rigid)
          ++rigid;
      }
    // Friction after the normal law: Coulomb's bound takes the normal force
    // of the same solve.
    for (unsigned int i = 0; i < size() && with_friction; ++i)
      {
        const std::array<bool, 2> moved = update_friction(i);
        changed += moved[0];
        adjusted += moved[1];
      }
    return {{changed, rigid, adjusted}};
  }



  // @sect4{ContactNodes::update_friction}
  //
  // The stick/slip rule of the semismooth Newton method for friction
  // (doc/model.md, section 7), in nodal forces: with the slip increment
  // ds = s - s_{n-1} and the tangential force t of the last solve,
  // q = t + c w ds names the state. |q| <= g: stick (then ds = 0 and t = q);
  // |q| > g: slip along d = q / |q| with the force g d. A zero bound leaves
  // the node free. As for the pieces, a node within rounding of its
  // threshold keeps its state.
  //
  // In 3D the direction of slip is an unknown too: the Newton linearisation
  // of t = g q / |q| adds a stiffness k_e = c w gamma / (1 - gamma),
  // gamma = g / |q|, across the slip direction (zero at convergence, where
  // ds is along d), capped at 100 c w where gamma is close to 1; changes of
  // the direction are reported as adjustments until the change of q they
  // stand for falls below the friction tolerance. Coulomb's bound mu z is not
  // frozen: the step problem couples a slipping node's tangential force to its
  // normal force of the same solve (directions()), the Newton linearisation of
  // t = mu z d, so the bound needs no fixed point.
  std::array<bool, 2>
  ContactNodes::update_friction(const unsigned int i)
  {
    const unsigned int k = tangential_directions[i];
    if (k == 0)
      return {{false, false}};
    const double     g         = bound_of(i);
    Tangential       q         = {{0, 0}};
    const Tangential reference = stick_position(i);
    for (unsigned int j = 0; j < k; ++j)
      q[j] = t[i][j] + c[i] * w[i] * (s[i][j] - reference[j]);
    // hypot: the squares of forces of a tiny bound (a Friction coefficient
    // of 1e-200, say) would underflow to zero.
    const double q_norm = std::hypot(q[0], q[1]);

    const unsigned int old      = friction_states[i];
    const double       rounding = 1e-9;
    unsigned int       next     = (q_norm <= g ? stick : slip);
    // A bound below the rounding of the node's forces (a Friction
    // coefficient or Slip bound of 1e-200, say) holds nothing the arithmetic
    // resolves: the node is free, as with a zero bound. Otherwise rounding in
    // q would decide between stick and slip, and the iteration would cycle.
    if (g <= 1e-14 * (std::abs(z[i]) + q_norm))
      next = free_tangential;
    else if (old == stick && q_norm <= g * (1 + rounding))
      next = stick;
    else if (old == slip && q_norm >= g * (1 - rounding))
      next = slip;
    // A slipping node whose q has turned against its slip direction goes
    // through stick instead of reversing: the Newton step overshot (the
    // solve with the force along d moved the node the other way), and
    // reversing would only overshoot back (a cycle of two iterations,
    // seen on a nearly incompressible Hertz cylinder). Stuck, the node's
    // next force is its reaction, which names the direction.
    if (old == slip && next == slip)
      {
        double turn = 0;
        for (unsigned int j = 0; j < k; ++j)
          turn += q[j] * slip_direction[i][j];
        if (turn < 0)
          next = stick;
      }

    bool adjusted = false;
    if (next == slip)
      {
        const Tangential previous = slip_direction[i];
        set_slip_direction(i, q, g);
        double change = 0;
        for (unsigned int j = 0; j < k; ++j)
          change += (slip_direction[i][j] - previous[j])
                    * (slip_direction[i][j] - previous[j]);
        // The turn counts by the change of q across d it stands for,
        // |q| |d - d_prev|, against the larger of |q| and the force c w D
        // of the node's spring over the slip scale D: the rounding
        // of the node's slip shows in q times c w, so a node that barely
        // slips (|q| near g, far below c w D) has a direction that follows
        // that rounding magnified by c w / |q| (on the cube with friction at
        // 108k dofs such a node turned by 1e-6 in every iteration while the
        // solves stood still), and a node that slips far (|q| of c w D or
        // more) is held to the relative change as before.
        adjusted = old == slip
                   && q_norm * std::sqrt(change)
                        > friction_tolerance
                            * std::max(q_norm, c[i] * w[i] * slip_scale);
      }
    bounds[i]          = g;
    friction_states[i] = next;
    return {{next != old, adjusted}};
  }



  // @sect4{ContactNodes::directions}
  //
  // The node's equations as directions of its frame: the normal one fixed on
  // a vertical piece (u.nu = beta + gap) or free with the force
  // w (o + m + s (u.nu - gap)), m the memory pressure; the tangential ones
  // fixed at the last step's tangential displacement when the node sticks, free
  // with no force when the bound is zero, and, when it slips, free along the
  // slip direction d with the force g (Tresca) or mu z (Coulomb, coupled to the
  // normal force z of the same solve) and (in 3D) free across it with the
  // stiffness k_e against the slip increment.
  NodeDirections
  ContactNodes::directions(const unsigned int i, const double gap) const
  {
    NodeDirections        result;
    const ContactLawPiece piece  = current_piece(i);
    NodeDirection        &normal = result.direction[0];
    normal.frame                 = {{1, 0, 0}};
    if (piece.vertical)
      {
        normal.fixed = true;
        normal.value = piece.r_lower + gap;
      }
    else
      {
        normal.value
          = w[i] * (piece.intercept + history_pressure(i) - piece.slope * gap);
        normal.stiffness = w[i] * piece.slope;
      }
    result.size          = 1 + tangential_directions[i];
    const unsigned int k = tangential_directions[i];
    if (k == 0)
      return result;
    const Tangential reference = stick_position(i);
    if (friction_states[i] != slip)
      {
        for (unsigned int j = 0; j < k; ++j)
          {
            NodeDirection &tangential = result.direction[1 + j];
            tangential.frame[1 + j]   = 1;
            tangential.fixed          = (friction_states[i] == stick);
            tangential.value
              = (friction_states[i] == stick ? reference[j] : 0.);
          }
        return result;
      }
    const Tangential &d     = slip_direction[i];
    NodeDirection    &along = result.direction[1];
    along.frame             = {{0, d[0], d[1]}};
    // The bound of the last update is weakened already; Coulomb's coupling
    // to the normal force weakens with it.
    const TangentialLaw           &law   = *zone_friction[node_zones[i]];
    const TangentialLaw::SlipForce force = law.slip_force(bounds[i]);
    along.value                          = force.value;
    along.coupling = force.coupling * law.weakening.factor(weakening_state[i]);
    if (k == 2)
      {
        NodeDirection &across = result.direction[2];
        across.frame          = {{0, -d[1], d[0]}};
        across.stiffness      = transverse_stiffness[i];
        across.value
          = -transverse_stiffness[i]
            * (across.frame[1] * reference[0] + across.frame[2] * reference[1]);
      }
    return result;
  }



  // @sect4{ContactNodes::store_solution}
  //
  // The back end's solution in the node's frame: y = sum_k a_k y_k and the
  // force sum_k a_k f_k, f_k from the law of a free direction or from the
  // back end for a fixed one. The normal comes first, since the coupled
  // directions need its force.
  void
  ContactNodes::store_solution(const unsigned int    i,
                               const double          gap,
                               const NodeDirections &node_directions,
                               const double         *displacements,
                               const double         *fixed_forces)
  {
    std::array<double, 3> y = {{0, 0, 0}}, force = {{0, 0, 0}};
    double                normal_force = 0;
    for (unsigned int k = 0; k < node_directions.size; ++k)
      {
        const NodeDirection &direction = node_directions.direction[k];
        const double         f
          = (direction.fixed
               ? fixed_forces[k]
               : direction.value + direction.stiffness * displacements[k]
                   + direction.coupling * normal_force);
        if (k == 0)
          normal_force = f;
        for (unsigned int e = 0; e < 3; ++e)
          {
            y[e] += direction.frame[e] * displacements[k];
            force[e] += direction.frame[e] * f;
          }
      }
    r[i]         = y[0] - gap;
    node_gaps[i] = gap;
    z[i]         = force[0];
    for (unsigned int j = 0; j < tangential_directions[i]; ++j)
      {
        s[i][j] = y[1 + j];
        t[i][j] = force[1 + j];
      }
  }



  // @sect4{ContactNodes::accept_slip and reset_slip}
  //
  // The slip of the next step starts from the final displacement of this
  // one (taken from u, not from the last solve's s, which the condensed
  // back end computes otherwise, to rounding); the slip of this one is
  // measured relative to its obstacle. A slipping node's bound and
  // direction are set from its normal and tangential force (the values of
  // its last update, to rounding), so that a run resumed from a
  // checkpoint, which stores u and the forces, continues with the same
  // numbers.
  void
  ContactNodes::accept_slip(
    const std::vector<Tangential> &tangential_displacements,
    const double                   step_length)
  {
    AssertDimension(tangential_displacements.size(), size());
    for (unsigned int i = 0; i < size(); ++i)
      {
        const unsigned int k = tangential_directions[i];
        if (k == 0)
          continue;
        s[i]                       = tangential_displacements[i];
        const Tangential reference = stick_position(i);
        for (unsigned int j = 0; j < k; ++j)
          last_slip[i][j] = s[i][j] - reference[j];
        // The weakening variable: the rate of this step's slip, or the
        // slip added to the path (a free node, out of contact under
        // Coulomb's law, moves without sliding on anything).
        const double slip_length = std::hypot(last_slip[i][0], last_slip[i][1]);
        if (step_length > 0)
          {
            if (zone_friction[node_zones[i]]->weakening.of_rate)
              weakening_state[i] = slip_length / step_length;
            else if (friction_states[i] != free_tangential)
              weakening_state[i] += slip_length;
          }
        slip_reference[i] = s[i];
        if (friction_states[i] != slip)
          continue;
        bounds[i] = bound_of(i);
        if (t[i][0] != 0 || t[i][1] != 0)
          set_slip_direction(i, t[i], bounds[i]);
      }
    obstacle_slip.clear();
  }



  void
  ContactNodes::set_obstacle_slip(const std::vector<Tangential> &obstacle_step)
  {
    AssertDimension(obstacle_step.size(), size());
    obstacle_slip = obstacle_step;
  }



  ContactNodes::Tangential
  ContactNodes::stick_position(const unsigned int i) const
  {
    if (obstacle_slip.empty())
      return slip_reference[i];
    return {{slip_reference[i][0] + obstacle_slip[i][0],
             slip_reference[i][1] + obstacle_slip[i][1]}};
  }



  // @sect4{ContactNodes::bound_of and set_slip_direction}
  //
  // The bound g of node i now: Tresca's, or mu z with the last normal
  // force, times the weakening factor of its accumulated slip. And the slip
  // direction d = q / |q| of a slipping node with the
  // transverse stiffness of the Newton linearisation (3D, update_friction()),
  // k_e = c w gamma / (1 - gamma), gamma = g / |q|, capped at 100 c w.
  double
  ContactNodes::bound_of(const unsigned int i) const
  {
    const TangentialLaw &law = *zone_friction[node_zones[i]];
    return law.bound(z[i], tresca_bound[i])
           * law.weakening.factor(weakening_state[i]);
  }



  double
  ContactNodes::weakening_variable(const unsigned int i) const
  {
    return weakening_state[i];
  }



  void
  ContactNodes::set_weakening_variable(const unsigned int i, const double slip)
  {
    weakening_state[i] = slip;
  }



  bool
  ContactNodes::has_slip_weakening() const
  {
    return std::any_of(zone_friction.begin(),
                       zone_friction.end(),
                       [](const FrictionLaw &law) {
                         return !law->weakening.points.empty();
                       });
  }



  void
  ContactNodes::set_slip_direction(const unsigned int i,
                                   const Tangential  &q,
                                   const double       g)
  {
    const unsigned int k      = tangential_directions[i];
    const double       q_norm = std::hypot(q[0], q[1]);
    for (unsigned int j = 0; j < k; ++j)
      slip_direction[i][j] = q[j] / q_norm;
    const double gamma = g / q_norm;
    transverse_stiffness[i]
      = (k == 2
           ? c[i] * w[i] * (gamma >= 100. / 101. ? 100. : gamma / (1 - gamma))
           : 0.);
  }



  void
  ContactNodes::reset_slip(
    const std::vector<Tangential> &tangential_displacements,
    const std::vector<Tangential> &tangential_forces)
  {
    AssertDimension(tangential_displacements.size(), size());
    AssertDimension(tangential_forces.size(), size());
    t              = tangential_forces;
    slip_reference = tangential_displacements;
    obstacle_slip.clear();
    accept_slip(tangential_displacements, /*step_length=*/0);
  }



  // @sect4{ContactNodes::solve}
  //
  // The iteration itself, the same for every back end and rank count: the
  // decision to stop depends on sums over all ranks only, so every rank
  // takes it at the same iteration.
  //
  // Each iteration solves the linear problem of the current pieces (the back
  // end writes r and z), moves every node to the piece that its q names, and
  // stops when no node has moved on any rank and the linear solve met the
  // tolerance. Since the step problem has the same fixed points whatever the
  // c_i, a converged iteration has solved the step problem of the current
  // operator.
  //
  // Inexact early solves: while the pieces are still changing, a solve only
  // has to tell each node which piece it goes to next, not the final
  // displacement. So the iteration asks for the relative accuracy
  // sqrt(tolerance) (1e-5 for the default 1e-10) until a solve moves no
  // node; that solve is then continued to the full tolerance, and every
  // later one asks for the full tolerance. The last solve is always a full
  // one, so the result is the one of the exact iteration; what
  // changes is the cost of the solves before the pieces settle, which the
  // full space back end's Krylov method stops early (the condensed back end
  // solves exactly anyway, and its report then meets the tolerance at once,
  // which leaves its iteration as it was). CG continues without a restart:
  // at the iterate where it would stop early it asks pieces_stay() and, if
  // no node would move, goes on to the tolerance (LinearSolveRequest). A
  // restarted CG would throw away its search directions: one or two
  // iterations more per settled step on the cube (528 against 498 over a
  // whole run at 108k dofs). The decision is the same as after a stop,
  // since the iterate is the same.
  ActiveSetResult
  ContactNodes::solve(
    const std::function<LinearSolveReport(const LinearSolveRequest &)>
                      &solve_for_pieces,
    const unsigned int max_iterations,
    const double       tolerance,
    const MPI_Comm     communicator)
  {
    ActiveSetResult result;
    const double    early_tolerance = std::max(std::sqrt(tolerance), tolerance);
    bool            pieces_settled  = false;
    // The fixed point on Coulomb's bound and on the slip directions stops
    // when they change by less than this (relative).
    friction_tolerance = std::max(1e-2 * std::sqrt(tolerance), tolerance);
    std::map<std::uint64_t, unsigned int> sets_seen;
    for (unsigned int iteration = 0; iteration < max_iterations; ++iteration)
      {
        // The linear problem of the current pieces. A failed solve (a Krylov
        // method that did not converge) fails on every rank alike, because
        // the Krylov methods decide with global norms; the iteration ends
        // with the back end's reason.
        LinearSolveReport report = solve_for_pieces(
          pieces_settled
            ? LinearSolveRequest{tolerance, tolerance, {}}
            : LinearSolveRequest{early_tolerance, tolerance, [&] {
                                   return pieces_stay(communicator);
                                 }});
        if (!report.converged)
          {
            result.failure = report.failure;
            return result;
          }
        // Every node moves (or stays), and all ranks learn how many moved
        // and how many are at the rigid limit.
        std::array<unsigned int, 3> moved = update_all_pieces(communicator);
        // An early solve that moved no node: the pieces have settled, so the
        // same linear problem is solved on to the full tolerance (from the
        // early solution), and the nodes are checked once more. This is
        // still the same iteration, on the same pieces, so an iteration
        // counts the sets of pieces tried, as with exact solves.
        if (moved[0] == 0 && !pieces_settled && report.residual > tolerance)
          {
            pieces_settled = true;
            const LinearSolveReport refined
              = solve_for_pieces({tolerance, tolerance, {}});
            if (!refined.converged)
              {
                result.failure = refined.failure;
                return result;
              }
            report.residual = refined.residual;
            report.inner_iterations += refined.inner_iterations;
            moved = update_all_pieces(communicator);
          }
        result.history.push_back({moved[0],
                                  moved[1],
                                  report.residual,
                                  report.inner_iterations,
                                  moved[2]});
        // Converged: the pieces the last solve used are the ones the nodes
        // sit on now, so (r, z) lies on the graph of the law at every node,
        // and no slipping node's bound or direction has changed. The
        // residual is a global norm, the same on every rank.
        if (moved[0] == 0 && moved[2] == 0 && report.residual <= tolerance)
          {
            result.converged = true;
            return result;
          }
        // A cycle: the same pieces and stick/slip states as two iterations
        // before, seen for the third time (with exact solves the iteration
        // would repeat them forever).
        if (moved[0] > 0)
          {
            const unsigned int seen
              = ++sets_seen[active_set_signature(communicator)];
            if (seen >= 3)
              {
                std::ostringstream reason;
                reason << "The active-set iteration cycles: iteration "
                       << result.history.size()
                       << " returned to a set of pieces and stick/slip "
                          "states it had reached twice before (a step too "
                          "long for the change of the contact zone, or a "
                          "law that softens more than the body carries, "
                          "doc/model.md, section 4).";
                result.failure = reason.str();
                return result;
              }
          }
        if (moved[0] == 0)
          pieces_settled = true;
        // Settled pieces whose linear solves no longer improve: more
        // iterations would only repeat them.
        if (moved[0] == 0 && stagnates(result.history, tolerance))
          {
            std::ostringstream reason;
            reason << "The pieces of the contact law settled, but the "
                      "linear solves stagnate at a relative residual of "
                   << report.residual << ", above Tolerance = " << tolerance
                   << " in subsection <Active set solver>.";
            result.failure = reason.str();
            return result;
          }
      }
    // Out of iterations: the caller cuts the time step or stops the run with
    // this reason, which names the parameters that bound the iteration.
    std::ostringstream reason;
    reason << "The active-set iteration did not converge within "
           << max_iterations
           << " iterations (Maximum iterations = " << max_iterations
           << ", Tolerance = " << tolerance
           << " in subsection <Active set solver>).";
    result.failure = reason.str();
    return result;
  }



  // @sect4{ContactNodes::pieces_stay}
  //
  // A trial of the update rule: the state is restored afterwards, with the
  // scales the rule's rounding is measured against.
  bool
  ContactNodes::pieces_stay(const MPI_Comm communicator)
  {
    const State  saved      = state();
    const double scale      = displacement_scale;
    const double slip_range = slip_scale;
    const bool   stay       = (update_all_pieces(communicator)[0] == 0);
    set_state(saved);
    displacement_scale = scale;
    slip_scale         = slip_range;
    return stay;
  }



  // @sect4{ContactNodes::state and set_state}
  //
  // The pieces and the last (r, z): what a time step that has to be retried
  // restores before it starts again (time_step.cc).
  ContactNodes::State
  ContactNodes::state() const
  {
    return {node_pieces,
            r,
            z,
            s,
            t,
            slip_reference,
            slip_direction,
            last_slip,
            friction_states,
            bounds,
            transverse_stiffness};
  }



  void
  ContactNodes::set_state(const State &state)
  {
    AssertDimension(state.pieces.size(), size());
    node_pieces          = state.pieces;
    r                    = state.r;
    z                    = state.z;
    s                    = state.s;
    t                    = state.t;
    slip_reference       = state.slip_reference;
    slip_direction       = state.slip_direction;
    last_slip            = state.last_slip;
    friction_states      = state.friction_states;
    bounds               = state.bounds;
    transverse_stiffness = state.transverse_stiffness;
  }



  // @sect4{ContactNodes::active_set_signature}
  //
  // A hash of the pieces and stick/slip states of all nodes of all ranks
  // (each rank's hash of its nodes, summed), to recognise a set the
  // iteration has been at before. Collective.
  std::uint64_t
  ContactNodes::active_set_signature(const MPI_Comm communicator) const
  {
    std::uint64_t hash = 1469598103934665603ULL;
    for (unsigned int i = 0; i < size(); ++i)
      {
        hash = (hash ^ node_pieces[i]) * 1099511628211ULL;
        hash = (hash ^ friction_states[i]) * 1099511628211ULL;
      }
    std::uint64_t sum = 0;
    const int     error
      = MPI_Allreduce(&hash, &sum, 1, MPI_UINT64_T, MPI_SUM, communicator);
    AssertThrowMPI(error);
    return sum;
  }



  // @sect4{Access to the nodes}
  //
  // Plain access: the number of nodes of this rank, the laws, and per node
  // the zone, the weight w_i and the piece. set_piece() is for
  // restoring a state node by node (a resumed checkpoint).
  unsigned int
  ContactNodes::size() const
  {
    return w.size();
  }



  const ContactLaws &
  ContactNodes::laws() const
  {
    return contact_laws;
  }



  unsigned int
  ContactNodes::zone(const unsigned int i) const
  {
    return node_zones[i];
  }



  double
  ContactNodes::weight(const unsigned int i) const
  {
    return w[i];
  }



  unsigned int
  ContactNodes::piece(const unsigned int i) const
  {
    return node_pieces[i];
  }



  void
  ContactNodes::set_piece(const unsigned int i, const unsigned int piece)
  {
    Assert(contact_laws.zone_of_piece(piece) == node_zones[i],
           ExcInternalError());
    node_pieces[i] = piece;
  }



  ContactLawPiece
  ContactNodes::current_piece(const unsigned int i) const
  {
    return contact_laws.piece(node_pieces[i], law_state(i));
  }



  const std::vector<unsigned int> &
  ContactNodes::pieces() const
  {
    return node_pieces;
  }



  // @sect4{Friction: access}
  //
  // Whether any zone has friction, and per node its tangential directions,
  // state, slip increment of the step and bound.
  bool
  ContactNodes::has_friction() const
  {
    for (const FrictionLaw &law : zone_friction)
      if (law->has_friction())
        return true;
    return false;
  }



  unsigned int
  ContactNodes::n_tangential(const unsigned int i) const
  {
    return tangential_directions[i];
  }



  ContactNodes::FrictionState
  ContactNodes::friction_state(const unsigned int i) const
  {
    return static_cast<FrictionState>(friction_states[i]);
  }



  void
  ContactNodes::set_friction_state(const unsigned int  i,
                                   const FrictionState state)
  {
    if (tangential_directions[i] > 0)
      friction_states[i] = state;
  }



  ContactNodes::Tangential
  ContactNodes::step_slip(const unsigned int i) const
  {
    return last_slip[i];
  }



  double
  ContactNodes::slip_bound(const unsigned int i) const
  {
    return bounds[i];
  }



  std::array<unsigned int, 2>
  ContactNodes::count_friction_states(const MPI_Comm communicator) const
  {
    std::array<unsigned int, 2> counts = {{0, 0}};
    for (unsigned int i = 0; i < size(); ++i)
      if (friction_states[i] == stick)
        ++counts[0];
      else if (friction_states[i] == slip)
        ++counts[1];
    return sum_over_ranks(counts, communicator);
  }



  // @sect4{ContactNodes::status}
  //
  // The contact state of a node as the output reports it: 2 at the rigid
  // limit (on the rigid piece), 1 in normal-compliance contact (penetrating
  // the layer, r > 0, pressed by it, z > 0, or held by adhesion: on the
  // glue's sloped piece, -L < r <= 0, with a bonding beta > 0, whatever the
  // rounding of its force at r = 0; a node separated beyond L counts as
  // out of contact; or by a cohesive interface: on a piece of its envelope
  // or its secant that carries a tension, or with a tension from the step,
  // which explicit damage takes from the opening reached before it while
  // the node has opened beyond delta_f in it), 0 out of contact.
  unsigned int
  ContactNodes::status(const unsigned int i) const
  {
    const ContactLawPiece piece = current_piece(i);
    if (piece.rigid)
      return 2;
    if (r[i] > 0 || z[i] > 0 || (piece.adhesive && piece.slope > 0)
        || (piece.cohesive && (piece.slope != 0 || piece.intercept != 0))
        || (z[i] < 0 && contact_laws.zone_law(node_zones[i]).has_cohesion()))
      return 1;
    return 0;
  }



  // @sect4{Contact pressures}
  //
  // The total pressure z_i / w_i, and the part the layer carries: p(g-) at
  // the rigid limit, where the foundation carries the rest, and the whole
  // pressure on every other piece, where the foundation carries nothing.
  double
  ContactNodes::contact_pressure(const unsigned int i) const
  {
    return z[i] / w[i];
  }



  double
  ContactNodes::compliance_pressure(const unsigned int i) const
  {
    const ContactLawPiece current = current_piece(i);
    return current.rigid ? current.p_lower + history_pressure(i)
                         : contact_pressure(i);
  }



  // @sect4{ContactNodes::count_states and total_force}
  //
  // Over all ranks: the nodes at the rigid limit, in normal-compliance
  // contact and out of contact (in this order, status 2, 1, 0), and the
  // total contact force sum_i z_i (per unit thickness in 2D). Both are
  // collective.
  std::array<unsigned int, 3>
  ContactNodes::count_states(const MPI_Comm communicator) const
  {
    std::array<unsigned int, 3> counts = {{0, 0, 0}};
    for (unsigned int i = 0; i < size(); ++i)
      ++counts[2 - status(i)];
    return sum_over_ranks(counts, communicator);
  }



  double
  ContactNodes::total_force(const MPI_Comm communicator) const
  {
    double sum = 0;
    for (const double force : z)
      sum += force;
    return Utilities::MPI::sum(sum, communicator);
  }



  std::vector<double>
  ContactNodes::zone_forces(const MPI_Comm communicator) const
  {
    std::vector<double> forces(contact_laws.n_zones(), 0.);
    for (unsigned int i = 0; i < size(); ++i)
      forces[node_zones[i]] += z[i];
    std::vector<double> sums(forces.size());
    Utilities::MPI::sum(ArrayView<const double>(forces.data(), forces.size()),
                        communicator,
                        ArrayView<double>(sums.data(), sums.size()));
    return sums;
  }



  // @sect4{ContactNodes::contact_area and peak_pressure}
  //
  // Over all ranks: the weights of the nodes that carry a pressure (z_i >
  // 0) summed, which is the contact width in 2D and the contact area in 3D
  // to within the weight of the nodes at the edge of the zone, and the
  // largest nodal pressure z_i / w_i. A node that touches the obstacle
  // without being pressed (at zero load, say) is not counted: the area is
  // where the pressure acts. Both are collective.
  double
  ContactNodes::contact_area(const MPI_Comm communicator) const
  {
    double sum = 0;
    for (unsigned int i = 0; i < size(); ++i)
      if (status(i) > 0 && z[i] > 0)
        sum += w[i];
    return Utilities::MPI::sum(sum, communicator);
  }



  double
  ContactNodes::peak_pressure(const MPI_Comm communicator) const
  {
    double peak = 0;
    for (unsigned int i = 0; i < size(); ++i)
      peak = std::max(peak, contact_pressure(i));
    return Utilities::MPI::max(peak, communicator);
  }



  std::vector<std::array<double, 2>>
  ContactNodes::zone_areas_and_peaks(const MPI_Comm communicator) const
  {
    const unsigned int  n_zones = contact_laws.n_zones();
    std::vector<double> areas(n_zones, 0.), peaks(n_zones, 0.);
    for (unsigned int i = 0; i < size(); ++i)
      {
        if (status(i) > 0 && z[i] > 0)
          areas[zone(i)] += w[i];
        peaks[zone(i)] = std::max(peaks[zone(i)], contact_pressure(i));
      }
    const std::vector<double> local_areas = areas, local_peaks = peaks;
    Utilities::MPI::sum(local_areas, communicator, areas);
    Utilities::MPI::max(local_peaks, communicator, peaks);
    std::vector<std::array<double, 2>> result(n_zones);
    for (unsigned int zone = 0; zone < n_zones; ++zone)
      result[zone] = {{areas[zone], peaks[zone]}};
    return result;
  }
} // namespace ViscoContact
